#pragma once
// Internal: the segment tests of the ring checks (the whole check, and the index an edit session keeps),
// exact through the engine's orient2d.
#include <algorithm>
#include <cstddef>
#include <utility>

#include "shoremesh/domain.hpp"
#include "shoremesh/engine/predicates.hpp"

namespace shoremesh::detail {

inline int orient(const Point2& a, const Point2& b, const Point2& c) {
  thread_local engine::PredicateCounters counters;
  return engine::orient2d(counters, a, b, c);
}

// Collinear point p lies within the closed box of segment ab (exact: comparisons only).
inline bool within_box(const Point2& a, const Point2& b, const Point2& p) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= p[1] &&
         p[1] <= std::max(a[1], b[1]);
}

// Closed segments ab and cd share at least one point (exact).
inline bool segments_meet(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d);
  const int o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 == 0 && within_box(a, b, c)) return true;
  if (o2 == 0 && within_box(a, b, d)) return true;
  if (o3 == 0 && within_box(c, d, a)) return true;
  if (o4 == 0 && within_box(c, d, b)) return true;
  return false;
}

// Consecutive edges a->b and b->c meet only at b unless c folds back along a->b (collinear, same side of b).
inline bool adjacent_edges_overlap(const Point2& a, const Point2& b, const Point2& c) {
  if (orient(a, b, c) != 0) return false;
  auto side = [](double u, double v) { return (u > v) - (u < v); };
  const int sa = a[0] != b[0] ? side(a[0], b[0]) : side(a[1], b[1]);
  const int sc = a[0] != b[0] ? side(c[0], b[0]) : side(c[1], b[1]);
  return sa == sc && sa != 0;
}

// Edges ab and cd of the rings conflict: they share a point other than a common end. Rings and lines may
// share a vertex (where they touch, a jetty's end on the shore, a .poly vertex where segments meet): edges
// with one common end meet only there unless they fold onto one another; the same edge twice conflicts.
inline bool edges_conflict(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  const bool ac = a == c, ad = a == d, bc = b == c, bd = b == d;
  if ((ac && bd) || (ad && bc)) return true;
  if (ac) return adjacent_edges_overlap(b, a, d);
  if (ad) return adjacent_edges_overlap(b, a, c);
  if (bc) return adjacent_edges_overlap(a, b, d);
  if (bd) return adjacent_edges_overlap(a, b, c);
  return segments_meet(a, b, c, d);
}

// Edges i and j of a ring of n vertices follow one another (they share a vertex by construction).
inline bool consecutive_edges(std::size_t i, std::size_t j, std::size_t n) { return (i + 1) % n == j || (j + 1) % n == i; }

// Edge vertex_a of ring_a meets edge vertex_b of ring_b: the defect, the pair in (ring, edge) order.
inline RingDefect crossing(std::size_t ring_a, std::size_t vertex_a, std::size_t ring_b, std::size_t vertex_b) {
  if (std::make_pair(ring_b, vertex_b) < std::make_pair(ring_a, vertex_a)) {
    std::swap(ring_a, ring_b);
    std::swap(vertex_a, vertex_b);
  }
  return RingDefect{RingDefect::Kind::Intersection, ring_a, vertex_a, ring_b, vertex_b};
}

// The local defects of ring r (fewer than three points, or two for a line; a repeated vertex; a fold at
// a vertex), the first in vertex order.
inline std::optional<RingDefect> local_ring_defect(const Ring& ring, std::size_t r) {
  const auto& pts = ring.points;
  if (pts.size() < (ring.closed() ? 3u : 2u)) return RingDefect{RingDefect::Kind::TooFewPoints, r, 0, r, 0};
  const std::size_t segments = ring.segment_count();
  for (std::size_t i = 0; i < segments; ++i) {
    const std::size_t j = (i + 1) % pts.size();
    if (pts[i] == pts[j]) return RingDefect{RingDefect::Kind::RepeatedVertex, r, i, r, j};
    if ((ring.closed() || i + 1 < segments) && adjacent_edges_overlap(pts[i], pts[j], pts[(j + 1) % pts.size()]))
      return RingDefect{RingDefect::Kind::Intersection, r, i, r, j};
  }
  return std::nullopt;
}

}  // namespace shoremesh::detail
