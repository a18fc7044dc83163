// Coordinate systems through GDAL/OGR (PROJ): every form PROJ accepts is honoured with the right kind, and
// text PROJ cannot read is refused with a message naming it.
#include <cmath>

#include "io_test_util.hpp"
#include "shoremesh/io/georeference.hpp"

namespace shoremesh::io {
namespace {

using ::testing::HasSubstr;
using test::expect_input_error;

void expect_utm(const std::string& text, int zone, bool north) {
  const auto cs = parse_coordinate_system(text);
  EXPECT_EQ(cs.kind, CoordinateSystem::Kind::Utm) << text;
  EXPECT_EQ(cs.zone, zone) << text;
  EXPECT_EQ(cs.north, north) << text;
}

TEST(CoordinateSystems, EpsgWktAndProjStringsAreHonoured) {
  EXPECT_EQ(parse_coordinate_system("EPSG:4326").kind, CoordinateSystem::Kind::Geographic);
  expect_utm("EPSG:32616", 16, true);
  const auto merc = parse_coordinate_system("EPSG:3857");
  EXPECT_EQ(merc.kind, CoordinateSystem::Kind::Other);
  EXPECT_THAT(merc.name, HasSubstr("Pseudo-Mercator"));
  // Web Mercator goes through lon/lat: x = R * lon, y = R * ln(tan(pi/4 + lat/2)) on the sphere R = 6378137.
  const auto to_lonlat = lonlat_transform(merc);
  const double R = 6378137, pi = std::acos(-1.0);
  const Point2 ll = to_lonlat({R * (-124.0) * pi / 180, R * std::log(std::tan(pi / 4 + 49.0 * pi / 360))});
  EXPECT_NEAR(ll[0], -124.0, 1e-9);
  EXPECT_NEAR(ll[1], 49.0, 1e-9);
  const auto wkt = parse_coordinate_system(
      "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],PRIMEM[\"Greenwich\",0],"
      "UNIT[\"degree\",0.0174532925199433]]");
  EXPECT_EQ(wkt.kind, CoordinateSystem::Kind::Geographic);
  expect_utm("+proj=utm +zone=33 +south +datum=WGS84 +units=m +no_defs", 33, false);
  // Another datum's lon/lat is not taken as WGS 84's: it goes through PROJ (NAD27 is tens of metres off).
  const auto nad27 = parse_coordinate_system("EPSG:4267");
  EXPECT_EQ(nad27.kind, CoordinateSystem::Kind::Other);
}

TEST(CoordinateSystems, UnknownCodesJunkWktAndGarbagePrjAreRefusedNamingThem) {
  auto e = expect_input_error([] { parse_coordinate_system("EPSG:99999"); });
  EXPECT_THAT(e.message(), HasSubstr("EPSG:99999"));
  e = expect_input_error([] { parse_coordinate_system("PROJCS[\"garbage", "bay.prj"); });
  EXPECT_EQ(e.file(), "bay.prj");
  EXPECT_THAT(e.message(), HasSubstr("PROJCS[\"garbage"));
  e = expect_input_error([] { parse_coordinate_system("GEOGCS[\"x\",DATUM[nonsense]]"); });
  EXPECT_THAT(e.message(), HasSubstr("does not know"));
  e = expect_input_error([] { parse_coordinate_system("+proj=nonexistent"); });
  EXPECT_THAT(e.message(), HasSubstr("+proj=nonexistent"));
  // A file name is not read as a coordinate system.
  e = expect_input_error([] { parse_coordinate_system("/etc/passwd"); });
  EXPECT_THAT(e.message(), HasSubstr("/etc/passwd"));
}

}  // namespace
}  // namespace shoremesh::io
