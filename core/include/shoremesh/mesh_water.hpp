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

 private:
  struct Edge {
    Point2 a, b;
  };
  std::size_t slab_of(double y) const;

  std::vector<Edge> edges_;
  bool empty_ = true;
  double y_low_ = 0, slab_height_ = 1;
  std::vector<std::vector<std::uint32_t>> slabs_;  // edge indices whose y-range meets each slab
};

}  // namespace shoremesh
