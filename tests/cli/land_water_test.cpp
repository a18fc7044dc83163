// `mesh --dem FILE --land-up-to Z [--max-error E]` end to end: the mesh is read back from the exported OBJ
// (x, y in the DEM's map coordinates, z the node's height) and checked against the raster read here with
// GDAL: node heights are the DEM's (bilinear between cell centres), the mesh covers the cells below Z and no
// more, no triangle holds samples from both sides of the shoreline, a straight shoreline is a chain of mesh
// edges, the error over land samples (measured here by locating each sample) is within E, and a second run
// (another thread count) writes the same file.
#include <gdal_priv.h>

#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_test_util.hpp"
#include "dem_test_util.hpp"
#include "../mesh/terrain_test_util.hpp"

namespace shoremesh::cli_test {
namespace {

using terrain_test::coast;

const std::string kSalish = samples("salish/salish_sea_topobathy.tif");

struct Raster : RasterBand {
  using RasterBand::RasterBand;
  // Cell coordinates, (0, 0) the centre of the upper-left cell.
  std::array<double, 2> cell(double x, double y) const { return {(x - g[0]) / g[1] - 0.5, (y - g[3]) / g[5] - 0.5}; }
  std::array<double, 2> centre(int c, int r) const { return {g[0] + (c + 0.5) * g[1], g[3] + (r + 0.5) * g[5]}; }
  double bilinear(double col, double row) const {
    col = std::clamp(col, 0.0, w - 1.0), row = std::clamp(row, 0.0, h - 1.0);
    const int c0 = std::min(static_cast<int>(col), w - 2), r0 = std::min(static_cast<int>(row), h - 2);
    const double tx = col - c0, ty = row - r0;
    return (1 - ty) * ((1 - tx) * at(c0, r0) + tx * at(c0 + 1, r0)) + ty * ((1 - tx) * at(c0, r0 + 1) + tx * at(c0 + 1, r0 + 1));
  }
};

struct Obj {
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<std::size_t, 3>> f;
};

Obj read_obj(const fs::path& path) {
  Obj o;
  std::istringstream in(read_file(path));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream w(line);
    std::string tag;
    w >> tag;
    if (tag == "v") {
      std::array<double, 3> p{};
      w >> p[0] >> p[1] >> p[2];
      o.v.push_back(p);
    } else if (tag == "f") {
      std::array<std::size_t, 3> t{};
      w >> t[0] >> t[1] >> t[2];
      for (auto& k : t) --k;
      o.f.push_back(t);
    }
  }
  return o;
}

double cross(const std::array<double, 3>& a, const std::array<double, 3>& b, double x, double y) {
  return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
}

// Calls f(triangle, interpolated z) for every raster cell centre in a triangle (closed, to rounding).
template <class F>
void for_each_centre(const Raster& r, const Obj& o, F&& f) {
  for (std::size_t t = 0; t < o.f.size(); ++t) {
    const auto &a = o.v[o.f[t][0]], &b = o.v[o.f[t][1]], &c = o.v[o.f[t][2]];
    const double area = cross(a, b, c[0], c[1]);
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const auto* p : {&a, &b, &c}) {
      const auto k = r.cell((*p)[0], (*p)[1]);
      for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], k[i]), hi[i] = std::max(hi[i], k[i]);
    }
    for (int row = std::max(0, int(std::ceil(lo[1] - 1e-9))); row <= std::min(r.h - 1, int(std::floor(hi[1] + 1e-9))); ++row)
      for (int col = std::max(0, int(std::ceil(lo[0] - 1e-9))); col <= std::min(r.w - 1, int(std::floor(hi[0] + 1e-9))); ++col) {
        const auto q = r.centre(col, row);
        const double l0 = cross(b, c, q[0], q[1]) / area, l1 = cross(c, a, q[0], q[1]) / area, l2 = cross(a, b, q[0], q[1]) / area;
        if (l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
        f(t, col, row, l0 * a[2] + l1 * b[2] + l2 * c[2]);
      }
  }
}

// How many of a cell's four neighbours lie on the other side of `level`.
int other_side(const Raster& r, int col, int row, double level) {
  const bool below = r.at(col, row) < level;
  int n = 0;
  for (const auto& [dc, dr] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
    const int c = col + dc, w = row + dr;
    if (c >= 0 && w >= 0 && c < r.w && w < r.h) n += (r.at(c, w) < level) != below;
  }
  return n;
}

double mesh_area(const Obj& o) {
  double s = 0;
  for (const auto& t : o.f) s += std::abs(cross(o.v[t[0]], o.v[t[1]], o.v[t[2]][0], o.v[t[2]][1])) / 2;
  return s;
}

struct SalishLandWater {
  TempDir dir;
  RunResult run;
  Obj obj;
  SalishLandWater() {
    run = shoremesh(dir, "mesh --dem " + quote(kSalish) + " --land-up-to 100 --max-error 5 --min-area 1 -o lw.obj");
    if (run.code == 0) obj = read_obj(dir / "lw.obj");
  }
};

SalishLandWater& salish() {
  static SalishLandWater s;
  return s;
}

TEST(LandWater, NodesCarryTheDemsBilinearHeights) {
  const auto& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  const Raster r(kSalish);
  ASSERT_GT(s.obj.v.size(), 100u);
  std::size_t at_samples = 0;
  for (const auto& p : s.obj.v) {
    const auto c = r.cell(p[0], p[1]);
    EXPECT_NEAR(p[2], r.bilinear(c[0], c[1]), 1e-6 * (1 + std::abs(p[2]))) << p[0] << ", " << p[1];
    at_samples += std::abs(c[0] - std::round(c[0])) < 1e-6 && std::abs(c[1] - std::round(c[1])) < 1e-6;
  }
  EXPECT_GT(at_samples, 0u);  // the greedy picks
  EXPECT_NE(s.run.out.find("land and water: "), std::string::npos) << s.run.out;
}

TEST(LandWater, TheMeshCoversTheCellsBelowZAndNoMore) {
  const auto& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  const Raster r(kSalish);
  // No node farther than 1.5 cells (Chebyshev) from a cell centre below Z: the domain's boundary is the
  // cells' edges as the tracer samples them (it cuts a staircase's corners, docs/terrain.md).
  for (const auto& p : s.obj.v) {
    const auto c = r.cell(p[0], p[1]);
    bool near = false;
    for (int row = int(std::floor(c[1] - 2)); row <= int(std::ceil(c[1] + 2)); ++row)
      for (int col = int(std::floor(c[0] - 2)); col <= int(std::ceil(c[0] + 2)); ++col)
        if (col >= 0 && row >= 0 && col < r.w && row < r.h && std::abs(col - c[0]) <= 1.5 && std::abs(row - c[1]) <= 1.5)
          near |= r.at(col, row) < 100;
    EXPECT_TRUE(near) << "node " << p[0] << ", " << p[1] << " is more than 1.5 cells from every cell below 100 m";
  }
  // Every cell centre inside the mesh is below Z, but for cells at a staircase's corner (two of their four
  // neighbours on the other side), which the tracer's sampling cuts; the mesh's area is that of the cells
  // below Z.
  std::size_t below = 0, inside = 0, corners = 0;
  for (float z : r.z) below += z < 100;
  for_each_centre(r, s.obj, [&](std::size_t, int col, int row, double) {
    ++inside;
    if (r.at(col, row) < 100) return;
    ++corners;
    EXPECT_GE(other_side(r, col, row, 100), 2) << "cell " << col << ", " << row << " (" << r.at(col, row) << " m) is in the mesh";
  });
  EXPECT_LT(corners, inside / 100) << corners << " corner cells at or above Z in the mesh";
  const double cells_area = below * std::abs(r.g[1] * r.g[5]);
  EXPECT_NEAR(mesh_area(s.obj) / cells_area, 1.0, 0.03);
}

TEST(LandWater, NoTriangleHoldsSamplesFromBothSidesOfTheShoreline) {
  const auto& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  const Raster r(kSalish);
  // Cells at a staircase's corner (two neighbours across the shoreline) are left out: the tracer's
  // sampling cuts those corners, for `--dem` as here. So are cells within two cells of one at or above Z:
  // where the two contours come within half a cell the shoreline's piece is left to the contour at Z, and
  // the line ends up to a cell and a half before (docs/terrain.md).
  auto near_top = [&](int col, int row) {
    for (int w = std::max(0, row - 2); w <= std::min(r.h - 1, row + 2); ++w)
      for (int c = std::max(0, col - 2); c <= std::min(r.w - 1, col + 2); ++c)
        if (r.at(c, w) >= 100) return true;
    return false;
  };
  std::vector<int> side(s.obj.f.size(), 0);  // 1 water, 2 land, 3 both
  std::size_t land = 0, water = 0;
  for_each_centre(r, s.obj, [&](std::size_t t, int col, int row, double) {
    if (other_side(r, col, row, 0) >= 2 || near_top(col, row)) return;
    const bool wet = r.at(col, row) < 0;
    side[t] |= wet ? 1 : 2;
    (wet ? water : land) += 1;
  });
  EXPECT_GT(land, 50u);
  EXPECT_GT(water, 1000u);
  for (std::size_t t = 0; t < side.size(); ++t) EXPECT_NE(side[t], 3) << "triangle " << t << " straddles the shoreline";
}

TEST(LandWater, ErrorOverLandSamplesIsWithinTheBound) {
  const auto& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  const Raster r(kSalish);
  double worst = 0;
  std::size_t measured = 0;
  for_each_centre(r, s.obj, [&](std::size_t, int col, int row, double z) {
    if (r.at(col, row) < 0) return;
    ++measured;
    worst = std::max(worst, std::abs(z - r.at(col, row)));
  });
  EXPECT_GT(measured, 50u);
  EXPECT_LE(worst, 5 + 1e-6);
  EXPECT_NE(s.run.out.find("error on land: max "), std::string::npos) << s.run.out;
}

TEST(LandWater, WithoutTheBoundTheLandIsCoarserAndStillWithinTheDomain) {
  const auto& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  TempDir dir;
  const RunResult run = shoremesh(dir, "mesh --dem " + quote(kSalish) + " --land-up-to 100 --min-area 1 -o plain.obj");
  ASSERT_EQ(run.code, 0) << run.err;
  const Obj plain = read_obj(dir / "plain.obj");
  EXPECT_LT(plain.f.size(), s.obj.f.size());
  EXPECT_NEAR(mesh_area(plain) / mesh_area(s.obj), 1.0, 1e-9);
  EXPECT_EQ(run.out.find("error on land"), std::string::npos);
}

TEST(LandWater, ASecondRunWithAnotherThreadCountWritesTheSameMesh) {
  const auto& s = salish();
  ASSERT_EQ(s.run.code, 0) << s.run.err;
  TempDir dir;
  const RunResult run = shoremesh(
      dir, "mesh --dem " + quote(kSalish) + " --land-up-to 100 --max-error 5 --min-area 1 --threads 1 -o again.obj");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(read_file(dir / "again.obj"), read_file(s.dir / "lw.obj"));
}

// A straight shoreline: water in columns 0-9, land 5 m in 10-14, cliffs 100 m from 15 on; Z = 10. The
// shoreline (x = 410 km, the cells' edge) must be covered by mesh edges along it, but for about half a cell
// at the DEM's edge (where the contour at Z runs across the shoreline's ends: docs/terrain.md).
TEST(LandWater, AStraightShorelineIsAChainOfMeshEdges) {
  TempDir dir;
  const int w = 30, h = 20;
  std::vector<float> z(static_cast<std::size_t>(w) * h);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) z[static_cast<std::size_t>(r) * w + c] = c < 10 ? -5.0f : c < 15 ? 5.0f + 0.1f * r : 100.0f;
  write_dem(dir / "straight.tif", w, h, z);
  const RunResult run = shoremesh(dir, "mesh --dem straight.tif --land-up-to 10 --max-error 0.5 -o s.obj");
  ASSERT_EQ(run.code, 0) << run.err;
  const Obj o = read_obj(dir / "s.obj");
  std::vector<std::array<double, 2>> along;  // y intervals of vertical edges within 0.3 cell of x = 410 km
  double shore_x = 0;
  std::size_t on = 0;
  for (const auto& t : o.f)
    for (int k = 0; k < 3; ++k) {
      const auto &a = o.v[t[k]], &b = o.v[t[(k + 1) % 3]];
      if (std::abs(a[0] - 410000) < 300 && std::abs(a[0] - b[0]) < 1e-3) {
        along.push_back({std::min(a[1], b[1]), std::max(a[1], b[1])});
        shore_x = a[0], ++on;
      }
    }
  ASSERT_GT(on, 0u) << "no mesh edge along the shoreline";
  std::sort(along.begin(), along.end());
  // From 3/4 of a cell inside the DEM's lower edge to 3/4 inside its upper edge: the line stops about half
  // a cell from the contour at Z, which runs along the DEM's edge there.
  double reach = 5380750;
  for (const auto& [lo, hi] : along)
    if (lo <= reach + 1e-6) reach = std::max(reach, hi);
  EXPECT_GE(reach, 5399250) << "the mesh edges along x = " << shore_x << " stop at y = " << reach;
  // Samples: columns 9 and 10 on either side, never in one triangle.
  const Raster r((dir / "straight.tif").string());
  for_each_centre(r, o, [&](std::size_t, int col, int, double) { EXPECT_LT(col, 15); });
  std::vector<int> side(o.f.size(), 0);
  for_each_centre(r, o, [&](std::size_t t, int col, int, double) { side[t] |= col < 10 ? 1 : 2; });
  for (int s : side) EXPECT_NE(s, 3);
}

TEST(LandWater, ZAboveEverySampleMeshesTheWholeDem) {
  TempDir dir;
  const RunResult run = shoremesh(dir, "mesh --dem " + quote(kSalish) + " --land-up-to 5000 -o all.obj");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.out.find("the DEM's whole extent"), std::string::npos) << run.out;
  const Raster r(kSalish);
  EXPECT_NEAR(mesh_area(read_obj(dir / "all.obj")) / (r.w * r.h * std::abs(r.g[1] * r.g[5])), 1.0, 1e-9);
}

TEST(LandWater, BadInputNamesTheOption) {
  TempDir dir;
  struct Case {
    std::string args, expect;
  };
  const std::vector<Case> cases = {
      {"--land-up-to -10", "--land-up-to -10 must lie above --shoreline-level 0"},
      {"--land-up-to 5 --shoreline-level 5", "must lie above --shoreline-level"},
      {"--land-up-to nan", "--land-up-to"},
      {"--land-up-to 10 --max-error 0", "--max-error"},
      {"--land-up-to 10 --max-error nan", "--max-error"},
      {"--land-up-to 10 --max-size 1000", "size control"},
  };
  for (const Case& c : cases) {
    const RunResult run = shoremesh(dir, "mesh --dem " + quote(kSalish) + " " + c.args + " -o x.obj");
    EXPECT_NE(run.code, 0) << c.args;
    EXPECT_NE(run.err.find(c.expect), std::string::npos) << c.args << ": " << run.err;
    EXPECT_FALSE(fs::exists(dir / "x.obj")) << c.args;
  }
  write_file(dir / "p.csv", "0,0\n1,0\n0,1\n");
  RunResult run = shoremesh(dir, "mesh p.csv --land-up-to 10 -o x.obj");
  EXPECT_NE(run.code, 0);
  EXPECT_NE(run.err.find("--land-up-to"), std::string::npos) << run.err;
  run = shoremesh(dir, "mesh --dem " + quote(kSalish) + " --max-error 5 -o x.obj");
  EXPECT_NE(run.code, 0);
  EXPECT_NE(run.err.find("--max-error"), std::string::npos) << run.err;
  run = shoremesh(dir, "edit --dem " + quote(kSalish) + " --land-up-to 10 --edits -", "stats\n");
  EXPECT_NE(run.code, 0);
  EXPECT_NE(run.err.find("--land-up-to"), std::string::npos) << run.err;
  run = shoremesh(dir, "mesh --dem " + quote(kSalish) + " --land-up-to -2000 -o x.obj");
  EXPECT_NE(run.code, 0);
  EXPECT_NE(run.err.find("--land-up-to"), std::string::npos) << run.err;
}


// The mesh of an OBJ as sets: its nodes (x, y, z) and its triangles (corners sorted), whatever the numbering.
struct MeshSets {
  std::set<std::array<double, 3>> nodes;
  std::set<std::array<std::array<double, 3>, 3>> triangles;
};
MeshSets sets_of(const Obj& o) {
  MeshSets m;
  for (const auto& v : o.v) m.nodes.insert(v);
  for (const auto& t : o.f) {
    std::array<std::array<double, 3>, 3> c{o.v[t[0]], o.v[t[1]], o.v[t[2]]};
    std::sort(c.begin(), c.end());
    m.triangles.insert(c);
  }
  return m;
}

// Random dem-patch lines on a DEM: each window raised or lowered (by enough to move the shoreline and the
// contour at Z across it) or reshaped; after each, the exported mesh equals a fresh run on the DEM as
// patched so far, node for node and triangle for triangle.
void random_patches_equal_fresh_runs(const std::vector<float>& dem, int w, int h, std::array<double, 6> g, int epsg,
                                     const std::string& args, unsigned seed, int steps, float swing) {
  TempDir dir;
  std::vector<float> z = dem;
  write_dem(dir / "dem.tif", w, h, z, {}, g, epsg);
  std::mt19937 rng(seed);
  std::string edits = "# random patches\n";
  for (int k = 0; k < steps; ++k) {
    const int pw = std::uniform_int_distribution<int>(2, std::max(2, w / 4))(rng);
    const int ph = std::uniform_int_distribution<int>(2, std::max(2, h / 4))(rng);
    const int col = std::uniform_int_distribution<int>(0, w - pw)(rng), row = std::uniform_int_distribution<int>(0, h - ph)(rng);
    const int kind = std::uniform_int_distribution<int>(0, 2)(rng);
    std::vector<float> cells;
    for (int r = row; r < row + ph; ++r)
      for (int c = col; c < col + pw; ++c) {
        float& v = z[std::size_t(r) * w + c];
        v = kind == 0 ? v - swing : kind == 1 ? v + swing : static_cast<float>(0.5 * swing * std::sin(0.7 * (c + 2 * r)));
        cells.push_back(v);
      }
    std::string name = "p";
    name += std::to_string(k);
    write_dem(dir / (name + ".tif"), pw, ph, cells, {}, {g[0] + col * g[1], g[1], 0, g[3] + row * g[5], 0, g[5]}, epsg);
    std::string patched = "dem";
    patched += std::to_string(k);
    write_dem(dir / (patched + ".tif"), w, h, z, {}, g, epsg);
    edits += "dem-patch " + name + ".tif\nexport after" + std::to_string(k) + ".obj\n";
  }
  write_file(dir / "edits.txt", edits);
  const RunResult r = shoremesh(dir, "mesh --dem dem.tif " + args + " --quiet -o final.obj --edits edits.txt");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  // The patches moved the contours: some reply counts ring and line vertices that went and came.
  std::size_t moved = 0;
  for (const std::string& line : lines_of(r.out)) moved += line.find("dem-patch") != std::string::npos &&
                                                            line.find("line vertices -0 +0 (") == std::string::npos;
  EXPECT_GE(moved, 2u) << r.out;
  for (int k = 0; k < steps; ++k) {
    const std::string n = std::to_string(k);
    EXPECT_NE(r.out.find("line " + std::to_string(2 * k + 2) + ": dem-patch p" + n + ".tif"), std::string::npos) << r.out;
    const RunResult fresh = shoremesh(dir, "mesh --dem dem" + n + ".tif " + args + " --quiet -o fresh" + n + ".obj");
    ASSERT_EQ(fresh.code, 0) << fresh.err;
    const MeshSets a = sets_of(read_obj(dir / ("after" + n + ".obj"))), b = sets_of(read_obj(dir / ("fresh" + n + ".obj")));
    EXPECT_EQ(a.nodes.size(), b.nodes.size()) << "patch " << k;
    EXPECT_TRUE(a.nodes == b.nodes) << "patch " << k;
    EXPECT_EQ(a.triangles.size(), b.triangles.size()) << "patch " << k;
    EXPECT_TRUE(a.triangles == b.triangles) << "patch " << k;
  }
  EXPECT_EQ(read_file(dir / "final.obj"), read_file(dir / ("fresh" + std::to_string(steps - 1) + ".obj")));
}

TEST(LandWaterEdits, RandomDemPatchesEqualFreshRunsOnASyntheticDem) {
  // Seed 100 reorders the traced rings (a line's place taken by a shore ring): that once lost the water.
  random_patches_equal_fresh_runs(coast(36, 28), 36, 28, {400000, 1000, 0, 5400000, 0, -1000}, 32610,
                                  "--land-up-to 15 --max-error 1.5", 100, 8, 18);
  random_patches_equal_fresh_runs(coast(36, 28), 36, 28, {400000, 1000, 0, 5400000, 0, -1000}, 32610,
                                  "--land-up-to 25 --shoreline-level 5 --max-error 0.8", 101, 4, 18);
}

TEST(LandWaterEdits, RandomDemPatchesEqualFreshRunsOnACropOfTheSalishSea) {
  const Raster full(kSalish);
  const int c0 = 30, r0 = 20, w = 48, h = 40;
  std::vector<float> z;
  for (int r = r0; r < r0 + h; ++r)
    for (int c = c0; c < c0 + w; ++c) z.push_back(full.at(c, r));
  const std::array<double, 6> g{full.g[0] + c0 * full.g[1], full.g[1], 0, full.g[3] + r0 * full.g[5], 0, full.g[5]};
  random_patches_equal_fresh_runs(z, w, h, g, 3857, "--land-up-to 100 --max-error 10 --min-area 1", 7, 4, 60);
  random_patches_equal_fresh_runs(z, w, h, g, 3857, "--land-up-to 300 --max-error 5", 200, 4, 60);
}

// A 3 x 3 patch on the Salish Sea's coast moves only the ring and line vertices next to it (the contours
// are anchored to the cells: docs/terrain.md, "Local contours"); a tracer that resamples whole rings
// moved about 2,200 of them, far along the coast.
TEST(LandWaterEdits, AThreeByThreePatchMovesOnlyTheRingVerticesNextToIt) {
  TempDir dir;
  const Raster full(kSalish);
  const int c0 = 60, r0 = 40;
  std::vector<float> cells;
  for (int r = r0; r < r0 + 3; ++r)
    for (int c = c0; c < c0 + 3; ++c) cells.push_back(static_cast<float>(full.at(c, r) - 40));
  write_dem(dir / "p.tif", 3, 3, cells, {}, {full.g[0] + c0 * full.g[1], full.g[1], 0, full.g[3] + r0 * full.g[5], 0, full.g[5]},
            3857);
  write_file(dir / "edits.txt", "dem-patch p.tif\n");
  const RunResult r = shoremesh(dir, "mesh --dem " + kSalish + " --land-up-to 100 --max-error 5 --min-area 1 --quiet "
                                     "-o a.obj --json --edits edits.txt");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const nlohmann::json reply = nlohmann::json::parse(lines_of(r.out).at(0));
  const std::size_t moved = reply.at("ring_points_removed").get<std::size_t>() + reply.at("ring_points_added").get<std::size_t>();
  EXPECT_GT(moved, 0u) << r.out;   // the patch moved the shoreline
  EXPECT_LE(moved, 60u) << r.out;  // at most the vertices on the cell edges within two cells of the window
  // A ring's vertices within two cells of the window, a line's end within 5.5 (tests/mesh/land_water_contour_test.cpp).
  EXPECT_LE(reply.at("ring_reach").get<double>(), 5.5) << r.out;
}

TEST(LandWaterEdits, BadLinesAreRefusedAndChangeNothing) {
  TempDir dir;
  const int w = 20, h = 16;
  std::vector<float> z = coast(w, h);
  write_dem(dir / "dem.tif", w, h, z);
  write_dem(dir / "nodata.tif", 2, 2, {1, -9999, 3, 4}, -9999.0, {405000, 1000, 0, 5395000, 0, -1000});
  write_dem(dir / "outside.tif", 4, 4, std::vector<float>(16, 1.0f), {}, {418000, 1000, 0, 5395000, 0, -1000});
  write_file(dir / "edits.txt", "dem-patch missing.tif\ndem-patch nodata.tif\ndem-patch outside.tif\nlevee 3\nstats\n");
  const RunResult r = shoremesh(dir, "mesh --dem dem.tif --land-up-to 15 --max-error 2 --quiet -o e.obj --edits edits.txt");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.out.find("line 1: error: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line 2: error: nodata.tif: a land-and-water patch must hold data in every cell"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line 3: error: outside.tif: the patch (4 x 4 cells"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line 4: error: unknown land-and-water edit 'levee'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line 5: "), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("4 edit line(s) failed"), std::string::npos) << r.err;
  ASSERT_EQ(shoremesh(dir, "mesh --dem dem.tif --land-up-to 15 --max-error 2 --quiet -o f.obj").code, 0);
  EXPECT_EQ(read_file(dir / "e.obj"), read_file(dir / "f.obj"));
  const RunResult water = shoremesh(dir, "mesh --dem dem.tif -o w.obj --edits edits.txt");
  EXPECT_NE(water.code, 0);
  EXPECT_NE(water.err.find("--edits"), std::string::npos) << water.err;
}

}  // namespace
}  // namespace shoremesh::cli_test
