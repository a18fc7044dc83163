// --crs and .prj files through PROJ on the command line: honoured forms reach metres with the projection
// said in the summary; unknown ones stop the run with exit code 1 and a message naming them.
#include "cli_test_util.hpp"

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
      {"EPSG:4326", "-92.5 46.2 -84 49.2", "UTM zone 16N"},
      {"EPSG:3857", "-10297100 5810000 -9350900 6307000", "taken through WGS 84 lon/lat"},
      {"EPSG:32616", "166000 5120000 812000 5450000", "WGS 84 / UTM zone 16N"},
      {"'+proj=longlat +datum=WGS84 +no_defs'", "-92.5 46.2 -84 49.2", "UTM zone 16N"},
      {"'GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],PRIMEM[\"Greenwich\",0],"
       "UNIT[\"degree\",0.0174532925199433]]'",
       "-92.5 46.2 -84 49.2", "UTM zone 16N"},
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

}  // namespace
}  // namespace shoremesh::cli_test
