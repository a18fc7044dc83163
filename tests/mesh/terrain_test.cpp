// Terrain TINs (core/include/shoremesh/terrain.hpp): the vertical error bound, measured here sample by
// sample with a point location of our own; the quality bound, with angles computed here; determinism; and
// Lemma 7.2 for DEM patches: after every random patch the session equals a fresh run on the patched grid.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>
#include <set>

#include "shoremesh/error.hpp"
#include "shoremesh/terrain.hpp"

namespace shoremesh {
namespace {

// Hills, a ridge and a terrace step: smooth parts the seeds cover and a break the greedy rounds find.
HeightGrid synthetic_grid(int w, int h, double dx = 30, std::uint32_t seed = 7) {
  HeightGrid g;
  g.width = w, g.height = h;
  g.x0 = 500000, g.y0 = 5400000, g.dx = dx, g.dy = -dx;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.4, 0.4);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double x = double(c) / w, y = double(r) / h;
      double z = 120 * std::exp(-((x - 0.3) * (x - 0.3) + (y - 0.4) * (y - 0.4)) / 0.02) +
                 60 * std::sin(6 * x + 2 * y) + 25 * (x + y > 1.2 ? 1 : 0) - 40 + noise(rng);
      g.z.push_back(static_cast<float>(z));
    }
  return g;
}

// The TIN's height under every sample by a location of our own: each triangle's samples by its bounding
// box, barycentric in long double. Returns the largest error (infinity when a sample is in no triangle).
double independent_max_error(const TerrainSession& s) {
  const HeightGrid& g = s.grid();
  std::vector<long double> err(g.z.size(), -1);
  const auto& p = s.points();
  const auto& hts = s.heights();
  for (const auto& t : s.triangles()) {
    long double lo[2] = {1e300L, 1e300L}, hi[2] = {-1e300L, -1e300L};
    for (auto v : t)
      for (int i = 0; i < 2; ++i) lo[i] = std::min<long double>(lo[i], p[v][i]), hi[i] = std::max<long double>(hi[i], p[v][i]);
    const auto [ax, ay] = p[t[0]];
    const auto [bx, by] = p[t[1]];
    const auto [cx, cy] = p[t[2]];
    const long double det = (long double)(bx - ax) * (cy - ay) - (long double)(by - ay) * (cx - ax);
    for (int r = 0; r < g.height; ++r)
      for (int c = 0; c < g.width; ++c) {
        const Point2 q = g.position(c, r);
        if (q[0] < lo[0] - 1e-6 || q[0] > hi[0] + 1e-6 || q[1] < lo[1] - 1e-6 || q[1] > hi[1] + 1e-6) continue;
        const long double u = ((long double)(bx - q[0]) * (cy - q[1]) - (long double)(by - q[1]) * (cx - q[0])) / det;
        const long double v = ((long double)(cx - q[0]) * (ay - q[1]) - (long double)(cy - q[1]) * (ax - q[0])) / det;
        const long double w = 1 - u - v;
        if (u < -1e-9L || v < -1e-9L || w < -1e-9L) continue;
        const long double z = u * hts[t[0]] + v * hts[t[1]] + w * hts[t[2]];
        const std::size_t i = g.index(c, r);
        err[i] = std::max(err[i], std::abs(z - (long double)g.z[i]));
      }
  }
  double worst = 0;
  for (std::size_t i = 0; i < err.size(); ++i) {
    if (!g.is_valid(i)) continue;
    worst = std::max(worst, err[i] < 0 ? INFINITY : double(err[i]));
  }
  return worst;
}

double min_angle_degrees(const TerrainSession& s) {
  double lo = 180;
  for (const auto& t : s.triangles())
    for (int k = 0; k < 3; ++k) {
      const Point2 &a = s.points()[t[k]], &b = s.points()[t[(k + 1) % 3]], &c = s.points()[t[(k + 2) % 3]];
      const double la = std::hypot(b[0] - c[0], b[1] - c[1]), lb = std::hypot(a[0] - c[0], a[1] - c[1]),
                   lc = std::hypot(a[0] - b[0], a[1] - b[1]);
      lo = std::min(lo, std::acos(std::clamp((lb * lb + lc * lc - la * la) / (2 * lb * lc), -1.0, 1.0)) * 180 / std::numbers::pi);
    }
  return lo;
}

void expect_same_tin(const TerrainSession& a, const TerrainSession& b) {
  ASSERT_EQ(a.points().size(), b.points().size());
  EXPECT_EQ(a.points(), b.points());
  EXPECT_EQ(a.heights(), b.heights());
  EXPECT_EQ(a.triangles(), b.triangles());
  EXPECT_EQ(a.pick_count(), b.pick_count());
  EXPECT_EQ(a.seed_count(), b.seed_count());
  EXPECT_EQ(a.block_pick_count(), b.block_pick_count());
  EXPECT_EQ(a.rounds(), b.rounds());
}

TEST(Terrain, EverySampleWithinTheErrorBoundMeasuredIndependently) {
  for (double e : {0.5, 2.0, 10.0}) {
    for (double fraction : {0.0, 0.5}) {
      TerrainOptions o;
      o.max_error = e;
      o.seed_fraction = fraction;
      const TerrainSession s(synthetic_grid(70, 55), o);
      SCOPED_TRACE("E = " + std::to_string(e) + ", seed fraction " + std::to_string(fraction));
      const double worst = independent_max_error(s);
      EXPECT_LE(worst, e + 1e-9);  // rounding only: the TIN's own computation keeps every sample within e
      const TerrainError own = s.error();
      EXPECT_EQ(own.over, 0u);
      EXPECT_NEAR(own.max, worst, 1e-6 * (1 + worst));
      if (e >= 2 && fraction == 0) {
        EXPECT_LT(s.points().size(), 70u * 55u / 2);  // above the noise: far fewer nodes than samples
      }
      s.check_valid();
    }
  }
}

TEST(Terrain, EveryTriangleMeetsTheQualityBoundInThePlane) {
  TerrainOptions o;
  o.max_error = 1.0;
  for (double dx : {30.0, 1e-3, 1e5}) {  // the same terrain at other scales
    const TerrainSession s(synthetic_grid(60, 48, dx), o);
    const double bound = std::asin(1 / (2 * std::sqrt(2.0))) * 180 / std::numbers::pi;
    EXPECT_GE(min_angle_degrees(s), bound - 1e-9) << "dx " << dx;
    EXPECT_EQ(angle_range(s.points(), s.triangles())[0], angle_range(s.points(), s.triangles())[0]);
  }
}

TEST(Terrain, SameGridGivesTheSameTin) {
  TerrainOptions o;
  o.max_error = 1.5;
  const TerrainSession a(synthetic_grid(64, 40), o), b(synthetic_grid(64, 40), o);
  expect_same_tin(a, b);
}

TEST(Terrain, NodesCarryTheGridsHeights) {
  TerrainOptions o;
  o.max_error = 2;
  const TerrainSession s(synthetic_grid(50, 50), o);
  const HeightGrid& g = s.grid();
  std::size_t samples = 0;
  for (std::size_t i = 0; i < s.points().size(); ++i) {
    const Point2 q = g.to_grid(s.points()[i]);
    if (s.kinds()[i] == PointKind::Input) {
      ++samples;
      const int c = int(std::lround(q[0])), r = int(std::lround(q[1]));
      EXPECT_EQ(s.points()[i], g.position(c, r));
      EXPECT_EQ(s.heights()[i], double(g.at(c, r)));
    } else {
      EXPECT_NEAR(s.heights()[i], g.bilinear(s.points()[i]), 1e-9);
    }
  }
  EXPECT_GE(samples, 4u);
}

TEST(Terrain, NodataSamplesAreSkipped) {
  HeightGrid g = synthetic_grid(40, 30);
  g.valid.assign(g.z.size(), 1);
  for (int r = 5; r < 15; ++r)
    for (int c = 10; c < 20; ++c) g.z[g.index(c, r)] = 9000, g.valid[g.index(c, r)] = 0;  // a spike nobody measured
  TerrainOptions o;
  o.max_error = 1;
  const TerrainSession s(g, o);
  EXPECT_LE(independent_max_error(s), 1.0);
  EXPECT_EQ(s.error().samples, 40u * 30u - 100u);
}

TEST(Terrain, BadInputIsRefusedWithAReason) {
  TerrainOptions o;
  for (double e : std::vector<double>{0.0, -1.0, std::nan(""), INFINITY}) {
    o.max_error = e;
    EXPECT_THROW(TerrainSession(synthetic_grid(10, 10), o), ParameterError);
  }
  o.max_error = 1;
  for (double sp : std::vector<double>{-1.0, std::nan(""), INFINITY}) {
    o.pick_spacing = sp;
    EXPECT_THROW(TerrainSession(synthetic_grid(10, 10), o), ParameterError);
  }
  o.pick_spacing = 1;
  EXPECT_THROW(TerrainSession(synthetic_grid(1, 1), o), InputError);
  EXPECT_THROW(TerrainSession(synthetic_grid(1, 9), o), InputError);
  HeightGrid empty = synthetic_grid(5, 5);
  empty.valid.assign(25, 0);
  try {
    TerrainSession s(empty, o);
    FAIL() << "an all-nodata grid was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no data"), std::string::npos) << e.what();
  }
  TerrainSession s(synthetic_grid(20, 20), o);
  const std::vector<float> z(9, 1.0f);
  EXPECT_THROW(s.patch(18, 18, 3, 3, z), InputError);
  EXPECT_THROW(s.patch(0, 0, 2, 2, z), InputError);
}

// The same patches in another order (another history of the engine, the mesh and the rounds) end in the
// same TIN: nothing of the order leaks into the result.
TEST(Terrain, PatchesInAnyOrderGiveTheSameTin) {
  TerrainOptions o;
  o.max_error = 1.5;
  const HeightGrid g = synthetic_grid(60, 50, 30, 5);
  struct Patch {
    int col, row, w, h;
    float delta;
  };
  const std::vector<Patch> patches = {{3, 4, 10, 6, -6}, {30, 20, 8, 12, 4}, {45, 35, 12, 10, -3}, {12, 30, 5, 5, 9}};
  auto run = [&](std::vector<int> order) {
    TerrainSession s(g, o);
    for (int k : order) {
      const Patch& p = patches[k];
      std::vector<float> z;
      for (int r = 0; r < p.h; ++r)
        for (int c = 0; c < p.w; ++c) z.push_back(g.at(p.col + c, p.row + r) + p.delta);
      s.patch(p.col, p.row, p.w, p.h, z);
    }
    return s;
  };
  const TerrainSession a = run({0, 1, 2, 3}), b = run({3, 1, 0, 2}), c = run({2, 3, 1, 0});
  expect_same_tin(a, b);
  expect_same_tin(a, c);
}

// Lemma 7.2 for the terrain: random windows of new heights (a dredged channel, a levee, noise, nodata),
// each followed by a comparison with a fresh session on the patched grid.
TEST(Terrain, RandomPatchesEqualAFreshRun) {
  const bool long_run = std::getenv("SHOREMESH_LONG_TESTS") != nullptr;
  // Seeds or none with the default pick spacing and blocks, every over-bound triangle's pick (spacing 0),
  // blocks of 8 cells (many block edges through every patch), and no blocks (rounds from the corners).
  struct Case {
    double fraction, spacing;
    int blocks, patches;
  };
  const TerrainOptions defaults;
  for (const Case& cs : {Case{0.5, defaults.pick_spacing, defaults.block_cells, long_run ? 60 : 12},
                         Case{0.0, defaults.pick_spacing, defaults.block_cells, long_run ? 60 : 12},
                         Case{0.0, 0.0, defaults.block_cells, long_run ? 20 : 4}, Case{0.0, defaults.pick_spacing, 8, long_run ? 30 : 6},
                         Case{0.0, defaults.pick_spacing, 0, long_run ? 20 : 4}}) {
    const double fraction = cs.fraction;
    const int patches = cs.patches;
    TerrainOptions o;
    o.max_error = 1.0;
    o.seed_fraction = fraction;
    o.pick_spacing = cs.spacing;
    o.block_cells = cs.blocks;
    TerrainSession s(synthetic_grid(72, 60, 30, 11), o);
    if (cs.blocks == defaults.block_cells && cs.fraction == 0) {
      // The rounds' levels built before any patch change nothing a fresh session shows.
      s.prepare_patches();
      EXPECT_NO_THROW(s.check_valid());
      expect_same_tin(s, TerrainSession(s.grid(), o));
    }
    std::mt19937 rng(1234);
    for (int k = 0; k < patches; ++k) {
      const int w = 1 + int(rng() % 14), h = 1 + int(rng() % 14);
      const int col = int(rng() % (72 - w + 1)), row = int(rng() % (60 - h + 1));
      std::vector<float> z(std::size_t(w) * h);
      std::vector<std::uint8_t> valid;
      const int kind = int(rng() % 4);
      for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) {
          const float old = s.grid().at(col + c, row + r);
          float v = old;
          if (kind == 0) v = old - 8;                                      // dredged
          if (kind == 1) v = old + 5 * float(std::sin(0.7 * c + 0.3 * r));  // reshaped
          if (kind == 2) v = old + float(int(rng() % 7) - 3);              // noise
          if (kind == 3) v = old + 3;                                      // raised, some nodata
          z[std::size_t(r) * w + c] = v;
        }
      if (kind == 3) {
        valid.assign(z.size(), 1);
        valid[rng() % valid.size()] = 0;
      }
      s.patch(col, row, w, h, z, valid);
      HeightGrid patched = s.grid();
      const TerrainSession fresh(patched, o);
      SCOPED_TRACE("patch " + std::to_string(k) + " seed fraction " + std::to_string(fraction) + " pick spacing " +
                   std::to_string(cs.spacing) + " blocks " + std::to_string(cs.blocks));
      expect_same_tin(s, fresh);
      EXPECT_LE(independent_max_error(s), 1.0);
      EXPECT_NO_THROW(s.check_valid());
      EXPECT_NO_THROW(fresh.check_valid());  // a session not yet patched: one engine ran the rounds
      if (testing::Test::HasFailure()) return;
    }
  }
}

// A patch changes only triangles within its reach. The round-0 input is local: seeds are re-decided only
// for quadtree nodes whose window meets the patch, block picks only for the blocks it meets; each round's
// level follows through its own engine. The reach here: twice the longest edge of the triangles (old or
// new) that meet those blocks grown by a cell, around the blocks. Each patch is also checked against a
// fresh run; with and without seeds.
TEST(Terrain, DemPatchChangesOnlyTrianglesWithinItsReach) {
  for (const double fraction : {0.5, 0.0}) {
  SCOPED_TRACE("seed fraction " + std::to_string(fraction));
  TerrainOptions o;
  o.max_error = 1.0;
  o.seed_fraction = fraction;
  // Without seeds the TIN is coarse: a grid of 12 x 10 blocks, so that four blocks are a small part of it.
  const int gw = fraction > 0 ? 96 : 192, gh = fraction > 0 ? 80 : 160;
  TerrainSession s(synthetic_grid(gw, gh, 30, 11), o);
  auto corners = [&]() {
    std::set<std::array<Point2, 3>> out;
    for (const auto& t : s.triangles()) {
      std::array<Point2, 3> c{s.points()[t[0]], s.points()[t[1]], s.points()[t[2]]};
      std::sort(c.begin(), c.end());
      out.insert(c);
    }
    return out;
  };
  std::mt19937 rng(99);
  for (int k = 0; k < 5; ++k) {
    const int w = 1 + int(rng() % 10), h = 1 + int(rng() % 10);
    const int col = int(rng() % unsigned(gw - w + 1)), row = int(rng() % unsigned(gh - h + 1));
    std::vector<float> z(std::size_t(w) * h);
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c) z[std::size_t(r) * w + c] = s.grid().at(col + c, row + r) - 8 + float(rng() % 9);
    const auto before = corners();
    s.patch(col, row, w, h, z);
    const auto after = corners();
    // The blocks the window meets (block edges shared): their block picks are decided again.
    const int bs = o.block_cells;
    const int c0 = std::max(0, ((col + bs - 1) / bs - 1) * bs), c1 = std::min(gw - 1, ((col + w - 1) / bs + 1) * bs);
    const int r0 = std::max(0, ((row + bs - 1) / bs - 1) * bs), r1 = std::min(gh - 1, ((row + h - 1) / bs + 1) * bs);
    // Distance in cells from a point to those blocks.
    auto distance = [&](const Point2& p) {
      const Point2 g = s.grid().to_grid(p);
      return std::hypot(std::max({0.0, c0 - g[0], g[0] - c1}), std::max({0.0, r0 - g[1], g[1] - r1}));
    };
    auto min_distance = [&](const std::array<Point2, 3>& t) { return std::min({distance(t[0]), distance(t[1]), distance(t[2])}); };
    double longest = 0;  // cells
    for (const auto* tins : {&before, &after})
      for (const auto& t : *tins) {
        if (min_distance(t) > 1) continue;
        for (int i = 0; i < 3; ++i) {
          const Point2 a = s.grid().to_grid(t[i]), b = s.grid().to_grid(t[(i + 1) % 3]);
          longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1]));
        }
      }
    std::size_t changed = 0;
    for (const auto* tins : {&before, &after})
      for (const auto& t : *tins) {
        if ((tins == &before ? after : before).count(t)) continue;
        ++changed;
        EXPECT_LE(min_distance(t), 2 * longest) << "patch " << k;
      }
    // A small part of the TIN: without seeds four blocks and their reach cover about a tenth of this grid.
    EXPECT_LT(changed, after.size() / (fraction > 0 ? 20 : 8)) << "patch " << k;
    expect_same_tin(s, TerrainSession(s.grid(), o));
    if (testing::Test::HasFailure()) return;
  }
  }
}

}  // namespace
}  // namespace shoremesh
