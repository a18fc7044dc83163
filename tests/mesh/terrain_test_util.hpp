#pragma once
// The synthetic DEMs of the land-and-water tests (terrain_domain_test.cpp, terrain_domain_patch_test.cpp,
// land_water_contour_test.cpp, and the CLI's land_water_test.cpp).
#include <cmath>
#include <vector>

#include "shoremesh/point.hpp"
#include "shoremesh/terrain.hpp"

namespace shoremesh::terrain_test {

// A sloping valley floor below 0 m on the left rising to hills on the right, with bumps.
inline HeightGrid valley(int w = 60, int h = 50) {
  HeightGrid g;
  g.width = w, g.height = h;
  g.x0 = 500000, g.y0 = 5400000, g.dx = 30, g.dy = -30;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double x = double(c) / w, y = double(r) / h;
      g.z.push_back(static_cast<float>(-30 + 80 * x + 12 * std::sin(9 * x) * std::cos(7 * y) + 5 * std::sin(23 * y)));
    }
  return g;
}

// A coast, row by row: water on the left, a beach, hills on the right, bumps.
inline std::vector<float> coast(int w, int h) {
  std::vector<float> z;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double x = double(c) / w, y = double(r) / h;
      z.push_back(static_cast<float>(-20 + 60 * x + 8 * std::sin(9 * x) * std::cos(7 * y) + 4 * std::sin(17 * y)));
    }
  return z;
}

// The plane position of (column c, row r) in cells.
inline Point2 at(const HeightGrid& g, double c, double r) { return {g.x0 + c * g.dx, g.y0 + r * g.dy}; }

}  // namespace shoremesh::terrain_test
