#pragma once
// Land and water in one mesh (`shoremesh mesh --dem FILE --land-up-to Z`, docs/terrain.md, "Land and water
// in one mesh"): the shoreline's contour pieces as constraint lines inside the domain below Z.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/mesh_element.hpp"

namespace shoremesh {

struct ShoreLines {
  std::vector<Ring> lines;
  std::size_t segments = 0, dropped_segments = 0;
};

// The pieces of `shore`'s rings clear of `domain`'s rings: a vertex at least `clearance` from every ring
// segment, a segment at least half of it; where the land between them is narrower, the domain's ring is the
// shoreline there and the piece is left out (the domain's check then decides exactly that no line touches a
// ring). A closed piece becomes two lines sharing their ends.
ShoreLines shoreline_lines(const Domain2& shore, const Domain2& domain, double clearance);

struct LandWaterCounts {
  std::size_t water_triangles = 0, shoreline_edges = 0;
};

// Triangles whose centroid lies in `shore`'s water (even-odd; all or none by the flags), and mesh edges with
// both ends within `tol` of one segment of `lines`.
LandWaterCounts land_water_counts(const std::vector<Point2>& points,
                                  const std::vector<Element<2>>& triangles, const Domain2& shore,
                                  bool all_below, bool none_below, const std::vector<Ring>& lines, double tol);

}  // namespace shoremesh
