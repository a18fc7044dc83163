// The mesh after dynamic updates must be the Delaunay mesh of the new point set, and the reported delta
// must be exactly the difference. Points are random doubles: with probability one no four are co-circular
// (no five co-spherical), so the Delaunay mesh is unique and element lists can be compared exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <set>

#include "mesh_test_util.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

using mesh_test::corner_list;
using mesh_test::random_points;

// With `box`, the mesh keeps only the elements whose circumcentre lies in it, before and after each change.
template <int D>
void check_random_changes(std::size_t n, int steps, std::uint32_t seed, std::optional<BoxTransform<D>> box = {}) {
  std::vector<Point<D>> points = random_points<D>(n, seed);
  Mesh<D> mesh(points, n / 2, box);
  mesh.check_valid();
  if (box) {
    ASSERT_GT(mesh.uncovered_count(), 0u);
    ASSERT_EQ(mesh.element_count() + mesh.uncovered_count(), Mesh<D>(points, n / 2).element_count());
  }
  std::mt19937 rng(seed + 1);
  for (int step = 0; step < steps; ++step) {
    // Remove up to 5 current points and add up to 5 new ones (some far outside, growing the hull).
    PointChange<D> change;
    std::shuffle(points.begin(), points.end(), rng);
    const std::size_t k = rng() % 6;
    change.removed.assign(points.end() - static_cast<std::ptrdiff_t>(k), points.end());
    points.resize(points.size() - k);
    auto fresh = random_points<D>(rng() % 6, seed * 1000 + static_cast<std::uint32_t>(step));
    if (step % 7 == 0 && !fresh.empty()) fresh[0][0] += 3;
    change.added = fresh;
    change.added_input_count = fresh.size() / 2;
    points.insert(points.end(), fresh.begin(), fresh.end());

    const auto before = corner_list(mesh);
    const MeshDelta<D> delta = mesh.apply(change);
    mesh.check_valid();
    const auto after = corner_list(mesh);
    ASSERT_EQ(after, corner_list(Mesh<D>(points, 0, box))) << "step " << step << ": not the Delaunay mesh of the points";

    // before - removed + added == after, with removed a subset of before and added disjoint from it.
    std::set<ElementCorners<D>> expected(before.begin(), before.end());
    for (const auto& e : delta.removed) ASSERT_EQ(expected.erase(e), 1u) << "step " << step;
    for (const auto& e : delta.added) ASSERT_TRUE(expected.insert(e).second) << "step " << step;
    ASSERT_EQ(std::vector<ElementCorners<D>>(expected.begin(), expected.end()), after) << "step " << step;
    ASSERT_EQ(mesh.points().size(), points.size());
  }
}

TEST(MeshIncremental, RandomChangesEqualFromScratch2D) { check_random_changes<2>(400, 60, 7); }
TEST(MeshIncremental, RandomChangesEqualFromScratch3D) { check_random_changes<3>(300, 40, 11); }
// A box inside the points' spread, so that many elements change sides of it as points come and go.
TEST(MeshIncremental, RandomChangesClippedToABoxEqualFromScratch2D) {
  check_random_changes<2>(400, 60, 13, BoxTransform<2>{{0.2, 0.25}, 0.5});
}
TEST(MeshIncremental, RandomChangesClippedToABoxEqualFromScratch3D) {
  check_random_changes<3>(300, 40, 17, BoxTransform<3>{{0.2, 0.25, 0.3}, 0.5});
}

TEST(MeshIncremental, GrowsFromFewPointsThroughLowerDimensions2D) {
  Mesh2 mesh(std::vector<Point2>{{0.1, 0.2}}, 1);
  EXPECT_EQ(mesh.element_count(), 0u);
  MeshDelta<2> d = mesh.apply({{}, {{0.9, 0.3}}});
  EXPECT_TRUE(d.empty());
  d = mesh.apply({{}, {{0.4, 0.8}}});  // the first triangle
  ASSERT_EQ(d.added.size(), 1u);
  EXPECT_TRUE(d.removed.empty());
  d = mesh.apply({{{0.9, 0.3}}, {}});  // back to a segment
  EXPECT_EQ(d.removed.size(), 1u);
  EXPECT_EQ(mesh.element_count(), 0u);
  mesh.check_valid();
}

// Removing one point of a full mesh replaces exactly its star: deg(v) triangles go, deg(v) - 2 come.
TEST(MeshIncremental, RemovalChangesOnlyTheStar) {
  std::vector<Point2> points = random_points<2>(500, 3);
  points.push_back({0.5, 0.5});  // surely interior
  Mesh2 mesh(points, points.size());
  std::size_t degree = 0;
  const std::uint32_t centre = static_cast<std::uint32_t>(points.size() - 1);
  for (const auto& e : mesh.elements()) degree += std::count(e.begin(), e.end(), centre);
  const MeshDelta<2> d = mesh.apply({{{0.5, 0.5}}, {}});
  EXPECT_EQ(d.removed.size(), degree);
  EXPECT_EQ(d.added.size(), degree - 2);
  for (const auto& e : d.removed) EXPECT_NE(std::find(e.begin(), e.end(), Point2{0.5, 0.5}), e.end());
}

// A square lake with a triangular island, its sides cut into pieces of 0.05 (the ring points).
Domain2 square_lake_with_island() {
  return mesh_test::subdivide({{Ring{{{0.1, 0.1}, {0.9, 0.1}, {0.9, 0.9}, {0.1, 0.9}}, RingRole::Shore},
                                Ring{{{0.4, 0.4}, {0.6, 0.45}, {0.5, 0.6}}, RingRole::Island}}},
                              0.05);
}

// With a domain, updates keep classifying the new triangles: after random changes of the Steiner points
// the kept triangles are those of a mesh of the new points built from scratch with the same rings.
TEST(MeshIncremental, RandomChangesWithDomainEqualFromScratch) {
  const Domain2 domain = square_lake_with_island();
  std::size_t input_count = 0;
  std::vector<Point2> points = mesh_test::sample_domain(domain, 0.05, 0.02, 31, input_count);
  Mesh2 mesh(points, input_count, domain);
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> u(0, 1);
  for (int step = 0; step < 30; ++step) {
    PointChange<2> change;
    // Remove a few Steiner points (never the ring vertices, which come first) and add a few.
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = input_count + rng() % (points.size() - input_count);
      change.removed.push_back(points[i]);
      points.erase(points.begin() + static_cast<std::ptrdiff_t>(i));
    }
    for (int k = 0; k < 3; ++k) change.added.push_back({u(rng), u(rng)});
    points.insert(points.end(), change.added.begin(), change.added.end());
    const auto before = corner_list(mesh);
    const MeshDelta<2> delta = mesh.apply(change);
    ASSERT_EQ(corner_list(mesh), corner_list(Mesh2(points, input_count, domain))) << "step " << step;
    std::set<ElementCorners<2>> expected(before.begin(), before.end());
    for (const auto& e : delta.removed) ASSERT_EQ(expected.erase(e), 1u);
    for (const auto& e : delta.added) ASSERT_TRUE(expected.insert(e).second);
    ASSERT_EQ(std::vector<ElementCorners<2>>(expected.begin(), expected.end()), corner_list(mesh));
  }
  mesh.check_valid();
}

// Shore edits change the rings too: a ring point moved, inserted or removed, with the rings passed to
// apply. Only the triangles near the changed stretch are classified again; the kept triangles must still
// be those of a mesh built from scratch on the new points and rings, and the delta exactly the change.
// With `box`, also clipped to it: a face's side of the water changes, its circumcentre does not.
void check_ring_edits(std::optional<BoxTransform<2>> box) {
  Domain2 domain = square_lake_with_island();
  std::size_t input_count = 0;
  std::vector<Point2> points = mesh_test::sample_domain(domain, 0.05, 0.02, 41, input_count);
  Mesh2 mesh(points, input_count, domain, box);
  if (box) {
    ASSERT_GT(mesh.uncovered_count(), 0u);
  }
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  auto erase_point = [&](const Point2& p) { points.erase(std::find(points.begin(), points.end(), p)); };
  for (int step = 0; step < 60; ++step) {
    PointChange<2> change;
    Domain2 edited = domain;
    auto& ring = edited.rings[rng() % edited.rings.size()].points;
    const std::size_t k = rng() % ring.size();
    const int kind = step == 59 ? 3 : int(rng() % 3);
    if (kind == 0) {  // move, by up to two ring segments: the old place can lie outside the new stretch's box
      change.removed.push_back(ring[k]);
      ring[k] = {ring[k][0] + 3 * jitter(rng), ring[k][1] + 3 * jitter(rng)};
      change.added.push_back(ring[k]);
    } else if (kind == 1) {  // insert after k, near the middle of the segment
      const Point2& a = ring[k];
      const Point2& b = ring[(k + 1) % ring.size()];
      const Point2 p{(a[0] + b[0]) / 2 + jitter(rng) / 3, (a[1] + b[1]) / 2 + jitter(rng) / 3};
      ring.insert(ring.begin() + static_cast<std::ptrdiff_t>(k + 1), p);
      change.added.push_back(p);
    } else if (kind == 2 && ring.size() > 3) {  // remove
      change.removed.push_back(ring[k]);
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
    } else if (kind == 3) {  // a new ring (a pond): every triangle is classified again
      edited.rings.push_back(Ring{{{0.2, 0.2}, {0.3, 0.2}, {0.25, 0.3}}, RingRole::Shore});
    }
    // The rings must stay valid (constraints never cross): an edit that breaks them is not made.
    if (find_ring_defect(edited)) continue;
    change.added_input_count = change.added.size();
    for (const Point2& p : change.removed) erase_point(p);
    points.insert(points.end(), change.added.begin(), change.added.end());

    const auto before = corner_list(mesh);
    const MeshDelta<2> delta = mesh.apply(change, edited);
    domain = edited;
    mesh.check_valid();
    const auto after = corner_list(mesh);
    ASSERT_EQ(after, corner_list(Mesh2(points, 0, domain, box))) << "step " << step << " (edit kind " << kind << ")";
    std::set<ElementCorners<2>> expected(before.begin(), before.end());
    for (const auto& e : delta.removed) ASSERT_EQ(expected.erase(e), 1u) << "step " << step;
    for (const auto& e : delta.added) ASSERT_TRUE(expected.insert(e).second) << "step " << step;
    ASSERT_EQ(std::vector<ElementCorners<2>>(expected.begin(), expected.end()), after) << "step " << step;
  }
}

TEST(MeshIncremental, RingEditsEqualFromScratch) { check_ring_edits(std::nullopt); }
// A box across the lake, so that the water and the box both cut the mesh.
TEST(MeshIncremental, RingEditsClippedToABoxEqualFromScratch) { check_ring_edits(BoxTransform<2>{{0.3, 0.25}, 0.5}); }

// A point lying inside a ring segment (not a ring vertex: CGAL splits the segment's constraint there) is
// removed: the segment must stay a constraint from end to end, as in a fresh mesh, although a point just
// outside the ring (p) would otherwise take a Delaunay edge across it.
TEST(MeshIncremental, RemovingAPointInsideARingSegmentKeepsTheSegment) {
  const Domain2 domain{{Ring{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, RingRole::Shore}}};
  std::vector<Point2> points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}, {5, 0}, {5, 0.5}, {5, -0.5}, {5, 6}};
  Mesh2 mesh(points, 4, domain);
  PointChange<2> change;
  change.removed.push_back({5, 0});
  points.erase(points.begin() + 4);
  mesh.apply(change);
  mesh.check_valid();
  EXPECT_EQ(corner_list(mesh), corner_list(Mesh2(points, 4, domain)));
  EXPECT_TRUE(mesh.shoreline_crossings().ok());
}

// A ring segment with a point inside it is replaced (its ring gets a vertex off the old line): the whole
// old segment stops being a constraint, not only its part next to the ends, as in a fresh mesh.
TEST(MeshIncremental, DroppingARingSegmentThroughAPointDropsAllOfIt) {
  const Domain2 before{{Ring{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, RingRole::Shore}}};
  const Domain2 after{{Ring{{{0, 0}, {5, -2}, {10, 0}, {10, 10}, {0, 10}}, RingRole::Shore}}};
  std::vector<Point2> points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}, {5, 0}, {2.5, 0.3}, {2.5, -0.3}, {7.5, 0.3}, {7.5, -0.3}, {5, 6}};
  Mesh2 mesh(points, 4, before);
  PointChange<2> change;
  change.added.push_back({5, -2});
  change.added_input_count = 1;
  points.push_back({5, -2});
  mesh.apply(change, after);
  mesh.check_valid();
  EXPECT_EQ(corner_list(mesh), corner_list(Mesh2(points, 4, after)));
}

// Inserting one point changes only the triangles whose circumcircle contained it: all new triangles
// have it as a corner.
TEST(MeshIncremental, InsertionChangesOnlyTheCavity) {
  Mesh2 mesh(random_points<2>(500, 4), 500);
  const MeshDelta<2> d = mesh.apply({{}, {{0.5, 0.5}}});
  EXPECT_EQ(d.added.size(), d.removed.size() + 2);
  for (const auto& e : d.added) EXPECT_NE(std::find(e.begin(), e.end(), Point2{0.5, 0.5}), e.end());
  EXPECT_LT(d.removed.size(), 20u);
}

// A grid is the degenerate case: four points on every circle, so the Delaunay mesh is not unique and the
// diagonal CGAL picks depends on the order of insertion. What does not depend on it is checked: CGAL's
// validity (which includes the empty-circle property), the element count, and the area covered.
TEST(MeshIncremental, CocircularGridStaysDelaunayThroughChanges) {
  std::vector<Point2> grid;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) grid.push_back({i * 0.25, j * 0.25});
  Mesh2 mesh(grid, grid.size());
  EXPECT_EQ(mesh.element_count(), 2u * 19 * 19);
  auto area = [](const Mesh2& m) {
    double a = 0;
    for (const auto& e : m.elements()) {
      const auto &p = m.points()[e[0]], &q = m.points()[e[1]], &r = m.points()[e[2]];
      a += 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
    }
    return a;
  };
  std::mt19937 rng(5);
  std::vector<Point2> present = grid, absent;
  for (int step = 0; step < 40; ++step) {
    PointChange<2> change;
    std::shuffle(present.begin(), present.end(), rng);
    std::shuffle(absent.begin(), absent.end(), rng);
    // Keep the four corners, so the hull (and the area) stays the square.
    for (std::size_t i = 0; i < present.size() && change.removed.size() < 3; ++i) {
      const Point2 p = present[i];
      if ((p[0] == 0 || p[0] == 4.75) && (p[1] == 0 || p[1] == 4.75)) continue;
      change.removed.push_back(p);
    }
    change.added.assign(absent.begin(), absent.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(2, absent.size())));
    for (const auto& p : change.removed) present.erase(std::find(present.begin(), present.end(), p));
    for (const auto& p : change.added) absent.erase(std::find(absent.begin(), absent.end(), p));
    present.insert(present.end(), change.added.begin(), change.added.end());
    absent.insert(absent.end(), change.removed.begin(), change.removed.end());
    const auto before = corner_list(mesh);
    const MeshDelta<2> delta = mesh.apply(change);
    mesh.check_valid();
    // Whatever diagonals were chosen, the delta is exactly what changed.
    std::set<ElementCorners<2>> expected(before.begin(), before.end());
    for (const auto& e : delta.removed) ASSERT_EQ(expected.erase(e), 1u);
    for (const auto& e : delta.added) ASSERT_TRUE(expected.insert(e).second);
    ASSERT_EQ(std::vector<ElementCorners<2>>(expected.begin(), expected.end()), corner_list(mesh));
    const Mesh2 fresh(present, present.size());
    ASSERT_EQ(mesh.element_count(), fresh.element_count()) << "step " << step;
    ASSERT_DOUBLE_EQ(area(mesh), 4.75 * 4.75) << "step " << step;
  }
}

// Exact predicates: scaling by a power of two (exact in floating point) changes no decision, so the
// mesh of the scaled points is the same mesh, element for element.
TEST(MeshIncremental, ScalingByPowersOfTwoKeepsTheMesh) {
  const auto points = random_points<2>(2000, 12);
  const Mesh2 reference(points, points.size());
  for (const double scale : {std::ldexp(1.0, -30), std::ldexp(1.0, 30)}) {
    std::vector<Point2> scaled = points;
    for (auto& p : scaled) p = {p[0] * scale, p[1] * scale};
    EXPECT_EQ(Mesh2(scaled, scaled.size()).elements(), reference.elements()) << "scale " << scale;
  }
}

// The mesh follows the engine through PointChange::from_update (as the edit session and bench_dynamic do):
// after every move it is the mesh of the engine's output, with its input points as such.
template <int D>
void check_engine_moves(std::size_t n, int moves, std::uint32_t seed) {
  WellSpacedSet<D> set;
  set.build(families::uniform<D>(n, seed));
  Mesh<D> mesh(set.output_points(), set.input_count());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::vector<std::size_t> ids = set.input_ids();
  for (int step = 0; step < moves; ++step) {
    const std::size_t id = ids[rng() % ids.size()];
    const Point<D> from = set.input_point(id);
    Point<D> to;
    for (int i = 0; i < D; ++i) to[i] = u(rng);
    UpdateReport<D> report;
    set.move(id, to, &report);
    ASSERT_FALSE(report.steiner_added.empty() && report.steiner_removed.empty()) << "step " << step;
    mesh.apply(PointChange<D>::from_update(report, {from}, {to}));
    const Mesh<D> fresh(set.output_points(), set.input_count());
    ASSERT_EQ(corner_list(mesh), corner_list(fresh)) << "step " << step;
    ASSERT_EQ(std::count(mesh.kinds().begin(), mesh.kinds().end(), PointKind::Input), std::ptrdiff_t(set.input_count()))
        << "step " << step;
  }
}

TEST(MeshIncremental, EngineMovesFollowedThroughTheirReportsEqualAFreshMesh2D) { check_engine_moves<2>(300, 30, 3); }
TEST(MeshIncremental, EngineMovesFollowedThroughTheirReportsEqualAFreshMesh3D) { check_engine_moves<3>(60, 10, 4); }

TEST(MeshIncremental, KeepsInputAndSteinerKinds) {
  Mesh2 mesh(random_points<2>(50, 5), 10);
  PointChange<2> change;
  change.added = {{2, 2}, {-1, 0.5}, {0.5, -1}};
  change.added_input_count = 1;
  mesh.apply(change);
  const auto& pts = mesh.points();
  const auto at = [&](Point2 p) { return mesh.kinds()[std::find(pts.begin(), pts.end(), p) - pts.begin()]; };
  EXPECT_EQ(at({2, 2}), PointKind::Input);
  EXPECT_EQ(at({-1, 0.5}), PointKind::Steiner);
  EXPECT_EQ(std::count(mesh.kinds().begin(), mesh.kinds().end(), PointKind::Input), 11);
}

TEST(MeshIncremental, BadChangeThrowsAndLeavesMeshUnchanged) {
  const auto points = random_points<2>(100, 9);
  Mesh2 mesh(points, 100);
  const auto before = corner_list(mesh);
  EXPECT_THROW(mesh.apply({{{7, 7}}, {}}), InputError);                             // not in the mesh
  EXPECT_THROW(mesh.apply({{points[0]}, {points[1]}}), InputError);                 // already present
  EXPECT_THROW(mesh.apply({{points[0], points[0]}, {}}), InputError);               // removed twice
  EXPECT_THROW(mesh.apply({{}, {{0.5, 0.123}, {0.5, 0.123}}}), InputError);         // added twice
  EXPECT_EQ(corner_list(mesh), before);
  // Removing a point and adding it back in one change is allowed and changes nothing.
  EXPECT_TRUE(mesh.apply({{points[3]}, {points[3]}}).empty());
  EXPECT_EQ(corner_list(mesh), before);
  mesh.check_valid();
}

TEST(MeshIncremental, DuplicateInputPointIsNamed) {
  const std::vector<Point2> pts{{0, 0}, {1, 0}, {0, 1}, {1, 0}};
  try {
    Mesh2 mesh(pts, 4);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("point 3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shoremesh
