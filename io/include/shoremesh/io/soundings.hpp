#pragma once
// Soundings: scattered x, y, depth points (a 3-column point file meshed in 2D) as the depth source of a
// mesh. A node at a sounding takes its depth exactly; any other node (a Steiner point) the linear
// interpolation over the Delaunay triangle of soundings that contains it, or the nearest sounding's depth
// outside their convex hull.
#include <memory>
#include <span>
#include <vector>

#include "shoremesh/io/dem.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::io {

class Soundings {
 public:
  // Points and depths (positive down) in the mesh's coordinates; at least one, pairwise distinct.
  Soundings(std::vector<Point2> points, std::vector<double> depths);
  ~Soundings();
  std::size_t size() const { return size_; }
  double depth_at(const Point2& p) const;

 private:
  struct Triangulation;
  std::unique_ptr<Triangulation> t_;
  std::size_t size_ = 0;
};

// Depths at `points` (then clamped by `options`).
std::vector<double> sounding_depths(const Soundings& soundings, std::span<const Point2> points,
                                    const DepthOptions& options = {});

}  // namespace shoremesh::io
