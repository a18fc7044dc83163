#include "shoremesh/mesh_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <tuple>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "shoremesh/mesh_coverage.hpp"
#include "shoremesh/shore_refinement.hpp"

namespace shoremesh {

namespace {

template <int D>
Point<D> sub(const Point<D>& a, const Point<D>& b) {
  Point<D> r;
  for (int i = 0; i < D; ++i) r[i] = a[i] - b[i];
  return r;
}

template <int D>
double dot(const Point<D>& a, const Point<D>& b) {
  double s = 0;
  for (int i = 0; i < D; ++i) s += a[i] * b[i];
  return s;
}

Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

double angle_between(double cosine) { return degrees(std::acos(std::clamp(cosine, -1.0, 1.0))); }

// Circumcentre relative to corner 0, solving the linear system 2 (p_i - p_0) . x = |p_i - p_0|^2 by
// Cramer's rule (a numerical construction, used for reporting only).
Point2 circumcentre_offset(const Point2& u, const Point2& v) {
  const double det = 2 * (u[0] * v[1] - u[1] * v[0]);
  const double uu = dot<2>(u, u), vv = dot<2>(v, v);
  const double inf = std::numeric_limits<double>::infinity();
  if (det == 0) return {inf, inf};
  return {(uu * v[1] - vv * u[1]) / det, (vv * u[0] - uu * v[0]) / det};
}

Point3 circumcentre_offset(const Point3& u, const Point3& v, const Point3& w) {
  const Point3 vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
  const double det = 2 * dot<3>(u, vw);
  const double inf = std::numeric_limits<double>::infinity();
  if (det == 0) return {inf, inf, inf};
  const double uu = dot<3>(u, u), vv = dot<3>(v, v), ww = dot<3>(w, w);
  Point3 r;
  for (int i = 0; i < 3; ++i) r[i] = (uu * vw[i] + vv * wu[i] + ww * uv[i]) / det;
  return r;
}

void add_to(Histogram& h, double value) {
  const double t = (value - h.low) / h.bin_width();
  const std::size_t last = h.counts.size() - 1;
  const std::size_t bin = !(t > 0) ? 0 : std::min(last, static_cast<std::size_t>(t));  // NaN/inf go to the ends
  ++h.counts[std::isnan(value) ? last : bin];
}

}  // namespace

// The circumcentre relative to corner 0, and the radius-edge ratio: what element_shape and radius_edge
// both give, computed once here so that the two agree to the bit.
template <int D>
double radius_edge_of(const ElementCorners<D>& c, Point<D>& offset) {
  double shortest = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= D; ++i)
    for (int j = i + 1; j <= D; ++j) shortest = std::min(shortest, std::sqrt(dot<D>(sub<D>(c[i], c[j]), sub<D>(c[i], c[j]))));
  if constexpr (D == 2) offset = circumcentre_offset(sub<2>(c[1], c[0]), sub<2>(c[2], c[0]));
  else offset = circumcentre_offset(sub<3>(c[1], c[0]), sub<3>(c[2], c[0]), sub<3>(c[3], c[0]));
  const double ratio = std::sqrt(dot<D>(offset, offset)) / shortest;
  return std::isnan(ratio) ? std::numeric_limits<double>::infinity() : ratio;
}

template <int D>
double radius_edge(const ElementCorners<D>& c) {
  Point<D> offset;
  return radius_edge_of<D>(c, offset);
}

template <int D>
ElementShape<D> element_shape(const ElementCorners<D>& c) {
  ElementShape<D> s;
  for (int i = 0; i < D; ++i) {
    double sum = 0;
    for (const auto& p : c) sum += p[i];
    s.centroid[i] = sum / (D + 1);
  }
  Point<D> offset;
  s.radius_edge = radius_edge_of<D>(c, offset);
  if constexpr (D == 2) {
    s.min_angle = 180;
    s.max_angle = 0;
    for (int i = 0; i < 3; ++i) {
      const Point2 u = sub<2>(c[(i + 1) % 3], c[i]), v = sub<2>(c[(i + 2) % 3], c[i]);
      const double a = angle_between(dot<2>(u, v) / std::sqrt(dot<2>(u, u) * dot<2>(v, v)));
      s.min_angle = std::min(s.min_angle, a);
      s.max_angle = std::max(s.max_angle, a);
    }
  } else {
    // The dihedral angle at edge (i, j) is the angle between the two faces that share it, measured
    // through the normals of the faces opposite k and l.
    s.min_angle = 180;
    s.max_angle = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        int k = 0;
        while (k == i || k == j) ++k;
        int l = 6 - i - j - k;
        const Point3 e = sub<3>(c[j], c[i]);
        // Components of (k - i) and (l - i) perpendicular to the edge; their angle is the dihedral angle.
        auto perpendicular = [&](const Point3& p) {
          const Point3 q = sub<3>(p, c[i]);
          const double t = dot<3>(q, e) / dot<3>(e, e);
          return Point3{q[0] - t * e[0], q[1] - t * e[1], q[2] - t * e[2]};
        };
        const Point3 a = perpendicular(c[k]), b = perpendicular(c[l]);
        const double angle = angle_between(dot<3>(a, b) / std::sqrt(dot<3>(a, a) * dot<3>(b, b)));
        s.min_angle = std::min(s.min_angle, angle);
        s.max_angle = std::max(s.max_angle, angle);
      }
  }
  for (int i = 0; i < D; ++i) s.circumcentre[i] = c[0][i] + offset[i];
  return s;
}

template <int D>
QualityReport<D> quality_report(std::span<const Point<D>> points, std::span<const Element<D>> elements, double rho,
                                std::optional<BoxTransform<D>> box, std::size_t worst_count) {
  QualityReport<D> r;
  r.elements = elements.size();
  r.rho = rho;
  r.min_angle_bound = D == 2 ? degrees(std::asin(std::min(1.0, 1.0 / (2 * rho)))) : 0.0;
  r.min_angle_histogram = {0, D == 2 ? 60.0 : 75.0, std::vector<std::size_t>(D == 2 ? 12 : 15)};
  r.radius_edge_histogram = {0.5, 3.0, std::vector<std::size_t>(25)};

  Point<D> low, high;
  if (box) {
    low = box->origin;
    for (int i = 0; i < D; ++i) high[i] = low[i] + box->side;
  } else {
    low.fill(std::numeric_limits<double>::infinity());
    high.fill(-std::numeric_limits<double>::infinity());
    for (const auto& p : points)
      for (int i = 0; i < D; ++i) low[i] = std::min(low[i], p[i]), high[i] = std::max(high[i], p[i]);
  }

  // A radius-edge ratio a few ulps above rho is rounding in the construction, not a broken guarantee.
  const double tolerance = rho * (1 + 1e-12);
  // The worst: the worst_count largest radius-edge ratios, ties by element order (a total order, so the
  // same elements whatever the split), each part of the work keeping its own few: a list of every
  // element's ratio held 11 MB at Superior's 700k triangles while the .msh was being written beside it.
  struct Ranked {
    double radius_edge;
    std::size_t element;
    bool before(const Ranked& o) const {
      return radius_edge > o.radius_edge || (radius_edge == o.radius_edge && element < o.element);
    }
  };
  const std::size_t k = std::min(worst_count, elements.size());
  auto keep_worst = [k](std::vector<Ranked>& top, const Ranked& x) {
    if (top.size() == k && (k == 0 || !x.before(top.back()))) return;
    top.insert(std::upper_bound(top.begin(), top.end(), x, [](const Ranked& a, const Ranked& b) { return a.before(b); }), x);
    if (top.size() > k) top.pop_back();
  };
  // Each element on its own, on every thread; the minima, maxima and counts do not depend on the split.
  struct Partial {
    double min_angle = std::numeric_limits<double>::infinity(), max_angle = 0;
    double min_radius_edge = std::numeric_limits<double>::infinity(), max_radius_edge = 0;
    double covered_max_radius_edge = 0;
    std::size_t meeting_bound = 0, covered = 0, covered_meeting_bound = 0;
    Histogram min_angle_histogram, radius_edge_histogram;
    std::vector<Ranked> worst;  // at most k, in the order `before`
  };
  Partial empty;
  empty.min_angle_histogram = r.min_angle_histogram;
  empty.radius_edge_histogram = r.radius_edge_histogram;
  const Partial all = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, elements.size(), 8192), empty,
      [&](const tbb::blocked_range<std::size_t>& range, Partial p) {
        for (std::size_t e = range.begin(); e != range.end(); ++e) {
          ElementCorners<D> corners;
          for (int i = 0; i <= D; ++i) corners[i] = points[elements[e][i]];
          const ElementShape<D> s = element_shape<D>(corners);
          p.min_angle = std::min(p.min_angle, s.min_angle);
          p.max_angle = std::max(p.max_angle, s.max_angle);
          p.min_radius_edge = std::min(p.min_radius_edge, s.radius_edge);
          p.max_radius_edge = std::max(p.max_radius_edge, s.radius_edge);
          const bool meets = s.radius_edge <= tolerance;
          const bool covered = circumcentre_in_box<D>(corners, low, high);  // exact, as the mesh clips
          p.meeting_bound += meets;
          if (covered) {
            ++p.covered;
            p.covered_meeting_bound += meets;
            p.covered_max_radius_edge = std::max(p.covered_max_radius_edge, s.radius_edge);
          }
          add_to(p.min_angle_histogram, s.min_angle);
          add_to(p.radius_edge_histogram, s.radius_edge);
          keep_worst(p.worst, {s.radius_edge, e});
        }
        return p;
      },
      [&](Partial a, const Partial& b) {
        for (const Ranked& x : b.worst) keep_worst(a.worst, x);
        a.min_angle = std::min(a.min_angle, b.min_angle);
        a.max_angle = std::max(a.max_angle, b.max_angle);
        a.min_radius_edge = std::min(a.min_radius_edge, b.min_radius_edge);
        a.max_radius_edge = std::max(a.max_radius_edge, b.max_radius_edge);
        a.covered_max_radius_edge = std::max(a.covered_max_radius_edge, b.covered_max_radius_edge);
        a.meeting_bound += b.meeting_bound;
        a.covered += b.covered;
        a.covered_meeting_bound += b.covered_meeting_bound;
        for (std::size_t i = 0; i < a.min_angle_histogram.counts.size(); ++i)
          a.min_angle_histogram.counts[i] += b.min_angle_histogram.counts[i];
        for (std::size_t i = 0; i < a.radius_edge_histogram.counts.size(); ++i)
          a.radius_edge_histogram.counts[i] += b.radius_edge_histogram.counts[i];
        return a;
      });
  r.min_angle = all.min_angle;
  r.max_angle = all.max_angle;
  r.min_radius_edge = all.min_radius_edge;
  r.max_radius_edge = all.max_radius_edge;
  r.covered_max_radius_edge = all.covered_max_radius_edge;
  r.meeting_bound = all.meeting_bound;
  r.covered = all.covered;
  r.covered_meeting_bound = all.covered_meeting_bound;
  r.min_angle_histogram = all.min_angle_histogram;
  r.radius_edge_histogram = all.radius_edge_histogram;
  if (elements.empty()) r.min_angle = r.min_radius_edge = 0;
  for (const Ranked& w : all.worst) {
    const std::size_t e = w.element;
    ElementCorners<D> corners;
    for (int j = 0; j <= D; ++j) corners[j] = points[elements[e][j]];
    r.worst.push_back({e, element_shape<D>(corners), circumcentre_in_box<D>(corners, low, high)});
  }
  return r;
}

template <int D>
std::string QualityReport<D>::summary() const {
  std::ostringstream out;
  out << elements << (D == 2 ? " triangles" : " tetrahedra") << "; " << (D == 2 ? "angles " : "dihedral angles ")
      << min_angle << ".." << max_angle << " deg; radius-edge " << min_radius_edge << ".." << max_radius_edge << "\n";
  out << "bound for rho = " << rho << ": radius-edge <= " << rho;
  if (D == 2) out << " (minimum angle >= " << min_angle_bound << " deg)";
  out << "; met by " << covered_meeting_bound << " of " << covered << " covered elements (circumcentre in the box), "
      << meeting_bound << " of " << elements << " overall; worst covered " << covered_max_radius_edge << "\n";
  for (const auto& w : worst) {
    out << "  element " << w.element << " at (";
    for (int i = 0; i < D; ++i) out << (i ? ", " : "") << w.shape.centroid[i];
    out << "): radius-edge " << w.shape.radius_edge << ", angles " << w.shape.min_angle << ".." << w.shape.max_angle
        << (w.covered ? "" : " (circumcentre outside the box: not covered by the bound)") << "\n";
  }
  return out.str();
}

std::vector<SharpCorner> sharp_corners(const Domain2& rings) {
  // Each vertex's other ends, over every ring and line through it (a shared vertex is one point): the
  // pairs (vertex, other end) sorted, so that a vertex's others are a sorted range.
  std::vector<std::pair<Point2, Point2>> ends;
  std::size_t count = 0;
  for (const Ring& ring : rings.rings) count += 2 * ring.segment_count();
  ends.reserve(count);
  for (const Ring& ring : rings.rings)
    for (std::size_t k = 0; k < ring.segment_count(); ++k) {
      const Point2& p = ring.points[k];
      const Point2& q = ring.points[(k + 1) % ring.points.size()];
      if (p == q) continue;
      ends.emplace_back(p, q);
      ends.emplace_back(q, p);
    }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  std::vector<SharpCorner> out;
  for (std::size_t first = 0, last = 0; first < ends.size(); first = last) {
    const Point2 apex = ends[first].first;
    while (last < ends.size() && ends[last].first == apex) ++last;
    for (std::size_t i = first; i < last; ++i)
      for (std::size_t j = i + 1; j < last; ++j) {
        const Point2 &a = ends[i].second, &b = ends[j].second;
        if (!corner_sharper_than_60(apex, a, b)) continue;
        const Point2 u = sub<2>(a, apex), w = sub<2>(b, apex);
        const double la = std::sqrt(dot<2>(u, u)), lb = std::sqrt(dot<2>(w, w));
        out.push_back({apex, a, b, angle_between(dot<2>(u, w) / (la * lb)), std::min(la, lb)});
      }
  }
  std::sort(out.begin(), out.end(), [](const SharpCorner& x, const SharpCorner& y) {
    return std::tie(x.apex, x.a, x.b) < std::tie(y.apex, y.a, y.b);
  });
  return out;
}

std::optional<std::size_t> sharp_corner_at(const ElementCorners<2>& t, std::span<const SharpCorner> corners) {
  const Point2 c{(t[0][0] + t[1][0] + t[2][0]) / 3, (t[0][1] + t[1][1] + t[2][1]) / 3};
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Point2 d = sub<2>(c, corners[i].apex);
    if (dot<2>(d, d) < corners[i].reach * corners[i].reach) return i;
  }
  return std::nullopt;
}

template double radius_edge<2>(const ElementCorners<2>&);
template double radius_edge<3>(const ElementCorners<3>&);
template ElementShape<2> element_shape<2>(const ElementCorners<2>&);
template ElementShape<3> element_shape<3>(const ElementCorners<3>&);
template QualityReport<2> quality_report<2>(std::span<const Point2>, std::span<const Element<2>>, double,
                                            std::optional<BoxTransform<2>>, std::size_t);
template QualityReport<3> quality_report<3>(std::span<const Point3>, std::span<const Element<3>>, double,
                                            std::optional<BoxTransform<3>>, std::size_t);
template struct QualityReport<2>;
template struct QualityReport<3>;

}  // namespace shoremesh
