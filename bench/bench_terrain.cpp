// Terrain TINs (issue 37): shoremesh's TerrainSession against a Garland-Heckbert greedy insertion written
// here over CGAL's Delaunay triangulation (Garland & Heckbert 1995, "Fast polygonal approximation of
// terrains and height fields", algorithm III: one point at a time, the worst sample of each triangle in a
// priority queue, the triangles around an inserted point rescanned), at the same max error on the same
// DEM; then random patches of the DEM applied to a session, each timed.
//
//   bench_terrain (DEM | --synthetic N | --upsample DEM K) --max-error E [E...] [--seed-fraction F]
//                 [--repeat R] [--patches P --patch-side CELLS] [--no-gh]
//
// Prints one line per configuration: triangles, vertices, max and RMS error measured at every sample,
// smallest angle, and the median wall time of R runs (reading the DEM not timed). Patches: a window of
// CELLS x CELLS samples lowered by 5 (a dredged pit) or raised (a levee), at random places; the median and
// 90th percentile of the update times.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <numbers>
#include <queue>
#include <random>
#include <string>
#include <vector>

#include "shoremesh/io/dem.hpp"
#include "shoremesh/terrain.hpp"

namespace {

using namespace shoremesh;
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}
double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

// ---- Garland-Heckbert greedy insertion -----------------------------------------------------------------
struct FaceInfo {
  std::uint64_t stamp = 0;
};
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Fb = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Tds = CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_2<K>, Fb>;
using Dt = CGAL::Delaunay_triangulation_2<K, Tds>;

struct GhResult {
  std::size_t vertices = 0, triangles = 0;
  double ms = 0, max_error = 0, rms = 0, min_angle = 0;
};

// Lattice coordinates (column, row) scaled by the cell size in the plane: the triangles are the DEM plane's.
GhResult garland_heckbert(const HeightGrid& g, double max_error) {
  const auto t0 = Clock::now();
  Dt dt;
  std::vector<std::uint8_t> used(g.z.size(), 0);
  auto point = [&](std::size_t s) {
    const Point2 p = g.position(int(s % g.width), int(s / g.width));
    return K::Point_2(p[0], p[1]);
  };
  auto height = [&](const K::Point_2& p) {
    const Point2 q = g.to_grid({p.x(), p.y()});
    return double(g.at(int(std::lround(q[0])), int(std::lround(q[1]))));
  };
  struct Entry {
    double error;
    std::size_t sample;
    Dt::Face_handle face;
    std::uint64_t stamp;
    bool operator<(const Entry& o) const { return error != o.error ? error < o.error : sample > o.sample; }
  };
  std::priority_queue<Entry> queue;
  std::uint64_t stamps = 0;
  auto scan = [&](Dt::Face_handle f) {
    f->info().stamp = ++stamps;
    const K::Point_2 a = f->vertex(0)->point(), b = f->vertex(1)->point(), c = f->vertex(2)->point();
    const double ha = height(a), hb = height(b), hc = height(c);
    const double d = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    double lo[2] = {std::min({a.x(), b.x(), c.x()}), std::min({a.y(), b.y(), c.y()})};
    double hi[2] = {std::max({a.x(), b.x(), c.x()}), std::max({a.y(), b.y(), c.y()})};
    const Point2 glo = g.to_grid({lo[0], lo[1]}), ghi = g.to_grid({hi[0], hi[1]});
    const int c0 = std::max(0, int(std::ceil(std::min(glo[0], ghi[0]) - 1e-9))), c1 = std::min(g.width - 1, int(std::floor(std::max(glo[0], ghi[0]) + 1e-9)));
    const int r0 = std::max(0, int(std::ceil(std::min(glo[1], ghi[1]) - 1e-9))), r1 = std::min(g.height - 1, int(std::floor(std::max(glo[1], ghi[1]) + 1e-9)));
    Entry best{-1, 0, f, f->info().stamp};
    for (int r = r0; r <= r1; ++r)
      for (int cc = c0; cc <= c1; ++cc) {
        const std::size_t s = g.index(cc, r);
        if (used[s] || !g.is_valid(s)) continue;
        const Point2 q = g.position(cc, r);
        const double l0 = ((b.x() - q[0]) * (c.y() - q[1]) - (b.y() - q[1]) * (c.x() - q[0])) / d;
        const double l1 = ((c.x() - q[0]) * (a.y() - q[1]) - (c.y() - q[1]) * (a.x() - q[0])) / d;
        const double l2 = 1 - l0 - l1;
        if (l0 < -1e-12 || l1 < -1e-12 || l2 < -1e-12) continue;
        const double e = std::abs(g.z[s] - (l0 * ha + l1 * hb + l2 * hc));
        if (e > best.error) best.error = e, best.sample = s;
      }
    if (best.error > max_error) queue.push(best);
  };
  for (std::size_t s : {std::size_t(0), std::size_t(g.width - 1), g.z.size() - g.width, g.z.size() - 1}) {
    dt.insert(point(s));
    used[s] = 1;
  }
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) scan(f);
  while (!queue.empty()) {
    const Entry e = queue.top();
    queue.pop();
    if (e.face->info().stamp != e.stamp || used[e.sample]) continue;
    used[e.sample] = 1;
    const Dt::Vertex_handle v = dt.insert(point(e.sample), e.face);
    Dt::Face_circulator f = dt.incident_faces(v), end = f;
    do {
      if (!dt.is_infinite(f)) scan(f);
    } while (++f != end);
  }
  GhResult r;
  r.ms = ms_since(t0);
  r.vertices = dt.number_of_vertices();
  r.triangles = dt.number_of_faces();
  // Measured afterwards at every sample, as for shoremesh (not timed).
  std::vector<double> err(g.z.size(), -1);
  r.min_angle = 180;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    const K::Point_2 a = f->vertex(0)->point(), b = f->vertex(1)->point(), c = f->vertex(2)->point();
    for (int k = 0; k < 3; ++k) {
      const K::Point_2 &p = f->vertex(k)->point(), &q = f->vertex((k + 1) % 3)->point(), &s = f->vertex((k + 2) % 3)->point();
      const double ux = q.x() - p.x(), uy = q.y() - p.y(), vx = s.x() - p.x(), vy = s.y() - p.y();
      r.min_angle = std::min(r.min_angle, std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / std::numbers::pi);
    }
    const double ha = height(a), hb = height(b), hc = height(c);
    const double d = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    const Point2 p0 = g.to_grid({a.x(), a.y()}), p1 = g.to_grid({b.x(), b.y()}), p2 = g.to_grid({c.x(), c.y()});
    const int c0 = int(std::ceil(std::min({p0[0], p1[0], p2[0]}) - 1e-9)), c1 = int(std::floor(std::max({p0[0], p1[0], p2[0]}) + 1e-9));
    const int r0 = int(std::ceil(std::min({p0[1], p1[1], p2[1]}) - 1e-9)), r1 = int(std::floor(std::max({p0[1], p1[1], p2[1]}) + 1e-9));
    for (int rr = std::max(r0, 0); rr <= std::min(r1, g.height - 1); ++rr)
      for (int cc = std::max(c0, 0); cc <= std::min(c1, g.width - 1); ++cc) {
        const Point2 q = g.position(cc, rr);
        const double l0 = ((b.x() - q[0]) * (c.y() - q[1]) - (b.y() - q[1]) * (c.x() - q[0])) / d;
        const double l1 = ((c.x() - q[0]) * (a.y() - q[1]) - (c.y() - q[1]) * (a.x() - q[0])) / d;
        const double l2 = 1 - l0 - l1;
        if (l0 < -1e-12 || l1 < -1e-12 || l2 < -1e-12) continue;
        const std::size_t s = g.index(cc, rr);
        err[s] = std::max(err[s], std::abs(g.z[s] - (l0 * ha + l1 * hb + l2 * hc)));
      }
  }
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t s = 0; s < err.size(); ++s)
    if (g.is_valid(s)) r.max_error = std::max(r.max_error, err[s] < 0 ? INFINITY : err[s]), sum += err[s] * err[s], ++n;
  r.rms = std::sqrt(sum / double(n));
  return r;
}

// ---- DEMs ------------------------------------------------------------------------------------------------
// Octave noise on an n x n lattice of 30 m cells: six octaves of hills, 400 m down to 4 m high, the
// shortest waves n / 32 cells long.
HeightGrid synthetic(int n) {
  HeightGrid g;
  g.width = g.height = n;
  g.dx = 30, g.dy = -30;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> phase(0, 2 * std::numbers::pi), dir(0, std::numbers::pi);
  struct Wave {
    double kx, ky, ph, amp;
  };
  std::vector<Wave> waves;
  for (int octave = 0; octave < 6; ++octave)
    for (int k = 0; k < 6; ++k) {
      const double f = std::pow(2.0, octave) / n * 2 * std::numbers::pi, th = dir(rng);
      waves.push_back({f * std::cos(th), f * std::sin(th), phase(rng), 400 / std::pow(2.5, octave)});
    }
  g.z.resize(std::size_t(n) * n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      double z = 0;
      for (const Wave& w : waves) z += w.amp * std::sin(w.kx * c + w.ky * r + w.ph);
      g.z[g.index(c, r)] = float(z);
    }
  return g;
}

HeightGrid upsample(const HeightGrid& a, int k) {
  HeightGrid g;
  g.width = (a.width - 1) * k + 1, g.height = (a.height - 1) * k + 1;
  g.x0 = a.x0, g.y0 = a.y0, g.dx = a.dx / k, g.dy = a.dy / k;
  g.z.resize(std::size_t(g.width) * g.height);
  for (int r = 0; r < g.height; ++r)
    for (int c = 0; c < g.width; ++c) g.z[g.index(c, r)] = float(a.bilinear(g.position(c, r)));
  return g;
}

}  // namespace

int main(int argc, char** argv) {
  std::string dem_path, label;
  int synthetic_n = 0, up = 0, repeat = 1, patches = 0, patch_side = 33;
  double fraction = 0;
  bool gh = true;
  std::vector<double> errors;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--synthetic") synthetic_n = std::stoi(argv[++i]);
    else if (a == "--upsample") dem_path = argv[++i], up = std::stoi(argv[++i]);
    else if (a == "--repeat") repeat = std::stoi(argv[++i]);
    else if (a == "--patches") patches = std::stoi(argv[++i]);
    else if (a == "--patch-side") patch_side = std::stoi(argv[++i]);
    else if (a == "--seed-fraction") fraction = std::stod(argv[++i]);
    else if (a == "--no-gh") gh = false;
    else if (a == "--max-error")
      while (i + 1 < argc && argv[i + 1][0] != '-') errors.push_back(std::stod(argv[++i]));
    else dem_path = a;
  }
  if (errors.empty() || (dem_path.empty() && synthetic_n == 0)) {
    std::cerr << "usage: bench_terrain (DEM | --synthetic N | --upsample DEM K) --max-error E [E...] [--seed-fraction F] "
                 "[--repeat R] [--patches P --patch-side CELLS] [--no-gh]\n";
    return 2;
  }
  HeightGrid grid;
  if (synthetic_n) {
    grid = synthetic(synthetic_n);
    label = "synthetic " + std::to_string(synthetic_n) + "^2";
  } else {
    grid = io::dem_grid(io::read_dem(dem_path)).grid;
    label = dem_path;
    if (up > 1) grid = upsample(grid, up), label += " upsampled x" + std::to_string(up);
  }
  std::printf("# %s: %d x %d samples, cell %.4g x %.4g\n", label.c_str(), grid.width, grid.height, grid.dx, std::abs(grid.dy));
  for (double e : errors) {
    std::vector<double> times;
    std::optional<TerrainSession> s;
    for (int k = 0; k < repeat; ++k) {
      TerrainOptions o;
      o.max_error = e;
      o.seed_fraction = fraction;
      const auto t0 = Clock::now();
      s.emplace(grid, o);
      times.push_back(ms_since(t0));
    }
    const TerrainError err = s->error();
    const auto angles = angle_range(s->points(), s->triangles());
    const TerrainUpdate& b = s->build_stats();
    std::printf("shoremesh E=%g: %zu triangles, %zu vertices (%zu seeds, %zu picks, %zu rounds), max %.4g rms %.4g, "
                "angles %.2f..%.2f, median %.1f ms of %d (seeds %.1f, engine %.1f, mesh %.1f, error %.1f)\n",
                e, s->triangles().size(), s->points().size(), s->seed_count(), s->pick_count(), s->rounds(), err.max,
                err.rms, angles[0], angles[1], median(times), repeat, b.seed_ms, b.engine_ms, b.mesh_ms, b.error_ms);
    if (gh) {
      std::vector<double> gtimes;
      GhResult r;
      for (int k = 0; k < repeat; ++k) r = garland_heckbert(grid, e), gtimes.push_back(r.ms);
      std::printf("garland-heckbert E=%g: %zu triangles, %zu vertices, max %.4g rms %.4g, min angle %.3f, median %.1f ms "
                  "of %d; shoremesh/gh triangles %.2f\n",
                  e, r.triangles, r.vertices, r.max_error, r.rms, r.min_angle, median(gtimes), repeat,
                  double(s->triangles().size()) / double(r.triangles));
    }
    if (patches > 0) {
      std::mt19937 rng(7);
      std::vector<double> pt, seeds, engine, mesh, error, numbering;
      std::vector<double> picks;
      const int side = std::min({patch_side, grid.width, grid.height});
      for (int k = 0; k < patches; ++k) {
        const int col = int(rng() % unsigned(grid.width - side + 1)), row = int(rng() % unsigned(grid.height - side + 1));
        std::vector<float> z(std::size_t(side) * side);
        const float delta = (k % 2 == 0) ? -5.0f : 3.0f;
        for (int r = 0; r < side; ++r)
          for (int c = 0; c < side; ++c) z[std::size_t(r) * side + c] = grid.at(col + c, row + r) + delta;
        const auto t0 = Clock::now();
        const TerrainUpdate u = s->patch(col, row, side, side, z);
        pt.push_back(ms_since(t0));
        const auto t1 = Clock::now();
        (void)s->triangles();  // the canonical lists, made when asked
        numbering.push_back(ms_since(t1));
        seeds.push_back(u.seed_ms), engine.push_back(u.engine_ms), mesh.push_back(u.mesh_ms), error.push_back(u.error_ms);
        picks.push_back(double(u.picks_removed));
      }
      std::printf("patches E=%g: %d of %d x %d samples: median %.1f ms, p90 %.1f ms (seeds %.1f, engine %.1f, mesh %.1f, "
                  "error %.1f; greedy picks replayed: median %.0f); then the canonical TIN lists for an export: "
                  "median %.1f ms\n",
                  e, patches, side, side, median(pt), percentile(pt, 0.9), median(seeds), median(engine), median(mesh),
                  median(error), median(picks), median(numbering));
    }
    std::fflush(stdout);
  }
  return 0;
}
