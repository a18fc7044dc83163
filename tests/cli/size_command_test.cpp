// The size options of `mesh` and `edit` (docs/sizing.md), checked from what the commands write.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <set>

#include "cli_test_util.hpp"
#include "dem_test_util.hpp"

namespace shoremesh::cli_test {
namespace {

// The issue's test: --max-size on Lake Superior, from the exported mesh. Every triangle's longest edge is
// at most H (1 % allowed); where H binds (triangles at least 2H from the shore's nodes) the node count is
// within 1.5x of the equilateral-triangle estimate area / (sqrt 3 / 4 H^2) (the triangle count of an
// equilateral mesh of side H: the seeds' square lattice of side 0.66 H has about that many nodes,
// docs/sizing.md).
TEST(SizeCommand, MaxSizeOnSuperiorBoundsEveryExportedEdgeAndTheNodeCount) {
  TempDir dir;
  const double H = 10000;
  const RunResult r = shoremesh(dir, "mesh " + quote(superior_mask()) + " --largest-water --spacing 10000 --max-size 10000 -o s.node");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("size: h 10000 m .. 10000 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("size seeds among the input points"), std::string::npos) << r.out;
  const TriangleFiles m = read_triangle_files(dir / "s.node");
  ASSERT_GT(m.triangles.size(), 100u);
  auto length = [&](std::size_t a, std::size_t b) { return std::hypot(m.nodes[a][0] - m.nodes[b][0], m.nodes[a][1] - m.nodes[b][1]); };
  double worst = 0;
  std::map<std::pair<std::size_t, std::size_t>, int> edge_uses;
  for (const auto& t : m.triangles)
    for (int i = 0; i < 3; ++i) {
      worst = std::max(worst, length(t[i], t[(i + 1) % 3]));
      ++edge_uses[std::minmax(t[i], t[(i + 1) % 3])];
    }
  EXPECT_LE(worst, 1.01 * H);
  std::vector<std::size_t> shore;
  for (const auto& [e, uses] : edge_uses)
    if (uses == 1) shore.push_back(e.first), shore.push_back(e.second);
  std::vector<double> to_shore(m.nodes.size(), 1e300);
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    for (std::size_t s : shore) to_shore[i] = std::min(to_shore[i], length(i, s));
  double area = 0;
  std::set<std::size_t> nodes;
  for (const auto& t : m.triangles) {
    if (to_shore[t[0]] < 2 * H || to_shore[t[1]] < 2 * H || to_shore[t[2]] < 2 * H) continue;
    const auto &a = m.nodes[t[0]], &b = m.nodes[t[1]], &c = m.nodes[t[2]];
    area += 0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    nodes.insert(t.begin(), t.end());
  }
  const double estimate = area / (std::sqrt(3.0) / 4 * H * H);
  ASSERT_GT(estimate, 100);
  EXPECT_LT(double(nodes.size()), 1.5 * estimate) << nodes.size() << " nodes, estimate " << estimate;
  EXPECT_GT(double(nodes.size()), estimate / 1.5) << nodes.size() << " nodes, estimate " << estimate;
}

TEST(SizeCommand, BadSizesAreRefusedNamingTheOption) {
  TempDir dir;
  write_file(dir / "lake.rings", "0 0\n1000 0\n1000 1000\n0 1000\n0 0\n");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--max-size 0", "--max-size must be a positive finite size (got 0)"},
      {"--max-size -5", "--max-size must be a positive finite size"},
      {"--max-size nan", "not a finite number"},
      {"--max-size 10 --min-size 20", "--min-size 20 is larger than --max-size 10"},
      {"--max-size 10 --grade 0", "--grade must be above 0"},
      {"--max-size 0.05", "--max-size 0.05 asks for about"},
      {"--max-size 100 --size-from-shore 0.05 0", "--size-from-shore 0.05 0 asks for about"},
      {"--size-from-depth 30", "--size-from-depth needs depths from a DEM"},
  };
  for (const auto& [options, message] : cases) {
    const RunResult r = shoremesh(dir, "mesh lake.rings " + options + " -o out.msh");
    EXPECT_NE(r.code, 0) << options;
    EXPECT_NE(r.err.find(message), std::string::npos) << options << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.msh")) << options;
  }
  write_file(dir / "bad.geojson",
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"size":-2},)"
             R"("geometry":{"type":"Polygon","coordinates":[[[1,1],[5,1],[5,5],[1,1]]]}}]})");
  const RunResult r = shoremesh(dir, "mesh lake.rings --size-polygons bad.geojson -o out.msh");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("bad.geojson: feature 1: size -2 is not a positive finite size"), std::string::npos) << r.err;
}

// A raster of sizes (an ESRI ASCII grid, read through GDAL) over one corner of a square lake: the mesh is
// finer there, and the summary's worst ratio stays within 1 %.
TEST(SizeCommand, SizeRasterRefinesWhereItsSizesAreSmaller) {
  TempDir dir;
  write_file(dir / "lake.rings", "0 0\n10000 0\n10000 10000\n0 10000\n0 0\n");
  std::string grid = "ncols 4\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 1250\nNODATA_value -9999\n";
  for (int i = 0; i < 4; ++i) grid += "150 150 150 150\n";
  write_file(dir / "sizes.asc", grid);
  const RunResult r = shoremesh(dir, "mesh lake.rings --max-size 1000 --size-raster sizes.asc -o out.node");
  ASSERT_EQ(r.code, 0) << r.err;
  const TriangleFiles m = read_triangle_files(dir / "out.node");
  std::size_t fine = 0, coarse = 0;
  double coarse_sum = 0;
  for (const auto& t : m.triangles) {
    const auto &a = m.nodes[t[0]], &b = m.nodes[t[1]], &c = m.nodes[t[2]];
    const double gx = (a[0] + b[0] + c[0]) / 3, gy = (a[1] + b[1] + c[1]) / 3;
    const double longest = std::max({std::hypot(a[0] - b[0], a[1] - b[1]), std::hypot(b[0] - c[0], b[1] - c[1]),
                                     std::hypot(c[0] - a[0], c[1] - a[1])});
    if (gx < 4000 && gy < 4000) {
      ++fine;
      EXPECT_LE(longest, 150 * 1.01);
    }
    if (gx > 7000 && gy > 7000) {
      ++coarse;
      coarse_sum += longest;
    }
  }
  EXPECT_GT(fine, 100u);
  EXPECT_GT(coarse, 10u);
  EXPECT_GT(coarse_sum / double(coarse), 4 * 150);  // the raster's sizes stay in its corner
  const auto at = r.out.find("longest edge / h(centroid) <= ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_LE(std::stod(r.out.substr(at + 30)), 1.01) << r.out;
}

// `size POLYGON H` in an edit session: the session's export equals a fresh `mesh` run with the polygon
// file carrying the new size (in the session's box).
TEST(SizeCommand, SizeEditLineEqualsAFreshRunWithTheNewSize) {
  TempDir dir;
  write_file(dir / "lake.rings", "0 0\n20000 0\n20000 20000\n0 20000\n0 0\n");
  auto polygons = [](int size) {
    return R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"size":)" + std::to_string(size) +
           R"(},"geometry":{"type":"Polygon","coordinates":[[[4000,4000],[9000,4000],[9000,9000],[4000,9000],[4000,4000]]]}}]})";
  };
  write_file(dir / "p.geojson", polygons(600));
  write_file(dir / "q.geojson", polygons(1500));
  const RunResult e = shoremesh(dir, "edit lake.rings --max-size 3000 --size-polygons p.geojson --json --edits -",
                                "size 0 1500\nexport edited.csv\nsize 3 100\n");
  ASSERT_EQ(e.code, 1) << e.err;  // the last line names no polygon
  const auto lines = lines_of(e.out);
  ASSERT_EQ(lines.size(), 4u) << e.out;
  EXPECT_NE(lines[1].find("\"op\":\"size\""), std::string::npos) << lines[1];
  EXPECT_NE(lines[3].find("no size polygon 3"), std::string::npos) << lines[3];
  const auto box_at = lines[0].find("\"box\":[");
  ASSERT_NE(box_at, std::string::npos);
  std::string box = lines[0].substr(box_at + 7, lines[0].find(']', box_at) - box_at - 7);
  std::replace(box.begin(), box.end(), ',', ' ');
  const RunResult f = shoremesh(dir, "mesh lake.rings --max-size 3000 --size-polygons q.geojson --box " + box + " -o fresh.csv");
  ASSERT_EQ(f.code, 0) << f.err;
  auto sorted_lines = [&](const char* name) {
    auto l = lines_of(read_file(dir / name));
    std::sort(l.begin(), l.end());
    return l;
  };
  EXPECT_EQ(sorted_lines("edited.csv"), sorted_lines("fresh.csv"));
}

// The depth, slope and raster terms change the mesh where and only where they bind. A synthetic bathymetry
// (GeoTIFF, UTM 10N, 1 km cells, 160 x 80): a basin with a cliff shore, 2000 m deep, with a 100 m bank at
// its west end (x < 20 km from its edge) and a ramp from 2000 m to 4000 m between 80 and 95 km. With
// --max-size 4000 --min-size 1000: --size-from-depth 1000 gives h = T sqrt(g d) / 1000 = 1400 m on the bank
// and above 4000 m at 2000 m (so it binds on the bank and along the shore, where the depth falls to 0);
// --size-from-slope 60 gives 2 pi d / (60 |grad d|) = 0.785 d on the ramp (1571 .. 3142 m) and binds
// there, at the bank's edge and along the shore, nowhere on the flat bottom; a raster of 1500 m sizes
// covers 120 .. 140 x 30 .. 50 km and sets no size beyond it. Against a run with the
// maximum alone, the triangles farther than 5 H (the seeds' and the engine's reach, as in
// SizeControl.EachTermChangesTheMeshOnlyWhereItBinds) from every place a term binds are the same
// triangles, and where it binds every longest edge is within 1 % of the term's h.
TEST(SizeCommand, DepthSlopeAndRasterTermsChangeTheMeshWhereAndOnlyWhereTheyBind) {
  TempDir dir;
  const int W = 160, Hc = 80;
  auto depth_at = [](int c) {  // by column
    return c < 20 ? 100.0 : c < 80 ? 2000.0 : c < 95 ? 2000.0 + 2000.0 * (c - 80) / 15 : 4000.0;
  };
  std::vector<float> z;
  for (int r = 0; r < Hc; ++r)
    for (int c = 0; c < W; ++c)
      z.push_back(r == 0 || c == 0 || r == Hc - 1 || c == W - 1 ? 10.0f : static_cast<float>(-depth_at(c)));
  write_dem(dir / "basin.tif", W, Hc, z);
  const double x0 = 400000, y0 = 5400000 - 1000.0 * Hc, H = 4000;
  // And a raster of sizes, 1500 m over 120 .. 140 x 30 .. 50 km of the basin (nothing beyond it).
  write_dem(dir / "sizes.tif", 20, 20, std::vector<float>(400, 1500.0f), std::nullopt,
            {x0 + 120000, 1000, 0, y0 + 50000, 0, -1000});
  auto run = [&](const std::string& options, const std::string& out) {
    const RunResult r = shoremesh(dir, "mesh --dem basin.tif --max-size 4000 --min-size 1000 " + options + " -o " + out);
    EXPECT_EQ(r.code, 0) << options << ": " << r.err;
    return read_triangle_files(dir / out);
  };
  using Corners = std::array<Point2, 3>;
  auto corners = [](const TriangleFiles& m) {
    std::vector<Corners> out;
    for (const auto& t : m.triangles) {
      Corners c{m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]};
      std::sort(c.begin(), c.end());
      out.push_back(c);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto base = corners(run("", "base.node"));
  ASSERT_GT(base.size(), 500u);
  // (u, v): km from the basin's south-west corner; the water is 1 .. 159 x 1 .. 79 km.
  auto local = [&](const Point2& p) { return Point2{(p[0] - x0) / 1000, (p[1] - y0) / 1000}; };
  struct Case {
    std::string option;
    std::vector<std::array<double, 2>> binds_u;  // the u ranges where the term binds off the shore
    double inner_u0, inner_u1;                  // where the term's h is known: check the longest edges there
    std::function<double(double)> h;             // h at u there
  };
  const double T = 44712;
  const std::vector<Case> cases{
      {"--size-from-depth 1000", {{0, 21}}, 3, 18, [&](double) { return T * std::sqrt(9.81 * 100) / 1000; }},
      {"--size-from-slope 60", {{19, 22}, {79, 96}}, 82, 93,
       [&](double u) { return 2 * std::numbers::pi * (2000 + 2000 * (u - 80.5) / 15) / (60 * 2000.0 / 15000); }},
      {"--size-raster sizes.tif", {{120, 140}}, 123, 137, [](double) { return 1500.0; }},
  };
  const double reach = 5 * H / 1000, shore_band = 1.5;  // km
  for (const Case& c : cases) {
    const TriangleFiles mesh = run(c.option, "term.node");
    const auto after = corners(mesh);
    auto far = [&](const Corners& t) {
      for (const Point2& p : t) {
        const Point2 q = local(p);
        if (std::min({q[0] - 1, 159 - q[0], q[1] - 1, 79 - q[1]}) < shore_band + reach) return false;
        for (const auto& [u0, u1] : c.binds_u)
          if (q[0] > u0 - reach && q[0] < u1 + reach) return false;
      }
      return true;
    };
    std::vector<Corners> b, a;
    std::copy_if(base.begin(), base.end(), std::back_inserter(b), far);
    std::copy_if(after.begin(), after.end(), std::back_inserter(a), far);
    EXPECT_GT(b.size(), 30u) << c.option;
    EXPECT_EQ(a, b) << c.option << ": the mesh changed far from where the term binds";
    EXPECT_NE(after, base) << c.option << ": the term changed nothing";
    std::size_t inside = 0;
    for (const Corners& t : after) {
      const Point2 g = local({(t[0][0] + t[1][0] + t[2][0]) / 3, (t[0][1] + t[1][1] + t[2][1]) / 3});
      const bool raster = c.option.find("raster") != std::string::npos;
      if (g[0] < c.inner_u0 || g[0] > c.inner_u1 || g[1] < (raster ? 33 : 3) || g[1] > (raster ? 47 : 77)) continue;
      ++inside;
      double longest = 0;
      for (int i = 0; i < 3; ++i)
        longest = std::max(longest, std::hypot(t[i][0] - t[(i + 1) % 3][0], t[i][1] - t[(i + 1) % 3][1]));
      EXPECT_LE(longest, 1.01 * c.h(g[0])) << c.option << " at " << g[0] << ", " << g[1] << " km";
    }
    EXPECT_GT(inside, 50u) << c.option;
  }
}

}  // namespace
}  // namespace shoremesh::cli_test
