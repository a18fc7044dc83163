// The operations of StableWS (paper, Figure 3): dispatch and fill, each in two steps. Computing reads the
// engine (its vertex's cell, the ranks, the Steiner points) and writes only the operation's own hints
// and dependency radii; committing asks for the fills, inserts the Steiner vertices and records what
// updates need. The operations of one time (rank, colour) are independent (Lemma 6.1): each sees only
// the vertices born before that time, so a build computes a large batch on every thread and commits it
// serially in batch order, which numbers vertices and operations exactly as one thread does.
#include "shoremesh/engine/engine.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "engine_internal.hpp"

namespace shoremesh {

using namespace engine;
using namespace engine_detail;

namespace engine {
namespace {
std::atomic<unsigned> g_threads{0};
std::mutex g_control_mutex;
std::unique_ptr<tbb::global_control> g_control;
}  // namespace

void set_thread_count(unsigned threads) {
  const std::lock_guard lock(g_control_mutex);
  g_threads = threads;
  // TBB keeps to the cores unless told otherwise: more threads than cores (oversubscribed, for tests
  // and measurements) need this leave.
  g_control.reset();
  if (threads > 0) g_control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

unsigned thread_count() {
  const unsigned t = g_threads;
  return t != 0 ? t : unsigned(std::max(1, tbb::info::default_concurrency()));
}
}  // namespace engine

template <int D>
struct WellSpacedEngine<D>::Workers {
  tbb::enumerable_thread_specific<Worker> local;
  std::unique_ptr<tbb::task_arena> arena;
  unsigned threads = 0;
};

template <int D>
void WellSpacedEngine<D>::WorkersDeleter::operator()(Workers* w) const {
  delete w;
}

template <int D>
void WellSpacedEngine<D>::compute(OpId o, Worker& w, Outcome& out) {
  out.requests.clear();
  out.steiner.clear();
  w.covering.clear();
  if (op_at(o).kind == OpKind::Dispatch) compute_dispatch(o, w, out);
  else compute_fill(o, w, out);
  std::swap(out.covering, w.covering);
  out.cover = w.cover;
}

template <int D>
void WellSpacedEngine<D>::commit(OpId o, Outcome& out) {
  op_at(o).flags &= std::uint8_t(~(kFresh | kRedo));
  if (recording_) register_reads(o, out.covering, out.cover);
  if (op_at(o).kind == OpKind::Dispatch) commit_dispatch(o, out);
  else commit_fill(o, out);
  op_at(o).flags |= kExecuted;
  if (stats_) ++stats_->executed;
  if (!recording_) release_executed(o);
}

template <int D>
void WellSpacedEngine<D>::execute(OpId o) {
  compute(o, serial_, serial_outcome_);
  commit(o, serial_outcome_);
}

// The vertex no longer names o: a fill leaves its vertex's fill list, a dispatch its dispatch slot.
template <int D>
void WellSpacedEngine<D>::unlink_from_vertex(OpId o) {
  const Op& op = op_at(o);
  Vertex& vx = vertices_[op.vertex];
  if (op.kind == OpKind::Fill) {
    for (OpId* link = &vx.first_fill; *link != kNoOp; link = &op_at(*link).next_fill)
      if (*link == o) {
        *link = op.next_fill;
        break;
      }
  } else if (recording_ && vertex_ops_[op.vertex].dispatch == o) {
    vertex_ops_[op.vertex].dispatch = kNoOp;
  }
}

// A one-shot build forgets an operation once it has run: nothing reads it again. A vertex's fills are
// looked up only at later times (request_fill: a dispatch asks for fills at its rank or later, and a
// fill's colour is never 0), so an executed fill leaves its vertex's list.
template <int D>
void WellSpacedEngine<D>::release_executed(OpId o) {
  unlink_from_vertex(o);
  Op& op = lean_ops_[o];
  op = Op{};
  op.flags = kDead;
  op.next_fill = lean_free_;  // the free slots' list, last freed first
  lean_free_ = o;
  ++lean_free_count_;
}

template <int D>
void WellSpacedEngine<D>::execute_batch_in_parallel() {
  if (outcomes_.size() < std::min(batch_.size(), kParallelChunk)) outcomes_.resize(std::min(batch_.size(), kParallelChunk));
  if (!workers_) workers_.reset(new Workers);
  const unsigned threads = engine::thread_count();
  if (!workers_->arena || workers_->threads != threads) {
    workers_->arena = std::make_unique<tbb::task_arena>(int(threads));
    workers_->threads = threads;
  }
  for (std::size_t first = 0; first < batch_.size(); first += kParallelChunk) {
    const std::size_t m = std::min(kParallelChunk, batch_.size() - first);
    workers_->arena->execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 8), [&](const tbb::blocked_range<std::size_t>& range) {
        Worker& w = workers_->local.local();
        for (std::size_t k = range.begin(); k != range.end(); ++k) compute(batch_[first + k], w, outcomes_[k]);
      });
    });
    for (std::size_t k = 0; k < m; ++k) commit(batch_[first + k], outcomes_[k]);
  }
}

namespace {
void add(Counters& to, const Counters& c) {
  to.dispatches += c.dispatches;
  to.fills += c.fills;
  to.fills_idle_by_rank += c.fills_idle_by_rank;
  to.fills_on_land += c.fills_on_land;
  to.clipped_voronoi_calls += c.clipped_voronoi_calls;
  to.cells_reused += c.cells_reused;
  to.neighbourhoods_reused += c.neighbourhoods_reused;
  to.cells_updated += c.cells_updated;
  to.steiner_points += c.steiner_points;
  to.predicate_calls += c.predicate_calls;
  to.exact_fallbacks += c.exact_fallbacks;
  to.neighbour_searches += c.neighbour_searches;
  to.leaves_visited += c.leaves_visited;
  to.candidates += c.candidates;
  to.clips += c.clips;
  to.delaunay_cells += c.delaunay_cells;
  to.delaunay_fallbacks += c.delaunay_fallbacks;
  to.operations_undone += c.operations_undone;
}
}  // namespace

// A worker's counts join the engine's (sums: the same whatever thread counted what).
template <int D>
void WellSpacedEngine<D>::add_counters(Worker& w) {
  add(counters_, w.counters);
  counters_.predicate_calls += w.cell.counters().calls;
  counters_.exact_fallbacks += w.cell.counters().exact;
  w.counters = Counters{};
  w.cell.counters() = PredicateCounters{};
}

namespace {
template <class T>
std::size_t bytes_of(const std::vector<T>& items) {
  return items.capacity() * sizeof(T);
}
}  // namespace

template <int D>
std::size_t WellSpacedEngine<D>::scratch_bytes() const {
  auto worker = [](const Worker& w) {
    return sizeof(Worker) + w.cell.memory_bytes() + w.part.memory_bytes() + bytes_of(w.hood.candidates) +
           bytes_of(w.unborn) + bytes_of(w.neighbours) + bytes_of(w.covering) + bytes_of(w.shore_edges);
  };
  auto outcome = [](const Outcome& out) {
    return sizeof(Outcome) + bytes_of(out.requests) + bytes_of(out.steiner) + bytes_of(out.covering);
  };
  std::size_t bytes = bytes_of(batch_) + bytes_of(batch_keys_) + bytes_of(batch_keys_scratch_) + bytes_of(new_children_) +
                      bytes_of(stash_) + worker(serial_) + outcome(serial_outcome_);
  for (const Outcome& out : outcomes_) bytes += outcome(out) - sizeof(Outcome);
  bytes += bytes_of(outcomes_);
  if (workers_)
    for (const Worker& w : workers_->local) bytes += worker(w);
  return bytes;
}

template <int D>
void WellSpacedEngine<D>::collect_counters() {
  add_counters(serial_);
  if (workers_)
    for (Worker& w : workers_->local) add_counters(w);
}

template <int D>
void WellSpacedEngine<D>::request_fill(VertexId w, int rank, bool crowded) {
  for (OpId f = vertices_[w].first_fill; f != kNoOp; f = op_at(f).next_fill)
    if (op_at(f).rank == rank && !(op_at(f).flags & kDead)) {
      if (op_at(f).requesters == std::numeric_limits<std::uint16_t>::max())
        throw std::length_error("a fill asked for by over 65535 dispatches");
      ++op_at(f).requesters;
      op_at(f).flags &= std::uint8_t(~kObsolete);  // asked for again before its time: it lives on
      new_children_.push_back(f);
      return;
    }
  const OpId f = new_op(OpKind::Fill, w, rank, ranks_.color(positions_[w], rank));
  op_at(f).crowded = crowded;  // a neighbour's: the places are near
  op_at(f).requesters = 1;
  op_at(f).next_fill = vertices_[w].first_fill;
  vertices_[w].first_fill = f;
  new_children_.push_back(f);
  mark_fresh(f);
}

template <int D>
void WellSpacedEngine<D>::compute_dispatch(OpId o, Worker& w, Outcome& out) {
  RoundingGuard guard;
  ++w.counters.dispatches;
  const VertexId v = op_at(o).vertex;
  const int op_rank = op_at(o).rank;
  compute_cell(o, v, false, w);
  if (w.hood.nearest == kNoVertex) return;  // a lone vertex is well-spaced
  PredicateCounters& pc = w.cell.counters();
  const Point<D>& p = positions_[v];
  // v's fill at its current rank, and fills that update the ranks of its beta-clipped Voronoi
  // neighbours (bisector faces of the cell no farther than 2 beta NN(v): a superset, harmless, since a
  // fill at rank floor(log |vw|) finds w already well-spaced unless it truly is due), less those that
  // cannot be due (already_below_rank). v's own fill is not asked for when v is well-spaced already:
  // should NN(v) still be |vu| at the beginning of rank r, no vertex came nearer since, the cell only
  // shrank, and v is well-spaced through rank r (Fact 2), so the fill would insert nothing; should a
  // vertex z come nearer first, v's fill at the new rank is the business of z's dispatch (Lemma 4.1).
  const int r = ranks_.rank_of(p, positions_[w.hood.nearest], pc);
  const bool well_spaced = w.cell.within_scaled_distance(params_.fill_rho_squared, positions_[w.hood.nearest]);
  if (r >= op_rank && (params_.literal_stable_ws || !well_spaced)) out.requests.push_back({v, r});
  const double limit2 = 4 * params_.beta_squared * squared_distance(v, w.hood.nearest) * (1 + kReachMargin);
  w.cell.bisector_neighbours(w.neighbours);
  for (VertexId x : w.neighbours) {
    if (squared_distance(v, x) > limit2) continue;
    const int rx = ranks_.rank_of(p, positions_[x], pc);
    if (rx < op_rank || (!params_.literal_stable_ws && already_below_rank(w, x, rx, pc))) continue;
    out.requests.push_back({x, rx});
  }
  if (recording_) record_facets(o, w);
}

template <int D>
void WellSpacedEngine<D>::commit_dispatch(OpId o, Outcome& out) {
  RoundingGuard guard;  // the colours of new fills are computed in it, as everywhere
  new_children_.clear();
  for (const auto& [x, rank] : out.requests) request_fill(x, rank, op_at(o).crowded);
  if (recording_) store_children(o);
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
bool WellSpacedEngine<D>::already_below_rank(const Worker& wk, VertexId w, int rw, PredicateCounters& pc) const {
  for (VertexId x : wk.neighbours)
    if (x != w && ranks_.rank_below(positions_[w], positions_[x], rw, pc)) return true;
  return false;
}

// The Steiner points of a fill, each clipped from v's cell before the next is picked (they are
// v's neighbours from then on). Their vertex ids exist only once committed: the cell's bisectors of
// them carry no id, which only bisector_neighbours would read, and only when there are none.
template <int D>
void WellSpacedEngine<D>::compute_fill(OpId o, Worker& w, Outcome& out) {
  RoundingGuard guard;
  ++w.counters.fills;
  const VertexId v = op_at(o).vertex;
  const int op_rank = op_at(o).rank;
  const Point<D> p = positions_[v];
  const bool has_cell = compute_cell(o, v, true, w);
  PredicateCounters& pc = w.cell.counters();
  // A fill that would insert, on a vertex whose cell cannot meet the water, inserts nothing (on land).
  op_at(o).on_land = false;
  op_at(o).shore_read = false;
  const bool due = water_ && has_cell && w.hood.nearest != kNoVertex &&
                   !w.cell.within_scaled_distance(params_.fill_rho_squared, positions_[w.hood.nearest]);
  if (due && fill_on_land(v, w)) {
    op_at(o).on_land = true;
    ++w.counters.fills_on_land;
  }
  // A shore vertex's cell stops at the shore: well-spacedness and the picking region on its water wedge.
  ShoreWedge wedge;
  bool wedged = false;
  if (due && !op_at(o).on_land && params_.shore_cells) {
    op_at(o).shore_read = true;
    wedged = shore_wedge(v, w, wedge);
  }
  for (int inserted = 0; has_cell && !op_at(o).on_land && w.hood.nearest != kNoVertex &&
                         (wedged ? !well_spaced_in_wedge(v, w, wedge)
                                 : !w.cell.within_scaled_distance(params_.fill_rho_squared, positions_[w.hood.nearest]));
       ++inserted) {
    if (inserted > 1000) throw std::logic_error("fill inserted over 1000 Steiner points around one vertex");
    // In the wedge's part that is not well-spaced, aimed at one of its vertices off the shore's lines (a
    // point on them would lie on the shore); when none is, as without the wedge (any aim keeps Fact 1).
    Point<D> aim;
    const bool in_wedge = wedged && aim_in_wedge(w, wedge, aim);
    const Point<D> q = pick_steiner(v, w, in_wedge ? &aim : nullptr);
    // Fact 1 puts q's rank above op's; the max only guards the table's rounding for a rho other than
    // sqrt(2) (for sqrt(2) the table is exact and it never applies).
    out.steiner.push_back({q, std::max(ranks_.rank_of(q, p, pc), op_rank + 1), tree_.locate(q, vertices_[v].leaf)});
    double d2 = 0;
    for (int i = 0; i < D; ++i) {
      const double d = p[i] - q[i];
      d2 += d * d;
    }
    w.cell.clip(kNoVertex, q, d2);
    w.hood.candidates.push_back({d2, kNoVertex, q});
  }
  // v was already well-spaced: a vertex inserted farther than NN(v) leaves NN(v) and the clipping cube
  // as they are and can only shrink the cell, so v stays well-spaced and this fill does nothing again.
  // (Not a fill skipped on land: it keeps the whole cell's dependencies, as one that inserted.)
  if (recording_ && has_cell && out.steiner.empty() && !op_at(o).on_land && w.hood.nearest != kNoVertex) {
    recorded_ops_[o].set_inserted_depends2(at_least(squared_distance(v, w.hood.nearest) * (1 + kRadiusMargin)));
    w.cell.bisector_neighbours(w.neighbours);
    record_facets(o, w);
  }
}

template <int D>
void WellSpacedEngine<D>::commit_fill(OpId o, Outcome& out) {
  const VertexId v = op_at(o).vertex;
  const int op_rank = op_at(o).rank;
  const std::uint32_t op_color = op_at(o).color;
  // The Steiner vertices of this fill's previous run, when it runs again (see undo).
  stash_.clear();
  if (op_at(o).flags & kStashed) {
    for (OpId d : children(o)) stash_.push_back(d);
    release_children(recorded_ops_[o]);
    op_at(o).flags &= std::uint8_t(~kStashed);
  }
  new_children_.clear();
  for (const auto& [q, rank, leaf] : out.steiner) {
    auto again = std::find_if(stash_.begin(), stash_.end(), [&](OpId d) { return positions_[op_at(d).vertex] == q; });
    if (again != stash_.end()) {
      // The same Steiner point as before: keep the vertex and its dispatch, nothing changes around it.
      new_children_.push_back(*again);
      *again = stash_.back();
      stash_.pop_back();
      continue;
    }
    const VertexId id = new_vertex(q);
    if (recording_) vertex_ops_[id].creator = o;
    vertices_[id].leaf = leaf;
    tree_.insert_vertex_at(leaf, id, q, time_key(op_rank, op_color));
    ++counters_.steiner_points;
    if (dynamic_) mark_readers_at(q, vertices_[id].leaf, VertexChange::Inserted, op_rank, op_color);
    if (caching_) vertex_arrived(id, q, time_key(op_rank, op_color));
    if constexpr (D == 2)
      if (delaunay_) delaunay_->defer(id, q, v, time_key(op_rank, op_color));
    if (stats_) stats_->steiner_added.push_back(q);
    const OpId d = new_op(OpKind::Dispatch, id, rank, 0);
    op_at(d).crowded = op_at(o).crowded;
    if (recording_) vertex_ops_[id].dispatch = d;
    new_children_.push_back(d);
    mark_fresh(d);
  }
  if (recording_) store_children(o);
  // Steiner vertices of the previous run not inserted again leave the output.
  for (OpId d : stash_) {
    const VertexId w = op_at(d).vertex;
    mark_obsolete(d);
    tree_.erase_vertex(w, vertices_[w].leaf);
    mark_readers_at(positions_[w], vertices_[w].leaf, VertexChange::Removed, op_rank, op_color);
    kill_vertex(w);
    if (stats_) stats_->steiner_removed.push_back(positions_[w]);
  }
  stash_.clear();
}

// The cell's box: its vertices' interval enclosures (exact positions inside) about v, widened by a margin
// far above the rounding of p + y (and of the shore's splits, which lie on the rings' edges up to one
// rounding: the mesh's water is the refined rings'). It is tested exactly against the rings' edges, and
// when none meets it, v's side decides for the whole box. It lies within max_vertex_distance2 of v, so in
// the box the operation's search covered and registered on (docs/water_only.md).
template <int D>
bool WellSpacedEngine<D>::fill_on_land(VertexId v, Worker& w) const {
  if constexpr (D != 2) {
    (void)v, (void)w;
    return false;
  } else {
    constexpr double kAbsolute = 0x1p-48;  // unit box: 16 ulps of 1, below any vertex spacing (2^-40)
    Point2 lo{0, 0}, hi{0, 0};
    w.cell.for_each_vertex_box([&](const std::array<Interval, 2>& y) {
      for (int i = 0; i < 2; ++i) {
        lo[i] = std::min(lo[i], y[i].inf());
        hi[i] = std::max(hi[i], y[i].sup());
      }
    });
    const Point2 p = positions_[v];
    const double margin = std::max(hi[0] - lo[0], hi[1] - lo[1]) * kLandMargin + kAbsolute;
    for (int i = 0; i < 2; ++i) {
      lo[i] = p[i] + lo[i] - margin;
      hi[i] = p[i] + hi[i] + margin;
    }
    return !water_->may_meet_water(p, lo, hi, w.cell.counters());
  }
}

// The cell vertex a fill's Steiner point aims at: among the vertices farther from v than steiner_aim rho NN,
// the nearest; the farthest when none is (always, for an infinite steiner_aim). Aiming at the nearest
// violating vertex inserts the circumcentre of the mildest bad Delaunay triangle at v first rather than a
// point beta NN out toward the worst one: on Lake Superior's shore 2.3% fewer water vertices (bench/RESULTS.md).
// Positions are the midpoints of the vertices' enclosures, a function of the cell alone (canonical, like
// the cell: Lemma 7.2); ties go by coordinates.
namespace {
template <int D>
Point<D> aim_vertex(const ConvexCell<D>& cell, double beyond2) {
  Point<D> best{};
  double best_d2 = -1;
  cell.for_each_vertex_box([&](const std::array<Interval, D>& box) {
    Point<D> y;
    double d2 = 0;
    for (int i = 0; i < D; ++i) {
      y[i] = 0.5 * (box[i].inf() + box[i].sup());
      d2 += y[i] * y[i];
    }
    if (d2 > beyond2 && (best_d2 < 0 || d2 < best_d2 || (d2 == best_d2 && y < best))) {
      best_d2 = d2;
      best = y;
    }
  });
  return best_d2 < 0 ? cell.farthest_vertex_offset() : best;
}
}  // namespace

// The Steiner point: toward a cell vertex c (aim_vertex), at distance min(|vc|, beta NN) shrunk by 2^-10 (so
// it lies strictly inside the cell, away from the bisectors through c, and rounding cannot push it out), but
// never nearer than rho NN. When |vc| <= beta NN that is c itself up to the shrink: the circumcentre of a
// Delaunay triangle at v, the point Delaunay refinement inserts. Every condition of the picking region is
// then checked exactly, so any choice of c keeps Fact 1 and with it every guarantee.
template <int D>
Point<D> WellSpacedEngine<D>::pick_steiner(VertexId v, Worker& wk, const Point<D>* aim) const {
  constexpr double kInside = 0x1p-10;  // the step's shrink, and the least margin above rho NN
  PredicateCounters& pc = wk.cell.counters();
  const Point<D> p = positions_[v];
  const Point<D> u = positions_[wk.hood.nearest];
  const double nn2 = squared_distance(v, wk.hood.nearest);
  const Point<D> y = aim ? *aim : aim_vertex(wk.cell, params_.steiner_aim_squared * nn2);
  double len2 = 0;
  for (int i = 0; i < D; ++i) len2 += y[i] * y[i];
  const double len = std::sqrt(len2);
  const double nn = std::sqrt(nn2);
  const double reach = std::min(len, params_.beta * nn);
  const double fallback = 0.5 * (params_.rho * nn + reach);
  double target = reach * (1 - kInside);
  if (target < params_.rho * nn * (1 + kInside)) target = fallback;
  for (double t : {target, fallback}) {
    Point<D> w;
    for (int i = 0; i < D; ++i) w[i] = std::clamp(p[i] + y[i] * (t / len), 0.0, 1.0);
    if (compare_squared_distance_scaled<D>(pc, w, p, params_.rho_squared, u, p) < 0) continue;
    if (compare_squared_distance_scaled<D>(pc, w, p, params_.beta_squared, u, p) >= 0) continue;
    bool inside = true;
    for (const Candidate& c : wk.hood.candidates)
      if (compare_squared_distances<D>(pc, w, p, w, c.position) >= 0) {
        inside = false;
        break;
      }
    if (inside) return w;
  }
  throw std::logic_error("no admissible Steiner point in the picking region of a vertex");
}

#define SHOREMESH_ENGINE_OPERATIONS(D)                                                                  \
  template void WellSpacedEngine<D>::WorkersDeleter::operator()(Workers*) const;                       \
  template void WellSpacedEngine<D>::compute(OpId, Worker&, Outcome&);                                 \
  template void WellSpacedEngine<D>::commit(OpId, Outcome&);                                           \
  template void WellSpacedEngine<D>::execute(OpId);                                                    \
  template void WellSpacedEngine<D>::release_executed(OpId);                                           \
  template void WellSpacedEngine<D>::unlink_from_vertex(OpId);                                         \
  template void WellSpacedEngine<D>::execute_batch_in_parallel();                                      \
  template void WellSpacedEngine<D>::add_counters(Worker&);                                            \
  template void WellSpacedEngine<D>::collect_counters();                                               \
  template std::size_t WellSpacedEngine<D>::scratch_bytes() const;                                     \
  template void WellSpacedEngine<D>::request_fill(VertexId, int, bool);                                \
  template void WellSpacedEngine<D>::compute_dispatch(OpId, Worker&, Outcome&);                        \
  template void WellSpacedEngine<D>::commit_dispatch(OpId, Outcome&);                                  \
  template bool WellSpacedEngine<D>::already_below_rank(const Worker&, VertexId, int, PredicateCounters&) const; \
  template void WellSpacedEngine<D>::compute_fill(OpId, Worker&, Outcome&);                            \
  template void WellSpacedEngine<D>::commit_fill(OpId, Outcome&);                                      \
  template Point<D> WellSpacedEngine<D>::pick_steiner(VertexId, Worker&, const Point<D>*) const;                        \
  template bool WellSpacedEngine<D>::fill_on_land(VertexId, Worker&) const;
SHOREMESH_ENGINE_OPERATIONS(2)
SHOREMESH_ENGINE_OPERATIONS(3)
#undef SHOREMESH_ENGINE_OPERATIONS

}  // namespace shoremesh
