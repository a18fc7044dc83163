#pragma once
// Does a 2D mesh respect its domain? Every ring segment must be a chain of mesh edges; otherwise mesh edges
// cross the shoreline and elements straddle water and land. Where that happens the sampling along the shore
// is too coarse, and the report says where and by how much.
#include <cstddef>
#include <string>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/mesh_element.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

// A ring segment that is not a chain of mesh edges.
struct ShoreSegmentIssue {
  std::size_t ring = 0, segment = 0;  // segment i joins ring point i to point i+1 (cyclically)
  Point2 a{}, b{};
  // A segment end that is not a mesh point: the segment cannot be covered. depth is then the distance
  // from that end to the nearest mesh point.
  bool endpoint_missing = false;
  std::size_t crossing_edges = 0;     // mesh edges that the segment crosses
  // How far the mesh misses the shoreline here: over the crossing edges, the larger of (the distance of
  // the edge's nearer endpoint to the segment). Zero when the segment only lacks an edge between two
  // points that both lie on it.
  double depth = 0;
  std::vector<Element<2>> crossing_elements;  // kept (water) elements the segment passes through
};

struct ShorelineReport {
  std::size_t segments = 0;  // ring segments checked (zero-length ones skipped)
  std::size_t covered = 0;   // of those, chains of mesh edges
  std::vector<ShoreSegmentIssue> issues;
  double worst_depth = 0;
  bool ok() const { return issues.empty(); }
  std::string summary() const;
};

}  // namespace shoremesh
