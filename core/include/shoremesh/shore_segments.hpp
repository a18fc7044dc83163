#pragma once
// A segment of the refined shoreline (a ring edge's subsegment between split points), as the shore's
// refinement reports its changes and the mesh takes them as constraints: ends in lexicographic order, and
// whether a closed ring holds it (it bounds water) or a line (it bounds nothing).
#include <compare>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh {

struct ShoreSegment {
  Point2 a, b;  // a < b
  bool water = true;
  auto operator<=>(const ShoreSegment&) const = default;
};

// The refined shoreline's change: the segments that went and those that came (none in both). Their
// bounding water segments form closed chains (every end met an even number of times), so the water changes
// only inside each connected chain's bounding box.
struct ShoreChange {
  std::vector<ShoreSegment> removed, added;
  bool empty() const { return removed.empty() && added.empty(); }
};

}  // namespace shoremesh
