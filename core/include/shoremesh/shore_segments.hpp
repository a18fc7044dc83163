#pragma once
// A segment of the refined shoreline (a ring edge's subsegment between split points), as the shore's
// refinement reports its changes and the mesh takes them as constraints: ends in lexicographic order, and
// whether a closed ring holds it (it bounds water) or a line (it bounds nothing).
#include <compare>
#include <cstddef>
#include <unordered_map>
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

// The connected chains of n segments joined through their common ends (union-find over the ends): each
// segment's chain, chains numbered 0, 1, ... in the order of their first segment. `ends(i)` gives segment
// i's two end points. Where a shore change's water bounds change: each chain's bounding box.
template <class Ends>
std::vector<std::size_t> segment_chains(std::size_t n, Ends&& ends) {
  std::unordered_map<Point2, std::size_t, PointHash<2>> end_id;
  std::vector<std::size_t> parent;
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  auto id = [&](const Point2& p) {
    const auto [it, fresh] = end_id.emplace(p, parent.size());
    if (fresh) parent.push_back(parent.size());
    return it->second;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const auto& [a, b] = ends(i);
    const std::size_t x = find(id(a)), y = find(id(b));
    parent[x] = y;
  }
  std::vector<std::size_t> chain(n);
  std::unordered_map<std::size_t, std::size_t> number;
  for (std::size_t i = 0; i < n; ++i)
    chain[i] = number.emplace(find(end_id.at(ends(i).first)), number.size()).first->second;
  return chain;
}

}  // namespace shoremesh
