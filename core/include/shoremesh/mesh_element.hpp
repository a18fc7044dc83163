#pragma once
// How a mesh names its elements: by point indices (compact, for exports) or by corner coordinates (stable
// across the renumbering that a dynamic update causes).
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh {

// Indices into the mesh's points, positively oriented (counter-clockwise in 2D).
template <int D>
using Element = std::array<std::uint32_t, D + 1>;

// An element named by its corners' coordinates, sorted lexicographically.
template <int D>
using ElementCorners = std::array<Point<D>, D + 1>;

// Elements by their sorted corners, the list sorted: independent of the numbering, so two meshes (an
// updated one and a fresh run) compare equal exactly when they have the same elements.
template <int D>
std::vector<ElementCorners<D>> sorted_corners(std::span<const Point<D>> points, std::span<const Element<D>> elements) {
  std::vector<ElementCorners<D>> out;
  out.reserve(elements.size());
  for (const auto& e : elements) {
    ElementCorners<D> c;
    for (std::size_t i = 0; i < c.size(); ++i) c[i] = points[e[i]];
    std::sort(c.begin(), c.end());
    out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Input points came from the user; Steiner points were added by the engine. Previews draw them apart.
enum class PointKind : std::uint8_t { Input, Steiner };

}  // namespace shoremesh
