// Depths from soundings by linear interpolation on their Delaunay triangulation (soundings.hpp).
#include "shoremesh/io/soundings.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <stdexcept>

namespace shoremesh::io {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;  // the project's kernel
using Vb = CGAL::Triangulation_vertex_base_with_info_2<double, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
}  // namespace

struct Soundings::Triangulation {
  Delaunay dt;
};

Soundings::Soundings(std::vector<Point2> points, std::vector<double> depths) : t_(std::make_unique<Triangulation>()) {
  if (points.empty() || points.size() != depths.size()) throw std::invalid_argument("soundings: points and depths differ");
  std::vector<std::pair<Kernel::Point_2, double>> v;
  v.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) v.emplace_back(Kernel::Point_2(points[i][0], points[i][1]), depths[i]);
  t_->dt.insert(v.begin(), v.end());
  size_ = points.size();
}

Soundings::~Soundings() = default;

double Soundings::depth_at(const Point2& p) const {
  const Delaunay& dt = t_->dt;
  const Kernel::Point_2 q(p[0], p[1]);
  if (dt.dimension() < 2) return dt.nearest_vertex(q)->info();
  Delaunay::Locate_type type;
  int li = 0;
  const auto f = dt.locate(q, type, li);
  if (type == Delaunay::VERTEX) return f->vertex(li)->info();
  if (type == Delaunay::OUTSIDE_CONVEX_HULL || type == Delaunay::OUTSIDE_AFFINE_HULL || dt.is_infinite(f))
    return dt.nearest_vertex(q)->info();
  // Barycentric coordinates in the triangle (its corners counter-clockwise).
  const auto &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &c = f->vertex(2)->point();
  const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
  const double l1 = ((q.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (q.y() - a.y())) / det;
  const double l2 = ((b.x() - a.x()) * (q.y() - a.y()) - (q.x() - a.x()) * (b.y() - a.y())) / det;
  const double l0 = 1 - l1 - l2;
  return l0 * f->vertex(0)->info() + l1 * f->vertex(1)->info() + l2 * f->vertex(2)->info();
}

std::vector<double> sounding_depths(const Soundings& soundings, std::span<const Point2> points,
                                    const DepthOptions& options) {
  std::vector<double> out;
  out.reserve(points.size());
  for (const Point2& p : points) {
    double d = soundings.depth_at(p);
    if (options.max_height) d = std::max(d, 0.0 - *options.max_height);
    if (options.min_depth) d = std::max(d, *options.min_depth);
    out.push_back(d);
  }
  return out;
}

}  // namespace shoremesh::io
