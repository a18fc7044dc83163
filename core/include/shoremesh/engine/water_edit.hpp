#pragma once
// A change of the water's edges in the engine's unit box (docs/water_only.md): what an edit of the rings
// took away and gave, as chains of ring vertices, so that the engine touches only the edges that changed.
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh::engine {

// The edges between consecutive points of `gone` went and those of `came` came; with `cyclic` each chain
// is a whole ring (its closing edge too; a chain of fewer than 3 points then bounds nothing and has no
// edge). An edit of a stretch of one ring is two open chains with the same two ends: the vertices kept
// on either side of the stretch, and between them its old and its new points.
struct WaterEdit {
  std::vector<Point2> gone, came;
  bool cyclic = false;
};

}  // namespace shoremesh::engine
