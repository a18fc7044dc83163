#include "shoremesh/domain.hpp"
#include "shoremesh/engine/predicates.hpp"
#include "shoremesh/ring_edge_index.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "io_test_names.hpp"
#include "shoremesh/io/input_set.hpp"

namespace {

__extension__ typedef __int128 int128;  // GCC/Clang extension, exact 2x64-bit products

int exact_int128_sign(long long ax, long long ay, long long bx, long long by, long long cx, long long cy) {
  const int128 d = static_cast<int128>(ax - cx) * (by - cy) - static_cast<int128>(ay - cy) * (bx - cx);
  return (d > 0) - (d < 0);
}

Domain2 domain_of(std::vector<std::vector<Point2>> rings) {
  Domain2 d;
  for (auto& r : rings) d.rings.push_back({std::move(r), RingRole::Shore});
  return d;
}

}  // namespace

TEST(ExactOrient, MatchesInt128OnNearlyCollinearPoints) {
  // Integer coordinates below 2^52 are exact doubles and their determinant fits in 128 bits; scaling by 2^-40
  // keeps everything exact. Nearly collinear triples defeat plain double evaluation.
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<long long> coord(-(1LL << 50), 1LL << 50), small(-3, 3);
  int naive_wrong = 0;
  shoremesh::engine::PredicateCounters counters;
  for (int i = 0; i < 200000; ++i) {
    const long long ax = coord(rng), ay = coord(rng), bx = coord(rng), by = coord(rng);
    // c near the line ab, between a and b.
    const long long cx = ax + (bx - ax) / 3 + small(rng), cy = ay + (by - ay) / 3 + small(rng);
    const double s = std::ldexp(1.0, -40);
    const Point2 a{ax * s, ay * s}, b{bx * s, by * s}, c{cx * s, cy * s};
    const int expect = exact_int128_sign(ax, ay, bx, by, cx, cy);
    ASSERT_EQ(shoremesh::engine::orient2d(counters, a, b, c), expect) << i;
    const double naive = (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
    naive_wrong += ((naive > 0) - (naive < 0)) != expect;
  }
  EXPECT_GT(naive_wrong, 0) << "the test should include cases plain doubles get wrong";
  std::printf("plain double orientation wrong in %d of 200000 near-collinear cases; exact: 0\n", naive_wrong);
}

TEST(RingCheck, ValidNestedRingsPassAndGetRolesByNesting) {
  auto d = domain_of({{{0, 0}, {10, 0}, {10, 10}, {0, 10}},
                      {{2, 2}, {2, 8}, {8, 8}, {8, 2}},
                      {{4, 4}, {6, 4}, {6, 6}, {4, 6}},
                      {{20, 0}, {30, 0}, {25, 5}}});
  EXPECT_FALSE(find_ring_defect(d).has_value());
  assign_roles_by_nesting(d);
  EXPECT_EQ(d.rings[0].role, RingRole::Shore);
  EXPECT_EQ(d.rings[1].role, RingRole::Island);
  EXPECT_EQ(d.rings[2].role, RingRole::Shore);  // a pond on the island
  EXPECT_EQ(d.rings[3].role, RingRole::Shore);
}

TEST(RingCheck, BowTieIsReported) {
  const auto defect = find_ring_defect(domain_of({{{0, 0}, {10, 10}, {10, 0}, {0, 10}}}));
  ASSERT_TRUE(defect.has_value());
  EXPECT_EQ(defect->kind, RingDefect::Kind::Intersection);
  EXPECT_EQ(defect->describe(), "ring 1 edge 1-2 crosses its own ring 1 edge 3-4");
}

TEST(RingCheck, TouchingRingsAndVertexOnEdgeAreReported) {
  // An island whose vertex lies exactly on the shore's edge.
  EXPECT_TRUE(find_ring_defect(domain_of({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{5, 0}, {6, 2}, {4, 2}}})).has_value());
  // A spike folding back along its own edge.
  EXPECT_TRUE(find_ring_defect(domain_of({{{0, 0}, {10, 0}, {5, 0}, {5, 5}}})).has_value());
  // Crossing rings.
  EXPECT_TRUE(find_ring_defect(domain_of({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{5, 5}, {15, 5}, {15, 6}}})).has_value());
}

TEST(RingCheck, TooFewPointsAndRepeatedVertex) {
  auto d = find_ring_defect(domain_of({{{0, 0}, {1, 0}}}));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->kind, RingDefect::Kind::TooFewPoints);
  d = find_ring_defect(domain_of({{{0, 0}, {1, 0}, {1, 0}, {0, 1}}}));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->kind, RingDefect::Kind::RepeatedVertex);
}

TEST(RingCheck, CheckRingsNamesFileAndLine) {
  InputSet set;
  set.sources.push_back({"lake.poly", Source::Location::Line});
  const std::vector<Point2> ring{{0, 0}, {10, 10}, {10, 0}, {0, 10}};
  set.ring_ids.push_back({0, 1, 2, 3});
  for (std::size_t i = 0; i < ring.size(); ++i) {
    set.points.push_back(ring[i]);
    set.origins.push_back({0, 0, 20 + i});
  }
  set.domain.rings.push_back({ring, RingRole::Shore});
  const auto e = shoremesh::io::test::expect_input_error([&] { check_rings(set); });
  EXPECT_EQ(e.file(), "lake.poly");
  EXPECT_EQ(e.line(), 20u);
  EXPECT_THAT(e.message(), HasSubstr("self-intersecting rings: ring 1 edge 1-2 crosses its own ring 1 edge 3-4 (at lake.poly:22"));
}

TEST(RingCheck, AValidRingOf200000EdgesHasNoDefect) {
  // A 200,000-vertex star-shaped ring.
  std::vector<Point2> ring;
  for (int i = 0; i < 200000; ++i) {
    const double t = 2 * 3.141592653589793 * i / 200000, r = 1000 + 10 * std::sin(50 * t);
    ring.push_back({r * std::cos(t), r * std::sin(t)});
  }
  EXPECT_FALSE(find_ring_defect(domain_of({ring})).has_value());
}

// The check of one edited vertex finds a defect exactly when the whole check does, for moves (small and
// large, so that many cross) and removals of vertices of a wavy lake with two islands.
TEST(RingCheck, IndexedCheckAtAnEditedVertexAgreesWithTheWholeCheckThroughAnEditSequence) {
  std::vector<Point2> shore, island, islet;
  for (int i = 0; i < 60; ++i) {
    const double t = 2 * 3.141592653589793 * i / 60, r = 100 + 15 * std::sin(5 * t);
    shore.push_back({r * std::cos(t), r * std::sin(t)});
  }
  for (int i = 0; i < 12; ++i) {
    const double t = -2 * 3.141592653589793 * i / 12;
    island.push_back({30 + 15 * std::cos(t), 10 * std::sin(t)});
    islet.push_back({-40 + 8 * std::cos(t), 20 + 8 * std::sin(t)});
  }
  // The edits that pass are committed, so the index is checked as an edit session keeps it: through a
  // sequence of moves, removals and insertions, against the whole check of the rings as they are.
  Domain2 lake = domain_of({shore, island, islet});
  ASSERT_FALSE(find_ring_defect(lake).has_value());
  RingEdgeIndex index(lake);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int defects = 0, valid = 0;
  std::array<int, 3> kinds{};  // accepted edits of each kind
  for (int k = 0; k < 3000; ++k) {
    Domain2 d = lake;
    RingVertexEdit edit;
    edit.ring = rng() % 3;
    auto& ring = d.rings[edit.ring].points;
    const std::size_t v = rng() % ring.size();
    edit.gone = ring[v];
    edit.vertex = v;
    if (k % 10 == 9 && ring.size() > 6) {
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(v));
      edit.kind = RingVertexEdit::Kind::Remove;
      edit.vertex = (v + ring.size() - 1) % ring.size();
    } else if (k % 10 == 4 || k % 10 == 7) {  // a vertex inserted near the middle of edge v -> v + 1
      const Point2 a = ring[v], b = ring[(v + 1) % ring.size()];
      const double reach = k % 10 == 4 ? 2 : 40;
      ring.insert(ring.begin() + static_cast<std::ptrdiff_t>(v + 1),
                  Point2{(a[0] + b[0]) / 2 + reach * u(rng), (a[1] + b[1]) / 2 + reach * u(rng)});
      edit.kind = RingVertexEdit::Kind::Insert;
      edit.vertex = v + 1;
    } else {
      const double reach = k % 4 == 0 ? 80 : 8;
      ring[v] = {ring[v][0] + reach * u(rng), ring[v][1] + reach * u(rng)};
    }
    const auto whole = find_ring_defect(d);
    const auto local = index.defect_at(d, edit);
    ASSERT_EQ(local.has_value(), whole.has_value()) << "edit " << k << (whole ? ": " + whole->describe() : "");
    if (local) {
      // One of its two edges is at the changed vertex.
      const std::size_t n = ring.size(), before = (edit.vertex + n - 1) % n;
      auto at_vertex = [&](std::size_t r, std::size_t e) { return r == edit.ring && (e == before || e == edit.vertex); };
      EXPECT_TRUE(at_vertex(local->ring_a, local->vertex_a) || at_vertex(local->ring_b, local->vertex_b))
          << "edit " << k << ": " << local->describe();
      ++defects;
      continue;
    }
    index.commit(d, edit);
    lake = std::move(d);
    std::size_t edges = 0;
    for (const auto& r : lake.rings) edges += r.points.size();
    ASSERT_EQ(index.size(), edges) << "edit " << k;
    ++valid;
    ++kinds[std::size_t(edit.kind)];
  }
  EXPECT_GT(defects, 300);  // both outcomes were really tried
  EXPECT_GT(valid, 300);
  EXPECT_GT(kinds[std::size_t(RingVertexEdit::Kind::Remove)], 30);
  EXPECT_GT(kinds[std::size_t(RingVertexEdit::Kind::Insert)], 100);
}

// A ring added whole (an island an edit session adds): the index's check of the new ring finds exactly
// the defect the whole check finds; once added and later removed, the index holds exactly the rings' edges;
// and its even-odd test agrees with counting the rings that contain the point.
TEST(RingCheck, IndexedCheckOfANewRingAgreesWithTheWholeCheckAndItsWaterTestWithTheRings) {
  std::vector<Point2> shore;
  for (int i = 0; i < 60; ++i) {
    const double t = 2 * 3.141592653589793 * i / 60, r = 100 + 15 * std::sin(5 * t);
    shore.push_back({r * std::cos(t), r * std::sin(t)});
  }
  Domain2 lake = domain_of({shore});
  RingEdgeIndex index(lake);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int defects = 0, added = 0, removed = 0;
  for (int k = 0; k < 2000; ++k) {
    if (k % 7 == 6 && lake.rings.size() > 1) {  // a ring goes (its place kept, as a session keeps it)
      const std::size_t r = 1 + rng() % (lake.rings.size() - 1);
      if (lake.rings[r].points.empty()) continue;
      index.erase_ring(r, lake.rings[r]);
      lake.rings[r].points.clear();
      ++removed;
    } else {  // a hexagon of random size somewhere around the lake, often crossing something
      const Point2 c{130 * u(rng), 130 * u(rng)};
      const double radius = 2 + 20 * std::abs(u(rng));
      std::vector<Point2> hexagon;
      for (int i = 0; i < 6; ++i)
        hexagon.push_back({c[0] + radius * std::cos(1.0471975511965976 * i), c[1] + radius * std::sin(1.0471975511965976 * i)});
      if (k % 13 == 0) std::swap(hexagon[1], hexagon[3]);  // a bow tie
      Domain2 after = lake;
      after.rings.push_back({hexagon, RingRole::Shore});
      const std::size_t r = after.rings.size() - 1;
      // The whole check of the live rings, numbered as the session numbers them.
      Domain2 live;
      std::vector<std::size_t> number;
      for (std::size_t s = 0; s < after.rings.size(); ++s)
        if (!after.rings[s].points.empty()) live.rings.push_back(after.rings[s]), number.push_back(s);
      auto whole = find_ring_defect(live);
      const auto local = index.defect_of_new_ring(after, r);
      ASSERT_EQ(local.has_value(), whole.has_value()) << "ring " << k << (whole ? ": " + whole->describe() : "");
      if (local) {
        whole->ring_a = number[whole->ring_a], whole->ring_b = number[whole->ring_b];
        EXPECT_EQ(local->describe(), whole->describe()) << "ring " << k;
        ++defects;
        continue;
      }
      index.insert_ring(r, Ring{hexagon, RingRole::Shore});
      lake = std::move(after);
      ++added;
    }
    std::size_t edges = 0;
    for (const auto& ring : lake.rings) edges += ring.points.size();
    ASSERT_EQ(index.size(), edges) << "step " << k;
    for (int q = 0; q < 20; ++q) {
      const Point2 p{140 * u(rng), 140 * u(rng)};
      int containing = 0;
      for (const auto& ring : lake.rings) containing += !ring.points.empty() && ring_contains(ring.points, p);
      ASSERT_EQ(index.inside(p), containing % 2 == 1) << "step " << k << " at " << p[0] << "," << p[1];
    }
  }
  EXPECT_GT(defects, 100);
  EXPECT_GT(added, 20);
  EXPECT_GT(removed, 10);
}

TEST(InputSetMerge, SameProjectionRequiredAndOriginsRenumbered) {
  InputSet a, b;
  a.units = b.units = Units::Metres;
  a.projection = b.projection = Projection::utm_ups(33, true);
  a.sources.push_back({"a.gpx", Source::Location::Line});
  a.points = {{0, 0}, {1, 0}};
  a.origins = {{0, PointOrigin::kNoRing, 3}, {0, PointOrigin::kNoRing, 4}};
  b.sources.push_back({"b.csv", Source::Location::Line});
  b.points = {{5, 5}};
  b.origins = {{0, PointOrigin::kNoRing, 9}};
  const auto m = merge({a, b});
  ASSERT_EQ(m.points.size(), 3u);
  EXPECT_EQ(describe_origin(m, 2), "b.csv:9");
  b.points = {{1, 0}};
  auto e = shoremesh::io::test::expect_input_error([&] { merge({a, b}); });
  EXPECT_EQ(e.message(), "duplicate point: b.csv:9 repeats a.gpx:4");
  b.projection = Projection::utm_ups(34, true);
  e = shoremesh::io::test::expect_input_error([&] { merge({a, b}); });
  EXPECT_THAT(e.message(), HasSubstr("different projections"));
  EXPECT_EQ(e.file(), "b.csv");
}
