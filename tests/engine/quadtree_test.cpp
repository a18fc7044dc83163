// The quadtree is canonical: after any sequence of input adds and removes it equals a fresh build.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

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

// With `steiner`, vertices of nonzero tags share the leaves (as the engine's Steiner vertices do): a leaf
// tells its input by tag 0, so they must count for nothing in the crowding rule.
template <int D>
void random_edits_match_fresh_build(std::uint64_t seed, bool steiner = false) {
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
  if (steiner) {
    // Near the clusters and elsewhere; ids after the inputs', positions kept in the same array.
    const auto extra = families::uniform<D>(300, seed + 2);
    for (std::size_t k = 0; k < extra.size(); ++k) {
      Point<D> p = extra[k];
      if (k % 2 == 0)
        for (int i = 0; i < D; ++i) p[i] = std::clamp(0.3 + 1e-3 * (p[i] - 0.5), 0.0, 1.0);
      const auto id = VertexId(positions.size());
      positions.push_back(p);
      tree.insert_vertex(id, p, 1 + std::uint32_t(k));
    }
  }
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
TEST(Quadtree, SteinerVerticesAreNoInputs2D) { random_edits_match_fresh_build<2>(13, true); }
TEST(Quadtree, SteinerVerticesAreNoInputs3D) { random_edits_match_fresh_build<3>(17, true); }

TEST(Quadtree, TagZeroIsRefusedForASteinerVertex) {
  const std::vector<Point<2>> pts{{0.25, 0.25}, {0.75, 0.75}};
  const std::vector<VertexId> ids{0, 1};
  Quadtree<2> t;
  t.build(pts, ids);
  EXPECT_THROW(t.insert_vertex(2, {0.5, 0.5}, 0), std::logic_error);
}

// An operation's count of reads has 4 bits (Op::reads_count): the nodes covering any box number at most
// 2^D. A box a hair wider than a cell, from just below one cell boundary to the next but one, meets
// three cells per axis at the level whose cells are that wide (log2 of its width rounds to it): the
// cover must come from the level above.
template <int D>
void covering_nodes_are_at_most_two_per_axis() {
  // Inputs on a grid near the origin, spacing 1/32: nodes of level 4 and finer exist over [0, 3/4]^D.
  std::vector<Point<D>> pts;
  std::vector<VertexId> ids;
  std::array<int, D> at{};
  for (;;) {
    Point<D> p;
    for (int i = 0; i < D; ++i) p[i] = (at[i] + 0.5) / 32;
    ids.push_back(VertexId(pts.size()));
    pts.push_back(p);
    int i = 0;
    while (i < D && ++at[i] == 24) at[i++] = 0;
    if (i == D) break;
  }
  Quadtree<D> t;
  t.build(pts, ids);
  std::vector<NodeId> out;
  std::size_t three_wide = 0;
  for (int level = 2; level <= 4; ++level) {
    const double s = std::ldexp(1.0, -level);
    for (int m = 1; m <= 4; ++m) {
      Point<D> lo, hi;
      for (int i = 0; i < D; ++i) {
        lo[i] = s * (1 - m * 0x1p-53);  // in cell 0, below the boundary at s
        hi[i] = 2 * s;                  // on the boundary of cell 2
      }
      const double width = hi[0] - lo[0];
      if (int(std::floor(-std::log2(width))) == level) ++three_wide;
      const std::uint32_t code = t.covering_nodes(lo, lo, hi, out);
      ASSERT_LE(out.size(), std::size_t(1) << D) << "level " << level << " m " << m;
      // The code finds the same nodes again.
      std::vector<NodeId> again;
      t.cover_nodes(lo, code, again);
      ASSERT_EQ(again, out);
      // They cover the box: its corners lie in them.
      for (int corner = 0; corner < (1 << D); ++corner) {
        Point<D> c;
        for (int i = 0; i < D; ++i) c[i] = (corner >> i & 1) ? hi[i] : lo[i];
        const NodeId leaf = t.locate(c);
        bool covered = false;
        for (NodeId n = leaf; n != kNoNode; n = t.parent(n)) covered = covered || std::find(out.begin(), out.end(), n) != out.end();
        ASSERT_TRUE(covered) << "corner " << corner;
      }
    }
  }
  EXPECT_GT(three_wide, 0u);  // the rounding this guards against happens here
}

TEST(Quadtree, CoveringNodesAreAtMostTwoPerAxis2D) { covering_nodes_are_at_most_two_per_axis<2>(); }
TEST(Quadtree, CoveringNodesAreAtMostTwoPerAxis3D) { covering_nodes_are_at_most_two_per_axis<3>(); }

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
