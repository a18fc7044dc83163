#include "shoremesh/box_transform.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shoremesh {

template <int D>
BoxTransform<D> BoxTransform<D>::fit(std::span<const Point<D>> points) {
  BoxTransform box;
  if (points.empty()) return box;
  Point<D> lo = points.front(), hi = points.front();
  for (const auto& p : points)
    for (int i = 0; i < D; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  double extent = 0;
  for (int i = 0; i < D; ++i) extent = std::max(extent, hi[i] - lo[i]);
  // 5% of the side on every face keeps the input off the box faces; a lone point gets a unit box.
  box.side = extent > 0 ? extent * 1.1 : 1.0;
  for (int i = 0; i < D; ++i) box.origin[i] = 0.5 * (lo[i] + hi[i]) - 0.5 * box.side;
  return box;
}

template <int D>
bool BoxTransform<D>::contains(const Point<D>& p) const {
  for (int i = 0; i < D; ++i)
    if (!(p[i] >= origin[i] && p[i] <= origin[i] + side)) return false;
  return true;
}

template <int D>
Point<D> BoxTransform<D>::to_unit(const Point<D>& p) const {
  Point<D> u;
  for (int i = 0; i < D; ++i) u[i] = std::clamp((p[i] - origin[i]) / side, 0.0, 1.0);
  return u;
}

template <int D>
Point<D> BoxTransform<D>::to_user(const Point<D>& u) const {
  Point<D> p;
  for (int i = 0; i < D; ++i) p[i] = origin[i] + u[i] * side;
  return p;
}

template struct BoxTransform<2>;
template struct BoxTransform<3>;

}  // namespace shoremesh
