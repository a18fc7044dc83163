// DEMs (dem.hpp): the frame between the mesh and the raster, and the shoreline traced as a contour. Reading
// is io/src/raster/dem_read.cpp.
#include "shoremesh/io/dem.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "../raster/raster_module.hpp"
#include "shoremesh/error.hpp"

namespace shoremesh::io {

Point2 Dem::cell_to_map(double col, double row) const {
  const auto& g = geotransform;
  const double x = col + 0.5, y = row + 0.5;
  return {g[0] + x * g[1] + y * g[2], g[3] + x * g[4] + y * g[5]};
}

Point2 Dem::map_to_cell(const Point2& xy) const {
  const auto& g = geotransform;
  const double det = g[1] * g[5] - g[2] * g[4];
  const double dx = xy[0] - g[0], dy = xy[1] - g[3];
  return {(g[5] * dx - g[2] * dy) / det - 0.5, (-g[4] * dx + g[1] * dy) / det - 0.5};
}

double Dem::bilinear(double col, double row) const {
  col = std::clamp(col, 0.0, static_cast<double>(width - 1));
  row = std::clamp(row, 0.0, static_cast<double>(height - 1));
  const int c0 = std::min(static_cast<int>(col), std::max(width - 2, 0));
  const int r0 = std::min(static_cast<int>(row), std::max(height - 2, 0));
  const int c1 = std::min(c0 + 1, width - 1), r1 = std::min(r0 + 1, height - 1);
  const double tx = col - c0, ty = row - r0;
  const double top = (1 - tx) * at(c0, r0) + tx * at(c1, r0);
  const double bottom = (1 - tx) * at(c0, r1) + tx * at(c1, r1);
  return (1 - ty) * top + ty * bottom;
}

// Mesh lon/lat -> the DEM's coordinate system (PROJ through OGR), traditional lon, lat axis order.
struct DemFrame::Transform {
  std::unique_ptr<detail::PointTransform> to_dem;
};

DemFrame::DemFrame(std::shared_ptr<const Dem> dem, const Projection& mesh_projection)
    : dem_(std::move(dem)), projection_(mesh_projection) {
  if (projection_.is_none() || dem_->geographic) return;
  if (dem_->crs_wkt.empty())
    throw InputError("the DEM has no coordinate system, and the mesh is in projected lon/lat: cannot place it", dem_->file);
  transform_ = std::make_unique<Transform>();
  transform_->to_dem = detail::dem_transform(*dem_);
}

DemFrame::~DemFrame() = default;
DemFrame::DemFrame(DemFrame&&) noexcept = default;
DemFrame& DemFrame::operator=(DemFrame&&) noexcept = default;

Point2 DemFrame::to_cell(const Point2& xy) const {
  if (projection_.is_none()) return dem_->map_to_cell(xy);
  const LonLat ll = projection_.reverse(xy);
  double x = ll.lon, y = ll.lat;
  if (transform_ && !transform_->to_dem->transform(x, y))
    throw InputError("PROJ cannot transform lon/lat " + std::to_string(ll.lon) + ", " + std::to_string(ll.lat) +
                         " to the DEM's coordinate system",
                     dem_->file);
  return dem_->map_to_cell({x, y});
}

namespace {
constexpr std::size_t kDemRefinement = 4;  // mask pixels per cell side, at most
}  // namespace

TracedDem trace_dem(const std::string& path, const DemTraceOptions& options) {
  return trace_dem(std::make_shared<const Dem>(read_dem(path)), options);
}

TracedDem trace_dem(std::shared_ptr<const Dem> dem, const DemTraceOptions& options) {
  if (!std::isfinite(options.level)) throw InputError("the shoreline level must be a finite height", dem->file);
  std::ostringstream level_text;
  level_text << options.level << " m";
  const std::string level = level_text.str();
  std::size_t water = 0;
  for (float v : dem->heights) water += v < options.level;
  if (water == 0) throw InputError("all land: no cell of the DEM lies below the shoreline level " + level, dem->file);
  if (water == dem->heights.size())
    throw InputError("all water: every cell of the DEM lies below the shoreline level " + level +
                         ", so there is no shoreline to trace",
                     dem->file);

  // Water is the cells below the level, each cell standing for its square (so the water's area is that of
  // the cells below the level, as GIS tools count it). The mask repeats each cell k x k times: the tracer's
  // ring, a quarter mask pixel inside the land from its pixel centres, then runs within 1/(4k) cell of the
  // cells' edges instead of a quarter cell into the land, and a channel one cell wide stays k pixels wide.
  // (The bilinear surface's contour was tried: on steep coasts it loses most of each one-cell fjord, 10 %
  // of the Salish Sea's water.)
  const std::size_t cells = dem->heights.size();
  if (cells > options.image.max_pixels)
    throw InputError("DEM too large to trace: " + std::to_string(dem->width) + " x " + std::to_string(dem->height) +
                         " cells, more than the tracer's limit of " + std::to_string(options.image.max_pixels) +
                         " (as a depth source, --depth-from reads up to 200 million)",
                     dem->file);
  const int k = static_cast<int>(std::clamp<std::size_t>(
      static_cast<std::size_t>(std::sqrt(static_cast<double>(options.image.max_pixels) / static_cast<double>(cells))), 1,
      kDemRefinement));
  WaterMask mask;
  mask.width = dem->width * k;
  mask.height = dem->height * k;
  mask.water.resize(static_cast<std::size_t>(mask.width) * static_cast<std::size_t>(mask.height));
  for (int r = 0; r < mask.height; ++r)
    for (int c = 0; c < mask.width; ++c)
      mask.water[static_cast<std::size_t>(r) * mask.width + c] = dem->at(c / k, r / k) < options.level;
  DemTraceOptions scaled = options;
  // --min-area counts cells. A ring's area in mask pixels misses the quarter-pixel strip along its edges
  // (k pixels for one cell's square), which would drop the one-cell islets --min-area 1 asks to keep.
  scaled.image.min_area = k > 1 ? options.image.min_area * k * k - k : options.image.min_area;
  if (options.image.spacing_unit == ImageTraceOptions::SpacingUnit::Pixels) scaled.image.spacing = options.image.spacing * k;

  Georeference g;
  g.source = Georeference::Source::Gdal;
  const auto& t = dem->geotransform;
  g.pixel_to_map = {t[1] / k, t[2] / k, t[0] + 0.5 * (t[1] + t[2]) / k, t[4] / k, t[5] / k, t[3] + 0.5 * (t[4] + t[5]) / k};
  if (dem->crs_wkt.empty()) {
    g.description = "DEM geotransform without a coordinate system: map units";
  } else {
    g.crs = parse_coordinate_system(dem->crs_wkt, dem->file);
    g.description = "DEM in " + g.crs.name;
    if (g.crs.kind == CoordinateSystem::Kind::Other) g.map_to_lonlat = lonlat_transform(g.crs, dem->file);
  }
  TracedDem out;
  out.dem = dem;
  out.traced = trace_water_mask(mask, scaled.image, g, dem->file);
  InputSet& set = out.traced.input;
  set.notes.push_back("shoreline: the DEM's contour at " + level + ", water below it (traced on the cells " +
                      "refined " + std::to_string(k) + " x " + std::to_string(k) + ": a cell is " +
                      std::to_string(k * k) + " pixels)");
  if (dem->nodata_cells > 0)
    set.notes.push_back(std::to_string(dem->nodata_cells) + " nodata cells of the DEM filled from their neighbours");
  return out;
}

}  // namespace shoremesh::io
