#pragma once
// Points of the engine: plain coordinate arrays in dimension D (2 or 3).
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace shoremesh {

template <int D>
using Point = std::array<double, D>;

using Point2 = Point<2>;
using Point3 = Point<3>;

// A hash of a point's exact coordinates, for maps keyed by points (-0 and +0 are the same point).
template <int D>
struct PointHash {
  std::size_t operator()(const Point<D>& p) const {
    std::size_t h = 0;
    for (double x : p) h = h * 0x9E3779B97F4A7C15ull + std::hash<std::uint64_t>{}(std::bit_cast<std::uint64_t>(x + 0.0));
    return h;
  }
};

}  // namespace shoremesh
