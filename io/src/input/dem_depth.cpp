// Depths at mesh nodes from a DEM (dem.hpp, docs/depths.md): the mean over the node's Voronoi cell within
// the mesh, bilinear where that cell holds no DEM cell centre.
#include <algorithm>
#include <cmath>
#include <limits>

#include "shoremesh/error.hpp"
#include "shoremesh/io/dem.hpp"

namespace shoremesh::io {

namespace {

// Nearest node by buckets on a uniform grid: exact (rings of buckets are searched until no closer node
// can remain), ties to the smaller index so the answer does not depend on any visiting order.
class NearestNode {
 public:
  NearestNode(std::span<const Point2> points, const std::vector<std::uint8_t>& used) : points_(points) {
    lo_ = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    Point2 hi{-lo_[0], -lo_[1]};
    std::size_t n = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (used[i]) {
        ++n;
        for (int k = 0; k < 2; ++k) lo_[k] = std::min(lo_[k], points[i][k]), hi[k] = std::max(hi[k], points[i][k]);
      }
    const double span = std::max({hi[0] - lo_[0], hi[1] - lo_[1], 1e-300});
    cols_ = rows_ = std::max<std::size_t>(1, static_cast<std::size_t>(std::sqrt(static_cast<double>(n))));
    size_ = span / static_cast<double>(cols_) * (1 + 1e-12);
    buckets_.resize(cols_ * rows_);
    for (std::size_t i = 0; i < points.size(); ++i)
      if (used[i]) buckets_[bucket(points[i])].push_back(static_cast<std::uint32_t>(i));
  }

  std::uint32_t nearest(const Point2& p) const {
    const long pc = coordinate(p[0], 0), pr = coordinate(p[1], 1);
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t best_i = std::numeric_limits<std::uint32_t>::max();
    const long limit = static_cast<long>(std::max(cols_, rows_)) + std::max(std::abs(pc), std::abs(pr)) + 1;
    for (long ring = 0; ring <= limit; ++ring) {
      for (long r = pr - ring; r <= pr + ring; ++r)
        for (long c = pc - ring; c <= pc + ring; ++c) {
          if (std::max(std::abs(r - pr), std::abs(c - pc)) != ring) continue;
          if (r < 0 || c < 0 || r >= static_cast<long>(rows_) || c >= static_cast<long>(cols_)) continue;
          for (std::uint32_t i : buckets_[static_cast<std::size_t>(r) * cols_ + static_cast<std::size_t>(c)]) {
            const double dx = points_[i][0] - p[0], dy = points_[i][1] - p[1], d = dx * dx + dy * dy;
            if (d < best || (d == best && i < best_i)) best = d, best_i = i;
          }
        }
      // Every node outside the searched square lies farther than `ring` buckets from p's bucket.
      const double reach = static_cast<double>(ring) * size_;
      if (best_i != std::numeric_limits<std::uint32_t>::max() && reach * reach >= best) break;
    }
    return best_i;
  }

 private:
  long coordinate(double v, int k) const { return static_cast<long>(std::floor((v - lo_[k]) / size_)); }
  std::size_t bucket(const Point2& p) const {
    const auto c = static_cast<std::size_t>(std::clamp<long>(coordinate(p[0], 0), 0, static_cast<long>(cols_) - 1));
    const auto r = static_cast<std::size_t>(std::clamp<long>(coordinate(p[1], 1), 0, static_cast<long>(rows_) - 1));
    return r * cols_ + c;
  }
  std::span<const Point2> points_;
  Point2 lo_{};
  std::size_t cols_ = 1, rows_ = 1;
  double size_ = 1;
  std::vector<std::vector<std::uint32_t>> buckets_;
};

}  // namespace

std::vector<double> node_depths(const DemFrame& frame, std::span<const Point2> points,
                                std::span<const std::array<std::uint32_t, 3>> triangles, const DepthOptions& options) {
  const Dem& dem = frame.dem();
  std::vector<Point2> cell(points.size());
  std::vector<std::uint8_t> used(points.size(), triangles.empty() ? 1 : 0);
  for (const auto& t : triangles)
    for (auto i : t) used[i] = 1;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (used[i]) cell[i] = frame.to_cell(points[i]);

  std::vector<double> sum(points.size(), 0.0);
  std::vector<std::uint32_t> count(points.size(), 0);
  if (!triangles.empty()) {
    const NearestNode nearest(points, used);
    // A DEM cell centre belongs to the first triangle (in the given order) that contains it, so a centre on
    // a shared edge counts once.
    std::vector<std::uint8_t> taken(dem.heights.size(), 0);
    for (const auto& t : triangles) {
      const Point2 &a = cell[t[0]], &b = cell[t[1]], &c = cell[t[2]];
      const double det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
      if (det == 0) continue;
      const int c0 = std::max(0, static_cast<int>(std::ceil(std::min({a[0], b[0], c[0]}))));
      const int c1 = std::min(dem.width - 1, static_cast<int>(std::floor(std::max({a[0], b[0], c[0]}))));
      const int r0 = std::max(0, static_cast<int>(std::ceil(std::min({a[1], b[1], c[1]}))));
      const int r1 = std::min(dem.height - 1, static_cast<int>(std::floor(std::max({a[1], b[1], c[1]}))));
      for (int r = r0; r <= r1; ++r)
        for (int col = c0; col <= c1; ++col) {
          const std::size_t k = static_cast<std::size_t>(r) * dem.width + col;
          if (taken[k]) continue;
          // Barycentric coordinates in cell space, where the triangle is (to within its curvature) affine.
          const double l1 = ((col - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (r - a[1])) / det;
          const double l2 = ((b[0] - a[0]) * (r - a[1]) - (col - a[0]) * (b[1] - a[1])) / det;
          const double l0 = 1 - l1 - l2;
          if (l0 < 0 || l1 < 0 || l2 < 0) continue;
          taken[k] = 1;
          const Point2 &A = points[t[0]], &B = points[t[1]], &C = points[t[2]];
          const Point2 p{l0 * A[0] + l1 * B[0] + l2 * C[0], l0 * A[1] + l1 * B[1] + l2 * C[1]};
          const std::uint32_t n = nearest.nearest(p);
          sum[n] += dem.heights[k];
          ++count[n];
        }
    }
  }
  std::vector<double> depth(points.size(), 0.0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!used[i]) continue;
    double height = count[i] > 0 ? sum[i] / count[i] : dem.bilinear(cell[i][0], cell[i][1]);
    if (options.max_height) height = std::min(height, *options.max_height);
    depth[i] = 0.0 - height;  // not -0 at the shoreline
    if (options.min_depth) depth[i] = std::max(depth[i], *options.min_depth);
  }
  return depth;
}

}  // namespace shoremesh::io
