#include "shoremesh/mesh_coverage.hpp"

#include "shoremesh/engine/predicates.hpp"

namespace shoremesh {

template <int D>
bool circumcentre_in_box(const ElementCorners<D>& corners, const Point<D>& lo, const Point<D>& hi) {
  const engine::RoundingGuard upwards;  // the interval filter needs it
  engine::PredicateCounters counters;
  for (int axis = 0; axis < D; ++axis) {
    const int below = engine::circumcentre_side<D>(counters, corners, axis, lo[axis]);
    if (below == engine::kUndecided || below < 0) return false;  // degenerate, or below the box
    if (engine::circumcentre_side<D>(counters, corners, axis, hi[axis]) > 0) return false;
  }
  return true;
}

template <int D>
bool circumcentre_in_box(const ElementCorners<D>& corners, const BoxTransform<D>& box) {
  Point<D> hi = box.origin;
  for (double& x : hi) x += box.side;
  return circumcentre_in_box<D>(corners, box.origin, hi);
}

template bool circumcentre_in_box<2>(const ElementCorners<2>&, const Point2&, const Point2&);
template bool circumcentre_in_box<3>(const ElementCorners<3>&, const Point3&, const Point3&);
template bool circumcentre_in_box<2>(const ElementCorners<2>&, const BoxTransform<2>&);
template bool circumcentre_in_box<3>(const ElementCorners<3>&, const BoxTransform<3>&);

}  // namespace shoremesh
