// DEM rasters through GDAL (dem.hpp): reading with nodata, and the transformation from lon/lat to a DEM's
// coordinate system (raster_module.hpp).
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "gdal_setup.hpp"
#include "raster_module.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/dem.hpp"

namespace shoremesh::io {

namespace {

std::string last_gdal_error() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(m) : std::string("unknown reason");
}

// Fills the nodata cells (mask 0) in waves: each empty cell with filled 8-neighbours takes their mean.
void fill_nodata(Dem& dem, std::vector<std::uint8_t>& has) {
  const int w = dem.width, h = dem.height;
  std::vector<std::size_t> empty;
  for (std::size_t i = 0; i < has.size(); ++i)
    if (!has[i]) empty.push_back(i);
  while (!empty.empty()) {
    std::vector<std::pair<std::size_t, float>> filled;
    std::vector<std::size_t> still;
    for (std::size_t i : empty) {
      const int c = static_cast<int>(i % w), r = static_cast<int>(i / w);
      double sum = 0;
      int n = 0;
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
          const int cc = c + dc, rr = r + dr;
          if ((dr == 0 && dc == 0) || cc < 0 || rr < 0 || cc >= w || rr >= h) continue;
          const std::size_t j = static_cast<std::size_t>(rr) * w + cc;
          if (has[j]) sum += dem.heights[j], ++n;
        }
      if (n > 0) filled.push_back({i, static_cast<float>(sum / n)});
      else still.push_back(i);
    }
    for (const auto& [i, v] : filled) dem.heights[i] = v, has[i] = 1;
    empty = std::move(still);
  }
}

}  // namespace

Dem read_dem(const std::string& path, std::size_t max_cells) {
  detail::register_gdal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError("cannot open file", path);
  CPLErrorReset();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) throw InputError("not a raster GDAL can read: " + last_gdal_error(), path);
  if (ds->GetRasterCount() < 1) throw InputError("the file holds no raster band", path);
  Dem dem;
  dem.file = path;
  dem.width = ds->GetRasterXSize();
  dem.height = ds->GetRasterYSize();
  const std::uint64_t cells = static_cast<std::uint64_t>(dem.width) * static_cast<std::uint64_t>(dem.height);
  if (cells == 0) throw InputError("the raster has no cells", path);
  if (cells > max_cells)
    throw InputError("DEM too large: " + std::to_string(dem.width) + " x " + std::to_string(dem.height) + " cells, more than " +
                         std::to_string(max_cells),
                     path);
  if (ds->GetGeoTransform(dem.geotransform.data()) != CE_None)
    throw InputError("the raster has no geotransform (where its cells lie on the map is unknown)", path);
  const auto& g = dem.geotransform;
  if (g[2] != 0 || g[4] != 0) throw InputError("rotated or sheared rasters are not supported", path);
  if (!(g[1] != 0 && g[5] != 0) || !std::isfinite(g[0] + g[1] + g[3] + g[5]))
    throw InputError("the raster's geotransform is degenerate", path);

  GDALRasterBand* band = ds->GetRasterBand(1);
  dem.heights.resize(cells);
  CPLErrorReset();
  if (band->RasterIO(GF_Read, 0, 0, dem.width, dem.height, dem.heights.data(), dem.width, dem.height, GDT_Float32, 0, 0) !=
      CE_None)
    throw InputError("cannot read the raster's cells (truncated or corrupt file?): " + last_gdal_error(), path);
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  const float nodata_f = static_cast<float>(nodata);
  std::vector<std::uint8_t> has(cells, 1);
  dem.min = std::numeric_limits<double>::infinity();
  dem.max = -dem.min;
  for (std::size_t i = 0; i < cells; ++i) {
    const float v = dem.heights[i];
    if (!std::isfinite(v) || (has_nodata && v == nodata_f)) {
      has[i] = 0;
      ++dem.nodata_cells;
      continue;
    }
    dem.min = std::min(dem.min, static_cast<double>(v));
    dem.max = std::max(dem.max, static_cast<double>(v));
  }
  if (dem.nodata_cells == cells) throw InputError("the raster holds no data (every cell is nodata)", path);
  if (dem.nodata_cells > 0) dem.valid = has;
  fill_nodata(dem, has);

  if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    dem.crs_wkt = wkt ? wkt : "";
    CPLFree(wkt);
    const CoordinateSystem cs = parse_coordinate_system(dem.crs_wkt, path);
    dem.crs_name = cs.name;
    dem.geographic = cs.kind == CoordinateSystem::Kind::Geographic;
  }
  return dem;
}

// Mesh lon/lat -> the DEM's coordinate system (PROJ through OGR), traditional lon, lat axis order.
std::unique_ptr<detail::PointTransform> detail::dem_transform(const Dem& dem) {
  register_gdal();
  OGRSpatialReference srs, ll;
  if (srs.importFromWkt(dem.crs_wkt.c_str()) != OGRERR_NONE)
    throw InputError("cannot read the DEM's coordinate system", dem.file);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  ll.SetWellKnownGeogCS("WGS84");
  ll.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<PointTransform> t = ogr_transform(OGRCreateCoordinateTransformation(&ll, &srs));
  if (!t)
    throw InputError("PROJ cannot transform between lon/lat and the DEM's coordinate system (" + dem.crs_name + ")",
                     dem.file);
  return t;
}

}  // namespace shoremesh::io
