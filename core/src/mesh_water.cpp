#include "shoremesh/mesh_water.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include "ring_geometry.hpp"

namespace shoremesh {

namespace {
std::pair<Point2, Point2> key_of(const Point2& a, const Point2& b) { return a < b ? std::pair{a, b} : std::pair{b, a}; }
}  // namespace

std::size_t WaterTest::EdgeKeyHash::operator()(const std::pair<Point2, Point2>& e) const {
  std::size_t h = 0;
  for (const Point2* p : {&e.first, &e.second})
    for (double x : *p) h = h * 0x9E3779B97F4A7C15ull + std::hash<std::uint64_t>{}(std::bit_cast<std::uint64_t>(x + 0.0));
  return h;
}

WaterTest::WaterTest(const Domain2& domain) {
  double y_high = 0;
  for (const Ring& ring : domain.rings) {
    if (!ring.closed()) continue;  // a line bounds no water
    const std::size_t n = ring.points.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point2& a = ring.points[i];
      const Point2& b = ring.points[(i + 1) % n];
      if (empty_) {
        y_low_ = y_high = a[1];
        empty_ = false;
      }
      y_low_ = std::min({y_low_, a[1], b[1]});
      y_high = std::max({y_high, a[1], b[1]});
      // A degenerate edge (a == b) is kept: it crosses no ray, and a point on it is on the ring.
      edges_.push_back({a, b});
    }
  }
  if (empty_) return;
  // About four edges per slab on average; the slab index is only a filter, every decision stays exact.
  const std::size_t slab_count = std::max<std::size_t>(1, edges_.size() / 4);
  slab_height_ = (y_high - y_low_) / static_cast<double>(slab_count);
  if (!(slab_height_ > 0)) slab_height_ = 1;
  slabs_.resize(slab_count);
  for (std::uint32_t e = 0; e < edges_.size(); ++e) add_to_slabs(e);
}

void WaterTest::add_to_slabs(std::uint32_t e) {
  const auto [lo, hi] = std::minmax(edges_[e].a[1], edges_[e].b[1]);
  for (std::size_t s = slab_of(lo); s <= slab_of(hi); ++s) slabs_[s].push_back(e);
}

void WaterTest::remove_from_slabs(std::uint32_t e) {
  const auto [lo, hi] = std::minmax(edges_[e].a[1], edges_[e].b[1]);
  for (std::size_t s = slab_of(lo); s <= slab_of(hi); ++s) {
    auto& slab = slabs_[s];
    slab.erase(std::find(slab.begin(), slab.end(), e));
  }
}

// Only an edit names edges: a mesh built once never needs the index, so it is made at the first edit.
void WaterTest::index_slots() {
  if (slots_indexed_) return;
  slots_indexed_ = true;
  slot_of_.reserve(edges_.size());
  for (std::uint32_t e = 0; e < edges_.size(); ++e) slot_of_.emplace(key_of(edges_[e].a, edges_[e].b), e);
}

void WaterTest::remove_edge(const Point2& a, const Point2& b) {
  index_slots();
  const auto it = slot_of_.find(key_of(a, b));
  if (it == slot_of_.end()) throw std::logic_error("water test: a removed edge is not there");
  remove_from_slabs(it->second);
  free_edges_.push_back(it->second);
  slot_of_.erase(it);
}

void WaterTest::add_edge(const Point2& a, const Point2& b) {
  index_slots();
  if (empty_) {  // no slab yet: one, which every edge joins (slab_of clamps)
    empty_ = false;
    y_low_ = a[1];
    slab_height_ = 1;
    slabs_.assign(1, {});
  }
  std::uint32_t e;
  if (free_edges_.empty()) {
    e = static_cast<std::uint32_t>(edges_.size());
    edges_.push_back({});
  } else {
    e = free_edges_.back();
    free_edges_.pop_back();
  }
  edges_[e] = {a, b};
  slot_of_.emplace(key_of(a, b), e);
  add_to_slabs(e);
}

// Edge k of a ring of n vertices touches the changed vertices [prefix, n - suffix) iff it lies in the
// cyclic run of edges from prefix - 1 to n - suffix - 1: those are replaced, the others stay.
void WaterTest::replace_stretch(std::size_t, const std::vector<Point2>& before, const std::vector<Point2>& after,
                                std::size_t prefix, std::size_t suffix) {
  // The run of edges touching the changed vertices, in a ring of `size` vertices (the run wraps when
  // prefix is 0): visited in O(run), not O(ring).
  auto for_each_changed = [&](std::size_t size, auto&& visit) {
    if (prefix == 0) {
      visit(size - 1);
      for (std::size_t k = 0; k + suffix + 1 <= size && k + 1 < size; ++k) visit(k);
    } else {
      for (std::size_t k = prefix - 1; k + suffix + 1 <= size; ++k) visit(k);
    }
  };
  const std::size_t m = before.size(), n = after.size();
  for_each_changed(m, [&](std::size_t k) { remove_edge(before[k], before[(k + 1) % m]); });
  for_each_changed(n, [&](std::size_t k) { add_edge(after[k], after[(k + 1) % n]); });
}

void WaterTest::replace_ring(const std::vector<Point2>& before, const std::vector<Point2>& after) {
  for (std::size_t k = 0; k < before.size(); ++k) remove_edge(before[k], before[(k + 1) % before.size()]);
  for (std::size_t k = 0; k < after.size(); ++k) add_edge(after[k], after[(k + 1) % after.size()]);
}

// Monotone in y, so an edge spanning [lo, hi] is found from any query height inside that range.
std::size_t WaterTest::slab_of(double y) const {
  const double s = std::floor((y - y_low_) / slab_height_);
  if (!(s > 0)) return 0;
  return std::min(static_cast<std::size_t>(s), slabs_.size() - 1);
}

WaterSide WaterTest::classify(const Point2& p) const {
  if (empty_) return WaterSide::Water;
  bool inside = false;
  for (std::uint32_t e : slabs_[slab_of(p[1])]) {
    const Point2& a = edges_[e].a;
    const Point2& b = edges_[e].b;
    // Half-open rule on y (exact comparisons): a vertex at the ray's height is counted once.
    const bool a_above = a[1] > p[1];
    const bool b_above = b[1] > p[1];
    if (a_above == b_above) {
      // A horizontal edge at the point's height: the point may lie on it.
      if (a[1] == p[1] && b[1] == p[1] && std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]))
        return WaterSide::OnRing;
      continue;
    }
    // An edge wholly left or right of the point at its height is decided by comparisons: the crossing
    // lies left of p (no crossing on the ray) or right of it (a crossing), and p is not on the edge.
    if (std::max(a[0], b[0]) < p[0]) continue;
    if (std::min(a[0], b[0]) > p[0]) {
      inside = !inside;
      continue;
    }
    const int o = detail::orient(a, b, p);
    if (o == 0) return WaterSide::OnRing;
    // The edge crosses the rightward ray from p iff p is left of an upward edge or right of a downward one.
    if ((b_above && o > 0) || (a_above && o < 0)) inside = !inside;
  }
  return inside ? WaterSide::Water : WaterSide::Land;
}

}  // namespace shoremesh
