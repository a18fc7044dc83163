// The engine's layout by place after a build for updates (engine.hpp: build): vertices along the curve,
// each vertex's operations after it, and the children and reads pools in that order.
#include "shoremesh/engine/engine.hpp"
#include "shoremesh/engine/spatial_order.hpp"

#include "engine_internal.hpp"

#include <algorithm>
#include <vector>

namespace shoremesh {

using namespace engine;

using engine_detail::permute_in_place;

namespace {
// The items in an array with room for an eighth more (and a thousand): the room a pool keeps.
template <class T>
void with_room(std::vector<T>& items) {
  const std::size_t room = items.size() + items.size() / 8 + 1024;
  if (items.capacity() <= room) return;
  std::vector<T> copy;
  copy.reserve(room);
  copy.assign(items.begin(), items.end());
  items.swap(copy);
}
}  // namespace

// The build numbers Steiner vertices and operations in time order (each time's batch along the curve),
// so the vertices and operations around one place lie in as many distant stretches of their arrays as
// there are times. An update reads those of one place at all times (marking readers loads every
// reader's operation and its vertex's position): at n = 1e6 each such load was a cache miss. Numbered
// by place instead (vertices along the curve, each vertex's operations in time order after it), they
// share cache lines. The ids are internal: only the references change (the facet filters hash each
// vertex's position, not its id).
template <int D>
std::vector<typename WellSpacedEngine<D>::VertexId> WellSpacedEngine<D>::renumber_vertices_by_place() {
  const std::size_t count = vertices_.size();
  std::vector<VertexId> live;
  std::vector<Point<D>> places;
  for (VertexId v = 0; v < count; ++v)
    if (vertices_[v].alive) {
      live.push_back(v);
      places.push_back(positions_[v]);
    }
  std::vector<VertexId> new_id(count, kNoVertex);
  VertexId next = 0;
  for (std::size_t k : engine::spatial_order<D>(places)) new_id[live[k]] = next++;
  for (VertexId& id : new_id)
    if (id == kNoVertex) id = next++;  // free slots last
  permute_in_place(vertices_, new_id);
  permute_in_place(positions_, new_id);
  permute_in_place(vertex_ops_, new_id);
  for (RecordedOp& op : recorded_ops_)
    if (op.vertex != kNoVertex) op.vertex = new_id[op.vertex];
  for (VertexId& v : free_vertices_) v = new_id[v];
  tree_.rename_vertices(new_id);
  return new_id;
}

template <int D>
void WellSpacedEngine<D>::renumber_operations_by_place() {
  const std::size_t m = recorded_ops_.size();
  std::vector<OpId> new_id(m, kNoOp);
  OpId next = 0;
  std::vector<OpId> own;
  for (VertexId v = 0; v < vertices_.size(); ++v) {  // along the curve, after renumber_vertices_by_place
    if (!vertices_[v].alive) continue;
    own.clear();
    if (vertex_ops_[v].dispatch != kNoOp) own.push_back(vertex_ops_[v].dispatch);
    for (OpId f = vertices_[v].first_fill; f != kNoOp; f = recorded_ops_[f].next_fill) own.push_back(f);
    std::sort(own.begin(), own.end(), [&](OpId a, OpId b) {
      return time_key(recorded_ops_[a].rank, recorded_ops_[a].color) < time_key(recorded_ops_[b].rank, recorded_ops_[b].color);
    });
    for (OpId o : own) new_id[o] = next++;
  }
  for (OpId& id : new_id)
    if (id == kNoOp) id = next++;  // deleted slots last
  permute_in_place(recorded_ops_, new_id);
  auto renamed = [&](OpId o) { return o == kNoOp ? kNoOp : new_id[o]; };
  for (RecordedOp& op : recorded_ops_) op.next_fill = renamed(op.next_fill);
  for (Vertex& vx : vertices_) vx.first_fill = renamed(vx.first_fill);
  for (VertexOps& vo : vertex_ops_) {
    vo.creator = renamed(vo.creator);
    vo.dispatch = renamed(vo.dispatch);
  }
  for (const RecordedOp& op : recorded_ops_)
    for (std::uint32_t k = op.children_begin; k < op.children_begin + op.children_count; ++k) children_[k] = new_id[children_[k]];
  readers_.rename([&](OpId o) { return new_id[o]; });
  for (OpId& o : free_ops_) o = new_id[o];
  lay_out_children();  // the children pool in the new order too
  // The arrays grew by doubling during the build: keep room for an eighth more (what an update adds
  // before the slots it frees come back), not up to twice as much.
  with_room(recorded_ops_);
  with_room(vertices_);
  with_room(positions_);
  with_room(vertex_ops_);
}

// Rewrites the children pool with each operation's run in operation order (after the build has
// numbered the operations by place), with room for an eighth more. The free lists are empty after a
// build, so the first updates append their runs, and a pool that grew in the middle of an update copied
// itself whole (41 to 52 ms at 2D n = 1e6, bench/RESULTS.md); later updates mostly take the blocks that
// earlier ones gave back. Room never written takes no physical memory.
template <int D>
void WellSpacedEngine<D>::lay_out_children() {
  const std::size_t live = live_children_entries();
  engine::BlockPool children;
  children.reserve(live + live / 8 + 1024);
  for (RecordedOp& op : recorded_ops_)
    op.children_begin = children.allocate(children_.run(op.children_begin, op.children_begin + op.children_count));
  children_ = std::move(children);
}

template <int D>
std::size_t WellSpacedEngine<D>::live_children_entries() const {
  std::size_t live = 0;
  for (const RecordedOp& op : recorded_ops_)
    if (!(op.flags & kDead)) live += engine::BlockPool::block_size(op.children_count);
  return live;
}

template std::vector<engine::VertexId> WellSpacedEngine<2>::renumber_vertices_by_place();
template std::vector<engine::VertexId> WellSpacedEngine<3>::renumber_vertices_by_place();
template void WellSpacedEngine<2>::renumber_operations_by_place();
template void WellSpacedEngine<3>::renumber_operations_by_place();
template void WellSpacedEngine<2>::lay_out_children();
template void WellSpacedEngine<3>::lay_out_children();
template std::size_t WellSpacedEngine<2>::live_children_entries() const;
template std::size_t WellSpacedEngine<3>::live_children_entries() const;

}  // namespace shoremesh
