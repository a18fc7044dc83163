// The quadtree is canonical: after any sequence of input adds and removes it equals a fresh build.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "shoremesh/engine/quadtree.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/error.hpp"

namespace shoremesh::engine {
namespace {

template <int D>
Quadtree<D> fresh(const std::vector<Point<D>>& positions, const std::vector<VertexId>& live) {
  std::vector<Point<D>> pts;
  for (VertexId v : live) pts.push_back(positions[v]);
  Quadtree<D> t;
  t.build(pts, live);
  return t;
}

template <int D>
void random_edits_match_fresh_build(std::uint64_t seed) {
  auto positions = families::uniform<D>(400, seed);
  // Clustered points too, so that the tree gets deep and balance ripples.
  std::mt19937_64 rng(seed + 1);
  std::normal_distribution<double> g(0.0, 1e-4);
  for (int i = 0; i < 100; ++i) {
    Point<D> p;
    for (int k = 0; k < D; ++k) p[k] = std::clamp(0.3 + g(rng), 0.0, 1.0);
    positions.push_back(p);
  }
  std::vector<VertexId> live, dead;
  for (VertexId v = 0; v < positions.size(); ++v) (v % 2 ? live : dead).push_back(v);
  Quadtree<D> tree = fresh<D>(positions, live);
  tree.check_valid(positions);
  for (int step = 0; step < 300; ++step) {
    const bool add = dead.size() > 0 && (live.size() < 2 || rng() % 2);
    if (add) {
      std::size_t k = rng() % dead.size();
      VertexId v = dead[k];
      dead.erase(dead.begin() + long(k));
      auto change = tree.add_input(v, positions);
      for (NodeId n : change.new_leaves) ASSERT_TRUE(tree.node(n).is_leaf());
      live.push_back(v);
    } else {
      std::size_t k = rng() % live.size();
      VertexId v = live[k];
      live.erase(live.begin() + long(k));
      auto change = tree.remove_input(v, positions);
      for (NodeId n : change.new_leaves) ASSERT_TRUE(tree.node(n).is_leaf());
      dead.push_back(v);
    }
    ASSERT_NO_THROW(tree.check_valid(positions)) << "step " << step;
    ASSERT_EQ(tree.leaf_cells(), fresh<D>(positions, live).leaf_cells()) << "step " << step;
  }
}

TEST(Quadtree, RandomEditsEqualFreshBuild2D) { random_edits_match_fresh_build<2>(7); }
TEST(Quadtree, RandomEditsEqualFreshBuild3D) { random_edits_match_fresh_build<3>(11); }

TEST(Quadtree, LeafSizeApproximatesNearestNeighbour) {
  auto pts = families::uniform<2>(2000, 3);
  std::vector<VertexId> ids(pts.size());
  for (VertexId i = 0; i < ids.size(); ++i) ids[i] = i;
  Quadtree<2> t;
  t.build(pts, ids);
  t.check_valid(pts);
  for (VertexId v = 0; v < pts.size(); ++v) {
    double nn = 1e9;
    for (VertexId u = 0; u < pts.size(); ++u)
      if (u != v) nn = std::min(nn, std::hypot(pts[u][0] - pts[v][0], pts[u][1] - pts[v][1]));
    const NodeId leaf = t.locate(pts[v]);
    const double h = t.side(leaf);
    EXPECT_LT(t.approximate_nn(leaf), nn);  // h/4 < NN <= 3 sqrt(2) h
    EXPECT_GE(3 * std::sqrt(2.0) * h, nn);
  }
}

TEST(Quadtree, TooClosePointsAreRefused) {
  std::vector<Point<2>> pts{{0.5, 0.5}, {0.5, 0.5 + 1e-14}};
  std::vector<VertexId> ids{0, 1};
  Quadtree<2> t;
  EXPECT_THROW(t.build(pts, ids), InputError);
}

}  // namespace
}  // namespace shoremesh::engine
