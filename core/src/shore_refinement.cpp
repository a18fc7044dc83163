#include "shoremesh/shore_refinement.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <tbb/parallel_invoke.h>

#include "shoremesh/engine/predicates.hpp"

namespace shoremesh {

namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox = bg::model::box<BPoint>;

// A ring edge, its ends in lexicographic order so that it has one name whichever way its ring runs.
struct EdgeKey {
  Point2 a, b;
  bool operator==(const EdgeKey&) const = default;
};
EdgeKey edge_key(const Point2& p, const Point2& q) { return p < q ? EdgeKey{p, q} : EdgeKey{q, p}; }
struct EdgeKeyHash {
  std::size_t operator()(const EdgeKey& e) const { return PointHash<2>{}(e.a) * 31 + PointHash<2>{}(e.b); }
};

// A subsegment of edge `edge`: parameters t0 < t1, dyadic, so exact in doubles.
struct Node {
  std::uint32_t edge;
  double t0, t1;
  bool operator==(const Node&) const = default;
};

using PointTree = bgi::rtree<BPoint, bgi::quadratic<16>>;
using DiskEntry = std::pair<BBox, Node>;
using DiskTree = bgi::rtree<DiskEntry, bgi::quadratic<16>>;

BPoint bpoint(const Point2& p) { return BPoint(p[0], p[1]); }
Point2 point_of(const BPoint& p) { return {bg::get<0>(p), bg::get<1>(p)}; }

// cos(angle between u and w) > 1/2, exactly: the two directions meet at less than 60 degrees.
bool sharper_than_60(engine::PredicateCounters& c, const Point2& s, const Point2& o1, const Point2& o2) {
  const int dot = engine::filtered_sign(c, [&](auto zero) {
    using NT = decltype(zero);
    return (NT(o1[0]) - NT(s[0])) * (NT(o2[0]) - NT(s[0])) + (NT(o1[1]) - NT(s[1])) * (NT(o2[1]) - NT(s[1]));
  });
  if (dot <= 0) return false;
  return engine::filtered_sign(c, [&](auto zero) {
           using NT = decltype(zero);
           const NT ux = NT(o1[0]) - NT(s[0]), uy = NT(o1[1]) - NT(s[1]);
           const NT wx = NT(o2[0]) - NT(s[0]), wy = NT(o2[1]) - NT(s[1]);
           const NT d = ux * wx + uy * wy;
           return NT(4) * d * d - (ux * ux + uy * uy) * (wx * wx + wy * wy);
         }) > 0;
}

}  // namespace

struct ShoreRefinement::Impl {
  struct Edge {
    Point2 a, b;             // a < b
    std::vector<double> ts;  // split parameters, sorted, in (0, 1)
    bool alive = false;
    bool water = true;  // a closed ring's edge (a line's bounds nothing)
  };
  struct Neighbours {
    Point2 prev, next;
  };

  RefinementRule rule;
  Domain2 rings;
  std::vector<Edge> edges;
  std::vector<std::uint32_t> free_edges;
  std::unordered_map<EdgeKey, std::uint32_t, EdgeKeyHash> edge_of;
  // A ring vertex's neighbours on each ring through it (several where rings share a vertex: a .poly's
  // segments meeting there, a line ending on a shore), by ring number. A shared vertex is one point.
  std::unordered_map<Point2, std::vector<std::pair<std::size_t, Neighbours>>, PointHash<2>> ring_vertex;
  std::unordered_map<Point2, std::uint32_t, PointHash<2>> split_owner;  // a split point's edge
  PointTree points;  // every input point: ring vertices, loose points, split points
  DiskTree disks;    // every subsegment (leaf or split) with the box of its test disk
  mutable engine::PredicateCounters counters;

  // Filled while closing: the split points made and undone (update nets them).
  std::vector<Point2> made, undone;
  // Filled by update: the refined segments of the edges it touched, before (each edge's first time) and
  // the edges to read after.
  bool recording = false;
  std::vector<ShoreSegment> segments_before;
  std::unordered_set<std::uint32_t> snapped;
  std::vector<std::uint32_t> touched;
  // Set by the rule-change update for the update it calls: which edges the new rule may treat otherwise.
  const std::function<bool(const Point2&, const Point2&)>* rule_changed = nullptr;
  // With it: rule_changed holds only for edges whose reach_box meets this box (lo, hi).
  const std::pair<Point2, Point2>* rule_near = nullptr;
  // The live edges by reach_box, made at the first update that gives rule_near (a fresh run has none).
  std::optional<bgi::rtree<std::pair<BBox, std::uint32_t>, bgi::quadratic<16>>> reach;
  // An edge's box grown by half its longer side (update's contract for rule_near).
  static BBox reach_box(const Edge& e) {
    const double g = 0.5 * std::max(std::abs(e.b[0] - e.a[0]), std::abs(e.b[1] - e.a[1]));
    return BBox(BPoint(std::min(e.a[0], e.b[0]) - g, std::min(e.a[1], e.b[1]) - g),
                BPoint(std::max(e.a[0], e.b[0]) + g, std::max(e.a[1], e.b[1]) + g));
  }

  void segments_of(std::uint32_t i, std::vector<ShoreSegment>& out) const {
    const Edge& e = edges[i];
    Point2 p = e.a;
    for (std::size_t k = 0; k <= e.ts.size(); ++k) {
      const Point2 q = k < e.ts.size() ? at(e, e.ts[k]) : e.b;
      out.push_back({std::min(p, q), std::max(p, q), e.water});
      p = q;
    }
  }
  // Edge i is about to change: its segments as they are, the first time.
  void snap(std::uint32_t i) {
    if (!recording) return;
    if (snapped.insert(i).second) segments_of(i, segments_before);
    touched.push_back(i);
  }

  Point2 at(const Edge& e, double t) const {
    if (t == 0) return e.a;
    if (t == 1) return e.b;
    return {e.a[0] + t * (e.b[0] - e.a[0]), e.a[1] + t * (e.b[1] - e.a[1])};
  }

  bool is_split(const Edge& e, double t) const { return std::binary_search(e.ts.begin(), e.ts.end(), t); }

  BBox disk_box(const Node& n) const {
    const Edge& e = edges[n.edge];
    const Point2 p = at(e, n.t0), q = at(e, n.t1), m = at(e, 0.5 * (n.t0 + n.t1));
    // The union of the test disk and the grading's disks (radius len/c about each end).
    const double grow = std::max(0.5 * rule.gamma, rule.grading > 0 ? 0.5 + 1 / rule.grading : 0.0);
    const double r = grow * std::hypot(q[0] - p[0], q[1] - p[1]) * (1 + 1e-9) + 1e-300 +
                     1e-15 * (std::abs(m[0]) + std::abs(m[1]));
    return BBox(BPoint(m[0] - r, m[1] - r), BPoint(m[0] + r, m[1] + r));
  }

  // The edges point q lies on: its own edge when it is a split, the two ring edges when a ring vertex.
  template <class F>
  void for_each_edge_of(const Point2& q, F&& f) const {
    if (auto it = split_owner.find(q); it != split_owner.end()) {
      const Edge& e = edges[it->second];
      f(e.a, e.b);
    } else if (auto v = ring_vertex.find(q); v != ring_vertex.end()) {
      for (const auto& [ring, n] : v->second) {
        f(q, n.prev);
        f(q, n.next);
      }
    }
  }

  // Whether q may encroach a subsegment of edge e: not when it lies on e, nor on an edge that meets e at a
  // corner sharper than 60 degrees.
  bool may_encroach(const Edge& e, std::uint32_t edge_index, const Point2& q) const {
    if (q == e.a || q == e.b) return false;
    if (auto it = split_owner.find(q); it != split_owner.end() && it->second == edge_index) return false;
    return !at_sharp_corner(e, q);
  }

  // Whether q lies on an edge that meets e at a corner sharper than 60 degrees.
  bool at_sharp_corner(const Edge& e, const Point2& q) const {
    bool excluded = false;
    for_each_edge_of(q, [&](const Point2& u, const Point2& w) {
      for (const auto& [s, o1] : {std::pair{e.a, e.b}, std::pair{e.b, e.a}}) {
        const Point2* o2 = u == s ? &w : w == s ? &u : nullptr;
        if (o2 && sharper_than_60(counters, s, o1, *o2)) excluded = true;
      }
    });
    return excluded;
  }

  // Whether q may drive the grading of edge e's subsegments (q is not the end measured from): e's own
  // points do (the grading along the edge), and any other point but one on an edge meeting e at a corner
  // sharper than 60 degrees (halving would never end there) or one inside e (a loose point on the shore,
  // towards which halving would not end either).
  bool may_grade(const Edge& e, std::uint32_t edge_index, const Point2& q) const {
    if (q == e.a || q == e.b) return true;
    if (auto it = split_owner.find(q); it != split_owner.end() && it->second == edge_index) return true;
    if (!off_line(e.a, e.b, q) && e.a < q && q < e.b) return false;
    return !at_sharp_corner(e, q);
  }

  // Whether x lies off the line through p and q (a point on it, where rings touch, would halve a subsegment
  // without end).
  bool off_line(const Point2& p, const Point2& q, const Point2& x) const {
    return engine::filtered_sign(counters, [&](auto zero) {
             using NT = decltype(zero);
             return (NT(q[0]) - NT(p[0])) * (NT(x[1]) - NT(p[1])) - (NT(q[1]) - NT(p[1])) * (NT(x[0]) - NT(p[0]));
           }) != 0;
  }

  // Whether leaf n must be halved (and can be: its midpoint is a new point strictly between its ends).
  bool encroached(const Node& n) const {
    const Edge& e = edges[n.edge];
    if (-std::ilogb(n.t1 - n.t0) >= rule.max_depth) return false;
    const Point2 p = at(e, n.t0), q = at(e, n.t1), m = at(e, 0.5 * (n.t0 + n.t1));
    if (m == p || m == q) return false;
    if (engine::compare_squared_distance_to<2>(counters, p, q, rule.min_length * rule.min_length) < 0) return false;
    const double g2 = rule.gamma * rule.gamma, c2 = rule.grading * rule.grading;
    bool hit = rule.max_length && std::hypot(q[0] - p[0], q[1] - p[1]) > rule.max_length(p, q), taken = false;
    for (auto it = points.qbegin(bgi::intersects(disk_box(n))); it != points.qend(); ++it) {
      const Point2 x = point_of(*it);
      if (x == m) taken = true;
      if (hit) continue;
      // Grading: |pq| > c |ex| for an end e of pq and another point x.
      if (c2 > 0)
        for (const Point2& end : {p, q})
          if (!hit && x != end && engine::compare_squared_distance_scaled<2>(counters, p, q, c2, end, x) > 0 &&
              may_grade(e, n.edge, x))
            hit = true;
      if (hit || !may_encroach(e, n.edge, x)) continue;
      hit = engine::filtered_sign(counters, [&](auto zero) {
              using NT = decltype(zero);
              return NT(g2) * engine::squared_distance<NT, 2>(p, q) -
                     NT(4) * engine::squared_distance<NT, 2>(x, m);
            }) > 0 &&
            off_line(p, q, x);
    }
    return hit && !taken;  // a midpoint that is already an input point cannot be a new one
  }

  void add_node(const Node& n) { disks.insert({disk_box(n), n}); }
  void remove_node(const Node& n) { disks.remove(DiskEntry{disk_box(n), n}); }

  // The leaves whose test disk holds p: what a new point may encroach.
  void leaves_near(const Point2& p, std::vector<Node>& out) const {
    for (auto it = disks.qbegin(bgi::intersects(bpoint(p))); it != disks.qend(); ++it) {
      const Node& n = it->second;
      if (!is_split(edges[n.edge], 0.5 * (n.t0 + n.t1))) out.push_back(n);
    }
  }

  bool has_point(const Point2& p) const {
    for (auto it = points.qbegin(bgi::intersects(bpoint(p))); it != points.qend(); ++it)
      if (point_of(*it) == p) return true;
    return false;
  }

  // A point that is there already (a vertex another ring shares) is one point.
  void add_point(const Point2& p, std::vector<Node>& work) {
    if (!has_point(p)) points.insert(bpoint(p));
    leaves_near(p, work);
  }

  // Ring r no longer has vertex p (its other rings keep it).
  void drop_ring_vertex(std::size_t r, const Point2& p) {
    const auto it = ring_vertex.find(p);
    if (it == ring_vertex.end()) return;
    std::erase_if(it->second, [&](const auto& e) { return e.first == r; });
    if (it->second.empty()) ring_vertex.erase(it);
  }

  // Applies the rule until no leaf is encroached (the least fixed point from the current state).
  void close(std::vector<Node> work) {
    while (!work.empty()) {
      const Node n = work.back();
      work.pop_back();
      Edge& e = edges[n.edge];
      const double tm = 0.5 * (n.t0 + n.t1);
      if (!e.alive || is_split(e, tm) || !encroached(n)) continue;
      // n may have been queued before its edge was reset: it must still be a node of the edge.
      if ((n.t0 != 0 && !is_split(e, n.t0)) || (n.t1 != 1 && !is_split(e, n.t1))) continue;
      snap(n.edge);
      e.ts.insert(std::upper_bound(e.ts.begin(), e.ts.end(), tm), tm);
      const Point2 m = at(e, tm);
      split_owner.emplace(m, n.edge);
      made.push_back(m);
      const Node left{n.edge, n.t0, tm}, right{n.edge, tm, n.t1};
      add_node(left);
      add_node(right);
      work.push_back(left);
      work.push_back(right);
      add_point(m, work);
    }
  }

  // `add`: its node goes into the disks' tree now (build loads the first nodes into it at once instead).
  std::uint32_t new_edge(const Point2& p, const Point2& q, bool water, bool add = true) {
    const EdgeKey k = edge_key(p, q);
    std::uint32_t i;
    if (!free_edges.empty()) {
      i = free_edges.back();
      free_edges.pop_back();
    } else {
      i = static_cast<std::uint32_t>(edges.size());
      edges.emplace_back();
    }
    edges[i] = Edge{k.a, k.b, {}, true, water};
    if (reach) reach->insert({reach_box(edges[i]), i});
    if (recording) {  // it had no segments: only its new ones count
      snapped.insert(i);
      touched.push_back(i);
    }
    edge_of.emplace(k, i);
    if (add) add_node({i, 0, 1});
    return i;
  }

  // Every node of edge i: the leaves and the subsegments that were split, from the sorted parameters.
  void for_each_node(std::uint32_t i, const std::function<void(const Node&)>& f) const {
    const Edge& e = edges[i];
    std::function<void(double, double)> walk = [&](double t0, double t1) {
      f({i, t0, t1});
      const double tm = 0.5 * (t0 + t1);
      if (is_split(e, tm)) {
        walk(t0, tm);
        walk(tm, t1);
      }
    };
    walk(0, 1);
  }

  // Takes back every split of edge i (and, unless `keep`, the edge itself).
  void reset_edge(std::uint32_t i, bool keep) {
    Edge& e = edges[i];
    for_each_node(i, [&](const Node& n) { remove_node(n); });
    for (double t : e.ts) {
      const Point2 m = at(e, t);
      points.remove(bpoint(m));
      split_owner.erase(m);
      undone.push_back(m);
    }
    e.ts.clear();
    if (keep) {
      add_node({i, 0, 1});
    } else {
      edge_of.erase(edge_key(e.a, e.b));
      if (reach) reach->remove({reach_box(e), i});
      e.alive = false;
      free_edges.push_back(i);
    }
  }

  // A line's ends have one neighbour: the other is the point itself (an edge of no length, which
  // excludes nothing in may_encroach).
  void add_ring_vertices(std::size_t r, const Ring& ring, std::size_t first, std::size_t count) {
    const std::size_t n = ring.points.size();
    for (std::size_t j = first; j < first + count; ++j) {
      const std::size_t k = j % n;
      const bool open_start = !ring.closed() && k == 0, open_end = !ring.closed() && k + 1 == n;
      const Neighbours pair{ring.points[open_start ? k : (k + n - 1) % n], ring.points[open_end ? k : (k + 1) % n]};
      drop_ring_vertex(r, ring.points[k]);
      ring_vertex[ring.points[k]].emplace_back(r, pair);
    }
  }

  void build(std::span<const Point2> loose) {
    std::size_t vertices = 0;
    for (const Ring& ring : rings.rings) vertices += ring.points.size();
    // Three parts that share nothing, made at the same time: the ring vertices' neighbours, the tree of
    // the points, and the edges with the tree of their first nodes.
    std::vector<Node> work;
    auto neighbours = [&] {
      ring_vertex.reserve(vertices);
      for (std::size_t r = 0; r < rings.rings.size(); ++r) add_ring_vertices(r, rings.rings[r], 0, rings.rings[r].points.size());
    };
    auto point_tree = [&] {
      std::vector<Point2> all;
      all.reserve(vertices + loose.size());
      for (const Ring& ring : rings.rings) all.insert(all.end(), ring.points.begin(), ring.points.end());
      all.insert(all.end(), loose.begin(), loose.end());
      std::sort(all.begin(), all.end());  // a vertex that rings share is one point
      all.erase(std::unique(all.begin(), all.end()), all.end());
      std::vector<BPoint> tree_points;
      tree_points.reserve(all.size());
      for (const Point2& p : all) tree_points.push_back(bpoint(p));
      all = {};
      points = PointTree(tree_points.begin(), tree_points.end());  // packed bulk load
    };
    auto edge_tree = [&] {
      edge_of.reserve(vertices);
      edges.reserve(vertices);
      for (const Ring& ring : rings.rings)
        for (std::size_t k = 0; k < ring.segment_count(); ++k) {
          const Point2& p = ring.points[k];
          const Point2& q = ring.points[(k + 1) % ring.points.size()];
          if (p == q || edge_of.count(edge_key(p, q))) continue;
          work.push_back({new_edge(p, q, ring.closed(), false), 0, 1});
        }
      // The edges' first nodes loaded at once (packed), not inserted one by one: the closure is the least
      // fixed point of the rule, whatever order the tree gives the leaves in.
      std::vector<DiskEntry> first_nodes;
      first_nodes.reserve(work.size());
      for (const Node& n : work) first_nodes.emplace_back(disk_box(n), n);
      disks = DiskTree(first_nodes.begin(), first_nodes.end());
    };
    tbb::parallel_invoke(neighbours, point_tree, edge_tree);
    close(std::move(work));
    made.clear();
  }
};

ShoreRefinement::ShoreRefinement(const Domain2& rings, std::span<const Point2> loose, RefinementRule rule)
    : impl_(std::make_unique<Impl>()) {
  if (!(rule.gamma >= 1) || rule.max_depth < 1 || rule.max_depth > 50 || !(rule.min_length >= 0) ||
      !(rule.grading == 0 || rule.grading >= 2))
    throw std::invalid_argument(
        "ShoreRefinement: gamma must be at least 1, max_depth in 1..50, min_length >= 0, grading 0 or at least 2");
  impl_->rule = rule;
  impl_->rings = rings;
  impl_->build(loose);
}

ShoreRefinement::~ShoreRefinement() = default;
ShoreRefinement::ShoreRefinement(ShoreRefinement&&) noexcept = default;
ShoreRefinement& ShoreRefinement::operator=(ShoreRefinement&&) noexcept = default;

const Domain2& ShoreRefinement::rings() const { return impl_->rings; }

Domain2 ShoreRefinement::refined() const {
  const Impl& m = *impl_;
  Domain2 out;
  out.rings.reserve(m.rings.rings.size());
  for (const Ring& ring : m.rings.rings) {
    Ring r{{}, ring.role};
    r.points.reserve(ring.points.size());
    for (std::size_t k = 0; k < ring.points.size(); ++k) {
      const Point2& p = ring.points[k];
      const Point2& q = ring.points[(k + 1) % ring.points.size()];
      r.points.push_back(p);
      const auto it = m.edge_of.find(edge_key(p, q));
      if (it == m.edge_of.end()) continue;
      const auto& e = m.edges[it->second];
      if (p == e.a)
        for (double t : e.ts) r.points.push_back(m.at(e, t));
      else
        for (auto t = e.ts.rbegin(); t != e.ts.rend(); ++t) r.points.push_back(m.at(e, *t));
    }
    out.rings.push_back(std::move(r));
  }
  return out;
}

std::vector<Point2> ShoreRefinement::split_points() const {
  std::vector<Point2> out;
  out.reserve(impl_->split_owner.size());
  for (const auto& [p, e] : impl_->split_owner) out.push_back(p);
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t ShoreRefinement::split_count() const { return impl_->split_owner.size(); }

bool corner_sharper_than_60(const Point2& apex, const Point2& a, const Point2& b) {
  engine::PredicateCounters counters;
  return sharper_than_60(counters, apex, a, b);
}

RingStretch apply_stretch(Domain2& rings, const RingStretch& s) {
  if (s.ring >= rings.rings.size()) rings.rings.resize(s.ring + 1);
  Ring& ring = rings.rings[s.ring];
  RingStretch undo{s.ring, s.prefix, s.suffix, {}, s.whole, ring.role};
  if (s.whole) {
    if (ring.points.empty()) ring.role = s.role;
    undo.middle = std::move(ring.points);
    ring.points = s.middle;
    return undo;
  }
  auto& pts = ring.points;
  const auto first = pts.begin() + static_cast<std::ptrdiff_t>(s.prefix);
  const auto last = pts.end() - static_cast<std::ptrdiff_t>(s.suffix);
  undo.middle.assign(first, last);
  if (static_cast<std::size_t>(last - first) == s.middle.size()) std::copy(s.middle.begin(), s.middle.end(), first);  // a move
  else pts.insert(pts.erase(first, last), s.middle.begin(), s.middle.end());
  return undo;
}

SplitChange ShoreRefinement::update(const Domain2& rings, std::span<const Point2> loose_removed,
                                    std::span<const Point2> loose_added) {
  // Each changed ring's stretch between its common prefix and suffix (a ring that came or went, or a line
  // that changed, whole).
  std::vector<RingStretch> edits;
  static const std::vector<Point2> no_ring;
  const Domain2& now = impl_->rings;
  for (std::size_t r = 0; r < std::max(rings.rings.size(), now.rings.size()); ++r) {
    const auto& o = r < now.rings.size() ? now.rings[r].points : no_ring;
    const auto& n = r < rings.rings.size() ? rings.rings[r].points : no_ring;
    if (o == n) continue;
    const bool line = (r < now.rings.size() && !now.rings[r].closed()) || (r < rings.rings.size() && !rings.rings[r].closed());
    const RingRole role = r < rings.rings.size() ? rings.rings[r].role : RingRole::Shore;
    if (o.empty() || n.empty() || line) {
      edits.push_back({r, 0, 0, n, true, role});
      continue;
    }
    const std::size_t common = std::min(o.size(), n.size());
    std::size_t prefix = 0, suffix = 0;
    while (prefix < common && o[prefix] == n[prefix]) ++prefix;
    while (suffix < common - prefix && o[o.size() - 1 - suffix] == n[n.size() - 1 - suffix]) ++suffix;
    edits.push_back({r, prefix, suffix, std::vector<Point2>(n.begin() + static_cast<std::ptrdiff_t>(prefix),
                                                            n.end() - static_cast<std::ptrdiff_t>(suffix)),
                     false, role});
  }
  SplitChange change = update(std::span<const RingStretch>(edits), loose_removed, loose_added);
  impl_->rings.rings.resize(rings.rings.size());  // a ring past the new last went
  return change;
}

SplitChange ShoreRefinement::update(std::span<const RingStretch> edits, std::span<const Point2> loose_removed,
                                    std::span<const Point2> loose_added, RefinementRule rule,
                                    const std::function<bool(const Point2&, const Point2&)>& rule_changed,
                                    std::optional<std::pair<Point2, Point2>> near) {
  Impl& m = *impl_;
  m.rule = std::move(rule);
  m.rule_changed = &rule_changed;
  m.rule_near = near ? &*near : nullptr;
  struct Clear {
    Impl& m;
    ~Clear() { m.rule_changed = nullptr, m.rule_near = nullptr; }
  } clear{m};
  return update(edits, loose_removed, loose_added);
}

SplitChange ShoreRefinement::update(std::span<const RingStretch> edits, std::span<const Point2> loose_removed,
                                    std::span<const Point2> loose_added) {
  Impl& m = *impl_;
  m.made.clear();
  m.undone.clear();
  m.recording = true;
  m.segments_before.clear();
  m.snapped.clear();
  m.touched.clear();

  // Per changed ring: the stretch between the common prefix and suffix, widened by two vertices each way,
  // since a vertex whose neighbour changed has a new corner, which decides what may encroach its edges.
  std::vector<std::uint32_t> dirty;
  std::unordered_set<std::uint32_t> is_dirty, old_stretch;
  std::vector<std::pair<EdgeKey, bool>> new_edges;  // with whether it bounds water
  std::vector<Point2> removed_points(loose_removed.begin(), loose_removed.end());
  std::vector<Point2> added_points(loose_added.begin(), loose_added.end());
  // Under a new rule: the edges it may treat otherwise lose their splits (the cascade below takes what
  // those justified); every other subsegment meets the same test as before.
  if (m.rule_changed) {
    auto test = [&](std::uint32_t i) {
      if (m.edges[i].alive && (*m.rule_changed)(m.edges[i].a, m.edges[i].b) && is_dirty.insert(i).second) dirty.push_back(i);
    };
    if (m.rule_near) {  // the edges whose reach meets the box, in the scan's order
      if (!m.reach) {
        std::vector<std::pair<BBox, std::uint32_t>> entries;
        for (std::uint32_t i = 0; i < m.edges.size(); ++i)
          if (m.edges[i].alive) entries.push_back({Impl::reach_box(m.edges[i]), i});
        m.reach.emplace(entries.begin(), entries.end());
      }
      std::vector<std::uint32_t> near;
      const BBox q(bpoint(m.rule_near->first), bpoint(m.rule_near->second));
      for (auto it = m.reach->qbegin(bgi::intersects(q)); it != m.reach->qend(); ++it) near.push_back(it->second);
      std::sort(near.begin(), near.end());
      for (std::uint32_t i : near) test(i);
    } else {
      for (std::uint32_t i = 0; i < m.edges.size(); ++i) test(i);
    }
  }
  for (const RingStretch& edit : edits) {
    const std::size_t r = edit.ring;
    if (r >= m.rings.rings.size()) m.rings.rings.resize(r + 1);
    Ring& ring = m.rings.rings[r];
    if (ring.points.empty()) ring.role = edit.role;
    const bool water = ring.closed();
    if (edit.whole || ring.points.empty()) {  // a ring came or went, or a line changed: all of its vertices and edges
      const std::vector<Point2>& o = ring.points;
      for (const Point2& p : o) {
        removed_points.push_back(p);
        m.drop_ring_vertex(r, p);
      }
      for (std::size_t k = 0; k < ring.segment_count(); ++k) {
        const auto it = m.edge_of.find(edge_key(o[k], o[(k + 1) % o.size()]));
        if (it == m.edge_of.end()) continue;
        old_stretch.insert(it->second);
        if (is_dirty.insert(it->second).second) dirty.push_back(it->second);
      }
      ring.points = edit.middle;
      const std::vector<Point2>& n = ring.points;
      added_points.insert(added_points.end(), n.begin(), n.end());
      for (std::size_t k = 0; k < ring.segment_count(); ++k)
        if (n[k] != n[(k + 1) % n.size()]) new_edges.push_back({edge_key(n[k], n[(k + 1) % n.size()]), water});
      if (!n.empty()) m.add_ring_vertices(r, ring, 0, n.size());
      continue;
    }
    const std::size_t prefix = edit.prefix, suffix = edit.suffix;
    std::vector<Point2>& pts = ring.points;
    // Changed vertices: pts[prefix, size - suffix) go, edit.middle comes.
    for (std::size_t k = prefix; k < pts.size() - suffix; ++k) {
      removed_points.push_back(pts[k]);
      m.drop_ring_vertex(r, pts[k]);
    }
    added_points.insert(added_points.end(), edit.middle.begin(), edit.middle.end());
    // Edges from vertex prefix - 2 to vertex size - suffix + 1 (cyclically), old and new.
    auto stretch_edges = [&](const std::vector<Point2>& points, auto&& f) {
      const std::size_t s = points.size();
      const std::size_t changed = s - suffix - prefix;
      const std::size_t count = std::min(s, changed + 4);
      for (std::size_t j = 0; j < count; ++j) {
        const std::size_t k = (prefix + 2 * s - 2 + j) % s;
        f(points[k], points[(k + 1) % s]);
      }
    };
    stretch_edges(pts, [&](const Point2& p, const Point2& q) {
      const auto it = m.edge_of.find(edge_key(p, q));
      if (it == m.edge_of.end()) return;
      old_stretch.insert(it->second);
      if (is_dirty.insert(it->second).second) dirty.push_back(it->second);
    });
    apply_stretch(m.rings, edit);
    stretch_edges(pts, [&](const Point2& p, const Point2& q) {
      if (p != q) new_edges.push_back({edge_key(p, q), water});
    });
    const std::size_t n = pts.size();
    m.add_ring_vertices(r, ring, prefix + n - 2, std::min(n, n - suffix - prefix + 4));
  }

  // Edges whose subsegments (at any level) had a removed point in their test region (disk_box: the test
  // disk and the grading's disks about the ends) lose their splits too, and so on with those splits: what
  // is left was justified without any removed point (docs/conforming.md).
  std::vector<Point2> gone = removed_points;
  for (std::uint32_t i : dirty)
    for (double t : m.edges[i].ts) gone.push_back(m.at(m.edges[i], t));
  for (std::size_t g = 0; g < gone.size(); ++g) {
    std::vector<std::uint32_t> hit;
    for (auto it = m.disks.qbegin(bgi::intersects(bpoint(gone[g]))); it != m.disks.qend(); ++it)
      hit.push_back(it->second.edge);
    for (std::uint32_t i : hit)
      if (is_dirty.insert(i).second) {
        dirty.push_back(i);
        for (double t : m.edges[i].ts) gone.push_back(m.at(m.edges[i], t));
      }
  }

  std::unordered_set<EdgeKey, EdgeKeyHash> keep;
  for (const auto& [k, water] : new_edges) keep.insert(k);
  // A vertex that another ring keeps (a line's end on a shore) stays a point; the edges near it were
  // reset all the same (its corners changed).
  for (const Point2& p : removed_points)
    if (!m.ring_vertex.count(p)) m.points.remove(bpoint(p));
  std::vector<Node> work;
  for (std::uint32_t i : dirty) {
    // An edge of an old stretch stays only when the new rings have it; the others are unchanged edges.
    const bool kept = !old_stretch.count(i) || keep.count(edge_key(m.edges[i].a, m.edges[i].b));
    m.snap(i);
    m.reset_edge(i, kept);
    if (kept) work.push_back({i, 0, 1});
  }
  for (const auto& [k, water] : new_edges)
    if (!m.edge_of.count(k)) work.push_back({m.new_edge(k.a, k.b, water), 0, 1});
  for (const Point2& p : added_points) m.add_point(p, work);
  m.close(std::move(work));

  // Net: a split undone and made again at the same place did not change; nor did a segment.
  SplitChange change;
  std::sort(m.made.begin(), m.made.end());
  std::sort(m.undone.begin(), m.undone.end());
  std::set_difference(m.undone.begin(), m.undone.end(), m.made.begin(), m.made.end(),
                      std::back_inserter(change.removed));
  std::set_difference(m.made.begin(), m.made.end(), m.undone.begin(), m.undone.end(),
                      std::back_inserter(change.added));
  std::vector<ShoreSegment> after;
  std::sort(m.touched.begin(), m.touched.end());
  m.touched.erase(std::unique(m.touched.begin(), m.touched.end()), m.touched.end());
  for (std::uint32_t i : m.touched)
    if (m.edges[i].alive) m.segments_of(i, after);
  std::sort(m.segments_before.begin(), m.segments_before.end());
  std::sort(after.begin(), after.end());
  std::set_difference(m.segments_before.begin(), m.segments_before.end(), after.begin(), after.end(),
                      std::back_inserter(change.segments.removed));
  std::set_difference(after.begin(), after.end(), m.segments_before.begin(), m.segments_before.end(),
                      std::back_inserter(change.segments.added));
  m.made.clear();
  m.undone.clear();
  m.recording = false;
  m.segments_before.clear();
  m.snapped.clear();
  m.touched.clear();
  return change;
}

void ShoreRefinement::check_valid() const {
  std::vector<Point2> loose;
  // The loose points are those of the point index that are neither ring vertices nor splits.
  for (const BPoint& b : impl_->points) {
    const Point2 p = point_of(b);
    if (!impl_->ring_vertex.count(p) && !impl_->split_owner.count(p)) loose.push_back(p);
  }
  const ShoreRefinement fresh(impl_->rings, loose, impl_->rule);
  if (fresh.split_points() != split_points())
    throw std::logic_error("shore refinement: " + std::to_string(split_count()) + " split points, a fresh one has " +
                           std::to_string(fresh.split_count()) + (fresh.split_count() == split_count() ? " (others)" : ""));
  if (fresh.refined().rings.size() != refined().rings.size())
    throw std::logic_error("shore refinement: ring count differs from a fresh one");
}

}  // namespace shoremesh
