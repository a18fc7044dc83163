// Local contours (core/src/land_water.cpp, docs/terrain.md "Local contours"): rings through the cell
// edges' midpoints, anchored to the cells, followed across height changes as stretches of rings in
// their places. After every random patch the followed rings are a fresh tracing's (Lemma 7.2's check for
// the rings), the vertices that moved lie next to the patch, and the shore refinement updated by the
// stretches equals a fresh one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/io/dem.hpp"
#include "shoremesh/land_water.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "terrain_test_util.hpp"

namespace shoremesh {
namespace {

using terrain_test::coast;

HeightGrid grid_of(int w, int h, std::vector<float> z) {
  HeightGrid g;
  g.width = w, g.height = h;
  g.x0 = 1000, g.y0 = 5000, g.dx = 30, g.dy = -30;
  g.z = std::move(z);
  return g;
}

// Each ring as a cyclic sequence from its smallest vertex (lines as they are), the rings sorted.
std::vector<std::pair<int, std::vector<Point2>>> canonical(const Domain2& d) {
  std::vector<std::pair<int, std::vector<Point2>>> out;
  for (const Ring& r : d.rings) {
    if (r.points.empty()) continue;
    std::vector<Point2> p = r.points;
    if (r.closed()) std::rotate(p.begin(), std::min_element(p.begin(), p.end()), p.end());
    out.push_back({static_cast<int>(r.role), p});
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(LocalContours, OneCellTwoDiagonalCellsAndAnIslandInALake) {
  // One water cell: a diamond through its four edge midpoints.
  {
    std::vector<float> z(25, 5.0f);
    z[2 * 5 + 2] = -1;
    const TracedContours t = trace_contours(grid_of(5, 5, z), {});
    ASSERT_EQ(t.rings.size(), 1u);
    EXPECT_EQ(t.rings[0].ring.role, RingRole::Shore);
    EXPECT_EQ(t.rings[0].ring.points.size(), 4u);
    EXPECT_EQ(t.rings[0].area, 1.0);
  }
  // Two water cells meeting at a corner: water is 4-connected, so two rings, apart (no shared vertex).
  {
    std::vector<float> z(25, 5.0f);
    z[1 * 5 + 1] = -1, z[2 * 5 + 2] = -1;
    const TracedContours t = trace_contours(grid_of(5, 5, z), {});
    ASSERT_EQ(t.rings.size(), 2u);
    EXPECT_FALSE(find_ring_defect(t.domain(), false).has_value());
  }
  // A lake with an island: a shore ring and an island ring inside it; --min-area drops the island.
  {
    const int w = 9;
    std::vector<float> z(81, 5.0f);
    for (int r = 1; r < 8; ++r)
      for (int c = 1; c < 8; ++c) z[r * w + c] = -1;
    z[4 * w + 4] = 3;
    const TracedContours t = trace_contours(grid_of(9, 9, z), {});
    ASSERT_EQ(t.rings.size(), 2u);
    EXPECT_EQ(t.rings[0].ring.role, RingRole::Shore);
    EXPECT_EQ(t.rings[0].area, 49.0);
    EXPECT_EQ(t.rings[1].ring.role, RingRole::Island);
    EXPECT_EQ(t.rings[1].parent, 0);
    EXPECT_EQ(t.rings[1].depth, 1);
    ContourOptions o;
    o.min_area = 2;
    const TracedContours dropped = trace_contours(grid_of(9, 9, z), o);
    ASSERT_EQ(dropped.rings.size(), 1u);
    EXPECT_EQ(dropped.dropped_small_islands, 1u);
    // A stride of 3 keeps the turns and every third grid line's vertices: the same polygon.
    o.min_area = 0;
    o.stride = 3;
    const TracedContours thin = trace_contours(grid_of(9, 9, z), o);
    ASSERT_EQ(thin.rings.size(), 2u);
    EXPECT_LT(thin.rings[0].ring.points.size(), t.rings[0].ring.points.size());
    EXPECT_EQ(thin.rings[0].area, t.rings[0].area);
  }
}

// The domain a land-and-water run meshes: the contour at z_top and the shoreline's lines clear of it.
Domain2 land_water_domain(const HeightGrid& g, double z_top, double level, int stride) {
  ContourOptions o;
  o.stride = stride;
  o.level = z_top;
  Domain2 d = trace_contours(g, o).domain();
  o.level = level;
  const Domain2 shore = trace_contours(g, o).domain();
  const ShoreLines lines = shoreline_lines(shore, d, 0.5 * std::abs(g.dx), contour_cut(g, 8 * stride));
  d.rings.insert(d.rings.end(), lines.lines.begin(), lines.lines.end());
  return d;
}

struct PatchStats {
  std::size_t moved = 0, far = 0, stretch_points = 0;
  double farthest = 0;
};

// Random windows raised, lowered or reshaped; after each: the rings followed in their places are the
// fresh tracing's, no ring vertex that went or came lies more than two cells from the window (a line's
// vertex, 2.5 + 3 strides), and a shore refinement updated by the stretches has the rings and split
// points of a fresh one on the fresh tracing.
PatchStats random_patches(HeightGrid g, double z_top, double level, int stride, unsigned seed, int steps,
                          float swing, int max_side) {
  PatchStats stats;
  std::mt19937 rng(seed);
  Domain2 slots = land_water_domain(g, z_top, level, stride);
  ShoreRefinement refinement(slots);
  for (int k = 0; k < steps; ++k) {
    const int pw = std::uniform_int_distribution<int>(1, max_side)(rng), ph = std::uniform_int_distribution<int>(1, max_side)(rng);
    const int col = std::uniform_int_distribution<int>(0, g.width - pw)(rng);
    const int row = std::uniform_int_distribution<int>(0, g.height - ph)(rng);
    const int kind = std::uniform_int_distribution<int>(0, 2)(rng);
    for (int r = row; r < row + ph; ++r)
      for (int c = col; c < col + pw; ++c) {
        float& v = g.z[g.index(c, r)];
        v = kind == 0 ? v - swing : kind == 1 ? v + swing : static_cast<float>(0.5 * swing * std::sin(0.7 * (c + 2 * r)));
      }
    const Domain2 fresh = land_water_domain(g, z_top, level, stride);
    const ContourFollow f = follow_contours(slots, fresh);
    EXPECT_EQ(canonical(f.next), canonical(fresh)) << "patch " << k;
    auto distance = [&](const Point2& p) {  // cells from the window (Chebyshev)
      const Point2 q = g.to_grid(p);
      return std::max({0.0, col - 0.5 - q[0], q[0] - (col + pw - 0.5), row - 0.5 - q[1], q[1] - (row + ph - 0.5)});
    };
    // A closed ring's vertex depends on the cells within two of it. A line's vertices are the shoreline's
    // (as close) and the points where it stops short of the contour at Z: those depend on the segments
    // of both contours within half a cell, each up to 1.5 strides long.
    std::set<Point2> on_rings;
    for (const Domain2* d : {static_cast<const Domain2*>(&slots), &fresh})
      for (const Ring& r : d->rings)
        if (r.closed()) on_rings.insert(r.points.begin(), r.points.end());
    const double line_reach = 2.5 + 3 * stride;
    for (const Point2& p : f.moved) {
      const double bound = on_rings.count(p) ? 2.0 : line_reach;
      stats.far += distance(p) > bound;
      stats.farthest = std::max(stats.farthest, distance(p));
      EXPECT_LE(distance(p), bound) << "patch " << k << " at (" << col << ", " << row << ") " << pw << " x " << ph
                                    << (on_rings.count(p) ? ": a ring's vertex" : ": a line's vertex");
    }
    stats.moved += f.moved.size();
    // (A stretch runs from a ring's first change to its last: it holds unchanged vertices where the ring
    // passes the window twice.)
    for (const RingStretch& e : f.edits) stats.stretch_points += e.middle.size();
    refinement.update(f.edits);
    EXPECT_EQ(refinement.split_points(), ShoreRefinement(fresh).split_points()) << "patch " << k;
    EXPECT_EQ(canonical(refinement.rings()), canonical(fresh)) << "patch " << k;
    slots = f.next;
  }
  return stats;
}

TEST(LocalContours, RandomPatchesOnASyntheticCoastMoveOnlyNearbyVertices) {
  const PatchStats a = random_patches(grid_of(60, 48, coast(60, 48)), 15, 0, 1, 1, 25, 18, 4);
  const PatchStats b = random_patches(grid_of(60, 48, coast(60, 48)), 25, 5, 2, 2, 25, 18, 4);
  EXPECT_GT(a.moved + b.moved, 50u);  // the patches did move the contours
  EXPECT_EQ(a.far + b.far, 0u);
}

TEST(LocalContours, RandomPatchesOnACropOfTheSalishSeaMoveOnlyNearbyVertices) {
  const io::Dem dem = io::read_dem(std::string(SHOREMESH_SAMPLES_DIR) + "/salish/salish_sea_topobathy.tif");
  const HeightGrid full = io::dem_grid(dem).grid;
  const int c0 = 30, r0 = 20, w = 60, h = 50;
  HeightGrid g = full;
  g.width = w, g.height = h;
  g.x0 = full.x0 + c0 * full.dx, g.y0 = full.y0 + r0 * full.dy;
  g.z.clear();
  for (int r = r0; r < r0 + h; ++r)
    for (int c = c0; c < c0 + w; ++c) g.z.push_back(full.at(c, r));
  const PatchStats a = random_patches(g, 100, 0, 1, 7, 25, 60, 3);
  const PatchStats b = random_patches(g, 300, 0, 1, 8, 15, 60, 6);
  EXPECT_GT(a.moved + b.moved, 50u);
  EXPECT_EQ(a.far + b.far, 0u);
}

}  // namespace
}  // namespace shoremesh
