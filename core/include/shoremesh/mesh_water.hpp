#pragma once
// Point-in-water for a 2D domain: the even-odd rule over all rings, decided with exact orientation tests
// (a ray crossing count where every "is the edge right of the point" is an exact predicate), so that points
// a hair from a projected coastline are classified right. Edges are bucketed in horizontal slabs so that a
// query tests only the edges that span its height.
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

enum class WaterSide : std::uint8_t { Water, Land, OnRing };

class WaterTest {
 public:
  explicit WaterTest(const Domain2& domain);
  // Without rings everything is water.
  WaterSide classify(const Point2& p) const;
  bool in_water(const Point2& p) const { return classify(p) == WaterSide::Water; }

  // Ring r changed from `before` to `after` between a common prefix and a common suffix of vertices
  // (prefix + suffix <= both sizes): only the edges touching the changed stretch are replaced, in
  // O(stretch + the slabs they span), so that a shore edit does not rebuild the test. The test then
  // answers as WaterTest(new domain) does.
  void replace_stretch(std::size_t r, const std::vector<Point2>& before, const std::vector<Point2>& after,
                       std::size_t prefix, std::size_t suffix);
  // A closed ring's points change from `before` to `after` (either empty: the ring came or went), in
  // O(its edges + the slabs they span).
  void replace_ring(const std::vector<Point2>& before, const std::vector<Point2>& after);
  // One edge of a closed ring goes or comes (the even-odd rule needs only the set of edges, not which ring
  // holds them): what a shore edit changes, segment by segment (Mesh::apply with a ShoreChange).
  void remove_edge(const Point2& a, const Point2& b);
  void add_edge(const Point2& a, const Point2& b);

 private:
  struct Edge {
    Point2 a, b;
  };
  struct EdgeKeyHash {
    std::size_t operator()(const std::pair<Point2, Point2>& e) const;
  };
  std::size_t slab_of(double y) const;
  void add_to_slabs(std::uint32_t e);
  void remove_from_slabs(std::uint32_t e);
  void index_slots();

  std::vector<Edge> edges_;  // with free slots (no slab lists them)
  // Each edge's slot by its ends in lexicographic order: a removal names the edge, not its place (made at
  // the first edit: index_slots).
  std::unordered_multimap<std::pair<Point2, Point2>, std::uint32_t, EdgeKeyHash> slot_of_;
  bool slots_indexed_ = false;
  std::vector<std::uint32_t> free_edges_;  // slots of removed edges, to reuse
  bool empty_ = true;
  double y_low_ = 0, slab_height_ = 1;
  std::vector<std::vector<std::uint32_t>> slabs_;  // edge indices whose y-range meets each slab
};

}  // namespace shoremesh
