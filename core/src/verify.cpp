// The independent verifier: the parts common to 2D and 3D (validation, containment, repeated points,
// nearest-neighbour and local-feature-size distances). The cells are in verify_cells2.cpp (exact) and
// verify_cells3.cpp (voro++).
#include "shoremesh/verify.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_2.h>
#include <CGAL/Search_traits_3.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "shoremesh/error.hpp"

namespace shoremesh {
namespace verify_detail {
// Defined in verify_cells2.cpp and verify_cells3.cpp.
void rate_cells_2d(std::span<const Point2> points, std::span<const std::uint8_t> rated, const BoxTransform<2>& box,
                   double rho_squared, std::vector<double>& ratio, std::vector<std::uint8_t>& violates);
void rate_cells_3d(std::span<const Point3> points, std::span<const std::uint8_t> rated, std::span<const double> nn,
                   const BoxTransform<3>& box, double rho, std::vector<double>& ratio,
                   std::vector<std::uint8_t>& violates);
}  // namespace verify_detail

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

template <int D>
struct SearchTraits;
template <>
struct SearchTraits<2> {
  using Point = CGAL::Epick::Point_2;
  using Traits = CGAL::Search_traits_2<CGAL::Epick>;
  static Point make(const Point2& p) { return Point(p[0], p[1]); }
};
template <>
struct SearchTraits<3> {
  using Point = CGAL::Epick::Point_3;
  using Traits = CGAL::Search_traits_3<CGAL::Epick>;
  static Point make(const Point3& p) { return Point(p[0], p[1], p[2]); }
};

// For every query, the distance to the second-nearest point of `sites` (infinity when there is none).
// With the query itself among the sites this is its nearest-neighbour distance; with the input as sites
// it is the local feature size.
template <int D>
std::vector<double> second_nearest_distances(std::span<const Point<D>> sites, std::span<const Point<D>> queries) {
  using S = SearchTraits<D>;
  using Search = CGAL::Orthogonal_k_neighbor_search<typename S::Traits>;
  std::vector<double> result(queries.size(), kInfinity);
  if (sites.size() < 2) return result;
  std::vector<typename S::Point> tree_points;
  tree_points.reserve(sites.size());
  for (const auto& p : sites) tree_points.push_back(S::make(p));
  typename Search::Tree tree(tree_points.begin(), tree_points.end());
  tree.build();
  for (std::size_t i = 0; i < queries.size(); ++i) {
    Search search(tree, S::make(queries[i]), 2);
    double second = kInfinity;
    for (auto it = search.begin(); it != search.end(); ++it) second = it->second;  // sorted: the last is 2nd
    result[i] = std::sqrt(second);
  }
  return result;
}

template <int D>
using Bits = std::array<std::uint64_t, D>;

template <int D>
Bits<D> bits_of(const Point<D>& p) {
  Bits<D> b;
  for (int k = 0; k < D; ++k) b[k] = std::bit_cast<std::uint64_t>(p[k]);
  return b;
}

template <int D>
void require_finite(std::span<const Point<D>> points, const char* which) {
  for (std::size_t i = 0; i < points.size(); ++i)
    for (double x : points[i])
      if (!std::isfinite(x)) throw InputError(std::string("verifier: ") + which + " point " + std::to_string(i) + " is not finite");
}

}  // namespace

double canonical_rho_squared(double rho) { return rho == std::sqrt(2.0) ? 2.0 : rho * rho; }

template <int D>
WellSpacedReport<D> verify_well_spaced(PointsOf<D> output, PointsOf<D> input, const BoxTransform<D>& box, double rho) {
  return verify_well_spaced<D>(output, input, box, rho, canonical_rho_squared(rho));
}

template <int D>
WellSpacedReport<D> verify_well_spaced(PointsOf<D> output, PointsOf<D> input, const BoxTransform<D>& box, double rho,
                                       double rho_squared) {
  if (!(std::isfinite(rho) && rho > 0 && std::isfinite(rho_squared) && rho_squared > 0))
    throw ParameterError("verifier: rho and rho_squared must be positive and finite");
  if (!(std::isfinite(box.side) && box.side > 0)) throw ParameterError("verifier: the box side must be positive and finite");
  for (double x : box.origin)
    if (!std::isfinite(x)) throw ParameterError("verifier: the box origin must be finite");
  require_finite<D>(output, "output");
  require_finite<D>(input, "input");

  WellSpacedReport<D> report;
  report.vertex_count = output.size();
  report.rho = rho;
  report.rho_squared = rho_squared;

  // Repeated points: sort indices by value (so 0.0 and -0.0 are one point); the first index of each run
  // stands for the point.
  std::vector<std::size_t> order(output.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return output[a] < output[b]; });
  std::vector<std::size_t> distinct_index;  // index into output of each distinct point
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && output[order[k]] == output[order[k - 1]])
      ++report.duplicate_points;
    else
      distinct_index.push_back(order[k]);
  }
  std::sort(distinct_index.begin(), distinct_index.end());  // back to output order
  std::vector<Point<D>> distinct(distinct_index.size());
  for (std::size_t k = 0; k < distinct.size(); ++k) distinct[k] = output[distinct_index[k]];

  // Containment, bit for bit: the engine promises to hand input points back unchanged.
  std::vector<Bits<D>> output_bits(output.size());
  for (std::size_t i = 0; i < output.size(); ++i) output_bits[i] = bits_of<D>(output[i]);
  std::sort(output_bits.begin(), output_bits.end());
  for (const auto& p : input)
    if (!std::binary_search(output_bits.begin(), output_bits.end(), bits_of<D>(p))) ++report.missing_input;
  report.input_contained = report.missing_input == 0;

  std::vector<std::uint8_t> rated(distinct.size(), 1);
  for (std::size_t k = 0; k < distinct.size(); ++k) {
    for (int a = 0; a < D; ++a) {
      const double lo = box.origin[a], hi = box.origin[a] + box.side;
      if (!(distinct[k][a] >= lo && distinct[k][a] <= hi)) rated[k] = 0;
    }
    if (!rated[k]) ++report.outside_box;
  }

  const std::vector<double> nn = second_nearest_distances<D>(distinct, distinct);
  std::vector<double> ratio;
  std::vector<std::uint8_t> violates;
  if constexpr (D == 2)
    verify_detail::rate_cells_2d(distinct, rated, box, rho_squared, ratio, violates);
  else
    verify_detail::rate_cells_3d(distinct, rated, nn, box, rho, ratio, violates);

  const std::vector<double> lfs = second_nearest_distances<D>(input, distinct);
  for (std::size_t k = 0; k < distinct.size(); ++k) {
    report.violations += violates[k];
    if (ratio[k] > report.worst_ratio) {
      report.worst_ratio = ratio[k];
      report.worst_vertex = distinct_index[k];
    }
    // lfs infinite (fewer than two input points) or NN infinite (a lone output point): nothing to bound.
    if (std::isfinite(lfs[k]) && std::isfinite(nn[k]) && lfs[k] / nn[k] > report.worst_size_conformity) {
      report.worst_size_conformity = lfs[k] / nn[k];
      report.worst_size_vertex = distinct_index[k];
    }
  }
  return report;
}

template WellSpacedReport<2> verify_well_spaced(PointsOf<2>, PointsOf<2>, const BoxTransform<2>&, double);
template WellSpacedReport<3> verify_well_spaced(PointsOf<3>, PointsOf<3>, const BoxTransform<3>&, double);
template WellSpacedReport<2> verify_well_spaced(PointsOf<2>, PointsOf<2>, const BoxTransform<2>&, double, double);
template WellSpacedReport<3> verify_well_spaced(PointsOf<3>, PointsOf<3>, const BoxTransform<3>&, double, double);

}  // namespace shoremesh
