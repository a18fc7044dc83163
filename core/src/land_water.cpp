// Land and water in one mesh (`shoremesh mesh --dem FILE --land-up-to Z`, docs/terrain.md): the shoreline's
// pieces kept as constraint lines inside the domain below Z, and the counts the summary gives.
#include "shoremesh/land_water.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <utility>

#include "shoremesh/mesh_water.hpp"

namespace shoremesh {

namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BSegment = bg::model::segment<BPoint>;
using BBox = bg::model::box<BPoint>;

BPoint bp(const Point2& p) { return BPoint(p[0], p[1]); }

}  // namespace

// The shoreline's pieces that lie clear of the domain's rings: a vertex at least `clearance` from every
// ring segment, a segment at least half of it. Where the land between the shoreline and Z is narrower
// than that (a cliff at the DEM's resolution), the domain's ring is the shoreline there, and the piece is
// left out. A closed piece becomes two lines sharing their ends (the domain accepts shared vertices).

ShoreLines shoreline_lines(const Domain2& shore, const Domain2& domain, double clearance) {
  std::vector<std::pair<BBox, std::size_t>> boxes;
  std::vector<BSegment> segments;
  for (const Ring& r : domain.rings)
    for (std::size_t k = 0; k < r.segment_count(); ++k) {
      const BSegment s(bp(r.points[k]), bp(r.points[(k + 1) % r.points.size()]));
      BBox b;
      bg::envelope(s, b);
      boxes.push_back({b, segments.size()});
      segments.push_back(s);
    }
  const bgi::rtree<std::pair<BBox, std::size_t>, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
  auto nearest_within = [&](const auto& geometry, double d) {
    BBox b;
    bg::envelope(geometry, b);
    const BBox grown(BPoint(b.min_corner().get<0>() - d, b.min_corner().get<1>() - d),
                     BPoint(b.max_corner().get<0>() + d, b.max_corner().get<1>() + d));
    double best = std::numeric_limits<double>::infinity();
    for (auto it = tree.qbegin(bgi::intersects(grown)); it != tree.qend(); ++it)
      best = std::min(best, static_cast<double>(bg::distance(geometry, segments[it->second])));
    return best;
  };
  ShoreLines out;
  for (const Ring& r : shore.rings) {
    const std::size_t n = r.points.size();
    if (n < 3) continue;
    std::vector<char> vertex_clear(n), segment_clear(n);
    for (std::size_t k = 0; k < n; ++k) vertex_clear[k] = nearest_within(bp(r.points[k]), clearance) >= clearance;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t j = (k + 1) % n;
      segment_clear[k] = vertex_clear[k] && vertex_clear[j] &&
                         nearest_within(BSegment(bp(r.points[k]), bp(r.points[j])), clearance) >= 0.5 * clearance;
      out.dropped_segments += !segment_clear[k];
    }
    const auto first_gap = std::find(segment_clear.begin(), segment_clear.end(), 0);
    if (first_gap == segment_clear.end()) {
      // Closed and clear: two lines, 0 .. n/2 and n/2 .. n (= 0).
      Ring a{{}, RingRole::Line}, b{{}, RingRole::Line};
      for (std::size_t k = 0; k <= n / 2; ++k) a.points.push_back(r.points[k]);
      for (std::size_t k = n / 2; k <= n; ++k) b.points.push_back(r.points[k % n]);
      out.segments += n;
      out.lines.push_back(std::move(a));
      out.lines.push_back(std::move(b));
      continue;
    }
    // Runs of clear segments, starting after a gap so that none wraps. A run goes on into the segments
    // beside it as far as the clearance holds (bisection), so that it stops about `clearance` from the
    // domain's ring rather than a whole segment before.
    auto clip = [&](const Point2& v, const Point2& w) -> std::optional<Point2> {
      auto at = [&](double t) { return Point2{v[0] + t * (w[0] - v[0]), v[1] + t * (w[1] - v[1])}; };
      auto ok = [&](double t) {
        const Point2 p = at(t);
        return nearest_within(bp(p), clearance) >= clearance &&
               nearest_within(BSegment(bp(v), bp(p)), clearance) >= 0.5 * clearance;
      };
      double lo = 0, hi = 1;
      for (int i = 0; i < 30; ++i) {
        const double mid = 0.5 * (lo + hi);
        (ok(mid) ? lo : hi) = mid;
      }
      if (lo * std::hypot(w[0] - v[0], w[1] - v[1]) < 0.1 * clearance) return std::nullopt;
      return at(lo);
    };
    const std::size_t start = static_cast<std::size_t>(first_gap - segment_clear.begin());
    Ring line{{}, RingRole::Line};
    auto flush = [&] {
      if (line.points.size() >= 2) out.segments += line.points.size() - 1, out.lines.push_back(line);
      line.points.clear();
    };
    for (std::size_t i = 1; i <= n; ++i) {
      const std::size_t k = (start + i) % n, next = (k + 1) % n, previous = (k + n - 1) % n;
      if (!segment_clear[k]) {
        if (!line.points.empty())
          if (const auto p = clip(r.points[k], r.points[next])) line.points.push_back(*p);
        flush();
        continue;
      }
      if (line.points.empty()) {
        if (!segment_clear[previous])
          if (const auto p = clip(r.points[k], r.points[previous])) line.points.push_back(*p);
        line.points.push_back(r.points[k]);
      }
      line.points.push_back(r.points[next]);
    }
    flush();
  }
  return out;
}


LandWaterCounts land_water_counts(const std::vector<Point2>& points,
                                  const std::vector<Element<2>>& triangles, const Domain2& shore,
                                  bool all_below, bool none_below, const std::vector<Ring>& lines, double tol) {
  std::size_t water = 0;
  if (all_below) {
    water = triangles.size();
  } else if (!none_below) {
    const WaterTest wet(shore);
    for (const auto& t : triangles) {
      const Point2 c{(points[t[0]][0] + points[t[1]][0] + points[t[2]][0]) / 3,
                     (points[t[0]][1] + points[t[1]][1] + points[t[2]][1]) / 3};
      water += wet.classify(c) != WaterSide::Land;  // on the contour: counted as water
    }
  }
  // Mesh edges along the shoreline's lines: both ends on one segment of a line (the refinement's splits
  // are midpoints, on the segment to rounding).
  std::size_t shore_edges = 0;
  {
    std::vector<std::pair<BBox, std::size_t>> boxes;
    std::vector<BSegment> segs;
    for (const Ring& l : lines)
      for (std::size_t k = 0; k + 1 < l.points.size(); ++k) {
        const BSegment s(bp(l.points[k]), bp(l.points[k + 1]));
        BBox b;
        bg::envelope(s, b);
        boxes.push_back({b, segs.size()});
        segs.push_back(s);
      }
    const bgi::rtree<std::pair<BBox, std::size_t>, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
    std::vector<std::vector<std::size_t>> on(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const BBox b(BPoint(points[i][0] - tol, points[i][1] - tol), BPoint(points[i][0] + tol, points[i][1] + tol));
      for (auto it = tree.qbegin(bgi::intersects(b)); it != tree.qend(); ++it)
        if (bg::distance(bp(points[i]), segs[it->second]) <= tol) on[i].push_back(it->second);
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    for (const auto& [u, v] : edges)
      for (std::size_t s : on[u])
        if (std::find(on[v].begin(), on[v].end(), s) != on[v].end()) {
          ++shore_edges;
          break;
        }
  }

  return {water, shore_edges};
}

}  // namespace shoremesh
