#include "shoremesh/io/point_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io_test_names.hpp"

TEST(PointFile, CsvWithHeaderCommentsAndBlankLines) {
  const auto pf = parse_point_file_text("# a comment\n\nx,y\n0.5, 1.25  # trailing\n\n-2,3e2\r\n", "pts.csv");
  ASSERT_EQ(pf.dimension, 2);
  ASSERT_EQ(pf.points2.size(), 2u);
  EXPECT_EQ(pf.points2[0], (Point2{0.5, 1.25}));
  EXPECT_EQ(pf.points2[1], (Point2{-2.0, 300.0}));
  EXPECT_EQ(pf.lines, (std::vector<std::size_t>{4, 6}));
  EXPECT_TRUE(pf.points3.empty());
}

TEST(PointFile, WhitespaceThreeColumnsGoTo3D) {
  const auto pf = parse_point_file_text("1 2 3\n\t4\t5  6\n+7 8 -9\n", "pts.xyz");
  ASSERT_EQ(pf.dimension, 3);
  ASSERT_EQ(pf.points3.size(), 3u);
  EXPECT_EQ(pf.points3[2], (Point3{7, 8, -9}));
  EXPECT_TRUE(pf.points2.empty());
}

TEST(PointFile, TextInNumberColumnNamesFileAndLine) {
  const auto e = expect_input_error([] { parse_point_file_text("0 0\n1 1\n1.5abc 2\n", "bad.txt"); });
  EXPECT_EQ(e.file(), "bad.txt");
  EXPECT_EQ(e.line(), 3u);
  EXPECT_THAT(e.what(), HasSubstr("bad.txt:3"));
  EXPECT_THAT(e.message(), HasSubstr("\"1.5abc\" is not a number"));
}

TEST(PointFile, HeaderOnlyAllowedFirst) {
  const auto e = expect_input_error([] { parse_point_file_text("x,y\n1,2\nx,y\n", "h.csv"); });
  EXPECT_EQ(e.line(), 3u);
  // A first line mixing names and numbers is not a header but a bad record.
  const auto e2 = expect_input_error([] { parse_point_file_text("x,2\n1,2\n", "h2.csv"); });
  EXPECT_EQ(e2.line(), 1u);
}

TEST(PointFile, WrongColumnCount) {
  const auto e = expect_input_error([] { parse_point_file_text("1 2\n1 2 3 4\n", "c.txt"); });
  EXPECT_EQ(e.line(), 2u);
  EXPECT_THAT(e.message(), HasSubstr("4 columns"));
  const auto e1 = expect_input_error([] { parse_point_file_text("7\n", "c1.txt"); });
  EXPECT_EQ(e1.line(), 1u);
}

TEST(PointFile, MixedTwoAndThreeColumns) {
  const auto e = expect_input_error([] { parse_point_file_text("1 2\n3 4\n5 6 7\n", "m.txt"); });
  EXPECT_EQ(e.line(), 3u);
  EXPECT_THAT(e.message(), HasSubstr("mixed"));
}

TEST(PointFile, NanAndInfAreNotFinite) {
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "infinity", "1e999"}) {
    const auto e = expect_input_error([&] { parse_point_file_text(std::string("0 0\n1 ") + bad + "\n", "f.txt"); });
    EXPECT_EQ(e.line(), 2u) << bad;
    EXPECT_THAT(e.message(), HasSubstr("not a finite number")) << bad;
  }
}

TEST(PointFile, DuplicateNamesBothLines) {
  const auto e = expect_input_error([] { parse_point_file_text("0 0\n1 1\n2 2\n# c\n5 5\n6 6\n1 1\n", "d.txt"); });
  EXPECT_EQ(e.line(), 7u);
  EXPECT_EQ(e.message(), "duplicate point: line 7 repeats line 2");
}

TEST(PointFile, DuplicateIn3DAndSignedZero) {
  const auto e = expect_input_error([] { parse_point_file_text("0 0 0\n1 1 1\n-0 0 0\n", "d3.txt"); });
  EXPECT_EQ(e.message(), "duplicate point: line 3 repeats line 1");
}

TEST(PointFile, EmptyFileHasNoPoints) {
  for (const char* text : {"", "\n\n", "# only comments\n", "x,y\n"}) {
    const auto e = expect_input_error([&] { parse_point_file_text(text, "empty.csv"); });
    EXPECT_EQ(e.message(), "no points") << '"' << text << '"';
    EXPECT_EQ(e.file(), "empty.csv");
  }
}

TEST(PointFile, EmptyCsvFieldIsAnError) {
  const auto e = expect_input_error([] { parse_point_file_text("1,,2\n", "e.csv"); });
  EXPECT_EQ(e.line(), 1u);
}

TEST(PointFile, ReadsFromDiskAndMissingFileIsAnInputError) {
  shoremesh::io::test::ScratchDir dir;
  const auto path = dir.write("p.csv", "x,y\n1,2\n3,4\n");
  const auto pf = read_point_file(path);
  EXPECT_EQ(pf.points2.size(), 2u);
  const auto e = expect_input_error([&] { read_point_file(dir.path("missing.csv")); });
  EXPECT_EQ(e.file(), dir.path("missing.csv"));
}

TEST(PointFile, ManyPointsDuplicateFoundQuickly) {
  std::string text;
  for (int i = 0; i < 200000; ++i) text += std::to_string(i % 1000) + " " + std::to_string(i / 1000) + "\n";
  text += "999 199\n";  // repeats the last generated point (line 200000)
  const auto e = expect_input_error([&] { parse_point_file_text(text, "big.txt"); });
  EXPECT_EQ(e.message(), "duplicate point: line 200001 repeats line 200000");
}
