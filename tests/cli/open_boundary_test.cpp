// --open-boundary: a user's line makes the mesh boundary along it an open (ocean) boundary in fort.14, beside
// the automatic ones, with the rest land (IBTYPE 20 mainland, 21 islands); fort.14 read back by the parser of
// dem_test_util.hpp (written from the ADCIRC manual). Bad files are refused naming the file and the line or
// feature, and nothing is written.
#include <ogr_spatialref.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <map>
#include <random>
#include <set>

#include "cli_test_util.hpp"
#include "dem_test_util.hpp"
#include "shoremesh/io/point_set_csv.hpp"

namespace shoremesh::cli_test {
namespace {

// A bay 0.1 degrees wide (lon 10.0 .. 10.1, lat 45.00 .. 45.05, water inside) with one island; its east
// side is open sea.
const char* kBay =
    "10.0,45.0\n10.1,45.0\n10.1,45.05\n10.0,45.05\n10.0,45.0\n"
    "\n"
    "10.04,45.02\n10.04,45.03\n10.05,45.03\n10.05,45.02\n10.04,45.02\n";
constexpr double kEast = 10.1;

struct BayRun {
  RunResult run;
  Fort14 f;
};

BayRun mesh_bay(const TempDir& dir, const std::string& extra) {
  write_file(dir / "bay.rings", kBay);
  BayRun b;
  b.run = shoremesh(dir, "mesh bay.rings --lonlat --spacing 600 -o bay.14 " + extra);
  if (b.run.code == 0) b.f = parse_fort14(read_file(dir / "bay.14"));
  return b;
}

TEST(OpenBoundary, UserLineMakesTheBaysMouthOpenAndTheRestLandIslandsStay21) {
  TempDir dir;
  const BayRun closed = mesh_bay(dir, "");
  ASSERT_EQ(closed.run.code, 0) << closed.run.err;
  EXPECT_TRUE(closed.f.open.empty()) << "without the line the bay is closed land";

  write_file(dir / "mouth.txt", "# the bay's mouth, lon,lat\n10.1,45.0\n10.1,45.05\n");
  const BayRun b = mesh_bay(dir, "--open-boundary mouth.txt");
  ASSERT_EQ(b.run.code, 0) << b.run.err;
  EXPECT_THAT(b.run.out, ::testing::HasSubstr("open boundaries also along 1 line(s) of mouth.txt"));
  const Fort14& f = b.f;
  expect_boundary_listed_once(f);
  ASSERT_EQ(f.open.size(), 1u);
  const auto& open = f.open.front();
  EXPECT_EQ(open.type, 0);
  // The open string is every node on the east side (fort.14 is in lon/lat), corners included, in order.
  // The side is cut straight in the projected plane: its nodes are within 1e-8 degrees (a millimetre) of
  // the meridian.
  std::size_t east_nodes = 0;
  for (const auto& [id, n] : f.nodes) east_nodes += std::abs(n.x - kEast) < 1e-7;
  EXPECT_EQ(open.nodes.size(), east_nodes);
  EXPECT_GT(east_nodes, 8u);  // 5.6 km at 600 m
  for (long id : open.nodes) EXPECT_NEAR(f.nodes.at(id).x, kEast, 1e-7);
  for (std::size_t j = 0; j + 1 < open.nodes.size(); ++j)
    EXPECT_NE(f.nodes.at(open.nodes[j]).y < f.nodes.at(open.nodes[j + 1]).y,
              f.nodes.at(open.nodes[0]).y > f.nodes.at(open.nodes[1]).y)
        << "the open string runs one way along the mouth";
  // Land: the mainland from one end of the open string to the other (IBTYPE 20, not closed), and the
  // island closed (IBTYPE 21).
  ASSERT_EQ(f.land.size(), 2u);
  EXPECT_EQ(f.land[0].type, 20);
  EXPECT_EQ(f.land[0].nodes.front(), open.nodes.back());
  EXPECT_EQ(f.land[0].nodes.back(), open.nodes.front());
  EXPECT_EQ(f.land[1].type, 21);
  EXPECT_EQ(f.land[1].nodes.front(), f.land[1].nodes.back());
  // Nodes and elements are those of the closed run: the line changes the boundary's kind only.
  EXPECT_EQ(f.nodes.size(), closed.f.nodes.size());
  EXPECT_EQ(f.triangles, closed.f.triangles);

  // The same line as GeoJSON gives the same file.
  write_file(dir / "mouth.geojson",
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"mouth"},)"
             R"("geometry":{"type":"LineString","coordinates":[[10.1,45.0],[10.1,45.05]]}}]})");
  const std::string text_file = read_file(dir / "bay.14");
  const BayRun g = mesh_bay(dir, "--open-boundary mouth.geojson");
  ASSERT_EQ(g.run.code, 0) << g.run.err;
  EXPECT_EQ(read_file(dir / "bay.14"), text_file);
  // And in UTM 32N metres, named by a legacy "crs" (PROJ puts them in the same place, within nanometres).
  OGRSpatialReference ll, utm;
  ll.importFromEPSG(4326);
  utm.importFromEPSG(32632);
  for (auto* s : {&ll, &utm}) s->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&ll, &utm));
  double x[2] = {kEast, kEast}, y[2] = {45.0, 45.05};
  ASSERT_TRUE(t->Transform(2, x, y));
  char coords[200];
  std::snprintf(coords, sizeof coords, "[[%.17g,%.17g],[%.17g,%.17g]]", x[0], y[0], x[1], y[1]);
  write_file(dir / "mouth_utm.geojson", std::string(R"({"type":"LineString","crs":{"type":"name","properties":)") +
                                            R"({"name":"urn:ogc:def:crs:EPSG::32632"}},"coordinates":)" + coords + "}");
  const BayRun u = mesh_bay(dir, "--open-boundary mouth_utm.geojson");
  ASSERT_EQ(u.run.code, 0) << u.run.err;
  EXPECT_EQ(read_file(dir / "bay.14"), text_file);
}

TEST(OpenBoundary, ALineBesideTheShoreNeedsTheDistanceThatReachesIt) {
  TempDir dir;
  // 0.0001 degrees (7.9 m) east of the mouth: off the boundary by default, on it within 20 m.
  write_file(dir / "near.txt", "10.1001,44.99\n10.1001,45.06\n");
  const BayRun strict = mesh_bay(dir, "--open-boundary near.txt");
  EXPECT_EQ(strict.run.code, 1);
  EXPECT_THAT(strict.run.err, ::testing::HasSubstr("near.txt:1"));
  EXPECT_THAT(strict.run.err, ::testing::HasSubstr("lies along no boundary edge"));
  EXPECT_THAT(strict.run.err, ::testing::HasSubstr("--open-boundary-distance"));
  EXPECT_FALSE(fs::exists(dir / "bay.14")) << "a run writes all of its outputs or none";
  const BayRun wide = mesh_bay(dir, "--open-boundary near.txt --open-boundary-distance 20");
  ASSERT_EQ(wide.run.code, 0) << wide.run.err;
  ASSERT_EQ(wide.f.open.size(), 1u);
  for (long id : wide.f.open.front().nodes) EXPECT_NEAR(wide.f.nodes.at(id).x, kEast, 1e-7);
}

TEST(OpenBoundary, BadFilesAreRefusedNamingTheFileAndTheLineOrFeature) {
  TempDir dir;
  struct Case {
    std::string name, text, says;
  };
  const std::vector<Case> cases = {
      {"word.txt", "10.1,45.0\n10.1,45.05\n10.1,north\n", "word.txt:3: \"north\" is not a number"},
      {"three.txt", "10.1,45.0,7\n10.1,45.05\n", "three.txt:1: expected two numbers (lon,lat), found 3 fields"},
      {"single.txt", "10.1,45.0\n\n10.1,45.0\n10.1,45.05\n", "single.txt:1: an open-boundary line needs at least two points"},
      {"far.txt", "10.2,45.0\n10.2,45.05\n", "far.txt:1 lies along no boundary edge of the mesh: the nearest boundary node is 78"},
      {"poly.geojson",
       R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[[10.1,45.0],[10.1,45.05]]}},)"
       R"({"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[10,45],[10.1,45],[10.1,45.05],[10,45]]]}}]})",
       "poly.geojson: features[1].geometry: an open boundary is a LineString or MultiLineString, not a Polygon"},
      {"deg.geojson", R"({"type":"LineString","coordinates":[[10.1,45.0],[1000,45.05]]})",
       "deg.geojson: (root).coordinates[1]: position 1000, 45.05 is not lon/lat"},
      {"code.geojson",
       R"({"type":"LineString","crs":{"type":"name","properties":{"name":"EPSG:99999"}},"coordinates":[[1,2],[3,4]]})",
       "code.geojson: crs: PROJ does not know the coordinate system \"EPSG:99999\""},
      {"empty.txt", "# nothing\n", "empty.txt: no open-boundary line"},
  };
  write_file(dir / "bay.rings", kBay);
  for (const Case& c : cases) {
    write_file(dir / c.name, c.text);
    const RunResult r = shoremesh(dir, "mesh bay.rings --lonlat --spacing 600 -o out.14 --open-boundary " + c.name);
    EXPECT_EQ(r.code, 1) << c.name << ": " << r.err;
    EXPECT_THAT(r.err, ::testing::HasSubstr(c.says)) << c.name;
    EXPECT_FALSE(fs::exists(dir / "out.14")) << c.name;
  }
  const RunResult missing = shoremesh(dir, "mesh bay.rings --lonlat -o out.14 --open-boundary nowhere.txt");
  EXPECT_EQ(missing.code, 2) << missing.err;
  EXPECT_THAT(missing.err, ::testing::HasSubstr("nowhere.txt"));
}

// Lemma 7.2 for exports: after each random edit (loose points added near the shore and the mouth, which
// splits their segments, and removed) the session's fort.14 equals a fresh run's on the edited input with
// the session's box, its open string included. In map units: the line is x,y in the mesh's own units.
TEST(OpenBoundary, EditSessionsFort14EqualsAFreshRunAfterEachRandomEdit) {
  TempDir dir;
  write_file(dir / "bay.rings", "0,0\n100,0\n100,60\n0,60\n0,0\n\n40,25\n40,35\n50,35\n50,25\n40,25\n");
  write_file(dir / "mouth.txt", "100,-1\n100,61\n");
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(60, 99.9), y(0.1, 59.9);
  std::map<std::size_t, std::array<double, 2>> loose;  // by id: the 8 ring points are ids 0..7
  std::size_t next_id = 8;
  std::string edits;
  std::vector<std::map<std::size_t, std::array<double, 2>>> after;
  for (int k = 0; k < 8; ++k) {
    if (k % 4 == 3 && !loose.empty()) {
      auto it = loose.begin();
      std::advance(it, static_cast<long>(rng() % loose.size()));
      edits += "remove " + std::to_string(it->first) + "\n";
      loose.erase(it);
    } else {
      const std::array<double, 2> p{std::round(x(rng) * 100) / 100, std::round(y(rng) * 100) / 100};
      edits += "add " + io::format_double(p[0]) + " " + io::format_double(p[1]) + "\n";
      loose[next_id++] = p;
    }
    edits += "export e" + std::to_string(k) + ".14\nexport e" + std::to_string(k) + ".csv\n";
    after.push_back(loose);
  }
  const RunResult r = shoremesh(dir, "edit bay.rings --open-boundary mouth.txt --edits -", edits);
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  for (int k = 0; k < 8; ++k) {
    const std::string n = std::to_string(k);
    std::string text = "x,y\n";
    for (const auto& [id, p] : after[static_cast<std::size_t>(k)])
      text += io::format_double(p[0]) + "," + io::format_double(p[1]) + "\n";
    write_file(dir / ("loose" + n + ".csv"), text);
    const std::string box = lines_of(read_file(dir / ("e" + n + ".csv"))).at(0).substr(6);
    const RunResult fresh =
        shoremesh(dir, "mesh -q bay.rings loose" + n + ".csv --open-boundary mouth.txt --box " + box + " -o f" + n + ".14");
    ASSERT_EQ(fresh.code, 0) << fresh.err;
    const std::string edited = read_file(dir / ("e" + n + ".14"));
    EXPECT_EQ(edited, read_file(dir / ("f" + n + ".14"))) << "after edit " << k;
    const Fort14 f = parse_fort14(edited);
    ASSERT_EQ(f.open.size(), 1u) << "after edit " << k;
    for (long id : f.open.front().nodes) EXPECT_EQ(f.nodes.at(id).x, 100.0) << "after edit " << k;
  }
}

}  // namespace
}  // namespace shoremesh::cli_test
