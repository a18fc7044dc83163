// The mesh clipped to the engine's box: the circumcentre test is exact (against CGAL's exact
// constructions, where a circumcentre computed in doubles errs), and the clipped mesh of a well-spaced
// set meets the radius-edge bound everywhere, which the whole Delaunay mesh does not.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <cmath>
#include <limits>
#include <random>

#include "shoremesh/error.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/mesh_coverage.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double up(double x) { return std::nextafter(x, kInf); }
double down(double x) { return std::nextafter(x, -kInf); }

// Right corners at the origin: the circumcentre is the midpoint of the far side, (x, 1[, 1]) exactly,
// with x = 1 + 2^-52 one ulp above 1.
TEST(MeshCoverage, ACircumcentreOnTheBoxSideIsInsideAndOneUlpBeyondIsOutside) {
  const double x = up(1.0);
  const ElementCorners<2> t = {{{0, 0}, {2 * x, 0}, {0, 2}}};
  EXPECT_TRUE(circumcentre_in_box<2>(t, Point2{x, 0}, Point2{3, 3}));
  EXPECT_FALSE(circumcentre_in_box<2>(t, Point2{up(x), 0}, Point2{3, 3}));
  EXPECT_TRUE(circumcentre_in_box<2>(t, Point2{0, 0}, Point2{x, 3}));
  EXPECT_FALSE(circumcentre_in_box<2>(t, Point2{0, 0}, Point2{down(x), 3}));
  EXPECT_FALSE(circumcentre_in_box<2>(t, Point2{0, up(1.0)}, Point2{3, 3}));

  const ElementCorners<3> s = {{{0, 0, 0}, {2 * x, 0, 0}, {0, 2, 0}, {0, 0, 2}}};
  EXPECT_TRUE(circumcentre_in_box<3>(s, Point3{x, 1, 1}, Point3{x, 1, 1}));  // a box of one point
  EXPECT_FALSE(circumcentre_in_box<3>(s, Point3{up(x), 0, 0}, Point3{3, 3, 3}));
  EXPECT_FALSE(circumcentre_in_box<3>(s, Point3{0, 0, 0}, Point3{3, 3, down(1.0)}));
  // A flat element has no circumcentre.
  EXPECT_FALSE(circumcentre_in_box<2>({{{0, 0}, {1, 1}, {2, 2}}}, Point2{-kInf, -kInf}, Point2{kInf, kInf}));
}

// Random triangles and tetrahedra with the box's side put within a few ulps of the exact circumcentre:
// the answer must be the exact one. The circumcentre computed in doubles gets some of them wrong, so
// these cases are the ones that need the exact test.
TEST(MeshCoverage, AgreesWithExactConstructionsNearTheSides2D) {
  using EK = CGAL::Exact_predicates_exact_constructions_kernel;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coordinate(0, 1);
  int double_construction_wrong = 0, cases = 0;
  for (int trial = 0; trial < 400; ++trial) {
    ElementCorners<2> t;
    for (auto& p : t) p = {coordinate(rng), coordinate(rng)};
    const EK::Point_2 c = CGAL::circumcenter(EK::Point_2(t[0][0], t[0][1]), EK::Point_2(t[1][0], t[1][1]),
                                             EK::Point_2(t[2][0], t[2][1]));
    const ElementShape<2> shape = element_shape<2>(t);  // the circumcentre in doubles
    for (int axis = 0; axis < 2; ++axis) {
      const EK::FT exact = axis == 0 ? c.x() : c.y();
      double side = CGAL::to_double(exact);
      for (int k = 0; k < 3; ++k) side = down(side);
      for (int k = 0; k < 7; ++k, side = up(side)) {
        Point2 lo = {-kInf, -kInf}, hi = {kInf, kInf};
        lo[axis] = side;
        const bool truth = EK::FT(side) <= exact;
        ASSERT_EQ(circumcentre_in_box<2>(t, lo, hi), truth) << "trial " << trial << " axis " << axis;
        hi[axis] = side;
        lo[axis] = -kInf;
        ASSERT_EQ(circumcentre_in_box<2>(t, lo, hi), exact <= EK::FT(side)) << "trial " << trial << " axis " << axis;
        double_construction_wrong += (side <= shape.circumcentre[axis]) != truth;
        ++cases;
      }
    }
  }
  EXPECT_GT(double_construction_wrong, 0) << "of " << cases << ": the test did not reach the hard cases";
}

TEST(MeshCoverage, AgreesWithExactConstructionsNearTheSides3D) {
  using EK = CGAL::Exact_predicates_exact_constructions_kernel;
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> coordinate(0, 1);
  int double_construction_wrong = 0;
  for (int trial = 0; trial < 200; ++trial) {
    ElementCorners<3> s;
    for (auto& p : s) p = {coordinate(rng), coordinate(rng), coordinate(rng)};
    auto ep = [](const Point3& p) { return EK::Point_3(p[0], p[1], p[2]); };
    const EK::Point_3 c = CGAL::circumcenter(ep(s[0]), ep(s[1]), ep(s[2]), ep(s[3]));
    const ElementShape<3> shape = element_shape<3>(s);
    for (int axis = 0; axis < 3; ++axis) {
      const EK::FT exact = c[axis];
      double side = CGAL::to_double(exact);
      for (int k = 0; k < 3; ++k) side = down(side);
      for (int k = 0; k < 7; ++k, side = up(side)) {
        Point3 lo = {-kInf, -kInf, -kInf}, hi = {kInf, kInf, kInf};
        lo[axis] = side;
        const bool truth = EK::FT(side) <= exact;
        ASSERT_EQ(circumcentre_in_box<3>(s, lo, hi), truth) << "trial " << trial << " axis " << axis;
        double_construction_wrong += (side <= shape.circumcentre[axis]) != truth;
      }
    }
  }
  EXPECT_GT(double_construction_wrong, 0);
}

// StableWS output: clipped to its box, every element meets radius-edge <= rho; the elements left out
// are exactly what the whole Delaunay mesh has beyond, and some of those are far worse.
template <int D>
void check_clipped_mesh_meets_the_bound(std::size_t n, std::uint64_t seed) {
  const auto input = families::uniform<D>(n, seed);
  const StableResult<D> result = stable_well_spaced<D>(input);
  const double rho = Parameters<D>{}.rho;
  const Mesh<D> clipped(result.points, result.input_count, result.box);
  const Mesh<D> whole(result.points, result.input_count);
  ASSERT_GT(clipped.uncovered_count(), 0u);
  EXPECT_EQ(clipped.element_count() + clipped.uncovered_count(), whole.element_count());
  EXPECT_EQ(whole.uncovered_count(), 0u);
  const QualityReport<D> q = clipped.quality(rho, result.box);
  EXPECT_EQ(q.elements, clipped.element_count());
  EXPECT_EQ(q.covered, q.elements);
  EXPECT_LE(q.max_radius_edge, rho * (1 + 1e-12)) << q.summary();
  const QualityReport<D> w = whole.quality(rho, result.box);
  EXPECT_EQ(w.covered, q.elements);  // the report's covered elements are the ones the mesh keeps
  EXPECT_GT(w.max_radius_edge, 10 * rho) << "the whole mesh has no sliver along the box: a weak test";
}

// A box that clips nothing sensibly (no size, infinite, NaN) is refused, not turned into an empty mesh.
TEST(MeshCoverage, ABoxWithoutAFiniteSizeIsRefused) {
  const std::vector<Point2> points = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const BoxTransform<2>& box : {BoxTransform<2>{{0, 0}, 0}, BoxTransform<2>{{0, 0}, -1}, BoxTransform<2>{{0, 0}, kInf},
                                     BoxTransform<2>{{nan, 0}, 1}, BoxTransform<2>{{0, -kInf}, 1}})
    EXPECT_THROW(Mesh2(points, 4, box), InputError) << box.origin[0] << " " << box.origin[1] << " " << box.side;
  EXPECT_EQ(Mesh2(points, 4, BoxTransform<2>{{0, 0}, 1}).element_count(), 2u);
}

TEST(MeshCoverage, ClippedMeshOfAWellSpacedSetMeetsTheBound2D) { check_clipped_mesh_meets_the_bound<2>(500, 3); }
TEST(MeshCoverage, ClippedMeshOfAWellSpacedSetMeetsTheBound3D) { check_clipped_mesh_meets_the_bound<3>(200, 4); }

}  // namespace
}  // namespace shoremesh
