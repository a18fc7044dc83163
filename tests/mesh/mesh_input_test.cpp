// A mesh's points must be finite and pairwise distinct: the build names the first offending point (the
// duplicates are looked for only once the triangulation merged some, so both paths are pinned here).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/mesh.hpp"

namespace shoremesh {
namespace {

template <int D, class... Extra>
std::string build_error(const std::vector<Point<D>>& points, const Extra&... extra) {
  try {
    Mesh<D> mesh(points, points.size(), extra...);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshInput, NamesTheFirstRepeatedPoint) {
  const std::vector<Point2> points{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {1, 0}, {0, 1}};
  const std::string what = build_error<2>(points);
  EXPECT_NE(what.find("point 4 (1.000000, 0.000000) repeats point 1"), std::string::npos) << what;
}

TEST(MeshInput, NamesTheFirstRepeatedPointWithRings) {
  Domain2 domain;
  domain.rings.push_back(Ring{{{0, 0}, {4, 0}, {4, 4}, {0, 4}}});
  const std::vector<Point2> points{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {2, 2}, {1, 3}, {2, 2}};
  const std::string what = build_error<2>(points, domain);
  EXPECT_NE(what.find("point 6 (2.000000, 2.000000) repeats point 4"), std::string::npos) << what;
}

TEST(MeshInput, NamesTheFirstRepeatedPoint3) {
  const std::vector<Point3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};
  const std::string what = build_error<3>(points);
  EXPECT_NE(what.find("point 4 (0.000000, 0.000000, 0.000000) repeats point 0"), std::string::npos) << what;
}

TEST(MeshInput, ANonFinitePointBeforeARepeatIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Point2> points{{0, 0}, {1, 0}, {nan, 1}, {0, 0}};
  const std::string what = build_error<2>(points);
  EXPECT_NE(what.find("point 2 is not finite"), std::string::npos) << what;
}

TEST(MeshInput, ARepeatBeforeANonFinitePointIsNamed) {
  const std::vector<Point2> points{{0, 0}, {1, 0}, {0, 0}, {std::numeric_limits<double>::infinity(), 1}};
  const std::string what = build_error<2>(points);
  EXPECT_NE(what.find("point 2 (0.000000, 0.000000) repeats point 0"), std::string::npos) << what;
}

TEST(MeshInput, DistinctPointsBuild) {
  const std::vector<Point2> points{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  Mesh2 mesh(points, points.size());
  mesh.check_valid();
  EXPECT_EQ(mesh.element_count(), 2u);
}

}  // namespace
}  // namespace shoremesh
