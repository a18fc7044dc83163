// The canonical shore splits (core/include/shoremesh/shore_refinement.hpp): a function of the input alone,
// whatever the order of the rings or the history of edits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "shoremesh/engine/predicates.hpp"
#include "shoremesh/shore_refinement.hpp"

namespace shoremesh {
namespace {

// A star-shaped ring around (cx, cy): vertices at increasing angles, radii in [r0, r1]. Any radii keep it
// simple, so random edits of the radii stay valid rings.
struct StarRing {
  double cx, cy, r0, r1;
  std::vector<double> angle, radius;
  Point2 vertex(std::size_t k) const {
    return {cx + radius[k] * std::cos(angle[k]), cy + radius[k] * std::sin(angle[k])};
  }
  Ring ring(RingRole role) const {
    Ring r{{}, role};
    for (std::size_t k = 0; k < angle.size(); ++k) r.points.push_back(vertex(k));
    return r;
  }
};

StarRing star(double cx, double cy, double r0, double r1, std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  StarRing s{cx, cy, r0, r1, {}, {}};
  for (std::size_t k = 0; k < n; ++k) {
    s.angle.push_back(2 * std::numbers::pi * (k + 0.2 + 0.6 * u(rng)) / double(n));
    s.radius.push_back(r0 + (r1 - r0) * u(rng));
  }
  return s;
}

// The squared distance from x to the midpoint of (p, q) against (gamma/2)^2 |pq|^2.
bool encroaches(const Point2& p, const Point2& q, const Point2& x, double gamma) {
  const Point2 m{0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])};
  return std::hypot(x[0] - m[0], x[1] - m[1]) < 0.5 * gamma * std::hypot(q[0] - p[0], q[1] - p[1]) * (1 - 1e-9);
}

TEST(ShoreRefinement, NoSubsegmentOfAStraightFarShoreIsEncroachedAfterTheSplits) {
  // A long thin bay: two parallel shores 1 apart, 40 long, given by their corners only.
  const Domain2 d{{Ring{{{0, 0}, {40, 0}, {40, 1}, {0, 1}}, RingRole::Shore}}};
  const ShoreRefinement r(d);
  const Domain2 refined = r.refined();
  ASSERT_EQ(refined.rings.size(), 1u);
  const auto& ring = refined.rings[0].points;
  EXPECT_GT(ring.size(), 30u);  // each long side halved down to about the width
  // Every subsegment of a long side is free of the other side's points within gamma/2 of its length.
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const Point2 p = ring[k], q = ring[(k + 1) % ring.size()];
    if (p[1] != q[1]) continue;  // the short ends meet the long sides at right angles: checked by the rule
    for (const Point2& x : ring) {
      if (x[1] == p[1]) continue;
      EXPECT_FALSE(encroaches(p, q, x, RefinementRule{}.gamma)) << p[0] << "," << p[1] << " - " << q[0];
    }
  }
}

TEST(ShoreRefinement, SplitsDoNotDependOnRingOrderOrStart) {
  std::mt19937 rng(7);
  const StarRing outer = star(0, 0, 6, 10, 40, rng), island = star(0.5, 0.3, 3.5, 5.2, 12, rng);
  const std::vector<Point2> loose{{3, 3}, {-4, 1}, {0, -5.5}};
  Domain2 a{{outer.ring(RingRole::Shore), island.ring(RingRole::Island)}};
  Domain2 b{{island.ring(RingRole::Island), outer.ring(RingRole::Shore)}};
  std::rotate(b.rings[1].points.begin(), b.rings[1].points.begin() + 17, b.rings[1].points.end());
  std::vector<Point2> loose_b(loose.rbegin(), loose.rend());
  const ShoreRefinement ra(a, loose), rb(b, loose_b);
  EXPECT_GT(ra.split_count(), 0u);
  EXPECT_EQ(ra.split_points(), rb.split_points());
}

RefinementRule graded(double c) {
  RefinementRule r;
  r.grading = c;
  return r;
}

TEST(ShoreRefinement, SharpCornersEndTheHalving) {
  // A 5 degree wedge: the two sides meet at a corner sharper than 60 degrees and neither split nor grade
  // each other (a point on one side is within 0.1 of its length from the other near the corner).
  const double a = 5 * std::numbers::pi / 180;
  const Domain2 d{{Ring{{{0, 0}, {10, 0}, {10 * std::cos(a), 10 * std::sin(a)}}, RingRole::Shore}}};
  for (double c : {0.0, 2.0, 3.0}) {
    const ShoreRefinement r(d, {}, graded(c));
    EXPECT_LT(r.split_count(), 20u) << "grading " << c;
  }
}

TEST(ShoreRefinement, GradingHalvesASubsegmentLongerThanCTimesItsEndsNearestPoint) {
  // A square of side 10 with one corner cut by a short edge (0.1 sqrt 2 long, at 135 degrees): the long
  // edge from (0.1, 0) is halved until its first piece is at most c times that, and along the edge each
  // piece is at most c times its neighbour (the neighbour's far end is a point that near).
  const Domain2 d{{Ring{{{0.1, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0.1}}, RingRole::Shore}}};
  const double cut = 0.1 * std::sqrt(2.0);
  auto bottom = [&](const ShoreRefinement& r) {  // the refined bottom edge's piece lengths, from x = 0.1
    std::vector<double> xs;
    const Domain2 refined = r.refined();
    for (const Point2& p : refined.rings[0].points)
      if (p[1] == 0) xs.push_back(p[0]);
    std::sort(xs.begin(), xs.end());
    std::vector<double> lengths;
    for (std::size_t k = 1; k < xs.size(); ++k) lengths.push_back(xs[k] - xs[k - 1]);
    return lengths;
  };
  // Without grading the diametral test alone leaves a first piece well over 3 times the cut.
  EXPECT_GT(bottom(ShoreRefinement(d, {}, graded(0))).front(), 3 * cut);
  for (double c : {2.0, 2.5, 3.0}) {
    const std::vector<double> l = bottom(ShoreRefinement(d, {}, graded(c)));
    ASSERT_GT(l.size(), 5u);
    EXPECT_LE(l.front(), c * cut) << "grading " << c;
    EXPECT_GT(l.front(), 0.5 * c * cut) << "grading " << c << ": halved once too often";
    for (std::size_t k = 1; k < l.size(); ++k) {
      EXPECT_LE(l[k], c * l[k - 1] * (1 + 1e-12)) << "grading " << c << " piece " << k;
      EXPECT_LE(l[k - 1], c * l[k] * (1 + 1e-12)) << "grading " << c << " piece " << k;
    }
  }
}

TEST(ShoreRefinement, GradingDoesNotCascadeAlongAStraightShore) {
  // A unit square whose bottom is 11 collinear vertices 0.1 apart with one piece of 0.001: the pieces
  // near it grade up by halves (a few levels each way), not down to the floor along the whole shore.
  Ring ring{{}, RingRole::Shore};
  for (int k = 0; k <= 10; ++k) ring.points.push_back({0.1 * k, 0});
  ring.points.insert(ring.points.begin() + 6, Point2{0.501, 0});
  ring.points.push_back({1, 1});
  ring.points.push_back({0, 1});
  for (double c : {2.0, 3.0}) {
    const ShoreRefinement r(Domain2{{ring}}, {}, graded(c));
    EXPECT_GT(r.split_count(), 4u) << "grading " << c;
    EXPECT_LT(r.split_count(), 40u) << "grading " << c;
  }
  EXPECT_THROW(ShoreRefinement(Domain2{{ring}}, {}, graded(1.5)), std::invalid_argument);
}

TEST(ShoreRefinement, MorePointsOnlyAddSplits) {
  // The rule is monotone (a point only ever makes a split more due), so the least fixed point of a
  // larger input holds the smaller one's.
  std::mt19937 rng(5);
  const StarRing outer = star(0, 0, 6, 10, 24, rng), island = star(0.5, 0.3, 3.5, 5.2, 9, rng);
  const Domain2 d{{outer.ring(RingRole::Shore), island.ring(RingRole::Island)}};
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point2> loose;
  for (double c : {0.0, 2.0, 2.5}) {
    std::vector<Point2> previous = ShoreRefinement(d, loose, graded(c)).split_points();
    for (int round = 0; round < 6; ++round) {
      for (int k = 0; k < 4; ++k) {
        const double a = 2 * std::numbers::pi * u(rng), r = 5.3 + 0.6 * u(rng);
        loose.push_back({r * std::cos(a), r * std::sin(a)});
      }
      const std::vector<Point2> now = ShoreRefinement(d, loose, graded(c)).split_points();
      EXPECT_TRUE(std::includes(now.begin(), now.end(), previous.begin(), previous.end()))
          << "grading " << c << " round " << round;
      previous = now;
    }
    loose.clear();
  }
}

// The refined rings' segments, ends sorted, the list sorted.
std::vector<ShoreSegment> segments_of(const Domain2& refined) {
  std::vector<ShoreSegment> out;
  for (const Ring& ring : refined.rings)
    for (std::size_t k = 0; k < ring.segment_count(); ++k) {
      const Point2 &a = ring.points[k], &b = ring.points[(k + 1) % ring.points.size()];
      out.push_back({std::min(a, b), std::max(a, b), ring.closed()});
    }
  std::sort(out.begin(), out.end());
  return out;
}

void every_edit_equals_a_fresh_refinement(const RefinementRule& rule, unsigned seed) {
  std::mt19937 rng(seed);
  StarRing outer = star(0, 0, 6, 10, 30, rng), island = star(0.4, -0.2, 3.5, 5.2, 10, rng);
  std::vector<Point2> loose{{5.6, 0.5}, {-5.4, 1}, {0.5, 5.6}};
  std::size_t with_splits = 0;
  auto domain = [&] { return Domain2{{outer.ring(RingRole::Shore), island.ring(RingRole::Island)}}; };
  ShoreRefinement r(domain(), loose, rule);
  std::uniform_real_distribution<double> u(0, 1);
  const int edits = 300;
  for (int step = 0; step < edits; ++step) {
    StarRing& s = u(rng) < 0.7 ? outer : island;
    const std::size_t k = std::size_t(u(rng) * double(s.angle.size())) % s.angle.size();
    const double what = u(rng);
    std::vector<Point2> loose_removed, loose_added;
    if (what < 0.5) {  // move
      s.radius[k] = s.r0 + (s.r1 - s.r0) * u(rng);
    } else if (what < 0.7) {  // add after k
      const double next = k + 1 < s.angle.size() ? s.angle[k + 1] : s.angle[0] + 2 * std::numbers::pi;
      s.angle.insert(s.angle.begin() + long(k) + 1, 0.5 * (s.angle[k] + next));
      s.radius.insert(s.radius.begin() + long(k) + 1, s.r0 + (s.r1 - s.r0) * u(rng));
    } else if (what < 0.85 && s.angle.size() > 6) {  // remove
      s.angle.erase(s.angle.begin() + long(k));
      s.radius.erase(s.radius.begin() + long(k));
    } else {  // a loose point moves
      const std::size_t j = k % loose.size();
      loose_removed.push_back(loose[j]);
      const double a = 2 * std::numbers::pi * u(rng);
      loose[j] = {5.7 * std::cos(a), 5.7 * std::sin(a)};
      loose_added.push_back(loose[j]);
    }
    const std::vector<Point2> before = r.split_points();
    const std::vector<ShoreSegment> segments_before = segments_of(r.refined());
    const SplitChange change = r.update(domain(), loose_removed, loose_added);
    const ShoreRefinement fresh(domain(), loose, rule);
    with_splits += fresh.split_count() > 0;
    ASSERT_EQ(r.split_points(), fresh.split_points()) << "after edit " << step;
    ASSERT_EQ(r.refined().rings.size(), 2u);
    EXPECT_EQ(r.refined().rings[0].points, fresh.refined().rings[0].points) << "after edit " << step;
    // The change is exactly the difference of the split sets.
    const std::vector<Point2> after = fresh.split_points();
    std::vector<Point2> expect_removed, expect_added;
    std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(expect_removed));
    std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(expect_added));
    std::vector<Point2> got_removed = change.removed, got_added = change.added;
    std::sort(got_removed.begin(), got_removed.end());
    std::sort(got_added.begin(), got_added.end());
    ASSERT_EQ(got_removed, expect_removed) << "after edit " << step;
    ASSERT_EQ(got_added, expect_added) << "after edit " << step;
    // And the refined segments it reports are exactly those that went and came (what the mesh takes as
    // its constraints' change: a stale one would stay a constraint).
    const std::vector<ShoreSegment> segments_after = segments_of(fresh.refined());
    std::vector<ShoreSegment> gone, came;
    std::set_difference(segments_before.begin(), segments_before.end(), segments_after.begin(), segments_after.end(),
                        std::back_inserter(gone));
    std::set_difference(segments_after.begin(), segments_after.end(), segments_before.begin(), segments_before.end(),
                        std::back_inserter(came));
    ASSERT_EQ(change.segments.removed, gone) << "after edit " << step;
    ASSERT_EQ(change.segments.added, came) << "after edit " << step;
  }
  EXPECT_GT(with_splits, std::size_t(edits) / 2);  // the edits do reach the splits
}

TEST(ShoreRefinement, EveryEditEqualsAFreshRefinement) { every_edit_equals_a_fresh_refinement(RefinementRule{}, 11); }

// The grading's test region (a point within len/c of an end) is wider than the diametral test's: the
// edits' reset must reach it, with the strongest grading and with none.
TEST(ShoreRefinement, EveryEditEqualsAFreshRefinementWithAndWithoutGrading) {
  every_edit_equals_a_fresh_refinement(graded(2), 12);
  every_edit_equals_a_fresh_refinement(graded(0), 13);
}

}  // namespace
}  // namespace shoremesh
