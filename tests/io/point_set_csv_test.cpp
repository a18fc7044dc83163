// The well-spaced point-set CSV round-trips exactly, and a malformed one is refused naming file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "shoremesh/error.hpp"
#include "shoremesh/io/point_set_csv.hpp"

namespace shoremesh::io {
namespace {

std::filesystem::path scratch(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "shoremesh_point_set_csv_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

TEST(PointSetCsv, RoundTripIsBitExact) {
  const BoxTransform<2> box{{-0.1, 1e-300}, 3.0000000000000004};
  const std::vector<Point<2>> points{{0.1, 1.0 / 3.0}, {2.5e-17, 123456.789}};
  const auto path = scratch("round.csv", "");
  write_point_set_csv<2>(path, box, points);
  const auto back = read_point_set_csv<2>(path);
  EXPECT_EQ(back.points, points);
  EXPECT_EQ(back.box.origin, box.origin);
  EXPECT_EQ(back.box.side, box.side);
}

void expect_error_at(const std::string& text, std::size_t line, const std::string& words) {
  const auto path = scratch("bad.csv", text);
  try {
    read_point_set_csv<2>(path);
    FAIL() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), std::optional<std::size_t>(line)) << e.what();
    EXPECT_EQ(e.file(), path.string());
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(PointSetCsv, MalformedFilesNameTheLine) {
  expect_error_at("# box 0 0 1\n0.5,abc\n", 2, "not a number");
  expect_error_at("# box 0 0 1\n0.5,0.5,0.5\n", 2, "comma-separated");
  expect_error_at("# box 0 0 1\n0.5\n", 2, "comma-separated");
  expect_error_at("# box 0 0 1\n0.5,nan\n", 2, "finite");
  expect_error_at("# box 0 1\n", 1, "box line");
  EXPECT_THROW(read_point_set_csv<2>(scratch("nobox.csv", "0.5,0.5\n")), InputError);
  EXPECT_THROW(read_point_set_csv<2>(scratch("missing", "") / "none.csv"), InputError);
}

}  // namespace
}  // namespace shoremesh::io
