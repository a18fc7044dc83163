// Terrain TINs (issue 37): shoremesh's TerrainSession against a Garland-Heckbert greedy insertion written
// here over CGAL's Delaunay triangulation (Garland & Heckbert 1995, "Fast polygonal approximation of
// terrains and height fields", algorithm III: one point at a time, the worst sample of each triangle in a
// priority queue, the triangles around an inserted point rescanned), at the same max error on the same
// DEM; then random patches of the DEM applied to a session, each timed.
//
//   bench_terrain (DEM | --synthetic N | --upsample DEM K) --max-error E [E...] [--seed-fraction F]
//                 [--repeat R] [--patches P --patch-side CELLS] [--no-gh] [--no-session] [--beta B]
//                 [--triangle PATH [--triangle-angle A]]
//
// Prints one line per configuration: triangles, vertices, max and RMS error measured at every sample,
// smallest angle, and the median wall time of R runs (reading the DEM not timed). Patches: a window of
// CELLS x CELLS samples lowered by 5 (a dredged pit) or raised (a levee), at random places; the median and
// 90th percentile of the update times.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>
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

#include "shoremesh/box_transform.hpp"
#include "shoremesh/io/dem.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/well_spaced.hpp"
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
  std::vector<std::size_t> samples;  // the TIN's vertices, sorted
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
  for (std::size_t k = 0; k < used.size(); ++k)
    if (used[k]) r.samples.push_back(k);
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

// ---- A quality reference: Triangle (Shewchuk) on the greedy TIN's vertices -------------------------------
// Not shipped and not a peer of the session's edits: an external binary run for a count. The greedy TIN's
// samples and the rectangle (its sides as segments between the boundary samples) go to `triangle -pq<A>`;
// Steiner points take bilinear heights, as shoremesh's do. If the quality mesh is then farther than E from
// some sample (its Steiner points replace the greedy TIN's surface), the worst sample of every such triangle
// is added and Triangle runs again on all of them, until every sample is within E: the fewest triangles
// this route needs for both bounds.
struct QualityRef {
  std::size_t triangles = 0, vertices = 0, samples = 0, passes = 0;
  double max_error = 0, min_angle = 180, first_max_error = 0;
  std::size_t first_triangles = 0;
};

QualityRef triangle_quality(const HeightGrid& g, std::vector<std::size_t> samples, double max_error,
                            const std::string& triangle, double angle, const std::string& work) {
  QualityRef q;
  std::vector<std::uint8_t> is_sample(g.z.size(), 0);
  for (std::size_t s : samples) is_sample[s] = 1;
  for (int pass = 1;; ++pass) {
    // The rectangle's ring: boundary samples in order (row 0, last column, last row, column 0).
    std::vector<std::size_t> ring;
    for (int c = 0; c < g.width; ++c) if (is_sample[g.index(c, 0)]) ring.push_back(g.index(c, 0));
    for (int r = 1; r < g.height; ++r) if (is_sample[g.index(g.width - 1, r)]) ring.push_back(g.index(g.width - 1, r));
    for (int c = g.width - 2; c >= 0; --c) if (is_sample[g.index(c, g.height - 1)]) ring.push_back(g.index(c, g.height - 1));
    for (int r = g.height - 2; r >= 1; --r) if (is_sample[g.index(0, r)]) ring.push_back(g.index(0, r));
    std::vector<std::size_t> all;
    for (std::size_t s = 0; s < is_sample.size(); ++s) if (is_sample[s]) all.push_back(s);
    std::vector<std::size_t> number(g.z.size(), 0);
    {
      FILE* f = std::fopen((work + ".poly").c_str(), "w");
      std::fprintf(f, "%zu 2 0 0\n", all.size());
      for (std::size_t k = 0; k < all.size(); ++k) {
        number[all[k]] = k + 1;
        const Point2 p = g.position(int(all[k] % g.width), int(all[k] / g.width));
        std::fprintf(f, "%zu %.17g %.17g\n", k + 1, p[0], p[1]);
      }
      std::fprintf(f, "%zu 0\n", ring.size());
      for (std::size_t k = 0; k < ring.size(); ++k)
        std::fprintf(f, "%zu %zu %zu\n", k + 1, number[ring[k]], number[ring[(k + 1) % ring.size()]]);
      std::fprintf(f, "0\n");
      std::fclose(f);
    }
    char cmd[1024];
    std::snprintf(cmd, sizeof cmd, "%s -pq%gQ %s.poly", triangle.c_str(), angle, work.c_str());
    if (std::system(cmd) != 0) throw std::runtime_error(std::string("failed: ") + cmd);
    std::vector<Point2> pts;
    {
      FILE* f = std::fopen((work + ".1.node").c_str(), "r");
      std::size_t n = 0;
      int dim = 0, attrs = 0, marks = 0;
      if (std::fscanf(f, "%zu %d %d %d", &n, &dim, &attrs, &marks) != 4) throw std::runtime_error("bad .node");
      pts.resize(n);
      for (std::size_t k = 0; k < n; ++k) {
        std::size_t id = 0;
        double x = 0, y = 0;
        if (std::fscanf(f, "%zu %lf %lf", &id, &x, &y) != 3) throw std::runtime_error("bad .node line");
        for (int a = 0; a < attrs + marks; ++a) { double skip; if (std::fscanf(f, "%lf", &skip) != 1) throw std::runtime_error("bad .node"); }
        pts[id - 1] = {x, y};
      }
      std::fclose(f);
    }
    std::vector<std::array<std::size_t, 3>> tris;
    {
      FILE* f = std::fopen((work + ".1.ele").c_str(), "r");
      std::size_t n = 0;
      int per = 0, attrs = 0;
      if (std::fscanf(f, "%zu %d %d", &n, &per, &attrs) != 3) throw std::runtime_error("bad .ele");
      tris.resize(n);
      for (std::size_t k = 0; k < n; ++k) {
        std::size_t id = 0, a = 0, b = 0, c = 0;
        if (std::fscanf(f, "%zu %zu %zu %zu", &id, &a, &b, &c) != 4) throw std::runtime_error("bad .ele line");
        tris[k] = {a - 1, b - 1, c - 1};
      }
      std::fclose(f);
    }
    // Heights: a sample's at a lattice point that is a sample, bilinear elsewhere.
    std::vector<double> h(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const Point2 c = g.to_grid(pts[k]);
      const double rc = std::round(c[0]), rr = std::round(c[1]);
      const bool lattice = std::abs(c[0] - rc) < 1e-9 && std::abs(c[1] - rr) < 1e-9;
      h[k] = lattice ? double(g.at(int(rc), int(rr))) : g.bilinear(pts[k]);
    }
    double worst_all = 0, min_angle = 180;
    std::vector<std::size_t> add;
    std::vector<double> err(g.z.size(), -1);
    for (const auto& t : tris) {
      const Point2 &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]];
      for (int k = 0; k < 3; ++k) {
        const Point2 &p = pts[t[k]], &u = pts[t[(k + 1) % 3]], &v = pts[t[(k + 2) % 3]];
        const double ux = u[0] - p[0], uy = u[1] - p[1], vx = v[0] - p[0], vy = v[1] - p[1];
        min_angle = std::min(min_angle, std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / std::numbers::pi);
      }
      const double d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      const Point2 p0 = g.to_grid(a), p1 = g.to_grid(b), p2 = g.to_grid(c);
      const int c0 = int(std::ceil(std::min({p0[0], p1[0], p2[0]}) - 1e-9)), c1 = int(std::floor(std::max({p0[0], p1[0], p2[0]}) + 1e-9));
      const int r0 = int(std::ceil(std::min({p0[1], p1[1], p2[1]}) - 1e-9)), r1 = int(std::floor(std::max({p0[1], p1[1], p2[1]}) + 1e-9));
      double worst = -1;
      std::size_t worst_s = 0;
      for (int rr = std::max(r0, 0); rr <= std::min(r1, g.height - 1); ++rr)
        for (int cc = std::max(c0, 0); cc <= std::min(c1, g.width - 1); ++cc) {
          const Point2 x = g.position(cc, rr);
          const double l0 = ((b[0] - x[0]) * (c[1] - x[1]) - (b[1] - x[1]) * (c[0] - x[0])) / d;
          const double l1 = ((c[0] - x[0]) * (a[1] - x[1]) - (c[1] - x[1]) * (a[0] - x[0])) / d;
          const double l2 = 1 - l0 - l1;
          if (l0 < -1e-12 || l1 < -1e-12 || l2 < -1e-12) continue;
          const std::size_t s = g.index(cc, rr);
          const double e = std::abs(g.z[s] - (l0 * h[t[0]] + l1 * h[t[1]] + l2 * h[t[2]]));
          err[s] = std::max(err[s], e);
          if (e > worst || (e == worst && s < worst_s)) worst = e, worst_s = s;
        }
      if (worst > max_error && !is_sample[worst_s]) add.push_back(worst_s);
    }
    for (std::size_t s = 0; s < err.size(); ++s) worst_all = std::max(worst_all, err[s] < 0 ? INFINITY : err[s]);
    if (pass == 1) q.first_triangles = tris.size(), q.first_max_error = worst_all;
    q.triangles = tris.size(), q.vertices = pts.size(), q.max_error = worst_all, q.min_angle = min_angle, q.passes = pass;
    q.samples = all.size();
    if (add.empty()) return q;
    for (std::size_t s : add) is_sample[s] = 1;
  }
}

// ---- The engine alone on a given vertex set ------------------------------------------------------------
// StableWS on `samples` exactly as TerrainSession feeds it (the rectangle through the boundary samples with
// its canonical splits, the other samples loose, the box fitted to the grid's corners), and the constrained
// Delaunay mesh of its output inside the rectangle: how many Steiner points the engine needs for these
// vertices, to set against Triangle's on the same ones (where the terrain's excess comes from).
struct EngineOn {
  std::size_t inputs = 0, splits = 0, steiner = 0, steiner_inside = 0, triangles = 0;
  double ms = 0;
};

EngineOn engine_on(const HeightGrid& g, const std::vector<std::size_t>& samples, const Parameters<2>& params) {
  const auto t0 = Clock::now();
  std::vector<std::uint8_t> is_sample(g.z.size(), 0);
  for (std::size_t s : samples) is_sample[s] = 1;
  for (std::size_t s : {g.index(0, 0), g.index(g.width - 1, 0), g.index(0, g.height - 1), g.index(g.width - 1, g.height - 1)})
    is_sample[s] = 1;
  Domain2 rect;
  rect.rings.push_back({{}, RingRole::Shore});
  auto take = [&](int c, int r) { if (is_sample[g.index(c, r)]) rect.rings[0].points.push_back(g.position(c, r)); };
  for (int c = 0; c < g.width; ++c) take(c, 0);
  for (int r = 1; r < g.height; ++r) take(g.width - 1, r);
  for (int c = g.width - 2; c >= 0; --c) take(c, g.height - 1);
  for (int r = g.height - 2; r >= 1; --r) take(0, r);
  std::vector<Point2> loose;
  for (int r = 1; r + 1 < g.height; ++r)
    for (int c = 1; c + 1 < g.width; ++c)
      if (is_sample[g.index(c, r)]) loose.push_back(g.position(c, r));
  const std::vector<Point2> corners = {g.position(0, 0), g.position(g.width - 1, g.height - 1)};
  const BoxTransform<2> box = BoxTransform<2>::fit(corners);
  const ShoreRefinement refinement(rect, loose, RefinementRule::for_box(box.side));
  std::vector<Point2> inputs(rect.rings[0].points);
  inputs.insert(inputs.end(), loose.begin(), loose.end());
  const std::vector<Point2> splits = refinement.split_points();
  inputs.insert(inputs.end(), splits.begin(), splits.end());
  const DynamicWellSpaced<2> ws(inputs, params, box, BuildFor::OutputOnly);
  const std::vector<Point2> points = ws.points();
  const Mesh<2> mesh(points, ws.input_count(), refinement.refined());
  EngineOn e;
  e.inputs = ws.input_count(), e.splits = splits.size(), e.steiner = ws.steiner_count();
  e.triangles = mesh.elements().size();
  const Point2 lo = g.position(0, 0), hi = g.position(g.width - 1, g.height - 1);
  for (std::size_t k = ws.input_count(); k < points.size(); ++k) {
    const Point2& p = points[k];
    if (p[0] > std::min(lo[0], hi[0]) && p[0] < std::max(lo[0], hi[0]) && p[1] > std::min(lo[1], hi[1]) &&
        p[1] < std::max(lo[1], hi[1]))
      ++e.steiner_inside;
  }
  e.ms = ms_since(t0);
  return e;
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
  bool gh = true, session = true;
  std::string triangle;  // --triangle PATH: the quality reference on the greedy TIN's vertices
  double triangle_angle = 20.7;
  double beta = 0;  // --beta B: the engine's picking-region radius (0: its default, 2)
  double pick_spacing = TerrainOptions{}.pick_spacing;  // --pick-spacing S
  int block_cells = TerrainOptions{}.block_cells;       // --block B (0: no block picks)
  double block_fraction = TerrainOptions{}.block_fraction;  // --block-fraction A
  bool engine_alone = false;  // --engine-on: StableWS alone on the greedy TIN's vertices and on our own samples
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
    else if (a == "--no-session") session = false;
    else if (a == "--triangle") triangle = argv[++i];
    else if (a == "--triangle-angle") triangle_angle = std::stod(argv[++i]);
    else if (a == "--beta") beta = std::stod(argv[++i]);
    else if (a == "--engine-on") engine_alone = true;
    else if (a == "--pick-spacing") pick_spacing = std::stod(argv[++i]);
    else if (a == "--block") block_cells = std::stoi(argv[++i]);
    else if (a == "--block-fraction") block_fraction = std::stod(argv[++i]);
    else if (a == "--max-error")
      while (i + 1 < argc && argv[i + 1][0] != '-') errors.push_back(std::stod(argv[++i]));
    else dem_path = a;
  }
  if (errors.empty() || (dem_path.empty() && synthetic_n == 0)) {
    std::cerr << "usage: bench_terrain (DEM | --synthetic N | --upsample DEM K) --max-error E [E...] [--seed-fraction F] "
                 "[--repeat R] [--patches P --patch-side CELLS] [--no-gh] [--no-session] [--beta B] [--triangle PATH [--triangle-angle A]] [--engine-on] [--pick-spacing S] [--block B] [--block-fraction A]\n";
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
    for (int k = 0; k < (session ? repeat : 0); ++k) {
      TerrainOptions o;
      o.max_error = e;
      o.seed_fraction = fraction;
      if (beta > 0) o.engine.beta = beta;
      o.pick_spacing = pick_spacing;
      o.block_cells = block_cells;
      o.block_fraction = block_fraction;
      const auto t0 = Clock::now();
      s.emplace(grid, o);
      times.push_back(ms_since(t0));
    }
    if (!session) {
      const GhResult r = garland_heckbert(grid, e);
      std::printf("garland-heckbert E=%g: %zu triangles, %zu vertices, max %.4g rms %.4g, min angle %.3f, %.1f ms\n", e,
                  r.triangles, r.vertices, r.max_error, r.rms, r.min_angle, r.ms);
      if (!triangle.empty()) {
        const QualityRef q = triangle_quality(grid, r.samples, e, triangle, triangle_angle, "/tmp/bench_terrain_quality");
        std::printf("triangle -pq%g on the greedy vertices E=%g: %zu triangles (%.2f x greedy), max %.4g; then with the "
                    "worst samples added until within E: %zu triangles (%.2f x greedy), %zu vertices (%zu samples), "
                    "max %.4g, min angle %.2f, %zu passes\n",
                    triangle_angle, e, q.first_triangles, double(q.first_triangles) / double(r.triangles),
                    q.first_max_error, q.triangles, double(q.triangles) / double(r.triangles), q.vertices, q.samples,
                    q.max_error, q.min_angle, q.passes);
      }
      std::fflush(stdout);
      continue;
    }
    const TerrainError err = s->error();
    const auto angles = angle_range(s->points(), s->triangles());
    const TerrainUpdate& b = s->build_stats();
    std::printf("shoremesh E=%g (blocks %d, fraction %g): %zu triangles, %zu vertices (%zu seeds, %zu block picks, %zu "
                "correction picks, %zu rounds), max %.4g rms %.4g, angles %.2f..%.2f, median %.1f ms of %d (seeds and blocks "
                "%.1f, engine %.1f, mesh %.1f, error %.1f)\n",
                e, block_cells, block_fraction, s->triangles().size(), s->points().size(), s->seed_count(),
                s->block_pick_count(), s->pick_count(), s->rounds(), err.max,
                err.rms, angles[0], angles[1], median(times), repeat, b.seed_ms, b.engine_ms, b.mesh_ms, b.error_ms);
    if (gh) {
      std::vector<double> gtimes;
      GhResult r;
      for (int k = 0; k < repeat; ++k) r = garland_heckbert(grid, e), gtimes.push_back(r.ms);
      std::printf("garland-heckbert E=%g: %zu triangles, %zu vertices, max %.4g rms %.4g, min angle %.3f, median %.1f ms "
                  "of %d; shoremesh/gh triangles %.2f\n",
                  e, r.triangles, r.vertices, r.max_error, r.rms, r.min_angle, median(gtimes), repeat,
                  double(s->triangles().size()) / double(r.triangles));
      if (engine_alone) {
        Parameters<2> params;
        if (beta > 0) params.beta = beta;
        const EngineOn a = engine_on(grid, r.samples, params);
        std::printf("engine alone on the greedy vertices E=%g: %zu inputs (%zu rectangle splits), %zu Steiner (%zu inside "
                    "the rectangle), %zu triangles (%.2f x greedy), %.1f ms\n",
                    e, a.inputs, a.splits, a.steiner, a.steiner_inside, a.triangles, double(a.triangles) / double(r.triangles), a.ms);
        // Our own session's samples (its picks and corners; its boundary halvings are left out) through the
        // engine alone and through Triangle: is the excess in our picks or in the refinement?
        std::vector<std::size_t> ours;
        for (std::size_t k = 0; k < s->points().size(); ++k) {
          if (s->kinds()[k] != PointKind::Input) continue;
          const Point2 c = grid.to_grid(s->points()[k]);
          const double rc = std::round(c[0]), rr = std::round(c[1]);
          if (c[0] == rc && c[1] == rr) ours.push_back(grid.index(int(rc), int(rr)));
        }
        std::sort(ours.begin(), ours.end());
        const EngineOn o = engine_on(grid, ours, params);
        std::printf("engine alone on our %zu samples E=%g: %zu inputs, %zu Steiner (%zu inside), %zu triangles (session: "
                    "%zu Steiner, %zu triangles)\n",
                    ours.size(), e, o.inputs, o.steiner, o.steiner_inside, o.triangles, s->steiner_count(), s->triangles().size());
        if (!triangle.empty()) {
          const QualityRef q = triangle_quality(grid, ours, e, triangle, triangle_angle, "/tmp/bench_terrain_quality");
          std::printf("triangle -pq%g on our samples E=%g: %zu triangles (%.2f x greedy), max %.4g; until within E: %zu "
                      "triangles, %zu vertices, %zu passes\n",
                      triangle_angle, e, q.first_triangles, double(q.first_triangles) / double(r.triangles),
                      q.first_max_error, q.triangles, q.vertices, q.passes);
        }
      }
      if (!triangle.empty()) {
        const QualityRef q = triangle_quality(grid, r.samples, e, triangle, triangle_angle, "/tmp/bench_terrain_quality");
        std::printf("triangle -pq%g on the greedy vertices E=%g: %zu triangles (%.2f x greedy), max %.4g; then with the "
                    "worst samples added until within E: %zu triangles (%.2f x greedy), %zu vertices (%zu samples), "
                    "max %.4g, min angle %.2f, %zu passes; shoremesh/that %.2f\n",
                    triangle_angle, e, q.first_triangles, double(q.first_triangles) / double(r.triangles),
                    q.first_max_error, q.triangles, double(q.triangles) / double(r.triangles), q.vertices, q.samples,
                    q.max_error, q.min_angle, q.passes, double(s->triangles().size()) / double(q.triangles));
      }
    }
    if (patches > 0) {
      std::mt19937 rng(7);
      std::vector<double> pt, seeds, engine, mesh, error, numbering;
      std::vector<double> picks, block_changes;
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
        block_changes.push_back(double(u.block_picks_added + u.block_picks_removed));
      }
      // The first patch of a session builds the rounds' levels (TerrainSession::prepare_patches): reported
      // apart, the median and p90 are over the others.
      const double first = pt.empty() ? 0.0 : pt[0];
      if (pt.size() > 1)
        for (auto* v : {&pt, &seeds, &engine, &mesh, &error, &numbering, &picks, &block_changes}) v->erase(v->begin());
      std::printf("patches E=%g: %d of %d x %d samples: median %.1f ms, p90 %.1f ms over all but the first; the first "
                  "%.1f ms (seeds %.1f, engine %.1f, mesh %.1f, "
                  "error %.1f; correction picks taken back: median %.0f, max %.0f; block picks changed: median %.0f); then the "
                  "canonical TIN lists for an export: median %.1f ms\n",
                  e, patches, side, side, median(pt), percentile(pt, 0.9), first, median(seeds), median(engine), median(mesh),
                  median(error), median(picks), picks.empty() ? 0.0 : *std::max_element(picks.begin(), picks.end()),
                  median(block_changes), median(numbering));
    }
    std::fflush(stdout);
  }
  return 0;
}
