// Cells that stop at the shore (docs/water_only.md, "Cells that stop at the shore"): the fill of an input
// vertex on the rings tests well-spacedness on its cell restricted to its water wedge and picks its
// Steiner points there. Every decision is exact (orient2d, the rings' stored doubles); the wedge is a
// function of v, NN(v) and the rings within NN(v) of v (and the parity of one point there), all inside
// the box the fill's search registered on, so a ring edit there reruns it (mark_water_readers).
#include <algorithm>
#include <cmath>

#include "engine_internal.hpp"
#include "shoremesh/engine/engine.hpp"

namespace shoremesh {

using namespace engine;

namespace {
// The box about v in which an edge counts as passing through v: far above the rounding of a split on its
// ring edge (an ulp of the unit box, 2^-53), far below any vertex spacing (2^-40). The same as
// fill_on_land's absolute margin.
constexpr double kAtVertex = 0x1p-48;
// The probe of the water side lies this fraction of NN(v) from v: inside the box the fill registered on.
constexpr double kProbe = 0x1p-4;
}  // namespace

// The wedge: the ring edges meeting v's box of half-side kAtVertex are either the two edges of a ring
// vertex v (P -> v, v -> N; the rings are stored as the user gave them, edge k from point k to k + 1)
// or one edge A -> B that v splits (v within rounding of it: P = A, N = B). Anything else (no edge,
// several rings at v, a tiny edge beside v) keeps the whole cell. The water side is the parity of a probe
// point q at kProbe NN(v) from v, strictly on one side of the shore at v, such that no other edge meets
// the box of v and q (widened by kAtVertex): then q and the shore's side at v lie in one region without
// an edge between them, and in_closed_water(q) is exact (q lies on no edge).
template <int D>
bool WellSpacedEngine<D>::shore_wedge(VertexId v, Worker& w, ShoreWedge& wedge) const {
  if constexpr (D != 2) {
    (void)v, (void)w, (void)wedge;
    return false;
  } else {
    if (!vertices_[v].is_input || w.hood.nearest == kNoVertex) return false;
    PredicateCounters& pc = w.cell.counters();
    const Point2 p = positions_[v];
    auto& edges = w.shore_edges;
    edges.clear();
    water_->edges_meeting({p[0] - kAtVertex, p[1] - kAtVertex}, {p[0] + kAtVertex, p[1] + kAtVertex}, pc, edges);
    bool split = false;  // v on the inside of one edge (a split) rather than a ring vertex
    if (edges.size() == 2 && edges[1][1] == p && edges[0][0] == p) std::swap(edges[0], edges[1]);
    if (edges.size() == 2 && edges[0][1] == p && edges[1][0] == p) {
      wedge.prev = edges[0][0];
      wedge.next = edges[1][1];
    } else if (edges.size() == 1 && edges[0][0] != p && edges[0][1] != p) {
      wedge.prev = edges[0][0];
      wedge.next = edges[0][1];
      split = true;
    } else {
      return false;
    }
    const Point2 a = wedge.prev, b = wedge.next;
    const int turn = orient2d(pc, a, p, b);  // > 0: the left side's angle is below 180 degrees
    // The probe's direction: into the left side, along the bisector of its angle (or straight on at a fold).
    const double l0 = std::hypot(p[0] - a[0], p[1] - a[1]), l1 = std::hypot(b[0] - p[0], b[1] - p[1]);
    const Point2 u0{(p[0] - a[0]) / l0, (p[1] - a[1]) / l0}, u1{(b[0] - p[0]) / l1, (b[1] - p[1]) / l1};
    Point2 dir{-u0[1] - u1[1], u0[0] + u1[0]};
    double len = std::hypot(dir[0], dir[1]);
    if (len < 0.1) {
      dir = {u0[0] - u1[0], u0[1] - u1[1]};
      len = std::hypot(dir[0], dir[1]);
      if (len < 0.1) return false;  // a fold back onto itself: no wedge
    }
    const double step = kProbe * std::sqrt(squared_distance(v, w.hood.nearest)) / len;
    const Point2 q{p[0] + step * dir[0], p[1] + step * dir[1]};
    // q strictly on the left of the shore at v: of both sides when that angle is convex, of either when reflex;
    // for a split, of its ring edge too (v lies on it only up to rounding).
    const int s0 = orient2d(pc, a, p, q), s1 = orient2d(pc, p, b, q);
    const bool left = s0 != 0 && s1 != 0 && (turn >= 0 ? (s0 > 0 && s1 > 0) : (s0 > 0 || s1 > 0));
    if (!left || (split && orient2d(pc, a, b, q) <= 0)) return false;
    // No other edge near v and q.
    const std::size_t at_v = edges.size();
    water_->edges_meeting({std::min(p[0], q[0]) - kAtVertex, std::min(p[1], q[1]) - kAtVertex},
                          {std::max(p[0], q[0]) + kAtVertex, std::max(p[1], q[1]) + kAtVertex}, pc, edges);
    for (std::size_t k = at_v; k < edges.size(); ++k)
      if (std::find(edges.begin(), edges.begin() + std::ptrdiff_t(at_v), edges[k]) == edges.begin() + std::ptrdiff_t(at_v))
        return false;
    const bool water_left = water_->in_closed_water(q, pc);
    wedge.side = water_left ? 1 : -1;
    wedge.convex = water_left ? turn >= 0 : turn <= 0;
    return true;
  }
}

// v's cell restricted to the wedge: its intersection with both half-planes (convex), or each half-plane's
// part in turn (reflex: the union). The first part not rho-well-spaced is left in w.part.
template <int D>
bool WellSpacedEngine<D>::well_spaced_in_wedge(VertexId v, Worker& w, const ShoreWedge& wedge) const {
  if constexpr (D != 2) {
    (void)v, (void)w, (void)wedge;
    return true;
  } else {
    const Point2& u = positions_[w.hood.nearest];
    // side * orient2d(prev, v, x) >= 0  <=>  -side * orient2d(v, prev, x) >= 0.
    auto clip_prev = [&] { w.part.clip_through_site(wedge.prev, -wedge.side); };
    auto clip_next = [&] { w.part.clip_through_site(wedge.next, wedge.side); };
    w.part.assign_geometry(w.cell);
    if (wedge.convex) {
      clip_prev();
      clip_next();
      return w.part.within_scaled_distance(params_.fill_rho_squared, u);
    }
    clip_prev();
    if (!w.part.within_scaled_distance(params_.fill_rho_squared, u)) return false;
    w.part.assign_geometry(w.cell);
    clip_next();
    return w.part.within_scaled_distance(params_.fill_rho_squared, u);
  }
}

// The part's vertices by their enclosures (a function of the cell: canonical); a vertex counts when the
// enclosure lies strictly inside the wedge's half-planes (interval signs), so one on a line (where the part
// was cut) or too near one to tell is left out. Then pick_steiner's rule: the nearest beyond steiner_aim
// rho NN, else the farthest beyond rho NN (midpoints; ties by coordinates).
template <int D>
bool WellSpacedEngine<D>::aim_in_wedge(const Worker& w, const ShoreWedge& wedge, Point<D>& aim) const {
  if constexpr (D != 2) {
    (void)w, (void)wedge, (void)aim;
    return false;
  } else {
    const Point2& p = positions_[w.hood.nearest == kNoVertex ? 0 : w.hood.nearest];
    const Point2& site = w.part.site();
    double nn2 = 0;
    for (int i = 0; i < 2; ++i) nn2 += (p[i] - site[i]) * (p[i] - site[i]);
    const double beyond2 = params_.steiner_aim_squared * nn2, violate2 = params_.rho_squared * nn2;
    // side * cross(x - v, y) for a line through v and x.
    auto sign_of = [&](const Point2& x, int side, const std::array<Interval, 2>& y) {
      const Interval d0 = Interval(x[0]) - Interval(site[0]), d1 = Interval(x[1]) - Interval(site[1]);
      const Interval c = (d0 * y[1] - d1 * y[0]) * Interval(double(side));
      return c.inf() > 0 ? 1 : (c.sup() < 0 ? -1 : 0);
    };
    Point2 nearest{}, farthest{};
    double nearest_d2 = -1, farthest_d2 = -1;
    w.part.for_each_vertex_box([&](const std::array<Interval, 2>& y) {
      // side * orient2d(prev, v, x) = -side * orient2d(v, prev, x).
      const int a = sign_of(wedge.prev, -wedge.side, y), b = sign_of(wedge.next, wedge.side, y);
      if (a == 0 || b == 0 || (wedge.convex ? (a < 0 || b < 0) : (a < 0 && b < 0))) return;
      const Point2 m{0.5 * (y[0].inf() + y[0].sup()), 0.5 * (y[1].inf() + y[1].sup())};
      const double d2 = m[0] * m[0] + m[1] * m[1];
      if (d2 > beyond2 && (nearest_d2 < 0 || d2 < nearest_d2 || (d2 == nearest_d2 && m < nearest))) nearest_d2 = d2, nearest = m;
      if (d2 > violate2 && (d2 > farthest_d2 || (d2 == farthest_d2 && m < farthest))) farthest_d2 = d2, farthest = m;
    });
    if (nearest_d2 >= 0) aim = nearest;
    else if (farthest_d2 >= 0) aim = farthest;
    else return false;
    return true;
  }
}

#define SHOREMESH_ENGINE_SHORE_CELLS(D)                                                        \
  template bool WellSpacedEngine<D>::shore_wedge(VertexId, Worker&, ShoreWedge&) const;       \
  template bool WellSpacedEngine<D>::well_spaced_in_wedge(VertexId, Worker&, const ShoreWedge&) const; \
  template bool WellSpacedEngine<D>::aim_in_wedge(const Worker&, const ShoreWedge&, Point<D>&) const;
SHOREMESH_ENGINE_SHORE_CELLS(2)
SHOREMESH_ENGINE_SHORE_CELLS(3)
#undef SHOREMESH_ENGINE_SHORE_CELLS

}  // namespace shoremesh
