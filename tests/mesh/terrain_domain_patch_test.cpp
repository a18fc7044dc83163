// A land-and-water TIN (TerrainOptions::domain) follows patches of its grid that also move its rings and
// lines (TerrainSession::patch with a domain): after every patch it equals a fresh session on the patched
// grid with the new rings, point for point, height for height, triangle for triangle (Lemma 7.2 extended
// to the DEM and the rings, docs/terrain.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "shoremesh/error.hpp"
#include "shoremesh/terrain.hpp"

namespace shoremesh {
namespace {

HeightGrid valley(int w = 60, int h = 50) {
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

Point2 at(const HeightGrid& g, double c, double r) { return {g.x0 + c * g.dx, g.y0 + r * g.dy}; }

// The rings of terrain_domain_test.cpp, with one outer vertex and the open line's middle vertex moved by
// (du, dv) cells, and the island present or not (a ring that goes and comes).
Domain2 rings(const HeightGrid& g, double du, double dv, bool island) {
  Domain2 d;
  d.rings.push_back(
      {{at(g, 5, 3), at(g, 40, 2.5), at(g, 55 + du, 20 + dv), at(g, 50, 46), at(g, 12, 47), at(g, 2.5, 25)}, RingRole::Shore});
  d.rings.push_back({{at(g, 20.3, 8.1), at(g, 22.7 + dv, 20.4 + du), at(g, 24.1, 33.3)}, RingRole::Line});
  const std::vector<Point2> loop = {at(g, 33.2, 8.3), at(g, 39.6, 9.1), at(g, 40.9, 15.2), at(g, 34.1, 16.7)};
  d.rings.push_back({{loop[0], loop[1], loop[2]}, RingRole::Line});
  d.rings.push_back({{loop[2], loop[3], loop[0]}, RingRole::Line});
  if (island) d.rings.push_back({{at(g, 30, 30), at(g, 36, 31), at(g, 34, 37)}, RingRole::Island});
  return d;
}

void expect_equal(const TerrainSession& s, const TerrainSession& fresh, int step) {
  ASSERT_EQ(s.points(), fresh.points()) << "step " << step;
  ASSERT_EQ(s.heights(), fresh.heights()) << "step " << step;
  ASSERT_EQ(s.triangles(), fresh.triangles()) << "step " << step;
  ASSERT_EQ(s.kinds(), fresh.kinds()) << "step " << step;
  ASSERT_EQ(s.pick_count(), fresh.pick_count()) << "step " << step;
}

TEST(TerrainDomainPatch, RandomPatchesAndRingMovesEqualAFreshRun) {
  HeightGrid g = valley();
  TerrainOptions o;
  o.max_error = 1.5;
  o.bound_from = 0;
  o.domain = rings(g, 0, 0, true);
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
    ASSERT_NO_THROW(s.check_valid()) << "step " << step;
    TerrainOptions fo = o;
    fo.domain = d;
    const TerrainSession fresh(g, fo);
    expect_equal(s, fresh, step);
    EXPECT_EQ(s.error().over, 0u);
  }
}

TEST(TerrainDomainPatch, BadRingsChangeNothing) {
  const HeightGrid g = valley();
  TerrainOptions o;
  o.max_error = 2;
  o.bound_from = 0;
  o.domain = rings(g, 0, 0, true);
  TerrainSession s(g, o);
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
