// The verifier's 3D cells: voro++ cuts Vor(v) ∩ box for every point, in floating point.
//
// This is the one inexact part of the verifier, so a vertex counts as a violation only when its ratio
// exceeds rho by more than a relative 1e-9: smaller excesses are below what the floating-point cell
// resolves.
//
// Why not voro::container: it decides with an absolute tolerance of 1e-11 in container coordinates, and
// on graded sets (a well-spaced output around a close pair spans nine orders of magnitude; Kuzmin's 1e5
// points in 3D) it loses cells outright. Here each cell is cut in its own frame, centred on v and scaled
// by NN(v), so the tolerance is relative to the local spacing: a voro::voronoicell starts as the box and
// is cut by the bisectors of the other points in order of distance (CGAL's incremental kd-tree search),
// until the next point is farther than twice the cell's radius and so cannot cut it. The cost of a cell
// grows with the number of points within twice its radius: a few dozen on a well-spaced set (radius at
// most rho * NN), all of them for raw inputs whose cells are long cones (points on a sphere).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_incremental_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <voro++/voro++.hh>

#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::verify_detail {

constexpr double kRelativeTolerance3 = 1e-9;

// For every point with rated[i] != 0: ratio[i] = max over the vertices c of Vor(i) ∩ box of |c - p_i| /
// nn[i] (0 when nn is infinite), violates[i] = 1 when ratio[i] > rho * (1 + 1e-9). `points` are pairwise
// distinct (user coordinates); rated points lie in the closed box.
void rate_cells_3d(std::span<const Point3> points, std::span<const std::uint8_t> rated, std::span<const double> nn,
                   const BoxTransform<3>& box, double rho, std::vector<double>& ratio,
                   std::vector<std::uint8_t>& violates) {
  using Traits = CGAL::Search_traits_3<CGAL::Epick>;
  using Search = CGAL::Orthogonal_incremental_neighbor_search<Traits>;
  ratio.assign(points.size(), 0.0);
  violates.assign(points.size(), 0);
  if (points.size() < 2) return;

  std::vector<CGAL::Epick::Point_3> sites;
  sites.reserve(points.size());
  for (const Point3& p : points) sites.emplace_back(p[0], p[1], p[2]);
  Search::Tree tree(sites.begin(), sites.end());
  tree.build();

  voro::voronoicell cell;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!rated[i]) continue;
    const Point3& v = points[i];
    const double scale = 1.0 / nn[i];  // the local frame: v at the origin, NN(v) = 1
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = (box.origin[a] - v[a]) * scale;
      hi[a] = (box.origin[a] + box.side - v[a]) * scale;
    }
    cell.init(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
    double radius_squared = 0.25 * cell.max_radius_squared();  // voro++ reports four times the square
    Search search(tree, sites[i]);
    for (auto it = search.begin(); it != search.end(); ++it) {
      const double d_squared = it->second * scale * scale;
      if (d_squared == 0) continue;                 // v itself
      if (d_squared > 4 * radius_squared) break;    // its bisector lies beyond every vertex
      const auto& u = it->first;
      const double x = (u.x() - v[0]) * scale, y = (u.y() - v[1]) * scale, z = (u.z() - v[2]) * scale;
      if (!cell.plane(x, y, z))
        throw std::logic_error("verifier: voro++ lost the cell of output point " + std::to_string(i));
      radius_squared = 0.25 * cell.max_radius_squared();
    }
    ratio[i] = std::sqrt(radius_squared);  // in units of NN(v)
    violates[i] = ratio[i] > rho * (1 + kRelativeTolerance3) ? 1 : 0;
  }
}

}  // namespace shoremesh::verify_detail
