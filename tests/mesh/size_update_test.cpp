// Element size control under edits (docs/sizing.md, "Lemma 7.2 under size control"): SizeField's local
// update equals a fresh field, node for node, and stays where the change reaches; the shore refinement's
// update under a changed rule equals a fresh refinement.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <utility>

#include "mesh_test_util.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/size_function.hpp"

namespace shoremesh {
namespace {

Domain2 lake(int n) { return mesh_test::wobbly_lake(n); }

SizePolygon square(double x0, double y0, double side, double size) {
  return {{{{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}}}, size, "test polygon"};
}

// Random edits of the rings (moves, insertions, removals of a vertex, the island going and coming) and
// of the polygons' sizes; after each, the updated field equals a fresh one on the new input: h, the water
// and the summary, exactly. What each update recorded (SizeUndo) reads min_over as it was and, every third
// edit, takes the update back to the field before it, exactly.
void expect_updates_equal_fresh(SizeTerms t, int edits, unsigned seed) {
  Domain2 rings = lake(90);
  const BoxTransform<2> box = BoxTransform<2>::fit(mesh_test::session_input(rings).points);
  SizeField field(t, box, rings);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const Domain2 island{{lake(90).rings[1]}};
  int changed = 0;
  for (int e = 0; e < edits; ++e) {
    const double what = u(rng);
    std::string kind;
    SizeChange c;
    const SizeField before = field;
    SizeUndo undo;
    std::function<SizeChange(SizeUndo*)> redo;
    if (what < 0.3 && !t.polygons.empty()) {
      kind = "size";
      const std::size_t q = rng() % t.polygons.size();
      t.polygons[q].size = 800 + 7000 * u(rng);
      redo = [&field, q, size = t.polygons[q].size](SizeUndo* un) { return field.set_polygon_size(q, size, un); };
    } else {
      auto& ring = rings.rings[0].points;
      const std::size_t k = rng() % ring.size();
      const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
      const Point2 mid{a[0] + 0.3 * (b[0] - a[0]) + 0.05 * (b[1] - a[1]), a[1] + 0.3 * (b[1] - a[1]) - 0.05 * (b[0] - a[0])};
      const std::size_t n = ring.size();
      RingStretch stretch;  // the same edit as a stretch (the session's way), k's wrap-around included
      if (what < 0.6) {
        kind = "move", ring[k] = mid;
        stretch = {0, k, n - k - 1, {mid}};
      } else if (what < 0.8) {
        kind = "insert", ring.insert(ring.begin() + static_cast<std::ptrdiff_t>(k) + 1, mid);
        stretch = {0, k + 1, n - k - 1, {mid}};
      } else if (what < 0.95 && ring.size() > 60) {
        kind = "remove", ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
        stretch = {0, k, n - k - 1, {}};
      } else {
        kind = "island";
        rings.rings[1].points = rings.rings[1].points.empty() ? island.rings[0].points : std::vector<Point2>{};
        stretch = {1, 0, 0, rings.rings[1].points, true};
      }
      // Two in three by stretches (the edge tree), the rest by the rings whole (which drops the tree).
      if (u(rng) < 0.67) {
        kind += " by stretch";
        redo = [&field, stretch](SizeUndo* un) { return field.set_rings(std::span<const RingStretch>(&stretch, 1), un); };
      } else {
        redo = [&field, &rings](SizeUndo* un) { return field.set_rings(rings, un); };
      }
    }
    c = redo(&undo);
    // What the update recorded reads h as it was, and takes it back exactly; then the edit again.
    for (int k = 0; k < 20; ++k) {
      const Point2 lo{box.origin[0] + u(rng) * box.side, box.origin[1] + u(rng) * box.side};
      const double side = std::ldexp(box.side, -static_cast<int>(rng() % 10));
      ASSERT_EQ(field.min_over_before(undo, lo, side), before.min_over(lo, side)) << "edit " << e;
    }
    if (e % 3 == 0) {
      field.take_back(std::move(undo));
      ASSERT_EQ(field.nodes(), before.nodes()) << "edit " << e << " (" << kind << ") taken back";
      ASSERT_EQ(field.water(), before.water()) << "edit " << e << " (" << kind << ") taken back";
      for (int k = 0; k < 20; ++k) {
        const Point2 lo{box.origin[0] + u(rng) * box.side, box.origin[1] + u(rng) * box.side};
        const double side = std::ldexp(box.side, -static_cast<int>(rng() % 10));
        ASSERT_EQ(field.min_over(lo, side), before.min_over(lo, side)) << "edit " << e;
      }
      c = redo(nullptr);
    }
    const SizeField fresh(t, box, rings);
    ASSERT_TRUE(field == fresh) << "edit " << e << " (" << kind << ")";
    ASSERT_EQ(field.nodes(), fresh.nodes()) << "edit " << e << " (" << kind << ")";
    ASSERT_EQ(field.water(), fresh.water()) << "edit " << e << " (" << kind << ")";
    ASSERT_EQ(field.summary().grading, fresh.summary().grading);
    EXPECT_FALSE(c.whole) << "edit " << e << " (" << kind << ")";
    changed += c.changed;
  }
  EXPECT_GT(changed, edits / 3);
}

TEST(SizeFieldUpdate, RandomShoreAndSizeEditsEqualAFreshFieldGraded) {
  SizeTerms t;
  t.max_size = 8000, t.shore_size = 1500, t.shore_rate = 0.3, t.grade = 0.3;
  t.polygons = {square(-30000, -10000, 20000, 2000), square(0, 20000, 15000, 3000)};
  expect_updates_equal_fresh(t, std::getenv("SHOREMESH_SANITIZER_BUILD") ? 10 : 60, 3501);
}

// Without --max-size the shore term is not clamped (its change reaches as far as the distance changes),
// without --grade h is the terms' minimum, with --min-size clamped from below.
TEST(SizeFieldUpdate, RandomShoreAndSizeEditsEqualAFreshFieldUnclampedAndUngraded) {
  SizeTerms t;
  t.shore_size = 1200, t.shore_rate = 0.2, t.grade = 0.25, t.min_size = 1000;
  t.polygons = {square(-30000, -10000, 20000, 900), square(0, 20000, 15000, 3000)};
  expect_updates_equal_fresh(t, std::getenv("SHOREMESH_SANITIZER_BUILD") ? 8 : 40, 3502);
  SizeTerms raw;
  raw.max_size = 6000, raw.shore_size = 1000, raw.shore_rate = 0.4;
  raw.polygons = {square(-30000, -10000, 20000, 1500)};
  expect_updates_equal_fresh(raw, std::getenv("SHOREMESH_SANITIZER_BUILD") ? 8 : 40, 3503);
}

// The update reads and writes only what the change reaches: on a 1025 x 1025 grid, a shore move under
// --size-from-shore 300 0.5 with --max-size 2000 (the shore term binds within 3.4 km of the shore) and a
// `size` edit of a 2 km polygon with --grade 0.2 (its cone reaches (2000 - 500) / 0.2 = 7.5 km) each visit
// well under a twentieth of the grid, and end equal to a fresh field.
TEST(SizeFieldUpdate, AnUpdateTouchesOnlyAWindow) {
  Domain2 rings = lake(400);
  const BoxTransform<2> box = BoxTransform<2>::fit(mesh_test::session_input(rings).points);
  SizeTerms t;
  t.max_size = 2000, t.shore_size = 300, t.shore_rate = 0.5, t.grade = 0.2;
  t.polygons = {square(-5000, -20000, 2000, 500)};
  SizeField field(t, box, rings);
  const std::size_t grid = field.nodes().size();
  ASSERT_EQ(field.cells(), 1024u);
  auto& ring = rings.rings[0].points;
  const Point2 a = ring[7], b = ring[8];
  ring[7] = {a[0] + 0.4 * (b[0] - a[0]) + 0.1 * (b[1] - a[1]), a[1] + 0.4 * (b[1] - a[1]) - 0.1 * (b[0] - a[0])};
  const SizeChange moved = field.set_rings(rings);
  EXPECT_TRUE(moved.changed);
  EXPECT_FALSE(moved.whole);
  EXPECT_LT(moved.visited, grid / 20);
  EXPECT_LT((moved.i1 - moved.i0 + 1) * (moved.j1 - moved.j0 + 1), grid / 20);
  EXPECT_TRUE(field == SizeField(t, box, rings));
  t.polygons[0].size = 1400;
  const SizeChange sized = field.set_polygon_size(0, 1400);
  EXPECT_TRUE(sized.changed);
  EXPECT_FALSE(sized.whole);
  EXPECT_LT(sized.visited, grid / 20);
  EXPECT_TRUE(field == SizeField(t, box, rings));
  RecordProperty("nodes visited by the move", std::to_string(moved.visited));
  RecordProperty("nodes visited by the size edit", std::to_string(sized.visited));
  RecordProperty("grid nodes", std::to_string(grid));
}

// A change of the rule (a `size` edit) resets only the edges whose max_length reads a changed node of h,
// and the refinement closes again to a fresh refinement's splits under the new rule.
TEST(SizeFieldUpdate, RefinementUnderAChangedRuleEqualsAFreshOne) {
  const Domain2 rings = lake(90);
  const BoxTransform<2> box = BoxTransform<2>::fit(mesh_test::session_input(rings).points);
  SizeTerms t;
  t.max_size = 8000, t.grade = 0.3;
  t.polygons = {square(-52000, -10000, 20000, 2000), square(30000, 20000, 25000, 3000)};
  auto rule_of = [&](std::shared_ptr<const SizeField> f) {
    RefinementRule r = RefinementRule::for_box(box.side);
    r.max_length = shore_max_length(std::move(f));
    return r;
  };
  auto field = std::make_shared<const SizeField>(t, box, rings);
  ShoreRefinement refinement(rings, {}, rule_of(field));
  std::mt19937 rng(3504);
  std::uniform_real_distribution<double> u(0, 1);
  std::size_t changes = 0;
  for (int e = 0; e < 16; ++e) {
    auto next = std::make_shared<SizeField>(*field);
    const std::size_t q = rng() % 2;
    t.polygons[q].size = 500 + 6000 * u(rng);
    const SizeChange c = next->set_polygon_size(q, t.polygons[q].size);
    // Every other edit finds the edges by their reach (an R-tree), the others by a scan.
    std::optional<std::pair<Point2, Point2>> near;
    if (c && e % 2 == 1) near = next->reach_of(c);
    if (c) {  // reach_of's contract, on segments of every length up to the box's side
      const auto [lo, hi] = next->reach_of(c);
      for (int k = 0; k < 400; ++k) {
        const Point2 a{box.origin[0] + u(rng) * box.side, box.origin[1] + u(rng) * box.side};
        const double len = std::ldexp(box.side, -static_cast<int>(rng() % 14)) * u(rng), dir = 2 * std::numbers::pi * u(rng);
        const Point2 b{a[0] + len * std::cos(dir), a[1] + len * std::sin(dir)};
        const double g = 0.5 * std::max(std::abs(b[0] - a[0]), std::abs(b[1] - a[1]));
        const bool meets = std::min(a[0], b[0]) - g <= hi[0] && lo[0] <= std::max(a[0], b[0]) + g &&
                           std::min(a[1], b[1]) - g <= hi[1] && lo[1] <= std::max(a[1], b[1]) + g;
        ASSERT_TRUE(meets || !next->reads(a, b, c)) << "edit " << e << " segment " << k;
      }
    }
    const SplitChange s = refinement.update({}, {}, {}, rule_of(next), [&](const Point2& a, const Point2& b) {
      return next->reads(a, b, c);
    }, near);
    changes += s.removed.size() + s.added.size();
    const ShoreRefinement fresh(rings, {}, rule_of(next));
    ASSERT_EQ(refinement.split_points(), fresh.split_points()) << "edit " << e;
    field = next;
  }
  EXPECT_GT(changes, 0u);
}

}  // namespace
}  // namespace shoremesh
