// The independent verifier must pass what is well-spaced and fail what is not, at the right vertex.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "shoremesh/error.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/verify.hpp"

namespace shoremesh {
namespace {

// k^D points at the cell centres (i + 1/2) * h, h = side / k, lowest index varying fastest.
template <int D>
std::vector<Point<D>> cell_centred_grid(int k, double side) {
  std::vector<Point<D>> points;
  const double h = side / k;
  int total = 1;
  for (int a = 0; a < D; ++a) total *= k;
  for (int i = 0; i < total; ++i) {
    Point<D> p;
    int rest = i;
    for (int a = 0; a < D; ++a) {
      p[a] = (rest % k + 0.5) * h;
      rest /= k;
    }
    points.push_back(p);
  }
  return points;
}

constexpr BoxTransform<2> kUnitSquare{{0, 0}, 1};
constexpr BoxTransform<3> kUnitCube{{0, 0, 0}, 1};

TEST(Verifier, CellCentredGridIsWellSpacedWithRatioOneOverSqrt2) {
  // Spacing 1/8 (exact in binary): every cell is the h-square around its point, farthest at h / sqrt 2.
  const auto grid = cell_centred_grid<2>(8, 1.0);
  const auto report = verify_well_spaced(grid, grid, kUnitSquare, std::sqrt(2.0));
  EXPECT_TRUE(report.ok());
  EXPECT_EQ(report.vertex_count, 64u);
  EXPECT_EQ(report.rho_squared, 2.0);
  EXPECT_EQ(report.violations, 0u);
  EXPECT_NEAR(report.worst_ratio, std::sqrt(0.5), 1e-15);
  EXPECT_TRUE(report.input_contained);
  EXPECT_EQ(report.duplicate_points, 0u);
  // lfs of a grid point is its nearest input neighbour, which is also its output nearest neighbour.
  EXPECT_EQ(report.worst_size_conformity, 1.0);
}

TEST(Verifier, GridRatioIsDecidedExactlyAtOneHalf) {
  // The squared ratio of every grid cell is exactly 1/2: a bound of exactly 1/2 passes (the ball is
  // closed), the next double below fails every vertex.
  const auto grid = cell_centred_grid<2>(8, 1.0);
  const auto at = verify_well_spaced(grid, grid, kUnitSquare, std::sqrt(0.5), 0.5);
  EXPECT_EQ(at.violations, 0u);
  const auto below = verify_well_spaced(grid, grid, kUnitSquare, std::sqrt(0.5), std::nextafter(0.5, 0.0));
  EXPECT_EQ(below.violations, 64u);
  EXPECT_FALSE(below.ok());
}

TEST(Verifier, GridWithPointsOnTheBoxBoundary) {
  // Points i/8, i = 0..8: boundary cells are half or quarter squares, still farthest at h / sqrt 2.
  std::vector<Point2> grid;
  for (int j = 0; j <= 8; ++j)
    for (int i = 0; i <= 8; ++i) grid.push_back({i / 8.0, j / 8.0});
  const auto report = verify_well_spaced(grid, grid, kUnitSquare, std::sqrt(2.0));
  EXPECT_TRUE(report.ok());
  EXPECT_EQ(report.outside_box, 0u);
  EXPECT_NEAR(report.worst_ratio, std::sqrt(0.5), 1e-15);
  const auto below = verify_well_spaced(grid, grid, kUnitSquare, std::sqrt(0.5), std::nextafter(0.5, 0.0));
  EXPECT_EQ(below.violations, grid.size());
}

TEST(Verifier, EmptyQuarterOfTheBoxFailsAtTheCornerPoint) {
  // The 8x8 grid of spacing h = 1/8 fills [0,1]^2 but the box is [0,2]^2. Points in the last column or
  // row have cells reaching the far box faces (15 violations); the corner point (15/16, 15/16) owns the
  // quadrant up to (2, 2): squared ratio 2 (17/16)^2 / (1/8)^2 = 144.5, the unique worst.
  const auto grid = cell_centred_grid<2>(8, 1.0);
  const auto report = verify_well_spaced(grid, grid, BoxTransform<2>{{0, 0}, 2}, std::sqrt(2.0));
  EXPECT_FALSE(report.ok());
  EXPECT_EQ(report.violations, 15u);
  EXPECT_EQ(report.worst_vertex, 63u);
  EXPECT_EQ(grid[report.worst_vertex], (Point2{15.0 / 16, 15.0 / 16}));
  EXPECT_NEAR(report.worst_ratio, std::sqrt(144.5), 1e-13);
}

TEST(Verifier, CollinearOutputUsesItsDelaunayEdges) {
  // Three points on y = 1/2: the cells are vertical strips; the end strips [0, 3/8] and [5/8, 1] are
  // farthest at the box corners, squared ratio (1/16 + 1/4) / (1/16) = 5; the first index wins the tie.
  const std::vector<Point2> line{{0.25, 0.5}, {0.5, 0.5}, {0.75, 0.5}};
  const auto report = verify_well_spaced(line, line, kUnitSquare, std::sqrt(2.0));
  EXPECT_EQ(report.violations, 3u);
  EXPECT_EQ(report.worst_vertex, 0u);
  EXPECT_NEAR(report.worst_ratio, std::sqrt(5.0), 1e-15);
}

TEST(Verifier, MissingInputPointIsReported) {
  const auto grid = cell_centred_grid<2>(8, 1.0);
  auto input = grid;
  input.push_back({0.3, 0.3});
  // One ulp away is not the input point: the engine must hand input back bit for bit.
  input.push_back({std::nextafter(grid[5][0], 1.0), grid[5][1]});
  const auto report = verify_well_spaced(grid, input, kUnitSquare, std::sqrt(2.0));
  EXPECT_FALSE(report.input_contained);
  EXPECT_EQ(report.missing_input, 2u);
  EXPECT_EQ(report.violations, 0u);
  EXPECT_FALSE(report.ok());
}

TEST(Verifier, DuplicateOutputPointIsReported) {
  auto output = cell_centred_grid<2>(8, 1.0);
  output.push_back(output[10]);
  const auto report = verify_well_spaced(output, output, kUnitSquare, std::sqrt(2.0));
  EXPECT_EQ(report.duplicate_points, 1u);
  EXPECT_EQ(report.vertex_count, 65u);
  EXPECT_EQ(report.violations, 0u);  // the cells are rated on the distinct points
  EXPECT_FALSE(report.ok());
}

TEST(Verifier, PointOutsideTheBoxIsReported) {
  auto output = cell_centred_grid<2>(8, 1.0);
  output.push_back({1.0625, 0.5});
  const auto report = verify_well_spaced(output, output, kUnitSquare, std::sqrt(2.0));
  EXPECT_EQ(report.outside_box, 1u);
  EXPECT_FALSE(report.ok());
}

TEST(Verifier, SizeConformityIsSecondNearestInputOverNearestOutput) {
  // Input a = (1/4, 1/2), b = (3/4, 1/2), one Steiner point s between them: lfs(a) = |ab| = 1/2 and
  // NN(a) = 1/4, ratio 2; lfs(s) = 1/4 = NN(s), ratio 1.
  const std::vector<Point2> input{{0.25, 0.5}, {0.75, 0.5}};
  const std::vector<Point2> output{{0.25, 0.5}, {0.75, 0.5}, {0.5, 0.5}};
  const auto report = verify_well_spaced(output, input, kUnitSquare, std::sqrt(2.0));
  EXPECT_EQ(report.worst_size_conformity, 2.0);
  EXPECT_EQ(report.worst_size_vertex, 0u);
  // A single input point has no second-nearest input point: lfs is infinite, nothing to bound.
  const std::vector<Point2> single{{0.25, 0.5}};
  EXPECT_EQ(verify_well_spaced(output, single, kUnitSquare, std::sqrt(2.0)).worst_size_conformity, 0.0);
}

TEST(Verifier, RejectsNonFinitePointsAndBadBounds) {
  const std::vector<Point2> bad{{0.5, std::numeric_limits<double>::quiet_NaN()}};
  EXPECT_THROW(verify_well_spaced(bad, {}, kUnitSquare, std::sqrt(2.0)), InputError);
  const auto grid = cell_centred_grid<2>(2, 1.0);
  EXPECT_THROW(verify_well_spaced(grid, grid, kUnitSquare, 0.0), ParameterError);
  EXPECT_THROW(verify_well_spaced(grid, grid, BoxTransform<2>{{0, 0}, -1}, std::sqrt(2.0)), ParameterError);
}

TEST(Verifier, CubicGridIsWellSpacedWithRatioHalfSqrt3) {
  // Cubic cells of side h around each point: farthest corner at h sqrt(3) / 2.
  const auto grid = cell_centred_grid<3>(8, 1.0);
  const auto report = verify_well_spaced(grid, grid, kUnitCube, std::sqrt(2.0));
  EXPECT_TRUE(report.ok());
  EXPECT_EQ(report.vertex_count, 512u);
  EXPECT_NEAR(report.worst_ratio, std::sqrt(3.0) / 2, 1e-9);
  EXPECT_EQ(report.worst_size_conformity, 1.0);
  // Just below the true ratio, every vertex fails.
  EXPECT_EQ(verify_well_spaced(grid, grid, kUnitCube, std::sqrt(3.0) / 2 * (1 - 1e-6)).violations, 512u);
}

TEST(Verifier, CubicGridWithPointsOnTheBoxFaces) {
  // Points i/8, i = 0..8: a cell on a face starts flat against the wall (the box clipped at the point).
  std::vector<Point3> grid;
  for (int k = 0; k <= 8; ++k)
    for (int j = 0; j <= 8; ++j)
      for (int i = 0; i <= 8; ++i) grid.push_back({i / 8.0, j / 8.0, k / 8.0});
  const auto report = verify_well_spaced(grid, grid, kUnitCube, std::sqrt(2.0));
  EXPECT_TRUE(report.ok());
  EXPECT_NEAR(report.worst_ratio, std::sqrt(3.0) / 2, 1e-9);
  EXPECT_EQ(verify_well_spaced(grid, grid, kUnitCube, std::sqrt(3.0) / 2 * (1 - 1e-6)).violations, grid.size());
}

TEST(Verifier, CubicGridInADoubleSizedBoxFailsAtTheCornerPoint) {
  // As in 2D: the grid fills [0,1]^3 of the box [0,2]^3; the corner point (15/16)^3 owns the octant up
  // to (2,2,2): ratio sqrt(3) (17/16) / (1/8) = 8.5 sqrt(3). Points on the three far faces fail: 8^3 - 7^3.
  const auto grid = cell_centred_grid<3>(8, 1.0);
  const auto report = verify_well_spaced(grid, grid, BoxTransform<3>{{0, 0, 0}, 2}, std::sqrt(2.0));
  EXPECT_EQ(report.violations, 512u - 343u);
  EXPECT_EQ(report.worst_vertex, 511u);
  EXPECT_NEAR(report.worst_ratio, 8.5 * std::sqrt(3.0), 1e-8);
}

template <int D>
void expect_close_pair_fails_at_the_pair() {
  // Two points 1e-9 apart among points about 0.1 apart: the pair's cells reach ~1e8 times their NN. The
  // 3D cells are cut in a frame scaled by NN, so voro++ keeps them; the pair is where the check fails.
  const auto points = families::close_pair<D>(500, 1e-9, 1);
  BoxTransform<D> unit;
  unit.origin.fill(0);
  unit.side = 1;
  const auto report = verify_well_spaced(points, points, unit, std::sqrt(2.0));
  EXPECT_GT(report.violations, 0u);
  EXPECT_LT(report.worst_vertex, 2u);  // families::close_pair puts the pair first
  EXPECT_GT(report.worst_ratio, 1e7);
}

TEST(Verifier, ClosePairFailsAtThePair2D) { expect_close_pair_fails_at_the_pair<2>(); }
TEST(Verifier, ClosePairFailsAtThePair3D) { expect_close_pair_fails_at_the_pair<3>(); }

// The cell of v by brute force: every D-tuple of the half-spaces (bisectors with all other points, box
// faces) meets in a candidate vertex; the feasible ones span Vor(v) ∩ box. Returns the worst ratio.
template <int D>
double brute_force_worst_ratio(const std::vector<Point<D>>& points, std::size_t* worst_vertex) {
  struct HalfSpace {
    std::array<double, D> a;
    double b;  // a . x <= b
  };
  double worst = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& v = points[i];
    std::vector<HalfSpace> h;
    double nn = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (j == i) continue;
      HalfSpace s{};
      double dist = 0;
      for (int k = 0; k < D; ++k) {
        s.a[k] = 2 * (points[j][k] - v[k]);
        s.b += points[j][k] * points[j][k] - v[k] * v[k];
        dist += (points[j][k] - v[k]) * (points[j][k] - v[k]);
      }
      nn = std::min(nn, std::sqrt(dist));
      h.push_back(s);
    }
    for (int k = 0; k < D; ++k) {
      HalfSpace up{}, down{};
      up.a[k] = 1, up.b = 1, down.a[k] = -1, down.b = 0;
      h.push_back(up);
      h.push_back(down);
    }
    auto det2 = [](double a, double b, double c, double d) { return a * d - b * c; };
    auto consider = [&](const std::array<double, D>& x) {
      for (const auto& s : h) {
        double lhs = 0;
        for (int k = 0; k < D; ++k) lhs += s.a[k] * x[k];
        if (lhs > s.b + 1e-12) return;
      }
      double d = 0;
      for (int k = 0; k < D; ++k) d += (x[k] - v[k]) * (x[k] - v[k]);
      if (std::sqrt(d) / nn > worst) {
        worst = std::sqrt(d) / nn;
        *worst_vertex = i;
      }
    };
    for (std::size_t p = 0; p < h.size(); ++p)
      for (std::size_t q = p + 1; q < h.size(); ++q) {
        if constexpr (D == 2) {
          const double det = det2(h[p].a[0], h[p].a[1], h[q].a[0], h[q].a[1]);
          if (std::abs(det) < 1e-14) continue;
          consider({det2(h[p].b, h[p].a[1], h[q].b, h[q].a[1]) / det, det2(h[p].a[0], h[p].b, h[q].a[0], h[q].b) / det});
        } else {
          for (std::size_t r = q + 1; r < h.size(); ++r) {
            const auto &A = h[p].a, &B = h[q].a, &C = h[r].a;
            auto det3 = [&](const std::array<double, 3>& c0, const std::array<double, 3>& c1, const std::array<double, 3>& c2) {
              return c0[0] * (c1[1] * c2[2] - c1[2] * c2[1]) - c1[0] * (c0[1] * c2[2] - c0[2] * c2[1]) +
                     c2[0] * (c0[1] * c1[2] - c0[2] * c1[1]);
            };
            // Columns of the matrix with rows A, B, C; Cramer's rule.
            const std::array<double, 3> col0{A[0], B[0], C[0]}, col1{A[1], B[1], C[1]}, col2{A[2], B[2], C[2]},
                rhs{h[p].b, h[q].b, h[r].b};
            const double det = det3(col0, col1, col2);
            if (std::abs(det) < 1e-14) continue;
            consider({det3(rhs, col1, col2) / det, det3(col0, rhs, col2) / det, det3(col0, col1, rhs) / det});
          }
        }
      }
  }
  return worst;
}

template <int D>
void expect_matches_brute_force(std::size_t n, std::uint64_t seed) {
  const auto points = families::uniform<D>(n, seed);
  BoxTransform<D> unit;
  unit.origin.fill(0);
  unit.side = 1;
  std::size_t expected_vertex = 0;
  const double expected = brute_force_worst_ratio<D>(points, &expected_vertex);
  const auto report = verify_well_spaced(points, points, unit, std::sqrt(2.0));
  EXPECT_NEAR(report.worst_ratio, expected, 1e-9 * expected);
  EXPECT_EQ(report.worst_vertex, expected_vertex);
}

TEST(Verifier, MatchesBruteForceCellsOnRandomPoints2D) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) expect_matches_brute_force<2>(60, seed);
}

TEST(Verifier, MatchesBruteForceCellsOnRandomPoints3D) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) expect_matches_brute_force<3>(30, seed);
}

// Random points on a 2^-20 lattice, so that scaling by 2^±30 and shifting stay exact in doubles.
template <int D>
std::vector<Point<D>> lattice_points(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::vector<Point<D>> points(n);
  for (auto& p : points)
    for (double& x : p) x = static_cast<double>(random() >> 44) * 0x1.0p-20;
  return points;
}

template <int D>
std::vector<Point<D>> transformed(const std::vector<Point<D>>& points, double scale, double shift) {
  auto out = points;
  for (auto& p : out)
    for (double& x : p) x = x * scale + shift;
  return out;
}

template <int D>
void expect_same_under_rescaling(const std::vector<Point<D>>& points) {
  BoxTransform<D> unit;
  unit.origin.fill(0);
  unit.side = 1;
  const auto reference = verify_well_spaced(points, points, unit, std::sqrt(2.0));
  ASSERT_GT(reference.violations, 0u);  // random points are far from well-spaced: a meaningful comparison
  // 2^30 ≈ 1.07e9 shifted by 1e9; 2^-30 ≈ 9.3e-10 shifted by 3 * 2^-30 ≈ 2.8e-9 (both exact).
  for (const auto& [scale, shift] : {std::pair{0x1.0p30, 1e9}, std::pair{0x1.0p-30, 3 * 0x1.0p-30}}) {
    BoxTransform<D> box;
    box.origin.fill(shift);
    box.side = scale;
    const auto copy = transformed<D>(points, scale, shift);
    const auto report = verify_well_spaced(copy, copy, box, std::sqrt(2.0));
    EXPECT_EQ(report.violations, reference.violations) << "scale " << scale;
    EXPECT_EQ(report.worst_vertex, reference.worst_vertex) << "scale " << scale;
    // Each ratio is within a relative 1e-12 of the true one, which the copies share.
    EXPECT_NEAR(report.worst_ratio, reference.worst_ratio, 2e-12 * reference.worst_ratio) << "scale " << scale;
    EXPECT_NEAR(report.worst_size_conformity, reference.worst_size_conformity,
                2e-12 * reference.worst_size_conformity) << "scale " << scale;
  }
}

TEST(Verifier, RescaledAndShiftedCopiesGiveTheSameRatios2D) { expect_same_under_rescaling<2>(lattice_points<2>(3000, 7)); }

TEST(Verifier, RescaledAndShiftedCopiesGiveTheSameRatios3D) { expect_same_under_rescaling<3>(lattice_points<3>(3000, 7)); }

}  // namespace
}  // namespace shoremesh
