// Terrain TINs through the dynamic engine (terrain.hpp, docs/terrain.md).
#include "shoremesh/terrain.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/well_spaced.hpp"
#include "terrain_seeds.hpp"

namespace shoremesh {

double HeightGrid::bilinear(const Point2& p) const {
  const Point2 g = to_grid(p);
  const double col = std::clamp(g[0], 0.0, static_cast<double>(width - 1));
  const double row = std::clamp(g[1], 0.0, static_cast<double>(height - 1));
  const int c0 = std::min(static_cast<int>(col), width - 2), r0 = std::min(static_cast<int>(row), height - 2);
  const double tx = col - c0, ty = row - r0;
  const double top = (1 - tx) * at(c0, r0) + tx * at(c0 + 1, r0);
  const double bottom = (1 - tx) * at(c0, r0 + 1) + tx * at(c0 + 1, r0 + 1);
  return (1 - ty) * top + ty * bottom;
}

std::array<double, 2> angle_range(std::span<const Point2> points, std::span<const Element<2>> triangles) {
  double lo = 180, hi = 0;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const Point2 &a = points[t[k]], &b = points[t[(k + 1) % 3]], &c = points[t[(k + 2) % 3]];
      const double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - a[0], vy = c[1] - a[1];
      const double angle = std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / M_PI;
      lo = std::min(lo, angle), hi = std::max(hi, angle);
    }
  return {lo, hi};
}

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Clock = std::chrono::steady_clock;
constexpr std::size_t kNoSample = std::numeric_limits<std::size_t>::max();

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct CornersHash {
  std::size_t operator()(const ElementCorners<2>& c) const {
    PointHash<2> h;
    return h(c[0]) * 31 + h(c[1]) * 17 + h(c[2]);
  }
};

double orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// The sample of largest error in a triangle (ties: the smallest row-major index), and the error.
struct TriangleError {
  double error = 0;
  std::size_t sample = kNoSample;
};

// Calls f(sample index, interpolated height) for every valid sample in the closed triangle.
template <class F>
void for_each_sample(const HeightGrid& g, const std::array<Point2, 3>& p, const std::array<double, 3>& h, F&& f) {
  const double d = orient(p[0], p[1], p[2]);
  if (d == 0) return;
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (const Point2& q : p) {
    const Point2 gq = g.to_grid(q);
    for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], gq[i]), hi[i] = std::max(hi[i], gq[i]);
  }
  // A sample on an edge may round to just outside: a relative slack keeps it in both triangles.
  const double slack = 1e-12 * std::abs(d);
  const int c0 = std::max(0, static_cast<int>(std::ceil(lo[0] - 1e-9))), c1 = std::min(g.width - 1, static_cast<int>(std::floor(hi[0] + 1e-9)));
  const int r0 = std::max(0, static_cast<int>(std::ceil(lo[1] - 1e-9))), r1 = std::min(g.height - 1, static_cast<int>(std::floor(hi[1] + 1e-9)));
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) {
      const std::size_t i = g.index(c, r);
      if (!g.is_valid(i)) continue;
      const Point2 q = g.position(c, r);
      const double l0 = orient(q, p[1], p[2]), l1 = orient(p[0], q, p[2]), l2 = orient(p[0], p[1], q);
      if (d > 0 ? (l0 < -slack || l1 < -slack || l2 < -slack) : (l0 > slack || l1 > slack || l2 > slack)) continue;
      f(i, (l0 * h[0] + l1 * h[1] + l2 * h[2]) / d);
    }
}

// Only the samples at or above `from` count (the land of a land-and-water TIN).
TriangleError measure(const HeightGrid& g, const std::array<Point2, 3>& p, const std::array<double, 3>& h, double from) {
  TriangleError e;
  for_each_sample(g, p, h, [&](std::size_t i, double zi) {
    if (!(g.z[i] >= from)) return;
    const double err = std::abs(g.z[i] - zi);
    if (err > e.error || (err == e.error && e.sample != kNoSample && i < e.sample)) e.error = err, e.sample = i;
  });
  return e;
}

struct Tin {
  std::vector<Point2> points;
  std::vector<double> heights;
  std::vector<PointKind> kinds;
  std::vector<Element<2>> triangles;
};

}  // namespace

struct TerrainSession::Impl {
  HeightGrid grid;
  TerrainOptions options;
  terrain::Seeds seeds;
  terrain::BlockPicks blocks;     // canonical and local (docs/terrain.md "One setting for both targets")
  std::set<std::size_t> samples;  // the samples that are input points: the corners, seeds, block picks, picks
  std::set<std::size_t> picks;    // the correction rounds' picks
  // Midpoints of boundary edges that a TIN vertex encroached (inside the edge's diametral circle), made
  // in the rounds like the picks: ring points that are not samples.
  std::set<Point2> boundary_splits;
  // With a domain (custom()): its rings with the boundary splits in them, and every constrained edge of
  // the mesh (a subsegment of the refined rings) with the ring and the segment of `current` it lies on.
  Domain2 current;
  std::map<std::pair<Point2, Point2>, std::pair<std::size_t, std::size_t>> constrained;
  std::map<Point2, std::pair<Point2, Point2>> split_edge;  // a boundary split: the edge it halves
  BoxTransform<2> box;
  std::optional<ShoreRefinement> refinement;
  std::optional<DynamicWellSpaced<2>> ws;
  std::optional<Mesh2> mesh;
  std::unordered_map<Point2, std::size_t, PointHash<2>> input_id;    // every engine input point: its id
  std::unordered_map<Point2, std::size_t, PointHash<2>> sample_at;   // sample input points: their sample
  // Every triangle of the mesh (= the TIN): its error, and the midpoints of its boundary edges that its
  // third corner encroaches; `flagged`: the triangles with an error above the bound or such a midpoint.
  struct TriangleState {
    TriangleError error;
    std::vector<Point2> splits;
  };
  std::unordered_map<ElementCorners<2>, TriangleState, CornersHash> triangles;
  std::unordered_set<ElementCorners<2>, CornersHash> flagged;
  mutable Tin tin;            // the canonical numbering, made when asked for
  mutable bool tin_stale = true;
  TerrainUpdate build;
  std::size_t rounds = 0;

  // A land-and-water TIN: the options' rings instead of the rectangle.
  bool custom() const { return !options.domain.empty(); }

  void check_in_box(const Domain2& d) const {
    for (const Ring& r : d.rings)
      for (const Point2& p : r.points)
        if (!box.contains(p))
          throw InputError("the TIN's rings reach (" + readable(p[0]) + ", " + readable(p[1]) +
                           "), more than a cell outside the grid");
  }

  // The rings' and lines' vertices (the engine's ring inputs before splits), sorted, each once.
  static std::vector<Point2> ring_points(const Domain2& d) {
    std::vector<Point2> out;
    for (const Ring& r : d.rings) out.insert(out.end(), r.points.begin(), r.points.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  Point2 position(std::size_t s) const {
    return grid.position(static_cast<int>(s % grid.width), static_cast<int>(s / grid.width));
  }
  bool on_boundary(std::size_t s) const {
    if (custom()) return false;  // samples are loose points inside the rings
    const int c = static_cast<int>(s % grid.width), r = static_cast<int>(s / grid.width);
    return c == 0 || r == 0 || c == grid.width - 1 || r == grid.height - 1;
  }
  std::array<std::size_t, 4> corners() const {
    const std::size_t w = grid.width, h = grid.height;
    return {0, w - 1, (h - 1) * w, h * w - 1};
  }

  // Where p lies along the rectangle's boundary (row 0, then the last column, the last row, column 0), or -1
  // when it is not on it. Ring points are samples or midpoints of ring points, so they lie on the
  // rectangle's lines exactly.
  double perimeter_position(const Point2& p) const {
    const Point2 lo = grid.position(0, 0), hi = grid.position(grid.width - 1, grid.height - 1);
    const double w = std::abs(hi[0] - lo[0]), h = std::abs(hi[1] - lo[1]);
    if (p[1] == lo[1]) return std::abs(p[0] - lo[0]);
    if (p[0] == hi[0]) return w + std::abs(p[1] - lo[1]);
    if (p[1] == hi[1]) return w + h + std::abs(hi[0] - p[0]);
    if (p[0] == lo[0]) return 2 * w + h + std::abs(hi[1] - p[1]);
    return -1;
  }

  // The grid's rectangle through the boundary samples that are inputs and the boundary's splits, in order.
  Domain2 rectangle() const {
    if (custom()) return current;
    std::vector<std::pair<double, Point2>> ring;
    auto take = [&](int c, int r) {
      const std::size_t s = grid.index(c, r);
      if (samples.count(s)) ring.push_back({perimeter_position(position(s)), position(s)});
    };
    for (int c = 0; c < grid.width; ++c) take(c, 0), take(c, grid.height - 1);
    for (int r = 1; r + 1 < grid.height; ++r) take(0, r), take(grid.width - 1, r);
    for (const Point2& p : boundary_splits) ring.push_back({perimeter_position(p), p});
    std::sort(ring.begin(), ring.end());
    Domain2 d;
    d.rings.push_back({{}, RingRole::Shore});
    for (const auto& [t, p] : ring) d.rings[0].points.push_back(p);
    return d;
  }

  bool same_boundary_line(const Point2& a, const Point2& b) const {
    if (custom()) return constrained.count(std::minmax(a, b)) != 0;
    const Point2 lo = grid.position(0, 0), hi = grid.position(grid.width - 1, grid.height - 1);
    return (a[0] == b[0] && (a[0] == lo[0] || a[0] == hi[0])) || (a[1] == b[1] && (a[1] == lo[1] || a[1] == hi[1]));
  }

  // The refined rings' consecutive points are the mesh's constrained edges; each lies on the segment of
  // `current` whose vertices the walk passed last (the refinement only inserts points into segments).
  void index_constrained() {
    constrained.clear();
    const Domain2& refined = refinement->refined();
    for (std::size_t k = 0; k < refined.rings.size() && k < current.rings.size(); ++k) {
      const Ring& r = refined.rings[k];
      const std::vector<Point2>& vertices = current.rings[k].points;
      if (r.points.size() < 2 || vertices.empty()) continue;
      std::size_t j = 0;
      for (std::size_t i = 0; i < r.segment_count(); ++i) {
        const Point2& a = r.points[i];
        const Point2& b = r.points[(i + 1) % r.points.size()];
        if (j + 1 < vertices.size() && a == vertices[j + 1]) ++j;
        constrained.emplace(std::minmax(a, b), std::make_pair(k, j));
      }
    }
  }

  // Boundary splits go into `current`, each after the vertex that starts its segment, in order along it.
  void insert_splits(const std::vector<Point2>& splits) {
    std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<double, Point2>>> by_segment;
    for (const Point2& m : splits) {
      const auto edge = split_edge.find(m);
      if (edge == split_edge.end()) continue;
      const auto at = constrained.find(std::minmax(edge->second.first, edge->second.second));
      if (at == constrained.end()) continue;
      const Point2& start = current.rings[at->second.first].points[at->second.second];
      by_segment[at->second].push_back({std::hypot(m[0] - start[0], m[1] - start[1]), m});
    }
    for (auto it = by_segment.rbegin(); it != by_segment.rend(); ++it) {  // later segments first
      std::sort(it->second.begin(), it->second.end());
      std::vector<Point2>& ring = current.rings[it->first.first].points;
      std::vector<Point2> mids;
      for (const auto& [d, m] : it->second) mids.push_back(m);
      ring.insert(ring.begin() + static_cast<std::ptrdiff_t>(it->first.second) + 1, mids.begin(), mids.end());
    }
  }

  double node_height(const Point2& p) const {
    const auto it = sample_at.find(p);
    return it != sample_at.end() ? static_cast<double>(grid.z[it->second]) : grid.bilinear(p);
  }

  Tin make_tin() const {
    const std::vector<Point2>& pts = mesh->points();
    const std::vector<Element<2>> tri = mesh->elements();  // canonical: Mesh::canonicalize_ties
    std::vector<std::uint32_t> used;
    for (const auto& t : tri) used.insert(used.end(), t.begin(), t.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::sort(used.begin(), used.end(), [&](std::uint32_t x, std::uint32_t y) { return pts[x] < pts[y]; });
    std::vector<std::uint32_t> renumber(pts.size(), 0);
    Tin out;
    for (std::uint32_t k = 0; k < used.size(); ++k) {
      const Point2& p = pts[used[k]];
      renumber[used[k]] = k;
      out.points.push_back(p);
      out.heights.push_back(node_height(p));
      out.kinds.push_back(sample_at.count(p) ? PointKind::Input : PointKind::Steiner);
    }
    for (auto t : tri) {
      for (auto& v : t) v = renumber[v];
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      out.triangles.push_back(t);
    }
    std::sort(out.triangles.begin(), out.triangles.end());
    return out;
  }

  const Tin& current_tin() const {
    if (tin_stale) tin = make_tin(), tin_stale = false;
    return tin;
  }

  // A triangle's error, and the midpoints of its boundary edges whose third corner lies in their
  // diametral circle (the triangle is then not Delaunay, and the angle bound does not cover it:
  // Ruppert's rule, which ends for the rectangle's right angles).
  void measure_triangle(const ElementCorners<2>& key, TerrainUpdate& u) {
    TriangleState st;
    st.error = measure(grid, {key[0], key[1], key[2]}, {node_height(key[0]), node_height(key[1]), node_height(key[2])},
                       options.bound_from);
    ++u.triangles_measured;
    for (int k = 0; k < 3; ++k) {
      const Point2 &a = key[(k + 1) % 3], &b = key[(k + 2) % 3], &c = key[k];
      if (!same_boundary_line(a, b)) continue;
      // Inside rings, the refinement already sees ring points and picks: only Steiner points encroach here.
      if (custom() && input_id.count(c)) continue;
      // c in the diametral circle of ab: an obtuse angle at c (CGAL's exact predicate).
      const bool encroached = CGAL::angle(Kernel::Point_2(a[0], a[1]), Kernel::Point_2(c[0], c[1]),
                                          Kernel::Point_2(b[0], b[1])) == CGAL::OBTUSE;
      const Point2 mid{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
      const Point2 gm = grid.to_grid(mid), ga = grid.to_grid(a);
      // No split below 1/1024 of a cell: the engine resolves it, but no DEM error needs it.
      if (encroached && std::hypot(gm[0] - ga[0], gm[1] - ga[1]) > 1.0 / 1024) {
        st.splits.push_back(mid);
        if (custom()) split_edge.insert_or_assign(mid, std::make_pair(a, b));
      }
    }
    if (st.error.error > options.max_error || !st.splits.empty()) flagged.insert(key);
    else flagged.erase(key);
    triangles.insert_or_assign(key, std::move(st));
  }

  // The triangles follow the mesh's change: those that went are forgotten, those that came measured.
  void follow(const MeshDelta<2>& delta, TerrainUpdate& u) {
    const auto t0 = Clock::now();
    for (const auto& k : delta.removed) triangles.erase(k), flagged.erase(k);
    for (const auto& k : delta.added) measure_triangle(k, u);
    tin_stale = true;
    u.error_ms += ms_since(t0);
  }

  // The round's picks: the sample of largest error of every triangle over the bound (sorted), and the
  // midpoints of encroached boundary edges. A function of the TIN: `flagged` holds exactly its triangles
  // that have either.
  std::vector<std::size_t> picks_of_round(std::vector<Point2>& splits) const {
    std::vector<std::size_t> out;
    // Candidates: sample -> (error, the longest edge squared of its triangles, in cells).
    std::map<std::size_t, std::pair<double, double>> candidates;
    for (const auto& key : flagged) {
      const TriangleState& st = triangles.at(key);
      if (st.error.error > options.max_error && st.error.sample != kNoSample && !samples.count(st.error.sample)) {
        out.push_back(st.error.sample);
        if (options.pick_spacing > 0) {
          double longest = 0;
          for (int k = 0; k < 3; ++k) {
            const Point2 a = grid.to_grid(key[k]), b = grid.to_grid(key[(k + 1) % 3]);
            longest = std::max(longest, (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]));
          }
          auto& c = candidates[st.error.sample];
          c.first = st.error.error;
          c.second = std::max(c.second, longest);
        }
      }
      splits.insert(splits.end(), st.splits.begin(), st.splits.end());
    }
    std::sort(splits.begin(), splits.end());
    splits.erase(std::unique(splits.begin(), splits.end()), splits.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    if (options.pick_spacing > 0) out = thin_picks(candidates);
    return out;
  }

  // The candidates that are local maxima of the error: none better (larger error, ties the smaller index)
  // within pick_spacing times its triangle's longest edge. Distances between lattice samples are exact in
  // integers; the candidates are a function of the TIN, so the kept ones are too, whatever their order.
  std::vector<std::size_t> thin_picks(const std::map<std::size_t, std::pair<double, double>>& candidates) const {
    constexpr long long kBucket = 16;  // cells per bucket side
    std::unordered_map<long long, std::vector<std::size_t>> buckets;
    const long long w = grid.width, span = (w + kBucket - 1) / kBucket + 1;
    auto bucket_of = [&](long long c, long long r) { return (r / kBucket) * span + c / kBucket; };
    for (const auto& [s, v] : candidates) buckets[bucket_of(static_cast<long long>(s) % w, static_cast<long long>(s) / w)].push_back(s);
    auto better = [&](std::size_t a, std::size_t b) {  // a before b
      const double ea = candidates.at(a).first, eb = candidates.at(b).first;
      return ea > eb || (ea == eb && a < b);
    };
    std::vector<std::size_t> out;
    for (const auto& [s, v] : candidates) {
      const long long c = static_cast<long long>(s) % w, r = static_cast<long long>(s) / w;
      const double reach2 = options.pick_spacing * options.pick_spacing * v.second;
      const long long reach = static_cast<long long>(std::ceil(std::sqrt(reach2)));
      bool kept = true;
      for (long long br = std::max(0LL, r - reach) / kBucket; kept && br <= (r + reach) / kBucket; ++br)
        for (long long bc = std::max(0LL, c - reach) / kBucket; kept && bc <= (c + reach) / kBucket; ++bc) {
          const auto it = buckets.find(br * span + bc);
          if (it == buckets.end()) continue;
          for (std::size_t o : it->second) {
            if (o == s || !better(o, s)) continue;
            const long long dc = static_cast<long long>(o) % w - c, dr = static_cast<long long>(o) / w - r;
            if (static_cast<double>(dc * dc + dr * dr) < reach2) {
              kept = false;
              break;
            }
          }
        }
      if (kept) out.push_back(s);
    }
    return out;
  }

  // The engine's input points for the current samples: the rectangle through the boundary samples, the
  // other samples, and the rectangle's canonical splits.
  void build_engine(TerrainUpdate& u) {
    const auto t0 = Clock::now();
    const Domain2 rect = rectangle();
    std::vector<Point2> loose;
    for (std::size_t s : samples)
      if (!on_boundary(s)) loose.push_back(position(s));
    refinement.emplace(rect, loose, RefinementRule::for_box(box.side));
    if (custom()) index_constrained();
    std::vector<Point2> inputs;
    for (const Ring& ring : rect.rings) inputs.insert(inputs.end(), ring.points.begin(), ring.points.end());
    if (custom()) {  // lines and rings may share vertices: each point once
      std::sort(inputs.begin(), inputs.end());
      inputs.erase(std::unique(inputs.begin(), inputs.end()), inputs.end());
    }
    inputs.insert(inputs.end(), loose.begin(), loose.end());
    for (const Point2& p : refinement->split_points()) inputs.push_back(p);
    for (std::size_t s : samples) sample_at.emplace(position(s), s);
    ws.emplace(inputs, options.engine, box);
    for (std::size_t i = 0; i < inputs.size(); ++i) input_id.emplace(inputs[i], i);
    u.engine_ms += ms_since(t0);
    const auto t1 = Clock::now();
    const std::vector<Point2> points = ws->points();
    mesh.emplace(points, ws->input_count(), refinement->refined());
    mesh->canonicalize_ties();
    u.mesh_ms += ms_since(t1);
    MeshDelta<2> all;
    for (const auto& e : mesh->elements()) {
      ElementCorners<2> c{points[e[0]], points[e[1]], points[e[2]]};
      std::sort(c.begin(), c.end());
      all.added.push_back(c);
    }
    follow(all, u);
  }

  // Samples become inputs (`added`) or stop being inputs (`removed`): one batch for the rectangle's splits,
  // the engine and the mesh.
  void change_samples(const std::vector<std::size_t>& added, const std::vector<std::size_t>& removed, TerrainUpdate& u,
                      const std::vector<Point2>& splits_added = {}, const std::vector<Point2>& splits_removed = {},
                      const std::vector<Point2>& ring_gone = {}, const std::vector<Point2>& ring_come = {},
                      bool rings_replaced = false, bool places_kept = false) {
    const auto t0 = Clock::now();
    std::vector<Point2> loose_added, loose_removed, gone(splits_removed), come(splits_added);
    gone.insert(gone.end(), ring_gone.begin(), ring_gone.end());
    come.insert(come.end(), ring_come.begin(), ring_come.end());
    for (const Point2& p : splits_removed) boundary_splits.erase(p);
    for (const Point2& p : splits_added) boundary_splits.insert(p);
    if (custom()) insert_splits(splits_added);
    for (std::size_t s : removed) {
      samples.erase(s);
      const Point2 p = position(s);
      sample_at.erase(p);
      gone.push_back(p);
      if (!on_boundary(s)) loose_removed.push_back(p);
    }
    for (std::size_t s : added) {
      samples.insert(s);
      const Point2 p = position(s);
      sample_at.emplace(p, s);
      come.push_back(p);
      if (!on_boundary(s)) loose_added.push_back(p);
    }
    // `rings_replaced`: the rings were traced again; the mesh is then made afresh. `places_kept`: they kept
    // their places (follow_contours), so the refinement follows them by stretches as it follows a round's
    // splits; otherwise (a new tracing's order) it is made afresh too.
    const bool new_rings = !ring_gone.empty() || !ring_come.empty() || rings_replaced;
    SplitChange splits;
    if (!new_rings || places_kept) {
      splits = refinement->update(rectangle(), loose_removed, loose_added);
    } else {
      // The rings were traced again: the refinement is made afresh (ShoreRefinement::update matches rings
      // by their place and keeps a ring's role, and a traced ring list reorders: a line at one index
      // became a shore ring there, and the mesh lost its water), the split points' change by difference.
      const std::vector<Point2> old_splits = refinement->split_points();
      std::vector<Point2> loose;
      for (std::size_t s : samples)
        if (!on_boundary(s)) loose.push_back(position(s));
      refinement.emplace(rectangle(), loose, RefinementRule::for_box(box.side));
      const std::vector<Point2> new_splits = refinement->split_points();  // sorted
      std::set_difference(old_splits.begin(), old_splits.end(), new_splits.begin(), new_splits.end(),
                          std::back_inserter(splits.removed));
      std::set_difference(new_splits.begin(), new_splits.end(), old_splits.begin(), old_splits.end(),
                          std::back_inserter(splits.added));
    }
    if (custom()) index_constrained();
    gone.insert(gone.end(), splits.removed.begin(), splits.removed.end());
    come.insert(come.end(), splits.added.begin(), splits.added.end());
    // A point that goes and comes (a split where a sample now is) keeps its id.
    std::sort(gone.begin(), gone.end());
    std::sort(come.begin(), come.end());
    gone.erase(std::unique(gone.begin(), gone.end()), gone.end());
    come.erase(std::unique(come.begin(), come.end()), come.end());
    std::vector<Point2> removed_points, added_points;
    std::set_difference(gone.begin(), gone.end(), come.begin(), come.end(), std::back_inserter(removed_points));
    std::set_difference(come.begin(), come.end(), gone.begin(), gone.end(), std::back_inserter(added_points));
    std::vector<Edit<2>> edits;
    for (const Point2& p : removed_points) {
      const auto it = input_id.find(p);
      edits.push_back({Edit<2>::Kind::Remove, it->second, {}});
      input_id.erase(it);
    }
    for (const Point2& p : added_points) edits.push_back({Edit<2>::Kind::Add, 0, p});
    UpdateReport<2> report;
    const std::vector<std::size_t> ids = ws->apply(edits, &report);
    for (std::size_t i = 0; i < ids.size(); ++i) input_id.emplace(added_points[i], ids[i]);
    u.steiner_added += report.steiner_added.size();
    u.steiner_removed += report.steiner_removed.size();
    u.operations += report.operations_touched();
    u.engine_ms += ms_since(t0);
    const auto t1 = Clock::now();
    MeshDelta<2> delta;
    if (!new_rings) {
      delta = mesh->apply(PointChange<2>::from_update(report, removed_points, added_points), refinement->refined());
    } else {
      // The rings were traced again: the mesh is built afresh on the engine's points and the new rings,
      // and the delta is the difference of the two triangle sets. Mesh::apply with the rings in their
      // places is no cheaper while the batch takes back every pick (201 against 115 ms on the Salish Sea,
      // bench/RESULTS.md), and it keeps a place's role: a shore ring taking a line's emptied place lost
      // its water (LandWaterEdits.RandomDemPatchesEqualFreshRunsOnACropOfTheSalishSea).
      std::vector<ElementCorners<2>> before;
      before.reserve(triangles.size());
      for (const auto& [key, st] : triangles) before.push_back(key);
      std::sort(before.begin(), before.end());
      const std::vector<Point2> points = ws->points();
      mesh.emplace(points, ws->input_count(), refinement->refined());
      mesh->canonicalize_ties();
      std::vector<ElementCorners<2>> after;
      for (const auto& e : mesh->elements()) {
        ElementCorners<2> c{points[e[0]], points[e[1]], points[e[2]]};
        std::sort(c.begin(), c.end());
        after.push_back(c);
      }
      std::sort(after.begin(), after.end());
      std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(delta.removed));
      std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(delta.added));
    }
    u.mesh_ms += ms_since(t1);
    follow(delta, u);
  }

  TerrainUpdate patch(int col, int row, int w, int h, std::span<const float> z, std::span<const std::uint8_t> valid,
                      const Domain2* domain);
  // The mesh equals a fresh one, the triangle cache fresh measurements (std::logic_error otherwise).
  void check_level() const;

  // Inside rings: midpoints of the constrained edges that a Steiner point encroaches from either side (in
  // the edge's diametral circle). measure_triangle sees only the apex of the kept triangle on an edge; a
  // Steiner point outside the domain (the engine fills its whole box) can lie in the diametral circle and
  // in the kept triangle's circumcircle behind the constraint, which then is not Delaunay and not covered
  // by the angle bound (docs/terrain.md: 18.77 degrees on the synthetic valley before). Recomputed every
  // round from the mesh's points (not cached by triangle: the encroacher is no corner of the kept
  // triangle), so a round stays a function of the TIN and its points.
  std::vector<Point2> encroached_from_anywhere() {
    std::vector<Point2> out;
    if (!custom()) return out;
    const std::vector<Point2>& pts = mesh->points();
    auto cell_of = [&](const Point2& p) {
      const Point2 q = grid.to_grid(p);
      return std::array<long long, 2>{static_cast<long long>(std::floor(q[0])), static_cast<long long>(std::floor(q[1]))};
    };
    std::map<std::array<long long, 2>, std::vector<std::uint32_t>> cells;
    for (std::uint32_t i = 0; i < pts.size(); ++i)
      if (!input_id.count(pts[i])) cells[cell_of(pts[i])].push_back(i);
    for (const auto& [edge, at] : constrained) {
      const auto& [a, b] = edge;
      const Point2 mid{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
      const Point2 gm = grid.to_grid(mid), ga = grid.to_grid(a);
      const double half = std::hypot(gm[0] - ga[0], gm[1] - ga[1]);  // in cells
      if (half <= 1.0 / 1024) continue;  // no split below 1/1024 of a cell, as measure_triangle
      const double radius = 0.5 * std::hypot(b[0] - a[0], b[1] - a[1]);
      const double hc = radius / std::abs(grid.dx), hr = radius / std::abs(grid.dy);
      const long long c0 = static_cast<long long>(std::floor(gm[0] - hc)), c1 = static_cast<long long>(std::floor(gm[0] + hc));
      const long long r0 = static_cast<long long>(std::floor(gm[1] - hr)), r1 = static_cast<long long>(std::floor(gm[1] + hr));
      bool encroached = false;
      const Kernel::Point_2 ka(a[0], a[1]), kb(b[0], b[1]);
      for (long long r = r0; r <= r1 && !encroached; ++r)
        for (long long c = c0; c <= c1 && !encroached; ++c) {
          const auto it = cells.find({c, r});
          if (it == cells.end()) continue;
          for (std::uint32_t i : it->second)
            if (CGAL::angle(ka, Kernel::Point_2(pts[i][0], pts[i][1]), kb) == CGAL::OBTUSE) {
              encroached = true;
              break;
            }
        }
      if (!encroached) continue;
      out.push_back(mid);
      split_edge.insert_or_assign(mid, std::make_pair(a, b));
    }
    return out;
  }

  // The round's output on the current TIN: the picked samples (sorted) and the midpoints of encroached
  // boundary edges (sorted) that are not samples. A function of the TIN and its points.
  void round_output(std::vector<std::size_t>& round, std::vector<Point2>& splits, TerrainUpdate& u) {
    splits = encroached_from_anywhere();
    const auto t0 = Clock::now();
    round = picks_of_round(splits);
    u.error_ms += ms_since(t0);
    // A midpoint at a sample (to rounding: it halves an edge between samples) is that sample (on the
    // rectangle, whose ring takes its input samples; inside rings a split stays a ring point).
    std::erase_if(splits, [&](const Point2& p) {
      if (custom()) return false;
      const Point2 g = grid.to_grid(p);
      const double c = std::round(g[0]), r = std::round(g[1]);
      if (std::abs(g[0] - c) > 1e-6 || std::abs(g[1] - r) > 1e-6) return false;
      round.push_back(grid.index(static_cast<int>(c), static_cast<int>(r)));
      return true;
    });
    std::sort(round.begin(), round.end());
    round.erase(std::unique(round.begin(), round.end()), round.end());
    std::erase_if(round, [&](std::size_t s) { return samples.count(s) != 0; });
  }

  // Inside rings: every round goes into this one engine (a patch takes all picks back and replays them).
  void run_rounds(TerrainUpdate& u) {
    rounds = 0;
    for (;;) {
      std::vector<std::size_t> round;
      std::vector<Point2> splits;
      round_output(round, splits, u);
      if (round.empty() && splits.empty()) break;
      ++rounds;
      picks.insert(round.begin(), round.end());
      u.picks_added += round.size();
      u.boundary_splits += splits.size();
      change_samples(round, {}, u, splits);
    }
    u.rounds = rounds;
  }

  // ---- Rounds in levels (the rectangle's TIN; docs/terrain.md "One setting for both targets") -------
  // Level 0 (this Impl) holds the round-0 input (corners, seeds, block picks); level k + 1 (deeper[k]) holds
  // level k's input and level k's round output, each level in an engine and a mesh of its own. A level's
  // TIN is therefore the TIN of round k of a fresh run, and a patch brings every level up to date through
  // its own engine: a level's round output is recomputed from its flagged triangles (kept exactly by the
  // mesh deltas), and only its difference goes to the next level.
  std::vector<std::unique_ptr<Impl>> deeper;
  std::vector<std::size_t> out_picks;  // this level's round output
  std::vector<Point2> out_splits;
  bool layered = false;

  Impl& last() { return deeper.empty() ? *this : *deeper.back(); }
  const Impl& last() const { return deeper.empty() ? *this : *deeper.back(); }
  Impl& level(std::size_t k) { return k == 0 ? *this : *deeper[k - 1]; }
  const Impl& level(std::size_t k) const { return k == 0 ? *this : *deeper[k - 1]; }

  // A build does not make the levels: it runs the rounds in one engine (a walker, which ends as the deepest
  // level, the session's TIN) and records every round's output; the first patch builds levels 0 to K - 1
  // from those (each afresh, StableWS on its input), before it changes any height. Until then `deeper`
  // holds the walker alone.
  bool levels_ready = true;
  std::vector<std::pair<std::vector<std::size_t>, std::vector<Point2>>> recorded;

  void walk_rounds(TerrainUpdate& u) {
    auto walker = std::make_unique<Impl>();
    walker->grid = grid;
    walker->options = options;
    walker->box = box;
    walker->samples = samples;
    walker->build_engine(u);
    recorded.clear();
    for (;;) {
      std::vector<std::size_t> round;
      std::vector<Point2> splits;
      walker->round_output(round, splits, u);
      if (round.empty() && splits.empty()) break;
      walker->picks.insert(round.begin(), round.end());
      u.picks_added += round.size();
      u.boundary_splits += splits.size();
      walker->change_samples(round, {}, u, splits);
      recorded.emplace_back(std::move(round), std::move(splits));
    }
    deeper.clear();
    deeper.push_back(std::move(walker));
    levels_ready = false;
    rounds = recorded.size();
    u.rounds = rounds;
  }

  void materialize(TerrainUpdate& u) {
    if (levels_ready) return;
    std::unique_ptr<Impl> walker = std::move(deeper.back());
    deeper.clear();
    build_engine(u);  // level 0: the round-0 input
    for (std::size_t k = 0; k < recorded.size(); ++k) {
      Impl& l = last();
      l.out_picks = recorded[k].first;
      l.out_splits = recorded[k].second;
      if (k + 1 < recorded.size()) push_level(u);
    }
    if (!recorded.empty()) deeper.push_back(std::move(walker));  // level K (no rounds: level 0 is it)
    recorded.clear();
    levels_ready = true;
  }

  // A new deepest level: the deepest level's input and its round output, built afresh (StableWS on it).
  void push_level(TerrainUpdate& u) {
    const Impl& from = last();
    auto next = std::make_unique<Impl>();
    next->grid = from.grid;
    next->options = options;
    next->box = box;
    next->samples = from.samples;
    next->samples.insert(from.out_picks.begin(), from.out_picks.end());
    next->picks = from.picks;
    next->picks.insert(from.out_picks.begin(), from.out_picks.end());
    next->boundary_splits = from.boundary_splits;
    next->boundary_splits.insert(from.out_splits.begin(), from.out_splits.end());
    u.picks_added += from.out_picks.size();
    u.boundary_splits += from.out_splits.size();
    next->build_engine(u);
    deeper.push_back(std::move(next));
  }

  // From level `k` on: each level's round output, and a new level while it is not empty.
  void grow_levels(std::size_t k, TerrainUpdate& u) {
    for (;; ++k) {
      Impl& l = level(k);
      l.round_output(l.out_picks, l.out_splits, u);
      if (l.out_picks.empty() && l.out_splits.empty()) break;
      push_level(u);
    }
    deeper.resize(k);
    rounds = deeper.size();
    u.rounds = rounds;
  }

  // A patch of a layered session: the window's heights are in level 0's grid and `added` / `removed` are
  // level 0's input change (already applied there). Every deeper level takes the heights, the same change
  // of the round-0 input, and the change of the picks and splits of the rounds above it.
  void patch_levels(int col, int row, int w, int h, const std::vector<std::size_t>& base_added,
                    const std::vector<std::size_t>& base_removed, TerrainUpdate& u) {
    std::size_t k = 0;
    for (; k < deeper.size(); ++k) {
      Impl& above = level(k);
      above.round_output(above.out_picks, above.out_splits, u);
      // Nothing over the bound: the fresh run stops at this level, and the deeper ones go.
      if (above.out_picks.empty() && above.out_splits.empty()) break;
      Impl& l = *deeper[k];
      // The level's heights.
      for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) {
          const std::size_t i = grid.index(col + c, row + r);
          l.grid.z[i] = grid.z[i];
        }
      l.grid.valid = grid.valid;  // small next to a rebuild; only a patch with a mask changes it
      // Its new input: the level above's input and output.
      std::set<std::size_t> picks_after(above.picks);
      picks_after.insert(above.out_picks.begin(), above.out_picks.end());
      std::set<Point2> splits_after(above.boundary_splits);
      splits_after.insert(above.out_splits.begin(), above.out_splits.end());
      std::vector<std::size_t> touched(base_added);
      touched.insert(touched.end(), base_removed.begin(), base_removed.end());
      std::set_symmetric_difference(l.picks.begin(), l.picks.end(), picks_after.begin(), picks_after.end(),
                                    std::back_inserter(touched));
      std::sort(touched.begin(), touched.end());
      touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
      std::vector<std::size_t> added, removed;
      for (std::size_t s : touched) {
        const bool want = in_base(s) || picks_after.count(s);
        const bool have = l.samples.count(s) != 0;
        if (want && !have) added.push_back(s);
        if (!want && have) removed.push_back(s);
      }
      std::vector<Point2> splits_added, splits_removed;
      std::set_difference(splits_after.begin(), splits_after.end(), l.boundary_splits.begin(), l.boundary_splits.end(),
                          std::back_inserter(splits_added));
      std::set_difference(l.boundary_splits.begin(), l.boundary_splits.end(), splits_after.begin(), splits_after.end(),
                          std::back_inserter(splits_removed));
      const std::size_t before = l.picks.size();
      l.picks = std::move(picks_after);
      u.picks_added += l.picks.size() > before ? l.picks.size() - before : 0;
      u.picks_removed += before > l.picks.size() ? before - l.picks.size() : 0;
      l.remeasure_window(col, row, w, h, u);
      if (!added.empty() || !removed.empty() || !splits_added.empty() || !splits_removed.empty())
        l.change_samples(added, removed, u, splits_added, splits_removed);
    }
    if (k < deeper.size()) {
      deeper.resize(k);
      rounds = deeper.size();
      u.rounds = rounds;
      return;
    }
    // The deepest level may now have an output: new levels.
    grow_levels(deeper.size(), u);
  }

  // Level 0's round-0 input membership (the same at every level).
  bool in_base(std::size_t s) const {
    const auto c = corners();
    return std::find(c.begin(), c.end(), s) != c.end() || seeds.contains(s) || blocks.contains(s);
  }

  // Triangles with a sample or a node in reach of changed heights are measured again.
  void remeasure_window(int col, int row, int w, int h, TerrainUpdate& u) {
    const auto t1 = Clock::now();
    // Within one cell (a node's bilinear height reads the samples less than a cell away); half a cell more
    // against rounding: measuring a triangle again is harmless.
    const Point2 a = grid.position(col, row), b = grid.position(col + w - 1, row + h - 1);
    const double mx = 1.5 * std::abs(grid.dx), my = 1.5 * std::abs(grid.dy);
    const Point2 lo{std::min(a[0], b[0]) - mx, std::min(a[1], b[1]) - my}, hi{std::max(a[0], b[0]) + mx, std::max(a[1], b[1]) + my};
    for (const auto& key : mesh->elements_meeting(lo, hi)) measure_triangle(key, u);
    tin_stale = true;  // heights changed
    u.error_ms += ms_since(t1);
  }
};

TerrainSession::TerrainSession(HeightGrid grid, const TerrainOptions& options) : impl_(std::make_unique<Impl>()) {
  const bool custom = !options.domain.empty();
  if (!(options.max_error > 0) || (!std::isfinite(options.max_error) && !custom))
    throw ParameterError("the maximum error must be a finite number above 0 (got " + readable(options.max_error) + ")");
  if (custom && options.seed_fraction != 0)
    throw ParameterError("seeds are for the rectangle's TIN, not for a TIN inside rings");
  if (std::isnan(options.bound_from)) throw ParameterError("the height the error bound applies from is NaN");
  if (!(options.pick_spacing >= 0 && std::isfinite(options.pick_spacing)))
    throw ParameterError("the picks' spacing must be a finite number >= 0 (got " + readable(options.pick_spacing) + ")");
  if (options.block_cells < 0 || options.block_cells == 1)
    throw ParameterError("the picks' blocks must be 0 (none) or at least 2 cells wide (got " +
                         std::to_string(options.block_cells) + ")");
  if (!(options.block_fraction > 0 && options.block_fraction <= 1))
    throw ParameterError("the block picks' fraction of the maximum error must lie in (0, 1] (got " +
                         readable(options.block_fraction) + ")");
  if (custom)
    if (const auto defect = find_ring_defect(options.domain, true))
      throw InputError("the TIN's rings and lines: " + defect->describe());
  if (!(options.seed_fraction >= 0 && options.seed_fraction <= 1))
    throw ParameterError("the seeds' fraction of the maximum error must lie in [0, 1] (got " +
                         readable(options.seed_fraction) + ")");
  if (grid.width < 2 || grid.height < 2)
    throw InputError("a terrain needs a grid of at least 2 x 2 samples (got " + std::to_string(grid.width) + " x " +
                     std::to_string(grid.height) + ")");
  if (grid.z.size() != static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height) ||
      (!grid.valid.empty() && grid.valid.size() != grid.z.size()))
    throw InputError("the grid's heights do not match its size");
  if (!(grid.dx != 0 && grid.dy != 0 && std::isfinite(grid.dx) && std::isfinite(grid.dy)))
    throw InputError("the grid's sample spacing must be finite and non-zero");
  std::size_t valid = 0;
  for (std::size_t i = 0; i < grid.z.size(); ++i) {
    if (!std::isfinite(grid.z[i])) throw InputError("sample " + std::to_string(i) + " has a height that is not finite");
    valid += grid.is_valid(i);
  }
  if (valid == 0) throw InputError("the grid holds no data (every sample is nodata)");
  Impl& m = *impl_;
  m.grid = std::move(grid);
  m.options = options;
  m.current = options.domain;
  const auto t0 = Clock::now();
  m.seeds.build(m.grid, options.seed_fraction * options.max_error);
  if (!custom)
    for (std::size_t s : m.corners()) m.samples.insert(s);
  for (std::size_t s : m.seeds.sorted()) m.samples.insert(s);
  if (!custom) {  // inside rings the samples are loose points of the rings' domain: no blocks
    m.blocks.build(m.grid, options.block_cells, options.block_fraction * options.max_error, options.bound_from);
    for (std::size_t s : m.blocks.sorted()) m.samples.insert(s);
  }
  m.build.seeds_added = m.seeds.size();
  m.build.block_picks_added = m.blocks.size();
  m.build.seed_ms = ms_since(t0);
  const std::array<std::size_t, 4> corners = m.corners();
  std::vector<Point2> corner_points;
  for (std::size_t s : corners) corner_points.push_back(m.position(s));
  if (custom) {
    // The box is a function of the grid alone (not of the rings), so that a patch that moves the rings
    // keeps the engine's box, as a fresh run on the patched grid has it: the samples' rectangle grown by a
    // cell (the traced contours lie within half a cell of it).
    corner_points = {m.grid.position(-1, -1), m.grid.position(m.grid.width, m.grid.height)};
    m.box = BoxTransform<2>::fit(corner_points);
    m.check_in_box(m.options.domain);
  } else {
    m.box = BoxTransform<2>::fit(corner_points);
  }
  m.layered = !custom;
  if (m.layered) {
    m.walk_rounds(m.build);
  } else {
    m.build_engine(m.build);
    m.run_rounds(m.build);
  }
}

TerrainSession::~TerrainSession() = default;
TerrainSession::TerrainSession(TerrainSession&&) noexcept = default;
TerrainSession& TerrainSession::operator=(TerrainSession&&) noexcept = default;

TerrainUpdate TerrainSession::patch(int col, int row, int w, int h, std::span<const float> z,
                                    std::span<const std::uint8_t> valid) {
  if (impl_->custom())
    throw ParameterError("a TIN inside rings (land and water) is patched with its rings traced on the patched grid");
  return impl_->patch(col, row, w, h, z, valid, nullptr);
}

TerrainUpdate TerrainSession::patch(int col, int row, int w, int h, std::span<const float> z,
                                    std::span<const std::uint8_t> valid, const Domain2& domain) {
  if (!impl_->custom()) throw ParameterError("the rectangle's TIN takes no rings: patch it without them");
  if (domain.empty()) throw InputError("a land-and-water TIN needs rings after the patch too");
  // Places emptied by rings that went (follow_contours) bound nothing: the check sees the others.
  bool has_empty = false;
  for (const Ring& r : domain.rings) has_empty = has_empty || r.points.empty();
  std::optional<RingDefect> defect;
  if (has_empty) {
    Domain2 filled;
    for (const Ring& r : domain.rings)
      if (!r.points.empty()) filled.rings.push_back(r);
    if (filled.empty()) throw InputError("a land-and-water TIN needs rings after the patch too");
    defect = find_ring_defect(filled, true);
  } else {
    defect = find_ring_defect(domain, true);
  }
  if (defect) throw InputError("the TIN's rings and lines after the patch: " + defect->describe());
  impl_->check_in_box(domain);
  return impl_->patch(col, row, w, h, z, valid, &domain);
}

TerrainUpdate TerrainSession::Impl::patch(int col, int row, int w, int h, std::span<const float> z,
                                          std::span<const std::uint8_t> valid, const Domain2* domain) {
  Impl& m = *this;
  HeightGrid& g = m.grid;
  if (w <= 0 || h <= 0 || col < 0 || row < 0 || col > g.width - w || row > g.height - h)
    throw InputError("the patch [" + std::to_string(col) + ", " + std::to_string(col + w) + ") x [" + std::to_string(row) +
                     ", " + std::to_string(row + h) + ") does not lie in the grid of " + std::to_string(g.width) + " x " +
                     std::to_string(g.height) + " samples");
  const std::size_t cells = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  if (z.size() != cells || (!valid.empty() && valid.size() != cells))
    throw InputError("the patch holds " + std::to_string(z.size()) + " heights for a window of " + std::to_string(cells));
  for (std::size_t i = 0; i < cells; ++i)
    if (!std::isfinite(z[i])) throw InputError("patch height " + std::to_string(i) + " is not finite");
  std::size_t still_valid = 0;
  if (!valid.empty()) {
    // Refuse a patch that leaves no data before changing anything.
    std::size_t outside = 0;
    for (std::size_t i = 0; i < g.z.size(); ++i) {
      const int c = static_cast<int>(i % g.width), r = static_cast<int>(i / g.width);
      if (c < col || c >= col + w || r < row || r >= row + h) outside += g.is_valid(i);
    }
    for (std::uint8_t v : valid) still_valid += v != 0;
    if (outside + still_valid == 0) throw InputError("the patch would leave the grid without data");
  }
  TerrainUpdate u;
  // The rounds' levels, built on the grid before the patch (their input was recorded by the build).
  if (m.layered) m.materialize(u);
  if (!valid.empty() && g.valid.empty()) g.valid.assign(g.z.size(), 1);
  const auto t0 = Clock::now();
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const std::size_t k = static_cast<std::size_t>(r) * w + c, i = g.index(col + c, row + r);
      g.z[i] = z[k];
      if (!g.valid.empty()) g.valid[i] = valid.empty() || valid[k] != 0;  // a patch without a mask is all data
    }
  const terrain::SampleWindow changed{col, row, col + w - 1, row + h - 1};
  std::vector<std::size_t> seeds_added, seeds_removed, blocks_added, blocks_removed;
  m.seeds.update(g, changed, seeds_added, seeds_removed);
  m.blocks.update(g, changed, blocks_added, blocks_removed);
  u.seeds_added = seeds_added.size();
  u.seeds_removed = seeds_removed.size();
  u.block_picks_added = blocks_added.size();
  u.block_picks_removed = blocks_removed.size();
  u.seed_ms = ms_since(t0);
  // The correction rounds start again from the round-0 input (corners, seeds, block picks): every
  // correction pick goes (one that is now a seed or a block pick stays). The samples go from `samples` to
  // the new round-0 input, computed from the change alone (not a copy of every sample).
  std::set<std::size_t> corner_samples;  // inside rings, the grid's corners are no inputs
  if (!m.custom())
    for (std::size_t s : m.corners()) corner_samples.insert(s);
  auto in_base = [&](std::size_t s) { return corner_samples.count(s) || m.seeds.contains(s) || m.blocks.contains(s); };
  std::set<std::size_t> leaving(m.picks.begin(), m.picks.end()), coming(corner_samples);
  leaving.insert(seeds_removed.begin(), seeds_removed.end());
  leaving.insert(blocks_removed.begin(), blocks_removed.end());
  coming.insert(seeds_added.begin(), seeds_added.end());
  coming.insert(blocks_added.begin(), blocks_added.end());
  std::vector<std::size_t> added, removed;
  for (std::size_t s : leaving)
    if (!in_base(s) && m.samples.count(s)) removed.push_back(s);
  for (std::size_t s : coming)
    if (in_base(s) && !m.samples.count(s)) added.push_back(s);
  u.picks_removed = m.picks.size();
  m.picks.clear();
  m.remeasure_window(col, row, w, h, u);
  const std::vector<Point2> splits_removed(m.boundary_splits.begin(), m.boundary_splits.end());
  if (domain) {
    // The rings move to the patched grid's contours, in the batch that takes back the picks and splits:
    // the engine then holds a fresh run's round-0 input (the new rings' points and their canonical
    // splits), and the rounds replay. A triangle that keeps its corners but whose edge stops or starts
    // being a constraint is measured again (its encroached midpoints change).
    const std::vector<Point2> before = ring_points(m.options.domain), after = ring_points(*domain);
    std::vector<Point2> ring_gone, ring_come;
    std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(ring_gone));
    std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(ring_come));
    std::vector<std::pair<Point2, Point2>> edges_before;
    for (const auto& [e, at] : m.constrained) edges_before.push_back(e);
    // Rings in their places (follow_contours: each place keeps its role until it is emptied) go to the
    // refinement as stretches; otherwise (a new tracing's order) it is made afresh.
    bool in_places = true;
    for (std::size_t k = 0; k < std::min(m.current.rings.size(), domain->rings.size()); ++k) {
      const Ring &was = m.current.rings[k], &now = domain->rings[k];
      if (!was.points.empty() && !now.points.empty() && (was.role != now.role || was.closed() != now.closed()))
        in_places = false;
    }
    m.options.domain = *domain;
    m.current = *domain;
    m.change_samples(added, removed, u, {}, splits_removed, ring_gone, ring_come, true, in_places);
    std::vector<std::pair<Point2, Point2>> edges_after, edges_changed;
    for (const auto& [e, at] : m.constrained) edges_after.push_back(e);
    std::set_symmetric_difference(edges_before.begin(), edges_before.end(), edges_after.begin(), edges_after.end(),
                                  std::back_inserter(edges_changed));
    std::set<ElementCorners<2>> again;
    for (const auto& [a, b] : edges_changed) {
      const Point2 lo{std::min(a[0], b[0]), std::min(a[1], b[1])}, hi{std::max(a[0], b[0]), std::max(a[1], b[1])};
      for (const auto& key : m.mesh->elements_meeting(lo, hi)) again.insert(key);
    }
    for (const auto& key : again) m.measure_triangle(key, u);
  } else if (!added.empty() || !removed.empty() || !splits_removed.empty()) {
    m.change_samples(added, removed, u, {}, splits_removed);
  }
  if (m.layered) m.patch_levels(col, row, w, h, added, removed, u);
  else m.run_rounds(u);
  return u;
}

void TerrainSession::prepare_patches() {
  TerrainUpdate u;
  if (impl_->layered) impl_->materialize(u);
}

const HeightGrid& TerrainSession::grid() const { return impl_->grid; }
const TerrainOptions& TerrainSession::options() const { return impl_->options; }
const TerrainUpdate& TerrainSession::build_stats() const { return impl_->build; }
const std::vector<Point2>& TerrainSession::points() const { return impl_->last().current_tin().points; }
const std::vector<double>& TerrainSession::heights() const { return impl_->last().current_tin().heights; }
const std::vector<PointKind>& TerrainSession::kinds() const { return impl_->last().current_tin().kinds; }
const std::vector<Element<2>>& TerrainSession::triangles() const { return impl_->last().current_tin().triangles; }
std::size_t TerrainSession::seed_count() const { return impl_->seeds.size(); }
std::size_t TerrainSession::pick_count() const { return impl_->last().picks.size(); }
std::size_t TerrainSession::block_pick_count() const { return impl_->blocks.size(); }
std::size_t TerrainSession::input_count() const { return impl_->last().ws->input_count(); }
std::size_t TerrainSession::steiner_count() const { return impl_->last().ws->steiner_count(); }
std::size_t TerrainSession::rounds() const { return impl_->rounds; }

TerrainError TerrainSession::error() const {
  const Impl& m = impl_->last();
  const HeightGrid& g = m.grid;
  std::vector<float> err(g.z.size(), -1.0f);
  std::vector<double> exact(g.z.size(), -1.0);
  const Tin& tin = m.current_tin();
  for (const auto& t : tin.triangles)
    for_each_sample(g, {tin.points[t[0]], tin.points[t[1]], tin.points[t[2]]},
                    {tin.heights[t[0]], tin.heights[t[1]], tin.heights[t[2]]},
                    [&](std::size_t i, double zi) { exact[i] = std::max(exact[i], std::abs(g.z[i] - zi)); });
  TerrainError e;
  double sum = 0;
  for (std::size_t i = 0; i < g.z.size(); ++i) {
    if (!g.is_valid(i) || !(g.z[i] >= m.options.bound_from)) continue;
    if (exact[i] < 0 && m.custom()) continue;  // outside the rings
    ++e.samples;
    const double x = exact[i] < 0 ? std::numeric_limits<double>::infinity() : exact[i];  // outside every triangle
    if (x > e.max || e.samples == 1) e.max = x, e.worst_sample = i;
    e.over += x > m.options.max_error;
    sum += x * x;
  }
  e.rms = e.samples ? std::sqrt(sum / static_cast<double>(e.samples)) : 0;
  return e;
}

void TerrainSession::check_valid() const {
  const Impl& top = *impl_;
  if (!top.levels_ready) {
    // Before the first patch: the walker ran every round; it holds the round-0 input and the recorded
    // round outputs, and its own round output is empty.
    const Impl& walker = *top.deeper.back();
    walker.check_level();
    std::vector<std::size_t> picks;
    std::vector<Point2> splits;
    TerrainUpdate u;
    const_cast<Impl&>(walker).round_output(picks, splits, u);
    if (!picks.empty() || !splits.empty()) throw std::logic_error("the TIN is over the bound");
    std::set<std::size_t> samples(top.samples);
    std::set<Point2> all_splits;
    for (const auto& [r, sp] : top.recorded) samples.insert(r.begin(), r.end()), all_splits.insert(sp.begin(), sp.end());
    if (samples != walker.samples || all_splits != walker.boundary_splits)
      throw std::logic_error("the TIN's input is not the round-0 input with the recorded rounds");
  }
  for (std::size_t k = 0; top.levels_ready && k <= top.deeper.size(); ++k) {
    const Impl& m = top.level(k);
    m.check_level();
    // Level k + 1 holds level k's input and its round output (recomputed here from level k's TIN), and the
    // deepest level's round is empty: the levels are the rounds of a fresh run.
    std::vector<std::size_t> picks;
    std::vector<Point2> splits;
    TerrainUpdate u;
    const_cast<Impl&>(m).round_output(picks, splits, u);
    if (picks != m.out_picks || splits != m.out_splits)
      throw std::logic_error("level " + std::to_string(k) + "'s round output differs from its TIN's");
    if (k == top.deeper.size()) {
      if (!picks.empty() || !splits.empty()) throw std::logic_error("the deepest level's TIN is over the bound");
      break;
    }
    const Impl& next = top.level(k + 1);
    std::set<std::size_t> samples(m.samples), next_picks(m.picks);
    samples.insert(picks.begin(), picks.end());
    next_picks.insert(picks.begin(), picks.end());
    std::set<Point2> next_splits(m.boundary_splits);
    next_splits.insert(splits.begin(), splits.end());
    if (samples != next.samples || next_picks != next.picks || next_splits != next.boundary_splits)
      throw std::logic_error("level " + std::to_string(k + 1) + "'s input is not level " + std::to_string(k) +
                             "'s with its round output");
  }
  const Impl& m = top;
  const Tin again = m.last().make_tin();
  const Tin& tin = m.last().current_tin();
  if (again.points != tin.points || again.triangles != tin.triangles || again.heights != tin.heights)
    throw std::logic_error("the session's TIN is not the canonical TIN of its mesh");
  terrain::Seeds fresh_seeds;
  fresh_seeds.build(m.grid, m.options.seed_fraction * m.options.max_error);
  if (fresh_seeds.sorted() != m.seeds.sorted()) throw std::logic_error("the seeds differ from a fresh quadtree");
  if (!m.custom()) {
    terrain::BlockPicks fresh_blocks;
    fresh_blocks.build(m.grid, m.options.block_cells, m.options.block_fraction * m.options.max_error, m.options.bound_from);
    if (fresh_blocks.sorted() != m.blocks.sorted()) throw std::logic_error("the block picks differ from fresh ones");
  }
  // The input samples of the first level (of the only one inside rings) are the corners (the rectangle's
  // TIN only), the seeds, the block picks and its picks, nothing else.
  std::set<std::size_t> inputs(m.picks.begin(), m.picks.end());
  for (std::size_t s : m.seeds.sorted()) inputs.insert(s);
  for (std::size_t s : m.blocks.sorted()) inputs.insert(s);
  if (!m.custom())
    for (std::size_t s : m.corners()) inputs.insert(s);
  if (inputs != m.samples) throw std::logic_error("the input samples are not the corners, seeds and picks");
}

void TerrainSession::Impl::check_level() const {
  const Impl& m = *this;
  m.mesh->check_valid();
  // The mesh the updates left equals a fresh one on the engine's output and the rectangle, triangle for
  // triangle; every triangle's cached state equals a fresh measurement.
  auto corners = [](const Mesh2& tin_mesh) {
    const auto elements = tin_mesh.elements();
    return sorted_corners<2>(tin_mesh.points(), elements);
  };
  Mesh2 fresh(m.ws->points(), m.ws->input_count(), m.refinement->refined());
  fresh.canonicalize_ties();
  const auto a = corners(*m.mesh), b = corners(fresh);
  if (a != b)
    throw std::logic_error("the updated mesh (" + std::to_string(a.size()) + " triangles) differs from a fresh one (" +
                           std::to_string(b.size()) + ")");
  if (m.triangles.size() != a.size()) throw std::logic_error("the triangle cache does not match the mesh");
  Impl copy;
  copy.grid = m.grid;
  copy.options = m.options;
  copy.sample_at = m.sample_at;
  copy.input_id = m.input_id;
  copy.constrained = m.constrained;
  for (const auto& key : a) {
    TerrainUpdate u;
    copy.measure_triangle(key, u);
    const auto it = m.triangles.find(key);
    const auto& y = copy.triangles.at(key);
    if (it == m.triangles.end() || it->second.error.error != y.error.error || it->second.error.sample != y.error.sample ||
        it->second.splits != y.splits || m.flagged.count(key) != copy.flagged.count(key))
      throw std::logic_error("a triangle's cached error differs from a fresh measurement");
  }
}

}  // namespace shoremesh
