// Where a fill aims its Steiner point (Parameters::steiner_aim, docs/picking_region.md): every rule the
// parameter allows keeps the output rho-well-spaced and size-conforming (Fact 1 holds for any point of the
// picking region), updates equal fresh runs under each, and the 2D default needs fewer points than aiming
// at the farthest cell vertex next to a dense shore.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "shoremesh/engine/engine.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/verify.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

constexpr double kFarthest = std::numeric_limits<double>::infinity();  // aims at the farthest cell vertex always

template <int D>
Parameters<D> aiming(double steiner_aim) {
  Parameters<D> p;
  p.steiner_aim = steiner_aim;
  return p;
}

template <int D>
std::vector<Point<D>> well_spaced_output(const std::vector<Point<D>>& input, double steiner_aim, const std::string& what) {
  const StableResult<D> r = stable_well_spaced<D>(input, aiming<D>(steiner_aim));
  const auto report = verify_well_spaced<D>(r.points, input, r.box, std::sqrt(2.0));
  EXPECT_TRUE(report.ok()) << what << ", steiner_aim " << steiner_aim << ": " << report.violations
                           << " violations, worst ratio " << report.worst_ratio << ", missing input "
                           << report.missing_input;
  EXPECT_LE(report.worst_size_conformity, 40.0) << what << ", steiner_aim " << steiner_aim;
  std::vector<Point<D>> points = r.points;
  std::sort(points.begin(), points.end());
  return points;
}

template <int D>
void every_aim_is_well_spaced(const std::vector<Point<D>>& input, const std::string& what, bool aims_differ) {
  const auto nearest_beyond_rho = well_spaced_output<D>(input, 1.0, what);
  const auto by_default = well_spaced_output<D>(input, Parameters<D>{}.steiner_aim, what);
  const auto farthest = well_spaced_output<D>(input, kFarthest, what);
  // The parameter reaches the engine: the rules pick different points where a fill inserts several.
  if (aims_differ) {
    EXPECT_NE(nearest_beyond_rho, farthest) << what;
    if (D == 2) {
      EXPECT_NE(by_default, farthest) << what;
    } else {
      EXPECT_EQ(by_default, farthest) << what;  // the 3D default aims at the farthest vertex
    }
  }
}

TEST(SteinerAim, EveryAimIsWellSpaced2D) {
  every_aim_is_well_spaced<2>(families::uniform<2>(1500, 71), "uniform", true);
  every_aim_is_well_spaced<2>(families::gaussian_clusters<2>(1000, 5, 72), "clusters", true);
  every_aim_is_well_spaced<2>(families::on_circle<2>(600), "circle", true);
  every_aim_is_well_spaced<2>(families::close_pair<2>(100, 1e-9), "close pair", true);
  every_aim_is_well_spaced<2>(families::grid<2>(20), "grid", false);  // co-circular: ties at exactly rho NN
  every_aim_is_well_spaced<2>(families::on_line<2>(500), "line", true);
}

TEST(SteinerAim, EveryAimIsWellSpaced3D) {
  every_aim_is_well_spaced<3>(families::uniform<3>(200, 73), "uniform", true);
  every_aim_is_well_spaced<3>(families::on_line<3>(100), "line", true);
  every_aim_is_well_spaced<3>(families::grid<3>(5), "grid", false);
}

// A dense shore (a round lake's) is where the water mesh spends its points: aiming at the nearest cell
// vertex beyond 1.15 rho NN (the circumcentre of the mildest bad triangle) instead of beta NN toward the
// farthest saves some of them.
TEST(SteinerAim, DefaultNeedsFewerPointsNextToADenseShore) {
  for (std::size_t n : {1000u, 3000u}) {
    const auto shore = families::on_circle<2>(n);
    const std::size_t by_default = stable_well_spaced<2>(shore).points.size();
    const std::size_t farthest = stable_well_spaced<2>(shore, aiming<2>(kFarthest)).points.size();
    EXPECT_LT(double(by_default), 0.99 * double(farthest)) << n << " shore points: " << by_default << " vs " << farthest;
  }
}

// Lemma 7.2 under the other rules too: the aim is a function of the cell alone, so after every edit the
// output and the operations equal a fresh run with the same parameters.
template <int D>
void edits_equal_fresh_runs(double steiner_aim, std::vector<Point<D>> initial, int edits, std::uint64_t seed) {
  const Parameters<D> params = aiming<D>(steiner_aim);
  WellSpacedSet<D> set(params);
  set.build(initial);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < edits; ++k) {
    const auto ids = set.input_ids();
    const std::size_t pick = ids[rng() % ids.size()];
    Point<D> q = set.input_point(pick);
    for (auto& x : q) x = std::clamp(x + 0.02 * (u(rng) - 0.5), 0.0, 1.0);
    std::string what;
    switch (rng() % 3) {
      case 0:
        set.add(q);
        what = "add next to a point";
        break;
      case 1:
        if (ids.size() > 3) {
          set.remove(pick);
          what = "remove";
          break;
        }
        [[fallthrough]];
      default:
        set.move(pick, q);
        what = "move";
    }
    std::vector<Point<D>> inputs;
    for (std::size_t id : set.input_ids()) inputs.push_back(set.input_point(id));
    WellSpacedSet<D> fresh(params);
    fresh.build(inputs);
    auto a = set.output_points(), b = fresh.output_points();
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    const std::string context = "steiner_aim " + std::to_string(steiner_aim) + ", edit " + std::to_string(k) + ": " + what;
    ASSERT_EQ(a, b) << context;
    ASSERT_EQ(set.engine().operation_signature(), fresh.engine().operation_signature()) << context;
  }
  ASSERT_NO_THROW(set.check_valid());
}

TEST(SteinerAim, EditsEqualFreshRunsUnderEveryAim2D) {
  for (double aim : {1.0, Parameters<2>{}.steiner_aim, kFarthest})
    edits_equal_fresh_runs<2>(aim, families::gaussian_clusters<2>(40, 3, 74), 60, 75);
}

TEST(SteinerAim, EditsEqualFreshRunsUnderEveryAim3D) {
  for (double aim : {1.0, 1.15, kFarthest}) edits_equal_fresh_runs<3>(aim, families::uniform<3>(8, 76), 8, 77);
}

TEST(SteinerAim, BelowOneIsRefused) {
  EXPECT_THROW(WellSpacedSet<2>(aiming<2>(0.9)), ParameterError);
  EXPECT_THROW(WellSpacedSet<3>(aiming<3>(std::nan(""))), ParameterError);
  EXPECT_NO_THROW(WellSpacedSet<2>(aiming<2>(kFarthest)));
}

}  // namespace
}  // namespace shoremesh
