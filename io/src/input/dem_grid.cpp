// A DEM as the terrain mesher's height grid, in a metric plane, with the way back to lon/lat (dem.hpp).
#include <cmath>
#include <numbers>

#include "shoremesh/io/dem.hpp"
#include "shoremesh/io/georeference.hpp"
#include "shoremesh/io/projection.hpp"

namespace shoremesh::io {

namespace {
constexpr double kEarthRadius = 6371008.8;  // metres, the mean radius (IUGG)
}  // namespace

DemGrid dem_grid(const Dem& dem) {
  DemGrid out;
  HeightGrid& g = out.grid;
  g.width = dem.width, g.height = dem.height;
  g.z = dem.heights;
  g.valid = dem.valid;
  const Point2 origin = dem.cell_to_map(0, 0);
  const auto& t = dem.geotransform;
  if (dem.geographic) {
    const Point2 centre = dem.cell_to_map(0.5 * (dem.width - 1), 0.5 * (dem.height - 1));
    const double k = std::numbers::pi / 180 * kEarthRadius, kx = k * std::cos(centre[1] * std::numbers::pi / 180);
    g.x0 = (origin[0] - centre[0]) * kx, g.y0 = (origin[1] - centre[1]) * k;
    g.dx = t[1] * kx, g.dy = t[5] * k;
    out.to_lonlat = [centre, k, kx](const Point2& p) { return Point2{centre[0] + p[0] / kx, centre[1] + p[1] / k}; };
    out.metres = true;
    return out;
  }
  g.x0 = origin[0], g.y0 = origin[1], g.dx = t[1], g.dy = t[5];
  if (dem.crs_wkt.empty()) return out;
  const CoordinateSystem crs = parse_coordinate_system(dem.crs_wkt, dem.file);
  if (crs.kind == CoordinateSystem::Kind::Utm) {
    const Projection utm = Projection::utm_ups(crs.zone, crs.north);
    out.to_lonlat = [utm](const Point2& p) {
      const LonLat ll = utm.reverse(p);
      return Point2{ll.lon, ll.lat};
    };
    out.metres = true;
  } else if (crs.kind == CoordinateSystem::Kind::Other) {
    out.to_lonlat = lonlat_transform(crs, dem.file);
    out.metres = true;
  }
  return out;
}

}  // namespace shoremesh::io
