#pragma once
// Which mesh elements rho-well-spacing covers: a Delaunay element of a rho-well-spaced set whose
// circumcentre lies in the box has radius-edge ratio <= rho (paper, section 2). An element whose
// circumcentre lies outside, along the box's edge where no point bounds the empty circles, can be a
// sliver of any shape.
#include "shoremesh/box_transform.hpp"
#include "shoremesh/mesh_element.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

// Whether the circumcentre of the element with these corners lies in the closed box [lo, hi]; false for
// a degenerate element. Exact: an interval filter, then rationals.
template <int D>
bool circumcentre_in_box(const ElementCorners<D>& corners, const Point<D>& lo, const Point<D>& hi);

// The same for the engine's box [origin, origin + side] (the upper corner rounded once, as everywhere).
template <int D>
bool circumcentre_in_box(const ElementCorners<D>& corners, const BoxTransform<D>& box);

}  // namespace shoremesh
