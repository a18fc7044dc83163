// A 2D one-shot build reads its cells' neighbours from a Delaunay triangulation of M_t, or searches the
// quadtree for them (engine::set_delaunay_neighbours). The output must be the same bit for bit, whatever
// the family (co-circular grids too, where which points are Delaunay neighbours depends on the
// triangulation), the thread count and the water.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/engine/delaunay_neighbours.hpp"
#include "shoremesh/engine/engine.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

struct OneShot {
  std::vector<Point2> points;  // inputs by id, then the Steiner points sorted
  std::uint64_t operations = 0, steiner = 0, delaunay_cells = 0, delaunay_fallbacks = 0, on_land = 0;
};

OneShot one_shot(const std::vector<Point2>& input, bool delaunay, unsigned threads, const Domain2* water = nullptr,
                 const BoxTransform<2>& box = {{0, 0}, 1}) {
  const bool before = engine::delaunay_neighbours();
  engine::set_delaunay_neighbours(delaunay);
  engine::set_thread_count(threads);
  WaterSource source;
  if (water) source = [water] { return water; };
  const DynamicWellSpaced<2> set(input, {}, box, BuildFor::OutputOnly, source);
  engine::set_thread_count(0);
  engine::set_delaunay_neighbours(before);
  const Counters& c = set.set().counters();
  return {set.points(), c.operations(), c.steiner_points, c.delaunay_cells, c.delaunay_fallbacks, c.fills_on_land};
}

void identical_to_tree_search(const std::vector<Point2>& input, const Domain2* water = nullptr,
                              const BoxTransform<2>& box = {{0, 0}, 1}) {
  const OneShot tree = one_shot(input, false, 1, water, box);
  ASSERT_GT(tree.steiner, 0u);
  EXPECT_EQ(tree.delaunay_cells, 0u);
  if (water) {
    EXPECT_NE(tree.steiner, one_shot(input, false, 1, nullptr, box).steiner);  // the water changes what is made
  }
  for (unsigned threads : {1u, 2u, 8u}) {
    const OneShot del = one_shot(input, true, threads, water, box);
    // The triangulation answered for most cells: the comparison compares something.
    EXPECT_GT(del.delaunay_cells, del.delaunay_fallbacks) << threads << " threads";
    EXPECT_EQ(del.operations, tree.operations) << threads << " threads";
    EXPECT_EQ(del.steiner, tree.steiner) << threads << " threads";
    EXPECT_EQ(del.on_land, tree.on_land) << threads << " threads";
    ASSERT_EQ(del.points.size(), tree.points.size()) << threads << " threads";
    std::size_t differ = 0;
    for (std::size_t k = 0; k < del.points.size(); ++k) differ += del.points[k] != tree.points[k];
    EXPECT_EQ(differ, 0u) << threads << " threads";
  }
}

TEST(DelaunayNeighbours, OneShotOutputIdenticalToTreeSearchUniform) {
  identical_to_tree_search(families::uniform<2>(4000, 21));
}

TEST(DelaunayNeighbours, OneShotOutputIdenticalToTreeSearchClusters) {
  identical_to_tree_search(families::gaussian_clusters<2>(3000, 5, 22));
}

TEST(DelaunayNeighbours, OneShotOutputIdenticalToTreeSearchGrid) {
  // Co-circular neighbourhoods everywhere (the triangulation's answer refused), loose points among them
  // making Steiner vertices, and a finer grid in one corner.
  auto input = families::grid<2>(30);
  for (const Point2& p : families::uniform<2>(60, 23)) input.push_back({0.01 + 0.98 * p[0], 0.013 + 0.97 * p[1]});
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) input.push_back({0.8 + 0.01 * i + 0.005, 0.8 + 0.01 * j + 0.005});
  identical_to_tree_search(input);
}

TEST(DelaunayNeighbours, OneShotOutputIdenticalToTreeSearchWater) {
  // A wavy lake with an island: shore points as inputs, fills on land skipped (docs/water_only.md).
  constexpr double kTau = 6.283185307179586;
  Domain2 lake;
  std::vector<Point2> input;
  auto ring = [&](Point2 c, double radius, int n, double phase, RingRole role) {
    lake.rings.push_back({{}, role});
    for (int i = 0; i < n; ++i) {
      const double t = kTau * i / n;
      const double r = radius * (1 + 0.12 * std::sin(5 * t + phase));
      const Point2 p{c[0] + r * std::cos(t), c[1] + r * std::sin(t)};
      lake.rings.back().points.push_back(p);
      input.push_back(p);
    }
  };
  ring({50, 50}, 38, 400, 0.3, RingRole::Shore);
  ring({42, 46}, 6, 60, 1.0, RingRole::Island);
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> u(25, 75);
  for (int i = 0; i < 30; ++i) input.push_back({u(rng), u(rng)});
  identical_to_tree_search(input, &lake, {{-60, -60}, 220});
}

}  // namespace
}  // namespace shoremesh
