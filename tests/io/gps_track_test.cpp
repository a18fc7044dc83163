#include "shoremesh/io/gps_track.hpp"

#include <GeographicLib/Geodesic.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io_test_names.hpp"
#include "shoremesh/io/point_file.hpp"

namespace {

const std::string kCerknica = samples("cerknica/cerknicko-jezero.gpx");

double geodesic_distance(const LonLat& a, const LonLat& b) {
  double s12 = 0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat, a.lon, b.lat, b.lon, s12);
  return s12;
}

// Largest relative difference between planar distances after projection and geodesic distances, over
// consecutive points and over pairs i, i + n/2 (long distances across the data).
double max_distance_error(const std::vector<LonLat>& ll, const Projection& proj) {
  double worst = 0;
  auto check = [&](std::size_t i, std::size_t j) {
    const double g = geodesic_distance(ll[i], ll[j]);
    if (g < 1.0) return;  // repeated fixes
    const Point2 a = proj.forward(ll[i]), b = proj.forward(ll[j]);
    worst = std::max(worst, std::abs(std::hypot(a[0] - b[0], a[1] - b[1]) - g) / g);
  };
  for (std::size_t i = 0; i + 1 < ll.size(); ++i) check(i, i + 1);
  for (std::size_t i = 0; i < ll.size() / 2; ++i) check(i, i + ll.size() / 2);
  return worst;
}

std::vector<LonLat> track_lonlat(const GpsData& d) {
  std::vector<LonLat> out;
  for (const auto& s : d.sequences)
    if (s.kind == GpsSequence::Kind::TrackSegment)
      for (const auto& p : s.points) out.push_back({p.lon, p.lat});
  return out;
}

std::string gpx_with(const std::string& body, const std::string& version = "1.1") {
  return "<?xml version=\"1.0\"?>\n<gpx version=\"" + version +
         "\" creator=\"test\" xmlns=\"http://www.topografix.com/GPX/1/1\">\n" + body + "</gpx>\n";
}

// A closed walk around a circle (radius r metres at 46N, 8E), n points, start repeated at the end.
std::string circle_walk_gpx(double radius, int n, bool figure_eight = false) {
  std::string body = "<trk><name>walk</name><trkseg>\n";
  const double lat0 = 46, lon0 = 8, mlat = 111132.0, mlon = 111320.0 * std::cos(lat0 * std::numbers::pi / 180);
  for (int i = 0; i <= n; ++i) {
    const double t = 2 * std::numbers::pi * (i % n) / n;
    const double x = radius * std::sin(t), y = figure_eight ? radius * std::sin(t) * std::cos(t) : radius * std::cos(t);
    char buf[160];
    std::snprintf(buf, sizeof buf, "<trkpt lat=\"%.9f\" lon=\"%.9f\"><ele>1</ele></trkpt>\n", lat0 + y / mlat, lon0 + x / mlon);
    body += buf;
  }
  return gpx_with(body + "</trkseg></trk>\n");
}

}  // namespace

TEST(GpxTrack, ReadsRealGpx10TracksAndWaypoints) {
  const auto d = read_gpx(kCerknica);
  EXPECT_EQ(d.version, "1.0");
  std::size_t track_points = 0, waypoints = 0, segments = 0;
  for (const auto& s : d.sequences) {
    if (s.kind == GpsSequence::Kind::TrackSegment) {
      track_points += s.points.size();
      ++segments;
    }
    if (s.kind == GpsSequence::Kind::Waypoints) waypoints += s.points.size();
  }
  EXPECT_EQ(track_points, 296u);
  EXPECT_EQ(waypoints, 7u);
  EXPECT_EQ(segments, 7u);  // 8 tracks, one with an empty segment
  for (const auto& s : d.sequences)
    for (const auto& p : s.points) {
      EXPECT_GE(p.lat, 45.73);
      EXPECT_LE(p.lat, 45.80);
      EXPECT_GE(p.lon, 14.28);
      EXPECT_LE(p.lon, 14.38);
      EXPECT_GT(p.line, 0u);
    }
}

TEST(GpxTrack, ProjectedDistancesMatchGeodesic) {
  const auto ll = track_lonlat(read_gpx(kCerknica));
  const auto utm = Projection::choose(ll, ProjectionChoice::Utm, kCerknica);
  EXPECT_EQ(utm.describe(), "UTM zone 33N (WGS84)");
  const double utm_error = max_distance_error(ll, utm);
  const auto tm = Projection::choose(ll, ProjectionChoice::LocalTransverseMercator, kCerknica);
  const double tm_error = max_distance_error(ll, tm);
  EXPECT_LT(utm_error, 1e-3);
  EXPECT_LT(tm_error, 1e-3);
  EXPECT_LT(tm_error, 1e-4);  // scale 1 on the data's own meridian
  RecordProperty("utm_max_relative_distance_error", std::to_string(utm_error));
  RecordProperty("local_tm_max_relative_distance_error", std::to_string(tm_error));
  std::printf("max relative distance error: UTM %.3g, local TM %.3g\n", utm_error, tm_error);
}

TEST(Projection, LonLatRoundTripsWithin1e9Degrees) {
  std::vector<std::pair<Projection, std::vector<LonLat>>> cases;
  cases.push_back({Projection::utm_ups(33, true), track_lonlat(read_gpx(kCerknica))});
  cases.push_back({Projection::utm_ups(33, false), {{14.3, -45.7}, {17.9, -0.1}, {12.1, -79.0}}});
  cases.push_back({Projection::utm_ups(0, true), {{0, 90}, {-120, 85}, {179.9, 84.1}, {45, 88}}});
  cases.push_back({Projection::utm_ups(0, false), {{10, -90}, {-60, -81}, {170, -85}}});
  cases.push_back({Projection::local_transverse_mercator(180, -16.5), {{179.9, -16.4}, {-179.8, -16.6}, {-180, -17}}});
  cases.push_back({Projection::local_transverse_mercator(-88.2, 47.6), {{-92.5, 46.2}, {-84, 49.2}, {-88, 47}}});
  double worst = 0;
  for (const auto& [proj, pts] : cases)
    for (const auto& p : pts) {
      const LonLat back = proj.reverse(proj.forward(p));
      double dlon = std::remainder(back.lon - p.lon, 360.0);
      if (std::abs(p.lat) == 90) dlon = 0;  // longitude is arbitrary at a pole
      worst = std::max({worst, std::abs(dlon), std::abs(back.lat - p.lat)});
      EXPECT_LE(std::abs(dlon), 1e-9) << proj.describe() << " " << p.lon << "," << p.lat;
      EXPECT_LE(std::abs(back.lat - p.lat), 1e-9) << proj.describe() << " " << p.lon << "," << p.lat;
    }
  std::printf("worst lon/lat round trip: %.3g degrees\n", worst);
}

TEST(Projection, TrackAcrossZoneBoundaryKeepsOneZone) {
  // 11.9E .. 12.1E crosses the boundary of UTM zones 32 and 33: one zone is used for all points.
  std::vector<LonLat> ll;
  for (int i = 0; i <= 20; ++i) ll.push_back({11.9 + 0.01 * i, 46.0 + 0.001 * i});
  const auto p = Projection::choose(ll, ProjectionChoice::Utm);
  EXPECT_TRUE(p.zone() == 32 || p.zone() == 33);
  EXPECT_LT(max_distance_error(ll, p), 1e-3);
}

TEST(Projection, TrackAcrossAntimeridianWorks) {
  std::vector<LonLat> ll;
  for (int i = 0; i <= 40; ++i) ll.push_back({179.8 + 0.01 * i - (179.8 + 0.01 * i > 180 ? 360 : 0), -16.8 + 0.002 * i});
  for (auto choice : {ProjectionChoice::Utm, ProjectionChoice::LocalTransverseMercator}) {
    const auto p = Projection::choose(ll, choice);
    // 180E is a UTM zone edge, 3 degrees from the central meridian, where UTM's scale reaches 1.0009.
    EXPECT_LT(max_distance_error(ll, p), choice == ProjectionChoice::Utm ? 1.5e-3 : 1e-5) << p.describe();
    // Consecutive points stay about 1.1 km apart: no jump of 40,000 km at the antimeridian.
    for (std::size_t i = 0; i + 1 < ll.size(); ++i) {
      const Point2 a = p.forward(ll[i]), b = p.forward(ll[i + 1]);
      EXPECT_LT(std::hypot(a[0] - b[0], a[1] - b[1]), 1500.0);
    }
  }
  EXPECT_NEAR(std::abs(Projection::choose(ll, ProjectionChoice::LocalTransverseMercator).lon0()), 180.0, 0.2);
}

TEST(Projection, TrackOverThePoleWorks) {
  std::vector<LonLat> ll;
  for (int i = 0; i < 36; ++i) ll.push_back({-180.0 + 10 * i, 89.9});  // a 22 km circle around the north pole
  const auto ups = Projection::choose(ll, ProjectionChoice::Utm);
  EXPECT_EQ(ups.zone(), 0);
  EXPECT_TRUE(ups.north());
  EXPECT_LT(max_distance_error(ll, ups), 1e-2);  // UPS scale is 0.994 at the pole (by design)
  const auto tm = Projection::choose(ll, ProjectionChoice::LocalTransverseMercator);
  EXPECT_LT(max_distance_error(ll, tm), 1e-3);
}

TEST(Projection, DataTooWideForOneProjectionIsAClearError) {
  std::vector<LonLat> ll{{-50, 0}, {0, 0}, {50, 0}};
  const auto e = expect_input_error([&] { Projection::choose(ll, ProjectionChoice::Utm, "wide.gpx"); });
  EXPECT_EQ(e.file(), "wide.gpx");
  EXPECT_THAT(e.message(), HasSubstr("central meridian"));
  EXPECT_THROW(Projection::choose({{0, 0}, {180, 0}}, ProjectionChoice::Utm), InputError);
}

TEST(Projection, WktAndProjStringNameTheZone) {
  const auto p = Projection::utm_ups(16, true);
  EXPECT_THAT(p.wkt(), HasSubstr("AUTHORITY[\"EPSG\",\"32616\"]"));
  EXPECT_EQ(p.proj4(), "+proj=utm +zone=16 +datum=WGS84 +units=m +no_defs");
  EXPECT_THAT(Projection::local_transverse_mercator(14.3, 45.7).wkt(), HasSubstr("\"central_meridian\",14.3"));
  EXPECT_TRUE(Projection().wkt().empty());
}

TEST(GpxTrack, GpsToInputProjectsAndResamples) {
  const auto d = read_gpx(kCerknica);
  TrackOptions opt;
  opt.spacing = 20;
  // One of these walks ends 20-40 m from its start but crosses itself: as a closed walk it is reported.
  const auto e = expect_input_error([&] { gps_to_input(d, kCerknica, opt); });
  ASSERT_TRUE(e.line().has_value());
  EXPECT_GT(*e.line(), 1100u);  // in that walk, not at the top of the file
  EXPECT_THAT(e.message(), HasSubstr("self-intersecting rings"));
  // The reader closed the walk by its own guess: the message says so, and how to keep walks open.
  EXPECT_THAT(e.message(), HasSubstr("ends within 40 m of its start is closed into a shore ring"));
  EXPECT_THAT(e.message(), HasSubstr("--track-close-distance 0"));
  opt.close_tolerance = 0;  // keep every walk open
  const auto set = gps_to_input(d, kCerknica, opt);
  EXPECT_TRUE(set.domain.empty());
  EXPECT_EQ(set.units, Units::Metres);
  EXPECT_EQ(set.projection.kind(), Projection::Kind::LocalTransverseMercator);  // centred on the walks
  EXPECT_NEAR(set.projection.lon0(), 14.35, 0.02);
  EXPECT_GT(set.points.size(), 50u);
  EXPECT_EQ(set.points.size(), set.origins.size());
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    const auto& o = set.origins[i];
    EXPECT_GT(o.location, 0u);
    const LonLat ll = set.projection.reverse(set.points[i]);
    EXPECT_NEAR(ll.lat, 45.76, 0.05);
    EXPECT_NEAR(ll.lon, 14.33, 0.06);
  }
}

namespace {

// Every piece of `pts` (closed: the closing edge too) between `shortest` and `longest` metres long.
void expect_pieces_between(const std::vector<Point2>& pts, bool closed, double shortest, double longest) {
  const std::size_t edges = closed ? pts.size() : pts.size() - 1;
  for (std::size_t i = 0; i < edges; ++i) {
    const auto& a = pts[i];
    const auto& b = pts[(i + 1) % pts.size()];
    const double d = std::hypot(a[0] - b[0], a[1] - b[1]);
    EXPECT_GE(d, shortest) << "piece " << i << " of " << edges;
    EXPECT_LE(d, longest) << "piece " << i << " of " << edges;
  }
}

}  // namespace

TEST(GpxTrack, ClosedShorelineWalkBecomesARing) {
  shoremesh::io::test::ScratchDir dir;
  // Fixes 15.7 m apart on a circle of 1 km: thinned to the spacing, none cut.
  const auto path = dir.write("walk.gpx", circle_walk_gpx(1000, 400));
  TrackOptions opt;
  opt.spacing = 100;
  opt.smooth_window = 2;
  const auto set = gps_to_input(read_gpx(path), path, opt);
  ASSERT_EQ(set.domain.rings.size(), 1u);
  const auto& ring = set.domain.rings[0];
  EXPECT_EQ(ring.role, RingRole::Shore);
  // Six fixes a piece (94 m), the farthest within 100 m: about 67 pieces.
  EXPECT_NEAR(static_cast<double>(ring.points.size()), 2 * std::numbers::pi * 1000 / 94, 4.0);
  expect_pieces_between(ring.points, true, 50.0, 100.0);
}

TEST(GpxTrack, SparseFixesAreCutToTheSpacing) {
  shoremesh::io::test::ScratchDir dir;
  // Fixes 157 m apart (a log every 30 s from a boat): a spacing of 50 m keeps every fix and cuts each gap
  // into four, on a closed walk and on an open one alike.
  const auto path = dir.write("sparse.gpx", circle_walk_gpx(1000, 40));
  const GpsData data = read_gpx(path);
  TrackOptions opt;
  opt.spacing = 50;
  const auto closed = gps_to_input(data, path, opt);
  ASSERT_EQ(closed.domain.rings.size(), 1u);
  const auto& ring = closed.domain.rings[0].points;
  EXPECT_EQ(ring.size(), 40u * 4);
  expect_pieces_between(ring, true, 25.0, 50.0);
  const auto& fixes = data.sequences[0].points;
  for (std::size_t i = 0; i < ring.size(); i += 4) {
    const Point2 fix = closed.projection.forward({fixes[i / 4].lon, fixes[i / 4].lat});
    EXPECT_EQ(ring[i], fix) << i;
  }
  // The fix each point came from: the one before it along the walk (its line in the file).
  EXPECT_EQ(closed.origins[1].location, closed.origins[0].location);
  EXPECT_LT(closed.origins[0].location, closed.origins[4].location);

  opt.close_tolerance = 0;
  const auto open = gps_to_input(data, path, opt);
  EXPECT_TRUE(open.domain.empty());
  // 41 fixes, the last on the first: 40 gaps of four pieces, the last fix an exact repeat of the first.
  EXPECT_EQ(open.points.size(), 40u * 4);
  expect_pieces_between(open.points, false, 25.0, 50.0);
}

TEST(GpxTrack, SelfIntersectingWalkIsReported) {
  shoremesh::io::test::ScratchDir dir;
  const auto path = dir.write("eight.gpx", circle_walk_gpx(1000, 200, true));
  const auto e = expect_input_error([&] { gps_to_input(read_gpx(path), path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_TRUE(e.line().has_value());
  EXPECT_THAT(e.message(), HasSubstr("self-intersecting"));
}

TEST(GpxTrack, TruncatedFileNamesFileAndLine) {
  const std::string text = shoremesh::io::test::read_file(kCerknica);
  const std::string cut = text.substr(0, text.size() / 2);
  const auto e = expect_input_error([&] { parse_gpx_text(cut, "cut.gpx"); });
  EXPECT_EQ(e.file(), "cut.gpx");
  ASSERT_TRUE(e.line().has_value());
  EXPECT_GT(*e.line(), 100u);
  EXPECT_THAT(e.message(), HasSubstr("malformed XML"));
}

TEST(GpxTrack, MalformedInputsGetClearErrors) {
  shoremesh::io::test::expect_errors(
      {
      {"<gpx version=\"1.1\"><trk><trkseg><trkpt lat=\"1\" lon=\"2\"></trkseg></trk></gpx>", "malformed XML", 1},
      {"<?xml version=\"1.0\"?>\n<kml><Placemark/></kml>\n", "not a GPX file", 2},
      {gpx_with("<wpt lat=\"45\" lon=\"14\"/>\n<wpt lon=\"14\"/>\n"), "without a lat attribute", 4},
      {gpx_with("<wpt lat=\"45abc\" lon=\"14\"/>\n"), "is not a number", 3},
      {gpx_with("<wpt lat=\"nan\" lon=\"14\"/>\n"), "not a finite number", 3},
      {gpx_with("<wpt lat=\"95\" lon=\"14\"/>\n"), "out of range", 3},
      {gpx_with("<wpt lat=\"45\" lon=\"14\"><ele>high</ele></wpt>\n"), "<ele>", 3},
      {gpx_with("<wpt lat=\"45\" lon=\"14\"/>\n", "2.0"), "unsupported GPX version", 2},
      {gpx_with("<trk><trkseg></trkseg></trk>\n"), "no points", 0},
      {"", "", 0},
  },
      "t.gpx", [](const std::string& text) { parse_gpx_text(text, "t.gpx"); });
}

TEST(TrackCsv, ColumnsFoundByHeaderName) {
  const std::string text = "time,Longitude,\"Latitude\",ele\n2010-08-05T14:00:00Z,14.3,45.7,550\n"
                           "2010-08-05T14:00:10Z,14.301,45.701,\n";
  EXPECT_TRUE(csv_header_has_lat_lon(text));
  EXPECT_FALSE(csv_header_has_lat_lon("x,y\n1,2\n"));
  const auto d = parse_track_csv_text(text, "t.csv");
  ASSERT_EQ(d.point_count(), 2u);
  const auto& p = d.sequences[0].points;
  EXPECT_DOUBLE_EQ(p[0].lon, 14.3);
  EXPECT_DOUBLE_EQ(p[0].lat, 45.7);
  EXPECT_EQ(p[0].ele, 550.0);
  EXPECT_FALSE(p[1].ele.has_value());
  EXPECT_EQ(p[1].line, 3u);
}

TEST(TrackCsv, MalformedRowsNameFileAndLine) {
  auto e = expect_input_error([] { parse_track_csv_text("lat,lon\n45,14\n45.1,abc\n", "t.csv"); });
  EXPECT_EQ(e.line(), 3u);
  EXPECT_THAT(e.message(), HasSubstr("lon column: \"abc\" is not a number"));
  e = expect_input_error([] { parse_track_csv_text("lat,lon\n45,inf\n", "t.csv"); });
  EXPECT_THAT(e.message(), HasSubstr("not a finite number"));
  e = expect_input_error([] { parse_track_csv_text("lat,lon\n45,14,3\n", "t.csv"); });
  EXPECT_EQ(e.line(), 2u);
  e = expect_input_error([] { parse_track_csv_text("x,y\n45,14\n", "t.csv"); });
  EXPECT_THAT(e.message(), HasSubstr("no lat/lon columns"));
  e = expect_input_error([] { parse_track_csv_text("lat,lon\n", "t.csv"); });
  EXPECT_EQ(e.message(), "no points");
}

TEST(GpxTrack, FixesAreThinnedToTheSpacingAndSmoothingReducesNoise) {
  // A dense, noisy walk along a straight shore: 2000 fixes 1 m apart eastwards at 46N with +-1.5 m of
  // deterministic lateral noise.
  GpsData d;
  d.version = "1.1";
  GpsSequence s;
  const double mlat = 111132.0, mlon = 111320.0 * std::cos(46.0 * std::numbers::pi / 180);
  for (int i = 0; i < 2000; ++i) {
    const double noise = 1.5 * std::sin(i * 2.3) * std::cos(i * 0.7);
    s.points.push_back({8.0 + i / mlon, 46.0 + noise / mlat, std::nullopt, static_cast<std::size_t>(i + 1)});
  }
  s.points.push_back(s.points.back());  // a repeated fix
  d.sequences.push_back(s);
  auto deviation = [&](const InputSet& set) {
    // RMS distance from the straight line through the first and last points.
    const Point2 a = set.points.front(), b = set.points.back();
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    double sum = 0;
    for (const auto& p : set.points) {
      const double cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
      sum += (cross / len) * (cross / len);
    }
    return std::sqrt(sum / static_cast<double>(set.points.size()));
  };
  TrackOptions opt;
  opt.spacing = 10;
  opt.close_tolerance = 0;
  const auto raw = gps_to_input(d, "walk.gpx", opt);
  // The farthest fix within 10 m of the last kept one: pieces of 8 to 10 m (the noise takes some).
  EXPECT_NEAR(static_cast<double>(raw.points.size()), 2000 / 9, 25);
  // The last fix of the walk is kept, however near the one before it.
  expect_pieces_between({raw.points.begin(), raw.points.end() - 1}, false, 7.0, 10.0);
  opt.smooth_window = 5;
  const auto smooth = gps_to_input(d, "walk.gpx", opt);
  std::printf("lateral RMS noise: %.2f m raw, %.2f m smoothed (window 11)\n", deviation(raw), deviation(smooth));
  EXPECT_LT(deviation(smooth), 0.5 * deviation(raw));
  TrackOptions all;
  all.close_tolerance = 0;
  const auto every_fix = gps_to_input(d, "walk.gpx", all);
  EXPECT_EQ(every_fix.points.size(), 2000u);  // spacing 0: only the exact repeat goes
  EXPECT_EQ(raw.points.back(), every_fix.points.back());
}

TEST(GpxTrack, RoutesAndWaypointsAreRead) {
  const auto d = parse_gpx_text(gpx_with("<wpt lat=\"45.1\" lon=\"14.1\"><name>a</name></wpt>\n"
                                         "<rte><name>r</name><rtept lat=\"45.2\" lon=\"14.2\"/><rtept lat=\"45.3\" lon=\"14.3\"/></rte>\n"),
                                "r.gpx");
  ASSERT_EQ(d.sequences.size(), 2u);
  EXPECT_EQ(d.sequences[0].kind, GpsSequence::Kind::Route);
  EXPECT_EQ(d.sequences[0].name, "r");
  EXPECT_EQ(d.sequences[0].points[1].line, 4u);
  EXPECT_EQ(d.sequences[1].kind, GpsSequence::Kind::Waypoints);
  TrackOptions opt;
  EXPECT_EQ(gps_to_input(d, "r.gpx", opt).points.size(), 3u);
  opt.waypoints = false;
  EXPECT_EQ(gps_to_input(d, "r.gpx", opt).points.size(), 2u);
}

namespace {
// A track of fixes at (x, y) metres from 46N, 8E.
std::string track_gpx(const std::vector<Point2>& xy) {
  const double lat0 = 46, lon0 = 8, mlat = 111132.0, mlon = 111320.0 * std::cos(lat0 * std::numbers::pi / 180);
  std::string body = "<trk><name>line</name><trkseg>\n";
  for (const Point2& p : xy) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "<trkpt lat=\"%.9f\" lon=\"%.9f\"></trkpt>\n", lat0 + p[1] / mlat, lon0 + p[0] / mlon);
    body += buf;
  }
  return body + "</trkseg></trk>\n";
}

std::string with_track(const std::string& gpx, const std::vector<Point2>& xy) {
  const std::size_t end = gpx.rfind("</gpx>");
  return gpx.substr(0, end) + track_gpx(xy) + gpx.substr(end);
}
}  // namespace

TEST(GpxTrack, OpenWalksBecomeConstraintLinesWhenAsked) {
  shoremesh::io::test::ScratchDir dir;
  // A walk around a lake of 1 km radius and a survey line across its middle that does not close.
  const auto path = dir.write("survey.gpx", with_track(circle_walk_gpx(1000, 200), {{-500, 0}, {0, 100}, {500, 0}}));
  TrackOptions opt;
  opt.spacing = 100;
  const auto loose = gps_to_input(read_gpx(path), path, opt);
  ASSERT_EQ(loose.domain.rings.size(), 1u);
  opt.open_lines = true;
  const auto lines = gps_to_input(read_gpx(path), path, opt);
  ASSERT_EQ(lines.domain.rings.size(), 2u);
  EXPECT_EQ(lines.domain.rings[1].role, RingRole::Line);
  // Cut to the spacing like a ring: 2 pieces of 510 m, 6 parts each, and the end.
  EXPECT_EQ(lines.domain.rings[1].points.size(), 13u);
  EXPECT_EQ(lines.size(), loose.size());
  EXPECT_THAT(lines.notes, ::testing::Contains(HasSubstr("1 open walk(s) became constraint lines")));
  // A line that leaves the lake is refused, naming the option.
  const auto out = dir.write("out.gpx", with_track(circle_walk_gpx(1000, 200), {{-500, 0}, {0, 100}, {1500, 0}}));
  const auto e = expect_input_error([&] { gps_to_input(read_gpx(out), out, opt); });
  EXPECT_THAT(e.message(), HasSubstr("--gps-open-lines"));
}
