// The verifier's 2D cells, decided exactly: Vor(v) ∩ box as the box square clipped by the bisectors of
// v's Delaunay neighbours, every construction and comparison in CGAL's exact-constructions kernel.
//
// Why the Delaunay neighbours suffice: the Voronoi cell of v in the whole plane is the intersection of
// the half-planes of its Voronoi neighbours, which are exactly its Delaunay neighbours; intersecting with
// the box afterwards gives Vor(v) ∩ box. Degenerate (co-circular) configurations only add neighbours whose
// bisectors touch the cell in a vertex, which leaves the intersection unchanged.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::verify_detail {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Epick>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Epick, Tds>;
using ExactPoint = Epeck::Point_2;
using ExactLine = Epeck::Line_2;

// Delaunay neighbours of every point, as compressed rows (offsets into one array). Built from the finite
// edges, which also covers a triangulation of dimension 1 (all points collinear).
struct Adjacency {
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> neighbours;
};

Adjacency delaunay_adjacency(std::span<const Point2> points) {
  std::vector<std::pair<Epick::Point_2, std::uint32_t>> sites;
  sites.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    sites.emplace_back(Epick::Point_2(points[i][0], points[i][1]), static_cast<std::uint32_t>(i));
  Delaunay dt(sites.begin(), sites.end());

  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * points.size());
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const std::uint32_t a = e->first->vertex(Delaunay::cw(e->second))->info();
    const std::uint32_t b = e->first->vertex(Delaunay::ccw(e->second))->info();
    edges.emplace_back(a, b);
  }
  Adjacency adj;
  adj.offsets.assign(points.size() + 1, 0);
  for (const auto& [a, b] : edges) {
    ++adj.offsets[a + 1];
    ++adj.offsets[b + 1];
  }
  for (std::size_t i = 0; i < points.size(); ++i) adj.offsets[i + 1] += adj.offsets[i];
  adj.neighbours.resize(adj.offsets.back());
  std::vector<std::uint32_t> fill(adj.offsets.begin(), adj.offsets.end() - 1);
  for (const auto& [a, b] : edges) {
    adj.neighbours[fill[a]++] = b;
    adj.neighbours[fill[b]++] = a;
  }
  return adj;
}

// A convex polygon as its vertices in counterclockwise order, each with the line of the edge that leaves
// it. Every line is oriented with the polygon on its positive side. Vertices created by clipping are the
// intersection of two of these lines, so each exact coordinate is a shallow expression in the input
// doubles (never a chain of clipped-and-reclipped points).
struct CellVertex {
  ExactPoint point;
  ExactLine leaving;
};

ExactPoint meet(const ExactLine& a, const ExactLine& b) {
  const auto hit = CGAL::intersection(a, b);
  const ExactPoint* p = hit ? boost::get<ExactPoint>(&*hit) : nullptr;
  // Only called for an edge whose endpoints lie strictly on opposite sides of the cutting line.
  CGAL_assertion(p != nullptr);
  return *p;
}

// Keeps the part of `cell` on the closed positive side of `cut` (Sutherland–Hodgman with exact sides).
// The cell keeps a positive area: the site lies in the box and strictly inside every bisector's side.
void clip(std::vector<CellVertex>& cell, const ExactLine& cut, std::vector<CellVertex>& scratch,
          std::vector<CGAL::Oriented_side>& sides) {
  sides.clear();
  bool any_outside = false;
  for (const CellVertex& c : cell) {
    sides.push_back(cut.oriented_side(c.point));
    any_outside = any_outside || sides.back() == CGAL::ON_NEGATIVE_SIDE;
  }
  if (!any_outside) return;
  scratch.clear();
  const std::size_t n = cell.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const CGAL::Oriented_side si = sides[i], sj = sides[j];
    if (si != CGAL::ON_NEGATIVE_SIDE) scratch.push_back(cell[i]);
    if (si == CGAL::ON_POSITIVE_SIDE && sj == CGAL::ON_NEGATIVE_SIDE) {
      scratch.push_back({meet(cell[i].leaving, cut), cut});  // leaving the kept side: follow the cut
    } else if (si == CGAL::ON_NEGATIVE_SIDE && sj == CGAL::ON_POSITIVE_SIDE) {
      scratch.push_back({meet(cut, cell[i].leaving), cell[i].leaving});  // back in: follow the old edge
    } else if (si == CGAL::ON_ORIENTED_BOUNDARY && sj == CGAL::ON_NEGATIVE_SIDE) {
      scratch.back().leaving = cut;  // a vertex on the cut whose old edge goes outside: the cut replaces it
    }
  }
  cell.swap(scratch);
}

// A double within a relative 1e-12 of x: the interval approximation when it is that tight, the exact
// value otherwise (a small cell far from the origin loses digits to cancellation). CGAL::to_double on a
// lazy number would settle for a relative 1e-5.
double close_double(const Epeck::FT& x) {
  const CGAL::Interval_nt<false>& a = x.approx();
  if (a.sup() - a.inf() <= 1e-12 * std::abs(a.sup())) return 0.5 * (a.inf() + a.sup());
  return CGAL::to_double(x.exact());
}

}  // namespace

// For every point with rated[i] != 0: ratio[i] = max over the vertices c of Vor(i) ∩ box of |c - p_i| /
// NN(p_i) (0 for a lone point), and violates[i] = 1 exactly when some |c - p_i|^2 > rho_squared * NN^2.
// `points` are pairwise distinct; rated points lie in the closed box.
void rate_cells_2d(std::span<const Point2> points, std::span<const std::uint8_t> rated, const BoxTransform<2>& box,
                   double rho_squared, std::vector<double>& ratio, std::vector<std::uint8_t>& violates) {
  ratio.assign(points.size(), 0.0);
  violates.assign(points.size(), 0);
  if (points.empty()) return;
  const Adjacency adj = delaunay_adjacency(points);

  const double x0 = box.origin[0], y0 = box.origin[1];
  const double x1 = x0 + box.side, y1 = y0 + box.side;
  const Epeck::FT exact_rho_squared(rho_squared);
  const ExactPoint origin(0, 0);

  std::vector<CellVertex> cell, scratch;
  std::vector<CGAL::Oriented_side> sides;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!rated[i] || adj.offsets[i] == adj.offsets[i + 1]) continue;
    // The cell is built in coordinates relative to v, translated exactly (lazy differences of doubles):
    // the same decisions, but the interval approximations stay tight for a small cell far from the
    // origin, so the exact fallback is rarely needed.
    const Epeck::FT vx(points[i][0]), vy(points[i][1]);
    auto relative = [&](double x, double y) { return ExactPoint(Epeck::FT(x) - vx, Epeck::FT(y) - vy); };
    const ExactPoint corners[4] = {relative(x0, y0), relative(x1, y0), relative(x1, y1), relative(x0, y1)};
    cell.clear();
    for (int k = 0; k < 4; ++k) cell.push_back({corners[k], ExactLine(corners[k], corners[(k + 1) % 4])});
    bool first = true;
    Epeck::FT nn_squared;
    for (std::uint32_t k = adj.offsets[i]; k < adj.offsets[i + 1]; ++k) {
      const Point2& q = points[adj.neighbours[k]];
      const ExactPoint u = relative(q[0], q[1]);
      const Epeck::FT d = CGAL::squared_distance(origin, u);
      if (first || d < nn_squared) nn_squared = d;
      first = false;
      clip(cell, CGAL::bisector(origin, u), scratch, sides);  // v lies on the bisector's positive side
    }
    // The farthest point of a convex polygon from v is one of its vertices.
    Epeck::FT far_squared = 0;
    for (const CellVertex& c : cell) {
      const Epeck::FT d = CGAL::squared_distance(c.point, origin);
      if (d > far_squared) far_squared = d;
    }
    violates[i] = far_squared > exact_rho_squared * nn_squared ? 1 : 0;
    ratio[i] = std::sqrt(close_double(far_squared) / close_double(nn_squared));
  }
}

}  // namespace shoremesh::verify_detail
