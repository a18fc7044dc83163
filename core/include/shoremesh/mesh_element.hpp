#pragma once
// How a mesh names its elements: by point indices (compact, for exports) or by corner coordinates (stable
// across the renumbering that a dynamic update causes).
#include <array>
#include <cstdint>

#include "shoremesh/point.hpp"

namespace shoremesh {

// Indices into the mesh's points, positively oriented (counter-clockwise in 2D).
template <int D>
using Element = std::array<std::uint32_t, D + 1>;

// An element named by its corners' coordinates, sorted lexicographically.
template <int D>
using ElementCorners = std::array<Point<D>, D + 1>;

// Input points came from the user; Steiner points were added by the engine. Previews draw them apart.
enum class PointKind : std::uint8_t { Input, Steiner };

}  // namespace shoremesh
