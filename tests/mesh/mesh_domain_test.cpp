// A 2D mesh with rings keeps only the water, and its shoreline check says where mesh edges cross a ring.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>

#include "mesh_test_util.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/mesh_water.hpp"

namespace shoremesh {
namespace {

using mesh_test::sample_domain;
using mesh_test::subdivide;

Ring square_ring(double x0, double y0, double x1, double y1, RingRole role) {
  return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, role};
}

double area(const Point2& a, const Point2& b, const Point2& c) {
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

int orient(const Point2& a, const Point2& b, const Point2& c) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  return static_cast<int>(CGAL::orientation(K::Point_2(a[0], a[1]), K::Point_2(b[0], b[1]), K::Point_2(c[0], c[1])));
}

double mesh_area(const Mesh2& mesh) {
  double s = 0;
  for (const auto& e : mesh.elements()) s += area(mesh.points()[e[0]], mesh.points()[e[1]], mesh.points()[e[2]]);
  return s;
}

// The undirected edges of the kept elements, as point index pairs.
std::set<std::pair<std::uint32_t, std::uint32_t>> edge_set(const Mesh2& mesh) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& e : mesh.elements())
    for (int i = 0; i < 3; ++i) edges.insert(std::minmax(e[i], e[(i + 1) % 3]));
  return edges;
}

TEST(MeshDomain, WaterTestUsesEvenOddRuleAndSeesTheRing) {
  Domain2 d{{square_ring(0, 0, 10, 10, RingRole::Shore), square_ring(4, 4, 6, 6, RingRole::Island),
             square_ring(4.5, 4.5, 5.5, 5.5, RingRole::Shore)}};
  const WaterTest w(d);
  EXPECT_EQ(w.classify({1, 1}), WaterSide::Water);
  EXPECT_EQ(w.classify({4.2, 4.2}), WaterSide::Land);
  EXPECT_EQ(w.classify({5, 5}), WaterSide::Water);  // a pond on the island
  EXPECT_EQ(w.classify({11, 5}), WaterSide::Land);
  EXPECT_EQ(w.classify({10, 5}), WaterSide::OnRing);
  EXPECT_EQ(w.classify({6, 4}), WaterSide::OnRing);  // a ring corner
  EXPECT_EQ(w.classify({1e-300, 5}), WaterSide::Water);
  EXPECT_EQ(w.classify({-1e-300, 5}), WaterSide::Land);
}

// A stretch of a ring replaced in place (a shore point moved, removed or added, the first and the last
// vertex included) answers every query as a test built afresh on the new rings does.
TEST(MeshDomain, WaterTestWithAStretchReplacedEqualsAFreshOne) {
  std::vector<Point2> shore, island;
  for (int i = 0; i < 40; ++i) {
    const double t = 2 * 3.141592653589793 * i / 40, r = 10 + 2 * std::sin(3 * t);
    shore.push_back({r * std::cos(t), r * std::sin(t)});
  }
  for (int i = 0; i < 8; ++i) island.push_back({3 + std::cos(-0.785 * i), std::sin(-0.785 * i)});
  Domain2 domain{{{shore, RingRole::Shore}, {island, RingRole::Island}}};
  WaterTest kept(domain);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 300; ++k) {
    Domain2 next = domain;
    auto& ring = next.rings[0].points;
    // Vertices 0 and n - 1 often: the stretch then wraps around the ring's start.
    const std::size_t v = k % 5 == 0 ? 0 : k % 5 == 1 ? ring.size() - 1 : rng() % ring.size();
    std::size_t prefix = v, suffix = ring.size() - v - 1;
    if (k % 3 == 0 && ring.size() > 10) {
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(v));
      suffix = ring.size() - v;
    } else if (k % 3 == 1) {
      ring.insert(ring.begin() + static_cast<std::ptrdiff_t>(v), {ring[v][0] + 0.3 * u(rng), ring[v][1] + 0.3 * u(rng)});
      suffix = ring.size() - v - 2;
      prefix = v;
      if (v + 2 > ring.size()) suffix = 0;
    } else {
      ring[v] = {ring[v][0] + 0.5 * u(rng), ring[v][1] + 0.5 * u(rng)};
    }
    kept.replace_stretch(0, domain.rings[0].points, ring, prefix, suffix);
    domain = next;
    const WaterTest fresh(domain);
    for (int q = 0; q < 200; ++q) {
      const Point2 p = q < 40 ? domain.rings[0].points[std::size_t(q) % ring.size()]  // on the ring
                              : Point2{13 * u(rng), 13 * u(rng)};
      ASSERT_EQ(kept.classify(p), fresh.classify(p)) << "edit " << k << ", query " << q;
    }
  }
}

TEST(MeshDomain, KeepsOnlyTheWaterBetweenShoreAndIsland) {
  const Domain2 domain = subdivide({{square_ring(0, 0, 10, 10, RingRole::Shore),
                                     square_ring(4, 4, 6, 6, RingRole::Island)}}, 0.5);
  std::size_t input_count = 0;
  const auto points = sample_domain(domain, 0.5, 0.2, 1, input_count);
  const Mesh2 mesh(points, input_count, domain);
  const ShorelineReport shore = mesh.shoreline_crossings();
  ASSERT_TRUE(shore.ok()) << shore.summary();
  EXPECT_EQ(shore.segments, 80u + 16u);
  EXPECT_NEAR(mesh_area(mesh), 100.0 - 4.0, 1e-9);
  const WaterTest water(domain);
  for (const auto& e : mesh.elements()) {
    const auto& p = mesh.points();
    const Point2 c{(p[e[0]][0] + p[e[1]][0] + p[e[2]][0]) / 3, (p[e[0]][1] + p[e[1]][1] + p[e[2]][1]) / 3};
    EXPECT_FALSE(c[0] > 4 && c[0] < 6 && c[1] > 4 && c[1] < 6) << "element on the island";
    EXPECT_TRUE(c[0] > 0 && c[0] < 10 && c[1] > 0 && c[1] < 10) << "element outside the shore";
  }
  // The box fill outside the shore is meshed by Delaunay but not kept.
  EXPECT_LT(mesh.element_count(), Mesh2(points, input_count).element_count());
}

// Real data: the double_hex PSLG (a rectangle with two hexagonal holes), its segments sampled at h. The
// shoreline check must agree with a brute-force look at the element edges, and the PSLG's hole points
// must be on land.
TEST(MeshShoreline, DoubleHexAgreesWithEdgeSet) {
  const Domain2 rings = mesh_test::rings_from_poly(mesh_test::samples("pslg/double_hex.poly"));
  ASSERT_EQ(rings.rings.size(), 3u);
  const WaterTest rings_water(rings);
  for (const Point2 hole : {Point2{0.25, 0.75}, Point2{0.6, 0.4}}) EXPECT_EQ(rings_water.classify(hole), WaterSide::Land);
  EXPECT_EQ(rings_water.classify({0.05, 0.05}), WaterSide::Water);

  // Fine: rings subdivided at h, grid points kept 0.6 h away. Coarse: the rings as given (segments up to
  // 0.1 long) and grid points up to 0.005 from them, which encroach on the segments (a Delaunay mesh
  // would cross them).
  for (const bool fine : {true, false}) {
    const double h = fine ? 0.01 : 0.05;
    const Domain2 domain = fine ? subdivide(rings, h) : rings;
    std::size_t input_count = 0;
    const auto points = sample_domain(domain, h, fine ? 0.6 * h : 0.005, 2, input_count);
    const Mesh2 mesh(points, input_count, domain);
    mesh.check_valid();
    const ShorelineReport report = mesh.shoreline_crossings();
    const auto edges = edge_set(mesh);
    std::map<Point2, std::uint32_t> index;
    for (std::uint32_t i = 0; i < mesh.points().size(); ++i) index[mesh.points()[i]] = i;
    std::size_t covered = 0, segments = 0;
    for (const Ring& r : domain.rings)
      for (std::size_t i = 0; i < r.points.size(); ++i, ++segments)
        covered += edges.count(std::minmax(index.at(r.points[i]), index.at(r.points[(i + 1) % r.points.size()])));
    EXPECT_EQ(report.segments, segments) << "fine = " << fine;
    EXPECT_EQ(report.covered, covered) << "fine = " << fine;
    // Each uncovered segment against all edges of the full Delaunay mesh: the proper crossings (exact
    // orientation signs) and their depth must be what the walk found.
    const auto all_edges = edge_set(Mesh2(points, input_count));
    const auto& q = mesh.points();
    for (const auto& issue : report.issues) {
      std::size_t crossings = 0;
      double depth = 0;
      for (const auto& [i, j] : all_edges) {
        if (orient(issue.a, issue.b, q[i]) * orient(issue.a, issue.b, q[j]) < 0 &&
            orient(q[i], q[j], issue.a) * orient(q[i], q[j], issue.b) < 0) {
          ++crossings;
          depth = std::max(depth, std::min(mesh_test::distance_to_segment(q[i], issue.a, issue.b),
                                           mesh_test::distance_to_segment(q[j], issue.a, issue.b)));
        }
      }
      EXPECT_GT(issue.crossing_edges, 0u);
      EXPECT_EQ(issue.crossing_edges, crossings);
      EXPECT_NEAR(issue.depth, depth, 1e-15);
    }
    if (report.ok()) {
      // No element crosses a ring, so the kept triangles tile the water exactly: the even-odd sum of the
      // rings' areas, each signed by how many other rings enclose it.
      double water_area = 0;
      for (std::size_t i = 0; i < domain.rings.size(); ++i) {
        const auto& r = domain.rings[i].points;
        double a = 0;
        for (std::size_t k = 0; k < r.size(); ++k) a += area({0, 0}, r[k], r[(k + 1) % r.size()]);
        int depth = 0;
        for (std::size_t j = 0; j < domain.rings.size(); ++j)
          depth += j != i && WaterTest(Domain2{{domain.rings[j]}}).in_water(r[0]);
        water_area += (depth % 2 ? -1 : 1) * std::abs(a);
      }
      EXPECT_NEAR(mesh_area(mesh), water_area, 1e-9) << "fine = " << fine;
    }
    // The ring segments are constraints: even grid points 0.005 from 0.1-long segments leave them edges.
    EXPECT_TRUE(report.ok()) << "fine = " << fine << ": " << report.summary();
  }
}

// One island segment encroached by a water point: the Delaunay edge from that point to the island's tip
// would cross the segment; as a constraint the segment stays a mesh edge, and the water is exactly the
// square less the island.
TEST(MeshShoreline, EncroachedSegmentStaysAMeshEdge) {
  const Domain2 domain{{subdivide({{square_ring(0, 0, 10, 10, RingRole::Shore)}}, 1).rings[0],
                        Ring{{{3, 5}, {7, 5}, {5, 5.5}}, RingRole::Island}}};
  std::vector<Point2> points;
  for (const Ring& r : domain.rings) points.insert(points.end(), r.points.begin(), r.points.end());
  const std::size_t input_count = points.size();
  points.push_back({5, 4});
  const Mesh2 mesh(points, input_count, domain);
  mesh.check_valid();
  const ShorelineReport report = mesh.shoreline_crossings();
  EXPECT_EQ(report.segments, 43u);
  EXPECT_EQ(report.covered, 43u);
  EXPECT_TRUE(report.ok()) << report.summary();
  // The Delaunay mesh of the same points crosses the island's base: the constraint is what keeps it.
  EXPECT_FALSE(Mesh2(points, input_count, Domain2{}).elements().empty());
  std::set<std::pair<Point2, Point2>> edges;
  for (const auto& e : mesh.elements())
    for (int i = 0; i < 3; ++i) edges.insert(std::minmax(mesh.points()[e[i]], mesh.points()[e[(i + 1) % 3]]));
  EXPECT_TRUE(edges.count(std::minmax(Point2{3, 5}, Point2{7, 5})));
  EXPECT_NEAR(mesh_area(mesh), 100 - 0.5 * 4 * 0.5, 1e-12);
}

TEST(MeshShoreline, RingPointMissingFromMeshIsReportedWithDistance) {
  const Domain2 domain{{square_ring(0, 0, 4, 4, RingRole::Shore)}};
  const std::vector<Point2> points{{0, 0}, {4, 0}, {4, 4}, {0, 3}, {2, 2}};  // (0, 4) is missing, (0, 3) is 1 away
  const Mesh2 mesh(points, 4, domain);
  const ShorelineReport report = mesh.shoreline_crossings();
  ASSERT_EQ(report.issues.size(), 2u) << report.summary();  // the two segments at (0, 4)
  for (const auto& issue : report.issues) {
    EXPECT_TRUE(issue.endpoint_missing);
    EXPECT_DOUBLE_EQ(issue.depth, 1.0);
  }
}

}  // namespace
}  // namespace shoremesh
