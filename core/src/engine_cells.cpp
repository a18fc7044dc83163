// The neighbourhood of an operation's vertex: its nearest neighbour and the vertices that can cut its
// cell, found in the quadtree (or the propagation's cell cache, or a 2D one-shot build's Delaunay
// triangulation: docs/delaunay_neighbours.md), and the cell clipped from them. Reads
// the engine only (and writes the operation's own dependency radii and hints): safe on several threads
// for the operations of one time when the cell cache is off (engine.hpp: compute).
#include "shoremesh/engine/engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine_internal.hpp"

namespace shoremesh {

using namespace engine;
using namespace engine_detail;

// One cell's computation in three steps: gathering the candidates (the vertices of M_t that may cut
// v's cell, and v's nearest neighbour among them), clipping the cell by them, and recording what the
// operation's result depends on. Clipping may ask the gathering for more (a larger box).
template <int D>
struct WellSpacedEngine<D>::CellSearch {
  using Box = typename Quadtree<D>::Box;

  WellSpacedEngine& e;
  const OpId o;
  const VertexId v;
  Worker& w;
  const CachedCell* const earlier;  // v's entry in the propagation's cell cache, if any
  const Point<D> p;
  const std::uint64_t now;          // only vertices born before this operation's time exist for it (M_t)
  PredicateCounters& pc;
  std::vector<Candidate>& pool;
  double best_d2 = 0;               // |v - nearest|^2, rounded
  // Once the cell exists among many candidates (or the operation is crowded, see Op::crowded),
  // searches skip what cannot cut it (ConvexCell::surely_uncut_by_box): the cell only shrinks, so such
  // a vertex never cuts it, now or at a later time that reuses the cell (cell_cache.cpp), and it is not
  // nearer than NN (a vertex nearer cuts the ball of radius NN / 2 about v, which the cell holds).
  // Along a dense shore seen from far out on the water, nearly all of a large cell's box is such
  // vertices. Among few (uniform inputs) the tests would cost more than they save (7 % more CPU at 2D
  // 10^5 when always on); with water rings there is a dense shore somewhere, and skipping from the first
  // cell on saves more than it costs (6 % less CPU at Superior's 196,843 shore points).
  bool has_cell = false, pruning = false;
  // The leaves searched so far: those that meet this box (the boxes only grow).
  Box seen = Box::empty();
  double half = 0;                  // the half-side of the box searched for the nearest neighbour
  double searched = 0;              // the half-side of the box searched so far
  std::size_t known = 0;            // pool[0, known): the candidates earlier->cell was computed from
  std::size_t next = 0;             // pool[0, next): the candidates clipped (or found unable to cut)
  double cap2 = 0;                  // nothing beyond 2 beta NN can cut the beta-ball

  CellSearch(WellSpacedEngine& engine, OpId op, VertexId vertex, Worker& worker, const CachedCell* entry, std::uint64_t t)
      : e(engine), o(op), v(vertex), w(worker), earlier(entry), p(engine.positions_[vertex]), now(t),
        pc(worker.cell.counters()), pool(worker.hood.candidates) {
    w.hood.nearest = kNoVertex;
    pool.clear();
  }

  // Gathering. Takes vertex u at q (squared distance d2 from v) as a candidate, tracking the nearest.
  void offer(VertexId u, const Point<D>& q, double d2) {
    pool.push_back({d2, u, q});
    ++w.counters.candidates;
    if (w.hood.nearest != kNoVertex && d2 > best_d2 * (1 + kNearestTie)) return;
    if (w.hood.nearest != kNoVertex && d2 >= best_d2 * (1 - kNearestTie)) {
      // Nearly tied: decide exactly, then by coordinates, so the nearest neighbour is canonical.
      const int c = compare_squared_distances<D>(pc, p, q, p, e.positions_[w.hood.nearest]);
      if (c > 0 || (c == 0 && !(q < e.positions_[w.hood.nearest]))) return;
    }
    w.hood.nearest = u;
    best_d2 = d2;
  }
  bool cannot_cut(const Point<D>& lo, const Point<D>& hi) const {
    Point<D> a, b;
    for (int i = 0; i < D; ++i) {
      a[i] = lo[i] - p[i];
      b[i] = hi[i] - p[i];
    }
    return w.cell.surely_uncut_by_box(a, b);
  }
  // A vertex of the tree other than v: a candidate if born before now, else remembered for the cache.
  void consider(VertexId u, const Point<D>& q, std::uint64_t birth) {
    if (pruning && cannot_cut(q, q)) return;
    if (birth >= now) {
      if (e.caching_) w.unborn.push_back({q, birth, u});
      return;
    }
    double d2 = 0;
    for (int i = 0; i < D; ++i) d2 += (q[i] - p[i]) * (q[i] - p[i]);
    // A vertex exactly at v's place can only be a Steiner point about to be removed by the
    // propagation (an input was just added there): it is not a neighbour.
    if (d2 == 0 && q == p) return;
    offer(u, q, d2);
  }
  Box box_of(double h) const {
    Box box;
    for (int i = 0; i < D; ++i) {
      box.lo[i] = p[i] - h;
      box.hi[i] = p[i] + h;
    }
    return box;
  }
  // Adds the vertices of the leaves of box [p - h, p + h] not searched yet.
  void search(double h) {
    const Box box = box_of(h);
    pruning = has_cell && (e.op_at(o).crowded || pool.size() > kCrowdedPool || e.water_ != nullptr);
    ++w.counters.neighbour_searches;
    const auto visit = [&](NodeId, std::span<const LeafVertex<D>> leaf) {
      for (const LeafVertex<D>& x : leaf)
        if (x.id != v) consider(x.id, x.position, x.tag);
    };
    // v's leaf lies at the box's centre: the node over its cell is found from it, not from the cell
    // map (about 60 % of the look-ups at Superior, each mostly a cache miss).
    const NodeId near = e.vertices_[v].leaf;
    if (pruning) {
      w.counters.leaves_visited += e.tree_.for_each_occupied_leaf(box, seen, visit, [&](int level, const auto& cell) {
        const Box node = Quadtree<D>::cell_box(level, cell);
        return !cannot_cut(node.lo, node.hi);
      }, near);
    } else {
      w.counters.leaves_visited += e.tree_.for_each_occupied_leaf(box, seen, visit, [](int, const auto&) { return true; }, near);
    }
    seen = box;
  }
  void gather_from_tree();
  bool gather_from_delaunay(engine::DelaunayNeighbours::Walk& walk);
  bool clip_from_delaunay(engine::DelaunayNeighbours::Walk& walk);
  // The cube of half-side beta NN(v) about v, cut to [0,1]^D, as the cell to clip (and cap2).
  void start_clipping();
  // Clipping: the cell clipped to the box and to the cube of half-side beta NN(v), from the candidates
  // (searching a larger box while a vertex outside may still cut it).
  void clip();
  // Among many candidates, keeps only those that may cut the cell.
  void keep_cutting_candidates();
  // Dependency recording: what op o read, and the radii within which a change may change its result.
  void record_dependencies();
  void record_lone_vertex();
};

// Grow the box until it holds a vertex no farther than its half-side: no vertex outside is nearer.
template <int D>
void WellSpacedEngine<D>::CellSearch::gather_from_tree() {
  // The first box spans v's leaf and a leaf-side margin (NN(v) is about 1.15 leaf sides in uniform 2D
  // inputs): a box of one leaf side mostly had to grow again, which cost 5 % more instructions per
  // update in 2D and 3 % in 3D. The result does not depend on the first box, only the work does. A
  // crowded operation's starts at half a side: the tree is refined for the input points only, so a
  // large leaf out on the water can hold many Steiner vertices near a shore, and a box of two of its
  // sides thousands.
  const Op& op = e.op_at(o);
  half = (op.crowded ? 0.5 : 2.0) * e.tree_.side(e.vertices_[v].leaf);
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
  const double previous2 = e.recording_ ? e.recorded_ops_[o].depends2 : 0.0;  // a one-shot build runs each once
  if (!op.crowded && previous2 > half * half && previous2 < 16 * half * half) half = std::sqrt(previous2) * (1 + kRadiusMargin);
  // With a stale entry (its cell computed earlier in this propagation): it lists what the leaves of
  // its box held then and what arrived there since, which is what they hold now, as a search would
  // find it (cell_cache.cpp). Only growing that box searches.
  if (earlier) {
    for (const Candidate& c : earlier->candidates) offer(c.id, c.position, c.d2);
    known = pool.size();
    for (const auto* list : {&earlier->unborn, &earlier->arrived})
      for (const TimedVertex& u : *list)
        if (e.vertices_[u.id].alive) consider(u.id, u.position, u.birth);
    half = earlier->searched;
    seen = box_of(half);
    ++w.counters.neighbourhoods_reused;
  } else {
    search(half);
  }
  while (!(w.hood.nearest != kNoVertex && best_d2 <= half * half * (1 - kReachMargin)) && half < 2.0) {
    half *= 2;  // until the box covers [0,1]^D
    search(half);
  }
  searched = half;
}

// 2D one-shot builds: the candidates from a walk through the triangulation of M_t outward from v in
// the order cells clip in, (d2, position), instead of the tree search. The cell is clipped by exactly
// the vertices, in exactly the order, that the tree search's clip() takes: every vertex within the reach
// as the cell shrinks (what lies beyond the reach cannot cut, and clip() stops at the first such vertex
// too). The walk has met them all: a vertex of a Delaunay triangulation has a neighbour strictly nearer
// v, so the vertices within any distance of v are connected to v within it (the walk goes a margin past
// the reach, for the rounding of d2). Same planes in the same order: the same cell bit for bit, with
// the same nearest neighbour (v's neighbours hold every vertex nearest it, chosen by the same rule). The
// candidates kept for pick_steiner include v's neighbours, which bound its Voronoi cell: a point is
// nearer v than all of them iff it is in the cell, as it is for the tree search's.
template <int D>
bool WellSpacedEngine<D>::CellSearch::gather_from_delaunay(engine::DelaunayNeighbours::Walk& walk) {
  if constexpr (D != 2) {
    (void)walk;
    return false;
  } else {
    if (!e.delaunay_->start_walk(v, p, walk)) return false;
    for (const engine::DelaunayNeighbours::Near& x : walk.pending()) offer(x.id, x.position, x.d2);
    return true;
  }
}

template <int D>
bool WellSpacedEngine<D>::CellSearch::clip_from_delaunay(engine::DelaunayNeighbours::Walk& walk) {
  if constexpr (D != 2) {
    (void)walk;
    return false;
  } else {
    // A vertex within the reach is met through ones nearer v, exactly; their rounded d2 may exceed its
    // own by a few ulps.
    constexpr double kWalkMargin = 1e-12;
    start_clipping();
    pool.clear();
    double reach2 = std::min(4 * w.cell.max_vertex_distance2() * (1 + kReachMargin), cap2);
    engine::DelaunayNeighbours::Near x;
    while (walk.next_d2() <= reach2 * (1 + kWalkMargin)) {
      // Among many (a large cell at a dense shore), the tree search skips what cannot cut the cell.
      if (walk.returned() >= kCrowdedPool) return false;
      e.delaunay_->next(walk, x);
      pool.push_back({x.d2, x.id, x.position});
      ++w.counters.candidates;
      if (x.d2 <= reach2) {
        ++w.counters.clips;
        if (w.cell.clip(x.id, x.position, x.d2)) reach2 = std::min(4 * w.cell.max_vertex_distance2() * (1 + kReachMargin), cap2);
      }
    }
    // Distances tied up to rounding met out of order: clip() would have cut in another order.
    if (walk.out_of_order()) return false;
    for (const engine::DelaunayNeighbours::Near& y : walk.pending()) pool.push_back({y.d2, y.id, y.position});
    half = searched = std::numeric_limits<double>::infinity();  // nothing else is needed
    return true;
  }
}

template <int D>
void WellSpacedEngine<D>::CellSearch::start_clipping() {
  // The box around v of half-side beta NN(v) (a little more, so it surely holds the beta-ball), cut to
  // [0,1]^D: inside the ball the cut cell equals the true Voronoi cell, which is all any decision uses.
  const double nn = std::sqrt(best_d2);
  const double s = e.params_.beta * nn * (1 + 0x1p-20);
  Point<D> cube_lo, cube_hi;
  for (int i = 0; i < D; ++i) {
    cube_lo[i] = std::max(0.0, p[i] - s);
    cube_hi[i] = std::min(1.0, p[i] + s);
  }
  w.cell.reset(p, cube_lo, cube_hi);
  next = 0;
  has_cell = true;
  cap2 = 4 * e.params_.beta_squared * best_d2 * (1 + kReachMargin);
}

template <int D>
void WellSpacedEngine<D>::CellSearch::clip() {
  // Clip by the vertices in order of distance (ties by coordinates: a canonical order, so the rounded
  // cell does not depend on insertion history). A vertex farther than twice the cell's reach cannot cut
  // it, nor can one beyond 2 beta NN cut the beta-ball: the search grows only while a cut is possible.
  auto by_distance = [&](const Candidate& a, const Candidate& b) {
    if (a.d2 != b.d2) return a.d2 < b.d2;
    return a.position < b.position;
  };
  next = 0;
  // With the same nearest neighbour (so the same clipping box) the earlier cell only has to be cut by
  // the vertices born since: none of the earlier candidates left, and the cut cell is the same polygon.
  // Without a vertex on D + 1 planes at once (checked, as for caching) each vertex of it is solved from
  // the same D planes in the same order as from scratch (ConvexCell::begin_out_of_order_cuts), so it
  // is the same cell bit for bit (cell_cache.cpp).
  bool incremental = earlier != nullptr && w.hood.nearest == earlier->nearest;
  auto start_afresh = [&] {
    incremental = false;
    start_clipping();
  };
  if (incremental) {
    cap2 = 4 * e.params_.beta_squared * best_d2 * (1 + kReachMargin);
    w.cell.assign_geometry(earlier->cell);
    w.cell.begin_out_of_order_cuts();
    next = known;
    has_cell = true;
    ++w.counters.cells_updated;
  } else {
    start_afresh();
  }
  for (;;) {
    double reach2 = std::min(4 * w.cell.max_vertex_distance2() * (1 + kReachMargin), cap2);
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
          ++w.counters.clips;
          if (w.cell.clip(pool[next].id, pool[next].position, pool[next].d2))
            reach2 = std::min(4 * w.cell.max_vertex_distance2() * (1 + kReachMargin), cap2);
        }
        ++next;
      }
      if (limit2 >= std::min(reach2, searched * searched)) break;
    }
    // The box searched ends up holding the whole dependency ball (depends2 below, with its margin),
    // which the cell cache needs: it then knows every vertex, born or not, that could change the cell.
    const double need2 = reach2 * (1 + 2 * kRadiusMargin);
    if (incremental && (need2 > searched * searched || w.cell.had_vertex_on_plane())) {
      // A cell that only shrank never needs a larger box (unless by rounding); a vertex on D + 1
      // planes may have met them in another order than from scratch. Either way: compute it afresh.
      --w.counters.cells_updated;
      start_afresh();
      continue;
    }
    if (need2 <= searched * searched) {
      if (incremental) w.cell.end_out_of_order_cuts();
      break;
    }
    // Grow at most twofold: the vertices found next usually shrink the cell, and with it the reach, so
    // a box of the whole reach at once reads leaves it need not. A search costs about as much as ten
    // leaves read (the descent from the box's top nodes, again for each larger box): at 196,843
    // Superior shore points a shore vertex's reach ends at 2 beta NN, 2.8 times its first box, which
    // steps of 1.5 took 2.9 searches to reach; steps of 2 take 22 % fewer searches over all cells for
    // 4 % more leaves. Which vertices are offered is all the schedule changes: each within the reach
    // is clipped, in (d2, position) order, whatever box first found it. With the cell cache (an update's
    // propagation) the box searched is also what the cell's entry lists and its reads cover: there
    // steps of 2 read 3 % more leaves per updated cell, and the median update (bench_dynamic 2D 10^5)
    // took about 4 % longer, so it grows by 1.5 as before.
    searched = std::min(std::sqrt(need2) * (1 + kReachMargin), (e.caching_ ? 1.5 : 2.0) * searched);
    search(searched);
  }
}

// Many candidates (a large cell among dense ones): the operation is crowded from now on, and keeps
// only the candidates that may cut its cell. The cell cache lists them, and a fill checks its Steiner
// point against each (pick_steiner: a point inside the cell is nearer v than any of the others).
template <int D>
void WellSpacedEngine<D>::CellSearch::keep_cutting_candidates() {
  if (pool.size() <= kCrowdedPool) return;
  e.op_at(o).crowded = true;
  const double reach_final2 = 4 * w.cell.max_vertex_distance2() * (1 + kRadiusMargin);
  pool.erase(std::remove_if(pool.begin(), pool.end(), [&](const Candidate& c) {
               return c.d2 > reach_final2 || cannot_cut(c.position, c.position);
             }), pool.end());
}

template <int D>
void WellSpacedEngine<D>::CellSearch::record_dependencies() {
  e.record_reads(w, p, searched);
  // Only a vertex that could cut the cell or be nearer than NN can change what this operation decides:
  // one within 2 x the cell's reach (capped at 2 beta NN), or within NN. A little margin on the rounding.
  if (!e.recording_) return;  // a one-shot build: nobody reads the radii
  RecordedOp& op = e.recorded_ops_[o];
  const double reach2 = std::min(4 * w.cell.max_vertex_distance2(), cap2);
  op.set_depends2(at_least(std::max(reach2, best_d2) * (1 + kRadiusMargin)));
  op.reach = engine::CellReach<D>::of([&](auto&& f) { w.cell.for_each_vertex_box(f); });
  if (e.caching_) e.store_cell(o, v, p, searched);
}

// No other vertex in the box [0,1]^D: v is alone, and anything in the box gives it a neighbour.
template <int D>
void WellSpacedEngine<D>::CellSearch::record_lone_vertex() {
  if (e.caching_) e.forget_cell(v);
  e.record_reads(w, p, half);
  if (e.recording_) e.recorded_ops_[o].set_depends2(at_least(4.0 * D));
}

namespace {
// The walk of the operation a thread computes (scratch, reused).
engine::DelaunayNeighbours::Walk& delaunay_walk() {
  static thread_local engine::DelaunayNeighbours::Walk walk;
  return walk;
}
}  // namespace

template <int D>
bool WellSpacedEngine<D>::compute_cell(OpId o, VertexId v, bool fill, Worker& w) {
  if (recording_) {
    recorded_ops_[o].facets = engine::FacetFilter<D>::everything();
    recorded_ops_[o].reach = engine::CellReach<D>::unbounded();
  }
  const Point<D> p = positions_[v];
  const std::uint64_t now = time_key(op_at(o).rank, op_at(o).color);
  const bool may_idle = fill && !params_.literal_stable_ws;
  // v's cell computed earlier in this propagation, if any: taken as it is when it still holds, else
  // the vertices its entry lists spare the search (gather_from_tree).
  const CachedCell* earlier = caching_ ? cached_neighbourhood(v, p) : nullptr;
  // The entry's nearest neighbour was born before the entry's time, so it is still in M_t (cell_cache.cpp),
  // stale entry or not: nearer v than rho^rank, it makes the fill idle whatever came nearer since, and the
  // fill depends on it alone (record_idle_fill), as on a nearest neighbour.
  if (earlier && may_idle && ranks_.rank_below(p, positions_[earlier->nearest], op_at(o).rank, w.cell.counters())) {
    w.hood.nearest = earlier->nearest;
    record_idle_fill(o, v, w);
    return false;
  }
  if (earlier && reuse_cell(o, *earlier, now)) return true;
  ++w.counters.clipped_voronoi_calls;
  w.unborn.clear();
  CellSearch search(*this, o, v, w, earlier, now);
  // A 2D one-shot build walks the triangulation of M_t for the candidates (gather_from_delaunay), else
  // searches the tree. It records nothing and caches nothing.
  const bool asked = delaunay_ && !recording_ && !caching_;
  engine::DelaunayNeighbours::Walk* walk = asked ? &delaunay_walk() : nullptr;
  bool from_delaunay = asked && search.gather_from_delaunay(*walk);
  if (!from_delaunay) search.gather_from_tree();
  if (w.hood.nearest == kNoVertex) {
    search.record_lone_vertex();
    return true;
  }
  if (may_idle && ranks_.rank_below(p, positions_[w.hood.nearest], op_at(o).rank, w.cell.counters())) {
    record_idle_fill(o, v, w);
    return false;
  }
  if (from_delaunay) {
    if (search.clip_from_delaunay(*walk)) {
      ++w.counters.delaunay_cells;
      search.keep_cutting_candidates();
      search.record_dependencies();
      return true;
    }
    // Crowded, or distances tied up to rounding: the tree search's cell (the same nearest neighbour).
    CellSearch again(*this, o, v, w, earlier, now);
    again.gather_from_tree();
    ++w.counters.delaunay_fallbacks;
    again.clip();
    again.keep_cutting_candidates();
    again.record_dependencies();
    return true;
  }
  if (asked) ++w.counters.delaunay_fallbacks;
  search.clip();
  search.keep_cutting_candidates();
  search.record_dependencies();
  return true;
}

// A fill at rank r whose vertex v has a nearest neighbour u nearer than rho^r does nothing: u cannot
// have been inserted during rank r (Fact 2 keeps the Steiner vertices of rank r farther than rho^(r+1)
// from everything), so NN(v) < rho^r at the beginning of rank r, where Lemma 4.2 (progress) makes v
// well-spaced, and Fact 2 keeps it so. No cell is needed, and the decision depends on u alone: a vertex
// inserted only brings NN(v) down, and removing another vertex leaves NN(v) as it is.
template <int D>
void WellSpacedEngine<D>::record_idle_fill(OpId o, VertexId v, Worker& w) {
  const double nn2 = squared_distance(v, w.hood.nearest);
  record_reads(w, positions_[v], std::sqrt(nn2) * (1 + kRadiusMargin));
  if (recording_) {
    RecordedOp& op = recorded_ops_[o];
    op.set_depends2(at_least(nn2 * (1 + kRadiusMargin)));
    op.set_inserted_depends2(0);  // only a vertex exactly at v's place, which reruns it
    op.facets = facet_bits(w.hood.nearest);
    op.reach = engine::CellReach<D>::unbounded();
  }
  ++w.counters.fills_idle_by_rank;
}

template <int D>
void WellSpacedEngine<D>::record_reads(Worker& w, const Point<D>& p, double h) const {
  if (!recording_) return;  // a one-shot build: nobody will ask who read what
  Point<D> lo, hi;
  for (int i = 0; i < D; ++i) {
    lo[i] = p[i] - h;
    hi[i] = p[i] + h;
  }
  w.cover = tree_.covering_nodes(p, lo, hi, w.covering);
}

template bool WellSpacedEngine<2>::compute_cell(OpId, VertexId, bool, Worker&);
template bool WellSpacedEngine<3>::compute_cell(OpId, VertexId, bool, Worker&);
template void WellSpacedEngine<2>::record_idle_fill(OpId, VertexId, Worker&);
template void WellSpacedEngine<3>::record_idle_fill(OpId, VertexId, Worker&);
template void WellSpacedEngine<2>::record_reads(Worker&, const Point<2>&, double) const;
template void WellSpacedEngine<3>::record_reads(Worker&, const Point<3>&, double) const;

}  // namespace shoremesh
