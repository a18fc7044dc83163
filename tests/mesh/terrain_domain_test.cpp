// A terrain TIN inside rings with constraint lines (TerrainOptions::domain, the land-and-water mesh of
// `mesh --dem --land-up-to`): the updated mesh equals a fresh one after the greedy rounds and the halving of
// encroached constrained edges (check_valid), the error bound holds at the samples at or above bound_from
// (measured here) and not below it, every line segment is a chain of TIN edges, the angle bound holds, two
// runs agree, and what the domain cannot take is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <numbers>
#include <vector>

#include "shoremesh/error.hpp"
#include "shoremesh/terrain.hpp"
#include "terrain_test_util.hpp"

namespace shoremesh {
namespace {

using terrain_test::at;
using terrain_test::valley;

// An outer ring (a hexagon), an island ring, an open line and a closed line as two halves sharing ends.
Domain2 domain_of(const HeightGrid& g) {
  Domain2 d;
  d.rings.push_back({{at(g, 5, 3), at(g, 40, 2.5), at(g, 55, 20), at(g, 50, 46), at(g, 12, 47), at(g, 2.5, 25)}, RingRole::Shore});
  d.rings.push_back({{at(g, 30, 30), at(g, 36, 31), at(g, 34, 37)}, RingRole::Island});
  d.rings.push_back({{at(g, 20.3, 8.1), at(g, 22.7, 20.4), at(g, 24.1, 33.3)}, RingRole::Line});
  const std::vector<Point2> loop = {at(g, 33.2, 8.3), at(g, 39.6, 9.1), at(g, 40.9, 15.2), at(g, 34.1, 16.7)};
  d.rings.push_back({{loop[0], loop[1], loop[2]}, RingRole::Line});
  d.rings.push_back({{loop[2], loop[3], loop[0]}, RingRole::Line});
  return d;
}

TerrainOptions options_for(const HeightGrid& g, double e) {
  TerrainOptions o;
  o.max_error = e;
  o.domain = domain_of(g);
  o.bound_from = 0;
  return o;
}

double orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

TEST(TerrainDomain, UpdatedMeshEqualsAFreshOneAndTheBoundHoldsOnLandOnly) {
  const HeightGrid g = valley();
  const TerrainSession s(g, options_for(g, 1.0));
  EXPECT_NO_THROW(s.check_valid());
  EXPECT_GT(s.pick_count(), 10u);
  // Every sample in a triangle, measured here: those at or above 0 m within 1 m, and some below 0 m
  // farther (the water is not refined).
  double land = 0, water = 0;
  std::size_t measured = 0;
  const auto& p = s.points();
  const auto& z = s.heights();
  for (const auto& t : s.triangles()) {
    const double d = orient(p[t[0]], p[t[1]], p[t[2]]);
    ASSERT_GT(d, 0);
    for (int r = 0; r < g.height; ++r)
      for (int c = 0; c < g.width; ++c) {
        const Point2 q = g.position(c, r);
        const double l0 = orient(q, p[t[1]], p[t[2]]) / d, l1 = orient(p[t[0]], q, p[t[2]]) / d, l2 = orient(p[t[0]], p[t[1]], q) / d;
        if (l0 < -1e-12 || l1 < -1e-12 || l2 < -1e-12) continue;
        const double e = std::abs(l0 * z[t[0]] + l1 * z[t[1]] + l2 * z[t[2]] - g.at(c, r));
        (g.at(c, r) >= 0 ? land : water) = std::max(g.at(c, r) >= 0 ? land : water, e);
        ++measured;
      }
  }
  EXPECT_GT(measured, 1000u);
  EXPECT_LE(land, 1.0 + 1e-9);
  EXPECT_GT(water, 1.0);
  const TerrainError e = s.error();
  EXPECT_LE(e.max, 1.0);
  EXPECT_EQ(e.over, 0u);
  EXPECT_NEAR(e.max, land, 1e-6);
}

TEST(TerrainDomain, EveryLineSegmentIsAChainOfTinEdges) {
  const HeightGrid g = valley();
  const TerrainSession s(g, options_for(g, 1.0));
  const auto& p = s.points();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& t : s.triangles())
    for (int k = 0; k < 3; ++k) edges.push_back(std::minmax(t[k], t[(k + 1) % 3]));
  for (const Ring& ring : s.options().domain.rings)
    for (std::size_t k = 0; k < ring.segment_count(); ++k) {
      const Point2 a = ring.points[k], b = ring.points[(k + 1) % ring.points.size()];
      const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
      // Edges whose ends both lie on ab (to rounding): their parameters along ab must tile [0, 1].
      std::vector<std::pair<double, double>> cover;
      auto param = [&](const Point2& q, double& t) {
        const double off = std::abs(orient(a, b, q)) / len;
        t = ((q[0] - a[0]) * (b[0] - a[0]) + (q[1] - a[1]) * (b[1] - a[1])) / (len * len);
        return off < 1e-6 * len && t > -1e-9 && t < 1 + 1e-9;
      };
      for (const auto& [u, v] : edges) {
        double tu, tv;
        if (param(p[u], tu) && param(p[v], tv)) cover.push_back(std::minmax(tu, tv));
      }
      std::sort(cover.begin(), cover.end());
      double reach = 0;
      for (const auto& [lo, hi] : cover)
        if (lo <= reach + 1e-9) reach = std::max(reach, hi);
      EXPECT_GE(reach, 1 - 1e-9) << "segment " << k << " of a ring or line is covered up to " << reach;
    }
}

TEST(TerrainDomain, AngleBoundAndDeterminism) {
  const HeightGrid g = valley();
  const TerrainSession a(g, options_for(g, 0.5)), b(g, options_for(g, 0.5));
  EXPECT_EQ(a.points(), b.points());
  EXPECT_EQ(a.triangles(), b.triangles());
  EXPECT_EQ(a.heights(), b.heights());
  // The angle bound on every triangle: the rounds also halve ring subsegments that a Steiner point outside
  // the domain encroaches (docs/terrain.md: 18.77 degrees here before, in the engine box of the rings).
  EXPECT_GE(angle_range(a.points(), a.triangles())[0], 20.7);
  // Without a bound: the rings and lines alone (no picks), still a valid, updated mesh.
  TerrainOptions none = options_for(g, std::numeric_limits<double>::infinity());
  const TerrainSession c(g, none);
  EXPECT_EQ(c.pick_count(), 0u);
  EXPECT_NO_THROW(c.check_valid());
  EXPECT_LT(c.triangles().size(), a.triangles().size());
}

TEST(TerrainDomain, WhatTheDomainCannotTakeIsRefused) {
  const HeightGrid g = valley();
  TerrainOptions o = options_for(g, 1.0);
  o.seed_fraction = 0.5;
  EXPECT_THROW(TerrainSession(g, o), ParameterError);
  o = options_for(g, 1.0);
  o.domain.rings.push_back({{at(g, 20, 2), at(g, 20, 10)}, RingRole::Line});  // crosses the outer ring
  EXPECT_THROW(TerrainSession(g, o), InputError);
  o = options_for(g, 1.0);
  o.bound_from = std::nan("");
  EXPECT_THROW(TerrainSession(g, o), ParameterError);
  TerrainOptions rectangle;
  rectangle.max_error = std::numeric_limits<double>::infinity();
  EXPECT_THROW(TerrainSession(g, rectangle), ParameterError);  // only a domain takes no bound
  TerrainSession s(g, options_for(g, 1.0));
  const std::vector<float> patch(4, 1.0f);
  EXPECT_THROW(s.patch(0, 0, 2, 2, patch), ParameterError);
}

}  // namespace
}  // namespace shoremesh
