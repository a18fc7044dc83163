#include "shoremesh/io/geojson_input.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>

#include "io_test_names.hpp"
#include "io_test_util.hpp"
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
  // The projection rule: lon/lat goes to a transverse Mercator centred on the data (scale 1 .. 1.0012 here).
  EXPECT_EQ(set.projection.describe(), "local transverse Mercator at 47.683284N 88.071793W (WGS84)");
  double area = ring_area(set.domain.rings[0].points);
  for (std::size_t r = 1; r < 46; ++r) area -= ring_area(set.domain.rings[r].points);
  std::printf("GeoJSON Superior water area, local transverse Mercator: %.0f km^2 (geodesic 82078 km^2)\n", area / 1e6);
  EXPECT_NEAR(area / 1e6, 82078, 0.001 * 82078);  // its scale stays below 1.0012 over the lake
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

namespace shoremesh::io {
namespace {

// 2008 GeoJSON names its coordinate system in "crs"; RFC 7946 reads positions as WGS 84 lon/lat without
// one. Positions are put in each system here with PROJ through GDAL, independently of the reader.
std::string polygon_in(const std::string& crs_name, const std::vector<std::array<double, 2>>& lonlat, bool as_epsg = true) {
  OGRSpatialReference ll, target;
  ll.importFromEPSG(4326);
  if (as_epsg) target.SetFromUserInput(crs_name.c_str());
  for (auto* s : {&ll, &target}) s->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&ll, &target));
  std::string coords;
  for (std::size_t i = 0; i <= lonlat.size(); ++i) {
    double x = lonlat[i % lonlat.size()][0], y = lonlat[i % lonlat.size()][1];
    t->Transform(1, &x, &y);
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s[%.17g,%.17g]", i ? "," : "", x, y);
    coords += buf;
  }
  return R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":")" + crs_name +
         R"("}},"features":[{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[)" + coords +
         "]]}}]}";
}

const std::vector<std::array<double, 2>> kBay = {{-124.2, 48.3}, {-123.1, 48.3}, {-123.1, 49.1}, {-124.2, 49.1}};

double ring_area(const InputSet& set) {
  double a = 0;
  const auto& r = set.points;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) a += r[j][0] * r[i][1] - r[i][0] * r[j][1];
  return std::abs(a) / 2;
}

TEST(GeoJson, LegacyCrsIsReadByProjWebMercatorReprojectedToTrueMetres) {
  const auto plain = parse_geojson_text(polygon_in("EPSG:4326", kBay), "ll.geojson");
  const auto merc = parse_geojson_text(polygon_in("EPSG:3857", kBay), "merc.geojson");
  const auto urn = parse_geojson_text(polygon_in("urn:ogc:def:crs:EPSG::3857", kBay), "urn.geojson");
  EXPECT_EQ(merc.units, Units::Metres);
  EXPECT_EQ(merc.projection.kind(), Projection::Kind::LocalTransverseMercator);
  // Web Mercator's metres are 1.5 times too long here: reprojected, the bay has the lon/lat polygon's area.
  EXPECT_NEAR(ring_area(merc) / ring_area(plain), 1.0, 1e-6);
  ASSERT_EQ(merc.points.size(), plain.points.size());
  for (std::size_t i = 0; i < merc.points.size(); ++i) {
    EXPECT_NEAR(merc.points[i][0], plain.points[i][0], 1e-4);
    EXPECT_NEAR(merc.points[i][1], plain.points[i][1], 1e-4);
    EXPECT_EQ(urn.points[i], merc.points[i]);
  }
  bool said = false;
  for (const auto& n : merc.notes) said = said || (n.find("reprojected from WGS 84 / Pseudo-Mercator") != std::string::npos);
  EXPECT_TRUE(said) << ::testing::PrintToString(merc.notes);
}

TEST(GeoJson, LegacyProjectedCrsWithinItsAreaIsKeptInItsOwnMetres) {
  // UTM 10N around -123.6 and British National Grid around London: scale within 0.1 % of 1, kept as given.
  const auto utm_text = polygon_in("urn:ogc:def:crs:EPSG::32610", kBay);
  const auto utm = parse_geojson_text(utm_text, "utm.geojson");
  EXPECT_EQ(utm.projection.describe(), "UTM zone 10N (WGS84)");
  const std::vector<std::array<double, 2>> london = {{-0.5, 51.3}, {0.3, 51.3}, {0.3, 51.7}, {-0.5, 51.7}};
  const auto bng = parse_geojson_text(polygon_in("EPSG:27700", london), "bng.geojson");
  EXPECT_EQ(bng.projection.kind(), Projection::Kind::Crs);
  EXPECT_THAT(bng.projection.describe(), ::testing::HasSubstr("British National Grid"));
  // Kept: the positions are the file's, and the projection takes lon/lat there (PROJ) to within a millimetre.
  OGRSpatialReference ll, grid;
  ll.importFromEPSG(4326);
  grid.importFromEPSG(27700);
  for (auto* s : {&ll, &grid}) s->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&ll, &grid));
  double x = 0.3, y = 51.7;
  t->Transform(1, &x, &y);
  EXPECT_TRUE(std::find(bng.points.begin(), bng.points.end(), Point2{x, y}) != bng.points.end());
  const Point2 f = bng.projection.forward({0.3, 51.7});
  EXPECT_NEAR(f[0], x, 1e-3);
  EXPECT_NEAR(f[1], y, 1e-3);
  const LonLat back = bng.projection.reverse(f);
  EXPECT_NEAR(back.lon, 0.3, 1e-7);  // OSGB36's datum shift is inverted to a millimetre
  EXPECT_NEAR(back.lat, 51.7, 1e-7);
}

TEST(GeoJson, LegacyNullLinkedAndUnknownCrsAreMapUnitsOrRefusedNamingThem) {
  const auto null_crs = parse_geojson_text(R"({"type":"Point","coordinates":[1000,2000],"crs":null})", "n.geojson");
  EXPECT_EQ(null_crs.units, Units::MapUnits);
  EXPECT_EQ(null_crs.points[0], (Point2{1000, 2000}));
  const auto crs84 = parse_geojson_text(
      R"({"type":"Point","coordinates":[14.3,45.7],"crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:OGC:1.3:CRS84"}}})",
      "c.geojson");
  EXPECT_EQ(crs84.units, Units::Metres);
  EXPECT_EQ(crs84.projection.kind(), Projection::Kind::LocalTransverseMercator);
  auto e = test::expect_input_error([] {
    parse_geojson_text(R"({"type":"Point","coordinates":[1,2],"crs":{"type":"name","properties":{"name":"EPSG:99999"}}})",
                       "bad.geojson");
  });
  EXPECT_EQ(e.file(), "bad.geojson");
  EXPECT_THAT(e.message(), ::testing::HasSubstr("crs"));
  EXPECT_THAT(e.message(), ::testing::HasSubstr("EPSG:99999"));
  e = test::expect_input_error([] {
    parse_geojson_text(R"({"type":"Point","coordinates":[1,2],"crs":{"type":"link","properties":{"href":"x.prj"}}})",
                       "link.geojson");
  });
  EXPECT_THAT(e.message(), ::testing::HasSubstr("link"));
  e = test::expect_input_error(
      [] { parse_geojson_text(R"({"type":"Point","coordinates":[1,2],"crs":"EPSG:32616"})", "str.geojson"); });
  EXPECT_THAT(e.message(), ::testing::HasSubstr("crs"));
}

}  // namespace
}  // namespace shoremesh::io
