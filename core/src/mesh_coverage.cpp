#include "shoremesh/mesh_coverage.hpp"

#include <cmath>

#include "shoremesh/engine/predicates.hpp"

namespace shoremesh {

// The circumcentre enclosed in intervals decides unless an interval meets a side of the box (or the
// determinant's may be zero); then it is computed exactly.
template <int D>
bool circumcentre_in_box(const ElementCorners<D>& corners, const Point<D>& lo, const Point<D>& hi) {
  for (int k = 0; k < D; ++k)
    if (std::isnan(lo[k]) || std::isnan(hi[k])) return false;  // no box
  {
    const engine::RoundingGuard upwards;  // the intervals need it
    std::array<engine::Interval, D> c;
    if (engine::circumcentre<engine::Interval, D>(corners, c)) {
      bool certain = true;
      for (int k = 0; k < D; ++k) {
        if (c[k].sup() < lo[k] || c[k].inf() > hi[k]) return false;
        certain = certain && lo[k] <= c[k].inf() && c[k].sup() <= hi[k];
      }
      if (certain) return true;
    }
  }
  std::array<engine::Exact, D> c;
  if (!engine::circumcentre<engine::Exact, D>(corners, c)) return false;  // flat: no circumcentre
  // An infinite side (a half-open box) is compared as such: rationals have no infinity.
  auto below = [](const engine::Exact& x, double side) { return std::isinf(side) ? side > 0 : x < engine::Exact(side); };
  auto above = [](const engine::Exact& x, double side) { return std::isinf(side) ? side < 0 : x > engine::Exact(side); };
  for (int k = 0; k < D; ++k)
    if (below(c[k], lo[k]) || above(c[k], hi[k])) return false;
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
