// Work only where the water is (docs/water_only.md), on Lake Superior's GSHHG rings: fills on land are
// skipped, no corner of a water triangle is a vertex whose fill was skipped, and the water mesh keeps its
// quality (below the bound only where the shore hides a point from the element: not Delaunay).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "mesh_test_util.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/engine/engine.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/mesh_quality.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/well_spaced.hpp"

using namespace shoremesh;

namespace {

struct SkipRun {
  std::vector<Point2> points;
  std::size_t input_count = 0;
  std::size_t skipped_fills = 0;
  std::set<Point2> skipped;  // vertices with a fill skipped on land, in the user's coordinates
};

SkipRun skip_run(const Domain2& rings, std::span<const Point2> input, bool water_only) {
  WaterSource source;
  if (water_only) source = [&rings] { return &rings; };
  const DynamicWellSpaced<2> set(input, {}, std::nullopt, BuildFor::Updates, source);
  SkipRun r;
  r.points = set.points();
  r.input_count = set.input_count();
  const auto& engine = set.set().engine();
  r.skipped_fills = engine.counters().fills_on_land;
  for (const auto v : engine.vertices_skipped_on_land()) r.skipped.insert(set.box().to_user(engine.positions()[v]));
  return r;
}

using mesh_test::below_bound_all_hidden;

}  // namespace

TEST(WaterOnlyMesh, SuperiorSkipsFillsOnLandAndNoWaterCornerWasSkipped) {
  const Domain2 rings = mesh_test::superior();
  const ShoreRefinement refinement(rings);
  std::vector<Point2> input = mesh_test::session_input(rings).points;
  for (const Point2& p : refinement.split_points()) input.push_back(p);
  const Domain2 refined = refinement.refined();

  const SkipRun water = skip_run(rings, input, true), everywhere = skip_run(rings, input, false);
  EXPECT_GT(water.skipped_fills, 0u);
  EXPECT_GT(water.skipped.size(), 0u);
  EXPECT_EQ(everywhere.skipped_fills, 0u);
  EXPECT_LT(water.points.size(), everywhere.points.size());

  const Mesh<2> mesh(water.points, water.input_count, refined);
  mesh.check_valid();
  EXPECT_TRUE(mesh.shoreline_crossings().ok());
  std::size_t corners = 0, skipped_corners = 0;
  for (const auto& e : mesh.elements())
    for (const auto i : e) {
      ++corners;
      skipped_corners += water.skipped.count(mesh.points()[i]);
    }
  EXPECT_GT(corners, 0u);
  EXPECT_EQ(skipped_corners, 0u);

  const Mesh<2> full(everywhere.points, everywhere.input_count, refined);
  const std::size_t below = below_bound_all_hidden(mesh), below_full = below_bound_all_hidden(full);
  RecordProperty("points (water only / everywhere)",
                 std::to_string(water.points.size()) + " / " + std::to_string(everywhere.points.size()));
  RecordProperty("fills skipped", std::to_string(water.skipped_fills));
  RecordProperty("vertices skipped", std::to_string(water.skipped.size()));
  RecordProperty("elements (water only / everywhere)",
                 std::to_string(mesh.element_count()) + " / " + std::to_string(full.element_count()));
  RecordProperty("below the bound (water only / everywhere)", std::to_string(below) + " / " + std::to_string(below_full));
  std::printf("Superior: %zu points water-only, %zu everywhere; %zu fills skipped on %zu vertices; elements %zu / %zu; "
              "below the bound %zu / %zu\n",
              water.points.size(), everywhere.points.size(), water.skipped_fills, water.skipped.size(),
              mesh.element_count(), full.element_count(), below, below_full);
}
