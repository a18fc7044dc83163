#pragma once
// What the engine's source files (engine*.cpp, cell_cache.cpp) share privately.
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace shoremesh::engine_detail {

inline constexpr int kBeforeEverything = std::numeric_limits<int>::min();

// The float nearest above x: a dependency radius stored in half the space, never smaller.
inline float at_least(double x) {
  float f = float(x);
  if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// Relative margins on computed squared distances, so that rounding only ever errs on the side of
// more work (a larger box, a rerun), never of a wrong answer.
inline constexpr double kRadiusMargin = 1e-6;    // dependency radii (depends2) and their boxes
inline constexpr double kReachMargin = 1e-9;     // what can still cut a cell, and the boxes searched
inline constexpr double kNearestTie = 1e-12;     // nearest-neighbour distances this close are decided exactly
inline constexpr double kLandMargin = 1e-6;      // the cell box a fill tests against the shore (fill_on_land)

// Moves item o of items to new_id[o], cycle by cycle (a copy would double the memory of the largest
// arrays of the engine).
template <class T>
void permute_in_place(std::vector<T>& items, const std::vector<std::uint32_t>& new_id) {
  std::vector<bool> placed(items.size(), false);
  for (std::uint32_t start = 0; start < items.size(); ++start) {
    if (placed[start]) continue;
    T carried = items[start];
    for (std::uint32_t from = start;;) {
      const std::uint32_t to = new_id[from];
      placed[to] = true;
      std::swap(carried, items[to]);
      if (to == start) break;
      from = to;
    }
  }
}

}  // namespace shoremesh::engine_detail
