#pragma once
// The Voronoi cell of one vertex v, clipped to a box, computed locally: start from a box around v and
// cut it by the bisectors of nearby vertices. A convex polygon in 2D (cyclic edge list) and a convex
// polyhedron in 3D, kept in its dual: each vertex is the triangle of its three planes, listed counter-
// clockwise seen from outside, and those triangles tile the sphere of planes (as in Ray et al., "Meshless
// Voronoi on the GPU", 2018): a cut needs no faces, only the vertices it removes. All decisions are exact
// (predicates.hpp); vertices are kept symbolically as the D constraints that define them, with interval
// coordinates for the filter.
// Degenerate inputs (grids: four co-circular points, eight co-spherical) give vertices that lie exactly
// on a new plane; those are kept (sign 0 counts as inside), so no ad-hoc epsilon is ever needed.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "shoremesh/engine/ids.hpp"
#include "shoremesh/engine/predicates.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::engine {

// A half-space n.y <= b in coordinates relative to v (y = x - v), so the filter works on small numbers.
template <int D>
struct Constraint {
  // Through (2D): the half-plane value * orient2d(v, other_point, x) >= 0, bounded by the line through v
  // and other_point (a cell restricted to the water side of the shore at v, docs/water_only.md).
  enum class Kind : std::uint8_t { Bisector, AxisMin, AxisMax, Through };
  // The small fields first, in one word, and the intervals (16-byte aligned) where they need no padding:
  // a cell copies its constraints whenever the cache stores or hands out a cell (112 bytes in 2D and 144
  // in 3D, 16 less than in declaration order with an int axis).
  Kind kind = Kind::Bisector;
  // For the vertex solve in doubles (convex_cell.cpp): whether every width below is within 2^-50 of |inf|.
  bool narrow = false;
  std::uint8_t axis = 0;       // AxisMin: x[axis] >= value; AxisMax: x[axis] <= value
  VertexId other = kNoVertex;  // Bisector: the vertex whose bisector with v this is
  double value = 0;
  std::array<Interval, D> n{};
  Interval b{};
  Point<D> other_point{};
  double order_d2 = 0;         // Bisector: |other - v|^2 as the engine orders its candidates
  // For the vertex solve in doubles: |inf| + width of each coefficient.
  std::array<double, D> n_magnitude{};
  double b_magnitude = 0;
};

template <int D>
class ConvexCell {
 public:
  // The box [lo, hi] around v (v inside it). Call under a RoundingGuard, like every other member.
  void reset(const Point<D>& v, const Point<D>& lo, const Point<D>& hi);
  // Cuts by the bisector of v and w (d2: |w - v|^2 as the caller orders its candidates, ties by
  // position). Returns whether any part of the cell was cut away.
  bool clip(VertexId w, const Point<D>& wp, double d2);
  // 2D: cuts by the half-plane side * orient2d(v, x, y) >= 0 (side +1 or -1; x != v), a line through v.
  // Returns whether any part of the cell was cut away.
  bool clip_through_site(const Point<D>& x, int side);
  // Cuts between these two calls may come out of distance order (a cached cell cut by vertices born
  // since). In 3D a vertex solves its three planes in plane order, and planes are numbered in the
  // order they cut, which from scratch is distance order: meanwhile new vertices order their planes
  // by distance instead, and the second call numbers all planes by distance. The cell is then what
  // cutting in distance order gives, bit for bit (when no cut met a vertex on its plane). No-ops in 2D,
  // where a vertex solves its incoming then its outgoing edge, whatever order they came in.
  void begin_out_of_order_cuts();
  void end_out_of_order_cuts();

  // Whether every vertex c of the cell has |c - v|^2 <= k |u - v|^2 (exact): v is rho-well-spaced with
  // k = rho^2 and u its nearest neighbour.
  bool within_scaled_distance(double k, const Point<D>& u);
  // The vertex farthest from v (by interval midpoints; ties by coordinates): where Steiner points aim.
  Point<D> farthest_vertex_offset() const;
  // Calls f(y) for every vertex of the cell, y: its position relative to v, enclosed in intervals.
  template <class F>
  void for_each_vertex_box(F&& f) const {
    for (const Vertex& vtx : verts_)
      if (vtx.first_at_its_point()) f(vtx.y);
  }
  // Whether every vertex's interval box holds its exact position (a self-check for tests: exact, slow).
  bool vertex_boxes_hold_exact_positions();
  // Vertices w whose bisector bounds the cell (the clipped Voronoi neighbours found so far).
  void bisector_neighbours(std::vector<VertexId>& out) const;

  // An upper bound on max |c - v|^2 over the cell's vertices: a bisector farther than twice this from v
  // cannot cut the cell.
  double max_vertex_distance2() const;
  // Whether no vertex w with w - v in the box [lo, hi] can cut the cell, with room to spare. w cuts the
  // cell iff some vertex c of it is nearer w than v, that is iff w lies in the ball about c through v;
  // the test asks that the box keep clear of every such ball by a thousandth of its radius squared
  // (and of rounding: the box is widened by a few ulps of the unit box). The cell only shrinks as it is
  // cut, so what cannot cut it now never will. Far cheaper than a clip, and decides no vertex on a
  // plane: a vertex whose bisector passes exactly through a corner of the cell is never let off.
  bool surely_uncut_by_box(const Point<D>& lo, const Point<D>& hi) const;
  // Whether some clip found a live vertex exactly on its plane (grids: co-circular, co-spherical
  // points). Without that, every vertex of the cell lies on exactly D of its planes, so the cell is a
  // function of its geometry alone, whatever other half-spaces that contain it were offered on the way.
  bool had_vertex_on_plane() const { return vertex_on_plane_; }
  // This cell becomes a copy of `other`'s cell (not of its scratch buffers, nor of its counters).
  void assign_geometry(const ConvexCell& other);
  // Heap bytes held by its buffers.
  std::size_t memory_bytes() const;
  const Point<D>& site() const { return v_; }
  // Distinct points among the vertices (counted: only tests ask).
  std::size_t vertex_count() const {
    return std::size_t(std::count_if(verts_.begin(), verts_.end(), [](const Vertex& vtx) { return vtx.first_at_its_point(); }));
  }
  PredicateCounters& counters() { return counters_; }
  const PredicateCounters& counters() const { return counters_; }

 private:
  struct Vertex {
    // The constraints that define it. 2D: its incoming, then its outgoing edge. 3D: its three planes
    // counter-clockwise seen from outside the cell (the dual triangle's orientation).
    std::array<std::uint16_t, D> planes{};
    double r2 = 0;                          // an upper bound on |y|^2 (in the planes' padding)
    std::array<Interval, D> y{};            // its position relative to v, enclosed
    std::int32_t exact = -1;                // index into exact_ once computed
    // 3D: a point on four or more planes is several dual triangles (a cut that met a kept vertex exactly
    // made a new one at the same point). `place` names the first vertex made at its point, by `serial`:
    // only that one counts as a vertex of the cell.
    std::uint32_t serial = 0, place = 0;
    bool first_at_its_point() const { return place == serial; }
  };
  // A directed edge a -> b of a dual triangle: the cell's edge on planes a and b.
  struct PlanePair {
    std::uint16_t a, b;
  };
  std::uint16_t add_constraint(const Constraint<D>& c);
  void set_magnitudes(Constraint<D>& c);
  bool before_in_distance_order(std::uint16_t a, std::uint16_t b) const;
  // Solves the vertex of these planes into vtx, a fresh Vertex{} in a vertex list (no copy after).
  void make_vertex(const std::array<std::uint16_t, D>& planes, Vertex& vtx);
  const std::array<Exact, D>& exact_position(Vertex& vtx);
  int side(Vertex& vtx, std::uint16_t plane);  // sign of n.y - b: > 0 outside
  // Whether vertices i and j are the same point (exact).
  bool same_point(std::size_t i, std::size_t j);
  bool mark_sides(std::uint16_t plane);
  // Cuts by the last constraint (its plane made), or forgets it when it cuts nothing: whether it cut.
  bool cut_by_last();
  void clip_polygon(std::uint16_t plane);
  void clip_polyhedron(std::uint16_t plane);
  void find_rim();

  Point<D> v_{};
  std::vector<Constraint<D>> constraints_;
  std::vector<std::array<Exact, D>> exact_;
  std::vector<Vertex> verts_, next_verts_;
  bool vertex_on_plane_ = false;
  bool out_of_order_ = false;  // between begin_ and end_out_of_order_cuts
  std::vector<std::int8_t> signs_;
  // 2D: edges_[i] is the constraint of the edge from vertex i to vertex i+1.
  std::vector<std::uint16_t> edges_, next_edges_;
  // 3D scratch of a cut: the directed edges of the triangles cut away, and those of them on the rim
  // (their reverse belongs to a kept triangle). plane_seen_, plane_places_: scratch of
  // bisector_neighbours.
  std::vector<PlanePair> cut_edges_, rim_;
  static constexpr std::uint32_t kNoEdge = ~std::uint32_t(0);  // planes are 16-bit: no edge's code
  std::vector<std::uint32_t> edge_table_;                     // cut_edges_ by code, to find reverses
  // find_rim's numbering of the planes of a cut, and each one's outgoing cut edges as bits.
  std::vector<std::uint32_t> plane_stamp_;
  std::vector<std::uint8_t> plane_local_;
  std::uint32_t stamp_ = 0;
  std::vector<std::uint16_t> order_scratch_, renamed_scratch_;  // end_out_of_order_cuts
  std::vector<Constraint<D>> sorted_scratch_;
  std::vector<std::uint64_t> out_bits_;  // 64 rows once used (a cached cell's copy never clips)
  std::uint32_t next_serial_ = 0;
  mutable std::vector<std::uint8_t> plane_seen_;
  mutable std::vector<std::uint64_t> plane_places_;
  // surely_uncut_by_box's copy of the vertices' enclosures, by component (a vertex's lower ends on each
  // axis, its upper ends, its r2; m entries each): the searches ask it many times per shape of the
  // cell (tens of millions of tests at Lake Superior), and read these 40 bytes per vertex instead of the
  // records. Rebuilt on the first call after the vertices change (balls_stale_).
  mutable std::vector<double> balls_;
  mutable bool balls_stale_ = true;
  // The vertex whose ball met the last box that the test could not let off: the next box (a nearby
  // leaf or point of the same search) mostly meets it too, so it is tried first.
  mutable std::uint32_t last_meeting_ = 0;
  void refresh_balls() const;
  PredicateCounters counters_;
};

}  // namespace shoremesh::engine
