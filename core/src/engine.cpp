#include "shoremesh/engine/engine.hpp"
#include "shoremesh/engine/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "shoremesh/error.hpp"
#include "engine_internal.hpp"

namespace shoremesh {

using namespace engine;
using namespace engine_detail;

namespace {
// A run's length as an Op keeps it. Runs are short: a dispatch asks for a fill per cell neighbour, a fill
// inserts at most a thousand points, an operation reads the few nodes covering one box.
std::uint16_t run_length(std::size_t length) {
  if (length > std::numeric_limits<std::uint16_t>::max()) throw std::length_error("an operation's run of over 65535 ids");
  return std::uint16_t(length);
}
// Room for one more item of a build's growing array, a quarter more at a time instead of the double a
// push_back takes: the vertex, position and operation arrays end a build with at most a fifth unused
// instead of up to half, and each move holds 2.25 times the array, not 3. The copies (five per item
// instead of one) cost little against the operations that make the items.
template <class T>
void room_for_one(std::vector<T>& items) {
  if (items.size() == items.capacity()) items.reserve(items.size() + items.size() / 4 + 1024);
}
}  // namespace

template <int D>
WellSpacedEngine<D>::WellSpacedEngine(const Parameters<D>& parameters)
    : params_(DerivedParameters<D>::derive(parameters)), ranks_(params_) {
  // An Op keeps its rank and colour in 16 bits each; the lowest rank is kept free so that no time key
  // is 0, the inputs' birth.
  if (ranks_.min_rank() <= std::numeric_limits<std::int16_t>::min() || ranks_.max_rank() > std::numeric_limits<std::int16_t>::max() ||
      ranks_.color_count() >= std::numeric_limits<std::uint16_t>::max())
    throw std::invalid_argument("parameters give over 2^15 ranks or 2^16 colours (rho too near 1 or kappa too large)");
}

template <int D>
WellSpacedEngine<D>::~WellSpacedEngine() = default;

template <int D>
void WellSpacedEngine<D>::reset() {
  vertices_.clear();
  vertex_ops_.clear();
  positions_.clear();
  lean_ops_.clear();
  recorded_ops_.clear();
  children_.clear();
  readers_.clear();
  for (auto& bucket : agenda_) bucket.clear();
  agenda_next_ = 0;
  agenda_size_ = 0;
  free_ops_.clear();
  lean_free_ = kNoOp;
  lean_free_count_ = 0;
  dead_ops_.clear();
  free_vertices_.clear();
  dead_vertices_.clear();
  counters_ = Counters{};
  serial_.cell.counters() = PredicateCounters{};
  input_count_ = 0;
  dynamic_ = false;
  caching_ = false;
  recording_ = true;
  cell_cache_live_ = 0;
  cache_table_.clear();
  delaunay_.reset();
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
                                                                                  bool for_updates) {
  return build(unit_points, nullptr, for_updates);
}

template <int D>
std::vector<typename WellSpacedEngine<D>::VertexId> WellSpacedEngine<D>::build(std::vector<Point<D>>&& unit_points,
                                                                                  bool for_updates) {
  return build(std::span<const Point<D>>(unit_points), &unit_points, for_updates);
}

template <int D>
std::vector<typename WellSpacedEngine<D>::VertexId> WellSpacedEngine<D>::build(std::span<const Point<D>> unit_points,
                                                                                  std::vector<Point<D>>* own,
                                                                                  bool for_updates) {
  reset();
  recording_ = for_updates;
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
  for (VertexId v = 0; v < input_count_; ++v) vertex_of_point[along_curve[v]] = v;
  if (own) {
    positions_ = std::move(*own);  // unit_points' array: not read from here on
    engine_detail::permute_in_place(positions_, vertex_of_point);
  } else {
    positions_.resize(input_count_);
    for (VertexId v = 0; v < input_count_; ++v) positions_[v] = unit_points[along_curve[v]];
  }
  vertices_.resize(input_count_);
  std::vector<VertexId> ids(input_count_);
  for (VertexId v = 0; v < input_count_; ++v) {
    vertices_[v].is_input = true;
    vertices_[v].alive = true;
    ids[v] = v;
  }
  if (recording_) vertex_ops_.resize(input_count_);
  tree_.build(positions_, ids, for_updates);
  for (NodeId n = 0; n < tree_.node_capacity(); ++n) {
    const auto& nd = tree_.node(n);
    if (nd.level < 0 || !nd.is_leaf()) continue;
    for (const LeafVertex<D>& e : nd.vertices) vertices_[e.id].leaf = n;
  }
  if (recording_) readers_.grow_to(tree_.node_capacity());
  if constexpr (D == 2)
    if (!for_updates && engine::delaunay_neighbours()) {
      delaunay_ = std::make_unique<engine::DelaunayNeighbours>();
      delaunay_->build(positions_);
    }
  // Input dispatches at the rank of QTApxNN(v) (a quarter of the side of its leaf): NN from below.
  for (VertexId v = 0; v < input_count_; ++v) {
    const int rank = ranks_.rank_of_length(tree_.approximate_nn(vertices_[v].leaf));
    const OpId o = new_op(OpKind::Dispatch, v, rank, 0);
    if (recording_) vertex_ops_[v].dispatch = o;
    mark_fresh(o);
  }
  // StableWS is a propagation in which every operation is fresh.
  propagate(nullptr);
  if (for_updates) {
    const std::vector<VertexId> new_id = renumber_vertices_by_place();
    for (VertexId& v : vertex_of_point) v = new_id[v];
    renumber_operations_by_place();
    // Room to grow in every reader list. Updates register readers again, and a list that outgrows its
    // block moves to a block elsewhere, away from the lists of its neighbours, which marking and undo
    // walk together: at 2D n = 1e6 the median update grew by a fifth over 40,000 changes without room,
    // by about a tenth with it (bench/RESULTS.md).
    readers_.lay_out();
  }
  dynamic_ = for_updates;
  return vertex_of_point;
}

template <int D>
typename WellSpacedEngine<D>::OpId WellSpacedEngine<D>::new_op(OpKind kind, VertexId v, int rank,
                                                               std::uint32_t color) {
  auto place = [&](auto& ops) {
    typename std::remove_reference_t<decltype(ops)>::value_type item{};
    item.kind = kind;
    item.vertex = v;
    item.rank = std::int16_t(rank);
    item.color = std::uint16_t(color);
    if (!free_ops_.empty()) {
      const OpId o = free_ops_.back();
      free_ops_.pop_back();
      ops[o] = item;
      return o;
    }
    if (lean_free_ != kNoOp) {
      const OpId o = lean_free_;
      lean_free_ = ops[o].next_fill;
      --lean_free_count_;
      ops[o] = item;
      return o;
    }
    if (!dynamic_) room_for_one(ops);
    ops.push_back(item);
    return OpId(ops.size() - 1);
  };
  return recording_ ? place(recorded_ops_) : place(lean_ops_);
}

template <int D>
void WellSpacedEngine<D>::enqueue(OpId o) {
  Op& op = op_at(o);
  if (op.flags & kQueued) return;
  op.flags |= kQueued;
  agenda_[agenda_slot(op.rank, op.color)].push_back(o);
  ++agenda_size_;
}

// The bucket of time (rank, colour), made when new (below the lowest rank so far too).
template <int D>
std::size_t WellSpacedEngine<D>::agenda_slot(int rank, std::uint32_t color) {
  const std::size_t colors = ranks_.color_count() + 1;  // dispatches 0, fills 1..kappa^D
  if (agenda_.empty()) agenda_base_rank_ = rank;
  if (rank < agenda_base_rank_) {
    const std::size_t shift = std::size_t(agenda_base_rank_ - rank) * colors;
    agenda_.insert(agenda_.begin(), shift, std::vector<OpId>{});
    agenda_base_rank_ = rank;
    agenda_next_ += shift;
  }
  const std::size_t slot = std::size_t(rank - agenda_base_rank_) * colors + color;
  if (slot >= agenda_.size()) agenda_.resize(slot + 1);
  agenda_next_ = std::min(agenda_next_, slot);
  return slot;
}

template <int D>
void WellSpacedEngine<D>::mark_fresh(OpId o) {
  op_at(o).flags |= kFresh;
  enqueue(o);
}

template <int D>
void WellSpacedEngine<D>::mark_obsolete(OpId o) {
  if (op_at(o).flags & kDead) return;
  op_at(o).flags |= kObsolete;
  enqueue(o);
}

template <int D>
void WellSpacedEngine<D>::mark_redo(OpId o) {
  Op& op = op_at(o);
  // Also when obsolete: a fill whose requesters all went away may be asked for again before its time,
  // and must then run again if what it read changed meanwhile.
  if ((op.flags & kDead) || !(op.flags & kExecuted)) return;
  op.flags |= kRedo;
  enqueue(o);
}

template <int D>
void WellSpacedEngine<D>::mark_readers_at(const Point<D>& p, NodeId leaf, VertexChange change, int rank, std::uint32_t color) {
  const bool inserted = change == VertexChange::Inserted;
  const auto bits = facet_bits_at(p);
  // The lists of the coarse nodes hold hundreds of readers each, scattered over recorded_ops_ (an array too large
  // for the caches at 10^6 inputs): each one's Op is fetched a few entries ahead.
  constexpr std::size_t kAhead = 8;
  for (NodeId n = leaf; n != kNoNode; n = tree_.parent(n)) {
    const std::span<const OpId> list = readers_.list(n);
    for (std::size_t k = 0; k < std::min(kAhead, list.size()); ++k) __builtin_prefetch(&recorded_ops_[list[k]]);
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (k + kAhead < list.size()) __builtin_prefetch(&recorded_ops_[list[k + kAhead]]);
      const OpId o = list[k];
      const RecordedOp& op = recorded_ops_[o];
      if (op.rank < rank || (op.rank == rank && op.color <= color)) continue;
      if (!inserted && !op.facets.may_hold(bits)) continue;
      const Point<D>& c = positions_[op.vertex];
      Point<D> d;
      double d2 = 0;
      for (int i = 0; i < D; ++i) {
        d[i] = p[i] - c[i];
        d2 += d[i] * d[i];
      }
      if (d2 > (inserted ? op.inserted_depends2() : double(op.depends2))) continue;
      if (inserted && !op.reach.may_be_cut_by(d)) continue;
      mark_redo(o);
    }
  }
}

template <int D>
void WellSpacedEngine<D>::record_facets(OpId o, const Worker& wk) {
  auto facets = facet_bits(wk.hood.nearest);
  for (VertexId w : wk.neighbours) facets.add(facet_bits(w));
  recorded_ops_[o].facets = facets;
}

template <int D>
void WellSpacedEngine<D>::mark_all_readers(NodeId n) {
  for (OpId o : readers_.list(n)) mark_redo(o);
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
  while (agenda_size_ > 0) {
    while (agenda_[agenda_next_].empty()) ++agenda_next_;
    batch_.clear();
    batch_.swap(agenda_[agenda_next_]);
    // A build never comes back to a time it has processed: the bucket's array (the last batch's) goes.
    // Updates keep theirs for the next propagation.
    if (!dynamic_) std::vector<OpId>().swap(agenda_[agenda_next_]);
    agenda_size_ -= batch_.size();
    for (OpId o : batch_) op_at(o).flags &= std::uint8_t(~kQueued);
    // The vertices committed at earlier times join the triangulation; this time's wait (M_t).
    if (delaunay_) delaunay_->insert_born_before(time_key(op_at(batch_[0]).rank, op_at(batch_[0]).color));
    // In any order (Lemma 6.1); along the curve, so that the Steiner vertices and operations a large
    // batch creates (a build's) are numbered, and later read, in the order of their places.
    if (batch_.size() > kSortedBatch) sort_batch_by_place();
    // A build's batches hold fresh operations only: computed on every thread when large enough.
    if (!dynamic_ && batch_.size() >= kParallelBatch && engine::thread_count() > 1) {
      execute_batch_in_parallel();
      continue;
    }
    for (OpId o : batch_) {
      Op& op = op_at(o);
      if (op.kind == OpKind::Fill && op.requesters == 0) op.flags |= kObsolete;
      if ((op.flags & (kObsolete | kRedo)) && (op.flags & kExecuted)) undo(o);
    }
    for (OpId o : batch_) {
      const std::uint8_t f = op_at(o).flags;
      if (f & kDead) continue;
      if (f & kObsolete) kill(o);
      else if (f & (kRedo | kFresh)) execute(o);
    }
  }
  clear_cell_cache();
  caching_ = false;
  collect_counters();
  // Slots of deleted operations and vertices are reused from now on.
  for (OpId o : dead_ops_) {
    if (recording_) recorded_ops_[o] = RecordedOp{};
    else lean_ops_[o] = Op{};
    op_at(o).flags = kDead;
    free_ops_.push_back(o);
  }
  dead_ops_.clear();
  for (VertexId v : dead_vertices_) free_vertices_.push_back(v);
  dead_vertices_.clear();
  stats_ = nullptr;
}

// The batch along the curve: by z-order key, ties by operation id. A least-significant-digit radix sort
// (stable) by the key, digits that are the same throughout skipped, then the rare runs of equal keys by
// id: the order std::sort gives the pairs, without its comparisons (the batch sort was a tenth of the
// agenda's time).
template <int D>
void WellSpacedEngine<D>::sort_batch_by_place() {
  constexpr int kDigitBits = 11;
  constexpr int kDigits = (64 + kDigitBits - 1) / kDigitBits;
  constexpr std::size_t kRadix = std::size_t(1) << kDigitBits;
  const std::size_t m = batch_.size();
  batch_keys_.resize(m);
  batch_keys_scratch_.resize(m);
  // The keys read each operation's vertex, scattered over memory: a build's large batches (all fresh,
  // nothing else runs meanwhile) fetch them on every thread.
  auto key_at = [&](std::size_t k) {
    batch_keys_[k] = {engine::z_order_key<D>(positions_[op_at(batch_[k]).vertex]), batch_[k]};
  };
  if (!dynamic_ && m >= kParallelBatch && engine::thread_count() > 1)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 1024), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t k = range.begin(); k != range.end(); ++k) key_at(k);
    });
  else
    for (std::size_t k = 0; k < m; ++k) key_at(k);
  std::vector<std::uint32_t> counts(kDigits * kRadix, 0);
  for (const auto& [key, o] : batch_keys_)
    for (int d = 0; d < kDigits; ++d) ++counts[std::size_t(d) * kRadix + (key >> (d * kDigitBits) & (kRadix - 1))];
  for (int d = 0; d < kDigits; ++d) {
    std::uint32_t* c = counts.data() + std::size_t(d) * kRadix;
    const std::uint64_t first_digit = batch_keys_[0].first >> (d * kDigitBits) & (kRadix - 1);
    if (c[first_digit] == m) continue;  // one digit value: this pass would keep the order
    std::uint32_t sum = 0;
    for (std::size_t b = 0; b < kRadix; ++b) {
      const std::uint32_t n = c[b];
      c[b] = sum;
      sum += n;
    }
    for (const auto& e : batch_keys_) batch_keys_scratch_[c[e.first >> (d * kDigitBits) & (kRadix - 1)]++] = e;
    batch_keys_.swap(batch_keys_scratch_);
  }
  for (std::size_t k = 0; k < m;) {
    std::size_t e = k + 1;
    while (e < m && batch_keys_[e].first == batch_keys_[k].first) ++e;
    if (e - k > 1) std::sort(batch_keys_.begin() + long(k), batch_keys_.begin() + long(e));
    k = e;
  }
  for (std::size_t k = 0; k < m; ++k) batch_[k] = batch_keys_[k].second;
  // A build's largest batches come first (the input dispatches): its keys would be held to the end,
  // 32 bytes per operation of the largest batch. Updates sort small batches again and again.
  if (!dynamic_) {
    std::vector<std::pair<std::uint64_t, OpId>>().swap(batch_keys_);
    std::vector<std::pair<std::uint64_t, OpId>>().swap(batch_keys_scratch_);
  }
}

// Takes back what operation o did: the fills a dispatch asked for lose a requester; the Steiner vertices
// a fill inserted leave the output (their operations become obsolete, their readers inconsistent); its
// read registrations go.
template <int D>
void WellSpacedEngine<D>::undo(OpId o) {
  RecordedOp& op = recorded_ops_[o];
  const int rank = op.rank;
  const std::uint32_t color = op.color;
  const std::uint32_t cb = op.children_begin, ce = op.children_begin + op.children_count;
  if (op.kind == OpKind::Dispatch) {
    for (std::uint32_t k = cb; k < ce; ++k) {
      Op& child = op_at(children_[k]);
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
      const VertexId w = op_at(d).vertex;
      mark_obsolete(d);
      if (!vertices_[w].alive) continue;
      tree_.erase_vertex(w, vertices_[w].leaf);
      mark_readers_at(positions_[w], vertices_[w].leaf, VertexChange::Removed, rank, color);
      kill_vertex(w);
      if (stats_) stats_->steiner_removed.push_back(positions_[w]);
    }
  }
  RecordedOp& again = recorded_ops_[o];
  if (again.reads_count != 0) {
    tree_.cover_nodes(positions_[again.vertex], again.reads_cover, undone_reads_);
    for (NodeId n : undone_reads_) readers_.erase(n, o);
  }
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
  if (vertex_ops_[v].dispatch != kNoOp) mark_obsolete(vertex_ops_[v].dispatch);
  for (OpId f = vx.first_fill; f != kNoOp; f = op_at(f).next_fill) mark_obsolete(f);
  dead_vertices_.push_back(v);
}

template <int D>
void WellSpacedEngine<D>::kill(OpId o) {
  RecordedOp& op = recorded_ops_[o];
  unlink_from_vertex(o);
  release_reads(op);  // none once undone; a fresh operation never ran
  release_children(op);
  op.flags = kDead;
  dead_ops_.push_back(o);
}


template <int D>
void WellSpacedEngine<D>::release_reads(RecordedOp& op) {
  op.reads_cover = 0;
  op.reads_count = 0;
}

template <int D>
void WellSpacedEngine<D>::release_children(RecordedOp& op) {
  children_.release(op.children_begin, op.children_count);
  op.children_begin = 0;
  op.children_count = 0;
}

// The children the operation being executed gathered in new_children_ become its run.
template <int D>
void WellSpacedEngine<D>::store_children(OpId o) {
  recorded_ops_[o].children_count = run_length(new_children_.size());
  recorded_ops_[o].children_begin = children_.allocate(new_children_);
}

template <int D>
void WellSpacedEngine<D>::register_reads(OpId o, std::span<const NodeId> nodes, std::uint32_t cover) {
  // covering_nodes gives at most 2^D: more would not fit the count's bits.
  if (nodes.size() > Op::kMaxReads) throw std::logic_error("an operation registered as a reader of over 15 nodes");
  recorded_ops_[o].reads_count = std::uint8_t(nodes.size());
  recorded_ops_[o].reads_cover = cover;
  for (NodeId n : nodes) readers_.push(n, o);
}


template <int D>
typename WellSpacedEngine<D>::VertexId WellSpacedEngine<D>::new_vertex(const Point<D>& p) {
  Vertex vx;
  vx.alive = true;
  if (!free_vertices_.empty()) {
    const VertexId id = free_vertices_.back();
    free_vertices_.pop_back();
    vertices_[id] = vx;
    positions_[id] = p;
    if (recording_) vertex_ops_[id] = VertexOps{};
    return id;
  }
  if (!dynamic_) {
    room_for_one(vertices_);
    room_for_one(positions_);
    if (recording_) room_for_one(vertex_ops_);
  }
  vertices_.push_back(vx);
  positions_.push_back(p);
  if (recording_) vertex_ops_.emplace_back();
  return VertexId(vertices_.size() - 1);
}

// After the quadtree changed: vertices in new leaves learn their leaf; readers of squares that were
// split or deleted are inconsistent (their registrations go with the squares); input vertices in new
// leaves have a new QTApxNN, so their dispatches are replaced.
template <int D>
void WellSpacedEngine<D>::apply_tree_change(const typename engine::Quadtree<D>::Change& change) {
  readers_.grow_to(tree_.node_capacity());
  for (NodeId n : change.removed_leaves) {
    mark_all_readers(n);
    readers_.clear(n);
  }
  for (NodeId n : change.new_leaves) {
    for (const LeafVertex<D>& e : tree_.node(n).vertices) vertices_[e.id].leaf = n;
    const VertexId input = tree_.node(n).input_vertex;
    if (input != kNoVertex) redispatch_input(input);
  }
}

template <int D>
void WellSpacedEngine<D>::redispatch_input(VertexId v) {
  if (vertex_ops_[v].dispatch != kNoOp) mark_obsolete(vertex_ops_[v].dispatch);
  const int rank = ranks_.rank_of_length(tree_.approximate_nn(vertices_[v].leaf));
  const OpId o = new_op(OpKind::Dispatch, v, rank, 0);
  vertex_ops_[v].dispatch = o;
  mark_fresh(o);
}

template <int D>
void WellSpacedEngine<D>::set_water(std::vector<std::vector<Point2>> unit_rings) {
  if constexpr (D != 2) {
    (void)unit_rings;
    throw std::logic_error("a water domain is for 2D engines");
  } else {
    water_ = std::make_unique<WaterRings>();
    water_->assign(std::move(unit_rings));
  }
}

template <int D>
std::vector<typename WellSpacedEngine<D>::VertexId> WellSpacedEngine<D>::vertices_skipped_on_land() const {
  std::vector<VertexId> out;
  for (OpId o = 0; o < op_count(); ++o) {
    const Op& x = op(o);
    if (!(x.flags & kDead) && x.kind == OpKind::Fill && x.on_land) out.push_back(x.vertex);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Every fill that read the water in the box: a fill reads it only inside the box it tests (fill_on_land),
// which lies in the box its search covered, and so in the nodes it registered on. Any node meeting the
// changed box, at any level, may hold such a registration: the walk goes down from the root through
// every node that meets it.
template <int D>
void WellSpacedEngine<D>::mark_water_readers(const Point<D>& lo, const Point<D>& hi) {
  std::vector<NodeId> stack{tree_.root()};
  while (!stack.empty()) {
    const NodeId n = stack.back();
    stack.pop_back();
    const auto& nd = tree_.node(n);
    std::array<std::int64_t, D> c;
    for (int i = 0; i < D; ++i) c[std::size_t(i)] = std::int64_t(nd.coords[std::size_t(i)]);
    const auto box = Quadtree<D>::cell_box(nd.level, c);
    bool meets = true;
    for (int i = 0; i < D; ++i) meets = meets && box.lo[i] <= hi[i] && lo[i] <= box.hi[i];
    if (!meets) continue;
    if (n < readers_.node_count())
      for (OpId o : readers_.list(n)) {
        const RecordedOp& op = recorded_ops_[o];
        // Only a fill that tested the water read it: one skipped on land, or one that inserted (a fill
        // that found its vertex well-spaced, or idle by rank, decided without it). Its box lies within
        // sqrt(depends2) of its vertex (docs/water_only.md): farther from the changed box, nothing it read changed.
        // A fill that looked for the shore at its vertex (shore_read) read it too, whatever it inserted.
        if (op.kind != OpKind::Fill || (!op.on_land && !op.shore_read && op.children_count == 0)) continue;
        const Point<D>& q = positions_[op.vertex];
        double d2 = 0;
        for (int i = 0; i < D; ++i) {
          const double d = std::max({lo[i] - q[i], q[i] - hi[i], 0.0});
          d2 += d * d;
        }
        if (d2 * (1 - kRadiusMargin) > op.depends2) continue;
        mark_redo(o);
      }
    if (!nd.is_leaf())
      for (int k = 0; k < Quadtree<D>::kChildren; ++k) stack.push_back(nd.first_child + NodeId(k));
  }
}

template <int D>
std::vector<typename WellSpacedEngine<D>::VertexId> WellSpacedEngine<D>::apply(std::span<const InputEdit> edits,
                                                                              PropagationStats* stats,
                                                                              std::span<const WaterEdit> water) {
  if (!recording_) throw std::logic_error("the engine was built for its output only: it cannot be updated");
  if (!water.empty() && !water_) throw std::logic_error("ring changes for an engine without a water domain");
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
      mark_readers_at(e.point, vertices_[v].leaf, VertexChange::Inserted, kBeforeEverything, 0);
      if (vertex_ops_[v].dispatch == kNoOp || recorded_ops_[vertex_ops_[v].dispatch].vertex != v) redispatch_input(v);
      added.push_back(v);
    } else {
      const VertexId v = e.vertex;
      const Point<D> p = positions_[v];
      const auto change = tree_.remove_input(v, positions_);
      --input_count_;
      apply_tree_change(change);
      const NodeId leaf = tree_.locate(p);
      mark_readers_at(p, leaf, VertexChange::Removed, kBeforeEverything, 0);
      // The input vertex of the leaf that now holds p has a new neighbourhood too.
      if (tree_.node(leaf).input_vertex != kNoVertex) redispatch_input(tree_.node(leaf).input_vertex);
      kill_vertex(v);  // an input, not a Steiner change: the report does not list it
    }
  }
  if constexpr (D == 2) {
    // The fills that read the water where it changed (the changed edges, and between old and new ones
    // the parity) decide again (docs/water_only.md).
    for (const WaterEdit& edit : water) {
      Point2 lo{2.0, 2.0}, hi{-1.0, -1.0};
      if (water_->apply(edit, lo, hi)) mark_water_readers(lo, hi);
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
  for (OpId o = 0; o < op_count(); ++o) {
    const Op& x = op(o);
    if (!(x.flags & kDead)) sig.emplace_back(positions_[x.vertex], x.rank, x.color);
  }
  std::sort(sig.begin(), sig.end());
  return sig;
}

template <int D>
typename WellSpacedEngine<D>::MemoryBreakdown WellSpacedEngine<D>::memory_breakdown() const {
  MemoryBreakdown m;
  m.vertices = vertices_.capacity() * sizeof(Vertex) + vertex_ops_.capacity() * sizeof(VertexOps);
  m.positions = positions_.capacity() * sizeof(Point<D>);
  m.operations = lean_ops_.capacity() * sizeof(Op) + recorded_ops_.capacity() * sizeof(RecordedOp);
  m.children = children_.memory_bytes();
  m.readers = readers_.memory_bytes();
  m.tree = tree_.memory_bytes();
  m.delaunay = delaunay_ ? delaunay_->memory_bytes() : 0;
  m.other = (free_ops_.capacity() + free_vertices_.capacity()) * sizeof(std::uint32_t);
  for (const auto& bucket : agenda_) m.other += bucket.capacity() * sizeof(OpId);
  m.scratch = scratch_bytes();
  m.other += cell_cache_.capacity() * sizeof(CachedCell) + cache_table_.capacity() * sizeof(CacheSlot);
  for (const CachedCell& c : cell_cache_)
    m.other += c.candidates.capacity() * sizeof(Candidate) + c.covering.capacity() * sizeof(NodeId) +
               (c.unborn.capacity() + c.arrived.capacity()) * sizeof(TimedVertex) + c.cell.memory_bytes();
  return m;
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
    const auto& list = tree_.node(vx.leaf).vertices;
    if (!tree_.node(vx.leaf).is_leaf() ||
        std::none_of(list.begin(), list.end(), [&](const LeafVertex<D>& e) { return e.id == v; }))
      fail("vertex " + std::to_string(v) + " not in its leaf");
    if (!recording_) continue;  // a one-shot build forgot its operations
    const VertexOps& vo = vertex_ops_[v];
    if (vo.dispatch == kNoOp || recorded_ops_[vo.dispatch].vertex != v || recorded_ops_[vo.dispatch].kind != OpKind::Dispatch)
      fail("vertex " + std::to_string(v) + " without its dispatch");
    if (!vx.is_input && (vo.creator == kNoOp || recorded_ops_[vo.creator].kind != OpKind::Fill)) fail("Steiner vertex creator");
  }
  if (inputs != input_count_) fail("input count");
  if (agenda_size_ != 0) fail("agenda not empty after propagation");
  if (!recording_) {
    if (live_op_count() != 0) fail("an operation of a one-shot build left");
    return;
  }
  for (OpId o = 0; o < recorded_ops_.size(); ++o) {
    const RecordedOp& op = recorded_ops_[o];
    if (op.flags & kDead) continue;
    if (op.flags != kExecuted) fail("operation " + std::to_string(o) + " left in state " + std::to_string(op.flags));
    if (op.vertex >= vertices_.size() || !vertices_[op.vertex].alive) fail("operation on a dead vertex");
    if ((op.kind == OpKind::Dispatch) != (op.color == 0)) fail("colour 0 is for dispatches only");
    if (op.kind == OpKind::Fill && op.requesters == 0) fail("a fill nobody asks for");
    for (OpId c : children(o)) {
      if (c >= recorded_ops_.size() || (recorded_ops_[c].flags & kDead))
        fail("operation " + std::to_string(o) + " (" + (op.kind == OpKind::Fill ? "fill" : "dispatch") + " rank " +
             std::to_string(op.rank) + " colour " + std::to_string(op.color) + ", vertex " + std::to_string(op.vertex) +
             (vertices_[op.vertex].is_input ? " input" : " Steiner") + ") has deleted child " + std::to_string(c));
      if (recorded_ops_[c].rank < op.rank) fail("a child runs before its parent");
    }
    // The nodes found again from its cover's code are those it registered on.
    const std::vector<NodeId> read = reads(o);
    if (read.size() != op.reads_count) fail("operation " + std::to_string(o) + " reads other nodes than it registered on");
    for (NodeId n : read) {
      const auto rs = readers_.list(n);
      if (std::find(rs.begin(), rs.end(), o) == rs.end()) fail("read edge without reader entry");
    }
  }
  // Memory is reclaimed: no reader entry of a deleted operation survives, and every block of the pools
  // holds a live operation's run or is free.
  for (NodeId n = 0; n < readers_.node_count(); ++n)
    for (OpId o : readers_.list(n))
      if (recorded_ops_[o].flags & kDead) fail("reader entry of a deleted operation");
  if (readers_.live_block_entries() + readers_.free_entries() != readers_.size()) fail("a reader block lost");
  if (live_children_entries() + children_.free_entries() != children_.size()) fail("a children block lost");
}

template class WellSpacedEngine<2>;
template class WellSpacedEngine<3>;

}  // namespace shoremesh
