#pragma once
// Internal: assembling an InputSet (sources, points with origins, rings stored contiguously in points).
#include <string>
#include <vector>

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
  void add_ring(std::vector<Point2> pts, RingRole role, const std::vector<std::size_t>& locations = {}) {
    const auto r = static_cast<std::uint32_t>(set_.domain.rings.size());
    set_.ring_offsets.push_back(set_.points.size());
    for (std::size_t k = 0; k < pts.size(); ++k) add_point(pts[k], locations.empty() ? 0 : locations[k], r);
    set_.domain.rings.push_back({std::move(pts), role});
  }

 private:
  InputSet& set_;
  std::uint32_t source_ = 0;
};

}  // namespace shoremesh::io::detail
