// `shoremesh info`, `shoremesh bench`, and several inputs at once.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <regex>

#include "cli_test_util.hpp"
#include "shoremesh/io/point_set_csv.hpp"

namespace shoremesh::cli_test {
namespace {

using ::testing::HasSubstr;

TEST(InfoCommand, ImageTrackAndPointSet) {
  TempDir dir;
  const RunResult image = shoremesh(dir, "info " + quote(superior_mask()) + " --largest-water");
  ASSERT_EQ(image.code, 0) << image.err;
  EXPECT_THAT(image.out, HasSubstr(": image"));
  // lon/lat input: a transverse Mercator centred on the data, with its scale over the data said.
  EXPECT_THAT(image.out, HasSubstr("local transverse Mercator at 47.732699N 88.250000W (WGS84), scale 1.00000 .. 1.00132"));
  EXPECT_THAT(image.out, ::testing::ContainsRegex("[0-9]+ rings \\([0-9]+ shore, [0-9]+ island"));
  EXPECT_THAT(image.out, ::testing::ContainsRegex("water area: .* = 8[0-9]{4}(\\.[0-9]+)? km\\^2"));

  const RunResult gpx = shoremesh(dir, "info " + quote(samples("cerknica/cerknicko-jezero.gpx")));
  ASSERT_EQ(gpx.code, 0) << gpx.err;
  EXPECT_THAT(gpx.out, HasSubstr("GPX"));
  EXPECT_THAT(gpx.out, HasSubstr("local transverse Mercator at 45.769452N 14.353633E"));
  EXPECT_THAT(gpx.out, ::testing::ContainsRegex("45\\.[0-9]+N 14\\.[0-9]+E"));

  write_file(dir / "p.csv", random_points(100, 10, 10, 9));
  ASSERT_EQ(shoremesh(dir, "mesh -q p.csv -o ws.csv").code, 0);
  const RunResult set = shoremesh(dir, "info ws.csv");
  ASSERT_EQ(set.code, 0) << set.err;
  EXPECT_THAT(set.out, HasSubstr("well-spaced point set (2D)"));
  std::smatch m;
  ASSERT_TRUE(std::regex_search(set.out, m, std::regex("bound met by ([0-9]+) of ([0-9]+) covered"))) << set.out;
  EXPECT_EQ(m[1], m[2]);
  EXPECT_NE(m[1], "0");

  const RunResult plain = shoremesh(dir, "info p.csv");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_THAT(plain.out, HasSubstr("input: 100 2D points; map units"));
}

TEST(MeshCommand, SeveralInputsKeepTheirOrderAndMustAgreeOnUnits) {
  TempDir dir;
  write_file(dir / "a.csv", random_points(30, 10, 10, 1));
  write_file(dir / "b.csv", random_points(20, 10, 10, 2));
  const RunResult r = shoremesh(dir, "mesh a.csv b.csv -o ab.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto ab = io::read_point_set_csv<2>(dir / "ab.csv");
  ASSERT_EQ(shoremesh(dir, "mesh a.csv -o a_only.csv").code, 0);
  const auto a = io::read_point_set_csv<2>(dir / "a_only.csv");
  for (std::size_t i = 0; i < 30; ++i) EXPECT_EQ(ab.points[i], a.points[i]);
  EXPECT_THAT(r.out, HasSubstr("input: 50 2D points"));

  // An image in metres and a point file in map units do not mix.
  const RunResult mixed = shoremesh(dir, "mesh " + quote(superior_mask()) + " a.csv -o mixed.msh");
  EXPECT_EQ(mixed.code, 1);
  EXPECT_THAT(mixed.err, HasSubstr("a.csv"));
  EXPECT_FALSE(fs::exists(dir / "mixed.msh"));
}

TEST(BenchCommand, PrintsTheBenchmarkLine) {
  TempDir dir;
  const RunResult r = shoremesh(dir, "bench --n 2000 --dim 2 --repeats 1 --verify");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("algo=stablews dim=2 family=uniform n=2000 seed=1 repeats=1 output_vertices="));
  EXPECT_THAT(r.out, HasSubstr("verify=ok"));
  EXPECT_THAT(r.out, HasSubstr("| dim | n | output vertices |"));
}

}  // namespace
}  // namespace shoremesh::cli_test
