// The cell map keys shallow cells by one 64-bit word and deep ones by 128 bits: every cell of every
// level stays distinct, and a tree deep enough to need both tables stays canonical under edits.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "shoremesh/engine/cell_map.hpp"
#include "shoremesh/engine/quadtree.hpp"

namespace shoremesh::engine {
namespace {

template <int D>
void every_level_keeps_its_cells(std::uint64_t seed) {
  struct Cell {
    int level;
    std::array<std::uint64_t, D> c;
  };
  std::mt19937_64 rng(seed);
  std::vector<Cell> cells;
  for (int level = 0; level <= kMaxLevel; ++level) {
    const std::uint64_t last = (std::uint64_t(1) << level) - 1;
    for (int k = 0; k < 6; ++k) {
      Cell cell{level, {}};
      for (int i = 0; i < D; ++i) cell.c[std::size_t(i)] = k == 0 ? 0 : k == 1 ? last : rng() & last;
      cells.push_back(cell);
    }
    // The same coordinates one level finer: a different cell, whichever table either lands in.
    Cell finer = cells.back();
    if (level < kMaxLevel) {
      ++finer.level;
      cells.push_back(finer);
    }
  }
  // Drop repeats (random coordinates may repeat 0 or last at shallow levels).
  std::vector<Cell> unique;
  for (const Cell& a : cells)
    if (std::none_of(unique.begin(), unique.end(), [&](const Cell& b) { return a.level == b.level && a.c == b.c; }))
      unique.push_back(a);
  CellMap map;
  for (std::size_t k = 0; k < unique.size(); ++k) map.insert<D>(unique[k].level, unique[k].c, NodeId(k));
  ASSERT_EQ(map.size(), unique.size());
  for (std::size_t k = 0; k < unique.size(); ++k) EXPECT_EQ(map.find<D>(unique[k].level, unique[k].c), NodeId(k));
  for (std::size_t k = 0; k < unique.size(); k += 2) map.erase<D>(unique[k].level, unique[k].c);
  for (std::size_t k = 0; k < unique.size(); ++k)
    EXPECT_EQ(map.find<D>(unique[k].level, unique[k].c), k % 2 ? NodeId(k) : kNoNode) << "cell " << k;
}

TEST(CellMap, EveryLevelKeepsItsCells2D) { every_level_keeps_its_cells<2>(3); }
TEST(CellMap, EveryLevelKeepsItsCells3D) { every_level_keeps_its_cells<3>(5); }

// Points 10^-9 apart: leaves below level 31 (2D) and 21 (3D), so the tree uses both tables.
template <int D>
void deep_tree_edits_match_fresh_build(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1e-9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point<D>> positions;
  for (int i = 0; i < 60; ++i) {
    Point<D> p;
    for (int k = 0; k < D; ++k) p[k] = i < 40 ? 0.6 + g(rng) : u(rng);
    positions.push_back(p);
  }
  auto fresh = [&](const std::vector<VertexId>& live) {
    std::vector<Point<D>> pts;
    for (VertexId v : live) pts.push_back(positions[v]);
    Quadtree<D> t;
    t.build(pts, live);
    return t;
  };
  std::vector<VertexId> live, dead;
  for (VertexId v = 0; v < positions.size(); ++v) (v % 3 ? live : dead).push_back(v);
  Quadtree<D> tree = fresh(live);
  int deepest = 0;
  for (const auto& [level, c] : tree.leaf_cells()) deepest = std::max(deepest, level);
  ASSERT_GT(deepest, kCompactLevels<D>);
  for (int step = 0; step < 80; ++step) {
    const bool add = !dead.empty() && (live.size() < 2 || rng() % 2);
    auto& from = add ? dead : live;
    const std::size_t k = rng() % from.size();
    const VertexId v = from[k];
    from.erase(from.begin() + long(k));
    if (add) {
      tree.add_input(v, positions);
      live.push_back(v);
    } else {
      tree.remove_input(v, positions);
      dead.push_back(v);
    }
    ASSERT_NO_THROW(tree.check_valid(positions)) << "step " << step;
    ASSERT_EQ(tree.leaf_cells(), fresh(live).leaf_cells()) << "step " << step;
  }
}

TEST(CellMap, DeepTreeEditsEqualFreshBuild2D) { deep_tree_edits_match_fresh_build<2>(7); }
TEST(CellMap, DeepTreeEditsEqualFreshBuild3D) { deep_tree_edits_match_fresh_build<3>(11); }

}  // namespace
}  // namespace shoremesh::engine
