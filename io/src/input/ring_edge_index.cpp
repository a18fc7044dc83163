#include "shoremesh/io/ring_edge_index.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <utility>
#include <vector>

#include "ring_geometry.hpp"

namespace shoremesh::io {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {

using BoxCorner = bg::model::point<double, 2, bg::cs::cartesian>;
using Box = bg::model::box<BoxCorner>;

struct IndexedEdge {
  std::size_t ring = 0;
  Point2 a{}, b{};
  bool operator==(const IndexedEdge&) const = default;
};
using Entry = std::pair<Box, IndexedEdge>;

// The closed box of segment ab: copies of the coordinates, so the tree's box tests are exact and miss
// no edge that segments_meet would find.
Box box_of(const Point2& a, const Point2& b) {
  return {BoxCorner(std::min(a[0], b[0]), std::min(a[1], b[1])), BoxCorner(std::max(a[0], b[0]), std::max(a[1], b[1]))};
}

Entry entry(std::size_t ring, const Point2& a, const Point2& b) { return {box_of(a, b), IndexedEdge{ring, a, b}}; }

// The index in `ring` of the edge a -> b (the error path only: a linear scan).
std::size_t edge_index(const std::vector<Point2>& ring, const Point2& a, const Point2& b) {
  for (std::size_t i = 0; i < ring.size(); ++i)
    if (ring[i] == a && ring[(i + 1) % ring.size()] == b) return i;
  throw std::logic_error("ring edge index: an indexed edge is not in the rings");
}

}  // namespace

struct RingEdgeIndex::Tree {
  bgi::rtree<Entry, bgi::quadratic<16>> rtree;
};

RingEdgeIndex::RingEdgeIndex(const Domain2& domain) : tree_(std::make_unique<Tree>()) {
  std::vector<Entry> entries;
  for (std::size_t r = 0; r < domain.rings.size(); ++r) {
    const auto& pts = domain.rings[r].points;
    for (std::size_t i = 0; i < pts.size(); ++i) entries.push_back(entry(r, pts[i], pts[(i + 1) % pts.size()]));
  }
  tree_->rtree = decltype(tree_->rtree)(entries.begin(), entries.end());  // packed: a bulk load
}

RingEdgeIndex::~RingEdgeIndex() = default;
RingEdgeIndex::RingEdgeIndex(RingEdgeIndex&&) noexcept = default;
RingEdgeIndex& RingEdgeIndex::operator=(RingEdgeIndex&&) noexcept = default;

std::size_t RingEdgeIndex::size() const { return tree_->rtree.size(); }

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
  std::vector<Entry> near;
  for (const std::size_t e : {before, vertex}) {
    const Point2 &a = pts[e], &b = pts[(e + 1) % n];
    const Point2 &prev = pts[(e + n - 1) % n], &next = pts[(e + 2) % n];
    near.clear();
    tree_->rtree.query(bgi::intersects(box_of(a, b)), std::back_inserter(near));
    std::optional<std::pair<std::size_t, std::size_t>> first;
    for (const auto& [box, f] : near) {
      if (taken_away(f)) continue;
      if (f.ring == ring && ((f.a == a && f.b == b) || (f.a == prev && f.b == a) || (f.a == b && f.b == next)))
        continue;  // itself, its neighbours
      if (!detail::segments_meet(a, b, f.a, f.b)) continue;
      const std::pair<std::size_t, std::size_t> at{f.ring, edge_index(after.rings.at(f.ring).points, f.a, f.b)};
      if (!first || at < *first) first = at;
    }
    if (first) return detail::crossing(ring, e, first->first, first->second);
  }
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

}  // namespace shoremesh::io
