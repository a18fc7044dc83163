// shoremesh mesh --dem FILE --land-up-to Z [--max-error E]: one TIN of the water and of the land below Z,
// the shoreline (the contour at --shoreline-level) a chain of mesh edges inside it, heights on every node,
// and the vertical error bound on land (docs/terrain.md, "Land and water in one mesh").
#include "land_water.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

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
#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/dem.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/mesh_quality.hpp"
#include "shoremesh/shore_session.hpp"
#include "shoremesh/terrain.hpp"

namespace shoremesh::tool {

namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BSegment = bg::model::segment<BPoint>;
using BBox = bg::model::box<BPoint>;

BPoint bp(const Point2& p) { return BPoint(p[0], p[1]); }

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

// The shoreline's pieces that lie clear of the domain's rings: a vertex at least `clearance` from every
// ring segment, a segment at least half of it. Where the land between the shoreline and Z is narrower
// than that (a cliff at the DEM's resolution), the domain's ring is the shoreline there, and the piece is
// left out. A closed piece becomes two lines sharing their ends (the domain accepts shared vertices).
struct ShoreLines {
  std::vector<Ring> lines;
  std::size_t segments = 0, dropped_segments = 0;
};

ShoreLines shoreline_lines(const Domain2& shore, const Domain2& domain, double clearance) {
  std::vector<std::pair<BBox, std::size_t>> boxes;
  std::vector<BSegment> segments;
  for (const Ring& r : domain.rings)
    for (std::size_t k = 0; k < r.segment_count(); ++k) {
      const BSegment s(bp(r.points[k]), bp(r.points[(k + 1) % r.points.size()]));
      BBox b;
      bg::envelope(s, b);
      boxes.push_back({b, segments.size()});
      segments.push_back(s);
    }
  const bgi::rtree<std::pair<BBox, std::size_t>, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
  auto nearest_within = [&](const auto& geometry, double d) {
    BBox b;
    bg::envelope(geometry, b);
    const BBox grown(BPoint(b.min_corner().get<0>() - d, b.min_corner().get<1>() - d),
                     BPoint(b.max_corner().get<0>() + d, b.max_corner().get<1>() + d));
    double best = std::numeric_limits<double>::infinity();
    for (auto it = tree.qbegin(bgi::intersects(grown)); it != tree.qend(); ++it)
      best = std::min(best, static_cast<double>(bg::distance(geometry, segments[it->second])));
    return best;
  };
  ShoreLines out;
  for (const Ring& r : shore.rings) {
    const std::size_t n = r.points.size();
    if (n < 3) continue;
    std::vector<char> vertex_clear(n), segment_clear(n);
    for (std::size_t k = 0; k < n; ++k) vertex_clear[k] = nearest_within(bp(r.points[k]), clearance) >= clearance;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t j = (k + 1) % n;
      segment_clear[k] = vertex_clear[k] && vertex_clear[j] &&
                         nearest_within(BSegment(bp(r.points[k]), bp(r.points[j])), clearance) >= 0.5 * clearance;
      out.dropped_segments += !segment_clear[k];
    }
    const auto first_gap = std::find(segment_clear.begin(), segment_clear.end(), 0);
    if (first_gap == segment_clear.end()) {
      // Closed and clear: two lines, 0 .. n/2 and n/2 .. n (= 0).
      Ring a{{}, RingRole::Line}, b{{}, RingRole::Line};
      for (std::size_t k = 0; k <= n / 2; ++k) a.points.push_back(r.points[k]);
      for (std::size_t k = n / 2; k <= n; ++k) b.points.push_back(r.points[k % n]);
      out.segments += n;
      out.lines.push_back(std::move(a));
      out.lines.push_back(std::move(b));
      continue;
    }
    // Runs of clear segments, starting after a gap so that none wraps. A run goes on into the segments
    // beside it as far as the clearance holds (bisection), so that it stops about `clearance` from the
    // domain's ring rather than a whole segment before.
    auto clip = [&](const Point2& v, const Point2& w) -> std::optional<Point2> {
      auto at = [&](double t) { return Point2{v[0] + t * (w[0] - v[0]), v[1] + t * (w[1] - v[1])}; };
      auto ok = [&](double t) {
        const Point2 p = at(t);
        return nearest_within(bp(p), clearance) >= clearance &&
               nearest_within(BSegment(bp(v), bp(p)), clearance) >= 0.5 * clearance;
      };
      double lo = 0, hi = 1;
      for (int i = 0; i < 30; ++i) {
        const double mid = 0.5 * (lo + hi);
        (ok(mid) ? lo : hi) = mid;
      }
      if (lo * std::hypot(w[0] - v[0], w[1] - v[1]) < 0.1 * clearance) return std::nullopt;
      return at(lo);
    };
    const std::size_t start = static_cast<std::size_t>(first_gap - segment_clear.begin());
    Ring line{{}, RingRole::Line};
    auto flush = [&] {
      if (line.points.size() >= 2) out.segments += line.points.size() - 1, out.lines.push_back(line);
      line.points.clear();
    };
    for (std::size_t i = 1; i <= n; ++i) {
      const std::size_t k = (start + i) % n, next = (k + 1) % n, previous = (k + n - 1) % n;
      if (!segment_clear[k]) {
        if (!line.points.empty())
          if (const auto p = clip(r.points[k], r.points[next])) line.points.push_back(*p);
        flush();
        continue;
      }
      if (line.points.empty()) {
        if (!segment_clear[previous])
          if (const auto p = clip(r.points[k], r.points[previous])) line.points.push_back(*p);
        line.points.push_back(r.points[k]);
      }
      line.points.push_back(r.points[next]);
    }
    flush();
  }
  return out;
}

// Even-odd: inside an odd number of the rings (their bounding boxes first).
class EvenOdd {
 public:
  explicit EvenOdd(const Domain2& d) : rings_(&d) {
    for (const Ring& r : d.rings) {
      Point2 lo = r.points.front(), hi = lo;
      for (const Point2& p : r.points)
        for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
      boxes_.push_back({lo, hi});
    }
  }
  bool inside(const Point2& p) const {
    bool in = false;
    for (std::size_t k = 0; k < rings_->rings.size(); ++k) {
      const auto& [lo, hi] = boxes_[k];
      if (p[0] < lo[0] || p[1] < lo[1] || p[0] > hi[0] || p[1] > hi[1]) continue;
      in ^= ring_contains(rings_->rings[k].points, p);
    }
    return in;
  }

 private:
  const Domain2* rings_;
  std::vector<std::array<Point2, 2>> boxes_;
};

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

  // Water: a triangle whose centroid lies below the shoreline (in the traced contour's water).
  std::size_t water = 0;
  if (shore.all_below) {
    water = triangles.size();
  } else if (!shore.none_below) {
    const EvenOdd wet(shore.rings);
    for (const auto& t : triangles) {
      const Point2 c{(points[t[0]][0] + points[t[1]][0] + points[t[2]][0]) / 3,
                     (points[t[0]][1] + points[t[1]][1] + points[t[2]][1]) / 3};
      water += wet.inside(c);
    }
  }
  // Mesh edges along the shoreline's lines: both ends on one segment of a line (the refinement's splits
  // are midpoints, on the segment to rounding).
  std::size_t shore_edges = 0;
  {
    std::vector<std::pair<BBox, std::size_t>> boxes;
    std::vector<BSegment> segs;
    for (const Ring& l : lines.lines)
      for (std::size_t k = 0; k + 1 < l.points.size(); ++k) {
        const BSegment s(bp(l.points[k]), bp(l.points[k + 1]));
        BBox b;
        bg::envelope(s, b);
        boxes.push_back({b, segs.size()});
        segs.push_back(s);
      }
    const bgi::rtree<std::pair<BBox, std::size_t>, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
    const double tol = 1e-9 * cell;
    std::vector<std::vector<std::size_t>> on(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const BBox b(BPoint(points[i][0] - tol, points[i][1] - tol), BPoint(points[i][0] + tol, points[i][1] + tol));
      for (auto it = tree.qbegin(bgi::intersects(b)); it != tree.qend(); ++it)
        if (bg::distance(bp(points[i]), segs[it->second]) <= tol) on[i].push_back(it->second);
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    for (const auto& [u, v] : edges)
      for (std::size_t s : on[u])
        if (std::find(on[v].begin(), on[v].end(), s) != on[v].end()) {
          ++shore_edges;
          break;
        }
  }

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
