#pragma once
// Inputs for the mesh tests: random and lattice point sets, rings from a shared Triangle .poly PSLG
// sampled along their segments, and sorted element lists named by coordinates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/mesh_quality.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/shore_session.hpp"
#include "../io/io_test_util.hpp"

namespace shoremesh::mesh_test {

// The angle bound of radius-edge sqrt 2, in degrees: arcsin(1 / (2 sqrt 2)).
inline constexpr double kBoundDeg = 20.704811054635442;

// The engine's input for rings meshed by a fresh run: each ring point once, then the refinement's splits.
inline std::vector<Point2> ring_input(const Domain2& rings, const ShoreRefinement& refinement) {
  std::vector<Point2> input;
  std::set<Point2> seen;
  for (const Ring& r : rings.rings)
    for (const Point2& p : r.points)
      if (seen.insert(p).second) input.push_back(p);
  for (const Point2& p : refinement.split_points()) input.push_back(p);
  return input;
}

// The angle at p between the directions to u and w, in degrees (for the tests' own quality checks).
inline double degrees_at(const Point2& p, const Point2& u, const Point2& w) {
  const double ux = u[0] - p[0], uy = u[1] - p[1], wx = w[0] - p[0], wy = w[1] - p[1];
  return std::atan2(std::abs(ux * wy - uy * wx), ux * wx + uy * wy) * 180 / std::numbers::pi;
}

// A wobbly lake of radius ~50 km (`n` vertices) with an island: shore edits keep it valid.
inline Domain2 wobbly_lake(int n) {
  Domain2 d{{Ring{{}, RingRole::Shore}, Ring{{}, RingRole::Shore}}};
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n, r = 50000 + 4000 * std::sin(5 * a) + 1500 * std::cos(11 * a);
    d.rings[0].points.push_back({r * std::cos(a), r * std::sin(a)});
  }
  for (int k = 0; k < 12; ++k) {
    const double a = -2 * std::numbers::pi * k / 12, r = 6000 + 1000 * std::sin(3 * a);
    d.rings[1].points.push_back({15000 + r * std::cos(a), -10000 + r * std::sin(a)});
  }
  return d;
}

// Equirectangular about the lake's middle: simple, invertible, and it maps the water mask's lon/lat
// rectangle onto a rectangle. Areas are within about 2.5% at the lake's north and south ends.
struct Equirectangular {
  double lon0 = -88.25, lat0 = 47.7, radius = 6371008.8;
  double k() const { return std::numbers::pi / 180 * radius; }
  Point2 forward(const Point2& ll) const { return {(ll[0] - lon0) * k() * std::cos(lat0 * std::numbers::pi / 180), (ll[1] - lat0) * k()}; }
  Point2 inverse(const Point2& xy) const { return {lon0 + xy[0] / (k() * std::cos(lat0 * std::numbers::pi / 180)), lat0 + xy[1] / k()}; }
};

// Rings separated by blank lines, first point repeated at the end (dropped here).
inline std::vector<std::vector<Point2>> read_rings(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<Point2>> rings(1);
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \r\t") == std::string::npos) {
      if (!rings.back().empty()) rings.emplace_back();
      continue;
    }
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    Point2 p;
    s >> p[0] >> p[1];
    rings.back().push_back(p);
  }
  if (rings.back().empty()) rings.pop_back();
  for (auto& r : rings)
    if (r.size() > 1 && r.front() == r.back()) r.pop_back();
  return rings;
}


template <int D>
std::vector<Point<D>> random_points(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point<D>> pts(n);
  for (auto& p : pts)
    for (auto& x : p) x = u(rng);
  return pts;
}

// A triangular lattice of spacing h over [0, side]^2, each point moved by up to `jitter` * h: well-spaced
// for small jitter (Voronoi cells are near-regular hexagons of circumradius h / sqrt 3).
inline std::vector<Point2> jittered_lattice(double side, double h, double jitter, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * h, jitter * h);
  std::vector<Point2> pts;
  const double row = h * std::sqrt(3.0) / 2;
  for (int j = 0; j * row <= side; ++j)
    for (int i = 0; i * h <= side; ++i) pts.push_back({i * h + (j % 2 ? h / 2 : 0) + u(rng), j * row + u(rng)});
  return pts;
}

// The elements of a mesh named by their sorted corner coordinates, sorted: two meshes of the same points
// are the same mesh iff these lists are equal.
template <int D>
std::vector<ElementCorners<D>> corner_list(const Mesh<D>& mesh) {
  const auto elements = mesh.elements();
  return sorted_corners<D>(mesh.points(), elements);
}

// Closed rings from a Triangle .poly file: its segments chained into loops (every vertex of the shared
// PSLGs has even degree). All rings get the Shore role; the even-odd rule decides the water.
inline Domain2 rings_from_poly(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('#'));
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  std::size_t at = 0;
  std::istringstream header(lines[at++]);
  std::size_t n = 0;
  header >> n;
  std::map<long, Point2> vertex;
  for (std::size_t i = 0; i < n; ++i) {
    std::istringstream l(lines[at++]);
    long id;
    Point2 p;
    l >> id >> p[0] >> p[1];
    vertex[id] = p;
  }
  std::istringstream seg_header(lines[at++]);
  std::size_t m = 0;
  seg_header >> m;
  std::map<long, std::vector<std::pair<long, std::size_t>>> adjacent;  // neighbour and segment number
  for (std::size_t i = 0; i < m; ++i) {
    std::istringstream l(lines[at++]);
    long id, a, b;
    l >> id >> a >> b;
    adjacent[a].push_back({b, i});
    adjacent[b].push_back({a, i});
  }
  // Follow unused segments until back at the start. Vertices of degree 4 (two loops touching) are passed
  // through; the even-odd rule only needs every segment in exactly one ring.
  Domain2 domain;
  std::vector<bool> used(m, false);
  for (const auto& [start, unused] : adjacent) {
    while (true) {
      Ring ring;
      long v = start;
      do {
        auto it = std::find_if(adjacent.at(v).begin(), adjacent.at(v).end(), [&](auto e) { return !used[e.second]; });
        if (it == adjacent.at(v).end()) break;
        used[it->second] = true;
        ring.points.push_back(vertex.at(v));
        v = it->first;
      } while (v != start);
      if (ring.points.empty()) break;
      domain.rings.push_back(ring);
    }
  }
  return domain;
}

// Subdivides every ring segment into pieces no longer than h; returns the new domain (the same rings with
// the subdivision points inserted) so that the ring vertices are exactly the sample points.
inline Domain2 subdivide(const Domain2& domain, double h) {
  Domain2 out;
  for (const Ring& ring : domain.rings) {
    Ring r{{}, ring.role};
    for (std::size_t i = 0; i < ring.points.size(); ++i) {
      const Point2 a = ring.points[i], b = ring.points[(i + 1) % ring.points.size()];
      const int k = std::max(1, static_cast<int>(std::ceil(std::hypot(b[0] - a[0], b[1] - a[1]) / h)));
      for (int j = 0; j < k; ++j) r.points.push_back({a[0] + (b[0] - a[0]) * j / k, a[1] + (b[1] - a[1]) * j / k});
    }
    out.rings.push_back(r);
  }
  return out;
}

inline double distance_to_segment(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double t = std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

// Ring vertices first (the input points), then a jittered grid of spacing h over the rings' bounding box
// (Steiner-like points), dropping grid points closer than `clearance` to any ring segment.
inline std::vector<Point2> sample_domain(const Domain2& domain, double h, double clearance, std::uint32_t seed,
                                         std::size_t& input_count) {
  std::vector<Point2> pts;
  std::set<Point2> seen;  // a vertex where two rings touch is one point
  Point2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const Ring& r : domain.rings)
    for (const Point2& p : r.points) {
      if (seen.insert(p).second) pts.push_back(p);
      for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
    }
  input_count = pts.size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.2 * h, 0.2 * h);
  for (double y = lo[1] - h; y <= hi[1] + h; y += h)
    for (double x = lo[0] - h; x <= hi[0] + h; x += h) {
      const Point2 p{x + u(rng), y + u(rng)};
      bool clear = true;
      for (const Ring& r : domain.rings)
        for (std::size_t i = 0; clear && i < r.points.size(); ++i)
          clear = distance_to_segment(p, r.points[i], r.points[(i + 1) % r.points.size()]) >= clearance;
      if (clear) pts.push_back(p);
    }
  return pts;
}

// The io tests' scratch directory and data paths serve here too.
using io::test::ScratchDir;
using io::test::samples;

// Lake Superior's GSHHG rings (46: the shore, then the islands) in metres, scaled by `scale`.
inline Domain2 superior(double scale = 1) {
  const auto lonlat = read_rings(samples("superior/lake_superior_lonlat.csv"));
  const Equirectangular projection;
  Domain2 d;
  for (std::size_t r = 0; r < lonlat.size(); ++r) {
    Ring ring{{}, r == 0 ? RingRole::Shore : RingRole::Island};
    for (const Point2& ll : lonlat[r]) {
      const Point2 p = projection.forward(ll);
      ring.points.push_back({p[0] * scale, p[1] * scale});
    }
    d.rings.push_back(std::move(ring));
  }
  return d;
}

// A session's input from rings: their points in ring order, nothing loose.
inline SessionInput<2> session_input(const Domain2& rings) {
  SessionInput<2> in;
  in.rings = rings;
  for (const Ring& r : rings.rings) {
    in.ring_ids.emplace_back();
    for (std::size_t k = 0; k < r.points.size(); ++k) in.ring_ids.back().push_back(in.points.size() + k);
    in.points.insert(in.points.end(), r.points.begin(), r.points.end());
  }
  return in;
}

// Elements below the bound (radius-edge > sqrt 2), each checked to be not Delaunay: a mesh point lies inside its
// circumcircle (one the shore's constraints hide from it). `what` names the mesh in failures.
inline std::size_t below_bound_all_hidden(const Mesh<2>& mesh, const std::string& what = "") {
  std::size_t below = 0;
  for (const auto& e : mesh.elements()) {
    const ElementCorners<2> c{mesh.points()[e[0]], mesh.points()[e[1]], mesh.points()[e[2]]};
    const ElementShape<2> shape = element_shape<2>(c);
    if (shape.radius_edge <= std::sqrt(2.0) * (1 + 1e-12)) continue;
    ++below;
    const double r = std::hypot(c[0][0] - shape.circumcentre[0], c[0][1] - shape.circumcentre[1]);
    bool hides = false;
    for (const Point2& p : mesh.points())
      hides = hides || std::hypot(p[0] - shape.circumcentre[0], p[1] - shape.circumcentre[1]) < r * (1 - 1e-9);
    EXPECT_TRUE(hides) << what << ": a Delaunay element below the bound at " << shape.centroid[0] << ","
                       << shape.centroid[1];
  }
  return below;
}

}  // namespace shoremesh::mesh_test
