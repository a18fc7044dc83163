#include "shoremesh/io/geojson_input.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>

#include "io_test_names.hpp"
#include "shoremesh/io/ring_file.hpp"

namespace {

double ring_area(const std::vector<Point2>& r) {
  double a = 0;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) a += r[j][0] * r[i][1] - r[i][0] * r[j][1];
  return std::abs(a) / 2;
}

// The Superior polygon (outer ring + 45 islands) as one GeoJSON Polygon, rings closed as RFC 7946 wants.
std::string superior_geojson() {
  const auto rf = read_ring_file(samples("superior/lake_superior_lonlat.csv"));
  std::string s = R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"Lake Superior"},)"
                  R"("geometry":{"type":"Polygon","coordinates":[)";
  char buf[64];
  for (std::size_t r = 0; r < rf.rings.size(); ++r) {
    s += r ? ",[" : "[";
    for (std::size_t k = 0; k <= rf.rings[r].size(); ++k) {
      const auto& p = rf.rings[r][k % rf.rings[r].size()];
      std::snprintf(buf, sizeof buf, "%s[%.7f,%.7f]", k ? "," : "", p[0], p[1]);
      s += buf;
    }
    s += "]";
  }
  return s + "]}}]}";
}

}  // namespace

TEST(GeoJson, SuperiorPolygonAreaMatchesGeodesicArea) {
  const auto set = parse_geojson_text(superior_geojson(), "superior.geojson");
  ASSERT_EQ(set.domain.rings.size(), 46u);
  EXPECT_EQ(set.domain.rings[0].role, RingRole::Shore);
  EXPECT_EQ(set.domain.rings[0].points.size(), 950u);
  for (std::size_t r = 1; r < 46; ++r) EXPECT_EQ(set.domain.rings[r].role, RingRole::Island);
  EXPECT_EQ(set.points.size(), 1679u - 46u);
  EXPECT_EQ(set.projection.describe(), "UTM zone 16N (WGS84)");
  double area = ring_area(set.domain.rings[0].points);
  for (std::size_t r = 1; r < 46; ++r) area -= ring_area(set.domain.rings[r].points);
  std::printf("GeoJSON Superior water area in UTM 16N: %.0f km^2 (geodesic 82078 km^2)\n", area / 1e6);
  EXPECT_NEAR(area / 1e6, 82078, 0.005 * 82078);  // UTM scale error across the lake is below 0.3 %
  EXPECT_EQ(describe_origin(set, 0), "superior.geojson, element 1, ring 1");
}

TEST(GeoJson, AllGeometryTypes) {
  const std::string text = R"({"type":"FeatureCollection","features":[
    {"type":"Feature","geometry":{"type":"Point","coordinates":[14.30,45.75]},"properties":null},
    {"type":"Feature","geometry":{"type":"MultiPoint","coordinates":[[14.31,45.75],[14.32,45.75,500]]},"properties":{}},
    {"type":"Feature","geometry":{"type":"LineString","coordinates":[[14.331,45.765],[14.339,45.765]]},"properties":{}},
    {"type":"Feature","geometry":null,"properties":{}},
    {"type":"Feature","geometry":{"type":"GeometryCollection","geometries":[
       {"type":"MultiPolygon","coordinates":[[[[14.33,45.74],[14.36,45.74],[14.36,45.77],[14.33,45.77],[14.33,45.74]],
                                             [[14.34,45.75],[14.35,45.75],[14.35,45.76],[14.34,45.75]]]]},
       {"type":"MultiLineString","coordinates":[[[14.355,45.741],[14.355,45.7509]]]}]},"properties":{}}]})";
  GeoJsonOptions opt;
  opt.spacing = 200;  // metres
  const auto set = parse_geojson_text(text, "all.geojson", opt);
  ASSERT_EQ(set.domain.rings.size(), 4u);  // the polygon's two rings, then the two LineStrings as lines
  EXPECT_EQ(set.domain.rings[0].role, RingRole::Shore);
  EXPECT_EQ(set.domain.rings[1].role, RingRole::Island);
  EXPECT_EQ(set.domain.rings[2].role, RingRole::Line);
  EXPECT_EQ(set.domain.rings[3].role, RingRole::Line);
  // 0.03 degrees of longitude at 45.75N is about 2.3 km: subdivided into pieces of at most 200 m.
  const auto& outer = set.domain.rings[0].points;
  for (std::size_t i = 0; i < outer.size(); ++i) {
    const auto& a = outer[i];
    const auto& b = outer[(i + 1) % outer.size()];
    EXPECT_LE(std::hypot(a[0] - b[0], a[1] - b[1]), 200.0 + 1e-9);
  }
  EXPECT_GT(outer.size(), 40u);
  // Lines, in the water: the LineString (620 m -> 4 pieces of at most 200 m: 5 points) and the
  // MultiLineString's (1.1 km -> 6 pieces: 7 points), open (no closing segment); loose points: the 3 points.
  EXPECT_EQ(set.domain.rings[2].points.size(), 5u);
  EXPECT_EQ(set.domain.rings[3].points.size(), 7u);
  EXPECT_EQ(set.domain.rings[2].segment_count(), 4u);
  std::size_t loose = 0;
  for (const auto& o : set.origins) loose += o.ring == PointOrigin::kNoRing;
  EXPECT_EQ(loose, 3u);
}

// A LineString is a chain of constraint edges in the water: one on land would be in no element, and is
// refused naming it.
TEST(GeoJson, ALineStringOnLandIsRefused) {
  const std::string text = R"({"type":"FeatureCollection","features":[
    {"type":"Feature","geometry":{"type":"Polygon","coordinates":[[[14.33,45.74],[14.36,45.74],[14.36,45.77],[14.33,45.77],[14.33,45.74]]]},"properties":{}},
    {"type":"Feature","geometry":{"type":"LineString","coordinates":[[14.30,45.76],[14.31,45.76]]},"properties":{}}]})";
  const auto e = expect_input_error([&] { parse_geojson_text(text, "land.geojson"); });
  EXPECT_EQ(e.file(), "land.geojson");
  EXPECT_THAT(e.message(), HasSubstr("line 2 lies on land"));
}

TEST(GeoJson, LegacyUtmCrsKeepsMetres) {
  const std::string text = R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32633"}},
    "features":[{"type":"Feature","geometry":{"type":"Polygon","coordinates":[[[450000,5065000],[451000,5065000],[451000,5066000],[450000,5065000]]]},"properties":{}}]})";
  const auto set = parse_geojson_text(text, "utm.geojson");
  EXPECT_EQ(set.units, Units::Metres);
  EXPECT_EQ(set.projection.describe(), "UTM zone 33N (WGS84)");
  EXPECT_EQ(set.points[1], (Point2{451000, 5065000}));
  const auto other = parse_geojson_text(
      R"({"type":"Point","coordinates":[1000,2000],"crs":{"type":"name","properties":{"name":"EPSG:3857"}}})", "m.geojson");
  EXPECT_EQ(other.units, Units::MapUnits);
  const auto versioned = parse_geojson_text(
      R"({"type":"Point","coordinates":[450000,5065000],"crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG:6.6:32733"}}})",
      "s.geojson");
  EXPECT_EQ(versioned.projection.describe(), "UTM zone 33S (WGS84)");
}

TEST(GeoJson, MalformedInputsNameFileAndElement) {
  shoremesh::io::test::expect_errors(
      {
      {"{\"type\":\"Point\",\n\"coordinates\":[1,2,]}", "malformed JSON"},
      {R"({"type":"Polygon","coordinates":[[[0,0],[1,0],[0,0]]]})", "coordinates[0]: polygon ring has fewer than three points"},
      {R"({"type":"FeatureCollection","features":[{"type":"Feature","geometry":{"type":"Point","coordinates":["14",45]}}]})",
       "features[0].geometry.coordinates[0]: not a number"},
      {R"({"type":"Circle","coordinates":[0,0]})", "unknown geometry type"},
      {R"({"type":"Point"})", "missing \"coordinates\""},
      {R"({"type":"Point","coordinates":[200,45]})", "not lon/lat"},
      {R"({"type":"FeatureCollection","features":[]})", "no points"},
      {R"({"type":"Polygon","coordinates":[[[0,0],[1,1],[1,0],[0,1],[0,0]]]})", "self-intersecting rings"},
      {R"({"type":"LineString","coordinates":[[0,0]]})", "at least two positions"},
      {"", "malformed JSON"},
      {R"({"type":"Point","coordinates":[1e999,2]})", "malformed JSON: number overflow"},
      {std::string(300, '[') + std::string(300, ']'), "nested deeper than 256"},
  },
      "bad.geojson", [](const std::string& text) { parse_geojson_text(text, "bad.geojson"); });
  const auto e = expect_input_error([] { parse_geojson_text("{\"type\":\"Point\",\n\"coordinates\":[1,2,]}", "l.geojson"); });
  EXPECT_EQ(e.line(), 2u);
}
