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
#include <new>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "shoremesh/engine/cell_map.hpp"
#include "shoremesh/engine/ids.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::engine {

// 2^e, exactly, for |e| < 1000 (a cell side; cheaper than std::ldexp in the neighbour search).
inline double power_of_two(int e) { return std::bit_cast<double>(std::uint64_t(1023 + e) << 52); }

// floor(x) and ceil(x) as integers, exactly, for |x| < 2^53: a truncation and one correction, cheaper
// than std::floor / std::ceil without SSE4.1.
inline std::int64_t floor_to_int(double x) {
  const auto i = std::int64_t(x);
  return i - std::int64_t(double(i) > x);
}
inline std::int64_t ceil_to_int(double x) {
  const auto i = std::int64_t(x);
  return i + std::int64_t(double(i) < x);
}

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
// reaching into the owner's per-vertex arrays at random. 24 bytes in 2D, 32 in 3D: a 64-bit tag made
// every slot 8 bytes larger (the pool holds about one slot per vertex).
template <int D>
struct LeafVertex {
  Point<D> position{};
  std::uint32_t tag = 0;
  VertexId id = kNoVertex;
};
static_assert(sizeof(LeafVertex<2>) == 24 && sizeof(LeafVertex<3>) == 32);

template <int D>
class Quadtree {
 public:
  static constexpr int kChildren = 1 << D;
  static constexpr int kCrowdingMargin = 2;  // the crowding ring is 2^-2 of the node's side
  // kHalf[i][h]: bit k set for the children k in the lower (h = 0) or upper (h = 1) half along axis i.
  static constexpr auto kHalf = [] {
    std::array<std::array<std::uint32_t, 2>, D> halves{};
    for (int k = 0; k < kChildren; ++k)
      for (int i = 0; i < D; ++i) halves[std::size_t(i)][std::size_t(k >> i & 1)] |= 1u << k;
    return halves;
  }();
  using Coords = std::array<std::uint64_t, D>;

  // A node as the owner reads it: assembled from the tree's arrays on each call (a view: `vertices`
  // stays valid until the tree changes). Free slots have level -1.
  struct Node {
    NodeId parent = kNoNode;
    NodeId first_child = kNoNode;        // the 2^D children are contiguous; kNoNode for a leaf
    int level = -1;
    Coords coords{};                     // cell index at its level
    // Input points in the subtree, and a leaf's input vertex (kNoVertex: none): the vertex of tag 0 it
    // holds. A one-shot tree keeps no counts of internal nodes: it reports 0 for them.
    std::uint32_t input_count = 0;
    VertexId input_vertex = kNoVertex;
    std::span<const LeafVertex<D>> vertices;  // leaves: every vertex inside (input and Steiner)
    bool is_leaf() const { return first_child == kNoNode; }
  };

  // A closed box [lo, hi]; lo > hi on some axis makes it empty.
  struct Box {
    Point<D> lo{}, hi{};
    static Box empty() {
      Box b;
      b.lo.fill(2.0);
      b.hi.fill(-1.0);
      return b;
    }
  };

  // What an add or remove changed: leaves that stopped being leaves (split, or deleted by a merge) and
  // leaves that appeared. The dynamic algorithm marks the readers of `removed_leaves` inconsistent.
  struct Change {
    std::vector<NodeId> removed_leaves;
    std::vector<NodeId> new_leaves;
  };

  // Builds the canonical tree of `inputs` (ids[i] is the vertex id of inputs[i]). Throws
  // PointInputError when two inputs are closer than the tree's resolution (2^-40 of the box).
  // `editable` false: a one-shot tree, which takes Steiner vertices (insert_vertex, erase_vertex) but
  // no input edits. It keeps no input counts of internal nodes (only the crowding rule of an edit reads
  // them) and no room for more nodes.
  void build(std::span<const Point<D>> inputs, std::span<const VertexId> ids, bool editable = true);

  // Adds an input vertex at `position` (ids index `positions`). Returns the structural change.
  Change add_input(VertexId id, std::span<const Point<D>> positions);
  Change remove_input(VertexId id, std::span<const Point<D>> positions);

  // Steiner vertices: inserted into / removed from the leaf containing them. Inputs have tag 0, which
  // is how a leaf tells its input vertex: a Steiner vertex's tag is never 0 (std::logic_error).
  NodeId insert_vertex(VertexId id, const Point<D>& p, std::uint32_t tag, NodeId hint = kNoNode);
  // The same into `leaf`, which locate(p) found (the tree's shape unchanged since).
  void insert_vertex_at(NodeId leaf, VertexId id, const Point<D>& p, std::uint32_t tag);
  void erase_vertex(VertexId id, NodeId leaf);

  // Vertex v becomes new_id[v] everywhere in the tree (the owner renumbered its vertices); the leaves'
  // arrays are allocated afresh in node order on the way.
  void rename_vertices(std::span<const VertexId> new_id);

  NodeId root() const { return 0; }
  Node node(NodeId n) const {
    const Record& r = nodes_[n];
    const SearchEntry& e = search_[n];
    Node out;
    out.parent = e.parent;
    out.first_child = e.first_child;
    out.level = r.level;
    out.coords = r.coords();
    if (e.first_child == kNoNode) out.vertices = leaf_vertices(e);
    if (e.first_child == kNoNode) {
      out.input_vertex = leaf_input(e);
      out.input_count = out.input_vertex != kNoVertex;
    } else if (editable_) {
      out.input_count = block_inputs_[e.first_child / kChildren];
    }
    return out;
  }
  std::size_t node_capacity() const { return nodes_.size(); }
  // The parent alone, from the search entry (node() also reads the node's record).
  NodeId parent(NodeId n) const { return search_[n].parent; }
  double side(NodeId n) const { return power_of_two(-nodes_[n].level); }
  // QTApxNN of the input vertex in leaf n: a lower bound on its nearest-neighbour distance.
  double approximate_nn(NodeId n) const { return power_of_two(-nodes_[n].level - kCrowdingMargin); }
  // The leaves' arrays share one pool: slots in use by leaves, and the pool's size (free blocks included).
  std::size_t pool_slots_used() const;
  std::size_t pool_size() const { return pool_.size(); }
  Point<D> lower_corner(NodeId n) const;

  // The leaf containing p (hint: a leaf near p, to start from; optional).
  NodeId locate(const Point<D>& p, NodeId hint = kNoNode) const;

  // Calls f(leaf, its vertices) for every leaf that holds a vertex and whose closed box meets `box` but
  // not `seen`. A search that grows its box passes the previous box as `seen`: it then visits only the
  // new leaves, and no node entirely inside `seen` is read. Returns the number of leaves reported.
  template <class F>
  std::size_t for_each_occupied_leaf(const Box& box, const Box& seen, F&& f) const {
    return for_each_occupied_leaf(box, seen, std::forward<F>(f), [](int, const std::array<std::int64_t, D>&) { return true; });
  }
  // The same, skipping every node that `keep(level, cell)` turns down, with its subtree (cell_box
  // gives its closed box). `near`: a leaf near the box (a search about a vertex: the vertex's leaf),
  // or kNoNode: the node over its cell at the level the search starts at is found from it by its
  // parents instead of a cell-map look-up. Any id will do: one that is not a leaf is ignored, and a
  // leaf far from the box only goes unused.
  template <class F, class Keep>
  std::size_t for_each_occupied_leaf(const Box& box, const Box& seen, F&& f, Keep&& keep, NodeId near = kNoNode) const;
  // Whether a search of the box [center - half, center + half] that already searched it counts `leaf`
  // as seen (the test for_each_occupied_leaf applies to its `seen` box).
  bool leaf_meets_box(NodeId leaf, const Point<D>& center, double half) const {
    const Record& nd = nodes_[leaf];
    const double scale = power_of_two(nd.level);
    for (int i = 0; i < D; ++i) {
      const auto [first, last] = meeting_cells(center[i] - half, center[i] + half, scale);
      const auto c = std::int64_t(nd.coord(i));
      if (c < first || c > last) return false;
    }
    return true;
  }
  // Nodes whose union covers the box [lo, hi], which holds p: the deepest existing node over each of the
  // (at most 2^D) cells of the finest level whose cells are at least as wide as the box. Operations
  // register their reads here: a few coarse nodes instead of every leaf they looked into. Returns the
  // cover's code (the level, and per axis whether the box's cells are p's and the one below, p's alone
  // or p's and the one above), from which cover_nodes(p, code) finds the same nodes again: the nodes
  // over given cells change only when a node there is split or merged away.
  std::uint32_t covering_nodes(const Point<D>& p, const Point<D>& lo, const Point<D>& hi, std::vector<NodeId>& out) const;
  void cover_nodes(const Point<D>& p, std::uint32_t code, std::vector<NodeId>& out) const;

  // Every leaf as (level, coords), sorted: two trees are equal iff these lists are.
  std::vector<std::pair<int, Coords>> leaf_cells() const;
  std::size_t leaf_count() const { return leaf_count_; }
  std::size_t memory_bytes() const;

  // Throws std::logic_error naming the first broken invariant (containment, counts, crowding, balance,
  // minimality, the cell map).
  void check_valid(std::span<const Point<D>> positions) const;

  static Coords cell_of(const Point<D>& p, int level);
  // The closed box of the cell of that level (exact: a power of two times an integer).
  static Box cell_box(int level, const std::array<std::int64_t, D>& c) {
    const double side = power_of_two(-level);
    Box b;
    for (int i = 0; i < D; ++i) {
      b.lo[i] = double(c[i]) * side;
      b.hi[i] = double(c[i] + 1) * side;
    }
    return b;
  }
  // Along one axis, at the level of cells 1 / scale wide: the indices j whose closed cell
  // [j, j + 1] / scale meets [lo, hi]. Scaling by a power of two, floor and ceil are exact, so this equals
  // the test on the boxes. The interval may be empty (lo > hi) or reach outside the unit box: it is
  // clamped first.
  static std::pair<std::int64_t, std::int64_t> meeting_cells(double lo, double hi, double scale) {
    return {ceil_to_int(std::clamp(lo, -1.0, 2.0) * scale) - 1, floor_to_int(std::clamp(hi, -1.0, 2.0) * scale)};
  }

 private:
  // The rest of a node (the search reads SearchEntry): 12 bytes in 2D, 20 in 3D. The cell index is at
  // most 40 bits per axis, kept as a low 32-bit word and a high byte.
  struct Record {
    std::array<std::uint32_t, D> coords_low{};
    std::int8_t level = -1;             // -1: a free slot
    std::uint8_t size_class = 0;        // leaf: its pool block holds 2^(size_class - 1) vertices; 0: none
    std::array<std::uint8_t, D> coords_high{};
    std::uint64_t coord(int i) const {
      return std::uint64_t(coords_low[std::size_t(i)]) | std::uint64_t(coords_high[std::size_t(i)]) << 32;
    }
    Coords coords() const {
      Coords c;
      for (int i = 0; i < D; ++i) c[std::size_t(i)] = coord(i);
      return c;
    }
    void set_coords(const Coords& c) {
      for (int i = 0; i < D; ++i) {
        coords_low[std::size_t(i)] = std::uint32_t(c[std::size_t(i)]);
        coords_high[std::size_t(i)] = std::uint8_t(c[std::size_t(i)] >> 32);
      }
    }
  };
  // What the neighbour search reads of each node, 16 bytes apiece beside nodes_ (same ids). Blocks of
  // 2^D siblings start at multiples of 2^D in a 64-byte aligned array, so a 2D block is one cache line
  // and a 3D block two: a descent reads one block per node it expands, and a leaf's vertex array
  // without reading the leaf's Record.
  struct SearchEntry {
    NodeId first_child = kNoNode;  // kNoNode: a leaf
    // Internal: bit k set when child k's subtree holds a vertex (searches skip empty subtrees unread:
    // about half the leaves in 2D, two thirds in 3D, hold none). Leaf: its number of vertices.
    std::uint32_t occupied_or_size = 0;
    std::uint32_t vertices = 0;    // leaf: where its array starts in pool_
    NodeId parent = kNoNode;
  };
  template <class T>
  struct LineAligned {
    using value_type = T;
    static constexpr std::align_val_t kAlign{64};
    LineAligned() = default;
    template <class U>
    LineAligned(const LineAligned<U>&) {}
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
    void deallocate(T* p, std::size_t) { ::operator delete(p, kAlign); }
    template <class U>
    bool operator==(const LineAligned<U>&) const { return true; }
  };

  std::span<const LeafVertex<D>> leaf_vertices(const SearchEntry& e) const {
    return {pool_.data() + e.vertices, e.occupied_or_size};
  }
  std::span<LeafVertex<D>> leaf_vertices(NodeId n) {
    return {pool_.data() + search_[n].vertices, search_[n].occupied_or_size};
  }
  // A leaf's input vertex: the one of tag 0 (the first, while add_input's leaf holds two), or kNoVertex.
  VertexId leaf_input(const SearchEntry& e) const {
    for (const LeafVertex<D>& v : leaf_vertices(e))
      if (v.tag == 0) return v.id;
    return kNoVertex;
  }
  // Input points in node n's subtree (an editable tree): a leaf's from its vertices' tags.
  std::uint32_t input_count(NodeId n) const {
    const SearchEntry& e = search_[n];
    if (e.first_child != kNoNode) return block_inputs_[e.first_child / kChildren];
    std::uint32_t count = 0;
    for (const LeafVertex<D>& v : leaf_vertices(e)) count += v.tag == 0;
    return count;
  }
  bool is_leaf(NodeId n) const { return search_[n].first_child == kNoNode; }
  // The pool of leaf arrays: a leaf's array is a block of 2^(c-1) slots (size class c), blocks freed by
  // a leaf that grew, shrank or went away are kept per class for the next leaf that needs one.
  std::uint32_t pool_allocate(int size_class);
  void pool_free(std::uint32_t offset, int size_class);
  // Gives leaf n a block of `size_class` (0: none), moving its vertices there.
  void resize_leaf_block(NodeId n, int size_class);
  void leaf_push(NodeId n, const LeafVertex<D>& e);
  // Removes the vertex at index i of leaf n's array (the last one takes its place).
  void leaf_erase(NodeId n, std::size_t i);
  void leaf_clear(NodeId n);

  void make_root();
  NodeId allocate_children();
  void split(NodeId n, std::vector<NodeId>* created);
  void merge(NodeId n, std::vector<NodeId>* removed);
  // Keep the occupied masks of the ancestors of a leaf that just gained its first vertex / lost its last.
  void mark_occupied(NodeId leaf);
  void mark_vacated(NodeId leaf);
  // The node of cell c at `level`, if it exists: the cell map holds each internal node's cell with its
  // children's block (a node exists iff its parent is internal), 2^D times fewer entries than nodes.
  NodeId find(int level, const Coords& c) const {
    if (level == 0) return root();
    Coords pc;
    int k = 0;
    for (int i = 0; i < D; ++i) {
      pc[i] = c[i] >> 1;
      k |= int(c[i] & 1u) << i;
    }
    const NodeId block = map_.template find<D>(level - 1, pc);
    return block == kNoNode ? kNoNode : block + NodeId(k);
  }
  NodeId deepest_containing(int level, Coords c) const;
  // The same, with the node's level (read from the cell map, not from the node).
  NodeId deepest_containing(int level, Coords c, int& found_level) const;
  // Sets search_[n] from node n: for an internal node, from its children's entries (sync them first).
  void sync_search(NodeId n);
  // Clamps [lo_in, hi_in] to the unit box into [lo, hi]; returns the finest level whose cells are at
  // least as wide as it (the box meets at most 2^D cells of that level).
  static int box_level(const Point<D>& lo_in, const Point<D>& hi_in, Point<D>& lo, Point<D>& hi);
  static constexpr int kLevelBits = 6;  // a level, 0 to kMaxLevel, in a cover's code
  static_assert(kMaxLevel < (1 << kLevelBits) && kLevelBits + 2 * D <= 32);
  bool cell_in_domain(int level, const std::array<std::int64_t, D>& c) const;
  std::uint32_t inputs_in_cell(int level, const Coords& c, std::span<const Point<D>> positions) const;
  bool crowded(NodeId n, std::span<const Point<D>> positions) const;
  template <class Count>
  bool crowded_by(int level, const Coords& c, std::uint32_t own, Count&& count) const;
  bool required_split(NodeId n, std::span<const Point<D>> positions) const;
  void balance_around(std::vector<NodeId>& worklist, std::vector<NodeId>* created_leaves,
                      std::vector<NodeId>* split_leaves);
  template <class F>
  void for_each_neighbour_cell(int level, const Coords& c, int reach, F&& f) const;
  template <class F>
  void for_each_node_near(const Point<D>& p, F&& f) const;

  std::vector<Record> nodes_;
  std::vector<SearchEntry, LineAligned<SearchEntry>> search_;
  // What only an edit's crowding rule reads: each internal node's count of input points in its subtree,
  // kept at its children's block (block_inputs_[first_child / 2^D]; block 0, the root's, is nobody's):
  // a leaf's count and input vertex are its vertices of tag 0. 4 bytes per 2^D nodes instead of 8 per
  // node. Empty in a one-shot tree.
  std::vector<std::uint32_t> block_inputs_;
  bool editable_ = true;
  std::vector<NodeId> free_blocks_;      // first ids of freed blocks of 2^D children
  std::vector<LeafVertex<D>> pool_;
  static constexpr int kSizeClasses = 33;
  std::array<std::vector<std::uint32_t>, kSizeClasses> free_arrays_;  // free pool blocks by size class
  CellMap map_;
  std::size_t leaf_count_ = 0;
};

template <int D>
template <class F, class Keep>
std::size_t Quadtree<D>::for_each_occupied_leaf(const Box& box, const Box& seen, F&& f, Keep&& keep, NodeId near) const {
  Point<D> lo, hi;
  const int level = box_level(box.lo, box.hi, lo, hi);
  // Per level L and axis i, the cell indices j whose closed cell [j, j+1] 2^-L meets the box
  // ([meet_lo, meet_hi]), meets `seen` ([seen_lo, seen_hi]) or lies inside `seen` ([in_lo, in_hi]).
  // Scaling by 2^L, floor and ceil are exact, so these integer tests equal the tests on the boxes.
  struct Ranges {
    std::array<std::int64_t, D> meet_lo, meet_hi, seen_lo, seen_hi, in_lo, in_hi;
  };
  std::array<Ranges, kMaxLevel + 2> ranges;
  std::uint64_t computed = 0;  // bit L: ranges[L] is filled in
  auto fill_ranges = [&](int l) {
    computed |= std::uint64_t(1) << l;
    Ranges& r = ranges[std::size_t(l)];
    const double scale = power_of_two(l);
    for (int i = 0; i < D; ++i) {
      std::tie(r.meet_lo[i], r.meet_hi[i]) = meeting_cells(lo[i], hi[i], scale);
      std::tie(r.seen_lo[i], r.seen_hi[i]) = meeting_cells(seen.lo[i], seen.hi[i], scale);
      r.in_lo[i] = r.seen_lo[i] + 1;
      r.in_hi[i] = r.seen_hi[i] - 1;
    }
  };
  auto ranges_at = [&](int l) __attribute__((always_inline)) -> const Ranges& {
    if (!(computed >> l & 1)) [[unlikely]] fill_ranges(l);
    return ranges[std::size_t(l)];
  };
  struct Item {
    NodeId node;
    int level;
    std::array<std::int64_t, D> c;
  };
  auto meets_seen = [](const Ranges& r, const std::array<std::int64_t, D>& c) {
    for (int i = 0; i < D; ++i)
      if (c[i] < r.seen_lo[i] || c[i] > r.seen_hi[i]) return false;
    return true;
  };
  auto inside_seen = [](const Ranges& r, const std::array<std::int64_t, D>& c) {
    for (int i = 0; i < D; ++i)
      if (c[i] < r.in_lo[i] || c[i] > r.in_hi[i]) return false;
    return true;
  };
  // The leaves found, reported once the descent is over. Per thread: the operations of one batch
  // search the tree on several threads at once (f must not search again from inside).
  static thread_local std::vector<NodeId> found;
  std::size_t count = 0;
  auto report = [&](NodeId n) {
    if (count == found.size()) found.resize(2 * count + 16);
    found[count++] = n;
    // The array's first and last bytes: a 3D leaf's two 40-byte vertices mostly span two lines.
    const LeafVertex<D>* array = pool_.data() + search_[n].vertices;
    __builtin_prefetch(array);
    __builtin_prefetch(reinterpret_cast<const char*>(array + search_[n].occupied_or_size) - 1);
  };
  // A block of children: one line in 2D, two in 3D (children 4 to 7 in the second).
  auto prefetch_block = [&](NodeId children) {
    __builtin_prefetch(&search_[children]);
    if constexpr (D == 3) __builtin_prefetch(&search_[children + 4]);
  };
  // The nodes to expand, first in first out: a node's children's block, prefetched when it was queued,
  // is read only after the nodes queued before it (a stack reads it at once, and the descent waits on
  // that miss). The order the leaves are found in is all that changes.
  static thread_local std::vector<Item> queue;
  std::size_t queued = 0;
  auto enqueue = [&](const Item& item) {
    if (queued == queue.size()) queue.resize(2 * queued + 64);
    queue[queued++] = item;
  };
  // From the first cell whose closed box meets the box: when lo lies exactly on a cell boundary, the
  // cell below it touches the box too, and its leaves count as seen in the next, larger search.
  Coords first;
  for (int i = 0; i < D; ++i) first[i] = std::uint64_t(std::max<std::int64_t>(0, ranges_at(level).meet_lo[i]));
  const Coords last = cell_of(hi, level);
  // The box's cells found so far (at most 3 per axis, when it ends on cell boundaries): a cell beside
  // one of them in the same parent is that one's sibling, and a cell inside the same coarser leaf is
  // that leaf; neither needs the cell map.
  struct Top {
    Coords cell;
    NodeId node;
    int level;
  };
  Top tops[28];
  int top_count = 0;
  // The hint, if it is a leaf: the node over its cell at the box's level is its ancestor there, or the
  // leaf itself when it is coarser. Either way a fact top_of may use like one it looked up (a cell of
  // the same parent, or one inside the coarser leaf), whether or not that cell meets the box.
  if (near < search_.size() && level > 0 && search_[near].first_child == kNoNode) {
    const Record& r = nodes_[near];
    if (r.level >= level) {
      NodeId n = near;
      for (int l = r.level; l > level; --l) n = search_[n].parent;
      Coords cell;
      for (int i = 0; i < D; ++i) cell[i] = r.coord(i) >> (r.level - level);
      tops[top_count++] = Top{cell, n, level};
    } else if (r.level >= 0) {
      tops[top_count++] = Top{r.coords(), near, r.level};
    }
  }
  auto top_of = [&](const Coords& cell, int& top_level) -> NodeId {
    for (int t = 0; t < top_count; ++t) {
      const Top& o = tops[t];
      const int shift = o.level == level ? 1 : level - o.level;
      bool same = level > 0;
      for (int i = 0; i < D; ++i) same = same && (cell[i] >> shift) == (o.cell[i] >> shift);
      if (!same) continue;
      top_level = o.level;
      if (o.level < level) return o.node;
      int k = 0;
      for (int i = 0; i < D; ++i) k |= int(cell[i] & 1u) << i;
      return search_[search_[o.node].parent].first_child + NodeId(k);
    }
    const NodeId n = deepest_containing(level, cell, top_level);
    tops[top_count++] = Top{cell, n, top_level};
    return n;
  };
  // The nodes over the box's cells first, their entries and children's blocks fetched together, then
  // the descent from all of them, level by level.
  Item starts[27];
  int start_count = 0;
  for_each_index_in_box<D>(first, last, [&](const Coords& cell) {
    std::array<std::int64_t, D> ci;
    for (int i = 0; i < D; ++i) ci[i] = std::int64_t(cell[i]);
    if (inside_seen(ranges_at(level), ci)) return;  // searched already, without a look-up
    int top_level = 0;
    const NodeId top_node = top_of(cell, top_level);
    for (int i = 0; i < D; ++i) ci[i] >>= (level - top_level);
    // A coarse leaf can contain several of the box's cells: search it once.
    if (top_level < level)
      for (int t = 0; t < start_count; ++t)
        if (starts[t].node == top_node) return;
    __builtin_prefetch(&search_[top_node]);
    starts[start_count++] = Item{top_node, top_level, ci};
  });
  for (int t = 0; t < start_count; ++t)
    if (const NodeId children = search_[starts[t].node].first_child; children != kNoNode) prefetch_block(children);
  for (int t = 0; t < start_count; ++t) enqueue(starts[t]);
  for (std::size_t head = 0; head < queued; ++head) {
    const Item it = queue[head];
    const SearchEntry& e = search_[it.node];
    const Ranges& r = ranges_at(it.level);
    // The tests on `seen` first: a few integer comparisons, where keep may cost far more (the engine's
    // pruning tests the node's box against its cell: 3 million fewer tests at Lake Superior).
    if (e.first_child == kNoNode) {
      if (e.occupied_or_size != 0 && !meets_seen(r, it.c) && keep(it.level, it.c)) report(it.node);
      continue;
    }
    if (inside_seen(r, it.c) || !keep(it.level, it.c)) continue;
    // Children meeting the box, from index ranges one level down: a child is read only if it meets
    // the box and its subtree holds a vertex. Child k is the upper half along axis i when bit i of k
    // is set; kHalf[i][h] is the set of children in half h along axis i.
    const Ranges& rc = ranges_at(it.level + 1);
    std::uint32_t wanted = e.occupied_or_size;
    for (int i = 0; i < D; ++i) {
      const std::int64_t low = 2 * it.c[i];
      std::uint32_t along = 0;
      if (low >= rc.meet_lo[i] && low <= rc.meet_hi[i]) along |= kHalf[i][0];
      if (low + 1 >= rc.meet_lo[i] && low + 1 <= rc.meet_hi[i]) along |= kHalf[i][1];
      wanted &= along;
    }
    // Occupied leaf children are reported here, internal ones go on the stack.
    for (; wanted != 0; wanted &= wanted - 1) {
      const int k = std::countr_zero(wanted);
      const NodeId child_node = e.first_child + NodeId(k);
      std::array<std::int64_t, D> cc;
      for (int i = 0; i < D; ++i) cc[i] = 2 * it.c[i] + ((k >> i) & 1);
      const NodeId grandchildren = search_[child_node].first_child;
      if (grandchildren == kNoNode) {
        if (!meets_seen(rc, cc) && keep(it.level + 1, cc)) report(child_node);
      } else if (!inside_seen(rc, cc)) {  // one inside `seen` would only be dropped when dequeued
        // Its children's block is read when it leaves the queue: fetched meanwhile, and for its
        // siblings in parallel (the descent's time goes mostly to these misses).
        prefetch_block(grandchildren);
        enqueue(Item{child_node, it.level + 1, cc});
      }
    }
  }
  for (std::size_t k = 0; k < count; ++k) f(found[k], leaf_vertices(search_[found[k]]));
  return count;
}

}  // namespace shoremesh::engine
