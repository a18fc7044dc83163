// PropagateWS: after every edit the output (and the multiset of operations) is bit-identical to StableWS
// run from scratch on the current input (Lemma 7.2); memory is reclaimed; bad edits change nothing; the
// work per update does not grow with n.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "shoremesh/engine/engine.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/verify.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

bool sanitizer_build() { return std::getenv("SHOREMESH_SANITIZER_BUILD") != nullptr; }

template <class T>
std::vector<T> sorted(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  return v;
}

template <int D>
std::vector<Point<D>> live_inputs(const WellSpacedSet<D>& set) {
  std::vector<Point<D>> pts;
  for (std::size_t id : set.input_ids()) pts.push_back(set.input_point(id));
  return pts;
}

// The strongest test: equal to a from-scratch run, points bit for bit and operations (vertex, rank, colour).
template <int D>
void expect_equal_to_fresh_run(const WellSpacedSet<D>& set, const std::string& context) {
  WellSpacedSet<D> fresh;
  fresh.build(live_inputs(set));
  ASSERT_EQ(sorted(set.output_points()), sorted(fresh.output_points())) << context;
  ASSERT_EQ(set.engine().operation_signature(), fresh.engine().operation_signature()) << context;
  ASSERT_EQ(set.engine().live_op_count(), fresh.engine().live_op_count()) << context;
  ASSERT_EQ(set.engine().live_vertex_count(), fresh.engine().live_vertex_count()) << context;
}

// A random edit of the kinds the issue names.
template <int D>
std::string random_edit(WellSpacedSet<D>& set, std::mt19937_64& rng, UpdateReport<D>* report) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto ids = set.input_ids();
  const std::size_t pick = ids[rng() % ids.size()];
  auto near = [&](const Point<D>& p, double r) {
    Point<D> q;
    for (int i = 0; i < D; ++i) q[i] = std::clamp(p[i] + r * (u(rng) - 0.5), 0.0, 1.0);
    return q;
  };
  switch (rng() % 7) {
    case 0: {  // insert far away: anywhere
      Point<D> p;
      for (auto& x : p) x = u(rng);
      set.add(p, report);
      return "add anywhere";
    }
    case 1:  // insert right next to an existing point
      set.add(near(set.input_point(pick), 1e-3), report);
      return "add next to a point";
    case 2:  // the lower-bound gadget: a point 1e-9 from another
      set.add(near(set.input_point(pick), 2e-9), report);
      return "add at 1e-9";
    case 3:
    case 4:
      if (ids.size() > 3) {
        set.remove(pick, report);
        return "remove";
      }
      [[fallthrough]];
    case 5:
      set.move(pick, near(set.input_point(pick), 0.05), report);
      return "move";
    default: {  // remove the input point that caused the most Steiner points: the one nearest to another
      std::size_t worst = ids[0];
      double best = 1e300;
      for (std::size_t a : ids)
        for (std::size_t b : ids) {
          if (a >= b) continue;
          double d = 0;
          for (int i = 0; i < D; ++i) d += std::pow(set.input_point(a)[i] - set.input_point(b)[i], 2);
          if (d < best) best = d, worst = a;
        }
      if (ids.size() > 3) {
        set.remove(worst, report);
        return "remove the closest point";
      }
      set.move(pick, near(set.input_point(pick), 0.05), report);
      return "move";
    }
  }
}

template <int D>
void random_edits_equal_fresh_runs(std::vector<Point<D>> initial, int edits, std::uint64_t seed) {
  WellSpacedSet<D> set;
  set.build(initial);
  std::mt19937_64 rng(seed);
  for (int k = 0; k < edits; ++k) {
    UpdateReport<D> report;
    const auto before = sorted(set.output_points());
    const std::string what = random_edit(set, rng, &report);
    const std::string context = "edit " + std::to_string(k) + ": " + what;
    expect_equal_to_fresh_run(set, context);
    if (::testing::Test::HasFatalFailure()) return;
    // The report is the net change of the Steiner points.
    const auto after = sorted(set.output_points());
    std::vector<Point<D>> gone, come;
    std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(gone));
    std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(come));
    EXPECT_LE(report.steiner_removed.size(), gone.size()) << context;  // gone also holds removed inputs
    EXPECT_LE(report.steiner_added.size(), come.size()) << context;
    for (const auto& p : report.steiner_removed) EXPECT_TRUE(std::binary_search(gone.begin(), gone.end(), p)) << context;
    for (const auto& p : report.steiner_added) EXPECT_TRUE(std::binary_search(come.begin(), come.end(), p)) << context;
    if (k % 100 == 0) {
      ASSERT_NO_THROW(set.check_valid()) << context;
    }
    // Long runs take a while: say how far they are.
    if (k % 100 == 99 && std::getenv("SHOREMESH_LONG_TESTS"))
      std::fprintf(stderr, "%dD: %d of %d edits equal fresh runs (%zu inputs, %zu Steiner points)\n", D, k + 1, edits,
                   set.input_count(), set.steiner_count());
  }
  ASSERT_NO_THROW(set.check_valid());
  const auto inputs = live_inputs(set);
  const auto report = verify_well_spaced<D>(set.output_points(), inputs, BoxTransform<D>{{}, 1.0}, std::sqrt(2.0));
  EXPECT_TRUE(report.ok()) << report.violations << " violations";
}

// The full 1000-edit runs are `SHOREMESH_LONG_TESTS=1` (on the 2-core machine, sharing it: 2D 3.7 min,
// 3D 1 h 56 min); CI runs shorter sequences.
int edits(int quick, int sanitizer, int full) {
  if (std::getenv("SHOREMESH_LONG_TESTS")) return full;
  return sanitizer_build() ? sanitizer : quick;
}

TEST(Dynamic, RandomEditsEqualFreshRuns2D) {
  random_edits_equal_fresh_runs<2>(families::gaussian_clusters<2>(25, 3, 21), edits(300, 100, 1000), 1);
}

TEST(Dynamic, RandomEditsEqualFreshRuns3D) {
  random_edits_equal_fresh_runs<3>(families::uniform<3>(6, 22), edits(40, 15, 1000), 2);
}

// A build for output only (stable_well_spaced's) records nothing that only updates read and forgets its
// operations once they have run: the same output as a build for updates, and it refuses updates.
template <int D>
void output_only_build_is_the_same(const std::vector<Point<D>>& input) {
  WellSpacedSet<D> laid_out, as_built;
  laid_out.build(input);
  as_built.build(input, BuildFor::OutputOnly);
  ASSERT_NO_THROW(as_built.check_valid());
  ASSERT_EQ(laid_out.output_points(), as_built.output_points());
  EXPECT_EQ(laid_out.counters().operations(), as_built.counters().operations());
  EXPECT_EQ(as_built.engine().live_op_count(), 0u);
  EXPECT_LT(as_built.memory_bytes(), laid_out.memory_bytes());
  EXPECT_THROW(as_built.add(Point<D>{}), std::logic_error);
}

TEST(Dynamic, OutputOnlyBuildIsTheSame2D) {
  output_only_build_is_the_same<2>(families::gaussian_clusters<2>(400, 4, 8));
}

TEST(Dynamic, OutputOnlyBuildIsTheSame3D) {
  output_only_build_is_the_same<3>(families::uniform<3>(50, 9));
}

// A propagation takes a vertex's cell from its cache when nothing that could change it was born since its
// last computation (core/src/cell_cache.cpp). On uniform 2D points a seventh of the cells of an update
// come from it: most fills that took their cell from it are now left out, or done without a cell (on
// grids, where vertices lie on several bisectors at once, cells with such a vertex are never kept, so no
// share is expected), and about half of the cells computed take their candidate vertices
// from a stale entry's lists instead of a search, most of them by cutting the earlier cell with the new
// vertices only. Either way every edit still equals a fresh run.
template <int D>
void reused_cells_equal_fresh_runs(const std::vector<Point<D>>& initial, int edits, double min_reused_share,
                                   double min_listed_share, double min_updated_share) {
  WellSpacedSet<D> set;
  set.build(initial);
  const Counters built = set.counters();
  std::mt19937_64 rng(5);
  for (int k = 0; k < edits; ++k) {
    const std::string what = random_edit(set, rng, static_cast<UpdateReport<D>*>(nullptr));
    expect_equal_to_fresh_run(set, "edit " + std::to_string(k) + ": " + what);
    if (::testing::Test::HasFatalFailure()) return;
  }
  const double computed = double(set.counters().clipped_voronoi_calls - built.clipped_voronoi_calls);
  const double reused = double(set.counters().cells_reused - built.cells_reused);
  const double listed = double(set.counters().neighbourhoods_reused - built.neighbourhoods_reused);
  if (min_reused_share > 0) {  // none on grids: there most cells have a vertex on several bisectors
    EXPECT_GE(reused / (reused + computed), min_reused_share) << reused << " reused, " << computed << " computed";
  }
  EXPECT_GE(listed / computed, min_listed_share) << listed << " of " << computed << " computed from lists";
  const double updated = double(set.counters().cells_updated - built.cells_updated);
  EXPECT_GE(updated / computed, min_updated_share) << updated << " of " << computed << " cut from the earlier cell";
}

TEST(Dynamic, ReusedCellsEqualFreshRuns2D) {
  reused_cells_equal_fresh_runs<2>(families::uniform<2>(300, 31), 60, 0.1, 0.3, 0.3);
  reused_cells_equal_fresh_runs<2>(families::grid<2>(14), 30, 0.0, 0.3, 0.3);
}

TEST(Dynamic, ReusedCellsEqualFreshRuns3D) {
  reused_cells_equal_fresh_runs<3>(families::uniform<3>(30, 32), 6, 0.1, 0.3, 0.3);
  reused_cells_equal_fresh_runs<3>(families::grid<3>(3), 4, 0.0, 0.3, 0.3);
}

TEST(Dynamic, InsertNextToExistingPointAndGadget2D) {
  auto pts = families::uniform<2>(200, 5);
  WellSpacedSet<2> set;
  set.build(pts);
  UpdateReport<2> report;
  const std::size_t id = set.add({pts[17][0] + 1e-9, pts[17][1]}, &report);
  EXPECT_EQ(id, 200u);
  // The gadget of section 8: growing rings of Steiner points around the new close pair, Omega(log Delta).
  EXPECT_GT(report.steiner_added.size(), 20u);
  expect_equal_to_fresh_run(set, "gadget");
  set.remove(id, &report);
  expect_equal_to_fresh_run(set, "gadget removed");
  EXPECT_GT(report.steiner_removed.size(), 20u);
}

TEST(Dynamic, BatchEqualsFreshRun) {
  auto pts = families::uniform<2>(300, 6);
  WellSpacedSet<2> set;
  set.build(pts);
  std::vector<Edit<2>> edits{{Edit<2>::Kind::Remove, 3, {}},
                             {Edit<2>::Kind::Add, 0, {0.5, 0.5}},
                             {Edit<2>::Kind::Move, 10, {0.25, 0.75}},
                             {Edit<2>::Kind::Add, 0, {0.5, 0.5000001}}};
  UpdateReport<2> report;
  const auto ids = set.apply(edits, &report);
  EXPECT_EQ(ids, (std::vector<std::size_t>{300, 301}));
  EXPECT_FALSE(set.has_input(3));
  EXPECT_EQ(set.input_point(10), (Point<2>{0.25, 0.75}));
  expect_equal_to_fresh_run(set, "batch");
}

TEST(Dynamic, MemoryIsReclaimed) {
  WellSpacedSet<2> set;
  set.build(families::uniform<2>(400, 7));
  std::mt19937_64 rng(3);
  for (int k = 0; k < 300; ++k) random_edit(set, rng, static_cast<UpdateReport<2>*>(nullptr));
  WellSpacedSet<2> fresh;
  fresh.build(live_inputs(set));
  EXPECT_EQ(set.engine().live_op_count(), fresh.engine().live_op_count());
  EXPECT_EQ(set.engine().live_vertex_count(), fresh.engine().live_vertex_count());
  // Free slots are reused: the arrays stay within a small factor of a fresh run's.
  EXPECT_LT(set.engine().op_count(), 2 * fresh.engine().op_count());
  EXPECT_LT(set.engine().vertex_count(), 2 * fresh.engine().vertex_count());
  EXPECT_LT(set.memory_bytes(), 3 * fresh.memory_bytes());
  ASSERT_NO_THROW(set.check_valid());
}

TEST(Dynamic, BadEditsChangeNothing) {
  WellSpacedSet<2> set;
  set.build(families::uniform<2>(50, 8));
  const auto before = set.output_points();
  const Point<2> existing = set.input_point(4);
  EXPECT_THROW(set.remove(999), InputError);
  EXPECT_THROW(set.move(999, {0.5, 0.5}), InputError);
  EXPECT_THROW(set.add(existing), InputError);
  EXPECT_THROW(set.add({1.5, 0.5}), InputError);
  EXPECT_THROW(set.add({std::nan(""), 0.5}), InputError);
  EXPECT_THROW(set.add({existing[0] + 1e-13, existing[1]}), InputError);  // below the resolution
  // A batch with one bad edit applies none of them.
  std::vector<Edit<2>> edits{{Edit<2>::Kind::Add, 0, {0.5, 0.25}}, {Edit<2>::Kind::Remove, 77, {}}};
  try {
    set.apply(edits);
    FAIL() << "bad batch accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("edit 2"), std::string::npos) << e.what();
  }
  EXPECT_EQ(set.output_points(), before);
  ASSERT_NO_THROW(set.check_valid());
  // Removing every point but the last works; the last is refused.
  for (std::size_t id = 0; id < 49; ++id) set.remove(id);
  EXPECT_THROW(set.remove(49), InputError);
  EXPECT_EQ(set.output_points().size(), 1u);
  ASSERT_NO_THROW(set.check_valid());
  // Ids are never reused.
  EXPECT_EQ(set.add({0.5, 0.5}), 50u);
  expect_equal_to_fresh_run(set, "after removing all but one");
}

TEST(Dynamic, UserCoordinatesAndBoxRefusal) {
  std::vector<Point<2>> pts;
  for (const auto& p : families::uniform<2>(100, 9)) pts.push_back({1000 + 500 * p[0], -200 + 500 * p[1]});
  DynamicWellSpaced<2> dyn(pts);
  const auto box = dyn.box();
  UpdateReport<2> report;
  const std::size_t id = dyn.add({1250, 50}, &report);
  dyn.move(0, {1100, 100}, &report);
  EXPECT_THROW(dyn.add({box.origin[0] - 1, 50}), InputError);
  // Equal to the static entry point on the final input and the same box, in user coordinates.
  std::vector<Point<2>> final_input;
  for (std::size_t k : dyn.input_ids()) final_input.push_back(dyn.input_point(k));
  const StableResult<2> fresh = stable_well_spaced<2>(final_input, {}, box);
  EXPECT_EQ(dyn.points(), fresh.points);
  EXPECT_EQ(dyn.input_point(id), (Point<2>{1250, 50}));
}

// A dense shore seen from far out on the water: points on a circle (a round lake) or a sphere. The
// cells of the coarse vertices inside reach the shore, whose points the nearer vertices hide from
// them; the searches skip those (compute_cell). Edits of shore points equal fresh runs.
template <int D>
void shore_edits_equal_fresh_runs(std::size_t n, int edits, double step, std::uint64_t seed) {
  WellSpacedSet<D> set;
  set.build(families::on_circle<D>(n));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  auto near = [&](const Point<D>& p) {
    Point<D> q;
    for (int i = 0; i < D; ++i) q[i] = p[i] + step * u(rng);
    return q;
  };
  for (int k = 0; k < edits; ++k) {
    const auto ids = set.input_ids();
    const std::size_t pick = ids[rng() % ids.size()];
    std::string what;
    switch (k % 3) {
      case 0:
        set.move(pick, near(set.input_point(pick)));
        what = "move a shore point";
        break;
      case 1:
        set.add(near(set.input_point(pick)));
        what = "add next to a shore point";
        break;
      default:
        set.remove(pick);
        what = "remove a shore point";
    }
    expect_equal_to_fresh_run(set, "edit " + std::to_string(k) + ": " + what);
    if (::testing::Test::HasFatalFailure()) return;
  }
  ASSERT_NO_THROW(set.check_valid());
}

TEST(Dynamic, DenseShoreEditsEqualFreshRuns2D) { shore_edits_equal_fresh_runs<2>(800, edits(45, 15, 300), 5e-4, 5); }

TEST(Dynamic, DenseShoreEditsEqualFreshRuns3D) { shore_edits_equal_fresh_runs<3>(800, edits(15, 6, 60), 4e-3, 6); }

// Work per computed cell stays bounded next to a dense shore: moving shore points of a round lake of
// 800 points, the cells the updates computed looked at 128 candidates each and clipped 47 before the
// searches skipped what cannot cut a cell (most of a coarse cell's box is shore), 49 and 21 since.
TEST(Dynamic, CellsNearADenseShoreLookAtFewCandidates) {
  WellSpacedSet<2> set;
  set.build(families::on_circle<2>(800));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const Counters before = set.counters();
  for (int k = 0; k < 40; ++k) {
    const auto ids = set.input_ids();
    const std::size_t pick = ids[rng() % ids.size()];
    Point<2> p = set.input_point(pick);
    for (double& x : p) x += 5e-4 * u(rng);
    set.move(pick, p);
  }
  const Counters& after = set.counters();
  const double cells = double(after.clipped_voronoi_calls - before.clipped_voronoi_calls);
  ASSERT_GT(cells, 0);
  const double candidates = double(after.candidates - before.candidates) / cells;
  const double clips = double(after.clips - before.clips) / cells;
  ::testing::Test::RecordProperty("candidates_per_cell", std::to_string(candidates));
  ::testing::Test::RecordProperty("clips_per_cell", std::to_string(clips));
  EXPECT_LT(candidates, 70);
  EXPECT_LT(clips, 30);
}

// Work per update grows with log(spread), not with n: operations touched per unit change (remove a
// random input point, then add a random point) stay bounded from n = 1e3 to 1e4 (1e5 in bench/).
TEST(Dynamic, OperationsPerUpdateBoundedInN) {
  std::vector<double> medians;
  for (std::size_t n : {std::size_t(1000), std::size_t(sanitizer_build() ? 3000 : 10000)}) {
    WellSpacedSet<2> set;
    set.build(families::uniform<2>(n, 10));
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::size_t> touched;
    for (int k = 0; k < 40; ++k) {
      UpdateReport<2> a, b;
      const auto ids = set.input_ids();
      set.remove(ids[rng() % ids.size()], &a);
      set.add({u(rng), u(rng)}, &b);
      touched.push_back(a.operations_touched());
      touched.push_back(b.operations_touched());
    }
    std::sort(touched.begin(), touched.end());
    medians.push_back(double(touched[touched.size() / 2]));
    ::testing::Test::RecordProperty("median_touched_n" + std::to_string(n), int(medians.back()));
    ::testing::Test::RecordProperty("max_touched_n" + std::to_string(n), int(touched.back()));
    EXPECT_LT(double(touched.back()), 0.5 * double(set.engine().live_op_count()));
  }
  EXPECT_LT(medians[1], 1.5 * medians[0]);
}

}  // namespace
}  // namespace shoremesh
