#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "ring_geometry.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/ring_edge_index.hpp"

namespace shoremesh {

std::string RingDefect::describe() const {
  auto edge = [](std::size_t r, std::size_t v) {
    return "ring " + std::to_string(r + 1) + " edge " + std::to_string(v + 1) + "-" + std::to_string(v + 2);
  };
  switch (kind) {
    case Kind::TooFewPoints: return "ring " + std::to_string(ring_a + 1) + " has fewer than three points";
    case Kind::RepeatedVertex:
      return "ring " + std::to_string(ring_a + 1) + " repeats vertex " + std::to_string(vertex_a + 1) + " at vertex " +
             std::to_string(vertex_b + 1);
    case Kind::LineOnLand:
      return "line " + std::to_string(ring_a + 1) + " lies on land (outside the water the rings bound), where no element is";
    case Kind::Intersection:
      return edge(ring_a, vertex_a) + (ring_a == ring_b ? " crosses its own " : " crosses ") + edge(ring_b, vertex_b);
  }
  return {};
}

std::optional<RingDefect> find_ring_defect(const Domain2& domain, bool shared_vertices) {
  for (std::size_t r = 0; r < domain.rings.size(); ++r)
    if (auto d = detail::local_ring_defect(domain.rings[r], r)) return d;
  const RingEdgeIndex index(domain);
  if (auto d = index.first_crossing(domain, shared_vertices)) return d;
  const bool water = std::any_of(domain.rings.begin(), domain.rings.end(),
                                 [](const Ring& r) { return r.closed() && !r.points.empty(); });
  for (std::size_t r = 0; water && r < domain.rings.size(); ++r)
    if (!domain.rings[r].closed() && !index.inside(index.line_probe(domain.rings[r])))
      return RingDefect{RingDefect::Kind::LineOnLand, r, 0, r, 0};
  return std::nullopt;
}

bool ring_contains(const std::vector<Point2>& ring, const Point2& p) {
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Point2 &a = ring[j], &b = ring[i];
    const int o = detail::orient(a, b, p);
    if (o == 0 && detail::within_box(a, b, p)) return true;
    // Edge crosses the horizontal ray to the right of p (half-open rule on y).
    if ((a[1] > p[1]) != (b[1] > p[1]))
      if ((b[1] > a[1]) ? o > 0 : o < 0) inside = !inside;
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
    if (domain.rings[r].points.empty() || !domain.rings[r].closed()) continue;
    const Point2 probe = domain.rings[r].points.front();
    int depth = 0;
    for (std::size_t s = 0; s < m; ++s) {
      if (s == r || domain.rings[s].points.size() < 3 || !domain.rings[s].closed()) continue;
      if (probe[0] < box[s][0] || probe[0] > box[s][2] || probe[1] < box[s][1] || probe[1] > box[s][3]) continue;
      if (ring_contains(domain.rings[s].points, probe)) ++depth;
    }
    domain.rings[r].role = depth % 2 == 0 ? RingRole::Shore : RingRole::Island;
  }
}

}  // namespace shoremesh
