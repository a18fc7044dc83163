#include "shoremesh/engine/engine.hpp"
#include "shoremesh/engine/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "shoremesh/error.hpp"

namespace shoremesh {

using namespace engine;

namespace {
constexpr int kBeforeEverything = std::numeric_limits<int>::min();

// The float nearest above x: a dependency radius stored in half the space, never smaller.
float at_least(double x) {
  float f = float(x);
  if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// Where id x is in ids (ids.size() if absent), eight entries per step: the reader lists of coarse
// squares hold hundreds of operations, and undo looks one up in each square its operation read
// (std::find there was 4 % of a 2D update's instructions).
std::size_t position_of(std::span<const std::uint32_t> ids, std::uint32_t x) {
  std::size_t i = 0;
#ifdef __SSE2__
  const __m128i key = _mm_set1_epi32(int(x));
  for (; i + 8 <= ids.size(); i += 8) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(ids.data() + i));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(ids.data() + i + 4));
    if (_mm_movemask_epi8(_mm_or_si128(_mm_cmpeq_epi32(a, key), _mm_cmpeq_epi32(b, key))) != 0) break;
  }
#endif
  for (; i < ids.size(); ++i)
    if (ids[i] == x) return i;
  return ids.size();
}
}

template <int D>
WellSpacedEngine<D>::WellSpacedEngine(const Parameters<D>& parameters)
    : params_(DerivedParameters<D>::derive(parameters)), ranks_(params_) {}

template <int D>
void WellSpacedEngine<D>::reset() {
  vertices_.clear();
  positions_.clear();
  ops_.clear();
  children_.clear();
  reads_.clear();
  readers_.clear();
  agenda_.clear();
  free_ops_.clear();
  dead_ops_.clear();
  free_vertices_.clear();
  dead_vertices_.clear();
  counters_ = Counters{};
  cell_.counters() = PredicateCounters{};
  input_count_ = 0;
  dynamic_ = false;
  caching_ = false;
  cell_cache_live_ = 0;
  cache_table_.clear();
}

template <int D>
double WellSpacedEngine<D>::squared_distance(VertexId a, VertexId b) const {
  double s = 0;
  for (int i = 0; i < D; ++i) {
    const double d = positions_[a][i] - positions_[b][i];
    s += d * d;
  }
  return s;
}

template <int D>
std::vector<typename WellSpacedEngine<D>::VertexId> WellSpacedEngine<D>::build(std::span<const Point<D>> unit_points,
                                                                                  bool lay_out_for_updates) {
  reset();
  for (std::size_t i = 0; i < unit_points.size(); ++i)
    for (int k = 0; k < D; ++k) {
      const double x = unit_points[i][k];
      if (!std::isfinite(x)) throw PointInputError("point " + std::to_string(i) + " is not finite", {i});
      if (x < 0 || x > 1) throw PointInputError("point " + std::to_string(i) + " lies outside the box", {i});
    }
  // Exact duplicates get their own message (the quadtree would call them too close). Equal points have
  // equal curve keys and are ordered by coordinates among those: they are neighbours in this order.
  const std::vector<std::size_t> along_curve = engine::spatial_order<D>(unit_points);
  for (std::size_t k = 1; k < along_curve.size(); ++k)
    if (unit_points[along_curve[k]] == unit_points[along_curve[k - 1]]) {
      const std::size_t a = std::min(along_curve[k], along_curve[k - 1]);
      const std::size_t b = std::max(along_curve[k], along_curve[k - 1]);
      throw PointInputError("points " + std::to_string(a) + " and " + std::to_string(b) + " are equal", {a, b});
    }

  input_count_ = unit_points.size();
  std::vector<VertexId> vertex_of_point(input_count_);
  positions_.resize(input_count_);
  for (VertexId v = 0; v < input_count_; ++v) {
    positions_[v] = unit_points[along_curve[v]];
    vertex_of_point[along_curve[v]] = v;
  }
  vertices_.resize(input_count_);
  std::vector<VertexId> ids(input_count_);
  for (VertexId v = 0; v < input_count_; ++v) {
    vertices_[v].position = positions_[v];
    vertices_[v].is_input = true;
    vertices_[v].alive = true;
    vertices_[v].filter_key = v;
    ids[v] = v;
  }
  tree_.build(positions_, ids);
  for (NodeId n = 0; n < tree_.node_capacity(); ++n) {
    const auto& nd = tree_.node(n);
    if (nd.level < 0 || !nd.is_leaf()) continue;
    for (const LeafVertex<D>& e : nd.vertices) vertices_[e.id].leaf = n;
  }
  readers_.assign(tree_.node_capacity(), {});
  // Input dispatches at the rank of QTApxNN(v) (a quarter of the side of its leaf): NN from below.
  for (VertexId v = 0; v < input_count_; ++v) {
    const int rank = ranks_.rank_of_length(tree_.approximate_nn(vertices_[v].leaf));
    const OpId o = new_op(OpKind::Dispatch, v, rank, 0);
    vertices_[v].dispatch = o;
    mark_fresh(o);
  }
  // StableWS is a propagation in which every operation is fresh.
  propagate(nullptr);
  if (lay_out_for_updates) {
    const std::vector<VertexId> new_id = renumber_vertices_by_place();
    for (VertexId& v : vertex_of_point) v = new_id[v];
    renumber_operations_by_place();
    // Room to grow in every reader list. Updates register readers again, and a list that outgrows its
    // block moves wherever the allocator finds room, away from the lists of its neighbours, which
    // marking and undo walk together: at 2D n = 1e6 the median update grew by a fifth over 40,000
    // changes without it, by about a tenth with it (bench/RESULTS.md), for 2 to 3 % more memory.
    for (auto& list : readers_) list.reserve(list.size() + list.size() / 2 + 2);
  }
  dynamic_ = true;
  return vertex_of_point;
}

template <int D>
typename WellSpacedEngine<D>::OpId WellSpacedEngine<D>::new_op(OpKind kind, VertexId v, int rank,
                                                               std::uint32_t color) {
  Op op;
  op.kind = kind;
  op.vertex = v;
  op.rank = rank;
  op.color = color;
  if (!free_ops_.empty()) {
    const OpId o = free_ops_.back();
    free_ops_.pop_back();
    ops_[o] = op;
    return o;
  }
  ops_.push_back(op);
  return OpId(ops_.size() - 1);
}

template <int D>
void WellSpacedEngine<D>::enqueue(OpId o) {
  Op& op = ops_[o];
  if (op.flags & kQueued) return;
  op.flags |= kQueued;
  agenda_.push_back({op.rank, op.color, o});
  std::push_heap(agenda_.begin(), agenda_.end(), std::greater<>());
}

template <int D>
void WellSpacedEngine<D>::mark_fresh(OpId o) {
  ops_[o].flags |= kFresh;
  enqueue(o);
}

template <int D>
void WellSpacedEngine<D>::mark_obsolete(OpId o) {
  if (ops_[o].flags & kDead) return;
  ops_[o].flags |= kObsolete;
  enqueue(o);
}

template <int D>
void WellSpacedEngine<D>::mark_redo(OpId o) {
  Op& op = ops_[o];
  // Also when obsolete: a fill whose requesters all went away may be asked for again before its time,
  // and must then run again if what it read changed meanwhile.
  if ((op.flags & kDead) || !(op.flags & kExecuted)) return;
  op.flags |= kRedo;
  enqueue(o);
}

template <int D>
void WellSpacedEngine<D>::mark_readers_at(VertexId w, const Point<D>& p, NodeId leaf, VertexChange change, int rank,
                                          std::uint32_t color) {
  const bool inserted = change == VertexChange::Inserted;
  const auto bits = facet_bits(w);
  for (NodeId n = leaf; n != kNoNode; n = tree_.node(n).parent)
    for (OpId o : readers_[n]) {
      const Op& op = ops_[o];
      if (op.rank < rank || (op.rank == rank && op.color <= color)) continue;
      if (!inserted && !op.facets.may_hold(bits)) continue;
      const Point<D>& c = positions_[op.vertex];
      Point<D> d;
      double d2 = 0;
      for (int i = 0; i < D; ++i) {
        d[i] = p[i] - c[i];
        d2 += d[i] * d[i];
      }
      if (d2 > (inserted ? op.inserted_depends2 : op.depends2)) continue;
      if (inserted && !op.reach.may_be_cut_by(d)) continue;
      mark_redo(o);
    }
}

template <int D>
void WellSpacedEngine<D>::record_facets(OpId o) {
  auto facets = facet_bits(hood_.nearest);
  for (VertexId w : neighbours_) facets.add(facet_bits(w));
  ops_[o].facets = facets;
}

template <int D>
void WellSpacedEngine<D>::mark_all_readers(NodeId n) {
  for (OpId o : readers_[n]) mark_redo(o);
}

// Processes the agenda in time order. At each time: fills nobody asks for any more become obsolete;
// obsolete and inconsistent operations are undone; then fresh and inconsistent ones run. Everything an
// operation at time t creates, undoes or marks lies strictly later, so each time is complete when its
// turn comes (Lemma 6.1 makes the operations of one time independent, in any order).
template <int D>
void WellSpacedEngine<D>::propagate(PropagationStats* stats) {
  stats_ = stats;
  clear_cell_cache();  // empty unless an earlier propagation threw
  caching_ = dynamic_;
  while (!agenda_.empty()) {
    const AgendaEntry now = agenda_.front();
    batch_.clear();
    while (!agenda_.empty() && agenda_.front().rank == now.rank && agenda_.front().color == now.color) {
      std::pop_heap(agenda_.begin(), agenda_.end(), std::greater<>());
      const OpId o = agenda_.back().op;
      agenda_.pop_back();
      ops_[o].flags &= std::uint8_t(~kQueued);
      batch_.push_back(o);
    }
    // In any order (Lemma 6.1); along the curve, so that the Steiner vertices and operations a large
    // batch creates (a build's) are numbered, and later read, in the order of their places.
    if (batch_.size() > kSortedBatch) {
      batch_keys_.resize(batch_.size());
      for (std::size_t k = 0; k < batch_.size(); ++k)
        batch_keys_[k] = {engine::z_order_key<D>(positions_[ops_[batch_[k]].vertex]), batch_[k]};
      std::sort(batch_keys_.begin(), batch_keys_.end());
      for (std::size_t k = 0; k < batch_.size(); ++k) batch_[k] = batch_keys_[k].second;
    }
    for (OpId o : batch_) {
      Op& op = ops_[o];
      if (op.kind == OpKind::Fill && op.requesters == 0) op.flags |= kObsolete;
      if ((op.flags & (kObsolete | kRedo)) && (op.flags & kExecuted)) undo(o);
    }
    for (OpId o : batch_) {
      const std::uint8_t f = ops_[o].flags;
      if (f & kDead) continue;
      if (f & kObsolete) kill(o);
      else if (f & (kRedo | kFresh)) execute(o);
    }
  }
  clear_cell_cache();
  caching_ = false;
  counters_.predicate_calls += cell_.counters().calls;
  counters_.exact_fallbacks += cell_.counters().exact;
  cell_.counters() = PredicateCounters{};
  // Slots of deleted operations and vertices are reused from now on.
  for (OpId o : dead_ops_) {
    ops_[o] = Op{};
    ops_[o].flags = kDead;
    free_ops_.push_back(o);
  }
  dead_ops_.clear();
  for (VertexId v : dead_vertices_) free_vertices_.push_back(v);
  dead_vertices_.clear();
  stats_ = nullptr;
}

// Takes back what operation o did: the fills a dispatch asked for lose a requester; the Steiner vertices
// a fill inserted leave the output (their operations become obsolete, their readers inconsistent); its
// read registrations go.
template <int D>
void WellSpacedEngine<D>::undo(OpId o) {
  Op& op = ops_[o];
  const int rank = op.rank;
  const std::uint32_t color = op.color;
  const std::uint32_t cb = op.children_begin, ce = op.children_end;
  if (op.kind == OpKind::Dispatch) {
    for (std::uint32_t k = cb; k < ce; ++k) {
      Op& child = ops_[children_[k]];
      if (child.flags & kDead) continue;
      if (child.requesters > 0 && --child.requesters == 0) mark_obsolete(children_[k]);
    }
  } else if ((op.flags & kRedo) && !(op.flags & kObsolete)) {
    // About to run again: keep its Steiner vertices for now. The new run reuses those it inserts again
    // at the very same place (their subtrees stay valid); fill() takes back the others.
    op.flags |= kStashed;
  } else {
    for (std::uint32_t k = cb; k < ce; ++k) {
      const OpId d = children_[k];
      const VertexId w = ops_[d].vertex;
      mark_obsolete(d);
      if (!vertices_[w].alive) continue;
      tree_.erase_vertex(w, vertices_[w].leaf);
      mark_readers_at(w, positions_[w], vertices_[w].leaf, VertexChange::Removed, rank, color);
      kill_vertex(w);
      if (stats_) stats_->steiner_removed.push_back(positions_[w]);
    }
  }
  for (std::uint32_t k = ops_[o].reads_begin; k < ops_[o].reads_end; ++k) {
    auto& rs = readers_[reads_[k]];
    const std::size_t at = position_of(rs, o);
    if (at != rs.size()) {
      rs[at] = rs.back();
      rs.pop_back();
    }
  }
  Op& again = ops_[o];
  release_reads(again);
  if (!(again.flags & kStashed)) release_children(again);  // a stashed fill's go when it runs (fill)
  again.flags &= std::uint8_t(~kExecuted);
  ++counters_.operations_undone;
  if (stats_) ++stats_->undone;
}

// A vertex leaves the output: every operation acting on it becomes obsolete.
template <int D>
void WellSpacedEngine<D>::kill_vertex(VertexId v) {
  Vertex& vx = vertices_[v];
  vx.alive = false;
  if (caching_) forget_cell(v);
  if (vx.dispatch != kNoOp) mark_obsolete(vx.dispatch);
  for (OpId f = vx.first_fill; f != kNoOp; f = ops_[f].next_fill) mark_obsolete(f);
  dead_vertices_.push_back(v);
}

template <int D>
void WellSpacedEngine<D>::kill(OpId o) {
  Op& op = ops_[o];
  Vertex& vx = vertices_[op.vertex];
  if (op.kind == OpKind::Fill) {
    // Unlink from the vertex's fill list.
    for (OpId* link = &vx.first_fill; *link != kNoOp; link = &ops_[*link].next_fill)
      if (*link == o) {
        *link = op.next_fill;
        break;
      }
  } else if (vx.dispatch == o) {
    vx.dispatch = kNoOp;
  }
  release_reads(op);  // none once undone; a fresh operation never ran
  release_children(op);
  op.flags = kDead;
  dead_ops_.push_back(o);
}

template <int D>
void WellSpacedEngine<D>::execute(OpId o) {
  ops_[o].flags &= std::uint8_t(~(kFresh | kRedo));
  if (ops_[o].kind == OpKind::Dispatch) dispatch(o);
  else fill(o);
  ops_[o].flags |= kExecuted;
  if (stats_) ++stats_->executed;
}

namespace {
// Moves item o of items to new_id[o], cycle by cycle (a copy would double the memory of the largest
// arrays of the engine).
template <class T>
void permute_in_place(std::vector<T>& items, const std::vector<std::uint32_t>& new_id) {
  std::vector<bool> placed(items.size(), false);
  for (std::uint32_t start = 0; start < items.size(); ++start) {
    if (placed[start]) continue;
    T carried = items[start];
    for (std::uint32_t from = start;;) {
      const std::uint32_t to = new_id[from];
      placed[to] = true;
      std::swap(carried, items[to]);
      if (to == start) break;
      from = to;
    }
  }
}
}  // namespace

// The build numbers Steiner vertices and operations in time order (each time's batch along the curve),
// so the vertices and operations around one place lie in as many distant stretches of their arrays as
// there are times. An update reads those of one place at all times (marking readers loads every
// reader's operation and its vertex's position): at n = 1e6 each such load was a cache miss. Numbered
// by place instead (vertices along the curve, each vertex's operations in time order after it), they
// share cache lines. The ids are internal: only the references change, and the facet filters hash each
// vertex's filter_key, which stays.
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
  for (Op& op : ops_)
    if (op.vertex != kNoVertex) op.vertex = new_id[op.vertex];
  for (VertexId& v : free_vertices_) v = new_id[v];
  tree_.rename_vertices(new_id);
  return new_id;
}

template <int D>
void WellSpacedEngine<D>::renumber_operations_by_place() {
  const std::size_t m = ops_.size();
  std::vector<OpId> new_id(m, kNoOp);
  OpId next = 0;
  std::vector<OpId> own;
  for (VertexId v = 0; v < vertices_.size(); ++v) {  // along the curve, after renumber_vertices_by_place
    if (!vertices_[v].alive) continue;
    own.clear();
    if (vertices_[v].dispatch != kNoOp) own.push_back(vertices_[v].dispatch);
    for (OpId f = vertices_[v].first_fill; f != kNoOp; f = ops_[f].next_fill) own.push_back(f);
    std::sort(own.begin(), own.end(), [&](OpId a, OpId b) {
      return time_key(ops_[a].rank, ops_[a].color) < time_key(ops_[b].rank, ops_[b].color);
    });
    for (OpId o : own) new_id[o] = next++;
  }
  for (OpId& id : new_id)
    if (id == kNoOp) id = next++;  // deleted slots last
  permute_in_place(ops_, new_id);
  auto renamed = [&](OpId o) { return o == kNoOp ? kNoOp : new_id[o]; };
  for (Op& op : ops_) op.next_fill = renamed(op.next_fill);
  for (Vertex& vx : vertices_) {
    vx.creator = renamed(vx.creator);
    vx.dispatch = renamed(vx.dispatch);
    vx.first_fill = renamed(vx.first_fill);
  }
  for (const Op& op : ops_)
    for (std::uint32_t k = op.children_begin; k < op.children_end; ++k) children_[k] = new_id[children_[k]];
  for (auto& list : readers_)
    for (OpId& o : list) o = new_id[o];
  for (OpId& o : free_ops_) o = new_id[o];
  lay_out_pools();  // the children and reads pools in the new order too
}

// Rewrites the children and reads pools with each operation's runs in operation order (after the
// build has numbered the operations by place), with room for an eighth more. The free lists are empty
// after a build, so the first updates append their runs, and a pool that grew in the middle of an
// update copied itself whole (41 to 52 ms at 2D n = 1e6, bench/RESULTS.md); later updates mostly take
// the blocks that earlier ones gave back. Room never written takes no physical memory.
template <int D>
void WellSpacedEngine<D>::lay_out_pools() {
  const PoolEntries live = live_pool_entries();
  engine::BlockPool children, reads;
  children.reserve(live.children + live.children / 8 + 1024);
  reads.reserve(live.reads + live.reads / 8 + 1024);
  for (Op& op : ops_) {
    const std::uint32_t children_count = op.children_end - op.children_begin;
    op.children_begin = children.allocate(children_.run(op.children_begin, op.children_end));
    op.children_end = op.children_begin + children_count;
    const std::uint32_t reads_count = op.reads_end - op.reads_begin;
    op.reads_begin = reads.allocate(reads_.run(op.reads_begin, op.reads_end));
    op.reads_end = op.reads_begin + reads_count;
  }
  children_ = std::move(children);
  reads_ = std::move(reads);
}

// The pool entries that the live operations' runs take (their blocks, not just their lengths).
template <int D>
typename WellSpacedEngine<D>::PoolEntries WellSpacedEngine<D>::live_pool_entries() const {
  PoolEntries live;
  for (const Op& op : ops_)
    if (!(op.flags & kDead)) {
      live.children += engine::BlockPool::block_size(op.children_end - op.children_begin);
      live.reads += engine::BlockPool::block_size(op.reads_end - op.reads_begin);
    }
  return live;
}

template <int D>
void WellSpacedEngine<D>::release_reads(Op& op) {
  reads_.release(op.reads_begin, op.reads_end - op.reads_begin);
  op.reads_begin = op.reads_end = 0;
}

template <int D>
void WellSpacedEngine<D>::release_children(Op& op) {
  children_.release(op.children_begin, op.children_end - op.children_begin);
  op.children_begin = op.children_end = 0;
}

// The children the operation being executed gathered in new_children_ become its run.
template <int D>
void WellSpacedEngine<D>::store_children(OpId o) {
  ops_[o].children_begin = children_.allocate(new_children_);
  ops_[o].children_end = ops_[o].children_begin + std::uint32_t(new_children_.size());
}

template <int D>
bool WellSpacedEngine<D>::compute_cell(OpId o, VertexId v, bool fill) {
  ops_[o].facets = engine::FacetFilter<D>::everything();
  ops_[o].reach = engine::CellReach<D>::unbounded();
  const Point<D> p = positions_[v];
  // Only vertices born before this operation's time exist for it (M_t).
  const std::uint64_t now = time_key(ops_[o].rank, ops_[o].color);
  const bool may_idle = fill && !params_.literal_stable_ws;
  // v's cell computed earlier in this propagation, if any: taken as it is when it still holds, else
  // the vertices its entry lists spare the search (below).
  const CachedCell* earlier = caching_ ? cached_neighbourhood(v, p) : nullptr;
  if (earlier && may_idle && now < earlier->valid_until &&
      ranks_.rank_below(p, positions_[earlier->nearest], ops_[o].rank, cell_.counters())) {
    hood_.nearest = earlier->nearest;  // still v's nearest neighbour: nothing came within its reach
    record_idle_fill(o, v);
    return false;
  }
  if (earlier && reuse_cell(o, *earlier, now)) return true;
  ++counters_.clipped_voronoi_calls;
  unborn_.clear();
  PredicateCounters& pc = cell_.counters();
  auto& pool = hood_.candidates;
  hood_.nearest = kNoVertex;
  pool.clear();
  double best_d2 = 0;
  // Takes vertex u at q (squared distance d2 from v) as a candidate, tracking the nearest.
  auto offer = [&](VertexId u, const Point<D>& q, double d2) {
    pool.push_back({d2, u, q});
    ++counters_.candidates;
    if (hood_.nearest != kNoVertex && d2 > best_d2 * (1 + 1e-12)) return;
    if (hood_.nearest != kNoVertex && d2 >= best_d2 * (1 - 1e-12)) {
      // Nearly tied: decide exactly, then by coordinates, so the nearest neighbour is canonical.
      const int c = compare_squared_distances<D>(pc, p, q, p, positions_[hood_.nearest]);
      if (c > 0 || (c == 0 && !(q < positions_[hood_.nearest]))) return;
    }
    hood_.nearest = u;
    best_d2 = d2;
  };
  // Once the cell exists among many candidates (or the operation is crowded, see Op::crowded),
  // searches skip what cannot cut it (ConvexCell::surely_uncut_by_box): the cell only shrinks, so such
  // a vertex never cuts it, now or at a later time that reuses the cell (cell_cache.cpp), and it is not
  // nearer than NN (a vertex nearer cuts the ball of radius NN / 2 about v, which the cell holds).
  // Along a dense shore seen from far out on the water, nearly all of a large cell's box is such
  // vertices. Among few (uniform inputs) the tests would cost more than they save.
  bool has_cell = false, pruning = false;
  auto cannot_cut = [&](const Point<D>& lo, const Point<D>& hi) {
    Point<D> a, b;
    for (int i = 0; i < D; ++i) {
      a[i] = lo[i] - p[i];
      b[i] = hi[i] - p[i];
    }
    return cell_.surely_uncut_by_box(a, b);
  };
  // A vertex of the tree other than v: a candidate if born before now, else remembered for the cache.
  auto consider = [&](VertexId u, const Point<D>& q, std::uint64_t birth) {
    if (pruning && cannot_cut(q, q)) return;
    if (birth >= now) {
      if (caching_) unborn_.push_back({q, birth, u});
      return;
    }
    double d2 = 0;
    for (int i = 0; i < D; ++i) d2 += (q[i] - p[i]) * (q[i] - p[i]);
    // A vertex exactly at v's place can only be a Steiner point about to be removed by the
    // propagation (an input was just added there): it is not a neighbour.
    if (d2 == 0 && q == p) return;
    offer(u, q, d2);
  };
  // Adds the vertices of the leaves of box [p - half, p + half] not searched yet. The boxes only grow,
  // so the leaves searched so far are those that meet the previous box.
  using Box = typename Quadtree<D>::Box;
  Box seen = Box::empty();
  auto box_of = [&](double half) {
    Box box;
    for (int i = 0; i < D; ++i) {
      box.lo[i] = p[i] - half;
      box.hi[i] = p[i] + half;
    }
    return box;
  };
  auto search = [&](double half) {
    const Box box = box_of(half);
    pruning = has_cell && (ops_[o].crowded || pool.size() > kCrowdedPool);
    ++counters_.neighbour_searches;
    const auto visit = [&](NodeId, std::span<const LeafVertex<D>> leaf) {
      for (const LeafVertex<D>& e : leaf)
        if (e.id != v) consider(e.id, e.position, e.tag);
    };
    if (pruning) {
      counters_.leaves_visited += tree_.for_each_occupied_leaf(box, seen, visit, [&](int level, const auto& cell) {
        const Box node = Quadtree<D>::cell_box(level, cell);
        return !cannot_cut(node.lo, node.hi);
      });
    } else {
      counters_.leaves_visited += tree_.for_each_occupied_leaf(box, seen, visit);
    }
    seen = box;
  };
  // Grow the box until it holds a vertex no farther than its half-side: no vertex outside is nearer.
  // The first box spans v's leaf and a leaf-side margin (NN(v) is about 1.15 leaf sides in uniform 2D
  // inputs): a box of one leaf side mostly had to grow again, which cost 5 % more instructions per
  // update in 2D and 3 % in 3D. The result does not depend on the first box, only the work does. A
  // crowded operation's starts at half a side: the tree is refined for the input points only, so a
  // large leaf out on the water can hold many Steiner vertices near a shore, and a box of two of its
  // sides thousands.
  double half = (ops_[o].crowded ? 0.5 : 2.0) * tree_.side(vertices_[v].leaf);
  // An operation run again (inconsistent) mostly needs the box it needed last time: starting from its
  // previous dependency radius saves most of the searches that grow the box step by step (2.4 -> 1.5
  // per 2D cell). Bounded, so that a vertex alone before does not search the whole domain. Not for a
  // crowded operation: a search before the cell exists cannot skip what the cell will not need, and
  // such a radius can hold a whole dense shore. Its box grows step by step, and each step skips what
  // the cell, cut by all that the steps before found, cannot need (jumping straight to the previous
  // radius once the cell existed skipped less: 130 candidates per cell against 40 at 171k Superior
  // shore points). (A fresh fill starting from the radius of its vertex's cell computed earlier in the
  // propagation searched more leaves than it saved: that cell is stale because a vertex came near, so
  // it shrank.)
  const double previous2 = ops_[o].depends2;
  if (!ops_[o].crowded && previous2 > half * half && previous2 < 16 * half * half) half = std::sqrt(previous2) * (1 + 1e-6);
  // With a stale entry (its cell computed earlier in this propagation): it lists what the leaves of
  // its box held then and what arrived there since, which is what they hold now, as a search would
  // find it (cell_cache.cpp). Only growing that box searches.
  std::size_t known = 0;  // pool[0, known): the candidates earlier->cell was computed from
  if (earlier) {
    for (const Candidate& c : earlier->candidates) offer(c.id, c.position, c.d2);
    known = pool.size();
    for (const auto* list : {&earlier->unborn, &earlier->arrived})
      for (const TimedVertex& u : *list)
        if (vertices_[u.id].alive) consider(u.id, u.position, u.birth);
    half = earlier->searched;
    seen = box_of(half);
    ++counters_.neighbourhoods_reused;
  } else {
    search(half);
  }
  while (!(hood_.nearest != kNoVertex && best_d2 <= half * half * (1 - 1e-9)) && half < 2.0) {
    half *= 2;  // until the box covers [0,1]^D
    search(half);
  }
  if (hood_.nearest == kNoVertex) {
    if (caching_) forget_cell(v);
    record_reads(o, p, half);
    ops_[o].depends2 = ops_[o].inserted_depends2 = at_least(4.0 * D);  // anything in the box gives it a neighbour
    return true;
  }
  if (may_idle && ranks_.rank_below(p, positions_[hood_.nearest], ops_[o].rank, pc)) {
    record_idle_fill(o, v);
    return false;
  }

  // The box around v of half-side beta NN(v) (a little more, so it surely holds the beta-ball), cut to
  // [0,1]^D: inside the ball the cut cell equals the true Voronoi cell, which is all any decision uses.
  const double nn = std::sqrt(best_d2);
  const double s = params_.beta * nn * (1 + 0x1p-20);
  Point<D> cube_lo, cube_hi;
  for (int i = 0; i < D; ++i) {
    cube_lo[i] = std::max(0.0, p[i] - s);
    cube_hi[i] = std::min(1.0, p[i] + s);
  }
  // Clip by the vertices in order of distance (ties by coordinates: a canonical order, so the rounded
  // cell does not depend on insertion history). A vertex farther than twice the cell's reach cannot cut
  // it, nor can one beyond 2 beta NN cut the beta-ball: the search grows only while a cut is possible.
  auto by_distance = [&](const Candidate& a, const Candidate& b) {
    if (a.d2 != b.d2) return a.d2 < b.d2;
    return a.position < b.position;
  };
  const double cap2 = 4 * params_.beta_squared * best_d2 * (1 + 1e-9);
  double searched = half;
  std::size_t next = 0;
  // With the same nearest neighbour (so the same clipping box) the earlier cell only has to be cut by
  // the vertices born since: none of the earlier candidates left, and the cut cell is the same polygon.
  // Without a vertex on D + 1 planes at once (checked, as for caching) each vertex of it is solved from
  // the same D planes in the same order as from scratch (ConvexCell::begin_out_of_order_cuts), so it
  // is the same cell bit for bit (cell_cache.cpp).
  bool incremental = earlier != nullptr && hood_.nearest == earlier->nearest;
  auto start_afresh = [&] {
    incremental = false;
    cell_.reset(p, cube_lo, cube_hi);
    next = 0;
    has_cell = true;
  };
  if (incremental) {
    cell_.assign_geometry(earlier->cell);
    cell_.begin_out_of_order_cuts();
    next = known;
    has_cell = true;
    ++counters_.cells_updated;
  } else {
    start_afresh();
  }
  for (;;) {
    double reach2 = std::min(4 * cell_.max_vertex_distance2() * (1 + 1e-9), cap2);
    // Only the vertices within the reach and the box searched can cut the cell, and the cell only
    // shrinks: sort just those (in 3D about a third of the candidates); the others wait unsorted.
    // Among many, in bands of distance each twice as far out as the last: a band's candidates that
    // surely cannot cut the cell as the nearer ones left it count as done, unsorted and unclipped. Seen
    // from far out on the water, most of a large box is a dense shore that nearer vertices hide.
    for (double band2 = 4 * best_d2;; band2 *= 4) {
      const bool crowded = pool.size() - next > kCrowdedPool;
      const double bound2 = std::min(reach2, searched * searched);
      const double limit2 = crowded ? std::min(bound2, band2) : bound2;
      const auto band_end = std::partition(pool.begin() + long(next), pool.end(), [&](const Candidate& c) { return c.d2 <= limit2; });
      if (crowded)
        next = std::size_t(std::partition(pool.begin() + long(next), band_end, [&](const Candidate& c) {
                 return cannot_cut(c.position, c.position);
               }) - pool.begin());
      std::sort(pool.begin() + long(next), band_end, by_distance);
      const std::size_t sorted_end = std::size_t(band_end - pool.begin());
      while (next < sorted_end && pool[next].d2 <= std::min(reach2, searched * searched)) {
        if (!crowded || !cannot_cut(pool[next].position, pool[next].position)) {
          ++counters_.clips;
          if (cell_.clip(pool[next].id, pool[next].position, pool[next].d2))
            reach2 = std::min(4 * cell_.max_vertex_distance2() * (1 + 1e-9), cap2);
        }
        ++next;
      }
      if (limit2 >= std::min(reach2, searched * searched)) break;
    }
    // The box searched ends up holding the whole dependency ball (depends2 below, with its margin),
    // which the cell cache needs: it then knows every vertex, born or not, that could change the cell.
    const double need2 = reach2 * (1 + 2e-6);
    if (incremental && (need2 > searched * searched || cell_.had_vertex_on_plane())) {
      // A cell that only shrank never needs a larger box (unless by rounding); a vertex on D + 1
      // planes may have met them in another order than from scratch. Either way: compute it afresh.
      --counters_.cells_updated;
      start_afresh();
      continue;
    }
    if (need2 <= searched * searched) {
      if (incremental) cell_.end_out_of_order_cuts();
      break;
    }
    // Grow gently: the vertices found next usually shrink the cell, and with it the reach.
    searched = std::min(std::sqrt(need2) * (1 + 1e-9), 1.5 * searched);
    search(searched);
  }
  // Many candidates (a large cell among dense ones): the operation is crowded from now on, and keeps
  // only the candidates that may cut its cell. The cell cache lists them, and a fill checks its Steiner
  // point against each (pick_steiner: a point inside the cell is nearer v than any of the others).
  if (pool.size() > kCrowdedPool) {
    ops_[o].crowded = true;
    const double reach_final2 = 4 * cell_.max_vertex_distance2() * (1 + 1e-6);
    pool.erase(std::remove_if(pool.begin(), pool.end(), [&](const Candidate& c) {
                 return c.d2 > reach_final2 || cannot_cut(c.position, c.position);
               }), pool.end());
  }
  record_reads(o, p, searched);
  // Only a vertex that could cut the cell or be nearer than NN can change what this operation decides:
  // one within 2 x the cell's reach (capped at 2 beta NN), or within NN. A little margin on the rounding.
  const double reach2 = std::min(4 * cell_.max_vertex_distance2(), cap2);
  ops_[o].depends2 = ops_[o].inserted_depends2 = at_least(std::max(reach2, best_d2) * (1 + 1e-6));
  ops_[o].reach = engine::CellReach<D>::of([&](auto&& f) { cell_.for_each_vertex_box(f); });
  if (caching_) store_cell(o, v, p, searched);
  return true;
}

// A fill at rank r whose vertex v has a nearest neighbour u nearer than rho^r does nothing: u cannot
// have been inserted during rank r (Fact 2 keeps the Steiner vertices of rank r farther than rho^(r+1)
// from everything), so NN(v) < rho^r at the beginning of rank r, where Lemma 4.2 (progress) makes v
// well-spaced, and Fact 2 keeps it so. No cell is needed, and the decision depends on u alone: a vertex
// inserted only brings NN(v) down, and removing another vertex leaves NN(v) as it is.
template <int D>
void WellSpacedEngine<D>::record_idle_fill(OpId o, VertexId v) {
  const double nn2 = squared_distance(v, hood_.nearest);
  record_reads(o, positions_[v], std::sqrt(nn2) * (1 + 1e-6));
  ops_[o].depends2 = at_least(nn2 * (1 + 1e-6));
  ops_[o].inserted_depends2 = 0;  // only a vertex exactly at v's place, which reruns it
  ops_[o].facets = facet_bits(hood_.nearest);
  ops_[o].reach = engine::CellReach<D>::unbounded();
  ++counters_.fills_idle_by_rank;
}

template <int D>
void WellSpacedEngine<D>::record_reads(OpId o, const Point<D>& p, double h) {
  Point<D> lo, hi;
  for (int i = 0; i < D; ++i) {
    lo[i] = p[i] - h;
    hi[i] = p[i] + h;
  }
  tree_.covering_nodes(lo, hi, covering_);
  register_reads(o, covering_);
}

template <int D>
void WellSpacedEngine<D>::register_reads(OpId o, std::span<const NodeId> nodes) {
  ops_[o].reads_begin = reads_.allocate(nodes);
  ops_[o].reads_end = ops_[o].reads_begin + std::uint32_t(nodes.size());
  for (NodeId n : nodes) readers_[n].push_back(o);
}

template <int D>
void WellSpacedEngine<D>::request_fill(VertexId w, int rank, bool crowded) {
  for (OpId f = vertices_[w].first_fill; f != kNoOp; f = ops_[f].next_fill)
    if (ops_[f].rank == rank && !(ops_[f].flags & kDead)) {
      ++ops_[f].requesters;
      ops_[f].flags &= std::uint8_t(~kObsolete);  // asked for again before its time: it lives on
      new_children_.push_back(f);
      return;
    }
  const OpId f = new_op(OpKind::Fill, w, rank, ranks_.color(positions_[w], rank));
  ops_[f].crowded = crowded;  // a neighbour's: the places are near
  ops_[f].requesters = 1;
  ops_[f].next_fill = vertices_[w].first_fill;
  vertices_[w].first_fill = f;
  new_children_.push_back(f);
  mark_fresh(f);
}

template <int D>
void WellSpacedEngine<D>::dispatch(OpId o) {
  RoundingGuard guard;
  ++counters_.dispatches;
  const VertexId v = ops_[o].vertex;
  const int op_rank = ops_[o].rank;
  compute_cell(o, v, false);
  new_children_.clear();
  if (hood_.nearest == kNoVertex) return;  // a lone vertex is well-spaced
  PredicateCounters& pc = cell_.counters();
  const Point<D>& p = positions_[v];
  // v's fill at its current rank, and fills that update the ranks of its beta-clipped Voronoi
  // neighbours (bisector faces of the cell no farther than 2 beta NN(v): a superset, harmless, since a
  // fill at rank floor(log |vw|) finds w already well-spaced unless it truly is due), less those that
  // cannot be due (already_below_rank). v's own fill is not asked for when v is well-spaced already:
  // should NN(v) still be |vu| at the beginning of rank r, no vertex came nearer since, the cell only
  // shrank, and v is well-spaced through rank r (Fact 2), so the fill would insert nothing; should a
  // vertex z come nearer first, v's fill at the new rank is the business of z's dispatch (Lemma 4.1).
  const int r = ranks_.rank_of(p, positions_[hood_.nearest], pc);
  const bool well_spaced = cell_.within_scaled_distance(params_.fill_rho_squared, positions_[hood_.nearest]);
  if (r >= op_rank && (params_.literal_stable_ws || !well_spaced)) request_fill(v, r, ops_[o].crowded);
  const double limit2 = 4 * params_.beta_squared * squared_distance(v, hood_.nearest) * (1 + 1e-9);
  cell_.bisector_neighbours(neighbours_);
  for (VertexId w : neighbours_) {
    if (squared_distance(v, w) > limit2) continue;
    const int rw = ranks_.rank_of(p, positions_[w], pc);
    if (rw < op_rank || (!params_.literal_stable_ws && already_below_rank(w, rw, pc))) continue;
    request_fill(w, rw, ops_[o].crowded);
  }
  store_children(o);
  record_facets(o);
}

// A fill of neighbour w at rank rw can only be due if v may be w's nearest neighbour at that rank. Say
// another neighbour x of v lies nearer w than rho^rw (|wx|^2 < T_rw, exact). Both were born before this
// dispatch, which runs at rank <= rw, so both are in the output at the beginning of rank rw, and
// NN(w) < rho^rw there. By Lemma 4.2 (progress) w is then rho-well-spaced, and by Fact 2 the Steiner
// vertices of rank rw keep it so: the fill would find w well-spaced and insert nothing. Figure 3 asks
// for it anyway, to keep its proof short; leaving it out keeps the output bit for bit (IdleFills tests)
// with a third fewer operations in 2D and two fifths fewer in 3D. Taking the witnesses x among v's
// cell neighbours adds no dependency: this dispatch already reruns when one of them goes (they bound
// the cell: facet filter) or when a vertex that would be one arrives (it cuts the cell: cell reach).
template <int D>
bool WellSpacedEngine<D>::already_below_rank(VertexId w, int rw, PredicateCounters& pc) const {
  for (VertexId x : neighbours_)
    if (x != w && ranks_.rank_below(positions_[w], positions_[x], rw, pc)) return true;
  return false;
}

template <int D>
void WellSpacedEngine<D>::fill(OpId o) {
  RoundingGuard guard;
  ++counters_.fills;
  const VertexId v = ops_[o].vertex;
  const int op_rank = ops_[o].rank;
  const std::uint32_t op_color = ops_[o].color;
  // The Steiner vertices of this fill's previous run, when it runs again (see undo).
  stash_.clear();
  if (ops_[o].flags & kStashed) {
    for (OpId d : children(o)) stash_.push_back(d);
    release_children(ops_[o]);
    ops_[o].flags &= std::uint8_t(~kStashed);
  }
  const bool has_cell = compute_cell(o, v, true);
  new_children_.clear();
  PredicateCounters& pc = cell_.counters();
  for (int inserted = 0; has_cell && hood_.nearest != kNoVertex &&
                         !cell_.within_scaled_distance(params_.fill_rho_squared, positions_[hood_.nearest]);
       ++inserted) {
    if (inserted > 1000) throw std::logic_error("fill inserted over 1000 Steiner points around one vertex");
    const Point<D> w = pick_steiner(v);
    auto again = std::find_if(stash_.begin(), stash_.end(), [&](OpId d) { return positions_[ops_[d].vertex] == w; });
    if (again != stash_.end()) {
      // The same Steiner point as before: keep the vertex and its dispatch, nothing changes around it.
      const OpId d = *again;
      *again = stash_.back();
      stash_.pop_back();
      const VertexId id = ops_[d].vertex;
      new_children_.push_back(d);
      const double d2 = squared_distance(v, id);
      cell_.clip(id, w, d2);
      hood_.candidates.push_back({d2, id, w});
      continue;
    }
    const VertexId id = new_vertex(w);
    vertices_[id].creator = o;
    vertices_[id].leaf = tree_.insert_vertex(id, w, time_key(op_rank, op_color), vertices_[v].leaf);
    ++counters_.steiner_points;
    if (dynamic_) mark_readers_at(id, w, vertices_[id].leaf, VertexChange::Inserted, op_rank, op_color);
    if (caching_) vertex_arrived(id, w, time_key(op_rank, op_color));
    if (stats_) stats_->steiner_added.push_back(w);
    // Fact 1 puts w's rank above op's; the max only guards the table's rounding for a rho other than
    // sqrt(2) (for sqrt(2) the table is exact and it never applies).
    const int rank = std::max(ranks_.rank_of(w, positions_[v], pc), op_rank + 1);
    const OpId d = new_op(OpKind::Dispatch, id, rank, 0);
    ops_[d].crowded = ops_[o].crowded;
    vertices_[id].dispatch = d;
    new_children_.push_back(d);
    mark_fresh(d);
    const double d2 = squared_distance(v, id);
    cell_.clip(id, w, d2);
    hood_.candidates.push_back({d2, id, w});
  }
  store_children(o);
  // v was already well-spaced: a vertex inserted farther than NN(v) leaves NN(v) and the clipping cube
  // as they are and can only shrink the cell, so v stays well-spaced and this fill does nothing again.
  if (has_cell && new_children_.empty() && hood_.nearest != kNoVertex) {
    ops_[o].inserted_depends2 = at_least(squared_distance(v, hood_.nearest) * (1 + 1e-6));
    cell_.bisector_neighbours(neighbours_);
    record_facets(o);
  }
  // Steiner vertices of the previous run not inserted again leave the output.
  for (OpId d : stash_) {
    const VertexId w = ops_[d].vertex;
    mark_obsolete(d);
    tree_.erase_vertex(w, vertices_[w].leaf);
    mark_readers_at(w, positions_[w], vertices_[w].leaf, VertexChange::Removed, op_rank, op_color);
    kill_vertex(w);
    if (stats_) stats_->steiner_removed.push_back(positions_[w]);
  }
  stash_.clear();
}

// The Steiner point: toward the cell vertex c farthest from v, at distance min(|vc|, beta NN) shrunk by
// 2^-10 (so it lies strictly inside the cell, away from the bisectors through c, and rounding cannot push
// it out), but never nearer than rho NN. That is the largest admissible step, which keeps the output
// small: the farthest Voronoi vertex is the circumcentre of the worst Delaunay simplex at v, the point
// Delaunay refinement inserts. Every condition of the picking region is then checked exactly.
template <int D>
Point<D> WellSpacedEngine<D>::pick_steiner(VertexId v) {
  PredicateCounters& pc = cell_.counters();
  const Point<D> p = positions_[v];
  const Point<D> u = positions_[hood_.nearest];
  const Point<D> y = cell_.farthest_vertex_offset();
  double len2 = 0;
  for (int i = 0; i < D; ++i) len2 += y[i] * y[i];
  const double len = std::sqrt(len2);
  const double nn = std::sqrt(squared_distance(v, hood_.nearest));
  const double reach = std::min(len, params_.beta * nn);
  const double fallback = 0.5 * (params_.rho * nn + reach);
  double target = reach * (1 - 0x1p-10);
  if (target < params_.rho * nn * (1 + 0x1p-10)) target = fallback;
  for (double t : {target, fallback}) {
    Point<D> w;
    for (int i = 0; i < D; ++i) w[i] = std::clamp(p[i] + y[i] * (t / len), 0.0, 1.0);
    if (compare_squared_distance_scaled<D>(pc, w, p, params_.rho_squared, u, p) < 0) continue;
    if (compare_squared_distance_scaled<D>(pc, w, p, params_.beta_squared, u, p) >= 0) continue;
    bool inside = true;
    for (const Candidate& c : hood_.candidates)
      if (compare_squared_distances<D>(pc, w, p, w, c.position) >= 0) {
        inside = false;
        break;
      }
    if (inside) return w;
  }
  throw std::logic_error("no admissible Steiner point in the picking region of a vertex");
}

template <int D>
typename WellSpacedEngine<D>::VertexId WellSpacedEngine<D>::new_vertex(const Point<D>& p) {
  Vertex vx;
  vx.position = p;
  vx.alive = true;
  if (!free_vertices_.empty()) {
    const VertexId id = free_vertices_.back();
    free_vertices_.pop_back();
    vx.filter_key = id;
    vertices_[id] = vx;
    positions_[id] = p;
    return id;
  }
  vx.filter_key = std::uint32_t(vertices_.size());
  vertices_.push_back(vx);
  positions_.push_back(p);
  return VertexId(vertices_.size() - 1);
}

// After the quadtree changed: vertices in new leaves learn their leaf; readers of squares that were
// split or deleted are inconsistent (their registrations go with the squares); input vertices in new
// leaves have a new QTApxNN, so their dispatches are replaced.
template <int D>
void WellSpacedEngine<D>::apply_tree_change(const typename engine::Quadtree<D>::Change& change) {
  if (readers_.size() < tree_.node_capacity()) readers_.resize(tree_.node_capacity());
  for (NodeId n : change.removed_leaves) {
    mark_all_readers(n);
    readers_[n].clear();
  }
  for (NodeId n : change.new_leaves) {
    for (const LeafVertex<D>& e : tree_.node(n).vertices) vertices_[e.id].leaf = n;
    const VertexId input = tree_.node(n).input_vertex;
    if (input != kNoVertex) redispatch_input(input);
  }
}

template <int D>
void WellSpacedEngine<D>::redispatch_input(VertexId v) {
  if (vertices_[v].dispatch != kNoOp) mark_obsolete(vertices_[v].dispatch);
  const int rank = ranks_.rank_of_length(tree_.approximate_nn(vertices_[v].leaf));
  const OpId o = new_op(OpKind::Dispatch, v, rank, 0);
  vertices_[v].dispatch = o;
  mark_fresh(o);
}

template <int D>
std::vector<typename WellSpacedEngine<D>::VertexId> WellSpacedEngine<D>::apply(std::span<const InputEdit> edits,
                                                                              PropagationStats* stats) {
  std::vector<VertexId> added;
  for (const InputEdit& e : edits) {
    if (e.add) {
      const VertexId v = new_vertex(e.point);
      vertices_[v].is_input = true;
      ++input_count_;
      const auto change = tree_.add_input(v, positions_);
      vertices_[v].leaf = tree_.locate(e.point);
      apply_tree_change(change);
      // The new vertex changes what every reader of its square saw.
      mark_readers_at(v, e.point, vertices_[v].leaf, VertexChange::Inserted, kBeforeEverything, 0);
      if (vertices_[v].dispatch == kNoOp || ops_[vertices_[v].dispatch].vertex != v) redispatch_input(v);
      added.push_back(v);
    } else {
      const VertexId v = e.vertex;
      const Point<D> p = positions_[v];
      const auto change = tree_.remove_input(v, positions_);
      --input_count_;
      apply_tree_change(change);
      const NodeId leaf = tree_.locate(p);
      mark_readers_at(v, p, leaf, VertexChange::Removed, kBeforeEverything, 0);
      // The input vertex of the leaf that now holds p has a new neighbourhood too.
      if (tree_.node(leaf).input_vertex != kNoVertex) redispatch_input(tree_.node(leaf).input_vertex);
      kill_vertex(v);  // an input, not a Steiner change: the report does not list it
    }
  }
  propagate(stats);
  if (stats) {
    // Net change: a Steiner point taken back and inserted again at the same place is no change.
    auto& r = stats->steiner_removed;
    auto& a = stats->steiner_added;
    std::sort(r.begin(), r.end());
    std::sort(a.begin(), a.end());
    std::vector<Point<D>> removed, inserted;
    std::set_difference(r.begin(), r.end(), a.begin(), a.end(), std::back_inserter(removed));
    std::set_difference(a.begin(), a.end(), r.begin(), r.end(), std::back_inserter(inserted));
    r = std::move(removed);
    a = std::move(inserted);
  }
  return added;
}

template <int D>
typename WellSpacedEngine<D>::VertexId WellSpacedEngine<D>::input_at(const Point<D>& p) const {
  const NodeId leaf = tree_.locate(p);
  const VertexId v = tree_.node(leaf).input_vertex;
  return (v != kNoVertex && positions_[v] == p) ? v : kNoVertex;
}

template <int D>
std::vector<std::tuple<Point<D>, int, std::uint32_t>> WellSpacedEngine<D>::operation_signature() const {
  std::vector<std::tuple<Point<D>, int, std::uint32_t>> sig;
  for (const Op& op : ops_)
    if (!(op.flags & kDead)) sig.emplace_back(positions_[op.vertex], op.rank, op.color);
  std::sort(sig.begin(), sig.end());
  return sig;
}

template <int D>
std::size_t WellSpacedEngine<D>::memory_bytes() const {
  std::size_t bytes = vertices_.capacity() * sizeof(Vertex) + positions_.capacity() * sizeof(Point<D>) +
                      ops_.capacity() * sizeof(Op) + children_.memory_bytes() +
                      reads_.memory_bytes() + readers_.size() * sizeof(std::vector<OpId>) +
                      (free_ops_.capacity() + free_vertices_.capacity()) * sizeof(std::uint32_t) +
                      tree_.memory_bytes();
  for (const auto& r : readers_) bytes += r.capacity() * sizeof(OpId);
  bytes += cell_cache_.capacity() * sizeof(CachedCell) + cache_table_.capacity() * sizeof(CacheSlot);
  for (const CachedCell& c : cell_cache_)
    bytes += c.candidates.capacity() * sizeof(Candidate) + c.covering.capacity() * sizeof(NodeId) +
             (c.unborn.capacity() + c.arrived.capacity()) * sizeof(TimedVertex) + c.cell.memory_bytes();
  return bytes;
}

template <int D>
void WellSpacedEngine<D>::check_valid() const {
  auto fail = [](const std::string& what) { throw std::logic_error("engine invalid: " + what); };
  tree_.check_valid(positions_);
  std::size_t inputs = 0;
  for (VertexId v = 0; v < vertices_.size(); ++v) {
    const Vertex& vx = vertices_[v];
    if (!vx.alive) continue;
    if (vx.is_input) ++inputs;
    if (vx.position != positions_[v]) fail("vertex position copy");
    const auto& list = tree_.node(vx.leaf).vertices;
    if (!tree_.node(vx.leaf).is_leaf() ||
        std::none_of(list.begin(), list.end(), [&](const LeafVertex<D>& e) { return e.id == v; }))
      fail("vertex " + std::to_string(v) + " not in its leaf");
    if (vx.dispatch == kNoOp || ops_[vx.dispatch].vertex != v || ops_[vx.dispatch].kind != OpKind::Dispatch)
      fail("vertex " + std::to_string(v) + " without its dispatch");
    if (!vx.is_input && (vx.creator == kNoOp || ops_[vx.creator].kind != OpKind::Fill)) fail("Steiner vertex creator");
  }
  if (inputs != input_count_) fail("input count");
  if (!agenda_.empty()) fail("agenda not empty after propagation");
  for (OpId o = 0; o < ops_.size(); ++o) {
    const Op& op = ops_[o];
    if (op.flags & kDead) continue;
    if (op.flags != kExecuted) fail("operation " + std::to_string(o) + " left in state " + std::to_string(op.flags));
    if (op.vertex >= vertices_.size() || !vertices_[op.vertex].alive) fail("operation on a dead vertex");
    if ((op.kind == OpKind::Dispatch) != (op.color == 0)) fail("colour 0 is for dispatches only");
    if (op.kind == OpKind::Fill && op.requesters == 0) fail("a fill nobody asks for");
    for (OpId c : children(o)) {
      if (c >= ops_.size() || (ops_[c].flags & kDead))
        fail("operation " + std::to_string(o) + " (" + (op.kind == OpKind::Fill ? "fill" : "dispatch") + " rank " +
             std::to_string(op.rank) + " colour " + std::to_string(op.color) + ", vertex " + std::to_string(op.vertex) +
             (vertices_[op.vertex].is_input ? " input" : " Steiner") + ") has deleted child " + std::to_string(c));
      if (ops_[c].rank < op.rank) fail("a child runs before its parent");
    }
    for (NodeId n : reads(o)) {
      const auto& rs = readers_[n];
      if (std::find(rs.begin(), rs.end(), o) == rs.end()) fail("read edge without reader entry");
    }
  }
  // Memory is reclaimed: no reader entry of a deleted operation survives, and every block of the pools
  // holds a live operation's run or is free.
  for (const auto& rs : readers_)
    for (OpId o : rs)
      if (ops_[o].flags & kDead) fail("reader entry of a deleted operation");
  const PoolEntries live = live_pool_entries();
  if (live.children + children_.free_entries() != children_.size()) fail("a children block lost");
  if (live.reads + reads_.free_entries() != reads_.size()) fail("a reads block lost");
}

template class WellSpacedEngine<2>;
template class WellSpacedEngine<3>;

}  // namespace shoremesh
