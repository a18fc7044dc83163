#pragma once
// Internal: assembling an InputSet (sources, points with origins, rings stored contiguously in points).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "shoremesh/error.hpp"
#include "shoremesh/io/input_set.hpp"

namespace shoremesh::io::detail {

class InputBuilder {
 public:
  InputBuilder(InputSet& set, const std::string& file, Source::Location kind) : set_(set) {
    source_ = static_cast<std::uint32_t>(set.sources.size());
    set.sources.push_back({file, kind});
  }
  void add_point(const Point2& p, std::size_t location, std::uint32_t ring = PointOrigin::kNoRing) {
    set_.points.push_back(p);
    set_.origins.push_back({source_, ring, location});
  }
  // Adds a ring; its vertices become points (in order), with the given locations (same size, or empty: 0).
  // With `share_vertices`, a vertex that an earlier ring of this builder shared with `share_vertices` has is
  // that ring's point (rings that meet there: a .poly's segments), not a new one.
  void add_ring(std::vector<Point2> pts, RingRole role, const std::vector<std::size_t>& locations = {},
                bool share_vertices = false) {
    const auto r = static_cast<std::uint32_t>(set_.domain.rings.size());
    std::vector<std::size_t> ids;
    ids.reserve(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      if (share_vertices)
        if (const auto it = shared_.find(pts[k]); it != shared_.end()) {
          ids.push_back(it->second);
          continue;
        }
      ids.push_back(set_.points.size());
      if (share_vertices) shared_.emplace(pts[k], ids.back());
      add_point(pts[k], locations.empty() ? 0 : locations[k], r);
    }
    set_.ring_ids.push_back(std::move(ids));
    set_.domain.rings.push_back({std::move(pts), role});
  }
  // The same, with points inserted along every segment longer than `spacing` (0: none), evenly; each
  // inserted point takes the location of the vertex before it. The caller has checked the count
  // against `max` (check_sampled_count).
  void add_ring(const std::vector<Point2>& pts, RingRole role, const std::vector<std::size_t>& locations,
                double spacing, std::size_t max = kMaxSampledPoints, bool share_vertices = false);
  std::size_t point_count() const { return set_.points.size(); }
  const std::string& file() const { return set_.sources[source_].file; }

 private:
  struct ExactHash {
    std::size_t operator()(const Point2& p) const {
      return std::hash<double>{}(p[0] + 0.0) * 0x9E3779B97F4A7C15ull ^ std::hash<double>{}(p[1] + 0.0);
    }
  };
  InputSet& set_;
  std::uint32_t source_ = 0;
  std::unordered_map<Point2, std::size_t, ExactHash> shared_;  // add_ring's shared vertices: their points
};

// How many points subdivide(pts, closed, spacing) gives, as a double: with a spacing far below the
// segments' lengths the count exceeds every integer type (an infinite or NaN length gives inf or NaN).
inline double subdivided_count(const std::vector<Point2>& pts, bool closed, double spacing) {
  if (!(spacing > 0) || pts.empty()) return static_cast<double>(pts.size());
  const std::size_t n = pts.size(), edges = closed ? n : n - 1;
  double count = static_cast<double>(n - edges);  // an open line's last point
  for (std::size_t i = 0; i < edges; ++i) {
    const Point2& a = pts[i];
    const Point2& b = pts[(i + 1) % n];
    count += std::max(1.0, std::ceil(std::hypot(b[0] - a[0], b[1] - a[1]) / spacing));
  }
  return count;
}

// Refuses, before any sampling, a spacing by which one input would have more than `max` points: `count`
// is the sum of subdivided_count over its rings and lines plus its other points. The message names the
// file, the spacing and the count. A NaN spacing is refused as such.
inline void check_sampled_count(double count, double spacing, std::size_t max, const std::string& file) {
  if (std::isnan(spacing)) throw InputError("spacing nan is not a number", file);
  if (count <= static_cast<double>(max)) return;
  throw InputError("--spacing " + readable(spacing) + " would cut the rings and segments into " + readable(count) +
                       " points, more than the " + std::to_string(max) + " allowed; choose a larger --spacing",
                   file);
}

// `pts` with points inserted evenly along every segment longer than `spacing` (none when spacing <= 0), so
// that no piece is longer; `closed`: the last point connects to the first. The caller has checked the
// count with check_sampled_count; a count beyond `max` here is a bug (std::logic_error).
inline std::vector<Point2> subdivide(const std::vector<Point2>& pts, bool closed, double spacing,
                                     std::size_t max = kMaxSampledPoints) {
  if (!(spacing > 0) || pts.empty()) return pts;
  if (!(subdivided_count(pts, closed, spacing) <= static_cast<double>(max)))
    throw std::logic_error("subdivide: the sampled count was not checked");
  std::vector<Point2> out;
  const std::size_t n = pts.size(), edges = closed ? n : n - 1;
  for (std::size_t i = 0; i < n; ++i) {
    out.push_back(pts[i]);
    if (i >= edges) break;
    const Point2& a = pts[i];
    const Point2& b = pts[(i + 1) % n];
    const auto pieces = static_cast<std::size_t>(std::ceil(std::hypot(b[0] - a[0], b[1] - a[1]) / spacing));
    for (std::size_t k = 1; k < pieces; ++k) {
      const double t = static_cast<double>(k) / static_cast<double>(pieces);
      out.push_back({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])});
    }
  }
  return out;
}

// For each point of `sub` (subdivide's output for `pts`), the index in `pts` of the vertex it is, or of
// the vertex before it for an inserted point: where each point came from.
inline std::vector<std::size_t> subdivided_from(const std::vector<Point2>& pts, const std::vector<Point2>& sub) {
  std::vector<std::size_t> from;
  from.reserve(sub.size());
  std::size_t k = 0;  // the next original vertex
  for (const Point2& q : sub) {
    if (k < pts.size() && q == pts[k]) ++k;
    from.push_back(k == 0 ? 0 : k - 1);
  }
  return from;
}

inline void InputBuilder::add_ring(const std::vector<Point2>& pts, RingRole role,
                                   const std::vector<std::size_t>& locations, double spacing, std::size_t max,
                                   bool share_vertices) {
  std::vector<Point2> sub = subdivide(pts, role != RingRole::Line, spacing, max);
  std::vector<std::size_t> sub_locations;
  for (const std::size_t v : subdivided_from(pts, sub)) sub_locations.push_back(locations.empty() ? 0 : locations[v]);
  add_ring(std::move(sub), role, sub_locations, share_vertices);
}

}  // namespace shoremesh::io::detail
