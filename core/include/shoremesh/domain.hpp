#pragma once
// The water domain of a 2D input: closed rings (a lake shore, its islands, ponds on islands).
#include <string>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh {

// What a ring bounds. Water is where a point lies inside an odd number of rings (even-odd rule): a shore
// ring encloses water, an island ring inside it encloses land, a pond ring inside an island water again.
enum class RingRole { Shore, Island };

struct Ring {
  std::vector<Point2> points;  // closed implicitly: the last point connects to the first (not repeated)
  RingRole role = RingRole::Shore;
};

struct Domain2 {
  std::vector<Ring> rings;
  bool empty() const { return rings.empty(); }
};

}  // namespace shoremesh
