// A build computes each (rank, colour) batch on several threads and commits it in batch order; a one-shot
// build (BuildFor::OutputOnly) records nothing for updates. Neither may change the output by a bit: the
// same points in the same order, the same counts, whatever the thread count and the purpose.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "shoremesh/engine/engine.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

// A shore like Lake Superior's at small scale: a ring with bays and headlands at several scales,
// sampled far more densely along the ring than its extent, and a few loose points on the water.
std::vector<Point2> shore_like(std::size_t ring_points, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> phase(0, 2 * std::numbers::pi);
  const double a = phase(rng), b = phase(rng), c = phase(rng);
  std::vector<Point2> points;
  for (std::size_t k = 0; k < ring_points; ++k) {
    const double t = 2 * std::numbers::pi * double(k) / double(ring_points);
    const double r = 0.3 + 0.06 * std::sin(3 * t + a) + 0.03 * std::sin(17 * t + b) + 0.01 * std::sin(61 * t + c);
    points.push_back({0.5 + r * std::cos(t), 0.5 + r * std::sin(t)});
  }
  std::uniform_real_distribution<double> inner(0.45, 0.55);
  for (int k = 0; k < 20; ++k) points.push_back({inner(rng), inner(rng)});
  return points;
}

template <int D>
struct BuiltD {
  std::vector<Point<D>> points;
  std::uint64_t operations = 0, steiner = 0;
  bool operator==(const BuiltD&) const = default;
};

template <int D>
BuiltD<D> build(const std::vector<Point<D>>& input, BuildFor purpose, unsigned threads) {
  engine::set_thread_count(threads);
  WellSpacedSet<D> set;
  set.build(input, purpose);
  engine::set_thread_count(0);
  // The engine's own numbering, not only the sorted output: commits in batch order number alike.
  const auto positions = set.engine().positions();
  return {std::vector<Point<D>>(positions.begin(), positions.end()), set.counters().operations(),
          set.counters().steiner_points};
}

template <int D>
void same_for_every_thread_count_and_purpose(const std::vector<Point<D>>& input) {
  const BuiltD<D> one = build<D>(input, BuildFor::OutputOnly, 1);
  ASSERT_GT(one.steiner, 0u);
  for (unsigned threads : {2u, 8u}) {
    const BuiltD<D> many = build<D>(input, BuildFor::OutputOnly, threads);
    EXPECT_TRUE(many == one) << threads << " threads";
  }
  // For updates the vertices are then renumbered by place: compare the outputs.
  for (unsigned threads : {1u, 8u}) {
    WellSpacedSet<D> lean, full;
    engine::set_thread_count(threads);
    lean.build(input, BuildFor::OutputOnly);
    full.build(input, BuildFor::Updates);
    engine::set_thread_count(0);
    EXPECT_EQ(lean.output_points(), full.output_points()) << threads << " threads";
    EXPECT_EQ(lean.counters().operations(), full.counters().operations());
    ASSERT_NO_THROW(full.check_valid());
  }
}

TEST(ParallelBuild, SameOutputForAnyThreadCountAndPurposeUniform2D) {
  same_for_every_thread_count_and_purpose<2>(families::uniform<2>(3000, 5));
}

TEST(ParallelBuild, SameOutputForAnyThreadCountAndPurposeClusters2D) {
  same_for_every_thread_count_and_purpose<2>(families::gaussian_clusters<2>(2000, 5, 6));
}

TEST(ParallelBuild, SameOutputForAnyThreadCountAndPurposeGrid2D) {
  // Co-circular neighbourhoods, and a few loose points that make Steiner vertices among them.
  auto input = families::grid<2>(30);
  for (const Point2& p : families::uniform<2>(40, 11)) input.push_back({0.01 + 0.98 * p[0], 0.013 + 0.97 * p[1]});
  same_for_every_thread_count_and_purpose<2>(input);
}

TEST(ParallelBuild, SameOutputForAnyThreadCountAndPurposeShoreLike2D) {
  same_for_every_thread_count_and_purpose<2>(shore_like(1500, 7));
}

TEST(ParallelBuild, SameOutputForAnyThreadCountAndPurposeUniform3D) {
  same_for_every_thread_count_and_purpose<3>(families::uniform<3>(300, 8));
}

// Updates after a parallel build equal fresh runs (the recorded computation is the serial one's).
TEST(ParallelBuild, UpdatesAfterAParallelBuildEqualFreshRuns) {
  const auto input = families::gaussian_clusters<2>(600, 3, 9);
  engine::set_thread_count(8);
  WellSpacedSet<2> set;
  set.build(input);
  engine::set_thread_count(0);
  ASSERT_NO_THROW(set.check_valid());
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> coordinate(0, 1);
  for (int k = 0; k < 10; ++k) {
    if (k % 2 == 0) set.add({coordinate(rng), coordinate(rng)});
    else set.remove(set.input_ids()[rng() % set.input_count()]);
    std::vector<Point2> now;
    for (std::size_t id : set.input_ids()) now.push_back(set.input_point(id));
    WellSpacedSet<2> fresh;
    fresh.build(now, BuildFor::OutputOnly);
    ASSERT_EQ(set.output_points(), fresh.output_points()) << "edit " << k;
  }
  ASSERT_NO_THROW(set.check_valid());
}

}  // namespace
}  // namespace shoremesh
