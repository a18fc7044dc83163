#pragma once
// The dynamic balanced 2^D-tree over the unit box (BEG94 style), canonical in its input points:
// the tree after any sequence of add/remove equals the tree a fresh build on the same input gives.
//
// The rule it is the minimal fixed point of (every required split, nothing more):
//  - crowding: a node that contains an input point splits while the 3^D block of same-size cells around
//    it (itself included) holds two or more input points. So the leaf of an input point v has side h with
//    h < NN_N(v) <= 6 sqrt(D) h: the leaf size is the approximate nearest-neighbour distance QTApxNN.
//  - balance: leaves that touch (faces, edges or corners) differ by at most one level.
// Equivalently, a node G at level K is split iff crowded(G) or some node at level K+2 touches G.
//
// Leaves ("squares") keep the vertices inside them: the input vertex (at most one) and Steiner vertices.
// Cells are half-open [i 2^-L, (i+1) 2^-L) except that coordinate 1 belongs to the last cell.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "shoremesh/engine/cell_map.hpp"
#include "shoremesh/engine/ids.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::engine {

template <int D>
class Quadtree {
 public:
  static constexpr int kChildren = 1 << D;
  using Coords = std::array<std::uint64_t, D>;

  struct Node {
    NodeId parent = kNoNode;
    NodeId first_child = kNoNode;        // the 2^D children are contiguous; kNoNode for a leaf
    std::int32_t level = 0;
    Coords coords{};                     // cell index at its level
    std::uint32_t input_count = 0;       // input points in the subtree
    VertexId input_vertex = kNoVertex;   // leaves: the input vertex inside, if any
    std::vector<VertexId> vertices;      // leaves: every vertex inside (input and Steiner)
    bool is_leaf() const { return first_child == kNoNode; }
  };

  // What an add or remove changed: leaves that stopped being leaves (split, or deleted by a merge) and
  // leaves that appeared. The dynamic algorithm marks the readers of `removed_leaves` inconsistent.
  struct Change {
    std::vector<NodeId> removed_leaves;
    std::vector<NodeId> new_leaves;
  };

  // Builds the canonical tree of `inputs` (ids[i] is the vertex id of inputs[i]). Throws
  // PointInputError when two inputs are closer than the tree's resolution (2^-40 of the box).
  void build(std::span<const Point<D>> inputs, std::span<const VertexId> ids);

  // Adds an input vertex at `position` (ids index `positions`). Returns the structural change.
  Change add_input(VertexId id, std::span<const Point<D>> positions);
  Change remove_input(VertexId id, std::span<const Point<D>> positions);

  // Steiner vertices: inserted into / removed from the leaf containing them.
  NodeId insert_vertex(VertexId id, const Point<D>& p, NodeId hint = kNoNode);
  void erase_vertex(VertexId id, NodeId leaf);

  NodeId root() const { return 0; }
  const Node& node(NodeId n) const { return nodes_[n]; }
  std::size_t node_capacity() const { return nodes_.size(); }
  double side(NodeId n) const { return std::ldexp(1.0, -nodes_[n].level); }
  Point<D> lower_corner(NodeId n) const;

  // The leaf containing p (hint: a leaf near p, to start from; optional).
  NodeId locate(const Point<D>& p, NodeId hint = kNoNode) const;

  // Calls f(leaf) once for every leaf whose closed box meets the closed box [lo, hi]. `hint`, a leaf
  // near the box, makes the search start at the right level. Returns the number of leaves visited.
  template <class F>
  std::size_t for_each_leaf_in_box(const Point<D>& lo, const Point<D>& hi, F&& f) const;

  // Every leaf as (level, coords), sorted: two trees are equal iff these lists are.
  std::vector<std::pair<int, Coords>> leaf_cells() const;
  std::size_t leaf_count() const { return leaf_count_; }
  std::size_t memory_bytes() const;

  // Throws std::logic_error naming the first broken invariant (containment, counts, crowding, balance,
  // minimality, the cell map).
  void check_valid(std::span<const Point<D>> positions) const;

  static Coords cell_of(const Point<D>& p, int level);

 private:
  NodeId new_node(NodeId parent, int level, const Coords& coords);
  NodeId allocate_children();
  void split(NodeId n, std::span<const Point<D>> positions, std::vector<NodeId>* created);
  void merge(NodeId n, std::vector<NodeId>* removed);
  NodeId find(int level, const Coords& c) const { return map_.find(make_cell_key<D>(level, c)); }
  NodeId deepest_containing(int level, Coords c) const;
  bool cell_in_domain(int level, const std::array<std::int64_t, D>& c) const;
  std::uint32_t inputs_in_cell(int level, const Coords& c, std::span<const Point<D>> positions) const;
  bool crowded(NodeId n, std::span<const Point<D>> positions) const;
  bool required_split(NodeId n, std::span<const Point<D>> positions) const;
  void balance_around(std::vector<NodeId>& worklist, std::span<const Point<D>> positions,
                      std::vector<NodeId>* created_leaves, std::vector<NodeId>* split_leaves);
  template <class F>
  void for_each_neighbour_cell(int level, const Coords& c, int reach, F&& f) const;
  template <class F>
  void for_each_node_near(const Point<D>& p, F&& f) const;

  std::vector<Node> nodes_;
  std::vector<NodeId> free_blocks_;      // first ids of freed blocks of 2^D children
  mutable std::vector<std::uint32_t> stamp_;  // per node: query id that last reported it
  mutable std::uint32_t query_stamp_ = 0;
  CellMap map_;
  std::size_t leaf_count_ = 0;
};

template <int D>
template <class F>
std::size_t Quadtree<D>::for_each_leaf_in_box(const Point<D>& lo_in, const Point<D>& hi_in, F&& f) const {
  Point<D> lo, hi;
  double width = 0;
  for (int i = 0; i < D; ++i) {
    lo[i] = std::max(0.0, lo_in[i]);
    hi[i] = std::min(1.0, hi_in[i]);
    width = std::max(width, hi[i] - lo[i]);
  }
  // The level whose cells are at least as wide as the box: the box meets at most 2^D of them.
  int level = 0;
  if (width > 0) level = std::clamp(int(std::floor(-std::log2(width))), 0, kMaxLevel);
  else level = kMaxLevel;
  if (++query_stamp_ == 0) {
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    query_stamp_ = 1;
  }
  if (stamp_.size() < nodes_.size()) stamp_.resize(nodes_.size(), 0u);
  const Coords first = cell_of(lo, level), last = cell_of(hi, level);
  std::size_t visited = 0;
  NodeId stack[kMaxLevel * kChildren + 8];
  Coords c = first;
  for (;;) {
    NodeId start = deepest_containing(level, c);
    if (stamp_[start] != query_stamp_) {
      int top = 0;
      stack[top++] = start;
      while (top > 0) {
        NodeId n = stack[--top];
        if (stamp_[n] == query_stamp_) continue;
        stamp_[n] = query_stamp_;
        const Node& nd = nodes_[n];
        if (nd.is_leaf()) {
          ++visited;
          f(n);
          continue;
        }
        const double child_side = std::ldexp(1.0, -(nd.level + 1));
        for (int k = 0; k < kChildren; ++k) {
          const NodeId ch = nd.first_child + NodeId(k);
          bool meets = true;
          for (int i = 0; i < D && meets; ++i) {
            const double clo = double(nodes_[ch].coords[i]) * child_side;
            meets = clo <= hi[i] && clo + child_side >= lo[i];
          }
          if (meets) stack[top++] = ch;
        }
      }
    }
    int i = 0;
    for (; i < D; ++i) {
      if (c[i] < last[i]) {
        ++c[i];
        break;
      }
      c[i] = first[i];
    }
    if (i == D) break;
  }
  return visited;
}

}  // namespace shoremesh::engine
