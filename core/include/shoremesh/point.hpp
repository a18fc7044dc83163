#pragma once
// Points of the engine: plain coordinate arrays in dimension D (2 or 3).
#include <array>
#include <cstddef>

namespace shoremesh {

template <int D>
using Point = std::array<double, D>;

using Point2 = Point<2>;
using Point3 = Point<3>;

}  // namespace shoremesh
