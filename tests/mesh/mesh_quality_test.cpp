// The quality report: exact shape values on known elements, the rho bound on a well-spaced set, and the
// worst elements found where they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "mesh_test_util.hpp"
#include "shoremesh/mesh.hpp"

namespace shoremesh {
namespace {

TEST(MeshQuality, EquilateralTriangleAndRegularTetrahedronShapes) {
  const ElementShape<2> t = element_shape<2>({{{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}}});
  EXPECT_NEAR(t.min_angle, 60, 1e-9);
  EXPECT_NEAR(t.max_angle, 60, 1e-9);
  EXPECT_NEAR(t.radius_edge, 1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(t.circumcentre[1], std::sqrt(3.0) / 6, 1e-12);

  const ElementShape<3> r = element_shape<3>({{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}});
  EXPECT_NEAR(r.min_angle, std::acos(1.0 / 3) * 180 / std::numbers::pi, 1e-9);  // 70.53 degrees
  EXPECT_NEAR(r.max_angle, r.min_angle, 1e-9);
  EXPECT_NEAR(r.radius_edge, std::sqrt(6.0) / 4, 1e-12);
  for (double x : r.circumcentre) EXPECT_NEAR(x, 0, 1e-12);

  const ElementShape<2> right = element_shape<2>({{{0, 0}, {2, 0}, {0, 1}}});
  EXPECT_NEAR(right.max_angle, 90, 1e-9);
  EXPECT_NEAR(right.radius_edge, std::sqrt(5.0) / 2, 1e-12);  // R = sqrt 5 / 2, shortest edge 1
}

// A jittered triangular lattice is well-spaced for rho = sqrt 2, so every triangle whose circumcentre is
// in the box must have radius-edge <= sqrt 2, hence minimum angle >= 20.7 degrees.
TEST(MeshQuality, WellSpacedLatticeMeetsRhoBound) {
  const auto points = mesh_test::jittered_lattice(1.0, 0.04, 0.08, 4);
  const Mesh2 mesh(points, points.size());
  const QualityReport<2> q = mesh.quality(std::sqrt(2.0));
  EXPECT_EQ(q.elements, mesh.element_count());
  EXPECT_NEAR(q.min_angle_bound, 20.7048, 1e-4);
  EXPECT_GT(q.covered, q.elements * 9 / 10);
  EXPECT_EQ(q.covered_meeting_bound, q.covered) << q.summary();
  EXPECT_LE(q.covered_max_radius_edge, std::sqrt(2.0));
  EXPECT_EQ(std::accumulate(q.min_angle_histogram.counts.begin(), q.min_angle_histogram.counts.end(), std::size_t{0}),
            q.elements);
  // Recheck the covered elements one by one: none has an angle below arcsin(1 / (2 sqrt 2)).
  const auto box = std::span<const Point2>(mesh.points());
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
  for (const auto& p : box) lo_x = std::min(lo_x, p[0]), hi_x = std::max(hi_x, p[0]), lo_y = std::min(lo_y, p[1]), hi_y = std::max(hi_y, p[1]);
  std::size_t covered = 0;
  for (const auto& e : mesh.elements()) {
    const auto s = element_shape<2>({mesh.points()[e[0]], mesh.points()[e[1]], mesh.points()[e[2]]});
    const auto& c = s.circumcentre;
    if (c[0] < lo_x || c[0] > hi_x || c[1] < lo_y || c[1] > hi_y) continue;
    ++covered;
    EXPECT_GE(s.min_angle, q.min_angle_bound);
  }
  EXPECT_EQ(covered, q.covered);
  for (std::size_t i = 1; i < q.worst.size(); ++i)
    EXPECT_GE(q.worst[i - 1].shape.radius_edge, q.worst[i].shape.radius_edge);
}

// Two points 0.0005 apart in a lattice of spacing 0.1 (a set that is not well-spaced): the triangles on
// that short edge have radius-edge ratios near 100 and are reported among the worst, where they are.
TEST(MeshQuality, BadElementsAreReportedWithLocation) {
  auto points = mesh_test::jittered_lattice(1.0, 0.1, 0.05, 5);
  points.insert(points.end(), {{0.5012, 0.5031}, {0.5017, 0.5031}});
  const Mesh2 mesh(points, points.size());
  const QualityReport<2> q = mesh.quality(std::sqrt(2.0));
  ASSERT_FALSE(q.worst.empty());
  // The lattice's hull has flat triangles too (uncovered by the guarantee); the sliver must be among the worst.
  const auto sliver = std::find_if(q.worst.begin(), q.worst.end(), [](const WorstElement<2>& w) {
    return std::hypot(w.shape.centroid[0] - 0.5, w.shape.centroid[1] - 0.5) < 0.1;
  });
  ASSERT_NE(sliver, q.worst.end()) << q.summary();
  EXPECT_GT(sliver->shape.radius_edge, 20.0);
  EXPECT_TRUE(sliver->covered);  // inside the lattice: a broken guarantee, not a boundary effect
  EXPECT_LT(sliver->shape.min_angle, 2.0);
  EXPECT_LT(q.covered_meeting_bound, q.covered);
  EXPECT_NE(q.summary().find("element"), std::string::npos);
}

TEST(MeshQuality, Report3DCountsDihedralAnglesAndBins) {
  const auto points = mesh_test::random_points<3>(400, 8);
  const Mesh3 mesh(points, points.size());
  const QualityReport<3> q = mesh.quality(2.0);
  EXPECT_EQ(q.elements, mesh.element_count());
  EXPECT_GT(q.min_angle, 0.0);
  EXPECT_LT(q.max_angle, 180.0);
  EXPECT_LE(q.min_angle, 70.53);  // no tetrahedron beats the regular one's smallest dihedral angle
  EXPECT_EQ(q.min_angle_bound, 0.0);
  EXPECT_EQ(std::accumulate(q.radius_edge_histogram.counts.begin(), q.radius_edge_histogram.counts.end(),
                            std::size_t{0}),
            q.elements);
  EXPECT_EQ(q.worst.size(), 10u);
  EXPECT_EQ(q.worst[0].shape.radius_edge, q.max_radius_edge);
}

}  // namespace
}  // namespace shoremesh
