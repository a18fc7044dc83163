// The cell cache of one propagation: a vertex's clipped cell, computed for one of its operations at
// time t1, taken again for its next operation at t2 > t1 instead of searching and clipping anew.
//
// Why the reused cell equals the one a fresh computation at t2 (and so a from-scratch run) gives:
//  - The vertices an operation at t sees are those born before t. When t1 runs, every operation before
//    t1 has run, so the vertices born before t1 no longer change: what an operation at t2 sees is what
//    t1 saw plus the vertices born in [t1, t2). Those are either already in the tree when t1 runs (their
//    earliest birth within reach is valid_until) or inserted later by a fill (vertex_arrived).
//  - A vertex w farther than sqrt(depends2) changes nothing: beyond 2 beta NN it is never offered to
//    the clipper; otherwise |w - v| exceeds twice the distance of every cell vertex, so its half-space
//    holds the whole cell strictly, and it is not nearer than NN. The cell at t2 is the same polygon.
//  - The same polygon is the same cell bit for bit when no clip found a vertex exactly on its plane: each
//    vertex then lies on exactly D of the planes kept, so it is computed from the same D planes, met in
//    the same order (candidates are clipped in a canonical order), whatever else was offered in between.
//    In 2D a vertex is always the crossing of its two edges' lines; in 3D the argument is the same for
//    simple vertices, and the 3D random-edit and grid tests check the result bit for bit. Cells with a
//    vertex on a plane (grids) are not cached.
// The box whose nodes the operation reads is the one t1 searched: it covers the dependency ball, which is
// all the reads must do.
//
// A stale entry still spares the search (compute_cell): it lists every vertex of the leaves that meet
// its box, as they were at t1 (candidates: born before t1; unborn: born later) and as fills inserted
// them since (arrived). At t2 those leaves hold exactly these, less the dead:
//  - a vertex born before t1 never leaves during the propagation: only undoing its creator, at its
//    birth, removes it (input edits happen before the propagation);
//  - an unborn or arrived vertex may have left (undone since): it is dropped unless alive. Vertex ids
//    are freed only when the propagation ends, so an id names one vertex throughout;
//  - arrivals are recorded with the test the search itself uses for its `seen` box
//    (Quadtree::leaf_meets_box): a larger box then searches just the leaves beyond, as for a cell
//    that searched the first box itself, and no vertex comes twice.
// The candidate set within any box the computation reaches is then the one a search finds, and the
// cell, the nearest neighbour (canonical in the set) and every decision are the same.
//
// When the nearest neighbour is the same, the stale entry's cell is cut by the new candidates only
// (those born since, and arrivals), not rebuilt: the clipping box depends on NN alone, and no earlier
// candidate left, so the cell at t2 is the earlier polygon intersected with the new half-spaces: the
// same polygon. An earlier candidate that did not cut then (its half-space held the cell, or it lay
// beyond the cell's reach) cannot cut the cell now, which only shrank since. Then the argument above
// for cells without a vertex on D + 1 planes makes it the same cell bit for bit, provided each vertex
// is solved from its planes in the same order: a 2D vertex always takes its incoming then its outgoing edge; a 3D vertex takes its
// planes in distance order, which a from-scratch run numbers them in and the out-of-order cuts of
// ConvexCell keep. Should a new cut meet a vertex exactly, or the reach outgrow the box by rounding,
// the cell is computed afresh.
#include <algorithm>
#include <limits>

#include "shoremesh/engine/engine.hpp"

namespace shoremesh {

// The slot of v: the one holding v, or the empty one where v would go.
template <int D>
typename WellSpacedEngine<D>::CacheSlot& WellSpacedEngine<D>::cache_slot(VertexId v) {
  if (cache_table_.empty()) cache_table_.resize(std::size_t(1) << kCacheTableBits);
  const std::size_t mask = cache_table_.size() - 1;
  std::size_t k = std::size_t((v * 0x9E3779B1u) >> (32 - kCacheTableBits));
  while (cache_table_[k].vertex != v && cache_table_[k].vertex != engine::kNoVertex) k = (k + 1) & mask;
  return cache_table_[k];
}

template <int D>
bool WellSpacedEngine<D>::reuse_cell(OpId o, const CachedCell& c, std::uint64_t now) {
  if (now >= c.valid_until) return false;
  ++counters_.cells_reused;
  serial_.cell.assign_geometry(c.cell);
  serial_.hood.nearest = c.nearest;
  serial_.hood.candidates = c.candidates;
  serial_.covering = c.covering;  // registered by its commit
  serial_.cover = c.cover;
  recorded_ops_[o].set_depends2(c.depends2);
  recorded_ops_[o].reach = c.reach;
  return true;
}

template <int D>
const typename WellSpacedEngine<D>::CachedCell* WellSpacedEngine<D>::cached_neighbourhood(VertexId v, const Point<D>& p) {
  if (cell_cache_live_ == 0) return nullptr;
  const CacheSlot& slot = cache_slot(v);
  if (slot.vertex != v || cell_cache_[slot.entry].position != p) return nullptr;
  return &cell_cache_[slot.entry];
}

template <int D>
void WellSpacedEngine<D>::store_cell(OpId o, VertexId v, const Point<D>& p, double searched) {
  const float depends2 = recorded_ops_[o].depends2;
  // The search must have seen every vertex within the dependency ball, born or not.
  if (serial_.cell.had_vertex_on_plane() || !(double(depends2) <= searched * searched)) {
    forget_cell(v);
    return;
  }
  CacheSlot& slot = cache_slot(v);
  if (slot.vertex != v) {
    if (cell_cache_live_ == kMaxCachedCells) return;
    if (cell_cache_live_ == cell_cache_.size()) cell_cache_.emplace_back();
    slot.vertex = v;
    slot.entry = std::uint32_t(cell_cache_live_++);
  }
  CachedCell& c = cell_cache_[slot.entry];
  c.position = p;
  c.valid_until = std::numeric_limits<std::uint64_t>::max();
  for (const TimedVertex& u : serial_.unborn)
    if (engine::squared_distance<double, D>(u.position, p) <= double(depends2))
      c.valid_until = std::min(c.valid_until, u.birth);
  c.depends2 = depends2;
  c.reach = recorded_ops_[o].reach;
  c.covering = serial_.covering;  // record_reads(o, p, searched) just left them there
  c.cover = serial_.cover;
  c.nearest = serial_.hood.nearest;
  c.searched = searched;
  c.candidates = serial_.hood.candidates;
  c.unborn = serial_.unborn;
  c.arrived.clear();
  c.cell.assign_geometry(serial_.cell);
}

template <int D>
void WellSpacedEngine<D>::forget_cell(VertexId v) {
  if (cell_cache_live_ == 0) return;
  const CacheSlot& slot = cache_slot(v);
  if (slot.vertex == v) cell_cache_[slot.entry].valid_until = 0;
}

template <int D>
void WellSpacedEngine<D>::vertex_arrived(VertexId w, const Point<D>& q, std::uint64_t birth) {
  const NodeId leaf = vertices_[w].leaf;
  for (std::size_t k = 0; k < cell_cache_live_; ++k) {
    CachedCell& c = cell_cache_[k];
    if (c.valid_until != 0 && engine::squared_distance<double, D>(q, c.position) <= double(c.depends2))
      c.valid_until = 0;
    // The leaves a search of that box reads: the same test, so the lists stay what a search finds.
    if (tree_.leaf_meets_box(leaf, c.position, c.searched)) c.arrived.push_back({q, birth, w});
  }
}

template <int D>
void WellSpacedEngine<D>::clear_cell_cache() {
  if (cell_cache_live_ != 0) std::fill(cache_table_.begin(), cache_table_.end(), CacheSlot{});
  cell_cache_live_ = 0;
  // A large batch needed many entries: give their memory back.
  if (cell_cache_.size() > kKeptCachedCells) {
    cell_cache_.resize(kKeptCachedCells);
    cell_cache_.shrink_to_fit();
  }
}

template bool WellSpacedEngine<2>::reuse_cell(OpId, const CachedCell&, std::uint64_t);
template bool WellSpacedEngine<3>::reuse_cell(OpId, const CachedCell&, std::uint64_t);
template void WellSpacedEngine<2>::store_cell(OpId, VertexId, const Point<2>&, double);
template void WellSpacedEngine<3>::store_cell(OpId, VertexId, const Point<3>&, double);
template void WellSpacedEngine<2>::forget_cell(VertexId);
template void WellSpacedEngine<3>::forget_cell(VertexId);
template void WellSpacedEngine<2>::vertex_arrived(VertexId, const Point<2>&, std::uint64_t);
template void WellSpacedEngine<3>::vertex_arrived(VertexId, const Point<3>&, std::uint64_t);
template const WellSpacedEngine<2>::CachedCell* WellSpacedEngine<2>::cached_neighbourhood(VertexId, const Point<2>&);
template const WellSpacedEngine<3>::CachedCell* WellSpacedEngine<3>::cached_neighbourhood(VertexId, const Point<3>&);
template WellSpacedEngine<2>::CacheSlot& WellSpacedEngine<2>::cache_slot(VertexId);
template WellSpacedEngine<3>::CacheSlot& WellSpacedEngine<3>::cache_slot(VertexId);
template void WellSpacedEngine<2>::clear_cell_cache();
template void WellSpacedEngine<3>::clear_cell_cache();

}  // namespace shoremesh
