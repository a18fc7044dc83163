#include "shoremesh/engine/engine.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "shoremesh/error.hpp"

namespace shoremesh {

using namespace engine;

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
  pending_dispatch_.assign(std::size_t(ranks_.max_rank() - ranks_.min_rank() + 1), {});
  pending_fill_.assign(pending_dispatch_.size(), {});
  counters_ = Counters{};
  cell_.counters() = PredicateCounters{};
  input_count_ = 0;
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
void WellSpacedEngine<D>::build(std::span<const Point<D>> unit_points) {
  reset();
  for (std::size_t i = 0; i < unit_points.size(); ++i)
    for (int k = 0; k < D; ++k) {
      const double x = unit_points[i][k];
      if (!std::isfinite(x)) throw PointInputError("point " + std::to_string(i) + " is not finite", {i});
      if (x < 0 || x > 1) throw PointInputError("point " + std::to_string(i) + " lies outside the box", {i});
    }
  // Exact duplicates get their own message (the quadtree would call them too close).
  std::vector<std::size_t> order(unit_points.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return unit_points[a] < unit_points[b]; });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (unit_points[order[k]] == unit_points[order[k - 1]]) {
      const std::size_t a = std::min(order[k], order[k - 1]), b = std::max(order[k], order[k - 1]);
      throw PointInputError("points " + std::to_string(a) + " and " + std::to_string(b) + " are equal", {a, b});
    }

  input_count_ = unit_points.size();
  positions_.assign(unit_points.begin(), unit_points.end());
  vertices_.resize(input_count_);
  std::vector<VertexId> ids(input_count_);
  for (VertexId v = 0; v < input_count_; ++v) {
    vertices_[v].position = positions_[v];
    vertices_[v].is_input = true;
    ids[v] = v;
  }
  tree_.build(positions_, ids);
  for (NodeId n = 0; n < tree_.node_capacity(); ++n) {
    const auto& nd = tree_.node(n);
    if (nd.level < 0 || !nd.is_leaf()) continue;
    for (VertexId v : nd.vertices) vertices_[v].leaf = n;
  }
  readers_.assign(tree_.node_capacity(), {});
  // Input dispatches at the rank of QTApxNN(v) (a quarter of the side of its leaf): NN from below.
  for (VertexId v = 0; v < input_count_; ++v) {
    const int rank = ranks_.rank_of_length(tree_.approximate_nn(vertices_[v].leaf));
    const OpId o = new_op(OpKind::Dispatch, v, rank, 0, kNoOp);
    vertices_[v].dispatch = o;
    schedule(o);
  }
  run();
}

template <int D>
typename WellSpacedEngine<D>::OpId WellSpacedEngine<D>::new_op(OpKind kind, VertexId v, int rank, std::uint32_t color,
                                                               OpId parent) {
  Op op;
  op.kind = kind;
  op.vertex = v;
  op.rank = rank;
  op.color = color;
  op.parent = parent;
  ops_.push_back(op);
  return OpId(ops_.size() - 1);
}

template <int D>
void WellSpacedEngine<D>::schedule(OpId o) {
  const std::size_t slot = std::size_t(ops_[o].rank - ranks_.min_rank());
  (ops_[o].kind == OpKind::Dispatch ? pending_dispatch_ : pending_fill_)[slot].push_back(o);
}

template <int D>
void WellSpacedEngine<D>::run() {
  for (int rank = ranks_.min_rank(); rank <= ranks_.max_rank(); ++rank) {
    current_rank_ = rank;
    const std::size_t slot = std::size_t(rank - ranks_.min_rank());
    // Dispatches only create fills, so this list does not grow while it runs.
    std::vector<OpId> batch = std::move(pending_dispatch_[slot]);
    pending_dispatch_[slot] = {};
    for (OpId o : batch) dispatch(o);
    // Fills of one rank and colour are independent (Lemma 6.1); sorting by colour, then position,
    // makes even their order canonical. Fills only create dispatches of higher ranks.
    batch = std::move(pending_fill_[slot]);
    pending_fill_[slot] = {};
    std::sort(batch.begin(), batch.end(), [&](OpId a, OpId b) {
      if (ops_[a].color != ops_[b].color) return ops_[a].color < ops_[b].color;
      return positions_[ops_[a].vertex] < positions_[ops_[b].vertex];
    });
    for (OpId o : batch) fill(o);
  }
  counters_.predicate_calls += cell_.counters().calls;
  counters_.exact_fallbacks += cell_.counters().exact;
  cell_.counters() = PredicateCounters{};
}

template <int D>
void WellSpacedEngine<D>::compute_cell(OpId o, VertexId v) {
  ++counters_.clipped_voronoi_calls;
  const Point<D> p = positions_[v];
  PredicateCounters& pc = cell_.counters();
  auto& pool = hood_.candidates;
  hood_.nearest = kNoVertex;
  pool.clear();
  double best_d2 = 0;
  tree_.begin_session();
  // Adds the vertices of the leaves of box [p - half, p + half] not searched yet, tracking the nearest.
  auto search = [&](double half) {
    Point<D> lo, hi;
    for (int i = 0; i < D; ++i) {
      lo[i] = p[i] - half;
      hi[i] = p[i] + half;
    }
    counters_.leaves_visited += tree_.for_each_leaf_in_box(lo, hi, [&](NodeId n) {
      for (VertexId u : tree_.node(n).vertices) {
        if (u == v) continue;
        const double d2 = squared_distance(v, u);
        pool.push_back({d2, u});
        if (hood_.nearest != kNoVertex && d2 > best_d2 * (1 + 1e-12)) continue;
        if (hood_.nearest != kNoVertex && d2 >= best_d2 * (1 - 1e-12)) {
          // Nearly tied: decide exactly, then by coordinates, so the nearest neighbour is canonical.
          const int c = compare_squared_distances<D>(pc, p, positions_[u], p, positions_[hood_.nearest]);
          if (c > 0 || (c == 0 && !(positions_[u] < positions_[hood_.nearest]))) continue;
        }
        hood_.nearest = u;
        best_d2 = d2;
      }
    });
  };
  // Grow the box until it holds a vertex no farther than its half-side: no vertex outside is nearer.
  double half = tree_.side(vertices_[v].leaf);
  for (;;) {
    search(half);
    if (hood_.nearest != kNoVertex && best_d2 <= half * half * (1 - 1e-9)) break;
    if (half >= 2.0) break;  // the box covers [0,1]^D
    half *= 2;
  }
  auto record_reads = [&](double h) {
    Point<D> lo, hi;
    for (int i = 0; i < D; ++i) {
      lo[i] = p[i] - h;
      hi[i] = p[i] + h;
    }
    tree_.covering_nodes(lo, hi, covering_);
    ops_[o].reads_begin = std::uint32_t(reads_.size());
    for (NodeId n : covering_) {
      reads_.push_back(n);
      readers_[n].push_back(o);
    }
    ops_[o].reads_end = std::uint32_t(reads_.size());
  };
  if (hood_.nearest == kNoVertex) {
    record_reads(half);
    return;
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
  cell_.reset(p, cube_lo, cube_hi);
  // Clip by the vertices in order of distance (ties by coordinates: a canonical order, so the rounded
  // cell does not depend on insertion history). A vertex farther than twice the cell's reach cannot cut
  // it, nor can one beyond 2 beta NN cut the beta-ball: the search grows only while a cut is possible.
  auto by_distance = [&](const Candidate& a, const Candidate& b) {
    if (a.d2 != b.d2) return a.d2 < b.d2;
    return positions_[a.id] < positions_[b.id];
  };
  std::sort(pool.begin(), pool.end(), by_distance);
  const double cap2 = 4 * params_.beta_squared * best_d2 * (1 + 1e-9);
  double searched = half;
  std::size_t next = 0;
  for (;;) {
    double reach2 = std::min(4 * cell_.max_vertex_distance2() * (1 + 1e-9), cap2);
    while (next < pool.size() && pool[next].d2 <= std::min(reach2, searched * searched)) {
      if (cell_.clip(pool[next].id, positions_[pool[next].id]))
        reach2 = std::min(4 * cell_.max_vertex_distance2() * (1 + 1e-9), cap2);
      ++next;
    }
    if (reach2 <= searched * searched) break;
    // Grow gently: the vertices found next usually shrink the cell, and with it the reach.
    searched = std::min(std::sqrt(reach2) * (1 + 1e-9), 1.5 * searched);
    const std::size_t old_size = pool.size();
    search(searched);
    if (pool.size() > old_size) std::sort(pool.begin() + long(next), pool.end(), by_distance);
  }
  record_reads(searched);
}

template <int D>
void WellSpacedEngine<D>::request_fill(OpId parent, VertexId w, int rank) {
  for (OpId f = vertices_[w].first_fill; f != kNoOp; f = ops_[f].next_fill)
    if (ops_[f].rank == rank) {
      ++ops_[f].requesters;
      children_.push_back(f);
      return;
    }
  const OpId f = new_op(OpKind::Fill, w, rank, ranks_.color(positions_[w], rank), parent);
  ops_[f].requesters = 1;
  ops_[f].next_fill = vertices_[w].first_fill;
  vertices_[w].first_fill = f;
  children_.push_back(f);
  schedule(f);
}

template <int D>
void WellSpacedEngine<D>::dispatch(OpId o) {
  RoundingGuard guard;
  ++counters_.dispatches;
  const VertexId v = ops_[o].vertex;
  const int op_rank = ops_[o].rank;
  compute_cell(o, v);
  ops_[o].children_begin = ops_[o].children_end = std::uint32_t(children_.size());
  if (hood_.nearest == kNoVertex) return;  // a lone vertex is well-spaced
  PredicateCounters& pc = cell_.counters();
  const Point<D>& p = positions_[v];
  // v's fill at its current rank, and fills that update the ranks of its beta-clipped Voronoi
  // neighbours (bisector faces of the cell no farther than 2 beta NN(v): a superset, harmless, since a
  // fill at rank floor(log |vw|) finds w already well-spaced unless it truly is due).
  const int r = ranks_.rank_of(p, positions_[hood_.nearest], pc);
  if (r >= op_rank) request_fill(o, v, r);
  const double limit2 = 4 * params_.beta_squared * squared_distance(v, hood_.nearest) * (1 + 1e-9);
  cell_.bisector_neighbours(neighbours_);
  for (VertexId w : neighbours_) {
    if (squared_distance(v, w) > limit2) continue;
    const int rw = ranks_.rank_of(p, positions_[w], pc);
    if (rw >= op_rank) request_fill(o, w, rw);
  }
  ops_[o].children_end = std::uint32_t(children_.size());
}

template <int D>
void WellSpacedEngine<D>::fill(OpId o) {
  RoundingGuard guard;
  ++counters_.fills;
  const VertexId v = ops_[o].vertex;
  const int op_rank = ops_[o].rank;
  compute_cell(o, v);
  ops_[o].children_begin = ops_[o].children_end = std::uint32_t(children_.size());
  if (hood_.nearest == kNoVertex) return;
  PredicateCounters& pc = cell_.counters();
  const Point<D> u = positions_[hood_.nearest];
  for (int inserted = 0; !cell_.within_scaled_distance(params_.rho_squared, u); ++inserted) {
    if (inserted > 1000) throw std::logic_error("fill inserted over 1000 Steiner points around one vertex");
    const Point<D> w = pick_steiner(v);
    const VertexId id = insert_steiner(w, o, vertices_[v].leaf);
    // Fact 1 puts w's rank above op's; the max only guards the table's rounding for a rho other than
    // sqrt(2) (for sqrt(2) the table is exact and it never applies).
    const int rank = std::max(ranks_.rank_of(w, positions_[v], pc), op_rank + 1);
    const OpId d = new_op(OpKind::Dispatch, id, rank, 0, o);
    vertices_[id].dispatch = d;
    children_.push_back(d);
    schedule(d);
    cell_.clip(id, w);
    hood_.candidates.push_back({squared_distance(v, id), id});
  }
  ops_[o].children_end = std::uint32_t(children_.size());
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
      if (compare_squared_distances<D>(pc, w, p, w, positions_[c.id]) >= 0) {
        inside = false;
        break;
      }
    if (inside) return w;
  }
  throw std::logic_error("no admissible Steiner point in the picking region of a vertex");
}

template <int D>
typename WellSpacedEngine<D>::VertexId WellSpacedEngine<D>::insert_steiner(const Point<D>& p, OpId creator, NodeId near) {
  const VertexId id = VertexId(vertices_.size());
  Vertex vx;
  vx.position = p;
  vx.creator = creator;
  positions_.push_back(p);
  vx.leaf = tree_.insert_vertex(id, p, near);
  vertices_.push_back(vx);
  ++counters_.steiner_points;
  return id;
}

template <int D>
std::size_t WellSpacedEngine<D>::memory_bytes() const {
  std::size_t bytes = vertices_.capacity() * sizeof(Vertex) + positions_.capacity() * sizeof(Point<D>) +
                      ops_.capacity() * sizeof(Op) + children_.capacity() * sizeof(OpId) +
                      reads_.capacity() * sizeof(NodeId) + readers_.capacity() * sizeof(std::vector<OpId>) +
                      tree_.memory_bytes();
  for (const auto& r : readers_) bytes += r.capacity() * sizeof(OpId);
  return bytes;
}

template <int D>
void WellSpacedEngine<D>::check_valid() const {
  auto fail = [](const std::string& what) { throw std::logic_error("engine invalid: " + what); };
  tree_.check_valid(positions_);
  for (VertexId v = 0; v < vertices_.size(); ++v) {
    const Vertex& vx = vertices_[v];
    if (vx.position != positions_[v]) fail("vertex position copy");
    const auto& list = tree_.node(vx.leaf).vertices;
    if (!tree_.node(vx.leaf).is_leaf() || std::find(list.begin(), list.end(), v) == list.end())
      fail("vertex " + std::to_string(v) + " not in its leaf");
    if (vx.dispatch == kNoOp || ops_[vx.dispatch].vertex != v || ops_[vx.dispatch].kind != OpKind::Dispatch)
      fail("vertex " + std::to_string(v) + " without its dispatch");
    if (vx.is_input != (v < input_count_)) fail("input flag");
    if (!vx.is_input && (vx.creator == kNoOp || ops_[vx.creator].kind != OpKind::Fill)) fail("Steiner vertex creator");
  }
  for (OpId o = 0; o < ops_.size(); ++o) {
    const Op& op = ops_[o];
    if (op.vertex >= vertices_.size()) fail("operation vertex");
    if ((op.kind == OpKind::Dispatch) != (op.color == 0)) fail("colour 0 is for dispatches only");
    for (OpId c : children(o)) {
      if (c >= ops_.size()) fail("child id");
      if (ops_[c].rank < op.rank) fail("a child runs before its parent");
    }
    for (NodeId n : reads(o)) {
      const auto& rs = readers_[n];
      if (std::find(rs.begin(), rs.end(), o) == rs.end()) fail("read edge without reader entry");
    }
  }
}

template class WellSpacedEngine<2>;
template class WellSpacedEngine<3>;

}  // namespace shoremesh
