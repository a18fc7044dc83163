// shoremesh mesh --dem FILE --land-up-to Z [--max-error E]: one TIN of the water and of the land below Z,
// the shoreline (the contour at --shoreline-level) a chain of mesh edges inside it, heights on every node,
// and the vertical error bound on land (docs/terrain.md, "Land and water in one mesh").
#include "land_water.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "pipeline.hpp"
#include "progress.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/land_water.hpp"
#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/dem.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/mesh_quality.hpp"
#include "shoremesh/shore_session.hpp"
#include "shoremesh/terrain.hpp"

namespace shoremesh::tool {

namespace {


// The DEM's contour at `level` traced as `--dem` traces the shoreline (water strictly below), the rings
// taken from the tracer's frame to the DEM's plane (io::dem_grid), where the TIN is built. Empty when no
// valid cell lies below the level; the DEM's outer cell edges when every cell does.
struct Contour {
  Domain2 rings;
  bool all_below = false, none_below = false;
  std::vector<std::string> notes;
};

Contour trace_level(const std::shared_ptr<const io::Dem>& dem, const HeightGrid& grid, double level,
                    const InputArgs& a) {
  Contour out;
  std::size_t below = 0;
  for (float z : dem->heights) below += z < level;
  if (below == 0) {
    out.none_below = true;
    return out;
  }
  if (below == dem->heights.size()) {
    out.all_below = true;
    const double c0 = -0.5, r0 = -0.5, c1 = grid.width - 0.5, r1 = grid.height - 0.5;
    auto at = [&](double c, double r) { return Point2{grid.x0 + c * grid.dx, grid.y0 + r * grid.dy}; };
    out.rings.rings.push_back({{at(c0, r0), at(c1, r0), at(c1, r1), at(c0, r1)}, RingRole::Shore});
    return out;
  }
  const io::InputOptions options = input_options(a);
  io::DemTraceOptions d;
  d.level = level;
  d.image = options.image;
  d.image.projection = options.projection;
  d.image.projection_choice = options.projection_choice;
  io::TracedDem traced = io::trace_dem(dem, d);
  const io::InputSet& set = traced.traced.input;
  const io::DemFrame frame(dem, set.projection);
  for (const Ring& ring : set.domain.rings) {
    if (ring.points.empty()) continue;
    Ring mapped{{}, ring.role};
    for (const Point2& p : ring.points) {
      const Point2 cell = frame.to_cell(p);
      mapped.points.push_back({grid.x0 + cell[0] * grid.dx, grid.y0 + cell[1] * grid.dy});
    }
    out.rings.rings.push_back(std::move(mapped));
  }
  out.notes = set.notes;
  return out;
}

std::string metres(double x) { return approx(x, 4) + " m"; }

}  // namespace

int run_land_water(const LandWaterRequest& req, Progress& progress) {
  const InputArgs& a = req.in;
  const double z_top = *a.land_up_to, level = a.shoreline_level;
  if (!std::isfinite(z_top)) throw ParameterError("--land-up-to must be a finite height (got " + readable(z_top) + ")");
  if (!std::isfinite(level))
    throw ParameterError("--shoreline-level must be a finite height (got " + readable(level) + ")");
  if (!(z_top > level))
    throw ParameterError("--land-up-to " + readable(z_top) + " must lie above --shoreline-level " + readable(level) +
                         " (the land meshed is between them)");
  if (a.max_error && (!(*a.max_error > 0) || !std::isfinite(*a.max_error)))
    throw ParameterError("--max-error must be a finite height above 0 (got " + readable(*a.max_error) + ")");
  if (!a.files.empty())
    throw ParameterError("--land-up-to meshes the DEM alone: give no input files beside --dem (got " + a.files.front() + ")");
  if (!a.depth_from.empty() || a.min_depth || !a.open_boundary.empty())
    throw ParameterError("--land-up-to takes the heights from --dem itself: no --depth-from, --min-depth or --open-boundary");
  if (!req.preview.empty()) throw ParameterError("--preview is not drawn for --land-up-to meshes (use `terrain` for a hillshade)");
  if (req.other_options) throw ParameterError("--land-up-to: " + *req.other_options + " does not apply (the mesh is a TIN of the DEM)");

  const std::filesystem::path output = req.output;
  const io::ExportFormat format = req.format.empty() ? io::export_format_from_path(output) : parse_export_format(req.format);
  io::OutputBatch batch(std::vector<std::filesystem::path>{a.dem});
  const std::filesystem::path staged = stage_output(batch, output, format, "-o");

  const auto t0 = std::chrono::steady_clock::now();
  progress.stage("reading " + std::filesystem::path(a.dem).filename().string());
  const auto dem = std::make_shared<const io::Dem>(io::read_dem(a.dem));
  io::DemGrid plane = io::dem_grid(*dem);
  if (format == io::ExportFormat::GeoJson && !plane.to_lonlat)
    throw InputError("-o: GeoJSON needs longitude/latitude, and the DEM has no coordinate system", a.dem);
  double cell = std::min(std::abs(plane.grid.dx), std::abs(plane.grid.dy));

  progress.stage("tracing the contours at " + metres(z_top) + " and " + metres(level));
  const Contour top = trace_level(dem, plane.grid, z_top, a);
  if (top.none_below)
    throw InputError("no cell of the DEM lies below --land-up-to " + readable(z_top) + " m: nothing to mesh", a.dem);
  const Contour shore = trace_level(dem, plane.grid, level, a);
  const ShoreLines lines = shoreline_lines(shore.rings, top.rings, 0.5 * cell);

  TerrainOptions options;
  options.max_error = a.max_error ? *a.max_error : std::numeric_limits<double>::infinity();
  options.engine = session_parameters<2>(req.rho);
  options.domain = top.rings;
  options.domain.rings.insert(options.domain.rings.end(), lines.lines.begin(), lines.lines.end());
  options.bound_from = level;
  progress.stage("TIN of the water and the land below " + metres(z_top));
  std::optional<TerrainSession> session;
  try {
    session.emplace(plane.grid, options);
  } catch (const InputError& e) {
    throw InputError("--land-up-to " + readable(z_top) + ": " + e.message(), a.dem);
  }
  const auto& points = session->points();
  const auto& triangles = session->triangles();
  const auto& heights = session->heights();

  // Water triangles (centroid below the shoreline) and mesh edges along the shoreline's lines.
  const LandWaterCounts counts =
      land_water_counts(points, triangles, shore.rings, shore.all_below, shore.none_below, lines.lines, 1e-9 * cell);
  const std::size_t water = counts.water_triangles, shore_edges = counts.shoreline_edges;

  progress.stage("writing " + output.filename().string());
  std::vector<double> depths(heights.size());
  for (std::size_t i = 0; i < heights.size(); ++i) depths[i] = -heights[i];
  const io::MeshSnapshot<2> snapshot(points, triangles, session->kinds());
  io::MeshView<2> view = plane.to_lonlat ? snapshot.view(plane.to_lonlat) : snapshot.view();
  view.heights = heights;
  view.depths = depths;
  io::export_mesh<2>(staged, view, format);
  const TerrainError error = a.max_error ? session->error() : TerrainError{};
  const auto angles = angle_range(points, triangles);
  std::size_t meeting = 0;
  for (const auto& t : triangles)
    meeting += element_shape<2>({points[t[0]], points[t[1]], points[t[2]]}).radius_edge <= req.rho;
  batch.commit();
  progress.finish();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  std::cout << "input: " << a.dem << " (" << dem->width << " x " << dem->height << " cells, heights "
            << approx(dem->min, 5) << " .. " << approx(dem->max, 5) << " m)";
  if (dem->nodata_cells) std::cout << ", " << dem->nodata_cells << " nodata cells filled";
  std::cout << '\n';
  std::cout << "domain: below " << metres(z_top) << " ("
            << (top.all_below ? "every cell: the DEM's whole extent" : std::to_string(top.rings.rings.size()) + " rings")
            << "); shoreline at " << metres(level) << ": "
            << (shore.none_below ? "none (no cell below it)"
                : shore.all_below ? "none (every cell below it)"
                                  : std::to_string(lines.lines.size()) + " lines, " + std::to_string(lines.segments) +
                                        " contour segments (" + std::to_string(lines.dropped_segments) +
                                        " within half a cell of the contour at " + metres(z_top) + " left to it)")
            << '\n';
  std::cout << "land and water: " << triangles.size() << " triangles (" << triangles.size() - water << " land, " << water
            << " water), " << points.size() << " nodes; shoreline: " << shore_edges << " constrained edges\n";
  std::cout << "quality: " << meeting << " of " << triangles.size() << " triangles meet radius-edge <= "
            << approx(req.rho, 4) << "; angles " << approx(angles[0], 4) << " .. " << approx(angles[1], 4)
            << " degrees\n";
  if (a.max_error)
    std::cout << "error on land: max " << metres(error.max) << ", RMS " << metres(error.rms) << " over " << error.samples
              << " samples at or above " << metres(level) << " (--max-error " << readable(*a.max_error) << "; "
              << session->pick_count() << " samples picked in " << session->rounds() << " rounds)\n";
  std::cout << "heights: every node's DEM height (a sample's, bilinear elsewhere); depth = -height in depth fields\n";
  std::cout << "time: " << approx(ms, 4) << " ms\n";
  std::cout << "wrote " << req.output << '\n';
  return kExitOk;
}

}  // namespace shoremesh::tool
