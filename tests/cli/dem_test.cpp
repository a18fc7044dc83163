// Terrain and bathymetry from a DEM, end to end through the command line: the Salish Sea sample traced at
// 0 m, its fort.14 read back by a parser written here from the ADCIRC manual's fort.14 description (not
// the project's reader), the depths checked against the raster read with GDAL and averaged here, the
// boundaries checked edge by edge, meshio reading the .msh and .vtu depths, and bad DEMs refused.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "cli_test_util.hpp"
#include "dem_test_util.hpp"

namespace shoremesh::cli_test {
namespace {

const std::string kSalish = samples("salish/salish_sea_topobathy.tif");

// The raster read with GDAL here, and lon/lat <-> the raster's CRS and a local equal-area projection.
struct Raster : RasterBand {
  std::unique_ptr<OGRCoordinateTransformation> to_raster, raster_to_lonlat, to_area;
  explicit Raster(const std::string& path) : RasterBand(path) {
    OGRSpatialReference ll, area;
    OGRSpatialReference raster(srs);
    ll.importFromEPSG(4326);
    area.importFromProj4("+proj=laea +lat_0=49 +lon_0=-124 +datum=WGS84 +units=m");
    for (auto* s : {&ll, &area, &raster}) s->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    to_raster.reset(OGRCreateCoordinateTransformation(&ll, &raster));
    raster_to_lonlat.reset(OGRCreateCoordinateTransformation(&raster, &ll));
    to_area.reset(OGRCreateCoordinateTransformation(&ll, &area));
  }
  // Cell coordinates (centre convention) of a lon/lat point.
  std::array<double, 2> cell(double lon, double lat) const {
    double x = lon, y = lat;
    to_raster->Transform(1, &x, &y);
    return {(x - g[0]) / g[1] - 0.5, (y - g[3]) / g[5] - 0.5};
  }
  std::array<double, 2> centre_lonlat(int c, int r) const {
    double x = g[0] + (c + 0.5) * g[1], y = g[3] + (r + 0.5) * g[5];
    raster_to_lonlat->Transform(1, &x, &y);
    return {x, y};
  }
  std::array<double, 2> equal_area(double lon, double lat) const {
    to_area->Transform(1, &lon, &lat);
    return {lon, lat};
  }
};

struct SalishRun {
  TempDir dir;
  RunResult run;
  Fort14 f;
  SalishRun() {
    run = shoremesh(dir, "mesh --dem " + quote(kSalish) + " --min-area 1 -o salish.14");
    if (run.code == 0) f = parse_fort14(read_file(dir / "salish.14"));
  }
};

SalishRun& salish() {
  static SalishRun r;  // one run shared by the Salish tests
  return r;
}

TEST(SalishSeaDem, WaterMeshAreaIsWithin3PercentOfTheDemsBelowZeroArea) {
  const SalishRun& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  const Raster dem(kSalish);
  // Below-zero area: each cell's square, measured in the equal-area projection from its corners.
  double below = 0;
  for (int r = 0; r < dem.h; ++r)
    for (int c = 0; c < dem.w; ++c) {
      if (!(dem.at(c, r) < 0)) continue;
      std::array<std::array<double, 2>, 4> q;
      const double corners[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
      for (int k = 0; k < 4; ++k) {
        // corners of cell (c, r): centre +- half a cell
        double x = dem.g[0] + (c + 0.5 + corners[k][0]) * dem.g[1], y = dem.g[3] + (r + 0.5 + corners[k][1]) * dem.g[5];
        dem.raster_to_lonlat->Transform(1, &x, &y);
        q[k] = dem.equal_area(x, y);
      }
      double a = 0;
      for (int k = 0; k < 4; ++k) a += q[k][0] * q[(k + 1) % 4][1] - q[(k + 1) % 4][0] * q[k][1];
      below += std::abs(a) / 2;
    }
  double mesh = 0;
  for (const auto& t : s.f.triangles) {
    std::array<std::array<double, 2>, 3> p;
    for (int k = 0; k < 3; ++k) p[k] = dem.equal_area(s.f.nodes.at(t[k]).x, s.f.nodes.at(t[k]).y);
    mesh += ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1])) / 2;
  }
  EXPECT_GT(below, 2.5e10);  // about 29,000 km2
  EXPECT_NEAR(mesh / below, 1.0, 0.03) << "mesh " << mesh / 1e6 << " km2, below zero " << below / 1e6 << " km2";
}

TEST(SalishSeaDem, EveryNodeDepthLiesBetweenTheDemExtremesOverItsVoronoiCell) {
  const SalishRun& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  const Raster dem(kSalish);
  // Nodes in the equal-area plane; every DEM cell centre goes to its nearest node (brute force, here).
  std::vector<long> ids;
  std::vector<std::array<double, 2>> xy;
  for (const auto& [id, n] : s.f.nodes) ids.push_back(id), xy.push_back(dem.equal_area(n.x, n.y));
  std::vector<double> lo(ids.size(), INFINITY), hi(ids.size(), -INFINITY);
  for (int r = 0; r < dem.h; ++r)
    for (int c = 0; c < dem.w; ++c) {
      const auto ll = dem.centre_lonlat(c, r);
      const auto p = dem.equal_area(ll[0], ll[1]);
      std::size_t best = 0;
      double bd = INFINITY;
      for (std::size_t i = 0; i < xy.size(); ++i) {
        const double d = std::hypot(xy[i][0] - p[0], xy[i][1] - p[1]);
        if (d < bd) bd = d, best = i;
      }
      const double depth = -dem.at(c, r);
      lo[best] = std::min(lo[best], depth), hi[best] = std::max(hi[best], depth);
    }
  std::size_t with_cells = 0, deep = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const Fort14::Node& n = s.f.nodes.at(ids[i]);
    // A cell holding no DEM cell centre: the node's value is bilinear between the four centres around it.
    const auto cc = dem.cell(n.x, n.y);
    const int c0 = std::clamp(static_cast<int>(std::floor(cc[0])), 0, dem.w - 2);
    const int r0 = std::clamp(static_cast<int>(std::floor(cc[1])), 0, dem.h - 2);
    double a = lo[i], b = hi[i];
    if (std::isfinite(a)) ++with_cells;
    for (int dr = 0; dr <= 1; ++dr)
      for (int dc = 0; dc <= 1; ++dc) a = std::min(a, -double(dem.at(c0 + dc, r0 + dr))), b = std::max(b, -double(dem.at(c0 + dc, r0 + dr)));
    // The mesh is the water below 0 m: heights above it are taken as 0 m (depth >= 0).
    a = std::max(a, 0.0), b = std::max(b, 0.0);
    EXPECT_GE(n.depth, a - 1e-3) << "node " << ids[i] << " at " << n.x << ", " << n.y;
    EXPECT_LE(n.depth, b + 1e-3) << "node " << ids[i] << " at " << n.x << ", " << n.y;
    deep += n.depth > 1000;
  }
  EXPECT_GT(with_cells, ids.size() / 4);  // the cell means, not only the bilinear fallback, are checked
  EXPECT_GT(deep, 0u);                    // positive down: the Pacific floor is over 1,000 m deep
}

TEST(SalishSeaDem, PacificEdgeIsOpenEveryOtherBoundaryIsLandIslandsAreType21) {
  const SalishRun& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  const Fort14& f = s.f;
  // Every boundary edge of the mesh (used by one triangle) is in exactly one segment, open or land.
  expect_boundary_listed_once(f);

  // Open segments lie on the raster's edge (lon -126, lat 48 or 50, within a cell), and the longest one
  // runs down the Pacific (west) edge.
  ASSERT_FALSE(f.open.empty());
  double west_span = 0;
  for (const auto& seg : f.open) {
    EXPECT_EQ(seg.type, 0);
    double lat_lo = 90, lat_hi = -90;
    for (long id : seg.nodes) {
      const auto& n = f.nodes.at(id);
      const bool edge = std::abs(n.x + 126.0) < 0.05 || std::abs(n.y - 48.005) < 0.04 || std::abs(n.y - 49.995) < 0.04;
      EXPECT_TRUE(edge) << "open node " << id << " at " << n.x << ", " << n.y << " is not on the DEM's edge";
      if (std::abs(n.x + 126.0) < 0.05) lat_lo = std::min(lat_lo, n.y), lat_hi = std::max(lat_hi, n.y);
    }
    west_span = std::max(west_span, lat_hi - lat_lo);
  }
  EXPECT_GT(west_span, 1.0);  // 48.0 .. 49.2 N, broken only where Vancouver Island's headlands touch it

  // Land: mainland segments (20) join open segments at both ends; islands (21) are closed and clockwise.
  std::set<long> open_ends;
  for (const auto& seg : f.open) open_ends.insert(seg.nodes.front()), open_ends.insert(seg.nodes.back());
  std::size_t islands = 0;
  for (const auto& seg : f.land) {
    ASSERT_TRUE(seg.type == 20 || seg.type == 21) << seg.type;
    if (seg.type == 20) {
      EXPECT_TRUE(open_ends.count(seg.nodes.front()) && open_ends.count(seg.nodes.back()));
      continue;
    }
    ++islands;
    EXPECT_EQ(seg.nodes.front(), seg.nodes.back());
    double a = 0;
    for (std::size_t j = 0; j + 1 < seg.nodes.size(); ++j) {
      const auto &p = f.nodes.at(seg.nodes[j]), &q = f.nodes.at(seg.nodes[j + 1]);
      a += p.x * q.y - q.x * p.y;
    }
    EXPECT_LT(a, 0) << "island segments run clockwise (water on their left)";
  }
  EXPECT_GT(islands, 10u);  // the Gulf and San Juan Islands
}

TEST(SalishSeaDem, InfoReadsTheFort14AndMshBackAndMeshioReadsTheDepths) {
  const SalishRun& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  RunResult info = shoremesh(s.dir, "info salish.14");
  ASSERT_EQ(info.code, 0) << info.err;
  std::size_t land20 = 0, land21 = 0;
  double sum = 0, lo = INFINITY, hi = -INFINITY;
  for (const auto& seg : s.f.land) ++(seg.type == 20 ? land20 : land21);
  for (const auto& [id, n] : s.f.nodes) sum += n.depth, lo = std::min(lo, n.depth), hi = std::max(hi, n.depth);
  EXPECT_NE(info.out.find(std::to_string(s.f.nodes.size()) + " nodes, " + std::to_string(s.f.triangles.size()) + " triangles"),
            std::string::npos) << info.out;
  EXPECT_NE(info.out.find("open boundaries: " + std::to_string(s.f.open.size()) + " segments"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("IBTYPE 20: " + std::to_string(land20) + "; IBTYPE 21: " + std::to_string(land21)),
            std::string::npos) << info.out;
  EXPECT_NE(info.out.find("depths: " + std::to_string(s.f.nodes.size()) + " nodes"), std::string::npos) << info.out;

  // The same mesh to .msh and .vtu: meshio finds the same nodes and the same depths (sum and extremes).
  for (const std::string out : {"salish.msh", "salish.vtu"}) {
    RunResult r = shoremesh(s.dir, "mesh --dem " + quote(kSalish) + " --min-area 1 -q -o " + out);
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string script = "import meshio; m = meshio.read('" + out + "'); d = m.point_data['depth']; "
                               "print(len(m.points), len(m.cells_dict['triangle']), repr(float(d.sum())), "
                               "repr(float(d.min())), repr(float(d.max())))";
    const std::string cmd = "cd " + quote(s.dir.path().string()) + " && /usr/bin/python3 -c " + quote(script) +
                            " > meshio.out 2> meshio.err";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read_file(s.dir / "meshio.err");
    std::istringstream words(read_file(s.dir / "meshio.out"));
    std::size_t points = 0, triangles = 0;
    double msum = 0, mlo = 0, mhi = 0;
    words >> points >> triangles >> msum >> mlo >> mhi;
    EXPECT_EQ(points, s.f.nodes.size()) << out;
    EXPECT_EQ(triangles, s.f.triangles.size()) << out;
    EXPECT_NEAR(msum, sum, 1e-6 * std::abs(sum)) << out;
    EXPECT_DOUBLE_EQ(mlo, lo) << out;
    EXPECT_DOUBLE_EQ(mhi, hi) << out;
    if (out == "salish.msh") {
      RunResult i = shoremesh(s.dir, "info salish.msh");
      ASSERT_EQ(i.code, 0) << i.err;
      EXPECT_NE(i.out.find("depths: " + std::to_string(points) + " nodes"), std::string::npos) << i.out;
    }
  }
}

// A bowl: water (below 0) in the middle, land around it.
std::vector<float> bowl(int w, int h) {
  std::vector<float> z;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) z.push_back(static_cast<float>(std::hypot(c - (w - 1) / 2.0, r - (h - 1) / 2.0) * 10 - 60));
  return z;
}

TEST(DemInput, NodataHolesAreFilledFromTheirNeighboursAndSaid) {
  TempDir dir;
  std::vector<float> z = bowl(30, 30);
  for (int r = 12; r < 17; ++r)
    for (int c = 12; c < 17; ++c) z[static_cast<std::size_t>(r) * 30 + c] = -9999;  // a hole in the deep middle
  write_dem(dir / "holes.tif", 30, 30, z, -9999);
  RunResult r = shoremesh(dir, "mesh --dem holes.tif -o holes.14");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("25 nodata cells of the DEM filled from their neighbours"), std::string::npos) << r.out;
  const Fort14 f = parse_fort14(read_file(dir / "holes.14"));
  for (const auto& [id, n] : f.nodes) {
    EXPECT_LT(n.depth, 61) << "a nodata value leaked into the depths";  // the bowl is at most 60 m deep
    EXPECT_GE(n.depth, 0);
  }
  EXPECT_EQ(f.open.size(), 0u);  // the water does not reach the DEM's edge
  ASSERT_EQ(f.land.size(), 1u);
  EXPECT_EQ(f.land[0].type, 20);  // a closed mainland shore
  EXPECT_EQ(f.land[0].nodes.front(), f.land[0].nodes.back());
}

TEST(DemInput, AllLandAllWaterOneCellAndTruncatedDemsAreRefusedNamingTheFile) {
  TempDir dir;
  write_dem(dir / "land.tif", 8, 8, std::vector<float>(64, 12.5f));
  write_dem(dir / "water.tif", 8, 8, std::vector<float>(64, -3.0f));
  write_dem(dir / "one.tif", 1, 1, {-5.0f});
  write_dem(dir / "bowl.tif", 30, 30, bowl(30, 30));
  {
    const std::string full = read_file(dir / "bowl.tif");
    write_file(dir / "cut.tif", full.substr(0, full.size() / 2));
  }
  write_dem(dir / "nodata.tif", 4, 4, std::vector<float>(16, -9999.0f), -9999);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"land.tif", "all land"}, {"water.tif", "all water"}, {"one.tif", "all water"},
      {"cut.tif", "cut.tif"},   {"nodata.tif", "holds no data"}};
  for (const auto& [file, says] : cases) {
    RunResult r = shoremesh(dir, "mesh --dem " + file + " -o out.14");
    EXPECT_EQ(r.code, 1) << file << ": " << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.14")) << file;
  }
  // A text file that is no raster.
  write_file(dir / "junk.tif", "not a raster\n");
  RunResult r = shoremesh(dir, "mesh --dem junk.tif -o out.14");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("junk.tif"), std::string::npos) << r.err;
}

// The bowl as an ESRI ASCII grid without a coordinate system, 10 map units a cell from (1000, 2000), with
// one NODATA_value cell when `hole`.
std::string bowl_ascii_grid(bool hole) {
  std::string text = "ncols 30\nnrows 30\nxllcorner 1000\nyllcorner 2000\ncellsize 10\nNODATA_value -9999\n";
  const std::vector<float> z = bowl(30, 30);
  for (int r = 0; r < 30; ++r) {
    for (int c = 0; c < 30; ++c) text += (hole && r == 3 && c == 4 ? std::string("-9999") : std::to_string(z[r * 30 + c])) + " ";
    text += "\n";
  }
  return text;
}

// Any raster GDAL reads: an ESRI ASCII grid without a coordinate system is traced in its map units, its
// NODATA_value cells filled, and the depths follow the grid (a bowl 0..60 m deep).
TEST(DemInput, EsriAsciiGridWithNodataIsReadInMapUnits) {
  TempDir dir;
  write_file(dir / "bowl.asc", bowl_ascii_grid(true));
  RunResult r = shoremesh(dir, "mesh --dem bowl.asc -o bowl.14");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("map units"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 nodata cells of the DEM filled"), std::string::npos) << r.out;
  const Fort14 f = parse_fort14(read_file(dir / "bowl.14"));
  double deepest = 0;
  for (const auto& [id, n] : f.nodes) {
    EXPECT_GT(n.x, 1000);
    EXPECT_LT(n.x, 1300);
    EXPECT_GT(n.y, 2000);
    EXPECT_LT(n.y, 2300);
    deepest = std::max(deepest, n.depth);
  }
  EXPECT_GT(deepest, 40);  // the middle of the bowl
  EXPECT_LE(deepest, 60);
}

// Soundings beside a DEM: their points join the mesh (in 2D, not refused as 3D input beside 2D rings) and
// the depths come from the DEM, said in the summary.
TEST(DemInput, SoundingsBesideADemJoinTheMeshWithTheDemsDepths) {
  TempDir dir;
  write_file(dir / "bowl.asc", bowl_ascii_grid(false));
  // Three points in the water of the bowl (its centre is at 1150, 2150), z = 999 (not a depth here).
  write_file(dir / "s.xyz", "1150 2150 999\n1140 2145 999\n1160 2155 999\n");
  RunResult r = shoremesh(dir, "mesh --dem bowl.asc s.xyz -o b.14");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("third column ignored"), std::string::npos) << r.out;
  const Fort14 f = parse_fort14(read_file(dir / "b.14"));
  EXPECT_TRUE(f.nodes.size() > 3);
  std::size_t soundings = 0;
  for (const auto& [id, n] : f.nodes) {
    EXPECT_LT(n.depth, 61);
    soundings += (n.x == 1150 && n.y == 2150) || (n.x == 1140 && n.y == 2145) || (n.x == 1160 && n.y == 2155);
  }
  EXPECT_EQ(soundings, 3u);
}

// Points without a shoreline: no land is known, the mesh ends where the water reaches the box, and
// fort.14 has one closed open boundary and no land boundary.
TEST(DemInput, PointsWithoutRingsAreOpenWaterAllAround) {
  TempDir dir;
  write_file(dir / "p.csv", random_points(200, 50, 30, 9));
  RunResult r = shoremesh(dir, "mesh p.csv -q -o p.14");
  ASSERT_EQ(r.code, 0) << r.err;
  const Fort14 f = parse_fort14(read_file(dir / "p.14"));
  ASSERT_EQ(f.open.size(), 1u);
  EXPECT_EQ(f.open[0].nodes.front(), f.open[0].nodes.back());
  EXPECT_EQ(f.land.size(), 0u);
  std::map<std::pair<long, long>, int> uses;
  for (const auto& t : f.triangles)
    for (int k = 0; k < 3; ++k) ++uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  std::size_t boundary = 0;
  for (const auto& [edge, n] : uses) boundary += n == 1;
  EXPECT_EQ(f.open[0].nodes.size(), boundary + 1);
}

TEST(DemInput, DepthFromGivesDepthsToAnotherInputsMesh) {
  TempDir dir;
  // A square of water in the Strait of Georgia (lon/lat ring), depths from the Salish Sea DEM.
  write_file(dir / "square.csv", "-123.6,49.1\n-123.3,49.1\n-123.3,49.3\n-123.6,49.3\n-123.6,49.1\n");
  RunResult r = shoremesh(dir, "mesh square.csv --lonlat --spacing 2000 --depth-from " + quote(kSalish) + " -o sq.14");
  ASSERT_EQ(r.code, 0) << r.err;
  const Fort14 f = parse_fort14(read_file(dir / "sq.14"));
  double mean = 0;
  for (const auto& [id, n] : f.nodes) mean += n.depth;
  mean /= static_cast<double>(f.nodes.size());
  EXPECT_GT(mean, 50);  // the strait is some 100-400 m deep there
  EXPECT_LT(mean, 500);
  // Without a depth source, --min-depth is a mistake on the command line.
  RunResult bad = shoremesh(dir, "mesh square.csv --lonlat --min-depth 2 -o sq2.14");
  EXPECT_EQ(bad.code, 2) << bad.err;
}

}  // namespace
}  // namespace shoremesh::cli_test
