#include "shoremesh/mesh_boundary.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <map>
#include <unordered_map>

namespace shoremesh {

std::vector<BoundaryLoop> boundary_loops(std::span<const Point2> points, std::span<const Element<2>> elements) {
  // A directed edge (a, b) of a counter-clockwise triangle is on the boundary iff no triangle has (b, a).
  std::map<std::pair<std::uint32_t, std::uint32_t>, bool> directed;  // edge -> used by a loop already
  for (const auto& e : elements)
    for (int i = 0; i < 3; ++i) directed.emplace(std::pair{e[i], e[(i + 1) % 3]}, false);
  std::unordered_multimap<std::uint32_t, std::uint32_t> outgoing;
  for (const auto& [edge, used] : directed)
    if (!directed.count({edge.second, edge.first})) outgoing.emplace(edge.first, edge.second);

  std::vector<BoundaryLoop> loops;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> starts;
  for (const auto& [a, b] : outgoing) starts.emplace_back(a, b);
  std::sort(starts.begin(), starts.end());  // deterministic loop order
  for (const auto& [a0, b0] : starts) {
    if (directed.at({a0, b0})) continue;
    BoundaryLoop loop;
    std::uint32_t a = a0, b = b0;
    while (true) {
      directed.at({a, b}) = true;
      loop.nodes.push_back(a);
      if (b == a0) break;
      auto [lo, hi] = outgoing.equal_range(b);
      auto next = std::find_if(lo, hi, [&](const auto& kv) { return !directed.at({kv.first, kv.second}); });
      if (next == hi) break;  // cannot happen for a manifold boundary; ends the loop defensively
      a = b;
      b = next->second;
    }
    // The lowest-leftmost node is a convex corner, so the turn there is the loop's orientation.
    const std::size_t n = loop.nodes.size();
    std::size_t k = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (points[loop.nodes[i]] < points[loop.nodes[k]]) k = i;
    using P = CGAL::Exact_predicates_inexact_constructions_kernel::Point_2;
    auto at = [&](std::size_t i) { return P(points[loop.nodes[i % n]][0], points[loop.nodes[i % n]][1]); };
    const bool ccw = CGAL::orientation(at(k + n - 1), at(k), at(k + 1)) == CGAL::LEFT_TURN;
    loop.role = ccw ? RingRole::Shore : RingRole::Island;
    loops.push_back(std::move(loop));
  }
  // Shores first (writers such as ADCIRC list the external boundaries before the islands).
  std::stable_sort(loops.begin(), loops.end(), [](const auto& x, const auto& y) {
    return x.role == RingRole::Shore && y.role == RingRole::Island;
  });
  return loops;
}

std::vector<std::array<std::uint32_t, 3>> boundary_faces(std::span<const Element<3>> elements) {
  // Face opposite corner i of a positive tetrahedron, ordered so that its normal points away from corner i.
  static constexpr int face[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<std::uint32_t, 3>, std::array<std::uint32_t, 3>> seen;  // sorted corners -> oriented face
  for (const auto& t : elements)
    for (const auto& f : face) {
      const std::array<std::uint32_t, 3> oriented{t[f[0]], t[f[1]], t[f[2]]};
      auto key = oriented;
      std::sort(key.begin(), key.end());
      if (!seen.erase(key)) seen.emplace(key, oriented);  // a shared face is interior
    }
  std::vector<std::array<std::uint32_t, 3>> out;
  out.reserve(seen.size());
  for (const auto& [key, f] : seen) out.push_back(f);
  return out;
}

}  // namespace shoremesh
