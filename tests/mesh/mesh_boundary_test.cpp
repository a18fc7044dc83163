// The boundary of a mesh: 2D loops with their role (water on their left), split where two loops touch at
// a node; 3D faces used by one tetrahedron only, oriented outwards.
#include <gtest/gtest.h>

#include <algorithm>

#include "shoremesh/mesh_boundary.hpp"

namespace shoremesh {
namespace {

// The loop's nodes rotated to start at the smallest, so loops compare whatever node they start from.
std::vector<std::uint32_t> from_smallest(std::vector<std::uint32_t> nodes) {
  std::rotate(nodes.begin(), std::min_element(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

TEST(MeshBoundary, ASquareWithAHoleHasAShoreAndAnIsland) {
  // Outer square 0..3 (counter-clockwise), inner square 4..7, and the eight triangles between them.
  const std::vector<Point2> points = {{0, 0}, {3, 0}, {3, 3}, {0, 3}, {1, 1}, {2, 1}, {2, 2}, {1, 2}};
  const std::vector<Element<2>> ring = {{0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                        {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  const auto loops = boundary_loops(points, ring);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].role, RingRole::Shore);  // shores first
  EXPECT_EQ(from_smallest(loops[0].nodes), (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(loops[1].role, RingRole::Island);
  EXPECT_EQ(from_smallest(loops[1].nodes), (std::vector<std::uint32_t>{4, 7, 6, 5}));  // clockwise
}

TEST(MeshBoundary, TwoTrianglesTouchingAtANodeGiveTwoLoops) {
  const std::vector<Point2> points = {{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}};
  const std::vector<Element<2>> bowtie = {{0, 1, 2}, {2, 3, 4}};
  const auto loops = boundary_loops(points, bowtie);
  ASSERT_EQ(loops.size(), 2u);
  std::vector<std::vector<std::uint32_t>> got = {from_smallest(loops[0].nodes), from_smallest(loops[1].nodes)};
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, (std::vector<std::vector<std::uint32_t>>{{0, 1, 2}, {2, 3, 4}}));
  for (const auto& l : loops) EXPECT_EQ(l.role, RingRole::Shore);
}

TEST(MeshBoundary, TetrahedraFacesUsedOnceFaceOutwards) {
  // Two positive tetrahedra sharing the face (1, 2, 3): six boundary faces, the shared one not among them.
  const std::vector<Element<3>> two = {{0, 1, 2, 3}, {4, 1, 3, 2}};
  const auto faces = boundary_faces(two);
  ASSERT_EQ(faces.size(), 6u);
  for (auto f : faces) {
    std::sort(f.begin(), f.end());
    EXPECT_NE(f, (std::array<std::uint32_t, 3>{1, 2, 3}));
  }
  // One tetrahedron: its four faces, each with the opposite corner behind it.
  const auto one = boundary_faces(std::vector<Element<3>>{{0, 1, 2, 3}});
  ASSERT_EQ(one.size(), 4u);
  for (const auto& f : one) {
    const std::uint32_t opposite = 6 - f[0] - f[1] - f[2];
    // Corners (0,0,0), (1,0,0), (0,1,0), (0,0,1): the face's normal (by its order) points away from it.
    const std::array<std::array<double, 3>, 4> p = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    std::array<double, 3> u, v, w;
    for (int k = 0; k < 3; ++k) {
      u[k] = p[f[1]][k] - p[f[0]][k];
      v[k] = p[f[2]][k] - p[f[0]][k];
      w[k] = p[opposite][k] - p[f[0]][k];
    }
    const double side = w[0] * (u[1] * v[2] - u[2] * v[1]) - w[1] * (u[0] * v[2] - u[2] * v[0]) + w[2] * (u[0] * v[1] - u[1] * v[0]);
    EXPECT_LT(side, 0) << f[0] << f[1] << f[2];
  }
}

}  // namespace
}  // namespace shoremesh
