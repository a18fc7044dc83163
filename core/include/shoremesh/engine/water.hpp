#pragma once
// The water of a 2D domain in the engine's unit box: the closed rings' edges in an R-tree, the water their
// even-odd interior. StableWS skips the fill of a vertex whose cell cannot meet the closed water
// (docs/water_only.md): every decision here is exact (the engine's orient2d) on the stored coordinates.
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "shoremesh/engine/predicates.hpp"
#include "shoremesh/engine/water_edit.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::engine {

class WaterRings {
 public:
  WaterRings();
  ~WaterRings();
  WaterRings(WaterRings&&) noexcept;
  WaterRings& operator=(WaterRings&&) noexcept;

  // All rings at once (ring r's points; empty for a line, a removed ring or fewer than 3 points).
  void assign(std::vector<std::vector<Point2>> rings);
  // Takes the edges `edit` names out and in: O(log n) each, nothing else is walked (the tree holds edges,
  // not rings). Returns whether any edge changed; when one did, [lo, hi] grows to hold every edge it took
  // out or in, and with them the only places whose parity changed (the region between the old and the new
  // edges).
  bool apply(const WaterEdit& edit, Point2& lo, Point2& hi);

  // Whether the closed box [lo, hi] may meet the closed water: some edge meets it, or, when none does,
  // `inside` (a point of the box) lies in the water (then the whole box does: no edge separates them).
  bool may_meet_water(const Point2& inside, const Point2& lo, const Point2& hi, PredicateCounters& pc) const;
  // The edges (a, b), in ring order, that meet the closed box [lo, hi] (exact), appended to `out`.
  void edges_meeting(const Point2& lo, const Point2& hi, PredicateCounters& pc,
                     std::vector<std::array<Point2, 2>>& out) const;
  // Whether p lies in the closed water (on an edge counts).
  bool in_closed_water(const Point2& p, PredicateCounters& pc) const;
  std::size_t edge_count() const;

 private:
  bool odd_crossings(const Point2& p, PredicateCounters& pc) const;
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace shoremesh::engine
