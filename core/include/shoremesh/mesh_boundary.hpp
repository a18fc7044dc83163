#pragma once
// The boundary of a mesh: in 2D closed loops of mesh nodes with their role, which writers turn into Gmsh
// physical groups, ADCIRC boundary lists and Triangle boundary markers; in 3D the boundary triangles.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/mesh_element.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

// A closed loop of node indices (the last connects to the first, not repeated), water on its left:
// counter-clockwise around a body of water (RingRole::Shore), clockwise around an island (RingRole::Island).
struct BoundaryLoop {
  std::vector<std::uint32_t> nodes;
  RingRole role = RingRole::Shore;
};

// The loops formed by the element edges that only one element uses, from counter-clockwise elements. The
// role comes from the loop's orientation, decided exactly at its lowest-leftmost node. Where two loops
// touch at a node the loops are split there by taking, at each node, the first unused outgoing edge.
std::vector<BoundaryLoop> boundary_loops(std::span<const Point2> points, std::span<const Element<2>> elements);

// The faces of positively oriented tetrahedra that only one tetrahedron uses, oriented outwards.
std::vector<std::array<std::uint32_t, 3>> boundary_faces(std::span<const Element<3>> elements);

}  // namespace shoremesh
