#include "shoremesh/io/ring_check.hpp"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "exact_orient.hpp"
#include "ring_geometry.hpp"

namespace shoremesh::io {

using detail::adjacent_edges_overlap;
using detail::consecutive_edges;
using detail::crossing;
using detail::segments_meet;
using detail::within_box;

namespace {

struct Edge {
  std::size_t ring, index;  // edge index -> index + 1 (mod n)
  Point2 a, b;
  double xmin, xmax, ymin, ymax;
};

}  // namespace

std::string RingDefect::describe() const {
  auto edge = [](std::size_t r, std::size_t v) {
    return "ring " + std::to_string(r + 1) + " edge " + std::to_string(v + 1) + "-" + std::to_string(v + 2);
  };
  switch (kind) {
    case Kind::TooFewPoints: return "ring " + std::to_string(ring_a + 1) + " has fewer than three points";
    case Kind::RepeatedVertex:
      return "ring " + std::to_string(ring_a + 1) + " repeats vertex " + std::to_string(vertex_a + 1) + " at vertex " +
             std::to_string(vertex_b + 1);
    case Kind::Intersection:
      return edge(ring_a, vertex_a) + (ring_a == ring_b ? " crosses its own " : " crosses ") + edge(ring_b, vertex_b);
  }
  return {};
}

std::optional<RingDefect> find_ring_defect(const Domain2& domain) {
  std::vector<Edge> edges;
  for (std::size_t r = 0; r < domain.rings.size(); ++r) {
    const auto& pts = domain.rings[r].points;
    if (pts.size() < 3) return RingDefect{RingDefect::Kind::TooFewPoints, r, 0, r, 0};
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::size_t j = (i + 1) % pts.size();
      if (pts[i] == pts[j]) return RingDefect{RingDefect::Kind::RepeatedVertex, r, i, r, j};
      const Point2 &a = pts[i], &b = pts[j];
      edges.push_back({r, i, a, b, std::min(a[0], b[0]), std::max(a[0], b[0]), std::min(a[1], b[1]), std::max(a[1], b[1])});
      if (adjacent_edges_overlap(a, b, pts[(j + 1) % pts.size()]))
        return RingDefect{RingDefect::Kind::Intersection, r, i, r, j};
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& e, const Edge& f) { return e.xmin < f.xmin; });
  std::vector<std::size_t> active;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Edge& e = edges[k];
    std::size_t keep = 0;
    for (std::size_t idx : active) {
      const Edge& f = edges[idx];
      if (f.xmax < e.xmin) continue;  // left behind by the sweep
      active[keep++] = idx;
      if (f.ymax < e.ymin || e.ymax < f.ymin) continue;
      // Neighbours in a ring: checked above.
      if (e.ring == f.ring && consecutive_edges(e.index, f.index, domain.rings[e.ring].points.size())) continue;
      if (segments_meet(e.a, e.b, f.a, f.b)) return crossing(f.ring, f.index, e.ring, e.index);
    }
    active.resize(keep);
    active.push_back(k);
  }
  return std::nullopt;
}

bool ring_contains(const std::vector<Point2>& ring, const Point2& p) {
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Point2 &a = ring[j], &b = ring[i];
    if (detail::orient2d_sign(a, b, p) == 0 && within_box(a, b, p)) return true;
    // Edge crosses the horizontal ray to the right of p (half-open rule on y).
    if ((a[1] > p[1]) != (b[1] > p[1])) {
      const int o = detail::orient2d_sign(a, b, p);
      if ((b[1] > a[1]) ? o > 0 : o < 0) inside = !inside;
    }
  }
  return inside;
}

void assign_roles_by_nesting(Domain2& domain) {
  const std::size_t m = domain.rings.size();
  std::vector<std::array<double, 4>> box(m);
  for (std::size_t r = 0; r < m; ++r) {
    box[r] = {1e308, 1e308, -1e308, -1e308};
    for (const auto& p : domain.rings[r].points)
      box[r] = {std::min(box[r][0], p[0]), std::min(box[r][1], p[1]), std::max(box[r][2], p[0]), std::max(box[r][3], p[1])};
  }
  for (std::size_t r = 0; r < m; ++r) {
    if (domain.rings[r].points.empty()) continue;
    const Point2 probe = domain.rings[r].points.front();
    int depth = 0;
    for (std::size_t s = 0; s < m; ++s) {
      if (s == r || domain.rings[s].points.size() < 3) continue;
      if (probe[0] < box[s][0] || probe[0] > box[s][2] || probe[1] < box[s][1] || probe[1] > box[s][3]) continue;
      if (ring_contains(domain.rings[s].points, probe)) ++depth;
    }
    domain.rings[r].role = depth % 2 == 0 ? RingRole::Shore : RingRole::Island;
  }
}

}  // namespace shoremesh::io
