#pragma once
// Element quality of a mesh, compared with what rho-well-spacedness guarantees: the Delaunay elements of
// a rho-well-spaced set whose circumcentre lies in the box have radius-edge ratio <= rho (the circumcentre
// is a Voronoi vertex of every corner, so R <= rho * NN <= rho * shortest edge), hence in 2D a minimum
// angle >= arcsin(1 / (2 rho)) (20.7 degrees for rho = sqrt 2). Elements whose circumcentre falls outside
// the box (along the box boundary) are not covered, and neither is anything the clipping to a domain did.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/mesh_element.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

// Measures of one element (numerical constructions, not decisions).
template <int D>
struct ElementShape {
  double radius_edge = 0;  // circumradius / shortest edge (infinite for a flat element)
  double min_angle = 0;    // degrees: triangle angles in 2D, dihedral angles in 3D
  double max_angle = 0;
  Point<D> circumcentre{};
  Point<D> centroid{};
};

template <int D>
ElementShape<D> element_shape(const ElementCorners<D>& corners);
// element_shape(corners).radius_edge alone (no angles), the same number.
template <int D>
double radius_edge(const ElementCorners<D>& corners);

struct Histogram {
  double low = 0, high = 0;          // bins of equal width over [low, high); the last bin takes values >= high
  std::vector<std::size_t> counts;
  double bin_width() const { return counts.empty() ? 0 : (high - low) / static_cast<double>(counts.size()); }
};

template <int D>
struct WorstElement {
  std::size_t element = 0;  // index into the element list the report was made from
  ElementShape<D> shape;
  bool covered = false;     // circumcentre in the box: the rho bound applies to this element
};

template <int D>
struct QualityReport {
  std::size_t elements = 0;
  double min_angle = 0, max_angle = 0;  // degrees, over all elements (2D: angles, 3D: dihedral angles)
  double min_radius_edge = 0, max_radius_edge = 0;
  double rho = 0;
  double min_angle_bound = 0;           // 2D: arcsin(1 / (2 rho)) in degrees; 3D: 0 (no dihedral guarantee)
  std::size_t covered = 0;              // elements whose circumcentre is in the box: the bound applies
  std::size_t covered_meeting_bound = 0;
  std::size_t meeting_bound = 0;        // over all elements, covered or not
  double covered_max_radius_edge = 0;   // the worst radius-edge ratio among the covered elements
  Histogram min_angle_histogram;        // per element minimum angle, 5 degree bins
  Histogram radius_edge_histogram;      // per element radius-edge ratio, bins of 0.1 over [0.5, 3)
  std::vector<WorstElement<D>> worst;   // the worst elements by radius-edge ratio, worst first

  double covered_fraction_meeting_bound() const {
    return covered == 0 ? 1.0 : static_cast<double>(covered_meeting_bound) / static_cast<double>(covered);
  }
  std::string summary() const;  // a few lines for a person
};

// The report for `elements` (indices into `points`). `box` as in Mesh::quality.
template <int D>
QualityReport<D> quality_report(std::span<const Point<D>> points, std::span<const Element<D>> elements, double rho,
                                std::optional<BoxTransform<D>> box = {}, std::size_t worst_count = 10);

// Where triangles may fall below the bound (docs/conforming.md, "Where the bound may fail"): two input
// segments (ring or line edges, as given to the shore's splits) that meet at a vertex at less than 60
// degrees, whichever side of them the water is. Inside the shorter of the two the splits ignore the other
// (halving there would never end), so a triangle there may be skinny; its reach is that length.
struct SharpCorner {
  Point2 apex, a, b;  // the segments apex-a and apex-b
  double angle = 0;   // degrees, between them
  double reach = 0;   // min(|apex a|, |apex b|)
};

// Every pair of input segments through a vertex that meet at less than 60 degrees (exact test), sorted.
std::vector<SharpCorner> sharp_corners(const Domain2& rings);

// The first of `corners` (sorted as sharp_corners gives them) whose apex is nearer than its reach to the
// triangle's centroid; none when the triangle is not at a sharp corner.
std::optional<std::size_t> sharp_corner_at(const ElementCorners<2>& triangle, std::span<const SharpCorner> corners);

}  // namespace shoremesh
