#include "shoremesh/engine/quadtree.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "shoremesh/error.hpp"

namespace shoremesh::engine {

template <int D>
typename Quadtree<D>::Coords Quadtree<D>::cell_of(const Point<D>& p, int level) {
  Coords c;
  const std::uint64_t cells = std::uint64_t(1) << level;
  for (int i = 0; i < D; ++i) {
    // Scaling by 2^level and floor are exact: the cell of a point is a deterministic function of its
    // coordinates.
    const double x = std::floor(p[i] * power_of_two(level));
    c[i] = x <= 0 ? 0 : std::min(cells - 1, std::uint64_t(x));
  }
  return c;
}

template <int D>
Point<D> Quadtree<D>::lower_corner(NodeId n) const {
  Point<D> p;
  const double s = side(n);
  for (int i = 0; i < D; ++i) p[i] = double(nodes_[n].coord(i)) * s;
  return p;
}

template <int D>
std::uint32_t Quadtree<D>::pool_allocate(int size_class) {
  auto& free = free_arrays_[std::size_t(size_class)];
  if (!free.empty()) {
    const std::uint32_t offset = free.back();
    free.pop_back();
    return offset;
  }
  const std::size_t slots = std::size_t(1) << (size_class - 1);
  const std::size_t offset = pool_.size();
  if (offset + slots > std::numeric_limits<std::uint32_t>::max()) throw std::length_error("quadtree leaf pool full");
  // Grows by half, not double: the pool is one of the engine's largest arrays.
  if (offset + slots > pool_.capacity()) pool_.reserve(std::max(offset + slots, pool_.capacity() + pool_.capacity() / 2));
  pool_.resize(offset + slots);
  return std::uint32_t(offset);
}

template <int D>
void Quadtree<D>::pool_free(std::uint32_t offset, int size_class) {
  if (size_class != 0) free_arrays_[std::size_t(size_class)].push_back(offset);
}

namespace {

// The smallest size class whose block holds `size` vertices: 0 for none, else 1 + ceil(log2 size).
int size_class_for(std::size_t size) { return size == 0 ? 0 : 1 + int(std::bit_width(size - 1)); }
std::size_t class_capacity(int size_class) { return size_class == 0 ? 0 : std::size_t(1) << (size_class - 1); }

}  // namespace

template <int D>
void Quadtree<D>::resize_leaf_block(NodeId n, int size_class) {
  Record& r = nodes_[n];
  if (size_class == r.size_class) return;
  const std::uint32_t offset = size_class == 0 ? 0 : pool_allocate(size_class);
  SearchEntry& e = search_[n];
  std::copy_n(pool_.begin() + e.vertices, e.occupied_or_size, pool_.begin() + offset);
  pool_free(e.vertices, r.size_class);
  e.vertices = offset;
  r.size_class = std::uint8_t(size_class);
}

template <int D>
void Quadtree<D>::leaf_push(NodeId n, const LeafVertex<D>& v) {
  const std::uint32_t size = search_[n].occupied_or_size;
  if (size == class_capacity(nodes_[n].size_class)) resize_leaf_block(n, nodes_[n].size_class + 1);
  pool_[search_[n].vertices + size] = v;
  search_[n].occupied_or_size = size + 1;
}

template <int D>
void Quadtree<D>::leaf_erase(NodeId n, std::size_t i) {
  SearchEntry& e = search_[n];
  const std::uint32_t size = e.occupied_or_size - 1;
  pool_[e.vertices + i] = pool_[e.vertices + size];
  e.occupied_or_size = size;
  // A block four times too large shrinks (hysteresis: a leaf going back and forth by one vertex does
  // not move each time); an empty leaf holds none.
  if (4 * std::size_t(size) <= class_capacity(nodes_[n].size_class)) resize_leaf_block(n, size_class_for(size));
}

template <int D>
void Quadtree<D>::leaf_clear(NodeId n) {
  search_[n].occupied_or_size = 0;
  resize_leaf_block(n, 0);
}

template <int D>
std::size_t Quadtree<D>::pool_slots_used() const {
  std::size_t slots = 0;
  for (NodeId n = 0; n < nodes_.size(); ++n)
    if (nodes_[n].level >= 0 && is_leaf(n)) slots += class_capacity(nodes_[n].size_class);
  return slots;
}

// The root, alone in the first block of 2^D slots (every later block then starts at a multiple of 2^D).
template <int D>
void Quadtree<D>::make_root() {
  nodes_.assign(kChildren, Record{});
  search_.assign(kChildren, SearchEntry{});
  if (editable_) block_inputs_.assign(1, 0);
  nodes_[0].level = 0;
}

template <int D>
NodeId Quadtree<D>::allocate_children() {
  if (!free_blocks_.empty()) {
    NodeId first = free_blocks_.back();
    free_blocks_.pop_back();
    return first;
  }
  NodeId first = NodeId(nodes_.size());
  // Grows by a quarter, not double: the node arrays are among the engine's largest (a build sizes
  // them to its tree and a sixteenth more, room for the edits that follow).
  if (nodes_.size() + kChildren > nodes_.capacity()) {
    const std::size_t capacity = nodes_.size() + std::max<std::size_t>(nodes_.size() / 4, 64 * kChildren);
    nodes_.reserve(capacity);
    search_.reserve(capacity);
    if (editable_) block_inputs_.reserve(capacity / kChildren);
  }
  nodes_.resize(nodes_.size() + kChildren);
  search_.resize(nodes_.size());
  if (editable_) block_inputs_.resize(nodes_.size() / kChildren);
  return first;
}

// Turns leaf n into an internal node with 2^D leaf children and hands its vertices down.
template <int D>
void Quadtree<D>::split(NodeId n, std::vector<NodeId>* created) {
  if (nodes_[n].level >= kMaxLevel)
    throw PointInputError("input points closer than the engine's resolution (2^-40 of the box side)", {});
  const NodeId first = allocate_children();
  const int level = nodes_[n].level + 1;
  const Coords pc = nodes_[n].coords();
  for (int k = 0; k < kChildren; ++k) {
    Record& ch = nodes_[first + NodeId(k)];
    ch = Record{};
    ch.level = std::int8_t(level);
    Coords cc;
    for (int i = 0; i < D; ++i) cc[i] = 2 * pc[i] + ((k >> i) & 1);
    ch.set_coords(cc);
    search_[first + NodeId(k)] = SearchEntry{};
    search_[first + NodeId(k)].parent = n;
    if (created) created->push_back(first + NodeId(k));
  }
  if (editable_) block_inputs_[first / kChildren] = input_count(n);
  // By index: a child's block may move the pool, the parent's block stays where it is until cleared.
  for (std::uint32_t j = 0; j < search_[n].occupied_or_size; ++j) {
    const LeafVertex<D> e = pool_[search_[n].vertices + j];
    const Coords c = cell_of(e.position, level);
    int k = 0;
    for (int i = 0; i < D; ++i) k |= int(c[i] & 1u) << i;
    leaf_push(first + NodeId(k), e);
  }
  leaf_clear(n);
  search_[n].first_child = first;
  map_.insert<D>(level - 1, pc, first);
  leaf_count_ += kChildren - 1;
  sync_search(n);
}

// Turns internal node n, whose children are all leaves, back into a leaf holding their vertices.
template <int D>
void Quadtree<D>::merge(NodeId n, std::vector<NodeId>* removed) {
  const NodeId first = search_[n].first_child;
  std::size_t total = 0;
  for (int k = 0; k < kChildren; ++k) {
    if (!is_leaf(first + NodeId(k))) throw std::logic_error("quadtree merge of a node with an internal child");
    total += search_[first + NodeId(k)].occupied_or_size;
  }
  search_[n].first_child = kNoNode;
  search_[n].occupied_or_size = 0;
  search_[n].vertices = 0;
  nodes_[n].size_class = 0;
  resize_leaf_block(n, size_class_for(total));
  for (int k = 0; k < kChildren; ++k) {
    const NodeId c = first + NodeId(k);
    SearchEntry& e = search_[n];
    std::copy_n(pool_.begin() + search_[c].vertices, search_[c].occupied_or_size, pool_.begin() + e.vertices + e.occupied_or_size);
    e.occupied_or_size += search_[c].occupied_or_size;
    leaf_clear(c);
    nodes_[c] = Record{};  // level -1: a free slot
    search_[c] = SearchEntry{};
    if (removed) removed->push_back(c);
  }
  map_.erase<D>(nodes_[n].level, nodes_[n].coords());
  free_blocks_.push_back(first);
  leaf_count_ -= kChildren - 1;
}

template <int D>
void Quadtree<D>::sync_search(NodeId n) {
  SearchEntry& e = search_[n];
  if (e.first_child == kNoNode) return;  // a leaf's entry is its array's place and size, kept by leaf_push/erase
  e.occupied_or_size = 0;
  for (int k = 0; k < kChildren; ++k)
    if (search_[e.first_child + NodeId(k)].occupied_or_size != 0) e.occupied_or_size |= 1u << k;
}

template <int D>
NodeId Quadtree<D>::deepest_containing(int level, Coords c, int& found_level) const {
  for (;;) {
    NodeId n = find(level, c);
    if (n != kNoNode) {
      found_level = level;
      return n;
    }
    --level;
    for (int i = 0; i < D; ++i) c[i] >>= 1;
  }
}

template <int D>
NodeId Quadtree<D>::deepest_containing(int level, Coords c) const {
  int found_level = 0;
  return deepest_containing(level, c, found_level);
}

template <int D>
int Quadtree<D>::box_level(const Point<D>& lo_in, const Point<D>& hi_in, Point<D>& lo, Point<D>& hi) {
  double width = 0;
  for (int i = 0; i < D; ++i) {
    lo[i] = std::max(0.0, lo_in[i]);
    hi[i] = std::min(1.0, hi_in[i]);
    width = std::max(width, hi[i] - lo[i]);
  }
  if (!(width > 0)) return kMaxLevel;
  return std::clamp(int(std::floor(-std::log2(width))), 0, kMaxLevel);
}

template <int D>
void Quadtree<D>::mark_occupied(NodeId leaf) {
  for (NodeId n = leaf, p = search_[n].parent; p != kNoNode; n = p, p = search_[p].parent) {
    std::uint32_t& mask = search_[p].occupied_or_size;
    const bool was_occupied = mask != 0;
    mask |= 1u << (n - search_[p].first_child);
    if (was_occupied) return;  // its ancestors already know
  }
}

template <int D>
void Quadtree<D>::mark_vacated(NodeId leaf) {
  for (NodeId n = leaf, p = search_[n].parent; p != kNoNode; n = p, p = search_[p].parent) {
    std::uint32_t& mask = search_[p].occupied_or_size;
    mask &= ~(1u << (n - search_[p].first_child));
    if (mask != 0) return;  // still holds a vertex elsewhere
  }
}

template <int D>
std::uint32_t Quadtree<D>::covering_nodes(const Point<D>& p, const Point<D>& lo_in, const Point<D>& hi_in,
                                          std::vector<NodeId>& out) const {
  Point<D> lo, hi;
  int level = box_level(lo_in, hi_in, lo, hi);
  Coords first = cell_of(lo, level), last = cell_of(hi, level);
  // At most two cells per axis, as an operation's count of reads assumes: box_level's log2 may round a
  // width a hair above a cell's side down to that side's level, where the box can meet three.
  auto wide = [&] {
    for (int i = 0; i < D; ++i)
      if (last[i] - first[i] > 1) return true;
    return false;
  };
  while (level > 0 && wide()) {
    --level;
    first = cell_of(lo, level);
    last = cell_of(hi, level);
  }
  const Coords own = cell_of(p, level);
  std::uint32_t code = std::uint32_t(level);
  for (int i = 0; i < D; ++i) {
    if (first[i] > own[i] || last[i] < own[i]) throw std::logic_error("quadtree covering_nodes: the box does not hold p");
    const std::uint32_t side = first[i] < own[i] ? 0 : last[i] > own[i] ? 2 : 1;
    code |= side << (kLevelBits + 2 * i);
  }
  cover_nodes(p, code, out);
  return code;
}

template <int D>
void Quadtree<D>::cover_nodes(const Point<D>& p, std::uint32_t code, std::vector<NodeId>& out) const {
  out.clear();
  const int level = int(code & ((1u << kLevelBits) - 1));
  Coords first = cell_of(p, level), last = first;
  for (int i = 0; i < D; ++i) {
    const std::uint32_t side = code >> (kLevelBits + 2 * i) & 3u;
    if (side == 0) --first[i];
    if (side == 2) ++last[i];
  }
  for_each_index_in_box<D>(first, last, [&](const Coords& c) {
    const NodeId n = deepest_containing(level, c);
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  });
}

template <int D>
NodeId Quadtree<D>::locate(const Point<D>& p, NodeId hint) const {
  int level = hint == kNoNode ? 0 : std::max(0, int(nodes_[hint].level));
  NodeId n = deepest_containing(level, cell_of(p, level), level);
  while (!is_leaf(n)) {
    const Coords c = cell_of(p, ++level);
    int k = 0;
    for (int i = 0; i < D; ++i) k |= int(c[i] & 1u) << i;
    n = search_[n].first_child + NodeId(k);
  }
  return n;
}

template <int D>
bool Quadtree<D>::cell_in_domain(int level, const std::array<std::int64_t, D>& c) const {
  const std::int64_t cells = std::int64_t(1) << level;
  for (int i = 0; i < D; ++i)
    if (c[i] < 0 || c[i] >= cells) return false;
  return true;
}

// Calls f(coords) for every cell at `level` within `reach` cells of c (c itself included) in the domain.
template <int D>
template <class F>
void Quadtree<D>::for_each_neighbour_cell(int level, const Coords& c, int reach, F&& f) const {
  std::array<std::int64_t, D> first, last;
  for (int i = 0; i < D; ++i) {
    first[i] = std::int64_t(c[i]) - reach;
    last[i] = std::int64_t(c[i]) + reach;
  }
  for_each_index_in_box<D>(first, last, [&](const std::array<std::int64_t, D>& q) {
    if (!cell_in_domain(level, q)) return;
    Coords qc;
    for (int i = 0; i < D; ++i) qc[i] = std::uint64_t(q[i]);
    f(qc);
  });
}

template <int D>
std::uint32_t Quadtree<D>::inputs_in_cell(int level, const Coords& c, std::span<const Point<D>> positions) const {
  if (level > kMaxLevel) throw PointInputError("input points closer than the engine's resolution (2^-40 of the box side)", {});
  const NodeId n = deepest_containing(level, c);
  const Record& nd = nodes_[n];
  if (nd.level == level) return input_count(n);
  // A leaf above the cell: its input points (one but during add_input) may or may not lie in the cell.
  std::uint32_t count = 0;
  for (const LeafVertex<D>& e : leaf_vertices(search_[n]))
    if (e.tag == 0 && cell_of(positions[e.id], level) == c) ++count;
  return count;
}

// The crowding rule, written once for the build (counts by Morton ranges) and for updates (counts from
// the tree): a cell with one input is crowded when another input lies in the ring of finer cells
// (kCrowdingMargin levels down) around it. Only same-size neighbours holding an input are looked into.
template <int D>
template <class Count>
bool Quadtree<D>::crowded_by(int level, const Coords& c, std::uint32_t own, Count&& count) const {
  if (own == 0) return false;
  if (own >= 2) return true;
  const int fine = level + kCrowdingMargin;
  const std::int64_t s = std::int64_t(1) << kCrowdingMargin;
  bool found = false;
  for_each_neighbour_cell(level, c, 1, [&](const Coords& q) {
    if (found || q == c || count(level, q) == 0) return;
    // Fine cells of q within one fine cell of c's block.
    std::array<std::int64_t, D> lo, hi;
    for (int i = 0; i < D; ++i) {
      lo[i] = std::max(std::int64_t(c[i]) * s - 1, std::int64_t(q[i]) * s);
      hi[i] = std::min(std::int64_t(c[i]) * s + s, std::int64_t(q[i]) * s + s - 1);
    }
    for_each_index_in_box<D>(lo, hi, [&](const std::array<std::int64_t, D>& r) {
      if (found) return;
      Coords fc;
      for (int i = 0; i < D; ++i) fc[i] = std::uint64_t(r[i]);
      found = count(fine, fc) > 0;
    });
  });
  return found;
}

template <int D>
bool Quadtree<D>::crowded(NodeId n, std::span<const Point<D>> positions) const {
  const Record& nd = nodes_[n];
  return crowded_by(nd.level, nd.coords(), input_count(n),
                    [&](int level, const Coords& q) { return inputs_in_cell(level, q, positions); });
}

// Calls f(node) for every node whose 3^D block contains p: at each level, the existing cells among the
// 3^D around p's cell. Deeper levels are searched while any such cell exists (a node near p at a finer
// level has an ancestor near p at every coarser level).
template <int D>
template <class F>
void Quadtree<D>::for_each_node_near(const Point<D>& p, F&& f) const {
  for (int level = 0; level <= kMaxLevel; ++level) {
    bool any = false;
    for_each_neighbour_cell(level, cell_of(p, level), 1, [&](const Coords& q) {
      const NodeId n = find(level, q);
      if (n == kNoNode) return;
      any = true;
      f(n);
    });
    if (!any) return;
  }
}

// Whether internal node n must stay split: crowded, or a node two levels finer touches it. A finer node
// inside n exists iff one of n's children is internal; one outside n exists iff an internal node at
// level+1 touches n from outside.
template <int D>
bool Quadtree<D>::required_split(NodeId n, std::span<const Point<D>> positions) const {
  const Record& nd = nodes_[n];
  if (crowded(n, positions)) return true;
  for (int k = 0; k < kChildren; ++k)
    if (!is_leaf(search_[n].first_child + NodeId(k))) return true;
  // Level+1 cells touching n from outside: within one cell of n's children's block.
  const int level = nd.level + 1;
  std::array<std::int64_t, D> first, last;
  for (int i = 0; i < D; ++i) {
    first[i] = 2 * std::int64_t(nd.coord(i)) - 1;
    last[i] = 2 * std::int64_t(nd.coord(i)) + 2;
  }
  bool touched = false;
  for_each_index_in_box<D>(first, last, [&](const std::array<std::int64_t, D>& q) {
    if (touched || !cell_in_domain(level, q)) return;
    bool outside = false;
    for (int i = 0; i < D; ++i) outside = outside || q[i] == first[i] || q[i] == last[i];
    if (!outside) return;
    Coords qc;
    for (int i = 0; i < D; ++i) qc[i] = std::uint64_t(q[i]);
    const NodeId m = find(level, qc);
    touched = m != kNoNode && !is_leaf(m);
  });
  return touched;
}

// Makes every leaf in `worklist` (and every leaf this creates) balanced against its neighbours: for a
// leaf at level L, each level-L cell that touches it lies in a node of level >= L-1.
template <int D>
void Quadtree<D>::balance_around(std::vector<NodeId>& worklist, std::vector<NodeId>* created_leaves,
                                 std::vector<NodeId>* split_leaves) {
  // Deepest first: forced splits only create leaves at coarser levels, which are checked later.
  std::vector<std::vector<NodeId>> by_level(kMaxLevel + 1);
  for (NodeId n : worklist) by_level[nodes_[n].level].push_back(n);
  worklist.clear();
  std::vector<NodeId> created;
  for (int level = kMaxLevel; level >= 2; --level) {
    for (std::size_t idx = 0; idx < by_level[level].size(); ++idx) {
      const NodeId s = by_level[level][idx];
      if (nodes_[s].level != level || !is_leaf(s)) continue;
      const Coords sc = nodes_[s].coords();
      // The 3^D neighbour cells lie in at most 2^D parent cells: each is looked up once (splits only
      // deepen the tree, so a parent cell made deep enough stays so).
      Coords done[1 << D];
      int done_count = 0;
      for_each_neighbour_cell(level, sc, 1, [&](const Coords& q) {
        Coords pc;
        for (int i = 0; i < D; ++i) pc[i] = q[i] >> 1;
        if (std::find(done, done + done_count, pc) != done + done_count) return;
        done[done_count++] = pc;
        NodeId n = deepest_containing(level - 1, pc);
        while (nodes_[n].level < level - 1) {
          created.clear();
          if (split_leaves) split_leaves->push_back(n);
          split(n, &created);
          for (NodeId ch : created) {
            by_level[nodes_[ch].level].push_back(ch);
            if (created_leaves) created_leaves->push_back(ch);
          }
          n = deepest_containing(level - 1, pc);
        }
      });
    }
  }
}

namespace {

// Morton codes by table: kSpread<D>[b] puts bit j of byte b at bit D j, so a coordinate's 5 bytes
// (coordinates are below 2^40) are spread with 5 look-ups instead of a loop over its 40 bits.
template <int D>
constexpr auto kSpread = [] {
  std::array<std::uint32_t, 256> t{};
  for (int b = 0; b < 256; ++b)
    for (int j = 0; j < 8; ++j)
      if (b >> j & 1) t[std::size_t(b)] |= 1u << (D * j);
  return t;
}();

// The Morton code of cell c (bit b of axis i at bit D b + i): a cell holds the finer cells whose codes
// have its code as prefix, so the inputs sorted by code list every cell's inputs as one range.
template <int D>
CellKey interleave(const std::array<std::uint64_t, D>& c) {
  CellKey code = 0;
  for (int i = 0; i < D; ++i) {
    CellKey spread = 0;
    for (int byte = 0; byte < 5; ++byte) spread |= CellKey(kSpread<D>[(c[i] >> (8 * byte)) & 0xff]) << (D * 8 * byte);
    code |= spread << i;
  }
  return code;
}

// The inverse: kGather<D>[phase][b][i] packs the bits of byte b that belong to axis i when the byte's
// first bit is bit `phase` (mod D) of a code.
template <int D>
constexpr auto kGather = [] {
  std::array<std::array<std::array<std::uint8_t, D>, 256>, D> t{};
  for (int phase = 0; phase < D; ++phase)
    for (int b = 0; b < 256; ++b) {
      std::array<int, D> next{};
      for (int m = 0; m < 8; ++m) {
        const int axis = (phase + m) % D;
        if (b >> m & 1) t[std::size_t(phase)][std::size_t(b)][std::size_t(axis)] |= std::uint8_t(1u << next[std::size_t(axis)]);
        ++next[std::size_t(axis)];
      }
    }
  return t;
}();

template <int D>
std::array<std::uint64_t, D> deinterleave(CellKey code) {
  std::array<std::uint64_t, D> c{};
  for (int byte = 0; code != 0; ++byte, code >>= 8) {
    const int first = 8 * byte;
    const auto& g = kGather<D>[std::size_t(first % D)][std::size_t(code & 0xff)];
    for (int i = 0; i < D; ++i) c[std::size_t(i)] |= std::uint64_t(g[std::size_t(i)]) << ((first + D - 1 - i) / D);
  }
  return c;
}

}  // namespace

// The build makes the canonical tree in three passes instead of splitting leaf by leaf:
//  1. crowding: a depth-first descent over the inputs sorted by Morton code (a cell's inputs are a
//     contiguous range) lists the crowded cells per level; they are closed under ancestors.
//  2. balance, per level from the deepest up: a cell of level K is internal iff it is crowded or touches
//     an internal cell of level K+1 (a node two levels finer than it touches it iff such a cell does).
//     The cells of level K touching an internal cell h of level K+1 are, per axis, (h-1)/2 .. (h+1)/2.
//  3. nodes: one depth-first descent allocates each internal node's children as it visits the node, the
//     arrays reserved to their final size (the count of internal cells is known), children in Morton
//     order, so the node ids run along the curve.
// The result is the same minimal fixed point as splitting and balance_around (tests/engine compares the
// build with a tree made by add_input one point at a time).
template <int D>
void Quadtree<D>::build(std::span<const Point<D>> inputs, std::span<const VertexId> ids, bool editable) {
  editable_ = editable;
  nodes_.clear();
  search_.clear();
  block_inputs_.clear();
  if (!editable) block_inputs_.shrink_to_fit();
  free_blocks_.clear();
  pool_.clear();
  pool_.shrink_to_fit();
  for (auto& free : free_arrays_) free.clear();
  map_.clear();
  leaf_count_ = 1;
  if (inputs.empty()) {
    make_root();
    return;
  }
  const std::size_t n = inputs.size();

  // Sort the inputs by Morton code at the finest level: every cell is then a contiguous range.
  struct Keyed {
    CellKey code;
    std::uint32_t index;
  };
  std::vector<Keyed> keyed(n);
  for (std::size_t i = 0; i < n; ++i) keyed[i] = {interleave<D>(cell_of(inputs[i], kMaxLevel)), std::uint32_t(i)};
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) { return a.code < b.code; });
  for (std::size_t i = 1; i < n; ++i)
    if (keyed[i].code == keyed[i - 1].code)
      throw PointInputError("input points " + std::to_string(keyed[i - 1].index) + " and " +
                                std::to_string(keyed[i].index) +
                                " are closer than the engine's resolution (2^-40 of the box side)",
                            {keyed[i - 1].index, keyed[i].index});
  std::vector<CellKey> codes(n);
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) {
    codes[i] = keyed[i].code;
    order[i] = keyed[i].index;
  }
  std::vector<Keyed>().swap(keyed);
  // The inputs of the cell of `level` with Morton code `key`, searched within [b, e) (a range holding it).
  auto range_of = [&](int level, CellKey key, std::uint32_t b, std::uint32_t e) {
    const int shift = D * (kMaxLevel - level);
    const CellKey lo = key << shift;
    const CellKey hi = lo + (CellKey(1) << shift);
    const auto first = std::lower_bound(codes.begin() + b, codes.begin() + e, lo);
    const auto last = std::lower_bound(first, codes.begin() + e, hi);
    return std::pair<std::uint32_t, std::uint32_t>(std::uint32_t(first - codes.begin()), std::uint32_t(last - codes.begin()));
  };
  // The inputs of child k of the cell (level, key) that holds [b, e): children split the range in order.
  auto child_ranges = [&](int level, CellKey key, std::uint32_t b, std::uint32_t e) {
    std::array<std::uint32_t, kChildren + 1> at;
    at[0] = b;
    at[kChildren] = e;
    const int shift = D * (kMaxLevel - level - 1);
    for (int k = 1; k < kChildren; ++k) {
      const CellKey lo = ((key << D) | CellKey(k)) << shift;
      std::uint32_t j = at[std::size_t(k - 1)];
      if (e - j <= 16)
        while (j < e && codes[j] < lo) ++j;
      else
        j = std::uint32_t(std::lower_bound(codes.begin() + j, codes.begin() + e, lo) - codes.begin());
      at[std::size_t(k)] = j;
    }
    return at;
  };

  // 1. Crowding. A cell with one input (sorted index b) is crowded when another input's cell two levels
  // finer lies within one such cell of the cell's block: such an input lies in a neighbour cell q, found
  // by binary search within the range of the common ancestor of the cell and q (held on the path).
  using Path = std::array<std::pair<std::uint32_t, std::uint32_t>, kMaxLevel + 1>;
  auto fine_cell = [&](std::uint32_t sorted, int fine) {
    if (fine > kMaxLevel) return cell_of(inputs[order[sorted]], fine);
    Coords c = deinterleave<D>(codes[sorted]);
    for (int i = 0; i < D; ++i) c[i] >>= (kMaxLevel - fine);
    return c;
  };
  auto ring_crowded = [&](const Path& path, int level, const Coords& c) {
    const int fine = level + kCrowdingMargin;
    const std::int64_t s = std::int64_t(1) << kCrowdingMargin;
    bool found = false;
    for_each_neighbour_cell(level, c, 1, [&](const Coords& q) {
      if (found || q == c) return;
      int lca = level;
      for (int i = 0; i < D; ++i) lca = std::min(lca, level - int(std::bit_width(c[i] ^ q[i])));
      const auto [qb, qe] = range_of(level, interleave<D>(q), path[std::size_t(lca)].first, path[std::size_t(lca)].second);
      std::array<std::int64_t, D> lo, hi;
      for (int i = 0; i < D; ++i) {
        lo[i] = std::max(std::int64_t(c[i]) * s - 1, std::int64_t(q[i]) * s);
        hi[i] = std::min(std::int64_t(c[i]) * s + s, std::int64_t(q[i]) * s + s - 1);
      }
      if (qe - qb <= std::uint32_t(kChildren)) {
        // Few inputs (always below level 39, where the finer cells have no Morton code): test each.
        for (std::uint32_t u = qb; u < qe && !found; ++u) {
          const Coords f = fine_cell(u, fine);
          bool inside = true;
          for (int i = 0; i < D; ++i) inside = inside && std::int64_t(f[i]) >= lo[i] && std::int64_t(f[i]) <= hi[i];
          found = inside;
        }
        return;
      }
      for_each_index_in_box<D>(lo, hi, [&](const std::array<std::int64_t, D>& r) {
        if (found) return;
        Coords fc;
        for (int i = 0; i < D; ++i) fc[i] = std::uint64_t(r[i]);
        const auto [fb, fe] = range_of(fine, interleave<D>(fc), qb, qe);
        found = fe > fb;
      });
    });
    return found;
  };
  // internal[L]: the Morton codes of the internal cells of level L, ascending.
  std::vector<std::vector<CellKey>> internal(kMaxLevel + 1);
  {
    struct Task {
      Coords c;
      CellKey key;
      std::uint32_t b, e;
      int level;
    };
    // The cells of the subtree of `first` in depth-first order, children of the cells of `stop_level`
    // left for later (`deferred`, with the path to them). Child 0 is popped first: each level's cells
    // come out in Morton order.
    struct Subtree {
      Task first;
      Path path;
    };
    auto expand = [&](const Subtree& from, std::vector<std::vector<CellKey>>& out, int stop_level,
                      std::vector<Subtree>* deferred) {
      Path path = from.path;
      std::vector<Task> tasks{from.first};
      while (!tasks.empty()) {
        const Task t = tasks.back();
        tasks.pop_back();
        path[std::size_t(t.level)] = {t.b, t.e};
        const std::uint32_t count = t.e - t.b;
        if (count == 0 || (count == 1 && !ring_crowded(path, t.level, t.c))) continue;
        if (t.level == stop_level) {
          deferred->push_back({t, path});
          continue;
        }
        if (t.level >= kMaxLevel)
          throw PointInputError("input points are closer than the engine's resolution (2^-40 of the box side)", {});
        out[std::size_t(t.level)].push_back(t.key);
        const auto at = child_ranges(t.level, t.key, t.b, t.e);
        for (int k = kChildren; k-- > 0;) {
          Coords cc;
          for (int i = 0; i < D; ++i) cc[i] = 2 * t.c[i] + ((k >> i) & 1);
          tasks.push_back({cc, (t.key << D) | CellKey(k), at[std::size_t(k)], at[std::size_t(k + 1)], t.level + 1});
        }
      }
    };
    // The coarse levels on this thread; the subtrees of the internal cells of level kSplit (a few hundred
    // at most) on every thread, their lists joined in Morton order: the same lists as one pass.
    constexpr int kSplit = D == 2 ? 4 : 3;
    std::vector<Subtree> subtrees;
    expand({{Coords{}, 0, 0, std::uint32_t(n), 0}, Path{}}, internal, kSplit, &subtrees);
    std::vector<std::vector<std::vector<CellKey>>> parts(subtrees.size());
    tbb::parallel_for(std::size_t(0), subtrees.size(), [&](std::size_t k) {
      parts[k].resize(kMaxLevel + 1);
      expand(subtrees[k], parts[k], -1, nullptr);
    });
    for (int level = kSplit; level <= kMaxLevel; ++level) {
      std::size_t size = 0;
      for (const auto& part : parts) size += part[std::size_t(level)].size();
      internal[std::size_t(level)].reserve(size);
      for (const auto& part : parts)
        internal[std::size_t(level)].insert(internal[std::size_t(level)].end(), part[std::size_t(level)].begin(),
                                            part[std::size_t(level)].end());
    }
  }

  // 2. Balance, deepest level first.
  int deepest = kMaxLevel;
  while (deepest > 0 && internal[std::size_t(deepest)].empty()) --deepest;
  std::size_t internal_count = internal[std::size_t(deepest)].size();
  for (int level = deepest - 1; level >= 0; --level) {
    std::vector<CellKey>& cells = internal[std::size_t(level)];
    const std::uint64_t top = (std::uint64_t(1) << level) - 1;
    // The finer level's cells come in Morton order, siblings together: the cells touching one parent's
    // internal children are listed once per parent.
    CellKey group_parent = ~CellKey(0);
    CellKey group[1 << (2 * D)];
    int group_count = 0;
    for (const CellKey h : internal[std::size_t(level + 1)]) {
      if ((h >> D) != group_parent) {
        group_parent = h >> D;
        group_count = 0;
      }
      const Coords hc = deinterleave<D>(h);
      Coords first, last;
      for (int i = 0; i < D; ++i) {
        first[i] = hc[i] == 0 ? 0 : (hc[i] - 1) >> 1;
        last[i] = std::min(top, (hc[i] + 1) >> 1);
      }
      for_each_index_in_box<D>(first, last, [&](const Coords& q) {
        const CellKey key = interleave<D>(q);
        if (std::find(group, group + group_count, key) != group + group_count) return;
        group[group_count++] = key;
        cells.push_back(key);
      });
    }
    // Equal keys are the same cell: any sort gives the same list, on every thread.
    tbb::parallel_sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    internal_count += cells.size();
  }

  // 3. Nodes, depth first, each internal node's children allocated when it is visited.
  std::size_t compact_cells = 0;
  for (int level = 0; level <= std::min(deepest, kCompactLevels<D>); ++level) compact_cells += internal[std::size_t(level)].size();
  map_.reserve(compact_cells, internal_count - compact_cells, editable_);
  const std::size_t node_count = kChildren * (1 + internal_count);
  // An editable tree gets a sixteenth more, room for the edits that follow.
  const std::size_t room = editable_ ? node_count + node_count / 16 : node_count;
  nodes_.reserve(room);
  search_.reserve(room);
  if (editable_) block_inputs_.reserve(room / kChildren);
  make_root();
  pool_.reserve(n);
  std::array<std::size_t, kMaxLevel + 1> next{};  // per level: the next internal cell in Morton order
  struct Visit {
    NodeId node;
    CellKey key;
    std::uint32_t b, e;
  };
  std::vector<Visit> visits{{root(), 0, 0, std::uint32_t(n)}};
  // The map's slots are scattered over a table larger than the caches: each cell's is fetched while the
  // next few cells are visited, and the cells are inserted in the order visited (the same table).
  constexpr std::size_t kMapAhead = 16;
  struct MapEntry {
    int level;
    Coords c;
    NodeId first;
  };
  std::array<MapEntry, kMapAhead> map_pending;
  std::size_t map_count = 0;
  while (!visits.empty()) {
    const Visit t = visits.back();
    visits.pop_back();
    const int level = nodes_[t.node].level;
    const std::vector<CellKey>& cells = internal[std::size_t(level)];
    std::size_t& at_level = next[std::size_t(level)];
    if (at_level == cells.size() || cells[at_level] != t.key) {
      if (t.e > t.b) {
        leaf_push(t.node, {inputs[order[t.b]], 0, ids[order[t.b]]});
      }
      continue;
    }
    ++at_level;
    const NodeId first = NodeId(nodes_.size());
    nodes_.resize(nodes_.size() + kChildren);
    search_.resize(nodes_.size());
    if (editable_) block_inputs_.push_back(t.e - t.b);
    search_[t.node].first_child = first;
    const Coords pc = nodes_[t.node].coords();
    map_.prefetch<D>(level, pc);
    MapEntry& entry = map_pending[map_count++ % kMapAhead];
    if (map_count > kMapAhead) map_.insert<D>(entry.level, entry.c, entry.first);
    entry = {level, pc, first};
    leaf_count_ += kChildren - 1;
    const auto at = child_ranges(level, t.key, t.b, t.e);
    for (int k = 0; k < kChildren; ++k) {
      Coords cc;
      for (int i = 0; i < D; ++i) cc[i] = 2 * pc[i] + ((k >> i) & 1);
      Record& ch = nodes_[first + NodeId(k)];
      ch.level = std::int8_t(level + 1);
      ch.set_coords(cc);
      search_[first + NodeId(k)].parent = t.node;
    }
    for (int k = kChildren; k-- > 0;)
      visits.push_back({first + NodeId(k), (t.key << D) | CellKey(k), at[std::size_t(k)], at[std::size_t(k + 1)]});
  }
  for (std::size_t k = map_count > kMapAhead ? map_count - kMapAhead : 0; k < map_count; ++k) {
    const MapEntry& entry = map_pending[k % kMapAhead];
    map_.insert<D>(entry.level, entry.c, entry.first);
  }
  for (int level = 0; level <= kMaxLevel; ++level)
    if (next[std::size_t(level)] != internal[std::size_t(level)].size()) throw std::logic_error("quadtree build: an internal cell without a parent");
  // The occupied masks bottom-up: children are allocated after their parent.
  for (NodeId m = NodeId(nodes_.size()); m-- > 0;) sync_search(m);
}

template <int D>
typename Quadtree<D>::Change Quadtree<D>::add_input(VertexId id, std::span<const Point<D>> positions) {
  if (!editable_) throw std::logic_error("quadtree add_input on a one-shot tree");
  Change change;
  const Point<D>& p = positions[id];
  NodeId leaf = locate(p);
  for (NodeId a = search_[leaf].parent; a != kNoNode; a = search_[a].parent) ++block_inputs_[search_[a].first_child / kChildren];
  // The leaf may now hold two inputs (two vertices of tag 0); every other leaf keeps at most one.
  leaf_push(leaf, {p, 0, id});
  if (search_[leaf].occupied_or_size == 1) mark_occupied(leaf);

  // Leaves whose 3^D block contains p may have become crowded: at every level, the cells around p's.
  std::vector<NodeId> work;
  for_each_node_near(p, [&](NodeId n) {
    if (n != leaf && is_leaf(n) && input_count(n) > 0) work.push_back(n);
  });
  // p's own leaf first (the stack is LIFO): until it is split down, it may hold two inputs, and counts
  // in the crowding test of its neighbours see only one of them.
  work.push_back(leaf);
  std::vector<NodeId> balance_work, created;
  while (!work.empty()) {
    const NodeId n = work.back();
    work.pop_back();
    if (!is_leaf(n) || !crowded(n, positions)) continue;
    change.removed_leaves.push_back(n);
    created.clear();
    split(n, &created);
    for (NodeId ch : created) {
      change.new_leaves.push_back(ch);
      balance_work.push_back(ch);
      if (input_count(ch) > 0) work.push_back(ch);
    }
  }
  std::vector<NodeId> more_created, more_split;
  balance_around(balance_work, &more_created, &more_split);
  change.removed_leaves.insert(change.removed_leaves.end(), more_split.begin(), more_split.end());
  change.new_leaves.insert(change.new_leaves.end(), more_created.begin(), more_created.end());
  // A leaf created and split within this call is neither new nor removed for the caller.
  std::vector<NodeId> transient;
  for (NodeId n : change.new_leaves)
    if (!is_leaf(n)) transient.push_back(n);
  std::sort(transient.begin(), transient.end());
  auto is_transient = [&](NodeId n) { return std::binary_search(transient.begin(), transient.end(), n); };
  std::erase_if(change.new_leaves, is_transient);
  std::erase_if(change.removed_leaves, is_transient);
  return change;
}

template <int D>
typename Quadtree<D>::Change Quadtree<D>::remove_input(VertexId id, std::span<const Point<D>> positions) {
  if (!editable_) throw std::logic_error("quadtree remove_input on a one-shot tree");
  Change change;
  const Point<D>& p = positions[id];
  const NodeId leaf = locate(p);
  const auto vs = leaf_vertices(leaf);
  auto it = std::find_if(vs.begin(), vs.end(), [&](const LeafVertex<D>& e) { return e.id == id; });
  if (it == vs.end() || it->tag != 0) throw std::logic_error("quadtree remove_input: vertex is not an input of its leaf");
  // The others keep their order (a fresh array would list them in the same order).
  std::copy(it + 1, vs.end(), it);
  leaf_erase(leaf, vs.size() - 1);
  if (search_[leaf].occupied_or_size == 0) mark_vacated(leaf);
  for (NodeId a = search_[leaf].parent; a != kNoNode; a = search_[a].parent) --block_inputs_[search_[a].first_child / kChildren];

  // Internal nodes whose block contained p may no longer be crowded; merging one can release its
  // level-1 neighbours (they were kept split by its children). Finest level first.
  std::vector<std::vector<NodeId>> candidates(kMaxLevel + 1);
  for_each_node_near(p, [&](NodeId n) {
    if (!is_leaf(n)) candidates[std::size_t(nodes_[n].level)].push_back(n);
  });
  std::vector<NodeId> merged;
  for (int level = kMaxLevel; level >= 0; --level) {
    auto& list = candidates[level];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    for (NodeId n : list) {
      if (nodes_[n].level != level || is_leaf(n) || required_split(n, positions)) continue;
      merge(n, &change.removed_leaves);
      merged.push_back(n);
      if (level == 0) continue;
      Coords pc;
      for (int i = 0; i < D; ++i) pc[i] = nodes_[n].coord(i) >> 1;
      for_each_neighbour_cell(level - 1, pc, 1, [&](const Coords& q) {
        const NodeId m = find(level - 1, q);
        if (m != kNoNode && !is_leaf(m)) candidates[level - 1].push_back(m);
      });
    }
  }
  // Removed leaves include children of merged nodes; merged nodes that merged again upward are gone.
  for (NodeId n : merged)
    if (nodes_[n].level >= 0 && is_leaf(n)) change.new_leaves.push_back(n);
  std::vector<NodeId> gone = change.removed_leaves;
  std::sort(gone.begin(), gone.end());
  std::erase_if(change.new_leaves, [&](NodeId n) { return std::binary_search(gone.begin(), gone.end(), n); });
  return change;
}

template <int D>
NodeId Quadtree<D>::insert_vertex(VertexId id, const Point<D>& p, std::uint32_t tag, NodeId hint) {
  const NodeId leaf = locate(p, hint);
  insert_vertex_at(leaf, id, p, tag);
  return leaf;
}

template <int D>
void Quadtree<D>::insert_vertex_at(NodeId leaf, VertexId id, const Point<D>& p, std::uint32_t tag) {
  if (tag == 0) throw std::logic_error("quadtree insert_vertex: tag 0 marks an input");
  leaf_push(leaf, {p, tag, id});
  if (search_[leaf].occupied_or_size == 1) mark_occupied(leaf);
}

template <int D>
void Quadtree<D>::rename_vertices(std::span<const VertexId> new_id) {
  // The pool is packed afresh, the leaves' arrays in node order (nodes are numbered along the curve)
  // with no free block between them: Steiner vertices grew the arrays at the times they arrived, so
  // neighbouring leaves' arrays lay far apart. With room for an eighth more, as the engine's other
  // arrays after a build: packed full, the first leaf an update grew made the pool grow by half
  // (pool_allocate), 16 bytes per output vertex at 2D n = 1e6.
  std::size_t slots = 0;
  for (NodeId n = 0; n < nodes_.size(); ++n)
    if (nodes_[n].level >= 0 && is_leaf(n)) slots += class_capacity(size_class_for(search_[n].occupied_or_size));
  std::vector<LeafVertex<D>> packed;
  packed.reserve(slots + slots / 8 + 1024);
  packed.resize(slots);
  std::size_t next = 0;
  for (NodeId n = 0; n < nodes_.size(); ++n) {
    Record& nd = nodes_[n];
    if (nd.level < 0) continue;  // a free slot
    if (!is_leaf(n)) continue;
    SearchEntry& e = search_[n];
    for (std::uint32_t j = 0; j < e.occupied_or_size; ++j) {
      packed[next + j] = pool_[e.vertices + j];
      packed[next + j].id = new_id[packed[next + j].id];
    }
    nd.size_class = std::uint8_t(size_class_for(e.occupied_or_size));
    e.vertices = std::uint32_t(nd.size_class == 0 ? 0 : next);
    next += class_capacity(nd.size_class);
  }
  pool_ = std::move(packed);
  for (auto& free : free_arrays_) {
    free.clear();
    free.shrink_to_fit();
  }
}

template <int D>
void Quadtree<D>::erase_vertex(VertexId id, NodeId leaf) {
  const auto vs = leaf_vertices(leaf);
  auto it = std::find_if(vs.begin(), vs.end(), [&](const LeafVertex<D>& e) { return e.id == id; });
  if (it == vs.end()) throw std::logic_error("quadtree erase_vertex: vertex not in leaf");
  leaf_erase(leaf, std::size_t(it - vs.begin()));
  if (search_[leaf].occupied_or_size == 0) mark_vacated(leaf);
}

template <int D>
std::vector<std::pair<int, typename Quadtree<D>::Coords>> Quadtree<D>::leaf_cells() const {
  std::vector<std::pair<int, Coords>> cells;
  for (NodeId n = 0; n < nodes_.size(); ++n)
    if (nodes_[n].level >= 0 && is_leaf(n) && (search_[n].parent != kNoNode || n == root()))
      cells.emplace_back(nodes_[n].level, nodes_[n].coords());
  std::sort(cells.begin(), cells.end());
  return cells;
}

template <int D>
std::size_t Quadtree<D>::memory_bytes() const {
  std::size_t bytes = nodes_.capacity() * sizeof(Record) + search_.capacity() * sizeof(SearchEntry) +
                      block_inputs_.capacity() * sizeof(std::uint32_t) + map_.memory_bytes() +
                      free_blocks_.capacity() * sizeof(NodeId) + pool_.capacity() * sizeof(LeafVertex<D>);
  for (const auto& free : free_arrays_) bytes += free.capacity() * sizeof(std::uint32_t);
  return bytes;
}

template <int D>
void Quadtree<D>::check_valid(std::span<const Point<D>> positions) const {
  auto fail = [](const std::string& what) { throw std::logic_error("quadtree invalid: " + what); };
  if (!editable_) {
    // The counts a one-shot tree leaves out, from its leaves (inputs have tag 0; a build numbers every
    // node after its parent), then the checks of an editable tree.
    Quadtree<D> full = *this;
    full.editable_ = true;
    full.block_inputs_.assign(nodes_.size() / kChildren, 0);
    std::vector<std::uint32_t> count(nodes_.size(), 0);
    for (NodeId n = NodeId(nodes_.size()); n-- > 0;) {
      if (nodes_[n].level < 0) continue;
      if (is_leaf(n))
        count[n] = input_count(n);
      else
        full.block_inputs_[search_[n].first_child / kChildren] = count[n];
      if (search_[n].parent != kNoNode) {
        if (search_[n].parent >= n) fail("a one-shot tree's node numbered before its parent");
        count[search_[n].parent] += count[n];
      }
    }
    full.check_valid(positions);
    return;
  }
  if (nodes_.size() != search_.size() || nodes_.size() % kChildren != 0 || block_inputs_.size() != nodes_.size() / kChildren) fail("node arrays");
  std::size_t leaves = 0;
  // Every pool slot lies in exactly one block: a leaf's or a free one.
  std::vector<std::pair<std::size_t, std::size_t>> blocks;  // (offset, capacity)
  for (int c = 1; c < kSizeClasses; ++c)
    for (std::uint32_t offset : free_arrays_[std::size_t(c)]) blocks.emplace_back(offset, class_capacity(c));
  for (NodeId n = 0; n < nodes_.size(); ++n) {
    const Record& nd = nodes_[n];
    const SearchEntry& se = search_[n];
    if (nd.level < 0) {
      if (nd.size_class != 0 || se.first_child != kNoNode || se.occupied_or_size != 0) fail("free slot " + std::to_string(n) + " in use");
      continue;
    }
    if (n != 0 && (se.parent == kNoNode || is_leaf(se.parent))) continue;  // unreachable slot
    if (n != 0 && (n - search_[se.parent].first_child) >= NodeId(kChildren))
      fail("parent link of node " + std::to_string(n));
    if (find(nd.level, nd.coords()) != n) fail("cell map does not point to node " + std::to_string(n));
    if (is_leaf(n)) {
      ++leaves;
      const std::size_t capacity = class_capacity(nd.size_class);
      // Blocks grow by doubling when full and shrink to fit at a quarter full: an empty leaf holds none.
      if (se.occupied_or_size > capacity || (capacity > 0 && 4 * std::size_t(se.occupied_or_size) <= capacity))
        fail("leaf " + std::to_string(n) + "'s array: " + std::to_string(se.occupied_or_size) + " vertices in a block of " + std::to_string(capacity));
      if (capacity > 0) {
        if (se.vertices + capacity > pool_.size()) fail("leaf " + std::to_string(n) + "'s array outside the pool");
        blocks.emplace_back(se.vertices, capacity);
      }
      for (const LeafVertex<D>& e : leaf_vertices(se)) {
        if (e.position != positions[e.id]) fail("leaf's copy of a vertex position");
        if (cell_of(e.position, nd.level) != nd.coords()) fail("vertex outside its leaf");
      }
      if (input_count(n) > 1) fail("leaf input count");
      if (crowded(n, positions)) fail("crowded leaf at level " + std::to_string(nd.level));
      // Balance: touching leaves differ by at most one level.
      if (nd.level >= 2)
        for_each_neighbour_cell(nd.level, nd.coords(), 1, [&](const Coords& q) {
          Coords pc;
          for (int i = 0; i < D; ++i) pc[i] = q[i] >> 1;
          if (nodes_[deepest_containing(nd.level - 1, pc)].level < nd.level - 1) fail("unbalanced leaves");
        });
    } else {
      if (se.first_child % kChildren != 0) fail("children block of node " + std::to_string(n) + " not aligned");
      if (nd.size_class != 0) fail("internal node holds vertices");
      std::uint32_t sum = 0;
      std::uint32_t occupied = 0;
      for (int k = 0; k < kChildren; ++k) {
        const NodeId c = se.first_child + NodeId(k);
        if (search_[c].parent != n || nodes_[c].level != nd.level + 1) fail("child links");
        sum += input_count(c);
        if (search_[c].occupied_or_size != 0) occupied |= 1u << k;
      }
      // Leaves' sizes are their arrays', so this checks every mask by induction.
      if (se.occupied_or_size != occupied) fail("occupied mask of internal node " + std::to_string(n));
      if (sum != input_count(n)) fail("subtree input count node " + std::to_string(n) + " level " + std::to_string(nd.level) + " count " + std::to_string(input_count(n)) + " sum " + std::to_string(sum));
      if (!required_split(n, positions)) fail("split not required (tree not minimal) at level " + std::to_string(nd.level));
    }
  }
  if (leaves != leaf_count_) fail("leaf count");
  if (map_.size() != (leaves - 1) / (kChildren - 1)) fail("cell map holds other cells than the internal nodes'");
  std::sort(blocks.begin(), blocks.end());
  std::size_t covered = 0;
  for (const auto& [offset, capacity] : blocks) {
    if (offset != covered) fail("leaf pool: slot " + std::to_string(std::min(offset, covered)) + " in no block or in two");
    covered += capacity;
  }
  if (covered != pool_.size()) fail("leaf pool: slots past the last block");
}

template class Quadtree<2>;
template class Quadtree<3>;

}  // namespace shoremesh::engine
