// Quadtree::build (crowding, then balance per level, then the nodes in one descent) against a tree made
// from the empty one by add_input, one point at a time (crowding per split, balance_around per split):
// two independent ways to the same canonical tree.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "shoremesh/engine/quadtree.hpp"
#include "shoremesh/families.hpp"

namespace shoremesh::engine {
namespace {

template <int D>
void expect_build_equals_one_by_one(const std::vector<Point<D>>& positions, std::uint64_t seed) {
  // The build's inputs in a shuffled order with their ids: the tree must not depend on it.
  std::vector<VertexId> ids(positions.size());
  std::iota(ids.begin(), ids.end(), VertexId(0));
  std::mt19937_64 rng(seed);
  std::shuffle(ids.begin(), ids.end(), rng);
  std::vector<Point<D>> inputs;
  for (VertexId v : ids) inputs.push_back(positions[v]);
  Quadtree<D> built;
  built.build(inputs, ids);
  ASSERT_NO_THROW(built.check_valid(positions));

  Quadtree<D> grown;
  grown.build({}, {});
  std::shuffle(ids.begin(), ids.end(), rng);
  for (VertexId v : ids) grown.add_input(v, positions);
  ASSERT_NO_THROW(grown.check_valid(positions));

  ASSERT_EQ(built.leaf_count(), grown.leaf_count());
  ASSERT_EQ(built.leaf_cells(), grown.leaf_cells());
  for (VertexId v = 0; v < positions.size(); ++v) {
    const NodeId a = built.locate(positions[v]), b = grown.locate(positions[v]);
    ASSERT_EQ(built.node(a).input_vertex, v);
    ASSERT_EQ(grown.node(b).input_vertex, v);
    ASSERT_EQ(built.node(a).level, grown.node(b).level);
  }
  // Rebuilding the same tree object starts afresh.
  built.build(inputs, ids);
  ASSERT_EQ(built.leaf_cells(), grown.leaf_cells());
}

// A closed wiggly curve sampled unevenly, with a few islands: a shore-like input, deep where the
// samples crowd and coarse in between, so balance ripples far.
std::vector<Point<2>> shore_like(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point<2>> pts;
  double t = 0;
  while (pts.size() < n) {
    const double r = 0.3 + 0.05 * std::sin(7 * t) + 0.02 * std::sin(31 * t);
    pts.push_back({0.5 + r * std::cos(t), 0.5 + r * std::sin(t)});
    t += 2e-4 + 4e-3 * u(rng) * u(rng) * u(rng);
    if (t > 6.283) break;
  }
  for (int island = 0; island < 5; ++island) {
    const double cx = 0.4 + 0.05 * island, cy = 0.45 + 0.02 * island, r = 1e-3 * (island + 1);
    for (int k = 0; k < 12; ++k) pts.push_back({cx + r * std::cos(0.5 * k), cy + r * std::sin(0.5 * k)});
  }
  pts.push_back({0.7, 0.2});
  pts.push_back({0.7 + 3e-9, 0.2 + 1e-9});  // a deep pair far from the rest
  return pts;
}

TEST(QuadtreeBuild, UniformEqualsOneByOne2D) { expect_build_equals_one_by_one<2>(families::uniform<2>(3000, 5), 1); }
TEST(QuadtreeBuild, UniformEqualsOneByOne3D) { expect_build_equals_one_by_one<3>(families::uniform<3>(1500, 6), 2); }
TEST(QuadtreeBuild, ClustersEqualOneByOne2D) { expect_build_equals_one_by_one<2>(families::gaussian_clusters<2>(3000, 7, 8), 3); }
TEST(QuadtreeBuild, ClustersEqualOneByOne3D) { expect_build_equals_one_by_one<3>(families::gaussian_clusters<3>(1500, 5, 9), 4); }
TEST(QuadtreeBuild, ShoreLikeEqualsOneByOne) { expect_build_equals_one_by_one<2>(shore_like(2500, 10), 5); }
// A pair 1e-9 apart among sparse points: 3D cells below level 21 take the cell map's wide keys.
TEST(QuadtreeBuild, ClosePairEqualsOneByOne2D) { expect_build_equals_one_by_one<2>(families::close_pair<2>(200, 1e-9, 11), 6); }
TEST(QuadtreeBuild, ClosePairEqualsOneByOne3D) { expect_build_equals_one_by_one<3>(families::close_pair<3>(200, 1e-9, 12), 7); }
TEST(QuadtreeBuild, CornersAndEdgesEqualOneByOne) {
  // Inputs on the box's boundary and corners (coordinate 1 belongs to the last cell).
  std::vector<Point<2>> pts{{0, 0}, {1, 1}, {0, 1}, {1, 0}, {1, 1 - 1e-6}, {0.5, 1}, {1e-7, 0}, {0.25, 0.25}};
  expect_build_equals_one_by_one<2>(pts, 8);
}

TEST(QuadtreeBuild, EmptyAndSingle) {
  Quadtree<2> t;
  t.build({}, {});
  EXPECT_EQ(t.leaf_count(), 1u);
  const std::vector<Point<2>> one{{0.3, 0.6}};
  const std::vector<VertexId> id{0};
  t.build(one, id);
  EXPECT_EQ(t.leaf_count(), 1u);
  EXPECT_EQ(t.node(t.root()).input_vertex, 0u);
  EXPECT_NO_THROW(t.check_valid(one));
}

}  // namespace
}  // namespace shoremesh::engine
