#pragma once
// Ranks and colours (paper, section 3). The rank of a distance d is floor(log_rho d), decided exactly as
// the largest r with T_r <= d^2 against a canonical table T_r = (rho^2)^r (powers of two for rho = sqrt 2,
// so exact). The colour of a vertex at rank r is its tile in a kappa^D periodic tiling of side l(r).
#include <span>
#include <vector>

#include "shoremesh/engine/predicates.hpp"
#include "shoremesh/parameters.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::engine {

template <int D>
class RankScale {
 public:
  explicit RankScale(const DerivedParameters<D>& p);

  int min_rank() const { return min_rank_; }
  int max_rank() const { return max_rank_; }  // floor(log_rho sqrt(D)): no two points of the box are farther
  // Exact rank of |a - b| (call under a RoundingGuard).
  int rank_of(const Point<D>& a, const Point<D>& b, PredicateCounters& counters) const;
  // Whether rank(|a - b|) < r, that is |a - b|^2 < T_r (exact).
  bool rank_below(const Point<D>& a, const Point<D>& b, int r, PredicateCounters& counters) const {
    return r > min_rank_ && compare_squared_distance_to<D>(counters, a, b, threshold(r)) < 0;
  }
  // Exact rank of a length whose square is exactly representable (quadtree sides, powers of two).
  int rank_of_length(double length) const;
  // Colour 1..kappa^D of vertex p at rank r (0 is reserved for dispatches).
  std::uint32_t color(const Point<D>& p, int rank) const;
  std::uint32_t color_count() const { return colors_; }

 private:
  double threshold(int r) const { return thresholds_[std::size_t(r - min_rank_)]; }
  int min_rank_ = 0, max_rank_ = 0;
  double log_rho2_ = 0;
  std::vector<double> thresholds_;  // T_r for r in [min_rank, max_rank + 1]
  std::vector<double> tile_sides_;  // l(r) for r in [min_rank, max_rank]
  int kappa_ = 0;
  std::uint32_t colors_ = 0;
};

}  // namespace shoremesh::engine
