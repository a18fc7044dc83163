#pragma once
// Values by 2D point for a set of points known up front, as a sorted array searched by halving: looked
// up many times (once per mesh vertex or element corner) without a node-based map's allocation per point.
#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh {

template <class V>
class PointTable {
 public:
  // Call add for each point, then seal; a point added twice is kept once, with the first value added.
  void add(const Point2& p, const V& value = V()) { slots_.push_back({p, value}); }
  void seal() {
    std::stable_sort(slots_.begin(), slots_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    slots_.erase(std::unique(slots_.begin(), slots_.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
                 slots_.end());
  }
  bool empty() const { return slots_.empty(); }
  V* find(const Point2& p) {
    const auto it = slot(p);
    return it != slots_.end() && it->first == p ? &slots_[std::size_t(it - slots_.cbegin())].second : nullptr;
  }
  const V& at(const Point2& p) const {
    const auto it = slot(p);
    if (it == slots_.end() || it->first != p) throw std::out_of_range("PointTable::at: no such point");
    return it->second;
  }

 private:
  typename std::vector<std::pair<Point2, V>>::const_iterator slot(const Point2& p) const {
    return std::lower_bound(slots_.cbegin(), slots_.cend(), p, [](const auto& s, const Point2& q) { return s.first < q; });
  }
  std::vector<std::pair<Point2, V>> slots_;
};

}  // namespace shoremesh
