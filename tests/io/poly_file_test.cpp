#include "shoremesh/io/poly_file.hpp"

#include <algorithm>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io_test_names.hpp"

static bool has_duplicates(std::vector<Point2> points) {
  std::sort(points.begin(), points.end());
  return std::adjacent_find(points.begin(), points.end()) != points.end();
}

TEST(PolyFile, DoubleHexRingsAndHoles) {
  const auto p = read_poly_file(samples("pslg/double_hex.poly"));
  EXPECT_EQ(p.points.size(), 96u);
  EXPECT_EQ(p.segments.size(), 96u);
  ASSERT_EQ(p.holes.size(), 2u);
  EXPECT_EQ(p.holes[1], (Point2{0.6, 0.4}));
  const auto set = pslg_to_input(p);
  ASSERT_EQ(set.domain.rings.size(), 3u);
  EXPECT_EQ(set.domain.rings[0].points.size(), 72u);
  EXPECT_EQ(set.domain.rings[0].role, RingRole::Shore);
  EXPECT_EQ(set.domain.rings[1].role, RingRole::Island);
  EXPECT_EQ(set.domain.rings[2].role, RingRole::Island);
  EXPECT_EQ(set.points.size(), 96u);
  EXPECT_EQ(set.units, Units::MapUnits);
  for (const auto& note : set.notes) EXPECT_THAT(note, ::testing::Not(HasSubstr("inside water")));
  EXPECT_EQ(describe_origin(set, 0), samples("pslg/double_hex.poly") + ":28, ring 1");
}

TEST(PolyFile, FishAndRectangleSegmentsSampled) {
  const auto p = read_poly_file(samples("pslg/fish-and-rectangle.poly"));
  EXPECT_EQ(p.points.size(), 31u);
  EXPECT_EQ(p.segments.size(), 44u);
  EXPECT_EQ(p.holes.size(), 3u);
  PslgOptions opt;
  opt.spacing = 0.05;
  const auto set = pslg_to_input(p, opt);
  EXPECT_GT(set.points.size(), 31u * 3);
  // The water's boundary, its lines (segments with water on both sides) and the pinch vertices where the
  // three hole faces touch the outline are said; every vertex is one point, shared by its rings.
  std::size_t lines = 0;
  for (const auto& ring : set.domain.rings) lines += !ring.closed();
  EXPECT_GT(lines, 0u);
  EXPECT_EQ(set.ring_ids.size(), set.domain.rings.size());
  EXPECT_FALSE(has_duplicates(set.points));
  const std::string notes = [&] {
    std::string all;
    for (const auto& note : set.notes) all += note + "\n";
    return all;
  }();
  EXPECT_THAT(notes, HasSubstr("30 segments bound the water"));
  EXPECT_THAT(notes, HasSubstr("10 segments with water on both sides are " + std::to_string(lines) + " constraint lines"));
  EXPECT_THAT(notes, HasSubstr("4 segments with land (a hole or the outside) on both sides"));
  EXPECT_THAT(notes, HasSubstr("the input has 4 pinch vertices"));
}

TEST(PolyFile, SegmentsAreSampledAtTheSpacing) {
  const auto p = parse_poly_text("4 2 0 0\n1 0 0\n2 10 0\n3 10 10\n4 0 10\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n", "sq.poly");
  PslgOptions opt;
  opt.spacing = 3;
  const auto set = pslg_to_input(p, opt);
  ASSERT_EQ(set.domain.rings.size(), 1u);
  const auto& r = set.domain.rings[0].points;
  ASSERT_EQ(r.size(), 16u);  // 4 pieces of 2.5 per side
  for (std::size_t i = 0; i < r.size(); ++i) {
    const auto& a = r[i];
    const auto& b = r[(i + 1) % r.size()];
    EXPECT_NEAR(std::hypot(a[0] - b[0], a[1] - b[1]), 2.5, 1e-12);
  }
}

TEST(NodeFile, DotsHasHundredPoints) {
  const auto p = read_node_file(samples("pslg/dots.node"));
  EXPECT_EQ(p.points.size(), 100u);
  EXPECT_EQ(p.point_lines[0], 2u);
  const auto set = pslg_to_input(p);
  EXPECT_TRUE(set.domain.empty());
  EXPECT_EQ(set.points.size(), 100u);
}

TEST(PolyFile, VerticesFromTheSiblingNodeFile) {
  shoremesh::io::test::ScratchDir dir;
  dir.write("lake.node", "3 2 0 0\n0 0 0\n1 4 0\n2 0 4\n");
  const auto path = dir.write("lake.poly", "0 2 0 0\n3 0\n0 0 1\n1 1 2\n2 2 0\n0\n");
  const auto p = read_poly_file(path);
  EXPECT_EQ(p.points.size(), 3u);
  EXPECT_EQ(p.vertex_file, dir.path("lake.node"));
  EXPECT_EQ(pslg_to_input(p).domain.rings.size(), 1u);
  const auto e = expect_input_error([] { parse_poly_text("0 2 0 0\n0 0\n", "alone.poly"); });
  EXPECT_THAT(e.message(), HasSubstr("no .node file"));
}

TEST(PolyFile, MalformedFilesNameTheLine) {
  shoremesh::io::test::expect_errors(
      {
      {"3 2 0 0\n1 0 0\n2 1 0\n", "file ends before vertex 3 of 3", 3},
      {"3 3 0 0\n1 0 0 0\n", "dimension 3", 1},
      {"3 2 0 0\n1 0 0\n2 1 0\n4 0 1\n", "vertex number 4 where 3 was expected", 4},
      {"3 2 0 0\n1 0 0\n2 1 zero\n3 0 1\n", "\"zero\" is not a number", 3},
      {"3 2 0 0\n1 0 0\n2 1 nan\n3 0 1\n", "not a finite number", 3},
      {"3 2 0 0\n1 0 0\n2 1 0 7\n3 0 1\n", "expected 3 values, found 4", 3},
      {"3 2 0 0\n1 0 0\n2 1 0\n3 0 0\n", "duplicate point: line 4 repeats line 2", 4},
      {"3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 1 4\n", "endpoint 4 is not a vertex", 6},
      {"3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 2 2\n", "to itself", 6},
      {"3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n2 0\n1 1 2\n", "file ends before segment 2 of 2", 6},
      {"3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n1\n", "file ends before hole 1 of 1", 6},
      {"", "file ends before the header", 0},
      {"x 2 0 0\n", "not an integer", 1},
  },
      "t.poly", [](const std::string& text) { parse_poly_text(text, "t.poly"); });
}

TEST(PolyFile, FewerThanThreePointsAndSelfIntersectingRing) {
  auto e = expect_input_error([] { pslg_to_input(parse_node_text("2 2 0 0\n1 0 0\n2 1 0\n", "two.node")); });
  EXPECT_THAT(e.message(), HasSubstr("fewer than three points"));
  const std::string bowtie = "4 2 0 0\n1 0 0\n2 10 10\n3 10 0\n4 0 10\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n";
  e = expect_input_error([&] { pslg_to_input(parse_poly_text(bowtie, "bow.poly")); });
  EXPECT_EQ(e.file(), "bow.poly");
  EXPECT_EQ(e.line(), 7u);
  EXPECT_THAT(e.message(), HasSubstr("segment 1 (line 7) meets segment 3 (line 9) other than at a common end point"));
}
