#pragma once
// Internal: duplicate detection by sorting (O(n log n)), shared by the point readers.
#include <algorithm>
#include <array>
#include <cstddef>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

namespace shoremesh::io::detail {

// Returns the first duplicate pair (in input order of the later point): {later index, earlier index}.
template <std::size_t D>
std::optional<std::pair<std::size_t, std::size_t>> find_duplicate(const std::vector<std::array<double, D>>& pts) {
  std::vector<std::size_t> order(pts.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  // Sort by coordinates, then by index: equal points end up adjacent, the earliest first.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (pts[a] != pts[b]) return pts[a] < pts[b];
    return a < b;
  });
  std::optional<std::pair<std::size_t, std::size_t>> best;
  for (std::size_t k = 1; k < order.size(); ++k) {
    const std::size_t prev = order[k - 1], cur = order[k];
    if (pts[prev] == pts[cur]) {
      // Find the first point of this run (the earliest occurrence).
      std::size_t first = k - 1;
      while (first > 0 && pts[order[first - 1]] == pts[cur]) --first;
      if (!best || cur < best->first) best = std::make_pair(cur, order[first]);
    }
  }
  return best;
}

}  // namespace shoremesh::io::detail
