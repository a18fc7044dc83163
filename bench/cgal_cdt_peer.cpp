// Peer for the conforming water mesh benchmark (bench/superior_conforming.py, issue 33): CGAL's constrained
// Delaunay refinement of the same polygon shoremesh meshes.
//
//   cgal_cdt_peer RING_FILE [--lonlat] [--projection utm|local] [--write-segments FILE] [--write-poly FILE]
//
// The ring file is read by shoremesh's own reader (io::read_input), so lon/lat rings are projected to metres
// exactly as `shoremesh mesh --lonlat` projects them. The rings become the constraints of a
// CGAL::Constrained_Delaunay_triangulation_2; the water faces are marked even-odd by nesting depth (CGAL's
// mark_domain example: depth 1 is the lake, 2 an island, ...); CGAL::refine_Delaunay_mesh_2 then refines the
// marked faces only with Delaunay_mesh_size_criteria_2(0.125, 0): sin^2 of the smallest angle >= 0.125,
// i.e. 20.7 degrees (the bound of rho = sqrt(2)), no size bound. Timed: building the CDT, marking and
// refining (reading and projecting are not). Checked afterwards on the result, not taken from CGAL's word:
// water vertices and triangles, how many input segments are unions of constrained mesh edges, how many water
// triangles have their smallest angle below 20.7 degrees, and the water area against the polygons' area.
// With --write-segments the projected shore segments are written (x1 y1 x2 y2 per line, shortest round-trip
// decimals) for the benchmark script's own conformity check of shoremesh's exported mesh.
// With --write-poly the same projected rings are written as a Triangle .poly (vertices, segments, and one hole
// seed per island: the centroid of a land face of the CDT inside the outer shore, one per connected land
// region), so that a Triangle binary built by the user from Shewchuk's public source can mesh the very same
// polygon in the benchmark (Triangle is not shipped: its license).
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <sys/resource.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <list>
#include <map>
#include <numbers>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "shoremesh/error.hpp"
#include "shoremesh/io/read_input.hpp"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Vertex_handle = Cdt::Vertex_handle;
using Face_handle = Cdt::Face_handle;
using Point = K::Point_2;

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

// CGAL's mark_domain example: faces reached from the infinite face without crossing a constraint get depth
// 0, across one constraint 1, and so on; water is odd depth.
void mark_domains(Cdt& cdt) {
  std::unordered_map<Face_handle, int> depth;
  for (Face_handle f : cdt.all_face_handles()) depth[f] = -1;
  std::list<Cdt::Edge> border;
  auto flood = [&](Face_handle start, int level) {
    if (depth[start] != -1) return;
    std::list<Face_handle> queue{start};
    while (!queue.empty()) {
      Face_handle fh = queue.front();
      queue.pop_front();
      if (depth[fh] != -1) continue;
      depth[fh] = level;
      for (int i = 0; i < 3; ++i) {
        Face_handle n = fh->neighbor(i);
        if (depth[n] != -1) continue;
        if (cdt.is_constrained({fh, i}))
          border.push_back({fh, i});
        else
          queue.push_back(n);
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    Cdt::Edge e = border.front();
    border.pop_front();
    Face_handle n = e.first->neighbor(e.second);
    if (depth[n] == -1) flood(n, depth[e.first] + 1);
  }
  for (Face_handle f : cdt.all_face_handles()) f->set_in_domain(!cdt.is_infinite(f) && depth[f] % 2 == 1);
}

// Whether the segment a-b is a chain of constrained mesh edges: walk from a along constrained edges, each to
// a vertex that is no input point (or is b) and lies nearer b, within 1e-9 of the segment's length of its
// line. Not exactly on it: CGAL splits a constrained edge at its midpoint computed in doubles (EPICK), which
// is off the line by a rounding; `off_line` gets the largest such distance.
bool segment_is_mesh_edges(const Cdt& cdt, Vertex_handle a, Vertex_handle b,
                           const std::unordered_set<Vertex_handle>& input_vertices, double& off_line) {
  const Point pa = a->point(), pb = b->point();
  const double length = std::sqrt(CGAL::to_double(CGAL::squared_distance(pa, pb)));
  const K::Line_2 line(pa, pb);
  Vertex_handle v = a;
  for (int steps = 0; v != b; ++steps) {
    if (steps > 100000) return false;
    Vertex_handle next;
    double deviation = 0;
    const double remaining = CGAL::to_double(CGAL::squared_distance(v->point(), pb));
    auto c = cdt.incident_edges(v), done = c;
    do {
      const Cdt::Edge e = *c;
      if (cdt.is_infinite(e) || !cdt.is_constrained(e)) continue;
      const Vertex_handle w = e.first->vertex(Cdt::cw(e.second)) == v ? e.first->vertex(Cdt::ccw(e.second))
                                                                       : e.first->vertex(Cdt::cw(e.second));
      if (w != b && input_vertices.count(w)) continue;
      const double d = w == b ? 0 : std::sqrt(CGAL::to_double(CGAL::squared_distance(line, w->point())));
      if (d <= 1e-9 * length && CGAL::to_double(CGAL::squared_distance(w->point(), pb)) < remaining) {
        next = w;
        deviation = d;
        break;
      }
    } while (++c != done);
    if (next == Vertex_handle()) return false;
    off_line = std::max(off_line, deviation);
    v = next;
  }
  return true;
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

std::string round_trip(double x) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, end);
}

// The polygon as a Triangle .poly. Hole seeds: faces not reached from the infinite face without crossing a
// constraint are inside the outer shore; those not in the water are land (islands), one seed per connected
// land region (flooded across unconstrained edges), at the centroid of its first face.
bool write_poly(const Cdt& cdt, const std::vector<Point>& points,
                const std::vector<std::pair<std::size_t, std::size_t>>& edges, const std::string& path) {
  std::unordered_set<Face_handle> reached;
  auto flood = [&](Face_handle start) {
    std::vector<Face_handle> stack{start};
    reached.insert(start);
    while (!stack.empty()) {
      const Face_handle f = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const Face_handle n = f->neighbor(i);
        if (cdt.is_constrained({f, i}) || reached.count(n)) continue;
        reached.insert(n);
        stack.push_back(n);
      }
    }
  };
  flood(cdt.infinite_face());
  std::vector<Point> seeds;
  for (Face_handle f : cdt.finite_face_handles()) {
    if (f->is_in_domain() || reached.count(f)) continue;
    seeds.push_back(CGAL::centroid(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()));
    flood(f);
  }
  std::ofstream out(path);
  out << points.size() << " 2 0 0\n";
  for (std::size_t i = 0; i < points.size(); ++i)
    out << i + 1 << ' ' << round_trip(points[i].x()) << ' ' << round_trip(points[i].y()) << '\n';
  out << edges.size() << " 0\n";
  for (std::size_t k = 0; k < edges.size(); ++k)
    out << k + 1 << ' ' << edges[k].first + 1 << ' ' << edges[k].second + 1 << '\n';
  out << seeds.size() << '\n';
  for (std::size_t k = 0; k < seeds.size(); ++k)
    out << k + 1 << ' ' << round_trip(seeds[k].x()) << ' ' << round_trip(seeds[k].y()) << '\n';
  return static_cast<bool>(out);
}

}  // namespace

int main(int argc, char** argv) {
  std::string path, segments_out, poly_out;
  shoremesh::io::InputOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--lonlat") {
      options.lonlat = true;
    } else if (a == "--projection" && i + 1 < argc) {
      const std::string p = argv[++i];
      if (p != "utm" && p != "local") {
        std::cerr << "cgal_cdt_peer: --projection is utm or local, not '" << p << "'\n";
        return 2;
      }
      options.projection_choice =
          p == "local" ? shoremesh::io::ProjectionChoice::LocalTransverseMercator : shoremesh::io::ProjectionChoice::Utm;
    } else if (a == "--write-segments" && i + 1 < argc) {
      segments_out = argv[++i];
    } else if (a == "--write-poly" && i + 1 < argc) {
      poly_out = argv[++i];
    } else if (path.empty() && !a.empty() && a[0] != '-') {
      path = a;
    } else {
      std::cerr << "usage: cgal_cdt_peer RING_FILE [--lonlat] [--projection utm|local] [--write-segments FILE] [--write-poly FILE]\n";
      return 2;
    }
  }
  if (path.empty()) {
    std::cerr << "usage: cgal_cdt_peer RING_FILE [--lonlat] [--projection utm|local] [--write-segments FILE] [--write-poly FILE]\n";
    return 2;
  }

  shoremesh::io::InputSet input;
  try {
    input = shoremesh::io::read_input(path, options);
  } catch (const shoremesh::InputError& e) {
    std::cerr << "cgal_cdt_peer: " << e.what() << "\n";
    return 1;
  }
  if (input.domain.empty()) {
    std::cerr << "cgal_cdt_peer: " << path << ": no rings\n";
    return 1;
  }
  std::size_t segment_count = 0, ring_points = 0;
  double polygon_area = 0;  // even-odd: |signed area| of the outer shore minus the islands'
  for (const shoremesh::Ring& r : input.domain.rings) {
    double a2 = 0;
    for (std::size_t k = 0; k < r.points.size(); ++k) {
      const auto& p = r.points[k];
      const auto& q = r.points[(k + 1) % r.points.size()];
      a2 += p[0] * q[1] - q[0] * p[1];
    }
    polygon_area += (r.role == shoremesh::RingRole::Shore ? 1 : -1) * std::abs(a2) / 2;
    segment_count += r.points.size();
    ring_points += r.points.size();
  }
  if (!segments_out.empty()) {
    std::ofstream out(segments_out);
    for (const shoremesh::Ring& r : input.domain.rings)
      for (std::size_t k = 0; k < r.points.size(); ++k) {
        const auto& p = r.points[k];
        const auto& q = r.points[(k + 1) % r.points.size()];
        out << round_trip(p[0]) << ' ' << round_trip(p[1]) << ' ' << round_trip(q[0]) << ' ' << round_trip(q[1]) << '\n';
      }
    if (!out) {
      std::cerr << "cgal_cdt_peer: cannot write " << segments_out << "\n";
      return 1;
    }
  }

  // All ring points and ring edges in one call: CGAL sorts the points spatially before inserting them.
  std::vector<Point> points;
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  points.reserve(ring_points);
  edges.reserve(segment_count);
  for (const shoremesh::Ring& r : input.domain.rings) {
    const std::size_t first = points.size();
    for (std::size_t k = 0; k < r.points.size(); ++k) {
      points.emplace_back(r.points[k][0], r.points[k][1]);
      edges.emplace_back(first + k, first + (k + 1) % r.points.size());
    }
  }

  using Clock = std::chrono::steady_clock;
  const double c0 = cpu_seconds();
  const auto t0 = Clock::now();
  Cdt cdt;
  cdt.insert_constraints(points.begin(), points.end(), edges.begin(), edges.end());
  const auto t1 = Clock::now();
  mark_domains(cdt);
  const auto t2 = Clock::now();
  if (!poly_out.empty()) {
    if (!write_poly(cdt, points, edges, poly_out)) {
      std::cerr << "cgal_cdt_peer: cannot write " << poly_out << "\n";
      return 1;
    }
    return 0;
  }
  CGAL::refine_Delaunay_mesh_2(cdt, Criteria(0.125, 0), /*domain_specified=*/true);
  const auto t3 = Clock::now();
  const double c3 = cpu_seconds();

  // Checks on the result.
  std::unordered_set<Vertex_handle> water_vertices;
  std::size_t triangles = 0, below_bound = 0;
  double water_area = 0, min_angle = 180;
  const double bound_deg = std::asin(1 / (2 * std::sqrt(2.0))) * 180 / std::numbers::pi;
  for (Face_handle f : cdt.finite_face_handles()) {
    if (!f->is_in_domain()) continue;
    ++triangles;
    for (int i = 0; i < 3; ++i) water_vertices.insert(f->vertex(i));
    const Point &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &c = f->vertex(2)->point();
    water_area += CGAL::area(a, b, c);
    double smallest = 180;
    const Point* v[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
      const auto u = *v[(i + 1) % 3] - *v[i], w = *v[(i + 2) % 3] - *v[i];
      const double angle = std::atan2(std::abs(u.x() * w.y() - u.y() * w.x()), u * w) * 180 / std::numbers::pi;
      smallest = std::min(smallest, angle);
    }
    min_angle = std::min(min_angle, smallest);
    if (smallest < bound_deg - 1e-9) ++below_bound;
  }
  std::map<std::pair<double, double>, Vertex_handle> vertex_at;
  for (Vertex_handle v : cdt.finite_vertex_handles()) vertex_at[{v->point().x(), v->point().y()}] = v;
  std::unordered_set<Vertex_handle> input_vertices;
  for (const Point& p : points) input_vertices.insert(vertex_at.at({p.x(), p.y()}));
  std::size_t conforming = 0;
  double off_line = 0;
  for (const auto& [i, j] : edges)
    conforming += segment_is_mesh_edges(cdt, vertex_at.at({points[i].x(), points[i].y()}),
                                        vertex_at.at({points[j].x(), points[j].y()}), input_vertices, off_line);

  const auto secs = [](auto d) { return std::chrono::duration<double>(d).count(); };
  std::printf(
      "peer=cgal_cdt rings=%zu ring_points=%zu segments=%zu cdt_seconds=%.3f mark_seconds=%.3f refine_seconds=%.3f "
      "seconds=%.3f cpu_seconds=%.3f water_vertices=%zu water_triangles=%zu all_vertices=%zu segments_mesh_edges=%zu split_off_line_m=%.2e "
      "below_20.7deg=%zu min_angle_deg=%.3f water_area_m2=%.6e polygon_area_m2=%.6e area_rel_diff=%.2e "
      "peak_rss_mb=%.1f\n",
      input.domain.rings.size(), ring_points, segment_count, secs(t1 - t0), secs(t2 - t1), secs(t3 - t2),
      secs(t3 - t0), c3 - c0, water_vertices.size(), triangles, static_cast<std::size_t>(cdt.number_of_vertices()), conforming, off_line,
      below_bound, min_angle, water_area, polygon_area, std::abs(water_area - polygon_area) / polygon_area,
      peak_rss_mb());
  return 0;
}
