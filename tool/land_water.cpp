// shoremesh mesh --dem FILE --land-up-to Z [--max-error E]: one TIN of the water and of the land below Z,
// the shoreline (the contour at --shoreline-level) a chain of mesh edges inside it, heights on every node,
// and the vertical error bound on land (docs/terrain.md, "Land and water in one mesh").
#include "land_water.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
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
#include "dem_patch.hpp"
#include "edit_session.hpp"
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


// The grid's contour at `level` (water strictly below), local to the cells (trace_contours,
// docs/terrain.md "Local contours"): --min-area in cells, --largest-water, and --spacing as the stride of
// the grid lines on which a straight ring keeps its vertices (1 cell by default).
struct Contour {
  Domain2 rings;
  bool all_below = false, none_below = false;
};

ContourOptions contour_options(const HeightGrid& grid, double level, const InputArgs& a) {
  ContourOptions o;
  o.level = level;
  o.min_area = a.min_area;
  o.largest_water_only = a.largest_water;
  if (a.spacing) {
    const double cell = std::min(std::abs(grid.dx), std::abs(grid.dy));
    o.stride = static_cast<int>(std::clamp(std::floor(*a.spacing / cell), 1.0, 1e6));
  }
  return o;
}

// The contour at `level`; when every cell lies below it, the DEM's outer cell edges (its whole extent, corners
// and all).
Contour trace_level(const HeightGrid& grid, double level, const InputArgs& a) {
  const TracedContours t = trace_contours(grid, contour_options(grid, level, a));
  Contour out{t.domain(), t.all_below, t.none_below};
  if (t.all_below) {
    auto at = [&](double c, double r) { return Point2{grid.x0 + c * grid.dx, grid.y0 + r * grid.dy}; };
    const double c0 = -0.5, r0 = -0.5, c1 = grid.width - 0.5, r1 = grid.height - 0.5;
    out.rings.rings = {{{at(c0, r0), at(c1, r0), at(c1, r1), at(c0, r1)}, RingRole::Shore}};
  }
  return out;
}

std::string metres(double x) { return approx(x, 4) + " m"; }

// The domain of a land-and-water TIN, a function of the DEM alone: the contour at Z, the shoreline's
// contour, its pieces clear of the contour at Z (constraint lines), and the rings and lines together.
struct LandWaterDomain {
  Contour top, shore;
  ShoreLines lines;
  Domain2 domain;
};

LandWaterDomain trace_domain(const HeightGrid& grid, double z_top, double level, const InputArgs& a) {
  LandWaterDomain d;
  const double cell = std::min(std::abs(grid.dx), std::abs(grid.dy));
  d.top = trace_level(grid, z_top, a);
  if (d.top.none_below)
    throw InputError("no cell of the DEM lies below --land-up-to " + readable(z_top) + " m: nothing to mesh", a.dem);
  if (d.top.rings.empty())
    throw InputError("no region below --land-up-to " + readable(z_top) + " m of at least --min-area " +
                         readable(a.min_area) + " cells: nothing to mesh",
                     a.dem);
  d.shore = trace_level(grid, level, a);
  // Lines cut every 8 strides (a line's change then stays within its few cells).
  d.lines = shoreline_lines(d.shore.rings, d.top.rings, 0.5 * cell,
                            contour_cut(grid, 8 * contour_options(grid, level, a).stride));
  d.domain = d.top.rings;
  d.domain.rings.insert(d.domain.rings.end(), d.lines.lines.begin(), d.lines.lines.end());
  return d;
}

std::string ms_text(double x) { return approx(x, 3) + " ms"; }

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

// The land-and-water mesh with its heights (z) and depths (-height), in lon/lat when the DEM has a system.
struct LandWaterView {
  std::vector<double> depths;
  io::MeshSnapshot<2> snapshot;
  io::MeshView<2> view;
  LandWaterView(const TerrainSession& s, const io::DemGrid& plane)
      : snapshot(s.points(), s.triangles(), s.kinds()),
        view(plane.to_lonlat ? snapshot.view(plane.to_lonlat) : snapshot.view()) {
    for (double h : s.heights()) depths.push_back(-h);
    view.heights = s.heights();
    view.depths = depths;
  }
};

// The edit lines of a land-and-water mesh (`mesh --dem --land-up-to --edits`), as `terrain --edits`:
//   dem-patch FILE   new heights for a window of the DEM; both contours are traced again on the patched
//                    DEM, the rings and lines move, the TIN updates and equals a fresh run on the patched DEM
//   export PATH      the mesh as it is now (heights as z, depths = -height)
//   stats            counts and the error on land against the current DEM
class LandWaterEdits {
 public:
  LandWaterEdits(TerrainSession& session, std::shared_ptr<const io::Dem>& dem, io::DemGrid& plane,
                 LandWaterDomain& domain, const InputArgs& a, std::vector<std::filesystem::path> inputs)
      : session_(session), dem_(dem), plane_(plane), domain_(domain), slots_(domain.domain), a_(a),
        inputs_(std::move(inputs)) {}

  std::optional<nlohmann::json> run(std::size_t line, const std::string& text) {
    return run_dem_edit_line(line, text, "land-and-water",
                             {[this](const std::string& f, nlohmann::json& r) { patch(f, r); },
                              [this](const std::string& p, nlohmann::json& r) { export_to(p, r); },
                              [this](nlohmann::json& r) { stats(r); }});
  }

  static std::string text(const nlohmann::json& r) {
    const std::string head = "line " + r["line"].dump() + ": ";
    if (!r.value("ok", false)) return head + "error: " + r.value("error", "");
    const std::string op = r.value("op", "");
    if (op == "dem-patch")
      return head + "dem-patch " + r.value("file", "") + ": " + r["cells"].dump() + " cells at column " +
             r["column"].dump() + ", row " + r["row"].dump() + ": ring and line vertices -" +
             r["ring_points_removed"].dump() + " +" + r["ring_points_added"].dump() + " (" + r["ring_stretches"].dump() +
             " ring stretches, the farthest vertex " + approx(r.value("ring_reach", 0.0), 3) +
             " cells from the window), triangles -" +
             r["triangles_removed"].dump() + " +" + r["triangles_added"].dump() + " (now " + r["triangles"].dump() +
             "); greedy picks +" + r["picks_added"].dump() + " -" + r["picks_removed"].dump() + " in " +
             r["rounds"].dump() + " rounds, " + r["operations"].dump() + " engine operations; " +
             ms_text(r.value("ms", 0.0)) + " (tracing " + ms_text(r.value("trace_ms", 0.0)) + ")";
    if (op == "export") return head + "wrote " + r.value("path", "") + " (" + r["triangles"].dump() + " triangles)";
    return head + r["triangles"].dump() + " triangles, " + r["nodes"].dump() + " nodes; error on land max " +
           approx(r.value("max_error", 0.0), 6) + ", RMS " + approx(r.value("rms_error", 0.0), 6);
  }

 private:
  void patch(const std::string& file, nlohmann::json& reply) {
    if (file.empty()) throw InputError("dem-patch takes a FILE (a raster with the DEM's cells)");
    const io::Dem p = io::read_dem(file);
    const PatchWindow at = locate_patch(*dem_, p);
    // A fresh run fills nodata from the neighbours, across the window's edge: a patch is a window of data
    // on a DEM without nodata, so that the patched DEM is the raster a fresh run reads.
    if (p.nodata_cells) throw InputError("a land-and-water patch must hold data in every cell", file);
    if (dem_->nodata_cells)
      throw InputError("the DEM has nodata cells (filled from their neighbours): a land-and-water mesh of it takes no "
                       "dem-patch",
                       file);
    const auto t0 = std::chrono::steady_clock::now();
    auto patched = std::make_shared<io::Dem>(*dem_);
    for (int r = 0; r < p.height; ++r)
      for (int c = 0; c < p.width; ++c)
        patched->heights[static_cast<std::size_t>(at.row + r) * patched->width + at.col + c] =
            p.heights[static_cast<std::size_t>(r) * p.width + c];
    const auto [lo, hi] = std::minmax_element(patched->heights.begin(), patched->heights.end());
    patched->min = *lo, patched->max = *hi;
    std::shared_ptr<const io::Dem> next = patched;
    HeightGrid grid = plane_.grid;
    for (int r = 0; r < p.height; ++r)
      for (int c = 0; c < p.width; ++c)
        grid.z[grid.index(at.col + c, at.row + r)] = p.heights[static_cast<std::size_t>(r) * p.width + c];
    LandWaterDomain traced;
    try {
      traced = trace_domain(grid, *a_.land_up_to, a_.shoreline_level, a_);
    } catch (const InputError& e) {
      throw InputError(e.message(), file);
    }
    // The rings' change as stretches of the rings in their places (follow_contours): local, since the
    // contours are.
    ContourFollow follow = follow_contours(slots_, traced.domain);
    double reach = 0;  // cells from the window to the farthest ring or line vertex that went or came
    for (const Point2& q : follow.moved) {
      const Point2 g = grid.to_grid(q);
      reach = std::max({reach, at.col - 0.5 - g[0], g[0] - (at.col + p.width - 0.5), at.row - 0.5 - g[1],
                        g[1] - (at.row + p.height - 0.5)});
    }
    std::size_t stretch_points = 0;
    for (const RingStretch& e : follow.edits) stretch_points += e.middle.size();
    const double trace_ms = ms_since(t0);
    const auto before = sorted_corners<2>(session_.points(), session_.triangles());
    const std::vector<Point2> was = domain_vertices(domain_.domain), now = domain_vertices(traced.domain);
    std::vector<Point2> ring_gone, ring_come;
    std::set_difference(was.begin(), was.end(), now.begin(), now.end(), std::back_inserter(ring_gone));
    std::set_difference(now.begin(), now.end(), was.begin(), was.end(), std::back_inserter(ring_come));
    TerrainUpdate u;
    try {
      u = session_.patch(at.col, at.row, p.width, p.height, p.heights, {}, follow.next);
    } catch (const InputError& e) {
      throw InputError("--land-up-to " + readable(*a_.land_up_to) + ": " + e.message(), file);
    }
    const double t = ms_since(t0);
    dem_ = next;
    plane_.grid.z = std::move(grid.z);
    domain_ = std::move(traced);
    slots_ = std::move(follow.next);
    const auto after = sorted_corners<2>(session_.points(), session_.triangles());
    std::vector<ElementCorners<2>> gone, came;
    std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(gone));
    std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(came));
    reply.update({{"file", file}, {"column", at.col}, {"row", at.row}, {"cells", std::size_t(p.width) * std::size_t(p.height)},
                  {"ring_points_removed", ring_gone.size()}, {"ring_points_added", ring_come.size()},
                  {"ring_stretches", follow.edits.size()}, {"ring_stretch_points", stretch_points},
                  {"ring_reach", reach},
                  {"triangles_removed", gone.size()}, {"triangles_added", came.size()},
                  {"triangles", session_.triangles().size()}, {"picks_added", u.picks_added},
                  {"picks_removed", u.picks_removed}, {"rounds", u.rounds}, {"operations", u.operations},
                  {"ms", t}, {"trace_ms", trace_ms}, {"engine_ms", u.engine_ms}, {"mesh_ms", u.mesh_ms},
                  {"error_ms", u.error_ms}});
  }

  void export_to(const std::string& path, nlohmann::json& reply) {
    if (path.empty()) throw InputError("export takes a PATH (.msh .vtu .obj .ply .off .geojson .node fort.14)");
    const io::ExportFormat format = io::export_format_from_path(path);
    if (format == io::ExportFormat::GeoJson && !plane_.to_lonlat)
      throw InputError("export: GeoJSON needs longitude/latitude, and the DEM has no coordinate system");
    io::OutputBatch batch(inputs_);  // never over an input
    const std::filesystem::path staged = stage_output(batch, path, format, "export");
    const LandWaterView mesh(session_, plane_);
    io::export_mesh<2>(staged, mesh.view, format);
    batch.commit();
    reply.update({{"path", path}, {"triangles", session_.triangles().size()}});
  }

  void stats(nlohmann::json& reply) const {
    const TerrainError e = session_.error();
    reply.update({{"triangles", session_.triangles().size()}, {"nodes", session_.points().size()},
                  {"max_error", e.max}, {"rms_error", e.rms}, {"samples_over", e.over}});
  }

  TerrainSession& session_;
  std::shared_ptr<const io::Dem>& dem_;
  io::DemGrid& plane_;
  LandWaterDomain& domain_;
  Domain2 slots_;  // the rings and lines in their places (follow_contours)
  const InputArgs& a_;
  std::vector<std::filesystem::path> inputs_;
};

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
  std::vector<std::filesystem::path> inputs{a.dem};
  std::ifstream edit_file;
  if (!req.edits.empty() && req.edits != "-") {
    edit_file.open(req.edits);
    if (!edit_file) throw InputError("cannot read the edits", req.edits);
    inputs.emplace_back(req.edits);
  }
  io::OutputBatch batch(inputs);
  const std::filesystem::path staged = stage_output(batch, output, format, "-o");

  const auto t0 = std::chrono::steady_clock::now();
  progress.stage("reading " + std::filesystem::path(a.dem).filename().string());
  std::shared_ptr<const io::Dem> dem = std::make_shared<const io::Dem>(io::read_dem(a.dem));
  const io::Dem first = *dem;  // the summary's input line
  io::DemGrid plane = io::dem_grid(*dem);
  if (format == io::ExportFormat::GeoJson && !plane.to_lonlat)
    throw InputError("-o: GeoJSON needs longitude/latitude, and the DEM has no coordinate system", a.dem);
  const double cell = std::min(std::abs(plane.grid.dx), std::abs(plane.grid.dy));

  progress.stage("tracing the contours at " + metres(z_top) + " and " + metres(level));
  LandWaterDomain domain = trace_domain(plane.grid, z_top, level, a);

  TerrainOptions options;
  options.max_error = a.max_error ? *a.max_error : std::numeric_limits<double>::infinity();
  options.engine = session_parameters<2>(req.rho);
  options.domain = domain.domain;
  options.bound_from = level;
  progress.stage("TIN of the water and the land below " + metres(z_top));
  std::optional<TerrainSession> session;
  try {
    session.emplace(plane.grid, options);
  } catch (const InputError& e) {
    throw InputError("--land-up-to " + readable(z_top) + ": " + e.message(), a.dem);
  }

  std::size_t failed = 0;
  if (!req.edits.empty()) {
    progress.stage("edits");
    LandWaterEdits edits(*session, dem, plane, domain, a, inputs);
    std::istream& in = req.edits == "-" ? std::cin : edit_file;
    std::size_t line_no = 0;
    for (std::string line; std::getline(in, line);) {
      const auto reply = edits.run(++line_no, line);
      if (!reply) continue;
      failed += !reply->value("ok", false);
      std::cout << (req.json ? reply->dump() : LandWaterEdits::text(*reply)) << std::endl;  // a program may wait
    }
  }

  const auto& points = session->points();
  const auto& triangles = session->triangles();
  // Water triangles (centroid below the shoreline) and mesh edges along the shoreline's lines.
  const LandWaterCounts counts = land_water_counts(points, triangles, domain.shore.rings, domain.shore.all_below,
                                                   domain.shore.none_below, domain.lines.lines, 1e-9 * cell);
  const std::size_t water = counts.water_triangles, shore_edges = counts.shoreline_edges;

  progress.stage("writing " + output.filename().string());
  const LandWaterView mesh(*session, plane);
  io::export_mesh<2>(staged, mesh.view, format);
  const TerrainError error = a.max_error ? session->error() : TerrainError{};
  const auto angles = angle_range(points, triangles);
  std::size_t meeting = 0;
  for (const auto& t : triangles)
    meeting += element_shape<2>({points[t[0]], points[t[1]], points[t[2]]}).radius_edge <= req.rho;
  batch.commit();
  progress.finish();
  const double ms = ms_since(t0);

  const Contour &top = domain.top, &shore = domain.shore;
  const ShoreLines& lines = domain.lines;
  std::cout << "input: " << a.dem << " (" << first.width << " x " << first.height << " cells, heights "
            << approx(first.min, 5) << " .. " << approx(first.max, 5) << " m)";
  if (first.nodata_cells) std::cout << ", " << first.nodata_cells << " nodata cells filled";
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
  if (failed) std::cerr << "shoremesh: " << failed << " edit line(s) failed (exit code 1)\n";
  return failed ? kExitBadInput : kExitOk;
}

}  // namespace shoremesh::tool
