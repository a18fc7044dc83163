#include "shoremesh/engine/rank_scale.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shoremesh::engine {

template <int D>
RankScale<D>::RankScale(const DerivedParameters<D>& p) : kappa_(p.kappa) {
  const double rho2 = p.rho_squared;
  log_rho2_ = std::log(rho2);
  // Squared distances in the box lie in (2^-100, D]: the quadtree refuses points closer than 2^-40, and
  // Steiner points are never closer than a constant fraction of the local feature size.
  min_rank_ = int(std::floor(std::log(0x1p-100) / log_rho2_));
  thresholds_.clear();
  double t = 1.0;
  // T_0 = 1, T_{r+1} = T_r * rho^2, T_{r-1} = T_r / rho^2: one canonical table for every decision.
  std::vector<double> down{1.0};
  for (int r = 0; r > min_rank_; --r) down.push_back(t /= rho2);
  for (auto it = down.rbegin(); it != down.rend(); ++it) thresholds_.push_back(*it);
  t = 1.0;
  int r = 0;
  while (t <= double(D)) {
    t *= rho2;
    ++r;
    thresholds_.push_back(t);
  }
  max_rank_ = r - 1;  // T_{max} <= D < T_{max+1}
  tile_sides_.resize(std::size_t(max_rank_ - min_rank_ + 1));
  for (int k = min_rank_; k <= max_rank_; ++k) tile_sides_[std::size_t(k - min_rank_)] = p.tile_side(k);
  colors_ = 1;
  for (int i = 0; i < D; ++i) colors_ *= std::uint32_t(kappa_);
}

template <int D>
int RankScale<D>::rank_of(const Point<D>& a, const Point<D>& b, PredicateCounters& counters) const {
  double d2 = 0;
  for (int i = 0; i < D; ++i) d2 += (a[i] - b[i]) * (a[i] - b[i]);
  int r = d2 > 0 ? int(std::floor(std::log(d2) / log_rho2_)) : min_rank_;
  r = std::clamp(r, min_rank_, max_rank_);
  // The guess is within one of the truth; settle it with exact comparisons against the table.
  while (r > min_rank_ && compare_squared_distance_to<D>(counters, a, b, threshold(r)) < 0) --r;
  while (r < max_rank_ && compare_squared_distance_to<D>(counters, a, b, threshold(r + 1)) >= 0) ++r;
  return r;
}

template <int D>
int RankScale<D>::rank_of_length(double length) const {
  const double l2 = length * length;  // exact for the powers of two it is called with
  int r = std::clamp(int(std::floor(std::log(l2) / log_rho2_)), min_rank_, max_rank_);
  while (r > min_rank_ && threshold(r) > l2) --r;
  while (r < max_rank_ && threshold(r + 1) <= l2) ++r;
  return r;
}

template <int D>
std::uint32_t RankScale<D>::color(const Point<D>& p, int rank) const {
  const double side = tile_sides_[std::size_t(rank - min_rank_)];
  std::uint32_t c = 0, scale = 1;
  for (int i = 0; i < D; ++i) {
    // fmod of a double by a small integer is exact: the tile index mod kappa, without overflow.
    const double tile = std::floor(p[i] / side);
    c += std::uint32_t(std::fmod(tile, double(kappa_))) * scale;
    scale *= std::uint32_t(kappa_);
  }
  return c + 1;
}

template class RankScale<2>;
template class RankScale<3>;

}  // namespace shoremesh::engine
