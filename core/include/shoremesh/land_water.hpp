#pragma once
// Land and water in one mesh (`shoremesh mesh --dem FILE --land-up-to Z`, docs/terrain.md, "Land and water
// in one mesh"): the shoreline's contour pieces as constraint lines inside the domain below Z.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/mesh_element.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/terrain.hpp"

namespace shoremesh {

// The contour of a grid at a level, local to the cells (docs/terrain.md, "Local contours"). Water is the
// samples strictly below `level`, each standing for its cell's square, 4-connected; the rest (and the
// outside of the grid) is land, 8-connected. A ring runs through the midpoints of the cell edges between
// water and land (binary marching squares: a one-cell channel stays a cell wide, a corner is cut by at
// most 0.36 cell); a midpoint is kept where the ring turns there, or where its cell edge lies on every
// `stride`-th grid line, so a segment is at most `stride` cells (~1.42 stride on a diagonal) long and
// whether a vertex exists depends only on the cells within two of it. A ring starts at its anchor, its
// lowest, leftmost midpoint (row first, in grid units), and the rings come in their anchors' order: a
// change of the heights moves only the vertices within two cells of the changed cells, and a ring keeps
// its place and its first vertex unless its own anchor's cells change.
struct ContourOptions {
  double level = 0;
  int stride = 1;                   // >= 1
  double min_area = 0;              // in cells: a ring enclosing fewer cell squares is dropped, with its insides
  bool largest_water_only = false;  // the largest region below the level (by area) and its islands alone
};

struct ContourRing {
  Ring ring;                     // in the grid's plane; Shore encloses water, Island land
  std::array<int, 2> anchor{};   // ring.points[0] as (2 row + 1, 2 col + 1) in the grid's cells (the lowest)
  int parent = -1, depth = 0;    // nesting among the kept rings (depth 0: outermost water)
  double area = 0;               // cell squares enclosed
};

struct TracedContours {
  std::vector<ContourRing> rings;  // sorted by anchor
  bool all_below = false, none_below = false;
  std::size_t dropped_small_water = 0, dropped_small_islands = 0, dropped_other_water = 0;
  Domain2 domain() const;
};

TracedContours trace_contours(const HeightGrid& grid, const ContourOptions& options);

// A session's rings following a new tracing (docs/terrain.md, "Local contours"). `slots` are the rings as
// the session holds them: a ring keeps its place and its rotation, a place emptied by a ring that went
// stays empty (no points) until a new ring takes it. Each traced ring continues the ring of `slots` that
// holds its first vertex also found there (same role; vertices are unique among a tracing's closed rings)
// and is rotated to start where that ring starts, so that it differs from it in one stretch between a
// common prefix and suffix (the whole ring when its first vertex went); a line is matched by its first
// vertex and replaced whole. `edits` are ShoreRefinement's stretches from `slots` to `next`, one per
// changed place; `moved` the vertices that went or came (in no ring or line before, or in none after).
// The places' rings, taken in any order and rotation, are the tracing's.
struct ContourFollow {
  Domain2 next;
  std::vector<RingStretch> edits;
  std::vector<Point2> moved;
};
ContourFollow follow_contours(const Domain2& slots, const Domain2& traced);
// The distinct vertices of a domain's rings and lines, sorted.
std::vector<Point2> domain_vertices(const Domain2& domain);

struct ShoreLines {
  std::vector<Ring> lines;
  std::size_t segments = 0, dropped_segments = 0;
};

// The pieces of `shore`'s rings clear of `domain`'s rings: a vertex at least `clearance` from every ring
// segment, a segment at least half of it; where the land between them is narrower, the domain's ring is the
// shoreline there and the piece is left out (the domain's check then decides exactly that no line touches a
// ring). Lines are cut at the vertices `cut` names (local contours: contour_cut), so that a change of the
// shoreline changes only the lines it meets; a closed piece with fewer than two such vertices becomes two
// lines sharing their ends (at its first vertex and half way).
ShoreLines shoreline_lines(const Domain2& shore, const Domain2& domain, double clearance,
                           const std::function<bool(const Point2&)>& cut = {});

// The vertices of trace_contours(grid, ...) where lines are cut: those on a cell edge whose column (a
// horizontal edge) or row (a vertical one) is a multiple of `every`; a function of the vertex alone.
std::function<bool(const Point2&)> contour_cut(const HeightGrid& grid, int every);

struct LandWaterCounts {
  std::size_t water_triangles = 0, shoreline_edges = 0;
};

// Triangles whose centroid lies in `shore`'s water (even-odd; all or none by the flags), and mesh edges with
// both ends within `tol` of one segment of `lines`.
LandWaterCounts land_water_counts(const std::vector<Point2>& points,
                                  const std::vector<Element<2>>& triangles, const Domain2& shore,
                                  bool all_below, bool none_below, const std::vector<Ring>& lines, double tol);

}  // namespace shoremesh
