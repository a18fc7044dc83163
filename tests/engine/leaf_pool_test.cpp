// The quadtree's leaves keep their vertices in one pool of blocks. Through random input adds and
// removes (splits, merges) and Steiner inserts and erases (arrays growing and shrinking), every pool
// slot lies in exactly one block (a leaf's or a free one; check_valid), every leaf holds exactly the
// live vertices inside its cell, and the tree equals a fresh build. Repacking (rename_vertices) leaves
// no free block.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>

#include "shoremesh/engine/quadtree.hpp"
#include "shoremesh/families.hpp"

namespace shoremesh::engine {
namespace {

template <int D>
struct Model {
  std::vector<Point<D>> positions;
  std::vector<std::uint32_t> tag;
  std::vector<bool> is_input;
  std::vector<VertexId> live_inputs, dead_inputs, live_steiner, dead_steiner;
};

template <int D>
Quadtree<D> fresh(const Model<D>& m) {
  std::vector<Point<D>> pts;
  for (VertexId v : m.live_inputs) pts.push_back(m.positions[v]);
  Quadtree<D> t;
  t.build(pts, m.live_inputs);
  return t;
}

// Every leaf's array holds exactly the live vertices in its cell, each once, with its position and tag.
// Returns the largest array.
template <int D>
std::size_t expect_leaves_hold_exactly_their_vertices(const Quadtree<D>& tree, const Model<D>& m) {
  std::size_t stored = 0, largest = 0;
  for (NodeId n = 0; n < tree.node_capacity(); ++n) {
    const auto nd = tree.node(n);
    if (nd.level < 0 || !nd.is_leaf()) continue;
    stored += nd.vertices.size();
    largest = std::max(largest, nd.vertices.size());
  }
  const std::size_t live = m.live_inputs.size() + m.live_steiner.size();
  EXPECT_EQ(stored, live);
  for (const auto* list : {&m.live_inputs, &m.live_steiner})
    for (VertexId v : *list) {
      const auto nd = tree.node(tree.locate(m.positions[v]));
      const auto copies = std::count_if(nd.vertices.begin(), nd.vertices.end(), [&](const LeafVertex<D>& e) {
        return e.id == v && e.position == m.positions[v] && e.tag == m.tag[v];
      });
      EXPECT_EQ(copies, 1) << "vertex " << v;
    }
  return largest;
}

template <int D>
void random_edits_keep_pool_and_leaves_exact(std::uint64_t seed) {
  Model<D> m;
  std::mt19937_64 rng(seed);
  // Inputs: uniform and a tight cluster (deep tree, merges rippling). Steiner points: mostly in a blob
  // that the tree does not refine for, so a few leaves grow large arrays and shrink them again.
  m.positions = families::uniform<D>(160, seed);
  std::normal_distribution<double> tight(0.0, 1e-4), wide(0.0, 0.02);
  auto around = [&](double centre, auto& g) {
    Point<D> p;
    for (int k = 0; k < D; ++k) p[k] = std::clamp(centre + g(rng), 0.0, 1.0);
    return p;
  };
  for (int i = 0; i < 40; ++i) m.positions.push_back(around(0.3, tight));
  const std::size_t inputs = m.positions.size();
  for (int i = 0; i < 300; ++i) m.positions.push_back(around(0.7, wide));
  for (const auto& p : families::uniform<D>(100, seed + 1)) m.positions.push_back(p);
  m.tag.resize(m.positions.size());
  m.is_input.resize(m.positions.size());
  for (VertexId v = 0; v < m.positions.size(); ++v) {
    m.is_input[v] = v < inputs;
    m.tag[v] = v < inputs ? 0 : 1000 + v;
    (v < inputs ? (v % 2 ? m.live_inputs : m.dead_inputs) : m.dead_steiner).push_back(v);
  }
  Quadtree<D> tree = fresh(m);
  std::size_t largest = 0;
  auto take = [&](std::vector<VertexId>& from) {
    const std::size_t k = rng() % from.size();
    const VertexId v = from[k];
    from.erase(from.begin() + long(k));
    return v;
  };
  for (int i = 0; i < 150; ++i) {
    const VertexId v = take(m.dead_steiner);
    tree.insert_vertex(v, m.positions[v], m.tag[v]);
    m.live_steiner.push_back(v);
  }
  for (int step = 0; step < 500; ++step) {
    const auto kind = rng() % 8;
    if (kind < 2 && !m.dead_inputs.empty()) {
      const VertexId v = take(m.dead_inputs);
      tree.add_input(v, m.positions);
      m.live_inputs.push_back(v);
    } else if (kind < 4 && m.live_inputs.size() > 2) {
      const VertexId v = take(m.live_inputs);
      tree.remove_input(v, m.positions);
      m.dead_inputs.push_back(v);
    } else if (kind < 6 + (step < 250) && !m.dead_steiner.empty()) {
      const VertexId v = take(m.dead_steiner);
      tree.insert_vertex(v, m.positions[v], m.tag[v]);
      m.live_steiner.push_back(v);
    } else if (!m.live_steiner.empty()) {
      const VertexId v = take(m.live_steiner);
      tree.erase_vertex(v, tree.locate(m.positions[v]));
      m.dead_steiner.push_back(v);
    }
    ASSERT_NO_THROW(tree.check_valid(m.positions)) << "step " << step;
    ASSERT_EQ(tree.leaf_cells(), fresh(m).leaf_cells()) << "step " << step;
    largest = std::max(largest, expect_leaves_hold_exactly_their_vertices(tree, m));
    ASSERT_FALSE(testing::Test::HasFailure()) << "step " << step;
    if (step % 100 == 99) {
      // Renumber the vertices (reversed) and repack the pool: the blocks then fill it with no gap, each
      // at most twice its array.
      std::vector<VertexId> new_id(m.positions.size());
      for (VertexId v = 0; v < new_id.size(); ++v) new_id[v] = VertexId(new_id.size() - 1 - v);
      tree.rename_vertices(new_id);
      Model<D> renamed = m;
      for (VertexId v = 0; v < new_id.size(); ++v) {
        renamed.positions[new_id[v]] = m.positions[v];
        renamed.tag[new_id[v]] = m.tag[v];
        renamed.is_input[new_id[v]] = m.is_input[v];
      }
      for (auto* list : {&renamed.live_inputs, &renamed.dead_inputs, &renamed.live_steiner, &renamed.dead_steiner})
        for (VertexId& v : *list) v = new_id[v];
      m = std::move(renamed);
      ASSERT_NO_THROW(tree.check_valid(m.positions)) << "after repacking at step " << step;
      expect_leaves_hold_exactly_their_vertices(tree, m);
      const std::size_t live = m.live_inputs.size() + m.live_steiner.size();
      EXPECT_EQ(tree.pool_size(), tree.pool_slots_used());
      EXPECT_LT(tree.pool_size(), 2 * live);
    }
  }
  // The edits did exercise arrays well beyond one vertex (growth across several size classes).
  EXPECT_GE(largest, 16u);
}

TEST(LeafPool, EverySlotInOneBlockAndLeavesHoldExactlyTheirVertices2D) { random_edits_keep_pool_and_leaves_exact<2>(5); }
TEST(LeafPool, EverySlotInOneBlockAndLeavesHoldExactlyTheirVertices3D) { random_edits_keep_pool_and_leaves_exact<3>(9); }

}  // namespace
}  // namespace shoremesh::engine
