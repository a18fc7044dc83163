// A land-and-water TIN (TerrainOptions::domain) follows patches of its grid that also move its rings and
// lines (TerrainSession::patch with a domain): after every patch it equals a fresh session on the patched
// grid with the new rings, point for point, height for height, triangle for triangle (Lemma 7.2 extended
// to the DEM and the rings, docs/terrain.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>
#include <iterator>
#include <limits>

#include "shoremesh/error.hpp"
#include "shoremesh/terrain.hpp"
#include "terrain_test_util.hpp"

namespace shoremesh {
namespace {

using terrain_test::at;
using terrain_test::valley;

// The rings of terrain_domain_test.cpp, with one outer vertex and the open line's middle vertex moved by
// (du, dv) cells, and the island present or not (a ring that goes and comes, first in the list: every
// other ring changes its place, a line's place taken by a closed ring, as a new tracing can do).
Domain2 rings(const HeightGrid& g, double du, double dv, bool island) {
  Domain2 d;
  if (island) d.rings.push_back({{at(g, 30, 30), at(g, 36, 31), at(g, 34, 37)}, RingRole::Island});
  d.rings.push_back(
      {{at(g, 5, 3), at(g, 40, 2.5), at(g, 55 + du, 20 + dv), at(g, 50, 46), at(g, 12, 47), at(g, 2.5, 25)}, RingRole::Shore});
  d.rings.push_back({{at(g, 20.3, 8.1), at(g, 22.7 + dv, 20.4 + du), at(g, 24.1, 33.3)}, RingRole::Line});
  const std::vector<Point2> loop = {at(g, 33.2, 8.3), at(g, 39.6, 9.1), at(g, 40.9, 15.2), at(g, 34.1, 16.7)};
  d.rings.push_back({{loop[0], loop[1], loop[2]}, RingRole::Line});
  d.rings.push_back({{loop[2], loop[3], loop[0]}, RingRole::Line});
  return d;
}

void expect_equal(const TerrainSession& s, const TerrainSession& fresh, int step) {
  ASSERT_EQ(s.points(), fresh.points()) << "step " << step;
  ASSERT_EQ(s.heights(), fresh.heights()) << "step " << step;
  ASSERT_EQ(s.triangles(), fresh.triangles()) << "step " << step;
  ASSERT_EQ(s.kinds(), fresh.kinds()) << "step " << step;
  ASSERT_EQ(s.pick_count(), fresh.pick_count()) << "step " << step;
}

// The patch tests' session: the valley with its rings (the island present), the bound from 0 m up.
TerrainOptions valley_options(const HeightGrid& g, double max_error) {
  TerrainOptions o;
  o.max_error = max_error;
  o.bound_from = 0;
  o.domain = rings(g, 0, 0, true);
  return o;
}

// After the patch of `step`: the session is valid, equals a fresh session on the patched grid with
// `fresh_rings`, and meets the bound.
void expect_fresh(const TerrainSession& s, const HeightGrid& g, TerrainOptions o, const Domain2& fresh_rings, int step) {
  ASSERT_NO_THROW(s.check_valid()) << "step " << step;
  o.domain = fresh_rings;
  const TerrainSession fresh(g, o);
  expect_equal(s, fresh, step);
  EXPECT_EQ(s.error().over, 0u);
}

TEST(TerrainDomainPatch, RandomPatchesAndRingMovesEqualAFreshRun) {
  HeightGrid g = valley();
  const TerrainOptions o = valley_options(g, 1.5);
  TerrainSession s(g, o);
  std::mt19937 rng(37);
  std::uniform_int_distribution<int> size(2, 12), kind(0, 3), ring_move(-4, 4), coin(0, 1);
  for (int step = 0; step < 8; ++step) {
    const int w = size(rng), h = size(rng);
    const int col = std::uniform_int_distribution<int>(0, g.width - w)(rng);
    const int row = std::uniform_int_distribution<int>(0, g.height - h)(rng);
    std::vector<float> z(static_cast<std::size_t>(w) * h);
    const int k = kind(rng);
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c) {
        const float before = g.at(col + c, row + r);
        float& out = z[static_cast<std::size_t>(r) * w + c];
        if (k == 0) out = before - 25;                       // dredged below the shoreline
        else if (k == 1) out = before + 25;                  // raised above it (a levee)
        else if (k == 2) out = static_cast<float>(3 * std::sin(c + r));  // reshaped around 0 m
        else out = before + std::uniform_real_distribution<float>(-4, 4)(rng);  // noise
      }
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c) g.z[g.index(col + c, row + r)] = z[static_cast<std::size_t>(r) * w + c];
    const Domain2 d = rings(g, 0.5 * ring_move(rng), 0.5 * ring_move(rng), coin(rng) == 1);
    s.patch(col, row, w, h, z, {}, d);
    ASSERT_NO_FATAL_FAILURE(expect_fresh(s, g, o, d, step));
  }
}

// The rings in their places, as the tool gives them (follow_contours): the island keeps place 0, empty
// while it is gone; the session updates its refinement by the places' stretches (docs/terrain.md).
TEST(TerrainDomainPatch, RingsInTheirPlacesEqualAFreshRun) {
  HeightGrid g = valley();
  const TerrainOptions o = valley_options(g, 1.5);
  TerrainSession s(g, o);
  std::mt19937 rng(371);
  std::uniform_int_distribution<int> size(2, 10), ring_move(-4, 4), coin(0, 2);
  for (int step = 0; step < 8; ++step) {
    const int w = size(rng), h = size(rng);
    const int col = std::uniform_int_distribution<int>(0, g.width - w)(rng);
    const int row = std::uniform_int_distribution<int>(0, g.height - h)(rng);
    std::vector<float> z(static_cast<std::size_t>(w) * h);
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c) {
        const float v = g.at(col + c, row + r) + (step % 2 ? 20.0f : -20.0f);
        z[static_cast<std::size_t>(r) * w + c] = v;
        g.z[g.index(col + c, row + r)] = v;
      }
    const bool island = coin(rng) != 0;
    const Domain2 fresh_rings = rings(g, 0.5 * ring_move(rng), 0.5 * ring_move(rng), island);
    Domain2 places = fresh_rings;
    if (!island) places.rings.insert(places.rings.begin(), Ring{{}, RingRole::Island});
    s.patch(col, row, w, h, z, {}, places);
    ASSERT_NO_FATAL_FAILURE(expect_fresh(s, g, o, fresh_rings, step));
  }
}

TEST(TerrainDomainPatch, BadRingsChangeNothing) {
  const HeightGrid g = valley();
  TerrainSession s(g, valley_options(g, 2));
  const auto triangles = s.triangles();
  const std::vector<float> z(4, 100.0f);
  Domain2 crossing = rings(g, 0, 0, true);
  crossing.rings.push_back({{at(g, 20, 2), at(g, 20, 10)}, RingRole::Line});  // crosses the outer ring
  EXPECT_THROW(s.patch(10, 10, 2, 2, z, {}, crossing), InputError);
  Domain2 far = rings(g, 0, 0, true);
  far.rings[0].points[2] = at(g, 80, 20);  // 20 cells outside the grid
  EXPECT_THROW(s.patch(10, 10, 2, 2, z, {}, far), InputError);
  EXPECT_THROW(s.patch(10, 10, 2, 2, z, {}, Domain2{}), InputError);
  EXPECT_EQ(s.triangles(), triangles);
  EXPECT_EQ(s.grid().at(10, 10), g.at(10, 10));
  EXPECT_THROW(s.patch(10, 10, 2, 2, z), ParameterError);  // a domain's TIN needs its new rings
  TerrainOptions rect;
  rect.max_error = 2;
  TerrainSession r(g, rect);
  EXPECT_THROW(r.patch(10, 10, 2, 2, z, {}, rings(g, 0, 0, true)), ParameterError);
}

}  // namespace
}  // namespace shoremesh
namespace shoremesh {
namespace {

// A ring of `n` vertices around the grid's centre (radius 40 cells, a wobble), the vertices whose cell
// lies in the window [c0, c1] x [r0, r1] pushed outward by `push` cells.
Domain2 round_ring(const HeightGrid& g, int n, int c0, int r0, int c1, int r1, double push) {
  Domain2 d;
  d.rings.push_back({{}, RingRole::Shore});
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n, rad = 40 + 3 * std::sin(5 * a);
    double c = 60 + rad * std::cos(a), r = 50 + 0.9 * rad * std::sin(a);
    if (c >= c0 && c <= c1 && r >= r0 && r <= r1) c += push * std::cos(a), r += push * std::sin(a);
    d.rings[0].points.push_back(at(g, c, r));
  }
  return d;
}

// Without an error bound (the rings' mesh and the engine's grading), a patch that moves the ring inside its
// window changes only triangles within a few local triangle sizes of the window; with the bound the greedy
// rounds start from the rings' coarse triangles, and a different pick in one of them moves later picks
// anywhere in it (docs/terrain.md): that reach is not pinned.
TEST(TerrainDomainPatch, WithoutTheBoundAPatchChangesOnlyTrianglesNearItsWindow) {
  HeightGrid g = valley(120, 100);
  const int col = 96, row = 44, w = 8, h = 12;  // across the ring's right side
  TerrainOptions o;
  o.max_error = std::numeric_limits<double>::infinity();
  o.bound_from = 0;
  o.domain = round_ring(g, 160, col, row, col + w - 1, row + h - 1, 0);
  TerrainSession s(g, o);
  const auto before = sorted_corners<2>(s.points(), s.triangles());
  std::vector<float> z;
  for (int r = row; r < row + h; ++r)
    for (int c = col; c < col + w; ++c) z.push_back(g.at(c, r) - 20);
  const Domain2 moved = round_ring(g, 160, col, row, col + w - 1, row + h - 1, 1.5);
  s.patch(col, row, w, h, z, {}, moved);
  ASSERT_NO_THROW(s.check_valid());
  const auto after = sorted_corners<2>(s.points(), s.triangles());
  std::vector<ElementCorners<2>> changed;
  std::set_symmetric_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(changed));
  ASSERT_FALSE(changed.empty());
  // The reach of a well-spaced mesh's change is relative to the size there (a coarse triangle in the
  // interior, its size set by distances to the ring, follows ring points far away): every changed triangle
  // lies within five of its own longest edges of the window.
  auto outside = [&](const Point2& p) {  // cells from the window
    const Point2 q = g.to_grid(p);
    return std::max({col - q[0], q[0] - (col + w - 1), row - q[1], q[1] - (row + h - 1), 0.0});
  };
  double worst = 0, far = 0;
  for (const auto& t : changed) {
    double edge = 0;
    for (int k = 0; k < 3; ++k) {
      const Point2 a = g.to_grid(t[k]), b = g.to_grid(t[(k + 1) % 3]);
      edge = std::max(edge, std::hypot(a[0] - b[0], a[1] - b[1]));
    }
    const double d = std::min({outside(t[0]), outside(t[1]), outside(t[2])});
    worst = std::max(worst, d / edge), far = std::max(far, d);
  }
  // Measured: 184 of 460 triangles, the farthest 47 cells away and 3.9 of its own edges.
  EXPECT_LE(worst, 5.0) << changed.size() << " of " << after.size() << " triangles changed, up to " << far << " cells away";
  EXPECT_LT(changed.size(), after.size() / 2);
}

}  // namespace
}  // namespace shoremesh
