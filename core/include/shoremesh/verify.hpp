#pragma once
// The guarantee as a checker (paper, section 2), written apart from the engine: it shares no code with
// the engine's clipped-Voronoi cells. Given an output M, the input N it must contain and the box B:
//   - every v in M is rho-well-spaced: Vor_M(v) ∩ B lies in the closed ball of radius rho * NN_M(v) at v;
//   - N ⊆ M (bitwise equal coordinates), and M has no repeated point;
//   - size conformity: lfs(v) / NN_M(v) over v in M, lfs = distance to the second-nearest input point.
// 2D decides well-spacedness exactly (CGAL, exact constructions); 3D uses voro++ in floating point.
#include <cstddef>
#include <span>
#include <type_traits>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

template <int D>
struct WellSpacedReport {
  std::size_t vertex_count = 0;
  double rho = 0;                    // the bound checked
  double rho_squared = 0;            // the squared bound the 2D decision used (exact)
  // max over output vertices v of (max distance from v to a point of Vor(v) ∩ box) / NN_M(v), to a
  // relative 1e-12 in 2D (the decisions themselves are exact)
  double worst_ratio = 0;
  std::size_t worst_vertex = 0;      // index into output (the lowest one on ties)
  std::size_t violations = 0;        // vertices with ratio > rho (exact in 2D; 3D within a relative 1e-9)
  bool input_contained = false;      // every input point is in the output (bitwise equal coordinates)
  std::size_t missing_input = 0;
  // max over v of lfs(v) / NN_M(v); 0 when the input has fewer than two distinct points (lfs = infinity).
  double worst_size_conformity = 0;
  std::size_t worst_size_vertex = 0; // index into output (the lowest one on ties)
  // Output points equal to an earlier output point. The cells are checked on the distinct points only
  // (a repeated point has NN = 0, which would make every ratio of its cell meaningless).
  std::size_t duplicate_points = 0;
  // Output points outside the closed box: a broken output. They still take part in the Voronoi diagram
  // (they cut their neighbours' cells), but their own cells are not rated.
  std::size_t outside_box = 0;

  bool ok() const { return violations == 0 && input_contained && duplicate_points == 0 && outside_box == 0; }
};

// The dimension is deduced from the box alone, so that vectors convert to spans without naming D.
template <int D>
using PointsOf = std::type_identity_t<std::span<const Point<D>>>;

// The squared bound used for an exact check: 2 exactly for the default rho = sqrt(2) (the value the
// engine uses), otherwise rho * rho rounded to double.
double canonical_rho_squared(double rho);

// Checks `output` (user coordinates) against `input` in the closed box box.origin .. box.origin + box.side
// (the upper corner as the double sum). Throws InputError for a non-finite point, ParameterError for a
// non-positive or non-finite rho or box side.
template <int D>
WellSpacedReport<D> verify_well_spaced(PointsOf<D> output, PointsOf<D> input, const BoxTransform<D>& box, double rho);

// The same with an explicit squared bound: 2D decides |c - v|^2 <= rho_squared * NN^2 exactly for every
// vertex c of every cell; `rho` is reported and used by the 3D floating-point check.
template <int D>
WellSpacedReport<D> verify_well_spaced(PointsOf<D> output, PointsOf<D> input, const BoxTransform<D>& box, double rho,
                                       double rho_squared);

}  // namespace shoremesh
