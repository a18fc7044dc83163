#pragma once
// The dynamic balanced 2^D-tree over the unit box (BEG94 style), canonical in its input points:
// the tree after any sequence of add/remove equals the tree a fresh build on the same input gives.
//
// The rule it is the minimal fixed point of (every required split, nothing more):
//  - crowding: a node of side h that contains an input point splits while the node grown by h/4 on every
//    side (a ring of cells two levels finer) holds two or more input points. So the leaf of an input v
//    has side h with h/4 < NN_N(v) <= 3 sqrt(D) h: QTApxNN(v) = h/4 approximates NN from below. (The
//    plain 3^D-block rule gives leaves of about NN/3, and every neighbour search then visits ~10x more.)
//  - balance: leaves that touch (faces, edges or corners) differ by at most one level.
// Equivalently, a node G at level K is split iff crowded(G) or some node at level K+2 touches G.
//
// Leaves ("squares") keep the vertices inside them: the input vertex (at most one) and Steiner vertices.
// Cells are half-open [i 2^-L, (i+1) 2^-L) except that coordinate 1 belongs to the last cell.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "shoremesh/engine/cell_map.hpp"
#include "shoremesh/engine/ids.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::engine {

// 2^e, exactly, for |e| < 1000 (a cell side; cheaper than std::ldexp in the neighbour search).
inline double power_of_two(int e) { return std::bit_cast<double>(std::uint64_t(1023 + e) << 52); }

// Calls f(c) for every index c with first <= c <= last in each coordinate, the first axis fastest: the
// cells of a box at one level.
template <int D, class Index, class F>
void for_each_index_in_box(const std::array<Index, D>& first, const std::array<Index, D>& last, F&& f) {
  std::array<Index, D> c = first;
  for (;;) {
    f(c);
    int i = 0;
    for (; i < D; ++i) {
      if (c[i] < last[i]) {
        ++c[i];
        break;
      }
      c[i] = first[i];
    }
    if (i == D) return;
  }
}

// A vertex as its leaf keeps it: the id, a copy of the position and a tag the owner gives it (the
// engine: its birth time). The neighbour search reads all three from the leaf's own array instead of
// reaching into the owner's per-vertex arrays at random.
template <int D>
struct LeafVertex {
  Point<D> position{};
  std::uint64_t tag = 0;
  VertexId id = kNoVertex;
};

template <int D>
class Quadtree {
 public:
  static constexpr int kChildren = 1 << D;
  static constexpr int kCrowdingMargin = 2;  // the crowding ring is 2^-2 of the node's side
  using Coords = std::array<std::uint64_t, D>;

  struct Node {
    NodeId parent = kNoNode;
    NodeId first_child = kNoNode;        // the 2^D children are contiguous; kNoNode for a leaf
    std::int32_t level = 0;
    Coords coords{};                     // cell index at its level
    std::uint32_t input_count = 0;       // input points in the subtree
    VertexId input_vertex = kNoVertex;   // leaves: the input vertex inside, if any
    std::vector<LeafVertex<D>> vertices; // leaves: every vertex inside (input and Steiner)
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

  // Steiner vertices: inserted into / removed from the leaf containing them. Inputs have tag 0.
  NodeId insert_vertex(VertexId id, const Point<D>& p, std::uint64_t tag, NodeId hint = kNoNode);
  void erase_vertex(VertexId id, NodeId leaf);

  NodeId root() const { return 0; }
  const Node& node(NodeId n) const { return nodes_[n]; }
  std::size_t node_capacity() const { return nodes_.size(); }
  double side(NodeId n) const { return power_of_two(-nodes_[n].level); }
  // QTApxNN of the input vertex in leaf n: a lower bound on its nearest-neighbour distance.
  double approximate_nn(NodeId n) const { return power_of_two(-nodes_[n].level - kCrowdingMargin); }
  Point<D> lower_corner(NodeId n) const;

  // The leaf containing p (hint: a leaf near p, to start from; optional).
  NodeId locate(const Point<D>& p, NodeId hint = kNoNode) const;

  // A search session: for_each_leaf_in_box reports each leaf at most once per session, so a search that
  // grows its box visits only the new leaves.
  void begin_session() const;
  // Calls f(leaf) for every leaf whose closed box meets the closed box [lo, hi] and that this session
  // has not reported yet. Returns the number of leaves reported.
  template <class F>
  std::size_t for_each_leaf_in_box(const Point<D>& lo, const Point<D>& hi, F&& f) const;
  // Nodes whose union covers the box: the deepest existing node over each of the (at most 2^D) cells
  // of the finest level whose cells are at least as wide as the box. Operations register their reads
  // here: a few coarse nodes instead of every leaf they looked into.
  void covering_nodes(const Point<D>& lo, const Point<D>& hi, std::vector<NodeId>& out) const;

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
  void split(NodeId n, std::vector<NodeId>* created);
  void merge(NodeId n, std::vector<NodeId>* removed);
  NodeId find(int level, const Coords& c) const { return map_.find(make_cell_key<D>(level, c)); }
  NodeId deepest_containing(int level, Coords c) const;
  // Clamps [lo_in, hi_in] to the unit box into [lo, hi]; returns the finest level whose cells are at
  // least as wide as it (the box meets at most 2^D cells of that level).
  static int box_level(const Point<D>& lo_in, const Point<D>& hi_in, Point<D>& lo, Point<D>& hi);
  bool cell_in_domain(int level, const std::array<std::int64_t, D>& c) const;
  std::uint32_t inputs_in_cell(int level, const Coords& c, std::span<const Point<D>> positions) const;
  bool crowded(NodeId n, std::span<const Point<D>> positions) const;
  template <class Count>
  bool crowded_by(int level, const Coords& c, std::uint32_t own, Count&& count) const;
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
  mutable std::vector<NodeId> found_;         // scratch of for_each_leaf_in_box
  CellMap map_;
  std::size_t leaf_count_ = 0;
};

template <int D>
template <class F>
std::size_t Quadtree<D>::for_each_leaf_in_box(const Point<D>& lo_in, const Point<D>& hi_in, F&& f) const {
  Point<D> lo, hi;
  const int level = box_level(lo_in, hi_in, lo, hi);
  if (stamp_.size() < nodes_.size()) stamp_.resize(nodes_.size(), 0u);
  const Coords first = cell_of(lo, level), last = cell_of(hi, level);
  found_.clear();
  NodeId stack[kMaxLevel * kChildren + 8];
  for_each_index_in_box<D>(first, last, [&](const Coords& c) {
    // Only leaves are stamped: a later, larger box of the same session must still descend into an
    // internal node whose other children it has not seen.
    int top = 0;
    stack[top++] = deepest_containing(level, c);
    while (top > 0) {
      NodeId n = stack[--top];
      const Node& nd = nodes_[n];
      if (nd.is_leaf()) {
        if (stamp_[n] == query_stamp_) continue;
        stamp_[n] = query_stamp_;
        found_.push_back(n);
        continue;
      }
      // Which children meet the box, from the parent's cell alone: a child is read only if it does.
      const double child_side = power_of_two(-(nd.level + 1));
      int meets_low = 0, meets_high = 0;  // bit i: the lower / upper half along axis i meets the box
      for (int i = 0; i < D; ++i) {
        const double mid = double(2 * nd.coords[i] + 1) * child_side;
        if (mid - child_side <= hi[i] && mid >= lo[i]) meets_low |= 1 << i;
        if (mid <= hi[i] && mid + child_side >= lo[i]) meets_high |= 1 << i;
      }
      for (int k = 0; k < kChildren; ++k)
        if ((~k & meets_low & (kChildren - 1)) == (~k & (kChildren - 1)) && (k & meets_high) == k)
          stack[top++] = nd.first_child + NodeId(k);
    }
  });
  // The leaves' vertex arrays live apart on the heap: fetch them all at once rather than wait for
  // each in turn.
  for (NodeId n : found_) __builtin_prefetch(nodes_[n].vertices.data());
  for (NodeId n : found_) f(n);
  return found_.size();
}

}  // namespace shoremesh::engine
