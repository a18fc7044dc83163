#include "shoremesh/ring_edge_index.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "ring_geometry.hpp"

namespace shoremesh {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {

using BoxCorner = bg::model::point<double, 2, bg::cs::cartesian>;
using Box = bg::model::box<BoxCorner>;

struct IndexedEdge {
  std::size_t ring = 0;
  Point2 a{}, b{};
  bool line = false;  // a segment of a line: a constraint that bounds no water
  bool operator==(const IndexedEdge&) const = default;
};
using Entry = std::pair<Box, IndexedEdge>;

// The closed box of segment ab: copies of the coordinates, so the tree's box tests are exact and miss
// no edge that segments_meet would find.
Box box_of(const Point2& a, const Point2& b) {
  return {BoxCorner(std::min(a[0], b[0]), std::min(a[1], b[1])), BoxCorner(std::max(a[0], b[0]), std::max(a[1], b[1]))};
}

Entry entry(std::size_t ring, const Point2& a, const Point2& b, bool line = false) {
  return {box_of(a, b), IndexedEdge{ring, a, b, line}};
}

std::vector<Entry> ring_entries(std::size_t r, const Ring& ring) {
  std::vector<Entry> out;
  const auto& pts = ring.points;
  out.reserve(pts.size());
  for (std::size_t i = 0; i < ring.segment_count(); ++i) out.push_back(entry(r, pts[i], pts[(i + 1) % pts.size()], !ring.closed()));
  return out;
}

// The index in `ring` of the edge a -> b (the error path only: a linear scan).
std::size_t edge_index(const std::vector<Point2>& ring, const Point2& a, const Point2& b) {
  for (std::size_t i = 0; i < ring.size(); ++i)
    if (ring[i] == a && ring[(i + 1) % ring.size()] == b) return i;
  throw std::logic_error("ring edge index: an indexed edge is not in the rings");
}

}  // namespace

struct RingEdgeIndex::Tree {
  bgi::rtree<Entry, bgi::quadratic<16>> rtree;

  // Among the indexed edges meeting edge e of ring `ring` in `rings` (other than e itself, its two
  // neighbours and those `skip` names), the first in (ring, edge) order. `shared_vertices`: edges that
  // have a common end meet only where they fold onto one another.
  template <class Skip = bool (*)(const IndexedEdge&)>
  std::optional<std::pair<std::size_t, std::size_t>> first_met(const Domain2& rings, std::size_t ring, std::size_t e,
                                                               Skip skip = [](const IndexedEdge&) { return false; },
                                                               bool shared_vertices = false) const {
    const auto& pts = rings.rings[ring].points;
    const std::size_t n = pts.size();
    const Point2 &a = pts[e], &b = pts[(e + 1) % n];
    const Point2 &prev = pts[(e + n - 1) % n], &next = pts[(e + 2) % n];
    std::vector<Entry> near;
    rtree.query(bgi::intersects(box_of(a, b)), std::back_inserter(near));
    std::optional<std::pair<std::size_t, std::size_t>> first;
    for (const auto& [box, f] : near) {
      if (skip(f)) continue;
      if (f.ring == ring && ((f.a == a && f.b == b) || (f.a == prev && f.b == a) || (f.a == b && f.b == next)))
        continue;  // itself, its neighbours
      if (!(shared_vertices ? detail::edges_conflict(a, b, f.a, f.b) : detail::segments_meet(a, b, f.a, f.b))) continue;
      const std::pair<std::size_t, std::size_t> at{f.ring, edge_index(rings.rings.at(f.ring).points, f.a, f.b)};
      if (!first || at < *first) first = at;
    }
    return first;
  }
};

RingEdgeIndex::RingEdgeIndex(const Domain2& domain) : tree_(std::make_unique<Tree>()) {
  std::vector<Entry> entries;
  for (std::size_t r = 0; r < domain.rings.size(); ++r) {
    auto e = ring_entries(r, domain.rings[r]);
    entries.insert(entries.end(), e.begin(), e.end());
  }
  tree_->rtree = decltype(tree_->rtree)(entries.begin(), entries.end());  // packed: a bulk load
}

RingEdgeIndex::~RingEdgeIndex() = default;
RingEdgeIndex::RingEdgeIndex(RingEdgeIndex&&) noexcept = default;
RingEdgeIndex& RingEdgeIndex::operator=(RingEdgeIndex&&) noexcept = default;

std::size_t RingEdgeIndex::size() const { return tree_->rtree.size(); }

std::optional<RingDefect> RingEdgeIndex::first_crossing(const Domain2& domain, bool shared_vertices) const {
  // The first edge in (ring, edge) order that meets another: its partner comes later in that order (an
  // earlier one would have been found at the partner).
  for (std::size_t r = 0; r < domain.rings.size(); ++r)
    for (std::size_t e = 0; e < domain.rings[r].segment_count(); ++e)
      if (const auto f = tree_->first_met(domain, r, e, [](const IndexedEdge&) { return false; }, shared_vertices))
        return detail::crossing(r, e, f->first, f->second);
  return std::nullopt;
}

std::optional<RingDefect> RingEdgeIndex::defect_at(const Domain2& after, const RingVertexEdit& edit) const {
  const std::size_t ring = edit.ring;
  const auto& pts = after.rings.at(ring).points;
  const std::size_t n = pts.size();
  if (n < 3) return RingDefect{RingDefect::Kind::TooFewPoints, ring, 0, ring, 0};
  const std::size_t vertex = edit.vertex, before = (vertex + n - 1) % n;
  for (const std::size_t i : {before, vertex}) {
    const std::size_t j = (i + 1) % n;
    if (pts[i] == pts[j]) return RingDefect{RingDefect::Kind::RepeatedVertex, ring, i, ring, j};
  }
  for (const std::size_t i : {(before + n - 1) % n, before, vertex})  // folds at before, vertex, after
    if (detail::adjacent_edges_overlap(pts[i], pts[(i + 1) % n], pts[(i + 2) % n]))
      return RingDefect{RingDefect::Kind::Intersection, ring, i, ring, (i + 1) % n};
  // The edges into and out of `vertex` (for a removal, the one into it was there before: harmless) against
  // the indexed edges their boxes meet. The tree holds the rings before the edit: the edges it took away
  // (at `gone`, or the edge an inserted vertex split) are not in `after`, and the edges after the edit that
  // it lacks are these two, which follow one another (the folds above). Among the crossings, the first in
  // (ring, edge) order, as a scan would find it.
  const bool insert = edit.kind == RingVertexEdit::Kind::Insert;
  const Point2 &split_a = pts[before], &split_b = pts[(vertex + 1) % n];  // Insert: the edge that went
  auto taken_away = [&](const IndexedEdge& f) {
    if (f.ring != ring) return false;
    return insert ? f.a == split_a && f.b == split_b : f.a == edit.gone || f.b == edit.gone;
  };
  for (const std::size_t e : {before, vertex})
    if (const auto first = tree_->first_met(after, ring, e, taken_away, true))
      return detail::crossing(ring, e, first->first, first->second);
  return std::nullopt;
}

void RingEdgeIndex::commit(const Domain2& after, const RingVertexEdit& edit) {
  const auto& pts = after.rings.at(edit.ring).points;
  const std::size_t n = pts.size(), before = (edit.vertex + n - 1) % n;
  if (edit.kind == RingVertexEdit::Kind::Insert) {
    if (tree_->rtree.remove(entry(edit.ring, pts[before], pts[(edit.vertex + 1) % n])) != 1)
      throw std::logic_error("ring edge index: an inserted vertex splits no indexed edge");
  } else {
    std::vector<Entry> leaving;
    tree_->rtree.query(bgi::intersects(box_of(edit.gone, edit.gone)), std::back_inserter(leaving));
    for (const Entry& e : leaving)
      if (e.second.ring == edit.ring && (e.second.a == edit.gone || e.second.b == edit.gone)) tree_->rtree.remove(e);
  }
  if (edit.kind != RingVertexEdit::Kind::Remove) tree_->rtree.insert(entry(edit.ring, pts[before], pts[edit.vertex]));
  tree_->rtree.insert(entry(edit.ring, pts[edit.vertex], pts[(edit.vertex + 1) % n]));
}

std::optional<RingDefect> RingEdgeIndex::defect_of_new_ring(const Domain2& after, std::size_t ring) const {
  const Ring& new_ring = after.rings.at(ring);
  if (auto d = detail::local_ring_defect(new_ring, ring)) return d;
  // Its own crossings, through an index of the ring alone, then against the indexed edges: the first
  // crossing in (ring, edge) order over both.
  Domain2 alone;
  alone.rings.resize(ring + 1);
  alone.rings[ring] = new_ring;
  std::optional<RingDefect> first = RingEdgeIndex(alone).first_crossing(alone);
  for (std::size_t e = 0; e < new_ring.segment_count(); ++e)
    if (const auto f = tree_->first_met(after, ring, e, [](const IndexedEdge&) { return false; }, true)) {
      const RingDefect d = detail::crossing(ring, e, f->first, f->second);
      if (!first || std::tie(d.ring_a, d.vertex_a, d.ring_b, d.vertex_b) <
                        std::tie(first->ring_a, first->vertex_a, first->ring_b, first->vertex_b))
        first = d;
    }
  if (first) return first;
  if (new_ring.closed()) {  // the water flips inside it: a line there would be left on land
    for (std::size_t l = 0; l < after.rings.size(); ++l)
      if (!after.rings[l].closed() && !after.rings[l].points.empty() &&
          ring_contains(new_ring.points, after.rings[l].points.front()))
        return RingDefect{RingDefect::Kind::LineOnLand, l, 0, l, 0};
    return std::nullopt;
  }
  // A line must lie in the water (when there is any).
  const bool water = std::any_of(after.rings.begin(), after.rings.end(),
                                 [](const Ring& r) { return r.closed() && !r.points.empty(); });
  if (water && !inside(line_probe(new_ring))) return RingDefect{RingDefect::Kind::LineOnLand, ring, 0, ring, 0};
  return std::nullopt;
}

void RingEdgeIndex::insert_ring(std::size_t r, const Ring& ring) {
  const auto entries = ring_entries(r, ring);
  tree_->rtree.insert(entries.begin(), entries.end());
}

void RingEdgeIndex::erase_ring(std::size_t r, const Ring& ring) {
  const auto entries = ring_entries(r, ring);
  if (tree_->rtree.remove(entries.begin(), entries.end()) != entries.size())
    throw std::logic_error("ring edge index: a removed ring's edge was not indexed");
}

bool RingEdgeIndex::has_vertex(const Point2& p, bool closed_only) const {
  for (auto it = tree_->rtree.qbegin(bgi::intersects(box_of(p, p))); it != tree_->rtree.qend(); ++it)
    if ((it->second.a == p || it->second.b == p) && !(closed_only && it->second.line)) return true;
  return false;
}

Point2 RingEdgeIndex::line_probe(const Ring& line) const {
  for (const Point2& p : line.points)
    if (!has_vertex(p, true)) return p;
  const Point2 &a = line.points.at(0), &b = line.points.at(1);
  return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
}

bool RingEdgeIndex::inside(const Point2& p) const {
  const Box ray(BoxCorner(p[0], p[1]), BoxCorner(std::numeric_limits<double>::max(), p[1]));
  bool in = false;
  for (auto it = tree_->rtree.qbegin(bgi::intersects(ray)); it != tree_->rtree.qend(); ++it) {
    if (it->second.line) continue;
    const Point2 &a = it->second.a, &b = it->second.b;
    const int o = detail::orient(a, b, p);
    if (o == 0 && detail::within_box(a, b, p)) return true;
    // Half-open rule on y (exact comparisons): a vertex at the ray's height is counted once.
    if ((a[1] > p[1]) != (b[1] > p[1]) && ((b[1] > a[1]) ? o > 0 : o < 0)) in = !in;
  }
  return in;
}

}  // namespace shoremesh
