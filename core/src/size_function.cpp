#include "shoremesh/size_function.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <queue>
#include <unordered_map>
#include <unordered_set>

#include "ring_geometry.hpp"
#include "shoremesh/engine/predicates.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/mesh_water.hpp"
#include "shoremesh/shore_segments.hpp"

namespace shoremesh {

namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox = bg::model::box<BPoint>;
using SegmentEntry = std::pair<BBox, std::uint32_t>;

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string number(double x) { return readable(x); }

void check_size(const std::optional<double>& v, const std::string& option) {
  if (v && !(std::isfinite(*v) && *v > 0))
    throw ParameterError(option + " must be a positive finite size (got " + number(*v) + ")");
}

double dist_to_segment(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}

// The even-odd rule over the polygon's rings (its outer ring and holes), exact (ring_contains).
bool polygon_contains(const SizePolygon& poly, const Point2& p) {
  bool in = false;
  for (const auto& r : poly.rings) in ^= ring_contains(r, p);
  return in;
}

// h(v) <= h(u) + grade * |uv| over the grid's 8-neighbours, by raster sweeps until nothing changes: the
// largest function below h that is grade-Lipschitz between neighbours (limgrad; Persson 2006).
void limit_gradient(std::vector<double>& h, std::size_t n, double cell, double grade) {
  const std::size_t w = n + 1;
  const double a = grade * cell, d = grade * cell * std::numbers::sqrt2;
  for (bool changed = true; changed;) {
    changed = false;
    auto relax = [&](std::size_t v, std::size_t u, double step) {
      const double c = h[u] + step;
      if (c < h[v]) h[v] = c, changed = true;
    };
    for (std::size_t j = 0; j < w; ++j)
      for (std::size_t i = 0; i < w; ++i) {
        const std::size_t v = j * w + i;
        if (i > 0) relax(v, v - 1, a);
        if (j > 0) {
          relax(v, v - w, a);
          if (i > 0) relax(v, v - w - 1, d);
          if (i + 1 < w) relax(v, v - w + 1, d);
        }
      }
    for (std::size_t j = w; j-- > 0;)
      for (std::size_t i = w; i-- > 0;) {
        const std::size_t v = j * w + i;
        if (i + 1 < w) relax(v, v + 1, a);
        if (j + 1 < w) {
          relax(v, v + w, a);
          if (i + 1 < w) relax(v, v + w + 1, d);
          if (i > 0) relax(v, v + w - 1, d);
        }
      }
  }
}

// limgrad's result is one function of the sources s: F(v) = the least, over the grid paths y = p0 .. pk = v,
// of s(y) + step_1 + ... + step_k added in path order in doubles. fl(x + step) is monotone in x, so any
// sequence of relaxations from s that ends where no edge relaxes ends there (every value it holds is such a
// sum, and a state where nothing relaxes is below every sum): the raster sweeps of a fresh field and the
// local repair below give the same doubles.
struct Stencil {
  std::size_t w;
  double a, d;  // the steps along an axis and along a diagonal
  template <class F>
  void each(std::size_t v, F&& f) const {
    const std::size_t i = v % w, j = v / w;
    if (i > 0) f(v - 1, a);
    if (i + 1 < w) f(v + 1, a);
    if (j > 0) {
      f(v - w, a);
      if (i > 0) f(v - w - 1, d);
      if (i + 1 < w) f(v - w + 1, d);
    }
    if (j + 1 < w) {
      f(v + w, a);
      if (i > 0) f(v + w - 1, d);
      if (i + 1 < w) f(v + w + 1, d);
    }
  }
};

// The fixed point F of the sources `source` (now), after they changed at `nodes` from `before`, repaired
// where the change reaches: A, the nodes whose source rose and every node a tight step (F(v) == F(u) + step,
// F(v) below its own source) leads to from them, takes its source again; then relaxations, smallest value
// first, from A, from the nodes whose source fell and from A's neighbours, until nothing relaxes. A node
// outside A keeps a path of its old value that avoids the risen sources (follow tight steps back to a node
// at its own source: F falls strictly along them, `strict` below), so the state starts above the new F and
// every value in it is a path's sum: it ends at the new F. Appends (node, old value) for every node whose
// value changed; returns the nodes popped.
std::size_t repair_gradient(std::vector<double>& F, const Stencil& st, const std::vector<std::size_t>& nodes,
                            const std::vector<double>& before, const std::function<double(std::size_t)>& source,
                            std::vector<std::pair<std::size_t, double>>& changed) {
  std::unordered_map<std::size_t, double> old_source;
  for (std::size_t k = 0; k < nodes.size(); ++k) old_source.emplace(nodes[k], before[k]);
  auto old_src = [&](std::size_t v) {
    const auto it = old_source.find(v);
    return it == old_source.end() ? source(v) : it->second;
  };
  std::vector<std::size_t> A;
  std::unordered_set<std::size_t> in_a;
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (source(nodes[k]) > before[k] && in_a.insert(nodes[k]).second) A.push_back(nodes[k]);
  for (std::size_t q = 0; q < A.size(); ++q) {
    const std::size_t u = A[q];
    st.each(u, [&](std::size_t v, double step) {
      if (!in_a.count(v) && std::isfinite(F[v]) && F[v] == F[u] + step && F[v] < old_src(v) && in_a.insert(v).second)
        A.push_back(v);
    });
  }
  std::unordered_map<std::size_t, double> saved;
  auto set = [&](std::size_t v, double x) {
    saved.try_emplace(v, F[v]);
    F[v] = x;
  };
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> heap;
  for (std::size_t v : A) set(v, source(v));
  for (std::size_t v : nodes)
    if (!in_a.count(v) && source(v) < F[v]) set(v, source(v));
  for (std::size_t v : A) {
    heap.push({F[v], v});
    st.each(v, [&](std::size_t u, double) {
      if (!in_a.count(u)) heap.push({F[u], u});
    });
  }
  for (std::size_t v : nodes)
    if (!in_a.count(v)) heap.push({F[v], v});
  std::size_t popped = 0;
  while (!heap.empty()) {
    const auto [x, u] = heap.top();
    heap.pop();
    if (x != F[u]) continue;
    ++popped;
    st.each(u, [&](std::size_t v, double step) {
      const double c = F[u] + step;
      if (c < F[v]) {
        set(v, c);
        heap.push({c, v});
      }
    });
  }
  for (const auto& [v, x] : saved)
    if (!(F[v] == x)) changed.push_back({v, x});
  return popped + A.size();
}

// Steps fall strictly along tight steps when every finite value x <= bound has x + step > x (with margin:
// half a step already moves the bound).
bool strict(double bound, double step) { return bound + 0.5 * step > bound; }

// The segments in one of a and b only (as unordered pairs), by ring.
std::vector<std::pair<Point2, Point2>> changed_segments(const Domain2& a, const Domain2& b) {
  std::vector<std::pair<Point2, Point2>> out;
  auto key = [](const Point2& p, const Point2& q) { return p < q ? std::pair{p, q} : std::pair{q, p}; };
  static const Ring none;
  for (std::size_t r = 0; r < std::max(a.rings.size(), b.rings.size()); ++r) {
    const Ring& ra = r < a.rings.size() ? a.rings[r] : none;
    const Ring& rb = r < b.rings.size() ? b.rings[r] : none;
    if (ra.points == rb.points && ra.role == rb.role) continue;
    std::vector<std::pair<Point2, Point2>> x, y;
    if (ra.role != rb.role) {  // a ring that becomes a line or back: what it bounds changes whole
      for (std::size_t k = 0; k < ra.segment_count(); ++k) out.push_back(key(ra.points[k], ra.points[(k + 1) % ra.points.size()]));
      for (std::size_t k = 0; k < rb.segment_count(); ++k) out.push_back(key(rb.points[k], rb.points[(k + 1) % rb.points.size()]));
      continue;
    }
    for (std::size_t k = 0; k < ra.segment_count(); ++k) x.push_back(key(ra.points[k], ra.points[(k + 1) % ra.points.size()]));
    for (std::size_t k = 0; k < rb.segment_count(); ++k) y.push_back(key(rb.points[k], rb.points[(k + 1) % rb.points.size()]));
    std::sort(x.begin(), x.end());
    std::sort(y.begin(), y.end());
    std::set_symmetric_difference(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(out));
  }
  return out;
}

// A leaf's canonical jitter in [-1, 1]^2 from its level and place (splitmix64): a grid of seeds would put
// four points on every circle, where the Delaunay mesh is not unique.
std::array<double, 2> jitter(int level, std::uint64_t ix, std::uint64_t iy) {
  std::uint64_t z = (static_cast<std::uint64_t>(level) << 58) ^ (ix << 29) ^ iy;
  auto next = [&z] {
    z += 0x9E3779B97F4A7C15ull;
    std::uint64_t x = z;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    x ^= x >> 31;
    return static_cast<double>(x >> 11) * 0x1.0p-53 * 2 - 1;
  };
  const double u = next();
  return {u, next()};
}

}  // namespace

// The rings' edges by their boxes, each in its ring's order (a, b as the ring has them: the shore term's
// distance is computed from them as a fresh field computes it, bit for bit) with whether a closed ring
// holds it. A multiset: rings may share an edge.
struct SizeField::EdgeTree {
  using Entry = std::pair<BBox, ShoreSegment>;
  static Entry entry(const ShoreSegment& e) {
    return {BBox(BPoint(std::min(e.a[0], e.b[0]), std::min(e.a[1], e.b[1])), BPoint(std::max(e.a[0], e.b[0]), std::max(e.a[1], e.b[1]))), e};
  }
  bgi::rtree<Entry, bgi::quadratic<16>> tree;
};

namespace {

// The edges of `ring` that touch its vertices lo .. hi - 1 (lo == hi: the edge across that gap), or all of
// them (`whole`), in ring order: what a stretch between a prefix and a suffix takes away or brings.
void stretch_edges(const Ring& ring, bool whole, std::size_t lo, std::size_t hi, std::vector<ShoreSegment>& out) {
  const std::size_t n = ring.points.size(), m = ring.segment_count();
  if (m == 0) return;
  auto edge = [&](std::size_t k) { out.push_back({ring.points[k], ring.points[(k + 1) % n], ring.closed()}); };
  if (whole) {
    for (std::size_t k = 0; k < m; ++k) edge(k);
  } else if (ring.closed()) {
    const std::size_t count = std::min(hi - lo + 1, n);  // edges lo - 1 .. hi - 1, cyclically
    for (std::size_t t = 0; t < count; ++t) edge((lo + n - 1 + t) % n);
  } else {
    for (std::size_t k = lo == 0 ? 0 : lo - 1; k < std::min(hi, m); ++k) edge(k);
  }
}

}  // namespace

template <class F>
void SizeField::edges_meeting(const Point2& lo, const Point2& hi, bool indexed, F&& f) const {
  if (indexed) {
    const BBox q(BPoint(lo[0], lo[1]), BPoint(hi[0], hi[1]));
    for (auto it = edge_tree_->tree.qbegin(bgi::intersects(q)); it != edge_tree_->tree.qend(); ++it)
      f(it->second.a, it->second.b, it->second.water);
    return;
  }
  for (const Ring& ring : rings_.rings)
    for (std::size_t k = 0; k < ring.segment_count(); ++k)
      f(ring.points[k], ring.points[(k + 1) % ring.points.size()], ring.closed());
}

SizeField::SizeField(SizeTerms terms, const BoxTransform<2>& box, const Domain2& rings)
    : terms_(std::move(terms)), box_(box), rings_(rings) {
  check_size(terms_.max_size, "--max-size");
  check_size(terms_.min_size, "--min-size");
  if (terms_.min_size && terms_.max_size && *terms_.min_size > *terms_.max_size)
    throw ParameterError("--min-size " + number(*terms_.min_size) + " is larger than --max-size " +
                         number(*terms_.max_size));
  if (terms_.grade && !(std::isfinite(*terms_.grade) && *terms_.grade > 0))
    throw ParameterError("--grade must be above 0 (got " + number(*terms_.grade) + ")");
  if (terms_.shore_size) {
    check_size(terms_.shore_size, "--size-from-shore H0");
    if (!terms_.shore_rate || !(std::isfinite(*terms_.shore_rate) && *terms_.shore_rate >= 0))
      throw ParameterError("--size-from-shore RATE must be a finite number >= 0 (got " +
                           number(terms_.shore_rate.value_or(std::nan(""))) + ")");
  }
  for (const SizePolygon& p : terms_.polygons)
    if (!(std::isfinite(p.size) && p.size > 0))
      throw ParameterError(p.name + ": size must be a positive finite number (got " + number(p.size) + ")");
  if (terms_.empty())
    throw ParameterError("--grade and --min-size need a size term: --max-size, --size-from-shore, --size-polygons, "
                         "--size-raster, --size-from-depth or --size-from-slope");

  // The grid: cells a little finer than the smallest of --max-size, --min-size, H0 and a quarter of each
  // polygon's narrower side, 2^5 .. 2^11 per side (2^10 without them). Not from the polygons' sizes: a
  // `size` edit must not move the grid (h would change everywhere), and a fresh run must choose the same.
  double hint = kInf;
  for (const auto& v : {terms_.max_size, terms_.min_size, terms_.shore_size})
    if (v) hint = std::min(hint, *v);
  for (const SizePolygon& p : terms_.polygons) {
    double lo[2] = {kInf, kInf}, hi[2] = {-kInf, -kInf};
    for (const Point2& q : p.rings.front())
      for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], q[a]), hi[a] = std::max(hi[a], q[a]);
    hint = std::min(hint, 0.25 * std::min(hi[0] - lo[0], hi[1] - lo[1]));
  }
  k_ = std::isfinite(hint) ? std::clamp(static_cast<int>(std::ceil(std::log2(box_.side / hint))) + 1, 5, 11) : 10;
  n_ = std::size_t{1} << k_;
  cell_ = box_.side / static_cast<double>(n_);
  const std::size_t w = n_ + 1;

  // Sampled terms, once (they do not read the rings; copies of the field share them).
  auto sampled = std::make_shared<std::vector<double>>(w * w, kInf);
  std::vector<double>& sampled_at = *sampled;
  for (const SampledSizeTerm& t : terms_.sampled)
    for (std::size_t j = 0; j < w; ++j)
      for (std::size_t i = 0; i < w; ++i) {
        const Point2 p{box_.origin[0] + static_cast<double>(i) * cell_, box_.origin[1] + static_cast<double>(j) * cell_};
        const double v = t.size(p);
        if (std::isnan(v)) continue;
        if (!(v > 0))
          throw InputError(t.name + ": size " + number(v) + " at (" + number(p[0]) + ", " + number(p[1]) +
                           ") is not above 0");
        sampled_at[node(i, j)] = std::min(sampled_at[node(i, j)], v);
      }
  for (double x : sampled_at)
    if (std::isfinite(x)) sampled_top_ = std::max(sampled_top_, x);
  sampled_ = std::move(sampled);
  compute();

  // The point cap, term by term: about area / (sqrt(3)/4 h^2) triangles, half as many points.
  const double cell_area = cell_ * cell_;
  auto estimate = [&](auto&& size_at) {
    double points = 0;
    for (std::size_t v = 0; v < w * w; ++v) {
      if (!water_[v]) continue;
      double s = size_at(v);
      if (terms_.min_size) s = std::max(s, *terms_.min_size);
      if (std::isfinite(s)) points += cell_area / (std::sqrt(3.0) / 2 * s * s);
    }
    return points;
  };
  auto check_cap = [&](double points, const std::string& term) {
    if (points > static_cast<double>(terms_.point_cap))
      throw InputError(term + " asks for about " + number(std::round(points)) + " points in the water, more than the " +
                       std::to_string(terms_.point_cap) + "-point cap; give a larger size");
  };
  if (terms_.max_size) check_cap(estimate([&](std::size_t) { return *terms_.max_size; }), "--max-size " + number(*terms_.max_size));
  if (terms_.shore_size) {
    check_cap(estimate([&](std::size_t v) { return shore_[v]; }),
              "--size-from-shore " + number(*terms_.shore_size) + " " + number(*terms_.shore_rate));
  }
  for (std::size_t q = 0; q < terms_.polygons.size(); ++q) {
    const SizePolygon& poly = terms_.polygons[q];
    double points = 0;
    for (std::size_t v : polygon_nodes_[q])
      if (water_[v]) points += cell_area / (std::sqrt(3.0) / 2 * std::pow(std::max(poly.size, terms_.min_size.value_or(0)), 2));
    check_cap(points, poly.name + " (size " + number(poly.size) + ")");
  }
  if (!terms_.sampled.empty()) {
    std::string names;
    for (const auto& t : terms_.sampled) names += (names.empty() ? "" : ", ") + t.name;
    check_cap(estimate([&](std::size_t v) { return (*sampled_)[v]; }), names);
  }
  check_cap(estimate([&](std::size_t v) { return h_[v]; }),
            terms_.grade ? "the graded size (--grade " + number(*terms_.grade) + ")" : "the size function");
  clamp_shore();
}

// h reads the shore term only below --max-size: kept there at most, the term's change stays where it
// binds. min(F(s), M) is the sweeps' fixed point of min(s, M) with M at every node (a path from a node at M
// sums to M or more), so a repair of the clamped term equals a fresh field's clamped term.
void SizeField::clamp_shore() {
  if (terms_.max_size)
    for (double& x : shore_) x = std::min(x, *terms_.max_size);
}

void SizeField::compute() {
  const std::size_t w = n_ + 1;
  auto position = [&](std::size_t v) {
    return Point2{box_.origin[0] + static_cast<double>(v % w) * cell_, box_.origin[1] + static_cast<double>(v / w) * cell_};
  };
  water_.assign(w * w, 0);
  water_mask(0, 0, n_, n_);

  // Polygons: the nodes inside each (kept, so that a size edit reads no geometry again).
  if (polygon_nodes_.size() != terms_.polygons.size()) {
    polygon_nodes_.assign(terms_.polygons.size(), {});
    for (std::size_t q = 0; q < terms_.polygons.size(); ++q) {
      double lo[2] = {kInf, kInf}, hi[2] = {-kInf, -kInf};
      for (const auto& r : terms_.polygons[q].rings)
        for (const Point2& p : r)
          for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
      auto index = [&](double x, int a, bool up) {
        const double t = (x - box_.origin[a]) / cell_;
        return static_cast<std::size_t>(std::clamp(up ? std::ceil(t) : std::floor(t), 0.0, static_cast<double>(n_)));
      };
      for (std::size_t j = index(lo[1], 1, false); j <= index(hi[1], 1, true); ++j)
        for (std::size_t i = index(lo[0], 0, false); i <= index(hi[0], 0, true); ++i)
          if (polygon_contains(terms_.polygons[q], position(node(i, j)))) polygon_nodes_[q].push_back(node(i, j));
    }
  }

  // The shore term: H0 + RATE * distance, exact beside each segment, carried on by the same sweeps.
  shore_.clear();
  shore_src_.clear();
  if (terms_.shore_size) {
    shore_.assign(w * w, kInf);
    for (const Ring& ring : rings_.rings)
      for (std::size_t k = 0; k < ring.segment_count(); ++k) {
        const Point2& a = ring.points[k];
        const Point2& b = ring.points[(k + 1) % ring.points.size()];
        auto range = [&](int axis) {
          const double lo = (std::min(a[axis], b[axis]) - box_.origin[axis]) / cell_ - 1;
          const double hi = (std::max(a[axis], b[axis]) - box_.origin[axis]) / cell_ + 1;
          return std::pair{static_cast<std::size_t>(std::clamp(std::floor(lo), 0.0, double(n_))),
                           static_cast<std::size_t>(std::clamp(std::ceil(hi), 0.0, double(n_)))};
        };
        const auto [i0, i1] = range(0);
        const auto [j0, j1] = range(1);
        for (std::size_t j = j0; j <= j1; ++j)
          for (std::size_t i = i0; i <= i1; ++i) {
            const std::size_t v = node(i, j);
            shore_[v] = std::min(shore_[v], *terms_.shore_size + *terms_.shore_rate * dist_to_segment(position(v), a, b));
          }
      }
    shore_src_ = shore_;
    if (*terms_.shore_rate > 0) limit_gradient(shore_, n_, cell_, *terms_.shore_rate);
    else std::fill(shore_.begin(), shore_.end(), rings_.empty() ? kInf : *terms_.shore_size);
  }

  h_ = *sampled_;
  if (terms_.max_size)
    for (double& x : h_) x = std::min(x, *terms_.max_size);
  if (!shore_.empty())
    for (std::size_t v = 0; v < h_.size(); ++v) h_[v] = std::min(h_[v], shore_[v]);
  for (std::size_t q = 0; q < terms_.polygons.size(); ++q)
    for (std::size_t v : polygon_nodes_[q]) h_[v] = std::min(h_[v], terms_.polygons[q].size);
  if (terms_.min_size)
    for (double& x : h_) x = std::max(x, *terms_.min_size);
  if (terms_.grade) limit_gradient(h_, n_, cell_, *terms_.grade);
  build_pyramid();
}

// Water at the nodes [c0, c1] x [r0, r1], for the estimates and the summary only (without closed rings:
// everywhere): exactly WaterTest::in_water at every node, by its rule (even-odd over the edges that cross
// the node's row half-open, a node on an edge is on the ring, not in the water) with its exact orientation
// tests, but along each row of nodes at once: an edge crossing the row has its crossing strictly right of
// the nodes 0 .. f - 1, f found from a double estimate and settled by orient2d (the test is monotone along
// the row).
void SizeField::water_mask(std::size_t c0, std::size_t r0, std::size_t c1, std::size_t r1, bool indexed) {
  const std::size_t w = n_ + 1;
  const bool any = std::any_of(rings_.rings.begin(), rings_.rings.end(),
                               [](const Ring& r) { return r.closed() && !r.points.empty(); });
  if (undo_) {
    undo_->water_box[0] = c0, undo_->water_box[1] = r0, undo_->water_box[2] = c1, undo_->water_box[3] = r1;
    for (std::size_t j = r0; j <= r1; ++j)
      for (std::size_t i = c0; i <= c1; ++i) undo_->water.push_back(water_[node(i, j)]);
  }
  if (!any) {
    for (std::size_t j = r0; j <= r1; ++j)
      for (std::size_t i = c0; i <= c1; ++i) water_[node(i, j)] = 1;
    return;
  }
  auto x_of = [&](std::size_t i) { return box_.origin[0] + static_cast<double>(i) * cell_; };
  auto y_of = [&](std::size_t j) { return box_.origin[1] + static_cast<double>(j) * cell_; };
  // Per window row: toggle[f - c0] flips the parity of the nodes left of f (c0 < f <= c1), base the
  // crossings right of the window; on_ring marks nodes on an edge.
  const std::size_t cols = c1 - c0 + 1, rows = r1 - r0 + 1;
  std::vector<std::uint8_t> toggle(rows * cols, 0), base(rows, 0), on_ring(rows * cols, 0);
  auto row_range = [&](double y0, double y1) {
    const double lo = std::floor((y0 - box_.origin[1]) / cell_) - 1, hi = std::ceil((y1 - box_.origin[1]) / cell_) + 1;
    return std::pair{std::max(r0, static_cast<std::size_t>(std::clamp(lo, 0.0, double(n_)))),
                     std::min(r1, static_cast<std::size_t>(std::clamp(hi, 0.0, double(n_))))};
  };
  // An edge acts on the window only where it meets its rows (row_range's margin is a cell) right of its
  // first column (an edge left of it is left of every node): the tree gives those of the strip.
  const double margin = 3 * cell_;
  edges_meeting({x_of(c0) - margin, y_of(r0) - margin}, {std::numeric_limits<double>::max(), y_of(r1) + margin}, indexed,
                [&](const Point2& a, const Point2& b, bool closed) {
    if (!closed) return;
    {
      const auto [j0, j1] = row_range(std::min(a[1], b[1]), std::max(a[1], b[1]));
      for (std::size_t j = j0; j <= j1 && j0 <= j1; ++j) {
        const std::size_t row = j - r0;
        const double y = y_of(j);
        if ((a[1] > y) == (b[1] > y)) {
          if (a[1] == y && b[1] == y) {  // a horizontal edge on the row: the nodes on it
            const double x0 = std::min(a[0], b[0]), x1 = std::max(a[0], b[0]);
            const auto lo = static_cast<std::size_t>(std::clamp(std::floor((x0 - box_.origin[0]) / cell_) - 1, 0.0, double(n_)));
            const auto hi = static_cast<std::size_t>(std::clamp(std::ceil((x1 - box_.origin[0]) / cell_) + 1, 0.0, double(n_)));
            for (std::size_t i = std::max(lo, c0); i <= std::min(hi, c1); ++i)
              if (x0 <= x_of(i) && x_of(i) <= x1) on_ring[row * cols + (i - c0)] = 1;
          }
          continue;
        }
        const Point2& down = a[1] < b[1] ? a : b;
        const Point2& up = a[1] < b[1] ? b : a;
        // Node i is strictly left of the upward edge: the crossing is strictly right of it.
        auto left = [&](std::size_t i) { return detail::orient(down, up, Point2{x_of(i), y}) > 0; };
        const double estimate = (a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]) - box_.origin[0]) / cell_;
        auto f = std::isnan(estimate) ? 0 : static_cast<std::size_t>(std::clamp(std::ceil(estimate), 0.0, double(w)));
        while (f > 0 && !left(f - 1)) --f;
        while (f < w && left(f)) ++f;
        if (f < w && f >= c0 && f <= c1 && detail::orient(down, up, Point2{x_of(f), y}) == 0) on_ring[row * cols + (f - c0)] = 1;
        if (f > c1) base[row] ^= 1;
        else if (f > c0) toggle[row * cols + (f - c0)] ^= 1;
      }
    }
  });
  for (std::size_t row = 0; row < rows; ++row) {
    std::uint8_t parity = base[row];
    for (std::size_t i = c1 + 1; i-- > c0;) {
      if (i + 1 <= c1) parity ^= toggle[row * cols + (i + 1 - c0)];  // the crossings right of node i
      water_[node(i, r0 + row)] = parity && !on_ring[row * cols + (i - c0)];
    }
  }
}

void SizeField::build_pyramid() {
  pyramid_.clear();
  std::vector<double> level(n_ * n_);
  for (std::size_t j = 0; j < n_; ++j)
    for (std::size_t i = 0; i < n_; ++i)
      level[j * n_ + i] = std::min({h_[node(i, j)], h_[node(i + 1, j)], h_[node(i, j + 1)], h_[node(i + 1, j + 1)]});
  pyramid_.push_back(std::move(level));
  for (std::size_t m = n_ / 2; m >= 1; m /= 2) {
    const auto& below = pyramid_.back();
    std::vector<double> up(m * m);
    for (std::size_t j = 0; j < m; ++j)
      for (std::size_t i = 0; i < m; ++i)
        up[j * m + i] = std::min({below[2 * j * 2 * m + 2 * i], below[2 * j * 2 * m + 2 * i + 1],
                                  below[(2 * j + 1) * 2 * m + 2 * i], below[(2 * j + 1) * 2 * m + 2 * i + 1]});
    pyramid_.push_back(std::move(up));
  }
}

double SizeField::at(const Point2& p) const {
  const double u = std::clamp((p[0] - box_.origin[0]) / cell_, 0.0, static_cast<double>(n_));
  const double v = std::clamp((p[1] - box_.origin[1]) / cell_, 0.0, static_cast<double>(n_));
  const std::size_t i = std::min(static_cast<std::size_t>(u), n_ - 1), j = std::min(static_cast<std::size_t>(v), n_ - 1);
  const double fu = u - static_cast<double>(i), fv = v - static_cast<double>(j);
  const double h00 = h_[node(i, j)], h10 = h_[node(i + 1, j)], h01 = h_[node(i, j + 1)], h11 = h_[node(i + 1, j + 1)];
  if (!std::isfinite(h00) || !std::isfinite(h10) || !std::isfinite(h01) || !std::isfinite(h11))
    return std::max({h00, h10, h01, h11}) == kInf && std::min({h00, h10, h01, h11}) == kInf ? kInf
                                                                                          : std::min({h00, h10, h01, h11});
  return (1 - fv) * ((1 - fu) * h00 + fu * h10) + fv * ((1 - fu) * h01 + fu * h11);
}

double SizeField::min_over(const Point2& lo, double side) const {
  return min_over_box(lo, {lo[0] + side, lo[1] + side});
}

double SizeField::min_over_segment(const Point2& a, const Point2& b) const {
  return min_over_box({std::min(a[0], b[0]), std::min(a[1], b[1])}, {std::max(a[0], b[0]), std::max(a[1], b[1])});
}

SizeField::CellSpan SizeField::cell_span(const Point2& lo, const Point2& hi) const {
  auto cell_range = [&](int axis) {
    const double a = std::floor((lo[axis] - box_.origin[axis]) / cell_);
    const double b = std::floor((hi[axis] - box_.origin[axis]) / cell_);
    return std::pair{static_cast<std::size_t>(std::clamp(a, 0.0, double(n_ - 1))),
                     static_cast<std::size_t>(std::clamp(b, 0.0, double(n_ - 1)))};
  };
  const auto [i0, i1] = cell_range(0);
  const auto [j0, j1] = cell_range(1);
  const std::size_t span = std::max(i1 - i0, j1 - j0) + 1;
  std::size_t l = 0;
  while (l + 1 < pyramid_.size() && (std::size_t{2} << l) * 2 <= span) ++l;
  return {l, i0, i1, j0, j1};
}

// The bilinear h over a cell lies between its nodes' values: the least over the cells the box meets, read
// from the coarsest pyramid level whose blocks stay at most about half the box.
double SizeField::min_over_box(const Point2& lo, const Point2& hi,
                               const std::function<double(std::size_t, std::size_t)>& before) const {
  const auto [l, i0, i1, j0, j1] = cell_span(lo, hi);
  const std::size_t m = n_ >> l;
  double out = kInf;
  for (std::size_t j = j0 >> l; j <= j1 >> l; ++j)
    for (std::size_t i = i0 >> l; i <= i1 >> l; ++i) out = std::min(out, before ? before(l, j * m + i) : pyramid_[l][j * m + i]);
  return out;
}

double SizeField::min_over_before(const SizeUndo& undo, const Point2& lo, double side) const {
  const std::function<double(std::size_t, std::size_t)> before = [&](std::size_t l, std::size_t b) {
    if (undo.whole_pyramid) return (*undo.whole_pyramid)[l][b];
    const auto it = undo.pyramid.find(static_cast<std::uint64_t>(l) << 56 | b);
    return it == undo.pyramid.end() ? pyramid_[l][b] : it->second;
  };
  return min_over_box(lo, {lo[0] + side, lo[1] + side}, before);
}

void SizeField::take_back(SizeUndo&& u) {
  if (u.whole_h) h_ = std::move(*u.whole_h);
  if (u.whole_shore) shore_ = std::move(*u.whole_shore);
  if (u.whole_src) shore_src_ = std::move(*u.whole_src);
  if (u.whole_water) water_ = std::move(*u.whole_water);
  if (u.whole_pyramid) pyramid_ = std::move(*u.whole_pyramid);
  for (const auto& [v, x] : u.h) h_[v] = x;
  for (const auto& [v, x] : u.shore) shore_[v] = x;
  for (const auto& [v, x] : u.shore_src) shore_src_[v] = x;
  for (std::size_t j = u.water_box[1], k = 0; !u.water.empty() && j <= u.water_box[3]; ++j)
    for (std::size_t i = u.water_box[0]; i <= u.water_box[2]; ++i) water_[node(i, j)] = u.water[k++];
  for (const auto& [key, x] : u.pyramid) pyramid_[key >> 56][key & ((std::uint64_t{1} << 56) - 1)] = x;
  if (u.polygon) terms_.polygons[u.polygon->first].size = u.polygon->second;
  if (u.rings) rings_ = std::move(*u.rings), edge_tree_.reset();
  for (auto it = u.stretches.rbegin(); it != u.stretches.rend(); ++it) apply_stretch(rings_, *it);
  if (edge_tree_ && (!u.edges_gone.empty() || !u.edges_came.empty())) {
    if (edge_tree_.use_count() > 1) edge_tree_ = std::make_shared<EdgeTree>(*edge_tree_);
    for (const ShoreSegment& e : u.edges_came) edge_tree_->tree.remove(EdgeTree::entry(e));
    for (const ShoreSegment& e : u.edges_gone) edge_tree_->tree.insert(EdgeTree::entry(e));
  }
}

void SizeField::update_pyramid(std::size_t i0, std::size_t j0, std::size_t i1, std::size_t j1) {
  // The cells with a changed node: [i0 - 1, i1] x [j0 - 1, j1] within the grid, then their blocks upward.
  std::size_t c0 = i0 > 0 ? i0 - 1 : 0, d0 = j0 > 0 ? j0 - 1 : 0;
  std::size_t c1 = std::min(i1, n_ - 1), d1 = std::min(j1, n_ - 1);
  auto write = [&](std::size_t l, std::size_t b, double x) {
    double& y = pyramid_[l][b];
    if (undo_ && !(x == y)) undo_->pyramid.emplace(static_cast<std::uint64_t>(l) << 56 | b, y);
    y = x;
  };
  for (std::size_t j = d0; j <= d1; ++j)
    for (std::size_t i = c0; i <= c1; ++i)
      write(0, j * n_ + i, std::min({h_[node(i, j)], h_[node(i + 1, j)], h_[node(i, j + 1)], h_[node(i + 1, j + 1)]}));
  for (std::size_t l = 1, m = n_ / 2; l < pyramid_.size(); ++l, m /= 2) {
    c0 /= 2, d0 /= 2, c1 /= 2, d1 /= 2;
    const auto& below = pyramid_[l - 1];
    for (std::size_t j = d0; j <= d1; ++j)
      for (std::size_t i = c0; i <= c1; ++i)
        write(l, j * m + i, std::min({below[2 * j * 2 * m + 2 * i], below[2 * j * 2 * m + 2 * i + 1],
                                      below[(2 * j + 1) * 2 * m + 2 * i], below[(2 * j + 1) * 2 * m + 2 * i + 1]}));
  }
}

double SizeField::raw(std::size_t v, double shore) const {
  double x = (*sampled_)[v];
  if (terms_.max_size) x = std::min(x, *terms_.max_size);
  x = std::min(x, shore);
  for (std::size_t q = 0; q < terms_.polygons.size(); ++q)
    if (std::binary_search(polygon_nodes_[q].begin(), polygon_nodes_[q].end(), v)) x = std::min(x, terms_.polygons[q].size);
  if (terms_.min_size) x = std::max(x, *terms_.min_size);
  return x;
}

double SizeField::shore_bound() const {
  // A source lies within a cell's diagonal of its segment's box; a grid path between two nodes is at
  // most two sides long.
  if (!terms_.shore_size) return 0;
  if (terms_.max_size) return *terms_.max_size;
  return *terms_.shore_size + *terms_.shore_rate * 8 * box_.side;
}

double SizeField::finite_bound() const {
  if (terms_.max_size) return *terms_.max_size;
  double b = std::max(sampled_top_, shore_bound());
  for (const SizePolygon& p : terms_.polygons) b = std::max(b, p.size);
  return std::max(b, terms_.min_size.value_or(0));
}

SizeChange SizeField::recompute_whole() {
  const std::vector<double> before = h_;
  SizeUndo* const undo = undo_;
  if (undo) {
    undo->whole_h = h_, undo->whole_shore = shore_, undo->whole_src = shore_src_;
    undo->whole_water = water_, undo->whole_pyramid = pyramid_;
  }
  undo_ = nullptr;  // the arrays are kept whole
  compute();
  undo_ = undo;
  clamp_shore();
  SizeChange c;
  c.whole = true;
  c.visited = h_.size();
  const std::size_t w = n_ + 1;
  for (std::size_t v = 0; v < h_.size(); ++v) {
    if (before[v] == h_[v]) continue;
    const std::size_t i = v % w, j = v / w;
    if (!c.changed) c.i0 = c.i1 = i, c.j0 = c.j1 = j;
    c.changed = true;
    c.i0 = std::min(c.i0, i), c.i1 = std::max(c.i1, i), c.j0 = std::min(c.j0, j), c.j1 = std::max(c.j1, j);
  }
  return c;
}

SizeChange SizeField::update_h(const std::vector<std::size_t>& nodes, const std::vector<double>& before) {
  SizeChange c;
  const std::size_t w = n_ + 1;
  auto now = [&](std::size_t v) { return raw(v, shore_.empty() ? kInf : shore_[v]); };
  std::vector<std::pair<std::size_t, double>> changed;
  if (terms_.grade) {
    if (!strict(finite_bound(), *terms_.grade * cell_)) return recompute_whole();
    c.visited = repair_gradient(h_, Stencil{w, *terms_.grade * cell_, *terms_.grade * cell_ * std::numbers::sqrt2}, nodes,
                                before, now, changed);
  } else {
    for (std::size_t v : nodes) {
      const double x = now(v);
      if (!(x == h_[v])) changed.push_back({v, h_[v]}), h_[v] = x;
    }
    c.visited = nodes.size();
  }
  if (undo_) undo_->h.insert(undo_->h.end(), changed.begin(), changed.end());
  for (const auto& [v, x] : changed) {
    const std::size_t i = v % w, j = v / w;
    if (!c.changed) c.i0 = c.i1 = i, c.j0 = c.j1 = j;
    c.changed = true;
    c.i0 = std::min(c.i0, i), c.i1 = std::max(c.i1, i), c.j0 = std::min(c.j0, j), c.j1 = std::max(c.j1, j);
  }
  if (c.changed) update_pyramid(c.i0, c.j0, c.i1, c.j1);
  return c;
}

// Only where the changed segments reach (docs/sizing.md): the water inside their bounding box (the two
// even-odd regions differ by the changed segments' own, empty outside their box), the shore term's values
// beside them and what its sweeps carry from there, and h where the shore term changed.
SizeChange SizeField::set_rings(const Domain2& rings, SizeUndo* undo) {
  undo_ = undo;
  struct Done {
    SizeUndo*& u;
    ~Done() { u = nullptr; }
  } done{undo_};
  const std::vector<std::pair<Point2, Point2>> segs = changed_segments(rings_, rings);
  const bool emptiness = rings_.empty() != rings.empty();
  if (undo) undo->rings = std::move(rings_);
  rings_ = rings;
  edge_tree_.reset();  // built again from the rings by the next update of stretches
  return rings_changed(segs, emptiness, false);
}

SizeChange SizeField::set_rings(std::span<const RingStretch> edits, SizeUndo* undo) {
  undo_ = undo;
  struct Done {
    SizeUndo*& u;
    ~Done() { u = nullptr; }
  } done{undo_};
  if (!edge_tree_) {
    std::vector<EdgeTree::Entry> entries;
    edges_meeting({}, {}, false, [&](const Point2& a, const Point2& b, bool closed) { entries.push_back(EdgeTree::entry({a, b, closed})); });
    edge_tree_ = std::make_shared<EdgeTree>();
    edge_tree_->tree = decltype(edge_tree_->tree)(entries.begin(), entries.end());
  } else if (edge_tree_.use_count() > 1) {
    edge_tree_ = std::make_shared<EdgeTree>(*edge_tree_);
  }
  const bool was_empty = rings_.empty();
  std::vector<ShoreSegment> gone, came;
  for (const RingStretch& s : edits) {
    const auto size_of = [&] { return s.ring < rings_.rings.size() ? rings_.rings[s.ring].points.size() : 0; };
    if (s.ring < rings_.rings.size()) stretch_edges(rings_.rings[s.ring], s.whole, s.prefix, size_of() - s.suffix, gone);
    RingStretch inverse = apply_stretch(rings_, s);
    stretch_edges(rings_.rings[s.ring], s.whole, s.prefix, size_of() - s.suffix, came);
    if (undo) undo->stretches.push_back(std::move(inverse));
  }
  // The edges in one side only, counted (an edge taken and given back in the same orientation stays).
  std::sort(gone.begin(), gone.end());
  std::sort(came.begin(), came.end());
  std::vector<ShoreSegment> went, come;
  std::set_difference(gone.begin(), gone.end(), came.begin(), came.end(), std::back_inserter(went));
  std::set_difference(came.begin(), came.end(), gone.begin(), gone.end(), std::back_inserter(come));
  std::vector<std::pair<Point2, Point2>> segs;
  for (const ShoreSegment& e : went) edge_tree_->tree.remove(EdgeTree::entry(e)), segs.push_back({e.a, e.b});
  for (const ShoreSegment& e : come) edge_tree_->tree.insert(EdgeTree::entry(e)), segs.push_back({e.a, e.b});
  if (undo) undo->edges_gone = std::move(went), undo->edges_came = std::move(come);
  return rings_changed(segs, was_empty != rings_.empty(), true);
}

SizeChange SizeField::rings_changed(const std::vector<std::pair<Point2, Point2>>& segs, bool emptiness, bool indexed) {
  SizeUndo* const undo = undo_;
  if (segs.empty()) return {};
  const std::size_t w = n_ + 1;
  auto index = [&](double x, int axis, double grow) {
    return static_cast<std::size_t>(std::clamp(std::floor((x - box_.origin[axis]) / cell_ + grow), 0.0, double(n_)));
  };
  double lo[2] = {kInf, kInf}, hi[2] = {-kInf, -kInf};
  for (const auto& [a, b] : segs)
    for (int x = 0; x < 2; ++x) lo[x] = std::min({lo[x], a[x], b[x]}), hi[x] = std::max({hi[x], a[x], b[x]});
  water_mask(index(lo[0], 0, 0), index(lo[1], 1, 0), std::min(n_, index(hi[0], 0, 0) + 1), std::min(n_, index(hi[1], 1, 0) + 1),
             indexed);
  if (!terms_.shore_size) return {};
  const double h0 = *terms_.shore_size, rate = *terms_.shore_rate;
  if (emptiness) return recompute_whole();
  if (rate == 0) return {};  // H0 wherever there are rings
  if (!strict(shore_bound(), rate * cell_)) return recompute_whole();
  // The sources beside the changed segments, from the segments whose range (compute()'s) meets theirs.
  auto range = [&](const Point2& a, const Point2& b, int axis) {
    const double l = (std::min(a[axis], b[axis]) - box_.origin[axis]) / cell_ - 1;
    const double h = (std::max(a[axis], b[axis]) - box_.origin[axis]) / cell_ + 1;
    return std::pair{static_cast<std::size_t>(std::clamp(std::floor(l), 0.0, double(n_))),
                     static_cast<std::size_t>(std::clamp(std::ceil(h), 0.0, double(n_)))};
  };
  std::size_t R[4] = {n_, n_, 0, 0};  // i0, j0, i1, j1
  for (const auto& [a, b] : segs) {
    const auto [i0, i1] = range(a, b, 0);
    const auto [j0, j1] = range(a, b, 1);
    R[0] = std::min(R[0], i0), R[1] = std::min(R[1], j0), R[2] = std::max(R[2], i1), R[3] = std::max(R[3], j1);
  }
  const std::size_t rw = R[2] - R[0] + 1;
  std::vector<double> src((R[3] - R[1] + 1) * rw, kInf);
  const double margin = 3 * cell_;
  const Point2 r_lo{box_.origin[0] + static_cast<double>(R[0]) * cell_ - margin, box_.origin[1] + static_cast<double>(R[1]) * cell_ - margin};
  const Point2 r_hi{box_.origin[0] + static_cast<double>(R[2]) * cell_ + margin, box_.origin[1] + static_cast<double>(R[3]) * cell_ + margin};
  edges_meeting(r_lo, r_hi, indexed, [&](const Point2& a, const Point2& b, bool) {
    {
      auto [i0, i1] = range(a, b, 0);
      auto [j0, j1] = range(a, b, 1);
      i0 = std::max(i0, R[0]), j0 = std::max(j0, R[1]), i1 = std::min(i1, R[2]), j1 = std::min(j1, R[3]);
      for (std::size_t j = j0; j <= j1 && i0 <= i1; ++j)
        for (std::size_t i = i0; i <= i1; ++i) {
          const Point2 p{box_.origin[0] + static_cast<double>(i) * cell_, box_.origin[1] + static_cast<double>(j) * cell_};
          double& x = src[(j - R[1]) * rw + (i - R[0])];
          x = std::min(x, h0 + rate * dist_to_segment(p, a, b));
        }
    }
  });
  const double cap = terms_.max_size.value_or(kInf);
  std::vector<std::size_t> nodes;
  std::vector<double> before;
  for (std::size_t j = R[1]; j <= R[3]; ++j)
    for (std::size_t i = R[0]; i <= R[2]; ++i) {
      const std::size_t v = node(i, j);
      const double x = src[(j - R[1]) * rw + (i - R[0])];
      if (x == shore_src_[v]) continue;
      if (std::min(x, cap) != std::min(shore_src_[v], cap)) nodes.push_back(v), before.push_back(std::min(shore_src_[v], cap));
      if (undo) undo->shore_src.push_back({v, shore_src_[v]});
      shore_src_[v] = x;
    }
  std::vector<std::pair<std::size_t, double>> shore_changed;
  const std::size_t visited =
      repair_gradient(shore_, Stencil{w, rate * cell_, rate * cell_ * std::numbers::sqrt2}, nodes, before,
                      [&](std::size_t v) { return std::min(shore_src_[v], cap); }, shore_changed) +
      rw * (R[3] - R[1] + 1);
  if (undo) undo->shore = shore_changed;
  std::vector<std::size_t> hn;
  std::vector<double> hb;
  for (const auto& [v, x] : shore_changed) hn.push_back(v), hb.push_back(raw(v, x));
  SizeChange c = update_h(hn, hb);
  if (!c.whole) c.visited += visited;
  return c;
}

SizeChange SizeField::set_polygon_size(std::size_t index, double size, SizeUndo* undo) {
  if (index >= terms_.polygons.size())
    throw InputError("no size polygon " + std::to_string(index) + " (size polygons: " +
                     (terms_.polygons.empty() ? std::string("none") : "0.." + std::to_string(terms_.polygons.size() - 1)) + ")");
  if (!(std::isfinite(size) && size > 0))
    throw ParameterError("size of polygon " + std::to_string(index) + " must be a positive finite number (got " +
                         number(size) + ")");
  const std::vector<std::size_t>& nodes = polygon_nodes_[index];
  std::vector<double> before;
  before.reserve(nodes.size());
  for (std::size_t v : nodes) before.push_back(raw(v, shore_.empty() ? kInf : shore_[v]));
  undo_ = undo;
  struct Done {
    SizeUndo*& u;
    ~Done() { u = nullptr; }
  } done{undo_};
  if (undo) undo->polygon = {index, terms_.polygons[index].size};
  terms_.polygons[index].size = size;
  return update_h(nodes, before);
}

// The pyramid blocks min_over_box reads for the box [lo, hi]: cells c[0] .. c[1] by c[2] .. c[3].
void SizeField::read_cells(const Point2& lo, const Point2& hi, std::size_t c[4]) const {
  const auto [l, i0, i1, j0, j1] = cell_span(lo, hi);
  c[0] = (i0 >> l) << l, c[1] = (((i1 >> l) + 1) << l) - 1, c[2] = (j0 >> l) << l, c[3] = (((j1 >> l) + 1) << l) - 1;
}

bool SizeField::reads(const Point2& a, const Point2& b, const SizeChange& change) const {
  if (!change.changed) return false;
  // The box grown by a cell: a subsegment's box (its ends computed in doubles) stays inside its edge's.
  std::size_t c[4];
  read_cells({std::min(a[0], b[0]) - cell_, std::min(a[1], b[1]) - cell_},
             {std::max(a[0], b[0]) + cell_, std::max(a[1], b[1]) + cell_}, c);
  // Cells c0 .. c1 hold the nodes c0 .. c1 + 1.
  return c[0] <= change.i1 && change.i0 <= c[1] + 1 && c[2] <= change.j1 && change.j0 <= c[3] + 1;
}

std::pair<Point2, Point2> SizeField::reach_of(const SizeChange& change) const {
  const double by = 5 * cell_;
  return {{box_.origin[0] + static_cast<double>(change.i0) * cell_ - by, box_.origin[1] + static_cast<double>(change.j0) * cell_ - by},
          {box_.origin[0] + static_cast<double>(change.i1) * cell_ + by, box_.origin[1] + static_cast<double>(change.j1) * cell_ + by}};
}

SizeSummary SizeField::summary() const {
  SizeSummary s;
  s.min = kInf;
  s.max = 0;
  s.grid_cells = n_;
  const std::size_t w = n_ + 1;
  for (std::size_t v = 0; v < w * w; ++v) {
    if (!water_[v] || !std::isfinite(h_[v])) continue;
    s.min = std::min(s.min, h_[v]);
    s.max = std::max(s.max, h_[v]);
    const std::size_t i = v % w, j = v / w;
    auto look = [&](std::size_t u, double len) {
      if (std::isfinite(h_[u])) s.grading = std::max(s.grading, std::abs(h_[u] - h_[v]) / len);
    };
    if (i + 1 < w) look(v + 1, cell_);
    if (j + 1 < w) {
      look(v + w, cell_);
      if (i + 1 < w) look(v + w + 1, cell_ * std::numbers::sqrt2);
      if (i > 0) look(v + w - 1, cell_ * std::numbers::sqrt2);
    }
  }
  if (s.min == kInf) s.min = 0;
  return s;
}


bool seed_clear_of_segment(const Point2& p, const Point2& a, const Point2& b, double near, double gamma) {
  thread_local engine::PredicateCounters counters;
  const engine::RoundingGuard guard;
  // Closer than `near` to the segment: to an end when the projection falls outside it, else to its line.
  auto dot_sign = [&](const Point2& o, const Point2& q) {  // sign((p - o) . (q - o))
    return engine::filtered_sign(counters, [&](auto zero) {
      using NT = decltype(zero);
      return (NT(p[0]) - NT(o[0])) * (NT(q[0]) - NT(o[0])) + (NT(p[1]) - NT(o[1])) * (NT(q[1]) - NT(o[1]));
    });
  };
  auto nearer_than = [&](const Point2& o) {  // |p - o| < near
    return engine::filtered_sign(counters, [&](auto zero) {
             using NT = decltype(zero);
             return engine::squared_distance<NT, 2>(p, o) - NT(near) * NT(near);
           }) < 0;
  };
  bool near_segment = false;
  if (dot_sign(a, b) <= 0) near_segment = nearer_than(a);
  else if (dot_sign(b, a) <= 0) near_segment = nearer_than(b);
  else
    near_segment = engine::filtered_sign(counters, [&](auto zero) {
                     using NT = decltype(zero);
                     const NT cross = (NT(b[0]) - NT(a[0])) * (NT(p[1]) - NT(a[1])) - (NT(b[1]) - NT(a[1])) * (NT(p[0]) - NT(a[0]));
                     return cross * cross - NT(near) * NT(near) * engine::squared_distance<NT, 2>(a, b);
                   }) < 0;
  if (near_segment) return false;
  // Strictly inside the diametral circle grown by gamma: |2p - a - b|^2 < gamma^2 |b - a|^2.
  return engine::filtered_sign(counters, [&](auto zero) {
           using NT = decltype(zero);
           const NT dx = NT(2) * NT(p[0]) - NT(a[0]) - NT(b[0]), dy = NT(2) * NT(p[1]) - NT(a[1]) - NT(b[1]);
           return dx * dx + dy * dy - NT(gamma) * NT(gamma) * engine::squared_distance<NT, 2>(a, b);
         }) >= 0;
}

namespace {

// The quadtree's root side: the box, or with --max-size the least square of side kSeedFactor * max * 2^m
// that covers it, so that where the maximum binds the leaves are exactly that size (docs/sizing.md).
double seed_root(const SizeField& field) {
  double root = field.box().side;
  if (const auto& max = field.terms().max_size) {
    root = kSeedFactor * *max;
    while (root < field.box().side) root *= 2;
  }
  return root;
}

struct SeedNode {
  int level;
  std::uint64_t ix, iy;
  int extra;  // levels below the size rule's leaf: a dropped seed's leaf is tried again in quarters
};

struct Rect {
  double x0, y0, x1, y1;
  bool meets(const Rect& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};

BBox bbox(const Rect& r) { return BBox(BPoint(r.x0, r.y0), BPoint(r.x1, r.y1)); }

// The square of a node, grown by `by` on every side.
Rect node_square(const SizeField& field, double root, const SeedNode& n, double by) {
  const double side = std::ldexp(root, -n.level);
  const double x = field.box().origin[0] + static_cast<double>(n.ix) * side, y = field.box().origin[1] + static_cast<double>(n.iy) * side;
  return {x - by, y - by, x + side + by, y + side + by};
}

// Where a seed would be too near segment ab: its box grown by the diametral circle grown by gamma.
Rect segment_reach(const Point2& a, const Point2& b, double gamma) {
  const double r = gamma * 0.5 * std::hypot(b[0] - a[0], b[1] - a[1]);
  const Point2 m{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
  return {std::min({a[0], b[0], m[0] - r}), std::min({a[1], b[1], m[1] - r}), std::max({a[0], b[0], m[0] + r}),
          std::max({a[1], b[1], m[1] + r})};
}

// The refined rings as the seeds' tests read them: the water (exact WaterTest over every ring) and the
// segments in an R-tree of their reach (only those whose reach meets `only`, when given).
class SeedShore {
 public:
  SeedShore(const Domain2& refined, double gamma, const std::optional<Rect>& only = {}) : gamma_(gamma), water_(refined) {
    std::vector<SegmentEntry> entries;
    for (const Ring& ring : refined.rings)
      for (std::size_t k = 0; k < ring.segment_count(); ++k) {
        const Point2& a = ring.points[k];
        const Point2& b = ring.points[(k + 1) % ring.points.size()];
        const Rect reach = segment_reach(a, b, gamma);
        if (only && !reach.meets(*only)) continue;
        entries.push_back({bbox(reach), static_cast<std::uint32_t>(segments_.size())});
        segments_.push_back({a, b});
      }
    index_ = bgi::rtree<SegmentEntry, bgi::quadratic<16>>(entries.begin(), entries.end());
  }
  bool in_water(const Point2& p) const { return water_.in_water(p); }
  bool clear(const Point2& p, double side) const {
    const double near = 0.25 * side;
    for (auto it = index_.qbegin(bgi::intersects(BBox(BPoint(p[0] - near, p[1] - near), BPoint(p[0] + near, p[1] + near))));
         it != index_.qend(); ++it) {
      const auto& [a, b] = segments_[it->second];
      if (!seed_clear_of_segment(p, a, b, near, gamma_)) return false;
    }
    return true;
  }

 private:
  double gamma_;
  WaterTest water_;
  std::vector<std::pair<Point2, Point2>> segments_;
  bgi::rtree<SegmentEntry, bgi::quadratic<16>> index_;
};

}  // namespace

struct SeedShoreIndex::Impl {
  using Entry = std::pair<BBox, ShoreSegment>;
  double gamma;
  WaterTest water;
  std::size_t water_edges = 0;  // none: everything is water, as WaterTest decides for rings without one
  bgi::rtree<Entry, bgi::quadratic<16>> index;

  Impl(const Domain2& refined, double g) : gamma(g), water(refined) {
    std::vector<Entry> entries;
    for (const Ring& ring : refined.rings)
      for (std::size_t k = 0; k < ring.segment_count(); ++k) {
        const Point2& a = ring.points[k];
        const Point2& b = ring.points[(k + 1) % ring.points.size()];
        entries.push_back(entry({std::min(a, b), std::max(a, b), ring.closed()}));
        water_edges += ring.closed();
      }
    index = decltype(index)(entries.begin(), entries.end());
  }
  // The reach is symmetric in the ends (so is the exact test): the segment's order does not matter.
  Entry entry(const ShoreSegment& s) const { return {bbox(segment_reach(s.a, s.b, gamma)), s}; }
  void remove(const ShoreSegment& s) {
    index.remove(entry(s));
    if (s.water) water.remove_edge(s.a, s.b), --water_edges;
  }
  void add(const ShoreSegment& s) {
    index.insert(entry(s));
    if (s.water) water.add_edge(s.a, s.b), ++water_edges;
  }
  bool in_water(const Point2& p) const { return water_edges == 0 || water.in_water(p); }
  bool clear(const Point2& p, double side) const {
    const double near = 0.25 * side;
    for (auto it = index.qbegin(bgi::intersects(BBox(BPoint(p[0] - near, p[1] - near), BPoint(p[0] + near, p[1] + near))));
         it != index.qend(); ++it)
      if (!seed_clear_of_segment(p, it->second.a, it->second.b, near, gamma)) return false;
    return true;
  }
};

SeedShoreIndex::SeedShoreIndex(const Domain2& refined, double gamma) : impl_(std::make_unique<Impl>(refined, gamma)) {}
SeedShoreIndex::~SeedShoreIndex() = default;
SeedShoreIndex::SeedShoreIndex(SeedShoreIndex&&) noexcept = default;
SeedShoreIndex& SeedShoreIndex::operator=(SeedShoreIndex&&) noexcept = default;
void SeedShoreIndex::apply(const ShoreChange& change) {
  for (const ShoreSegment& s : change.removed) impl_->remove(s);
  for (const ShoreSegment& s : change.added) impl_->add(s);
}
void SeedShoreIndex::take_back(const ShoreChange& change) {
  for (const ShoreSegment& s : change.added) impl_->remove(s);
  for (const ShoreSegment& s : change.removed) impl_->add(s);
}
double SeedShoreIndex::gamma() const { return impl_->gamma; }

struct SeedShoreAccess {
  static const SeedShoreIndex::Impl& of(const SeedShoreIndex& s) { return *s.impl_; }
};

namespace {

// The split rule of a node (retries aside): -1 no term sets a size there (no seed), 1 split, 0 a leaf.
// With `before`: as the field was before the update that filled it.
int seed_split(const SizeField& field, double root, const SeedNode& n, const SizeUndo* before = nullptr) {
  const double side = std::ldexp(root, -n.level);
  const BoxTransform<2>& box = field.box();
  const Point2 lo{box.origin[0] + static_cast<double>(n.ix) * side, box.origin[1] + static_cast<double>(n.iy) * side};
  const double h = before ? field.min_over_before(*before, {lo[0] - side, lo[1] - side}, 3 * side)
                          : field.min_over({lo[0] - side, lo[1] - side}, 3 * side);
  if (!std::isfinite(h)) return -1;
  return side > kSeedFactor * h && n.level < 60 ? 1 : 0;
}

bool beyond_box(const SizeField& field, double root, const SeedNode& n) {
  const double side = std::ldexp(root, -n.level);
  const BoxTransform<2>& box = field.box();
  return box.origin[0] + static_cast<double>(n.ix) * side >= box.origin[0] + box.side ||
         box.origin[1] + static_cast<double>(n.iy) * side >= box.origin[1] + box.side;
}

void push_children(std::vector<SeedNode>& work, const SeedNode& n, int extra) {
  for (std::uint64_t c = 0; c < 4; ++c) work.push_back({n.level + 1, 2 * n.ix + (c & 1), 2 * n.iy + (c >> 1), extra});
}

// The seeds of the subtrees at `work` (unsorted), appended to `seeds`.
template <class Shore>
void walk_seeds(const SizeField& field, double root, const Shore& shore, std::vector<SeedNode> work,
                std::vector<Point2>& seeds) {
  const BoxTransform<2>& box = field.box();
  const std::size_t hard_cap = 4 * field.terms().point_cap;
  std::size_t visited = 0;
  while (!work.empty()) {
    const SeedNode n = work.back();
    work.pop_back();
    if (beyond_box(field, root, n)) continue;
    if (++visited > hard_cap)
      throw InputError("the size function asks for more than " + std::to_string(hard_cap) + " quadtree cells");
    if (n.extra == 0) {
      const int rule = seed_split(field, root, n);
      if (rule < 0) continue;  // no term sets a size here
      if (rule > 0) {
        push_children(work, n, 0);
        continue;
      }
    }
    const double side = std::ldexp(root, -n.level);
    const Point2 lo{box.origin[0] + static_cast<double>(n.ix) * side, box.origin[1] + static_cast<double>(n.iy) * side};
    const auto [u, v] = jitter(n.level, n.ix, n.iy);
    const Point2 p{lo[0] + (0.5 + kSeedJitter * u) * side, lo[1] + (0.5 + kSeedJitter * v) * side};
    if (box.contains(p) && shore.in_water(p) && shore.clear(p, side)) {
      seeds.push_back(p);
    } else if (n.extra < kSeedRetries && n.level < 60) {
      push_children(work, n, n.extra + 1);  // near the shore: the leaf's quarters fill what it leaves
    }
  }
}

// The segments of `a` not in `b` (as unordered pairs, counted), appended to `out`.
void segments_not_in(const Domain2& a, const Domain2& b, std::vector<std::pair<Point2, Point2>>& out) {
  auto key = [](const Point2& p, const Point2& q) { return p < q ? std::pair{p, q} : std::pair{q, p}; };
  for (std::size_t r = 0; r < a.rings.size(); ++r) {
    const Ring& ra = a.rings[r];
    const Ring* rb = r < b.rings.size() ? &b.rings[r] : nullptr;
    if (rb && rb->points == ra.points && rb->role == ra.role) continue;
    std::vector<std::pair<Point2, Point2>> mine, theirs;
    for (std::size_t k = 0; k < ra.segment_count(); ++k) mine.push_back(key(ra.points[k], ra.points[(k + 1) % ra.points.size()]));
    if (rb)
      for (std::size_t k = 0; k < rb->segment_count(); ++k) theirs.push_back(key(rb->points[k], rb->points[(k + 1) % rb->points.size()]));
    std::sort(mine.begin(), mine.end());
    std::sort(theirs.begin(), theirs.end());
    std::set_difference(mine.begin(), mine.end(), theirs.begin(), theirs.end(), std::back_inserter(out));
  }
}

}  // namespace

std::vector<Point2> size_seeds(const SizeField& field, const Domain2& refined, double gamma) {
  std::vector<Point2> seeds;
  walk_seeds(field, seed_root(field), SeedShore(refined, gamma), {{0, 0, 0, 0}}, seeds);
  std::sort(seeds.begin(), seeds.end());
  return seeds;
}

namespace {

// update_size_seeds with where h changed (the grid nodes [i0, i1] x [j0, j1]) and the refined segments
// that went or came.
std::vector<Point2> update_seeds(const std::function<int(const SeedNode&)>& old_split, const std::vector<Point2>& old_seeds,
                                 const SizeChange& h_change, const std::vector<std::pair<Point2, Point2>>& changed,
                                 const SizeField& field, const Domain2* refined, const SeedShoreIndex::Impl* shore_kept,
                                 double gamma, SeedUpdate* stats) {
  const double root = seed_root(field);
  const double cell = field.box().side / static_cast<double>(field.cells());
  std::optional<Rect> h_changed;
  if (h_change.changed) {
    const Point2& o = field.box().origin;
    h_changed = Rect{o[0] + static_cast<double>(h_change.i0) * cell, o[1] + static_cast<double>(h_change.j0) * cell,
                     o[0] + static_cast<double>(h_change.i1) * cell, o[1] + static_cast<double>(h_change.j1) * cell};
  }
  // Where the refined rings changed: each changed segment's reach (the seeds' distance tests), and per
  // connected group of changed segments its bounding box (the water: the two domains' even-odd regions
  // differ by the even-odd region of the changed segments, whose every group is a union of closed chains,
  // empty outside its box).
  std::vector<SegmentEntry> reach_entries;
  std::vector<Rect> water_boxes;
  for (const auto& [a, b] : changed) reach_entries.push_back({bbox(segment_reach(a, b, gamma)), 0});
  const std::vector<std::size_t> chain = segment_chains(changed.size(), [&](std::size_t i) -> const auto& { return changed[i]; });
  for (std::size_t i = 0; i < changed.size(); ++i) {
    const auto& [a, b] = changed[i];
    const Rect r{std::min(a[0], b[0]), std::min(a[1], b[1]), std::max(a[0], b[0]), std::max(a[1], b[1])};
    if (chain[i] == water_boxes.size()) {
      water_boxes.push_back(r);
    } else {
      Rect& o = water_boxes[chain[i]];
      o = {std::min(o.x0, r.x0), std::min(o.y0, r.y0), std::max(o.x1, r.x1), std::max(o.y1, r.y1)};
    }
  }
  const bgi::rtree<SegmentEntry, bgi::quadratic<16>> reach_index(reach_entries.begin(), reach_entries.end());
  // A node's subtree reads h over its square grown by 3 sides and a few cells (min_over reads pyramid
  // blocks up to half its box beyond it), the segments within a quarter side of its square and the water
  // in it: when none of these changed, it is the same subtree with the same seeds.
  auto dirty = [&](const SeedNode& n) {
    const double side = std::ldexp(root, -n.level);
    if (h_changed && h_changed->meets(node_square(field, root, n, 3 * side + 4 * cell))) return true;
    const Rect near = node_square(field, root, n, 0.5 * side);
    if (reach_index.qbegin(bgi::intersects(bbox(near))) != reach_index.qend()) return true;
    const Rect square = node_square(field, root, n, 0);
    return std::any_of(water_boxes.begin(), water_boxes.end(), [&](const Rect& r) { return r.meets(square); });
  };
  // Descend while a node is dirty and splits before and after; the nodes where that stops are recomputed
  // whole (their old seeds go), the clean ones keep theirs.
  std::vector<SeedNode> redo, work{{0, 0, 0, 0}};
  std::size_t visited = 0;
  while (!work.empty()) {
    const SeedNode n = work.back();
    work.pop_back();
    ++visited;
    if (beyond_box(field, root, n) || !dirty(n)) continue;
    if (seed_split(field, root, n) == 1 && old_split(n) == 1) {
      push_children(work, n, 0);
      continue;
    }
    redo.push_back(n);
  }
  std::vector<Point2> fresh;
  if (!redo.empty()) {
    Rect all = node_square(field, root, redo.front(), 0);
    for (const SeedNode& n : redo) {
      const Rect r = node_square(field, root, n, 0);
      all = {std::min(all.x0, r.x0), std::min(all.y0, r.y0), std::max(all.x1, r.x1), std::max(all.y1, r.y1)};
    }
    const double margin = 0.5 * std::ldexp(root, -std::min_element(redo.begin(), redo.end(), [](auto& a, auto& b) {
                                                  return a.level < b.level;
                                                })->level);
    if (shore_kept)
      walk_seeds(field, root, *shore_kept, redo, fresh);
    else
      walk_seeds(field, root, SeedShore(*refined, gamma, Rect{all.x0 - margin, all.y0 - margin, all.x1 + margin, all.y1 + margin}),
                 redo, fresh);
  }
  // The old seeds outside the recomputed squares (a seed lies inside its leaf, strictly: the jitter keeps it
  // off the leaf's sides), then the fresh ones.
  std::vector<Point2> out;
  out.reserve(old_seeds.size() + fresh.size());
  std::vector<Rect> squares;
  for (const SeedNode& n : redo) squares.push_back(node_square(field, root, n, 0));
  std::vector<std::uint8_t> gone(old_seeds.size(), 0);
  for (const Rect& r : squares) {
    auto it = std::lower_bound(old_seeds.begin(), old_seeds.end(), Point2{r.x0, -kInf});
    for (; it != old_seeds.end() && (*it)[0] <= r.x1; ++it)
      if ((*it)[1] >= r.y0 && (*it)[1] <= r.y1) gone[static_cast<std::size_t>(it - old_seeds.begin())] = 1;
  }
  for (std::size_t i = 0; i < old_seeds.size(); ++i)
    if (!gone[i]) out.push_back(old_seeds[i]);
  const std::size_t kept = out.size();
  std::sort(fresh.begin(), fresh.end());
  out.insert(out.end(), fresh.begin(), fresh.end());
  std::inplace_merge(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(kept), out.end());
  if (stats) *stats = {visited, redo.size(), old_seeds.size() - kept, fresh.size()};
  return out;
}

bool same_grid(const SizeField& a, const SizeField& b) {
  return a.cells() == b.cells() && a.box().origin == b.box().origin && a.box().side == b.box().side &&
         seed_root(a) == seed_root(b);
}

}  // namespace

std::vector<Point2> update_size_seeds(const SizeField& old_field, const std::vector<Point2>& old_seeds,
                                      const Domain2& old_refined, const SizeField& field, const Domain2& refined,
                                      double gamma, SeedUpdate* stats) {
  if (!same_grid(old_field, field)) {
    if (stats) *stats = {};
    return size_seeds(field, refined, gamma);
  }
  // Where h changed: the grid nodes whose value changed.
  const std::size_t w = field.cells() + 1;
  SizeChange h_change;
  for (std::size_t v = 0; &old_field != &field && v < w * w; ++v) {
    if (old_field.nodes()[v] == field.nodes()[v] ||
        (std::isnan(old_field.nodes()[v]) && std::isnan(field.nodes()[v])))
      continue;
    const std::size_t i = v % w, j = v / w;
    if (!h_change.changed) h_change.i0 = h_change.i1 = i, h_change.j0 = h_change.j1 = j;
    h_change.changed = true;
    h_change.i0 = std::min(h_change.i0, i), h_change.i1 = std::max(h_change.i1, i);
    h_change.j0 = std::min(h_change.j0, j), h_change.j1 = std::max(h_change.j1, j);
  }
  std::vector<std::pair<Point2, Point2>> changed;
  segments_not_in(old_refined, refined, changed);
  segments_not_in(refined, old_refined, changed);
  const double root = seed_root(field);
  return update_seeds([&](const SeedNode& n) { return seed_split(old_field, root, n); }, old_seeds, h_change, changed,
                      field, &refined, nullptr, gamma, stats);
}

std::vector<Point2> update_size_seeds(const SizeField& old_field, const std::vector<Point2>& old_seeds,
                                      const SizeChange& h_change, const ShoreChange& refined_change,
                                      const SizeField& field, const Domain2& refined, double gamma, SeedUpdate* stats) {
  if (!same_grid(old_field, field)) {
    if (stats) *stats = {};
    return size_seeds(field, refined, gamma);
  }
  std::vector<std::pair<Point2, Point2>> changed;
  for (const auto* list : {&refined_change.removed, &refined_change.added})
    for (const ShoreSegment& s : *list) changed.push_back({s.a, s.b});
  const double root = seed_root(field);
  return update_seeds([&](const SeedNode& n) { return seed_split(old_field, root, n); }, old_seeds, h_change, changed,
                      field, &refined, nullptr, gamma, stats);
}

std::vector<Point2> update_size_seeds(const SizeField& field, const SizeUndo& before, const std::vector<Point2>& old_seeds,
                                      const SizeChange& h_change, const ShoreChange& refined_change,
                                      const Domain2& refined, double gamma, SeedUpdate* stats) {
  std::vector<std::pair<Point2, Point2>> changed;
  for (const auto* list : {&refined_change.removed, &refined_change.added})
    for (const ShoreSegment& s : *list) changed.push_back({s.a, s.b});
  const double root = seed_root(field);
  return update_seeds([&](const SeedNode& n) { return seed_split(field, root, n, &before); }, old_seeds, h_change,
                      changed, field, &refined, nullptr, gamma, stats);
}

std::vector<Point2> update_size_seeds(const SizeField& field, const SizeUndo& before, const std::vector<Point2>& old_seeds,
                                      const SizeChange& h_change, const ShoreChange& refined_change,
                                      const SeedShoreIndex& shore, SeedUpdate* stats) {
  std::vector<std::pair<Point2, Point2>> changed;
  for (const auto* list : {&refined_change.removed, &refined_change.added})
    for (const ShoreSegment& s : *list) changed.push_back({s.a, s.b});
  const double root = seed_root(field);
  return update_seeds([&](const SeedNode& n) { return seed_split(field, root, n, &before); }, old_seeds, h_change,
                      changed, field, nullptr, &SeedShoreAccess::of(shore), shore.gamma(), stats);
}

std::function<double(const Point2&, const Point2&)> shore_max_length(std::shared_ptr<const SizeField> field) {
  return [field](const Point2& a, const Point2& b) { return kShoreFactor * field->min_over_segment(a, b); };
}

SizeRatio size_ratio(const SizeField& field, const std::vector<Point2>& points,
                     const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  SizeRatio r;
  double sum = 0;
  std::size_t count = 0;
  for (const auto& t : triangles) {
    const Point2 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
    const Point2 g{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3};
    const double h = field.at(g);
    if (!std::isfinite(h)) continue;
    const double longest = std::max({std::hypot(a[0] - b[0], a[1] - b[1]), std::hypot(b[0] - c[0], b[1] - c[1]),
                                     std::hypot(c[0] - a[0], c[1] - a[1])});
    const double ratio = longest / h;
    sum += ratio;
    ++count;
    if (ratio > r.worst) r.worst = ratio, r.worst_at = g;
  }
  r.mean = count ? sum / static_cast<double>(count) : 0;
  return r;
}

}  // namespace shoremesh
