// The water of a 2D domain for the engine's skip of fills on land (docs/water_only.md).
#include "shoremesh/engine/water.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <utility>

namespace shoremesh::engine {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {

using Corner = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox = bg::model::box<Corner>;
using Edge = std::array<double, 4>;  // a.x, a.y, b.x, b.y
using Entry = std::pair<BBox, Edge>;

// The closed box of segment ab: copies of the coordinates, so the tree's box tests are exact.
Entry entry(const Point2& a, const Point2& b) {
  return {BBox(Corner(std::min(a[0], b[0]), std::min(a[1], b[1])), Corner(std::max(a[0], b[0]), std::max(a[1], b[1]))),
          Edge{a[0], a[1], b[0], b[1]}};
}

// Whether segment ab meets the closed box [lo, hi]: their boxes overlap (the tree checked it) and the box's
// corners are not all strictly on one side of the line ab (separating axes: x, y and ab's normal).
bool segment_meets_box(const Edge& e, const Point2& lo, const Point2& hi, PredicateCounters& pc) {
  const Point2 a{e[0], e[1]}, b{e[2], e[3]};
  if (std::max(a[0], b[0]) < lo[0] || std::min(a[0], b[0]) > hi[0] || std::max(a[1], b[1]) < lo[1] ||
      std::min(a[1], b[1]) > hi[1])
    return false;
  int pos = 0, neg = 0;
  for (const Point2& c : {lo, Point2{hi[0], lo[1]}, hi, Point2{lo[0], hi[1]}}) {
    const int s = orient2d(pc, a, b, c);
    pos += s > 0;
    neg += s < 0;
  }
  return !(pos == 4 || neg == 4);
}

}  // namespace

struct WaterRings::Tree {
  bgi::rtree<Entry, bgi::quadratic<16>> tree;
};

WaterRings::WaterRings() : tree_(std::make_unique<Tree>()) {}
WaterRings::~WaterRings() = default;
WaterRings::WaterRings(WaterRings&&) noexcept = default;
WaterRings& WaterRings::operator=(WaterRings&&) noexcept = default;

std::size_t WaterRings::edge_count() const { return tree_->tree.size(); }

void WaterRings::assign(std::vector<std::vector<Point2>> rings) {
  std::vector<Entry> all;
  for (const auto& ring : rings)
    if (ring.size() >= 3)
      for (std::size_t k = 0; k < ring.size(); ++k) all.push_back(entry(ring[k], ring[(k + 1) % ring.size()]));
  tree_->tree = bgi::rtree<Entry, bgi::quadratic<16>>(all.begin(), all.end());  // packed
}

bool WaterRings::apply(const WaterEdit& edit, Point2& lo, Point2& hi) {
  auto grow = [&](const Point2& p) {
    for (int i = 0; i < 2; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  };
  // Edge k joins point k to k + 1; a ring's closing edge joins its last point to its first.
  auto for_each_edge = [&](const std::vector<Point2>& chain, auto&& f) {
    const std::size_t n = chain.size();
    if (edit.cyclic && n < 3) return;
    for (std::size_t k = 0; k + 1 < n; ++k) f(chain[k], chain[k + 1]);
    if (edit.cyclic) f(chain[n - 1], chain[0]);
  };
  bool changed = false;
  for_each_edge(edit.gone, [&](const Point2& p, const Point2& q) {
    tree_->tree.remove(entry(p, q));
    grow(p), grow(q);
    changed = true;
  });
  for_each_edge(edit.came, [&](const Point2& p, const Point2& q) {
    tree_->tree.insert(entry(p, q));
    grow(p), grow(q);
    changed = true;
  });
  return changed;
}

bool WaterRings::odd_crossings(const Point2& p, PredicateCounters& pc) const {
  // The edges that cross the rightward ray from p, each decided exactly (half-open in y).
  bool odd = false;
  const BBox ray(Corner(p[0], p[1]), Corner(2.0, p[1]));
  for (auto it = tree_->tree.qbegin(bgi::intersects(ray)); it != tree_->tree.qend(); ++it) {
    const Edge& e = it->second;
    const Point2 a{e[0], e[1]}, b{e[2], e[3]};
    if ((a[1] > p[1]) == (b[1] > p[1])) continue;
    const int o = orient2d(pc, a, b, p);
    if (b[1] > a[1] ? o > 0 : o < 0) odd = !odd;
  }
  return odd;
}

bool WaterRings::may_meet_water(const Point2& inside, const Point2& lo, const Point2& hi, PredicateCounters& pc) const {
  const BBox box(Corner(lo[0], lo[1]), Corner(hi[0], hi[1]));
  for (auto it = tree_->tree.qbegin(bgi::intersects(box)); it != tree_->tree.qend(); ++it)
    if (segment_meets_box(it->second, lo, hi, pc)) return true;
  return odd_crossings(inside, pc);
}

bool WaterRings::in_closed_water(const Point2& p, PredicateCounters& pc) const {
  return may_meet_water(p, p, p, pc);
}

}  // namespace shoremesh::engine
