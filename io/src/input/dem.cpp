// DEM rasters through GDAL: reading with nodata, the frame between the mesh and the raster, and the
// shoreline traced as a contour (dem.hpp).
#include "shoremesh/io/dem.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "gdal_setup.hpp"
#include "shoremesh/error.hpp"

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
struct DemFrame::Transform {
  std::unique_ptr<OGRCoordinateTransformation> to_dem;
};

namespace {

// A PROJ transformation from lon/lat (WGS84, lon first) to the DEM's coordinate system.
std::unique_ptr<OGRCoordinateTransformation> dem_transform(const Dem& dem) {
  OGRSpatialReference srs, ll;
  if (srs.importFromWkt(dem.crs_wkt.c_str()) != OGRERR_NONE)
    throw InputError("cannot read the DEM's coordinate system", dem.file);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  ll.SetWellKnownGeogCS("WGS84");
  ll.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&ll, &srs));
  if (!t)
    throw InputError("PROJ cannot transform between lon/lat and the DEM's coordinate system (" + dem.crs_name + ")",
                     dem.file);
  return t;
}

}  // namespace

DemFrame::DemFrame(std::shared_ptr<const Dem> dem, const Projection& mesh_projection)
    : dem_(std::move(dem)), projection_(mesh_projection) {
  detail::register_gdal();
  if (projection_.is_none() || dem_->geographic) return;
  if (dem_->crs_wkt.empty())
    throw InputError("the DEM has no coordinate system, and the mesh is in projected lon/lat: cannot place it", dem_->file);
  transform_ = std::make_unique<Transform>();
  transform_->to_dem = dem_transform(*dem_);
}

DemFrame::~DemFrame() = default;
DemFrame::DemFrame(DemFrame&&) noexcept = default;
DemFrame& DemFrame::operator=(DemFrame&&) noexcept = default;

Point2 DemFrame::to_cell(const Point2& xy) const {
  if (projection_.is_none()) return dem_->map_to_cell(xy);
  const LonLat ll = projection_.reverse(xy);
  double x = ll.lon, y = ll.lat;
  if (transform_ && !transform_->to_dem->Transform(1, &x, &y))
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
