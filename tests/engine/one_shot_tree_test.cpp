// A one-shot tree (Quadtree::build with editable false: no per-node input counts, no spare room) is the
// same tree as an editable build, before and after Steiner vertices come and go; it refuses input edits.
// The cell map at any table size (a build reserves what it needs, not a power of two) against std::map.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "shoremesh/engine/cell_map.hpp"
#include "shoremesh/engine/quadtree.hpp"

namespace shoremesh::engine {
namespace {

template <int D>
std::vector<Point<D>> clustered(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1e-3);
  std::vector<Point<D>> pts;
  Point<D> centre{};
  for (std::size_t k = 0; k < n; ++k) {
    if (k % 50 == 0)
      for (int i = 0; i < D; ++i) centre[i] = 0.1 + 0.8 * u(rng);
    Point<D> p;
    for (int i = 0; i < D; ++i) p[i] = std::clamp(k % 3 == 0 ? u(rng) : centre[i] + g(rng), 0.0, 1.0);
    pts.push_back(p);
  }
  return pts;
}

template <int D>
void expect_same_nodes(const Quadtree<D>& a, const Quadtree<D>& b) {
  ASSERT_EQ(a.node_capacity(), b.node_capacity());
  ASSERT_EQ(a.leaf_cells(), b.leaf_cells());
  for (NodeId n = 0; n < a.node_capacity(); ++n) {
    const auto x = a.node(n), y = b.node(n);
    ASSERT_EQ(std::tie(x.parent, x.first_child, x.level, x.coords), std::tie(y.parent, y.first_child, y.level, y.coords)) << n;
    if (!x.is_leaf()) continue;
    ASSERT_EQ(x.input_vertex, y.input_vertex) << n;
    ASSERT_EQ(x.vertices.size(), y.vertices.size()) << n;
    for (std::size_t k = 0; k < x.vertices.size(); ++k) ASSERT_EQ(x.vertices[k].id, y.vertices[k].id) << n;
  }
}

template <int D>
void one_shot_equals_editable(std::size_t n, std::uint64_t seed) {
  std::vector<Point<D>> positions = clustered<D>(n, seed);
  std::vector<VertexId> ids(n);
  std::iota(ids.begin(), ids.end(), VertexId(0));
  Quadtree<D> editable, one_shot;
  editable.build(positions, ids);
  one_shot.build(positions, ids, false);
  ASSERT_NO_THROW(one_shot.check_valid(positions));
  expect_same_nodes(editable, one_shot);
  EXPECT_LT(one_shot.memory_bytes(), editable.memory_bytes());

  // Steiner vertices (tags above 0) inserted, some erased again: the same leaves hold the same ones.
  std::mt19937_64 rng(seed + 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::pair<VertexId, NodeId>> steiner;
  for (std::size_t k = 0; k < 2 * n; ++k) {
    Point<D> p;
    for (int i = 0; i < D; ++i) p[i] = u(rng);
    const auto id = VertexId(positions.size());
    positions.push_back(p);
    const NodeId leaf = editable.insert_vertex(id, p, 1 + k);
    ASSERT_EQ(one_shot.insert_vertex(id, p, 1 + k), leaf);
    steiner.emplace_back(id, leaf);
  }
  for (std::size_t k = 0; k < steiner.size(); k += 3) {
    editable.erase_vertex(steiner[k].first, steiner[k].second);
    one_shot.erase_vertex(steiner[k].first, steiner[k].second);
  }
  ASSERT_NO_THROW(editable.check_valid(positions));
  ASSERT_NO_THROW(one_shot.check_valid(positions));
  expect_same_nodes(editable, one_shot);
  EXPECT_THROW(one_shot.add_input(VertexId(positions.size() - 1), positions), std::logic_error);
}

TEST(OneShotTree, SameTreeAsEditable2D) { one_shot_equals_editable<2>(3000, 11); }
TEST(OneShotTree, SameTreeAsEditable3D) { one_shot_equals_editable<3>(1500, 12); }

// Tables reserved to sizes that are not powers of two, then grown past them by inserts and shrunk by
// erases (backward shifts across the wrap from the last slot to the first).
TEST(OneShotTree, CellMapAtAnySize) {
  std::mt19937_64 rng(5);
  for (std::size_t reserved : {0u, 1u, 3u, 37u, 1000u}) {
    CellMap map;
    map.reserve(reserved, reserved / 3, reserved % 2 == 1);
    std::map<std::pair<int, std::array<std::uint64_t, 2>>, NodeId> truth;
    for (int step = 0; step < 6000; ++step) {
      const int level = int(rng() % 41);
      const std::uint64_t mask = level == 0 ? 0 : (std::uint64_t(1) << std::min(level, 6)) - 1;
      const std::array<std::uint64_t, 2> c{rng() & mask, rng() & mask};
      const auto key = std::make_pair(level, c);
      if (rng() % 3 == 0) {
        map.erase<2>(level, c);
        truth.erase(key);
      } else if (!truth.count(key)) {
        map.insert<2>(level, c, NodeId(step));
        truth[key] = NodeId(step);
      }
      if (step % 500 == 0 || step == 5999) {
        ASSERT_EQ(map.size(), truth.size());
        for (const auto& [k, node] : truth) ASSERT_EQ(map.find<2>(k.first, k.second), node) << "step " << step;
      }
      const int ql = int(rng() % 41);
      const std::uint64_t qm = ql == 0 ? 0 : (std::uint64_t(1) << std::min(ql, 6)) - 1;
      const std::array<std::uint64_t, 2> q{rng() & qm, rng() & qm};
      const auto it = truth.find({ql, q});
      ASSERT_EQ(map.find<2>(ql, q), it == truth.end() ? kNoNode : it->second) << "step " << step;
    }
  }
}

}  // namespace
}  // namespace shoremesh::engine
