#include "shoremesh/io/read_input.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "shoremesh/io/ring_file.hpp"

#include "io_test_names.hpp"

TEST(ReadInput, DetectsEverySampleFormat) {
  EXPECT_EQ(detect_input_format(samples("superior/superior_watermask_h.png")), InputFormat::Image);
  EXPECT_EQ(detect_input_format(samples("superior/superior_watermask_h.tif")), InputFormat::Image);
  EXPECT_EQ(detect_input_format(samples("superior/lake_superior_lonlat.csv")), InputFormat::RingFile);
  EXPECT_EQ(detect_input_format(samples("cerknica/cerknicko-jezero.gpx")), InputFormat::Gpx);
  EXPECT_EQ(detect_input_format(samples("pslg/double_hex.poly")), InputFormat::Poly);
  EXPECT_EQ(detect_input_format(samples("pslg/dots.node")), InputFormat::Node);
  shoremesh::io::test::ScratchDir dir;
  EXPECT_EQ(detect_input_format(dir.write("t.csv", "time,lat,lon\n1,45,14\n")), InputFormat::TrackCsv);
  EXPECT_EQ(detect_input_format(dir.write("p.txt", "1 2\n3 4\n")), InputFormat::PointFile);
  const auto e = expect_input_error([&] { detect_input_format(dir.write("x.shp", "")); });
  EXPECT_THAT(e.message(), HasSubstr("unknown input format"));
}

TEST(ReadInput, SuperiorSamplesImageAndPolygonShareOneProjection) {
  InputOptions opt;
  opt.lonlat = true;
  opt.image.largest_water_only = true;
  // Asked for UTM, two files of one region read apart get the same zone (the default transverse Mercator
  // is centred on each file's own data).
  opt.projection_choice = ProjectionChoice::Utm;
  const auto image = read_input(samples("superior/superior_watermask_h.png"), opt);
  EXPECT_EQ(image.units, Units::Metres);
  EXPECT_EQ(image.projection.describe(), "UTM zone 16N (WGS84)");
  const auto polygon = read_input(samples("superior/lake_superior_lonlat.csv"), opt);
  EXPECT_EQ(polygon.domain.rings.size(), 46u);
  EXPECT_EQ(polygon.projection, image.projection);
  // read_inputs fixes the first projection for all files and merges.
  opt.projection_choice = ProjectionChoice::LocalTransverseMercator;
  const auto both = read_inputs({samples("superior/superior_watermask_h.png"), samples("superior/lake_superior_lonlat.csv")}, opt);
  EXPECT_EQ(both.projection.kind(), Projection::Kind::LocalTransverseMercator);
  EXPECT_EQ(both.points.size(), both.origins.size());
  EXPECT_EQ(both.domain.rings.size(), image.domain.rings.size() + 46);
  EXPECT_EQ(both.sources.size(), 2u);
}

TEST(ReadInput, GpxAndPointFilesInLonLat) {
  InputOptions opt;
  opt.track.close_tolerance = 0;
  opt.track.spacing = 10;
  const auto gpx = read_input(samples("cerknica/cerknicko-jezero.gpx"), opt);
  EXPECT_EQ(gpx.projection.describe(), "local transverse Mercator at 45.769452N 14.353633E (WGS84)");
  shoremesh::io::test::ScratchDir dir;
  const auto pts = dir.write("pts.csv", "lon,lat,depth\n14.33,45.76,-3\n14.34,45.765,-4.5\n");
  // "lon,lat" names the columns of a GPS CSV: read as a track.
  EXPECT_EQ(detect_input_format(pts), InputFormat::TrackCsv);
  const auto plain = dir.write("pts.xyz", "14.33 45.76 -3\n14.34 45.765 -4.5\n");
  opt.lonlat = true;
  opt.projection = gpx.projection;
  const auto p3 = read_input(plain, opt);
  EXPECT_EQ(p3.dimension, 3);
  ASSERT_EQ(p3.points3.size(), 2u);
  EXPECT_EQ(p3.points3[1][2], -4.5);
  const LonLat back = p3.projection.reverse({p3.points3[1][0], p3.points3[1][1]});
  EXPECT_NEAR(back.lon, 14.34, 1e-9);
  EXPECT_NEAR(back.lat, 45.765, 1e-9);
  // Different units cannot be merged.
  opt.lonlat = false;
  const auto map_units = dir.write("map.txt", "0 0\n1 0\n");
  const auto e = expect_input_error([&] { read_inputs({samples("cerknica/cerknicko-jezero.gpx"), map_units}, opt); });
  EXPECT_THAT(e.message(), HasSubstr("cannot merge"));
}

// --spacing reaches ring files too: every ring segment longer than it is cut into equal pieces, and each
// inserted point names the line of the ring vertex before it.
TEST(ReadInput, RingFileSegmentsAreCutToTheSpacing) {
  shoremesh::io::test::ScratchDir dir;
  const auto path = dir.write("square.txt", "0 0\n10 0\n10 10\n0 10\n0 0\n");
  ASSERT_EQ(detect_input_format(path), InputFormat::RingFile);
  InputOptions opt;
  EXPECT_EQ(read_input(path, opt).points.size(), 4u);  // as given without a spacing
  opt.ring_spacing = 2.5;
  const auto set = read_input(path, opt);
  ASSERT_EQ(set.domain.rings.size(), 1u);
  const auto& ring = set.domain.rings[0].points;
  ASSERT_EQ(ring.size(), 16u);  // each side of 10 in four pieces
  ASSERT_EQ(set.points.size(), 16u);
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const auto& a = ring[k];
    const auto& b = ring[(k + 1) % ring.size()];
    EXPECT_NEAR(std::hypot(b[0] - a[0], b[1] - a[1]), 2.5, 1e-12) << "segment " << k;
    EXPECT_EQ(set.origins[k].location, k / 4 + 1) << "point " << k;  // vertex j is on line j + 1
  }
}

// A spacing far below the input's scale is refused with a message, before it fills the memory (a ring
// file at 1e-9 asked for about 10^10 points) or overflows the piece count (1e-300).
TEST(ReadInput, SpacingThatWouldCutTooManyPointsIsRefused) {
  shoremesh::io::test::ScratchDir dir;
  const auto path = dir.write("square.txt", "0 0\n10 0\n10 10\n0 10\n0 0\n");
  for (const double spacing : {1e-9, 1e-300}) {
    InputOptions opt;
    opt.ring_spacing = spacing;
    const auto e = expect_input_error([&] { read_input(path, opt); });
    EXPECT_THAT(e.message(), HasSubstr("choose a larger --spacing")) << spacing;
    EXPECT_THAT(e.message(), HasSubstr(spacing == 1e-9 ? "spacing 1e-09 " : "spacing 1e-300 "));
    EXPECT_THAT(e.file(), HasSubstr("square.txt")) << spacing;
  }
  InputOptions not_a_number;
  not_a_number.ring_spacing = std::nan("");
  EXPECT_THAT(expect_input_error([&] { read_input(path, not_a_number); }).message(), HasSubstr("spacing nan is not a number"));
  InputOptions poly;
  poly.poly.spacing = 1e-12;
  const auto e = expect_input_error([&] { read_input(samples("pslg/double_hex.poly"), poly); });
  EXPECT_THAT(e.message(), HasSubstr("choose a larger --spacing"));
}

// The points a spacing cuts are counted before any is made, rings, lines, segments and the other points
// together (a fuzzed .poly vertex at -713454 with a spacing of 0.25 asked for millions, GPX at 5 m too): at
// the cap the input is read; one over it is refused naming the file, the spacing and the count.
TEST(ReadInput, ASpacingThatWouldCreateMoreThanTheCapIsRefusedWithTheCount) {
  shoremesh::io::test::ScratchDir dir;
  struct Case {
    std::string file, text;
    double spacing;
    std::size_t points;  // what the spacing gives
  };
  const std::vector<Case> cases = {
      // A square of side 10 in pieces of 2.5 (16 points) and a segment of 10 in it (a constraint line: its
      // ends and 3 inside).
      {"sq.poly", "6 2 0 0\n1 0 0\n2 10 0\n3 10 10\n4 0 10\n5 1 2\n6 9 8\n5 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n5 5 6\n0\n",
       3, 21},
      // About 1112 m of meridian in 12 pieces of at most 100 m (13 points), and a waypoint or a point.
      {"walk.gpx",
       R"(<gpx version="1.1"><wpt lat="45.1" lon="14.1"/><trk><trkseg><trkpt lat="45" lon="14"/>)"
       R"(<trkpt lat="45.01" lon="14"/></trkseg></trk></gpx>)",
       100, 14},
      {"line.geojson",
       R"({"type":"GeometryCollection","geometries":[{"type":"LineString","coordinates":[[14,45],[14,45.01]]},)"
       R"({"type":"Point","coordinates":[14.1,45.1]}]})",
       100, 14},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write(c.file, c.text);
    InputOptions opt;
    opt.poly.spacing = opt.track.spacing = opt.geojson.spacing = c.spacing;
    opt.poly.max_points = opt.track.max_points = opt.geojson.max_points = c.points;
    EXPECT_EQ(read_input(path, opt).points.size(), c.points) << c.file;
    opt.poly.max_points = opt.track.max_points = opt.geojson.max_points = c.points - 1;
    const auto e = expect_input_error([&] { read_input(path, opt); });
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.message(), "--spacing " + readable(c.spacing) + " would cut the rings and segments into " +
                               std::to_string(c.points) + " points, more than the " + std::to_string(c.points - 1) +
                               " allowed; choose a larger --spacing");
  }
  // A count beyond every integer is said as a number, not overflowed: 5 segments of 10 at 1e-300.
  InputOptions tiny;
  tiny.poly.spacing = 1e-300;
  EXPECT_THAT(expect_input_error([&] { read_input(dir.path("sq.poly"), tiny); }).message(),
              HasSubstr("into 5e+301 points, more than the 10000000 allowed"));
}

// A ring file of a few megabytes is read in pieces on every thread: the rings, their points and each
// vertex's line are those of a reading line by line (comments, blank lines and "\r\n" endings across the
// pieces' ends), and of two malformed lines the error names the first in the file, with its line; a ring
// of two points before it is reported first, as a reading line by line meets it first.
TEST(ReadInput, LargeRingFileReadInPiecesAsLineByLine) {
  constexpr int kRings = 40, kPoints = 4000;
  std::string text = "# rings\n";
  std::size_t line = 1;
  std::vector<std::vector<Point2>> points;
  std::vector<std::vector<std::size_t>> lines;
  auto number = [](double x) {
    char buf[32];
    return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
  };
  for (int r = 0; r < kRings; ++r) {
    text += r % 3 ? "\n" : "# ring\r\n";
    ++line;
    points.emplace_back();
    lines.emplace_back();
    for (int k = 0; k <= kPoints; ++k) {  // the last repeats the first
      const double a = 2 * std::numbers::pi * (k % kPoints) / kPoints;
      const Point2 p{100.0 * r + 10 * std::cos(a), 10 * std::sin(a)};
      text += number(p[0]) + (k % 2 ? "," : " , ") + number(p[1]) + (k % 5 ? "\n" : "\r\n");
      ++line;
      if (k == kPoints) continue;
      points.back().push_back(p);
      lines.back().push_back(line);
    }
  }
  ASSERT_GT(text.size(), std::size_t(3) << 20);
  const RingFile rf = parse_ring_file_text(text, "big.csv");
  EXPECT_EQ(rf.rings, points);
  EXPECT_EQ(rf.lines, lines);
  const auto once = parse_ring_file_if_rings(text, "big.csv");
  ASSERT_TRUE(once.has_value());
  EXPECT_EQ(once->rings, points);
  EXPECT_EQ(once->lines, lines);
  EXPECT_TRUE(looks_like_ring_file(text));

  // Line `at` (1-based) replaced by `with`.
  auto replaced = [&](std::string t, std::size_t at, const std::string& with) {
    std::size_t begin = 0;
    for (std::size_t l = 1; l < at; ++l) begin = t.find('\n', begin) + 1;
    const std::size_t end = t.find('\n', begin);
    return t.replace(begin, end - begin, with);
  };
  const std::size_t early = lines[7][100], late = lines[33][2500];
  const std::string bad = replaced(replaced(text, late, "1,2,3"), early, "1,abc");
  auto e = expect_input_error([&] { parse_ring_file_text(bad, "big.csv"); });
  EXPECT_EQ(e.file(), "big.csv");
  EXPECT_EQ(e.line(), early);
  EXPECT_THAT(e.message(), HasSubstr("\"abc\" is not a number"));
  e = expect_input_error([&] { parse_ring_file_text(replaced(text, late, "1,2,3"), "big.csv"); });
  EXPECT_EQ(e.line(), late);
  EXPECT_THAT(e.message(), HasSubstr("expected 2 numbers, found 3 columns"));
  EXPECT_FALSE(parse_ring_file_if_rings(bad, "big.csv").has_value());
  EXPECT_FALSE(looks_like_ring_file(bad));
  // Ring 12 cut to two points (a blank line after its second): reported before the bad line after it.
  const std::string short_ring = replaced(replaced(text, late, "1,abc"), lines[12][2], "");
  e = expect_input_error([&] { parse_ring_file_text(short_ring, "big.csv"); });
  EXPECT_EQ(e.line(), lines[12][0]);
  EXPECT_THAT(e.message(), HasSubstr("a ring needs at least three points, this one has 2"));
}
