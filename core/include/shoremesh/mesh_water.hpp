#pragma once
// Point-in-water for a 2D domain: the even-odd rule over all rings, decided with exact orientation tests
// (a ray crossing count where every "is the edge right of the point" is an exact predicate), so that points
// a hair from a projected coastline are classified right. Edges are bucketed in horizontal slabs so that a
// query tests only the edges that span its height.
#include <cstddef>
#include <cstdint>
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
  // Ring r (a new one past the last, or an existing one) becomes `after` (empty: it went), in
  // O(its edges + the slabs they span).
  void replace_ring(std::size_t r, const std::vector<Point2>& after);

 private:
  struct Edge {
    Point2 a, b;
  };
  static constexpr std::uint32_t kNoEdge = 0xffffffffu;
  std::size_t slab_of(double y) const;
  void add_to_slabs(std::uint32_t e);
  std::uint32_t add_edge(const Point2& a, const Point2& b);  // a free slot (or a new one), in its slabs
  void remove_from_slabs(std::uint32_t e);

  std::vector<Edge> edges_;  // with the edges replaced since the build (no slab lists them)
  std::vector<std::vector<std::uint32_t>> ring_edges_;  // per ring: edge k, from vertex k to k + 1
  std::vector<std::uint32_t> free_edges_;               // replaced edges, to reuse
  bool empty_ = true;
  double y_low_ = 0, slab_height_ = 1;
  std::vector<std::vector<std::uint32_t>> slabs_;  // edge indices whose y-range meets each slab
};

}  // namespace shoremesh
