// shoremesh terrain: the exported TIN read back and checked here against the DEM read here (GDAL),
// sample by sample; the angles of every exported triangle; the same bytes for the same DEM; every format
// with its heights; a patched run equal to a fresh run on the patched DEM; bad input refused.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "cli_test_util.hpp"
#include "dem_test_util.hpp"

namespace shoremesh::cli_test {
namespace {

struct Tin {
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<std::size_t, 3>> f;
};

Tin read_obj(const fs::path& p) {
  Tin t;
  std::istringstream in(read_file(p));
  for (std::string tag; in >> tag;) {
    if (tag == "v") {
      std::array<double, 3> x{};
      in >> x[0] >> x[1] >> x[2];
      t.v.push_back(x);
    } else if (tag == "f") {
      std::array<std::size_t, 3> x{};
      in >> x[0] >> x[1] >> x[2];
      for (auto& i : x) --i;
      t.f.push_back(x);
    } else {
      std::string rest;
      std::getline(in, rest);
    }
  }
  return t;
}

struct Raster {
  int w = 0, h = 0;
  std::array<double, 6> g{};
  std::vector<float> z;
  std::vector<bool> valid;
};

Raster read_raster(const std::string& path) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  Raster r;
  r.w = ds->GetRasterXSize(), r.h = ds->GetRasterYSize();
  ds->GetGeoTransform(r.g.data());
  r.z.resize(std::size_t(r.w) * r.h);
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, r.w, r.h, r.z.data(), r.w, r.h, GDT_Float32, 0, 0), CE_None);
  int has = 0;
  const double nodata = ds->GetRasterBand(1)->GetNoDataValue(&has);
  for (float x : r.z) r.valid.push_back(std::isfinite(x) && !(has && x == float(nodata)));
  return r;
}

// The largest |TIN - DEM| over the DEM's valid cell centres, the TIN located by a bucket grid here.
double max_vertical_error(const Tin& t, const Raster& dem) {
  const int nb = 64;
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (auto& p : t.v)
    for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
  auto bucket = [&](double x, int i) { return std::clamp(int((x - lo[i]) / (hi[i] - lo[i]) * nb), 0, nb - 1); };
  std::vector<std::vector<std::size_t>> buckets(nb * nb);
  for (std::size_t k = 0; k < t.f.size(); ++k) {
    double a[2] = {1e300, 1e300}, b[2] = {-1e300, -1e300};
    for (auto n : t.f[k])
      for (int i = 0; i < 2; ++i) a[i] = std::min(a[i], t.v[n][i]), b[i] = std::max(b[i], t.v[n][i]);
    for (int y = bucket(a[1], 1); y <= bucket(b[1], 1); ++y)
      for (int x = bucket(a[0], 0); x <= bucket(b[0], 0); ++x) buckets[y * nb + x].push_back(k);
  }
  double worst = 0;
  for (int r = 0; r < dem.h; ++r)
    for (int c = 0; c < dem.w; ++c) {
      if (!dem.valid[std::size_t(r) * dem.w + c]) continue;
      const double x = dem.g[0] + (c + 0.5) * dem.g[1], y = dem.g[3] + (r + 0.5) * dem.g[5];
      double best = INFINITY;
      for (std::size_t k : buckets[bucket(y, 1) * nb + bucket(x, 0)]) {
        const auto &A = t.v[t.f[k][0]], &B = t.v[t.f[k][1]], &C = t.v[t.f[k][2]];
        const double d = (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]);
        const double u = ((B[0] - x) * (C[1] - y) - (B[1] - y) * (C[0] - x)) / d;
        const double v = ((C[0] - x) * (A[1] - y) - (C[1] - y) * (A[0] - x)) / d;
        const double w = 1 - u - v;
        const double tol = 1e-9;
        if (u < -tol || v < -tol || w < -tol) continue;
        best = std::min(best, std::abs(u * A[2] + v * B[2] + w * C[2] - dem.z[std::size_t(r) * dem.w + c]));
      }
      worst = std::max(worst, best);  // a sample in no triangle counts as infinite
    }
  return worst;
}

double min_angle(const Tin& t) {
  double lo = 180;
  for (const auto& f : t.f)
    for (int k = 0; k < 3; ++k) {
      const auto &a = t.v[f[k]], &b = t.v[f[(k + 1) % 3]], &c = t.v[f[(k + 2) % 3]];
      const double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - a[0], vy = c[1] - a[1];
      lo = std::min(lo, std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / std::numbers::pi);
    }
  return lo;
}

const double kBound = std::asin(1 / (2 * std::numbers::sqrt2)) * 180 / std::numbers::pi;

std::string salish() { return samples("salish/salish_sea_topobathy.tif"); }

TEST(TerrainCommand, SalishTinWithinTheBoundAtEverySampleAndAboveTheAngleBound) {
  TempDir dir;
  const Raster dem = read_raster(salish());
  std::size_t previous = 0;
  for (double e : {100.0, 20.0, 5.0}) {
    const std::string args = "terrain " + quote(salish()) + " --max-error " + std::to_string(e) + " -o t.obj --quiet";
    const RunResult run = shoremesh(dir, args);
    ASSERT_EQ(run.code, 0) << run.err << run.out;
    EXPECT_NE(run.out.find("met by all"), std::string::npos) << run.out;
    const Tin t = read_obj(dir / "t.obj");
    SCOPED_TRACE("E = " + std::to_string(e));
    // Rounding: a sample exactly E away (integer heights) may measure E + 1e-12 in another order of operations.
    EXPECT_LE(max_vertical_error(t, dem), e + 1e-9);
    EXPECT_GE(min_angle(t), kBound - 1e-9);
    EXPECT_GT(t.f.size(), previous);  // a tighter bound takes more triangles
    EXPECT_LT(t.v.size(), std::size_t(dem.w) * dem.h);
    previous = t.f.size();
  }
}

TEST(TerrainCommand, SameDemGivesTheSameBytes) {
  TempDir dir;
  const std::string args = "terrain " + quote(salish()) + " --max-error 10 --quiet -o ";
  ASSERT_EQ(shoremesh(dir, args + "a.ply").code, 0);
  ASSERT_EQ(shoremesh(dir, args + "b.ply").code, 0);
  EXPECT_EQ(read_file(dir / "a.ply"), read_file(dir / "b.ply"));
}

// Every format carries the same heights: as z (.obj .ply .off .msh .vtu) or as each GeoJSON position's
// third coordinate, in lon/lat.
TEST(TerrainCommand, EveryFormatCarriesTheHeights) {
  TempDir dir;
  const std::string args = "terrain " + quote(salish()) + " --max-error 30 --quiet -o ";
  for (const char* f : {"t.obj", "t.ply", "t.msh", "t.vtu", "t.geojson"}) ASSERT_EQ(shoremesh(dir, args + f).code, 0) << f;
  const Tin obj = read_obj(dir / "t.obj");
  std::multiset<double> z;
  for (auto& v : obj.v) z.insert(v[2]);
  ASSERT_GT(*z.rbegin(), 100.0);  // mountains
  ASSERT_LT(*z.begin(), -50.0);   // and the sea floor
  auto numbers_after = [](const std::string& text, const std::string& from, const std::string& to) {
    const std::size_t a = text.find(from), b = text.find(to, a);
    std::istringstream in(text.substr(a + from.size(), b - a - from.size()));
    std::vector<double> out;
    for (double x; in >> x;) out.push_back(x);
    return out;
  };
  {
    const std::string ply = read_file(dir / "t.ply");
    const auto n = numbers_after(ply, "end_header\n", "\n3 ");
    std::multiset<double> zs;
    for (std::size_t i = 2; i < 3 * obj.v.size(); i += 3) zs.insert(n[i]);
    EXPECT_EQ(zs, z);
  }
  {
    const std::string vtu = read_file(dir / "t.vtu");
    const std::string points = vtu.substr(vtu.find("<Points>"));
    const auto n = numbers_after(points, "format=\"ascii\">\n", "</DataArray>");
    ASSERT_EQ(n.size(), 3 * obj.v.size());
    std::multiset<double> zs;
    for (std::size_t i = 2; i < n.size(); i += 3) zs.insert(n[i]);
    EXPECT_EQ(zs, z);
    EXPECT_NE(vtu.find("Name=\"height\""), std::string::npos);
  }
  {
    const std::string msh = read_file(dir / "t.msh");
    const std::string nodes = msh.substr(msh.find("$Nodes"));
    const auto n = numbers_after(nodes, "$Nodes\n", "$EndNodes");
    // 4 header numbers, an entity line of 4, the tags, then x y z per node.
    const std::size_t np = obj.v.size();
    ASSERT_EQ(n.size(), 8 + np + 3 * np);
    std::multiset<double> zs;
    for (std::size_t i = 0; i < np; ++i) zs.insert(n[8 + np + 3 * i + 2]);
    EXPECT_EQ(zs, z);
  }
  {
    const std::string gj = read_file(dir / "t.geojson");
    std::size_t positions = 0, at = 0;
    std::multiset<double> zs;
    while ((at = gj.find("[[[", at)) != std::string::npos) {
      at += 2;
      for (int k = 0; k < 4; ++k) {
        const std::size_t open = gj.find('[', at), close = gj.find(']', open);
        std::string inner = gj.substr(open + 1, close - open - 1);
        std::replace(inner.begin(), inner.end(), ',', ' ');
        std::istringstream in(inner);
        double lon = 0, lat = 0, h = NAN;
        in >> lon >> lat >> h;
        EXPECT_GT(lon, -126.0);
        EXPECT_LT(lon, -121.0);
        EXPECT_GT(lat, 47.0);
        EXPECT_LT(lat, 50.5);
        ASSERT_TRUE(std::isfinite(h)) << inner;
        if (k < 3) zs.insert(h);
        ++positions;
        at = close + 1;
      }
    }
    EXPECT_EQ(positions, 4 * obj.f.size());
    std::set<double> distinct(z.begin(), z.end()), seen(zs.begin(), zs.end());
    EXPECT_EQ(seen, distinct);
  }
}

TEST(TerrainCommand, HillshadedHeightPreview) {
  TempDir dir;
  const RunResult r = shoremesh(dir, "terrain " + quote(salish()) +
                                         " --max-error 20 --quiet -o t.obj --preview p.png --preview-colour height");
  ASSERT_EQ(r.code, 0) << r.err;
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open((dir / "p.png").c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  ASSERT_TRUE(ds);
  const int w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
  std::vector<std::uint8_t> rgb(std::size_t(w) * h * 3);
  int bands[3] = {1, 2, 3};
  ASSERT_EQ(ds->RasterIO(GF_Read, 0, 0, w, h, rgb.data(), w, h, GDT_Byte, 3, bands, 3, 3 * w, 1, nullptr), CE_None);
  std::size_t blue = 0, green_or_brown = 0;
  std::set<int> shades;
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    const int r8 = rgb[i], g8 = rgb[i + 1], b8 = rgb[i + 2];
    blue += b8 > r8 + 40 && b8 > g8;
    green_or_brown += (g8 > b8 + 20 || r8 > b8 + 20);
    shades.insert(r8 / 8 * 1024 + g8 / 8 * 32 + b8 / 8);
  }
  EXPECT_GT(blue, std::size_t(w) * h / 20);             // the sea
  EXPECT_GT(green_or_brown, std::size_t(w) * h / 20);   // the land
  EXPECT_GT(shades.size(), 50u);                        // shaded, not flat tints
  EXPECT_EQ(shoremesh(dir, "mesh --dem " + quote(salish()) + " -o m.msh --preview-colour height --preview q.png").code, 2);
}

std::vector<float> hills(int w, int h) {
  std::vector<float> z;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      z.push_back(float(200 * std::exp(-((c - 15.0) * (c - 15.0) + (r - 12.0) * (r - 12.0)) / 60) + 3 * std::sin(c * 0.9) - 20));
  return z;
}

TEST(TerrainCommand, PatchedRunEqualsAFreshRunOnThePatchedDem) {
  TempDir dir;
  const int w = 40, h = 30;
  std::vector<float> z = hills(w, h);
  write_dem(dir / "dem.tif", w, h, z);
  // A dredged channel: 12 x 3 cells at column 20, row 8, 15 m lower.
  std::vector<float> channel;
  for (int r = 8; r < 11; ++r)
    for (int c = 20; c < 32; ++c) channel.push_back(z[std::size_t(r) * w + c] - 15);
  write_dem(dir / "channel.tif", 12, 3, channel, {}, {400000 + 20 * 1000, 1000, 0, 5400000 - 8 * 1000, 0, -1000});
  std::size_t k = 0;
  for (int r = 8; r < 11; ++r)
    for (int c = 20; c < 32; ++c) z[std::size_t(r) * w + c] = channel[k++];
  write_dem(dir / "patched.tif", w, h, z);
  const RunResult patched = shoremesh(dir, "terrain dem.tif --max-error 2 --quiet -o a.vtu --patch channel.tif");
  ASSERT_EQ(patched.code, 0) << patched.err;
  EXPECT_NE(patched.out.find("patch channel.tif: 12 x 3 cells at column 20, row 8"), std::string::npos) << patched.out;
  const RunResult fresh = shoremesh(dir, "terrain patched.tif --max-error 2 --quiet -o b.vtu");
  ASSERT_EQ(fresh.code, 0) << fresh.err;
  EXPECT_EQ(read_file(dir / "a.vtu"), read_file(dir / "b.vtu"));
  // A patch whose cells are not the DEM's is refused, naming it.
  write_dem(dir / "off.tif", 2, 2, {1, 2, 3, 4}, {}, {400500, 1000, 0, 5400000, 0, -1000});
  const RunResult off = shoremesh(dir, "terrain dem.tif --max-error 2 -o c.vtu --patch off.tif");
  EXPECT_EQ(off.code, 1);
  EXPECT_NE(off.err.find("off.tif"), std::string::npos) << off.err;
  EXPECT_FALSE(fs::exists(dir / "c.vtu"));
}

// The terrain's edit lines: each dem-patch updates the TIN, an export in between equals a fresh run on
// the DEM patched so far, the final -o equals a fresh run on the DEM with every patch; a bad line gets an
// error reply naming it, the session goes on, and the exit code is 1.
TEST(TerrainCommand, DemPatchEditLinesEqualFreshRunsOnThePatchedDem) {
  TempDir dir;
  const int w = 40, h = 30;
  std::vector<float> z = hills(w, h);
  write_dem(dir / "dem.tif", w, h, z);
  struct Window {
    int col, row, w, h;
    float delta;
  };
  const std::vector<Window> windows = {{20, 8, 12, 3, -15}, {3, 18, 5, 6, 9}};
  for (std::size_t k = 0; k < windows.size(); ++k) {
    const Window& p = windows[k];
    std::vector<float> cells;
    for (int r = p.row; r < p.row + p.h; ++r)
      for (int c = p.col; c < p.col + p.w; ++c) cells.push_back(z[std::size_t(r) * w + c] + p.delta);
    std::string name = std::to_string(k);
    name.insert(0, 1, 'p');
    name.append(".tif");
    write_dem(dir / name, p.w, p.h, cells, {},
              {400000 + p.col * 1000.0, 1000, 0, 5400000 - p.row * 1000.0, 0, -1000});
    std::size_t i = 0;
    for (int r = p.row; r < p.row + p.h; ++r)
      for (int c = p.col; c < p.col + p.w; ++c) z[std::size_t(r) * w + c] = cells[i++];
    write_dem(dir / ("dem" + std::to_string(k) + ".tif"), w, h, z);
  }
  write_file(dir / "edits.txt",
             "# a dredged channel, then a raised bank\ndem-patch p0.tif\nexport after0.vtu\ndem-patch missing.tif\n"
             "dem-patch p1.tif\nstats\nlevee 3\n");
  const RunResult r = shoremesh(dir, "terrain dem.tif --max-error 2 --quiet -o final.vtu --edits edits.txt");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.out.find("line 2: dem-patch p0.tif: 36 cells at column 20, row 8: triangles -"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line 4: error: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("missing.tif"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line 5: dem-patch p1.tif"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line 7: error: unknown terrain edit 'levee'"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("2 edit line(s) failed"), std::string::npos) << r.err;
  ASSERT_EQ(shoremesh(dir, "terrain dem0.tif --max-error 2 --quiet -o fresh0.vtu").code, 0);
  ASSERT_EQ(shoremesh(dir, "terrain dem1.tif --max-error 2 --quiet -o fresh1.vtu").code, 0);
  EXPECT_EQ(read_file(dir / "after0.vtu"), read_file(dir / "fresh0.vtu"));
  EXPECT_EQ(read_file(dir / "final.vtu"), read_file(dir / "fresh1.vtu"));
  // JSON replies for programs; an export over an input is refused.
  write_file(dir / "json.txt", "stats\nexport dem.tif\n");
  const RunResult j = shoremesh(dir, "terrain dem.tif --max-error 2 --quiet -o j.obj --json --edits json.txt");
  EXPECT_EQ(j.code, 1);
  EXPECT_NE(j.out.find("{\"line\":1,\"max_error\":"), std::string::npos) << j.out;
  EXPECT_NE(j.out.find("\"ok\":false"), std::string::npos) << j.out;
}

TEST(TerrainCommand, BadInputIsRefusedWithAClearError) {
  TempDir dir;
  write_dem(dir / "dem.tif", 10, 10, hills(10, 10));
  for (const char* e : {"0", "-3", "nan", "inf"}) {
    const RunResult r = shoremesh(dir, std::string("terrain dem.tif -o t.obj --max-error ") + e);
    EXPECT_EQ(r.code, 2) << e << r.err;
    EXPECT_NE(r.err.find("max-error"), std::string::npos) << r.err;
  }
  write_dem(dir / "none.tif", 4, 4, std::vector<float>(16, -9999.0f), -9999.0);
  const RunResult none = shoremesh(dir, "terrain none.tif --max-error 1 -o t.obj");
  EXPECT_EQ(none.code, 1);
  EXPECT_NE(none.err.find("no data"), std::string::npos) << none.err;
  write_dem(dir / "one.tif", 1, 1, {5.0f});
  const RunResult one = shoremesh(dir, "terrain one.tif --max-error 1 -o t.obj");
  EXPECT_EQ(one.code, 1);
  EXPECT_NE(one.err.find("one.tif"), std::string::npos) << one.err;
  EXPECT_NE(one.err.find("2 x 2"), std::string::npos) << one.err;
  EXPECT_FALSE(fs::exists(dir / "t.obj"));
}

}  // namespace
}  // namespace shoremesh::cli_test
