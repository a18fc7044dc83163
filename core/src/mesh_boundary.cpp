#include "shoremesh/mesh_boundary.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace shoremesh {

std::vector<BoundaryLoop> boundary_loops(std::span<const Point2> points, std::span<const Element<2>> elements) {
  // A directed edge (a, b) of a counter-clockwise triangle is on the boundary iff no triangle has (b, a).
  // The directed edges bucketed by their first node (a counting sort: a mesh of a million triangles has
  // three million of them), so that (b, a) is looked for among the few edges leaving b.
  using Edge = std::pair<std::uint32_t, std::uint32_t>;
  std::uint32_t nodes = 0;
  for (const auto& e : elements)
    for (int i = 0; i < 3; ++i) nodes = std::max(nodes, e[i] + 1);
  std::vector<std::uint32_t> first(std::size_t(nodes) + 1, 0);  // edges leaving node a: [first[a], first[a + 1])
  for (const auto& e : elements)
    for (int i = 0; i < 3; ++i) ++first[e[i] + 1];
  for (std::size_t a = 0; a < nodes; ++a) first[a + 1] += first[a];
  std::vector<std::uint32_t> target(first.back());
  {
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (const auto& e : elements)
      for (int i = 0; i < 3; ++i) target[next[e[i]]++] = e[(i + 1) % 3];
  }
  std::vector<Edge> outgoing;  // the boundary edges, sorted: those leaving a node are a range
  for (std::uint32_t a = 0; a < nodes; ++a) {
    const std::size_t begin = outgoing.size();
    for (std::uint32_t k = first[a]; k < first[a + 1]; ++k) {
      const std::uint32_t b = target[k];
      const auto from_b = target.begin() + first[b], end_b = target.begin() + first[b + 1];
      if (std::find(from_b, end_b, a) == end_b) outgoing.emplace_back(a, b);
    }
    std::sort(outgoing.begin() + static_cast<std::ptrdiff_t>(begin), outgoing.end());
  }
  std::vector<bool> used(outgoing.size(), false);
  auto index_of = [&](const Edge& e) { return std::size_t(std::lower_bound(outgoing.begin(), outgoing.end(), e) - outgoing.begin()); };

  std::vector<BoundaryLoop> loops;
  for (std::size_t start = 0; start < outgoing.size(); ++start) {  // in sorted order: deterministic loops
    if (used[start]) continue;
    BoundaryLoop loop;
    const std::uint32_t a0 = outgoing[start].first;
    std::size_t edge = start;
    while (true) {
      used[edge] = true;
      loop.nodes.push_back(outgoing[edge].first);
      const std::uint32_t b = outgoing[edge].second;
      if (b == a0) break;
      // The first unused edge leaving b.
      std::size_t next = index_of({b, 0});
      while (next < outgoing.size() && outgoing[next].first == b && used[next]) ++next;
      if (next == outgoing.size() || outgoing[next].first != b) break;  // cannot happen for a closed boundary
      edge = next;
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
  using Face = std::array<std::uint32_t, 3>;
  std::vector<std::pair<Face, Face>> faces;  // sorted corners, oriented face
  faces.reserve(4 * elements.size());
  for (const auto& t : elements)
    for (const auto& f : face) {
      const Face oriented{t[f[0]], t[f[1]], t[f[2]]};
      Face key = oriented;
      std::sort(key.begin(), key.end());
      faces.emplace_back(key, oriented);
    }
  std::sort(faces.begin(), faces.end());
  // A face two tetrahedra share is interior; the others, in the order of their sorted corners.
  std::vector<Face> out;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].first == faces[i].first) ++j;
    if (j - i == 1) out.push_back(faces[i].second);
    i = j;
  }
  return out;
}

}  // namespace shoremesh
