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
  // The edges that cross a ray from p, each decided exactly (half-open across the ray). p lies on no edge
  // (the callers found none meeting a box that holds it), so every ray gives the same parity: the one to
  // the nearest side of the edges' bounds crosses the fewest tree nodes.
  if (tree_->tree.empty()) return false;
  const BBox bounds = tree_->tree.bounds();
  const double gaps[4] = {bounds.max_corner().get<0>() - p[0], p[0] - bounds.min_corner().get<0>(),
                          bounds.max_corner().get<1>() - p[1], p[1] - bounds.min_corner().get<1>()};
  const int side = int(std::min_element(gaps, gaps + 4) - gaps);  // right, left, up, down
  const int along = side < 2 ? 0 : 1, across = 1 - along;       // the ray's axis and the other
  const bool forward = side % 2 == 0;
  Point2 far = p;
  far[along] = forward ? 2.0 : -1.0;  // past every edge: the rings lie in the unit box
  const BBox ray(Corner(std::min(p[0], far[0]), std::min(p[1], far[1])), Corner(std::max(p[0], far[0]), std::max(p[1], far[1])));
  bool odd = false;
  for (auto it = tree_->tree.qbegin(bgi::intersects(ray)); it != tree_->tree.qend(); ++it) {
    const Edge& e = it->second;
    const Point2 a{e[0], e[1]}, b{e[2], e[3]};
    if ((a[across] > p[across]) == (b[across] > p[across])) continue;
    // The edge crosses the line through p along the ray; o != 0 (p is on no edge). Along x, the crossing
    // is past p (rightward) when p lies left of the edge directed upward; along y, it is above p when p
    // lies right of the edge directed rightward.
    const int o = orient2d(pc, a, b, p);
    const bool up = b[across] > a[across];
    const bool ahead = along == 0 ? (up ? o > 0 : o < 0) : (up ? o < 0 : o > 0);
    if (ahead == forward) odd = !odd;
  }
  return odd;
}

bool WaterRings::may_meet_water(const Point2& inside, const Point2& lo, const Point2& hi, PredicateCounters& pc) const {
  const BBox box(Corner(lo[0], lo[1]), Corner(hi[0], hi[1]));
  for (auto it = tree_->tree.qbegin(bgi::intersects(box)); it != tree_->tree.qend(); ++it)
    if (segment_meets_box(it->second, lo, hi, pc)) return true;
  return odd_crossings(inside, pc);
}

void WaterRings::edges_meeting(const Point2& lo, const Point2& hi, PredicateCounters& pc,
                               std::vector<std::array<Point2, 2>>& out) const {
  const BBox box(Corner(lo[0], lo[1]), Corner(hi[0], hi[1]));
  for (auto it = tree_->tree.qbegin(bgi::intersects(box)); it != tree_->tree.qend(); ++it)
    if (segment_meets_box(it->second, lo, hi, pc)) {
      const Edge& e = it->second;
      out.push_back({Point2{e[0], e[1]}, Point2{e[2], e[3]}});
    }
}

bool WaterRings::in_closed_water(const Point2& p, PredicateCounters& pc) const {
  return may_meet_water(p, p, p, pc);
}

}  // namespace shoremesh::engine
