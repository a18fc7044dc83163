// --crs and .prj files through PROJ on the command line: honoured forms reach metres with the projection
// said in the summary; unknown ones stop the run with exit code 1 and a message naming them.
#include <algorithm>
#include <cmath>

#include "cli_test_util.hpp"
#include "dem_test_util.hpp"

namespace shoremesh::cli_test {
namespace {

// The Superior mask (1700 x 600 pixels) placed by --map-box in each coordinate system, traced and meshed.
TEST(CrsCommand, EachFormProjAcceptsIsHonouredWithTheProjectionSaid) {
  TempDir dir;
  const std::string mask = quote(superior_mask());
  struct Case {
    std::string crs, box, says;
  };
  const std::vector<Case> cases = {
      // lon/lat, and projected systems whose scale leaves 0.1 % of 1 across the lake (the projection rule),
      // go to a transverse Mercator centred on the data.
      {"EPSG:4326", "-92.5 46.2 -84 49.2", "local transverse Mercator"},
      {"EPSG:3857", "-10297100 5810000 -9350900 6307000", "reprojected from WGS 84 / Pseudo-Mercator"},
      {"EPSG:32616", "166000 5120000 812000 5450000", "reprojected from UTM zone 16N (WGS84)"},
      {"'+proj=longlat +datum=WGS84 +no_defs'", "-92.5 46.2 -84 49.2", "local transverse Mercator"},
      {"'GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],PRIMEM[\"Greenwich\",0],"
       "UNIT[\"degree\",0.0174532925199433]]'",
       "-92.5 46.2 -84 49.2", "local transverse Mercator"},
  };
  for (const Case& c : cases) {
    RunResult r = shoremesh(dir, "info " + mask + " --largest-water --map-box " + c.box + " --crs " + c.crs);
    ASSERT_EQ(r.code, 0) << c.crs << ": " << r.err;
    EXPECT_NE(r.out.find("metres"), std::string::npos) << c.crs << ":\n" << r.out;
    EXPECT_NE(r.out.find(c.says), std::string::npos) << c.crs << ":\n" << r.out;
    // Lake Superior is 82,000 km2; the mask holds it (and a few other lakes when not --largest-water).
    const auto at = r.out.find("water area:");
    ASSERT_NE(at, std::string::npos) << r.out;
    const auto km2 = r.out.find("m^2 = ", at);
    ASSERT_NE(km2, std::string::npos) << r.out;
    const double area = std::stod(r.out.substr(km2 + 6));
    EXPECT_GT(area, 78000) << c.crs;
    EXPECT_LT(area, 86000) << c.crs;
  }
}

TEST(CrsCommand, UnknownCodeJunkWktAndGarbagePrjAreRefusedNamingThem) {
  TempDir dir;
  const std::string mask = quote(superior_mask());
  for (const std::string crs : {"EPSG:99999", "'PROJCS[\"garbage'", "'+proj=nonsense'"}) {
    RunResult r = shoremesh(dir, "info " + mask + " --map-box -92.5 46.2 -84 49.2 --crs " + crs);
    EXPECT_EQ(r.code, 1) << crs << ": " << r.err;
    const std::string bare = crs.front() == '\'' ? crs.substr(1, crs.size() - 2) : crs;
    EXPECT_NE(r.err.find(bare), std::string::npos) << r.err;
  }
  // A world file with a garbage .prj beside it.
  fs::copy_file(superior_mask(), dir / "bay.png");
  fs::copy_file(samples("superior/superior_watermask_h.wld"), dir / "bay.wld");
  write_file(dir / "bay.prj", "PROJCS[\"garbage");
  RunResult r = shoremesh(dir, "mesh bay.png -o bay.msh");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("bay.prj"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("garbage"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "bay.msh"));
}

double water_km2(const std::string& out) {
  const auto at = out.find("water area:");
  const auto eq = out.find("m^2 = ", at);
  if (at == std::string::npos || eq == std::string::npos) return -1;
  return std::stod(out.substr(eq + 6));
}

// The largest |k - 1| of the summary's "scale A .. B".
double worst_scale_error(const std::string& out) {
  const auto at = out.find("scale ");
  const auto dots = out.find(" .. ", at);
  if (at == std::string::npos || dots == std::string::npos) return -1;
  return std::max(std::abs(std::stod(out.substr(at + 6)) - 1), std::abs(std::stod(out.substr(dots + 4)) - 1));
}

// Lake Superior's GSHHG rings (82,078 km2 geodesic) span 7.9 degrees of longitude: UTM 16N's scale runs
// from 0.9996 to 1.0015 over them, the local transverse Mercator's from 1 to 1.0012.
TEST(CrsCommand, SuperiorLonLatIsMeshedInALocalTransverseMercatorAndTheSummarySaysTheScale) {
  TempDir dir;
  const std::string rings = quote(samples("superior/lake_superior_lonlat.csv"));
  const RunResult local = shoremesh(dir, "info " + rings + " --lonlat");
  ASSERT_EQ(local.code, 0) << local.err;
  EXPECT_THAT(local.out, ::testing::HasSubstr("projected lon/lat to metres with local transverse Mercator at 47."));
  EXPECT_THAT(local.out, ::testing::HasSubstr("scale 1.00000 .. 1.001"));
  const RunResult utm = shoremesh(dir, "info " + rings + " --lonlat --projection utm");
  ASSERT_EQ(utm.code, 0) << utm.err;
  EXPECT_THAT(utm.out, ::testing::HasSubstr("UTM zone 16N (WGS84), scale 0.99960 .. 1.001"));
  EXPECT_LT(worst_scale_error(local.out), worst_scale_error(utm.out)) << local.out << utm.out;
  EXPECT_GT(worst_scale_error(utm.out), 1e-3);
  EXPECT_NEAR(water_km2(local.out), 82078, 0.001 * 82078);
}

// A 40 x 30 DEM with a lake of 30 x 20 cells in the middle.
std::vector<float> z40x30() {
  std::vector<float> z(40 * 30, 10.0f);
  for (int r = 5; r < 25; ++r)
    for (int c = 5; c < 35; ++c) z[static_cast<std::size_t>(r) * 40 + c] = -15.0f;
  return z;
}

// A projected DEM inside its area keeps its own metres (the file's coordinates are the mesh's).
TEST(CrsCommand, UtmAndNationalGridDemsInsideTheirAreaAreMeshedInTheirOwnMetres) {
  TempDir dir;
  std::vector<float> z(20 * 20, 10.0f);
  for (int r = 4; r < 16; ++r)
    for (int c = 4; c < 16; ++c) z[static_cast<std::size_t>(r) * 20 + c] = -20.0f;
  write_dem(dir / "lake.tif", 20, 20, z);
  const RunResult r = shoremesh(dir, "mesh --dem lake.tif -o lake.msh");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("meshed in UTM zone 10N (WGS84): its scale 0.99"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("stays within 0.1 % of 1"));
  // The lake's cells are 400,000 + 4..16 km east: so are the mesh's nodes.
  EXPECT_THAT(r.out, ::testing::HasSubstr("box: origin (40"));
  // A national grid too (British National Grid, 10 km around London: scale 0.9998), through PROJ.
  write_dem(dir / "bng.tif", 40, 30, z40x30(), std::nullopt, {530000, 250, 0, 185000, 0, -250}, 27700);
  const RunResult bng = shoremesh(dir, "mesh --dem bng.tif -o bng.14");
  ASSERT_EQ(bng.code, 0) << bng.err;
  EXPECT_THAT(bng.out, ::testing::HasSubstr("meshed in OSGB36 / British National Grid: its scale 0.9998"));
  EXPECT_THAT(bng.out, ::testing::HasSubstr("box: origin (53"));
  // fort.14 is in lon/lat, back through PROJ: the lake lies at 0.1 W .. 0.03 E, 51.47 .. 51.52 N.
  const Fort14 f = parse_fort14(read_file(dir / "bng.14"));
  ASSERT_FALSE(f.nodes.empty());
  for (const auto& [id, n] : f.nodes) {
    EXPECT_GT(n.x, -0.13);
    EXPECT_LT(n.x, 0.06);
    EXPECT_GT(n.y, 51.45);
    EXPECT_LT(n.y, 51.54);
  }
}

}  // namespace
}  // namespace shoremesh::cli_test
