#pragma once
// Validation of the rings of a water domain: every ring has at least three distinct points, no ring crosses or
// touches itself or another ring. Orientation tests are exact (see io/src/input/exact_orient.hpp), so a
// reported intersection is a real one and none is missed, whatever the coordinates.
//
// The search sorts the edges by their x-interval and sweeps, testing only edges whose boxes overlap: O(n log n
// + k) for n edges and k overlapping box pairs (a few per edge for shorelines).
#include <cstddef>
#include <optional>
#include <string>

#include "shoremesh/domain.hpp"

namespace shoremesh::io {

struct RingDefect {
  enum class Kind { TooFewPoints, RepeatedVertex, Intersection };
  Kind kind = Kind::Intersection;
  std::size_t ring_a = 0, vertex_a = 0;  // edge vertex_a -> vertex_a + 1 of ring_a (or the offending vertex)
  std::size_t ring_b = 0, vertex_b = 0;  // the other edge (Intersection) or the repeated vertex
  std::string describe() const;          // "ring 2 edge 5-6 crosses ring 2 edge 17-18"
};

// The first defect found, or nothing when the rings are valid.
std::optional<RingDefect> find_ring_defect(const Domain2& domain);

// The check after one vertex moved, went or came, which reads only the edges near the new ones:
// RingEdgeIndex (ring_edge_index.hpp).

// Sets each ring's role from its nesting depth (the number of other rings containing it): even -> Shore,
// odd -> Island, as the even-odd rule implies. For rings that neither cross nor touch (check first).
void assign_roles_by_nesting(Domain2& domain);

// Point-in-ring test with exact orientations (crossing number); points on the boundary count as inside.
bool ring_contains(const std::vector<Point2>& ring, const Point2& p);

}  // namespace shoremesh::io
