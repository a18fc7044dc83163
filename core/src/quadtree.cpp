#include "shoremesh/engine/quadtree.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "shoremesh/error.hpp"

namespace shoremesh::engine {

namespace {

// Morton code of a cell at the finest level: the bits of the D coordinates interleaved, so that every
// cell at every level is one contiguous range of codes (used to count inputs in a cell during build).
template <int D>
CellKey morton(const std::array<std::uint64_t, D>& c, int level) {
  CellKey code = 0;
  for (int b = level - 1; b >= 0; --b)
    for (int i = D - 1; i >= 0; --i) code = (code << 1) | CellKey((c[i] >> b) & 1u);
  return code;
}

}  // namespace

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
  for (int i = 0; i < D; ++i) p[i] = double(nodes_[n].coords[i]) * s;
  return p;
}

template <int D>
NodeId Quadtree<D>::new_node(NodeId parent, int level, const Coords& coords) {
  NodeId id = NodeId(nodes_.size());
  nodes_.emplace_back();
  search_.emplace_back();
  Node& nd = nodes_.back();
  nd.parent = parent;
  nd.level = level;
  nd.coords = coords;
  map_.insert<D>(level, coords, id);
  return id;
}

template <int D>
NodeId Quadtree<D>::allocate_children() {
  if (!free_blocks_.empty()) {
    NodeId first = free_blocks_.back();
    free_blocks_.pop_back();
    return first;
  }
  NodeId first = NodeId(nodes_.size());
  nodes_.resize(nodes_.size() + kChildren);
  search_.resize(nodes_.size());
  return first;
}

// Turns leaf n into an internal node with 2^D leaf children and hands its vertices down.
template <int D>
void Quadtree<D>::split(NodeId n, std::vector<NodeId>* created) {
  if (nodes_[n].level >= kMaxLevel)
    throw PointInputError("input points closer than the engine's resolution (2^-40 of the box side)", {});
  const NodeId first = allocate_children();
  Node& parent = nodes_[n];
  for (int k = 0; k < kChildren; ++k) {
    Node& ch = nodes_[first + NodeId(k)];
    ch = Node{};
    ch.parent = n;
    ch.level = parent.level + 1;
    for (int i = 0; i < D; ++i) ch.coords[i] = 2 * parent.coords[i] + ((k >> i) & 1);
    map_.insert<D>(ch.level, ch.coords, first + NodeId(k));
    if (created) created->push_back(first + NodeId(k));
  }
  for (const LeafVertex<D>& e : parent.vertices) {
    const Coords c = cell_of(e.position, parent.level + 1);
    int k = 0;
    for (int i = 0; i < D; ++i) k |= int(c[i] & 1u) << i;
    Node& ch = nodes_[first + NodeId(k)];
    ch.vertices.push_back(e);
    if (e.id == parent.input_vertex) {
      ch.input_vertex = e.id;
      ch.input_count = 1;
    }
  }
  parent.vertices.clear();
  parent.vertices.shrink_to_fit();
  parent.input_vertex = kNoVertex;
  parent.first_child = first;
  leaf_count_ += kChildren - 1;
  for (int k = 0; k < kChildren; ++k) sync_search(first + NodeId(k));
  sync_search(n);
}

// Turns internal node n, whose children are all leaves, back into a leaf holding their vertices.
template <int D>
void Quadtree<D>::merge(NodeId n, std::vector<NodeId>* removed) {
  Node& parent = nodes_[n];
  const NodeId first = parent.first_child;
  for (int k = 0; k < kChildren; ++k) {
    Node& ch = nodes_[first + NodeId(k)];
    if (!ch.is_leaf()) throw std::logic_error("quadtree merge of a node with an internal child");
    parent.vertices.insert(parent.vertices.end(), ch.vertices.begin(), ch.vertices.end());
    if (ch.input_vertex != kNoVertex) parent.input_vertex = ch.input_vertex;
    map_.erase<D>(ch.level, ch.coords);
    ch = Node{};
    ch.level = -1;  // marks a free slot
    if (removed) removed->push_back(first + NodeId(k));
  }
  parent.first_child = kNoNode;
  free_blocks_.push_back(first);
  leaf_count_ -= kChildren - 1;
  sync_search(n);
  for (int k = 0; k < kChildren; ++k) sync_search(first + NodeId(k));
}

template <int D>
void Quadtree<D>::sync_search(NodeId n) {
  const Node& nd = nodes_[n];
  SearchEntry& e = search_[n];
  e.first_child = nd.first_child;
  e.vertices = nd.is_leaf() ? nd.vertices.data() : nullptr;
  if (nd.is_leaf()) {
    e.occupied_or_size = std::uint32_t(nd.vertices.size());
    return;
  }
  e.occupied_or_size = 0;
  for (int k = 0; k < kChildren; ++k)
    if (search_[nd.first_child + NodeId(k)].occupied_or_size != 0) e.occupied_or_size |= 1u << k;
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
  for (NodeId n = leaf, p = nodes_[n].parent; p != kNoNode; n = p, p = nodes_[p].parent) {
    std::uint32_t& mask = search_[p].occupied_or_size;
    const bool was_occupied = mask != 0;
    mask |= 1u << (n - nodes_[p].first_child);
    if (was_occupied) return;  // its ancestors already know
  }
}

template <int D>
void Quadtree<D>::mark_vacated(NodeId leaf) {
  for (NodeId n = leaf, p = nodes_[n].parent; p != kNoNode; n = p, p = nodes_[p].parent) {
    std::uint32_t& mask = search_[p].occupied_or_size;
    mask &= ~(1u << (n - nodes_[p].first_child));
    if (mask != 0) return;  // still holds a vertex elsewhere
  }
}

template <int D>
void Quadtree<D>::covering_nodes(const Point<D>& lo_in, const Point<D>& hi_in, std::vector<NodeId>& out) const {
  out.clear();
  Point<D> lo, hi;
  const int level = box_level(lo_in, hi_in, lo, hi);
  const Coords first = cell_of(lo, level), last = cell_of(hi, level);
  for_each_index_in_box<D>(first, last, [&](const Coords& c) {
    const NodeId n = deepest_containing(level, c);
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  });
}

template <int D>
NodeId Quadtree<D>::locate(const Point<D>& p, NodeId hint) const {
  int level = hint == kNoNode ? 0 : nodes_[hint].level;
  NodeId n = deepest_containing(level, cell_of(p, level));
  while (!nodes_[n].is_leaf()) {
    const Coords c = cell_of(p, nodes_[n].level + 1);
    int k = 0;
    for (int i = 0; i < D; ++i) k |= int(c[i] & 1u) << i;
    n = nodes_[n].first_child + NodeId(k);
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
  const Node& nd = nodes_[n];
  if (nd.level == level) return nd.input_count;
  // A leaf above the cell: its (single) input point may or may not lie in the cell.
  if (nd.input_vertex == kNoVertex) return 0;
  return cell_of(positions[nd.input_vertex], level) == c ? 1u : 0u;
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
  const Node& nd = nodes_[n];
  return crowded_by(nd.level, nd.coords, nd.input_count,
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
  const Node& nd = nodes_[n];
  if (crowded(n, positions)) return true;
  for (int k = 0; k < kChildren; ++k)
    if (!nodes_[nd.first_child + NodeId(k)].is_leaf()) return true;
  // Level+1 cells touching n from outside: within one cell of n's children's block.
  const int level = nd.level + 1;
  std::array<std::int64_t, D> first, last;
  for (int i = 0; i < D; ++i) {
    first[i] = 2 * std::int64_t(nd.coords[i]) - 1;
    last[i] = 2 * std::int64_t(nd.coords[i]) + 2;
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
    touched = m != kNoNode && !nodes_[m].is_leaf();
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
      if (nodes_[s].level != level || !nodes_[s].is_leaf()) continue;
      const Coords sc = nodes_[s].coords;
      for_each_neighbour_cell(level, sc, 1, [&](const Coords& q) {
        Coords pc;
        for (int i = 0; i < D; ++i) pc[i] = q[i] >> 1;
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

template <int D>
void Quadtree<D>::build(std::span<const Point<D>> inputs, std::span<const VertexId> ids) {
  nodes_.clear();
  search_.clear();
  free_blocks_.clear();
  map_.clear();
  leaf_count_ = 1;
  new_node(kNoNode, 0, Coords{});
  if (inputs.empty()) return;

  // Sort the inputs by Morton code at the finest level: every cell is then a contiguous range.
  struct Keyed {
    CellKey code;
    std::uint32_t index;
  };
  std::vector<Keyed> keyed(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    keyed[i] = {morton<D>(cell_of(inputs[i], kMaxLevel), kMaxLevel), std::uint32_t(i)};
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) { return a.code < b.code; });
  for (std::size_t i = 1; i < keyed.size(); ++i)
    if (keyed[i].code == keyed[i - 1].code)
      throw PointInputError("input points " + std::to_string(keyed[i - 1].index) + " and " +
                                std::to_string(keyed[i].index) +
                                " are closer than the engine's resolution (2^-40 of the box side)",
                            {keyed[i - 1].index, keyed[i].index});
  auto range_of = [&](int level, const Coords& c) {
    const int shift = D * (kMaxLevel - level);
    const CellKey lo = morton<D>(c, level) << shift;
    const CellKey hi = lo + (CellKey(1) << shift);
    auto b = std::lower_bound(keyed.begin(), keyed.end(), lo, [](const Keyed& k, CellKey v) { return k.code < v; });
    auto e = std::lower_bound(b, keyed.end(), hi, [](const Keyed& k, CellKey v) { return k.code < v; });
    return std::pair<std::size_t, std::size_t>(std::size_t(b - keyed.begin()), std::size_t(e - keyed.begin()));
  };

  // Top-down crowding splits. A node with two inputs is crowded; with one, when a neighbour cell of the
  // same size holds an input too (counted by binary search in the Morton order).
  struct Task {
    NodeId node;
    std::size_t begin, end;
  };
  std::vector<Task> tasks{{0, 0, inputs.size()}};
  std::vector<NodeId> leaves;
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    Node& nd = nodes_[t.node];
    nd.input_count = std::uint32_t(t.end - t.begin);
    const bool is_crowded = crowded_by(nd.level, nd.coords, nd.input_count, [&](int level, const Coords& q) {
      auto [b, e] = range_of(level, q);
      return std::uint32_t(e - b);
    });
    if (!is_crowded) {
      if (nd.input_count == 1) {
        const VertexId v = ids[keyed[t.begin].index];
        nd.input_vertex = v;
        nd.vertices.push_back({inputs[keyed[t.begin].index], 0, v});
      }
      leaves.push_back(t.node);
      continue;
    }
    if (nd.level >= kMaxLevel)
      throw PointInputError("input points are closer than the engine's resolution (2^-40 of the box side)", {});
    const NodeId first = allocate_children();
    Node& parent = nodes_[t.node];
    parent.first_child = first;
    const int level = parent.level + 1;
    const Coords pc = parent.coords;
    leaf_count_ += kChildren - 1;
    for (int k = 0; k < kChildren; ++k) {
      Coords cc;
      for (int i = 0; i < D; ++i) cc[i] = 2 * pc[i] + ((k >> i) & 1);
      Node& ch = nodes_[first + NodeId(k)];
      ch = Node{};
      ch.parent = t.node;
      ch.level = level;
      ch.coords = cc;
      map_.insert<D>(level, cc, first + NodeId(k));
      auto [b, e] = range_of(level, cc);
      tasks.push_back({first + NodeId(k), b, e});
    }
  }
  balance_around(leaves, nullptr, nullptr);
  // The search entries bottom-up: a fresh build appends children after their parent.
  for (NodeId n = NodeId(nodes_.size()); n-- > 0;) sync_search(n);
}

template <int D>
typename Quadtree<D>::Change Quadtree<D>::add_input(VertexId id, std::span<const Point<D>> positions) {
  Change change;
  const Point<D>& p = positions[id];
  NodeId leaf = locate(p);
  for (NodeId a = leaf; a != kNoNode; a = nodes_[a].parent) ++nodes_[a].input_count;
  nodes_[leaf].vertices.push_back({p, 0, id});
  sync_search(leaf);
  if (nodes_[leaf].vertices.size() == 1) mark_occupied(leaf);
  // The one input that may now share a leaf with `id`; every other leaf keeps at most one input.
  const VertexId neighbour = nodes_[leaf].input_vertex;
  if (neighbour == kNoVertex) nodes_[leaf].input_vertex = id;

  // Leaves whose 3^D block contains p may have become crowded: at every level, the cells around p's.
  std::vector<NodeId> work;
  for_each_node_near(p, [&](NodeId n) {
    if (n != leaf && nodes_[n].is_leaf() && nodes_[n].input_count > 0) work.push_back(n);
  });
  // p's own leaf first (the stack is LIFO): until it is split down, it may hold two inputs, and counts
  // in the crowding test of its neighbours see only one of them.
  work.push_back(leaf);
  std::vector<NodeId> balance_work, created;
  while (!work.empty()) {
    const NodeId n = work.back();
    work.pop_back();
    if (!nodes_[n].is_leaf() || !crowded(n, positions)) continue;
    change.removed_leaves.push_back(n);
    created.clear();
    // The leaf of `id` may hold two inputs: hand both down (split itself knows only input_vertex).
    const VertexId own = nodes_[n].input_vertex;
    auto is_input = [&](VertexId v) { return v == id || v == neighbour || v == own; };
    split(n, &created);
    for (NodeId ch : created) {
      Node& c = nodes_[ch];
      c.input_count = 0;
      c.input_vertex = kNoVertex;
      for (const LeafVertex<D>& e : c.vertices)
        if (is_input(e.id)) {
          ++c.input_count;
          c.input_vertex = e.id;
        }
      change.new_leaves.push_back(ch);
      balance_work.push_back(ch);
      if (c.input_count > 0) work.push_back(ch);
    }
  }
  std::vector<NodeId> more_created, more_split;
  balance_around(balance_work, &more_created, &more_split);
  change.removed_leaves.insert(change.removed_leaves.end(), more_split.begin(), more_split.end());
  change.new_leaves.insert(change.new_leaves.end(), more_created.begin(), more_created.end());
  // A leaf created and split within this call is neither new nor removed for the caller.
  std::vector<NodeId> transient;
  for (NodeId n : change.new_leaves)
    if (!nodes_[n].is_leaf()) transient.push_back(n);
  std::sort(transient.begin(), transient.end());
  auto is_transient = [&](NodeId n) { return std::binary_search(transient.begin(), transient.end(), n); };
  std::erase_if(change.new_leaves, is_transient);
  std::erase_if(change.removed_leaves, is_transient);
  return change;
}

template <int D>
typename Quadtree<D>::Change Quadtree<D>::remove_input(VertexId id, std::span<const Point<D>> positions) {
  Change change;
  const Point<D>& p = positions[id];
  const NodeId leaf = locate(p);
  Node& lf = nodes_[leaf];
  auto it = std::find_if(lf.vertices.begin(), lf.vertices.end(), [&](const LeafVertex<D>& e) { return e.id == id; });
  if (it == lf.vertices.end() || lf.input_vertex != id)
    throw std::logic_error("quadtree remove_input: vertex is not an input of its leaf");
  lf.vertices.erase(it);
  lf.input_vertex = kNoVertex;
  sync_search(leaf);
  if (lf.vertices.empty()) mark_vacated(leaf);
  for (NodeId a = leaf; a != kNoNode; a = nodes_[a].parent) --nodes_[a].input_count;

  // Internal nodes whose block contained p may no longer be crowded; merging one can release its
  // level-1 neighbours (they were kept split by its children). Finest level first.
  std::vector<std::vector<NodeId>> candidates(kMaxLevel + 1);
  for_each_node_near(p, [&](NodeId n) {
    if (!nodes_[n].is_leaf()) candidates[nodes_[n].level].push_back(n);
  });
  std::vector<NodeId> merged;
  for (int level = kMaxLevel; level >= 0; --level) {
    auto& list = candidates[level];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    for (NodeId n : list) {
      if (nodes_[n].level != level || nodes_[n].is_leaf() || required_split(n, positions)) continue;
      merge(n, &change.removed_leaves);
      merged.push_back(n);
      if (level == 0) continue;
      Coords pc;
      for (int i = 0; i < D; ++i) pc[i] = nodes_[n].coords[i] >> 1;
      for_each_neighbour_cell(level - 1, pc, 1, [&](const Coords& q) {
        const NodeId m = find(level - 1, q);
        if (m != kNoNode && !nodes_[m].is_leaf()) candidates[level - 1].push_back(m);
      });
    }
  }
  // Removed leaves include children of merged nodes; merged nodes that merged again upward are gone.
  for (NodeId n : merged)
    if (nodes_[n].level >= 0 && nodes_[n].is_leaf()) change.new_leaves.push_back(n);
  std::vector<NodeId> gone = change.removed_leaves;
  std::sort(gone.begin(), gone.end());
  std::erase_if(change.new_leaves, [&](NodeId n) { return std::binary_search(gone.begin(), gone.end(), n); });
  return change;
}

template <int D>
NodeId Quadtree<D>::insert_vertex(VertexId id, const Point<D>& p, std::uint64_t tag, NodeId hint) {
  const NodeId leaf = locate(p, hint);
  nodes_[leaf].vertices.push_back({p, tag, id});
  sync_search(leaf);
  if (nodes_[leaf].vertices.size() == 1) mark_occupied(leaf);
  return leaf;
}

template <int D>
void Quadtree<D>::rename_vertices(std::span<const VertexId> new_id) {
  // Each leaf's array is allocated afresh, in node order (nodes are numbered along the curve), all
  // before the old ones are freed (which the new ones would fill, scattered): Steiner vertices grew
  // the arrays at the times they arrived, so neighbouring leaves lay far apart on the heap.
  std::vector<std::vector<LeafVertex<D>>> old_arrays;
  for (NodeId n = 0; n < nodes_.size(); ++n) {
    Node& nd = nodes_[n];
    if (nd.level < 0) continue;  // a free slot
    if (nd.input_vertex != kNoVertex) nd.input_vertex = new_id[nd.input_vertex];
    for (LeafVertex<D>& e : nd.vertices) e.id = new_id[e.id];
    if (nd.is_leaf() && !nd.vertices.empty()) {
      std::vector<LeafVertex<D>> repacked(nd.vertices.begin(), nd.vertices.end());
      old_arrays.push_back(std::move(nd.vertices));
      nd.vertices = std::move(repacked);
      search_[n].vertices = nd.vertices.data();
    }
  }
}

template <int D>
void Quadtree<D>::erase_vertex(VertexId id, NodeId leaf) {
  auto& vs = nodes_[leaf].vertices;
  auto it = std::find_if(vs.begin(), vs.end(), [&](const LeafVertex<D>& e) { return e.id == id; });
  if (it == vs.end()) throw std::logic_error("quadtree erase_vertex: vertex not in leaf");
  *it = vs.back();
  vs.pop_back();
  sync_search(leaf);
  if (vs.empty()) mark_vacated(leaf);
}

template <int D>
std::vector<std::pair<int, typename Quadtree<D>::Coords>> Quadtree<D>::leaf_cells() const {
  std::vector<std::pair<int, Coords>> cells;
  for (const Node& n : nodes_)
    if (n.level >= 0 && n.is_leaf() && (n.parent != kNoNode || &n == &nodes_[0])) cells.emplace_back(n.level, n.coords);
  std::sort(cells.begin(), cells.end());
  return cells;
}

template <int D>
std::size_t Quadtree<D>::memory_bytes() const {
  std::size_t bytes = nodes_.capacity() * sizeof(Node) + search_.capacity() * sizeof(SearchEntry) + map_.memory_bytes() +
                      free_blocks_.capacity() * sizeof(NodeId);
  for (const Node& n : nodes_) bytes += n.vertices.capacity() * sizeof(LeafVertex<D>);
  return bytes;
}

template <int D>
void Quadtree<D>::check_valid(std::span<const Point<D>> positions) const {
  auto fail = [](const std::string& what) { throw std::logic_error("quadtree invalid: " + what); };
  std::size_t leaves = 0;
  for (NodeId n = 0; n < nodes_.size(); ++n) {
    const Node& nd = nodes_[n];
    if (nd.level < 0) continue;
    if (n != 0 && (nd.parent == kNoNode || nodes_[nd.parent].is_leaf())) continue;  // unreachable slot
    if (find(nd.level, nd.coords) != n) fail("cell map does not point to node " + std::to_string(n));
    if (nd.is_leaf()) {
      ++leaves;
      std::uint32_t inputs = 0;
      for (const LeafVertex<D>& e : nd.vertices) {
        if (e.position != positions[e.id]) fail("leaf's copy of a vertex position");
        if (cell_of(e.position, nd.level) != nd.coords) fail("vertex outside its leaf");
        if (e.id == nd.input_vertex) ++inputs;
      }
      if (inputs != nd.input_count || nd.input_count > 1) fail("leaf input count");
      if (search_[n].first_child != kNoNode || search_[n].occupied_or_size != nd.vertices.size() ||
          search_[n].vertices != nd.vertices.data())
        fail("search entry of leaf " + std::to_string(n));
      if (crowded(n, positions)) fail("crowded leaf at level " + std::to_string(nd.level));
      // Balance: touching leaves differ by at most one level.
      if (nd.level >= 2)
        for_each_neighbour_cell(nd.level, nd.coords, 1, [&](const Coords& q) {
          Coords pc;
          for (int i = 0; i < D; ++i) pc[i] = q[i] >> 1;
          if (nodes_[deepest_containing(nd.level - 1, pc)].level < nd.level - 1) fail("unbalanced leaves");
        });
    } else {
      std::uint32_t sum = 0;
      std::uint32_t occupied = 0;
      for (int k = 0; k < kChildren; ++k) {
        const NodeId c = nd.first_child + NodeId(k);
        const Node& ch = nodes_[c];
        if (ch.parent != n || ch.level != nd.level + 1) fail("child links");
        sum += ch.input_count;
        if (search_[c].occupied_or_size != 0) occupied |= 1u << k;
      }
      // Leaves' entries are checked against their vertices, so this checks every mask by induction.
      if (search_[n].first_child != nd.first_child || search_[n].occupied_or_size != occupied)
        fail("search entry of internal node " + std::to_string(n));
      if (sum != nd.input_count) fail("subtree input count node " + std::to_string(n) + " level " + std::to_string(nd.level) + " count " + std::to_string(nd.input_count) + " sum " + std::to_string(sum));
      if (!nd.vertices.empty()) fail("internal node holds vertices");
      if (!required_split(n, positions)) fail("split not required (tree not minimal) at level " + std::to_string(nd.level));
    }
  }
  if (leaves != leaf_count_) fail("leaf count");
}

template class Quadtree<2>;
template class Quadtree<3>;

}  // namespace shoremesh::engine
