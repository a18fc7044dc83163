// The water of a 2D domain for the engine's skip of fills on land (docs/water_only.md).
#include "shoremesh/engine/water.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

// The parity of points by cells of a 2^k x 2^k grid over the unit box, so that a point's parity is decided
// inside its cell instead of along a ray across the whole domain (at Lake Superior's 196,843 shore points
// the rays were a twentieth of the engine's time: each crossed many R-tree nodes and shore edges). Every
// cell keeps the parity of its centre and the edges that meet it (closed boxes): the segment from the
// centre to a point p of the cell crosses only those, each crossing decided exactly (orient2d), so p's
// parity is the centre's flipped once per crossing. Where that is not clear-cut (the segment through an
// edge's end point or along an edge, or the centre on an edge) the ray decides, as without the grid.
// The centres' parities come from one sweep of each row of centres: the ray rule of odd_crossings
// (leftward, half-open across the row's line), each edge flipping the centres right of its crossing.
// Edits (apply) drop the grid: an edge taken in or out may change the parity of cells far from it.
struct WaterGrid {
  static constexpr std::uint32_t kOdd = 1, kOnEdge = 2;  // a cell's flags; its edges' list index above them
  int bits = 0;                       // 2^bits cells per side; 0: no grid
  std::vector<std::uint32_t> cells;   // flags | (1 + list index) << 2, or flags alone for a cell no edge meets
  std::vector<std::uint32_t> first;   // list m: listed[first[m], first[m + 1])
  // The edges of each list, copied in place: a query reads its list in one run instead of through indices
  // (those reads were half of its time).
  std::vector<Edge> listed;

  bool empty() const { return bits == 0; }
  void clear() { *this = WaterGrid{}; }
  std::size_t side() const { return std::size_t(1) << bits; }
  double centre(std::size_t i) const { return (double(i) + 0.5) / double(side()); }
  // The cells whose closed extent along one axis meets [lo, hi] (scaling by 2^bits and floor, ceil: exact);
  // for a range beyond the unit box, the nearest border cell (which then holds every edge it meets: none).
  std::pair<std::size_t, std::size_t> meeting(double lo, double hi) const {
    const double g = double(side());
    const double from = std::clamp(std::ceil(lo * g) - 1, 0.0, g - 1), to = std::min(g - 1, std::floor(hi * g));
    return {std::size_t(from), std::size_t(std::max(from, to))};
  }
  void build(std::vector<Edge> all, PredicateCounters& pc);
  // p's parity, or -1 when the ray must decide.
  int parity(const Point2& p, PredicateCounters& pc) const;
  // Calls f(edge) once for every edge whose closed box meets the closed box [lo, hi] (the R-tree's set),
  // until f returns true; returns whether one did. Each edge is listed in every cell its box meets, so the
  // cells meeting [lo, hi] hold them all; an edge is taken only in the first of those cells (lowest row,
  // then column) that lists it, the corner of the two cell ranges. false, f not called: the box spans more
  // than kMostCells cells (the R-tree skips open water faster) or there is no grid.
  static constexpr std::size_t kMostCells = 16;
  template <class F>
  bool for_each_edge_meeting(const Point2& lo, const Point2& hi, bool& done, F&& f) const {
    done = false;
    if (empty()) return false;
    const auto [x0, x1] = meeting(lo[0], hi[0]);
    const auto [y0, y1] = meeting(lo[1], hi[1]);
    if ((x1 - x0 + 1) * (y1 - y0 + 1) > kMostCells) return false;
    done = true;
    const std::size_t g = side();
    for (std::size_t y = y0; y <= y1; ++y)
      for (std::size_t x = x0; x <= x1; ++x) {
        const std::uint32_t cell = cells[y * g + x];
        if ((cell >> 2) == 0) continue;
        const std::size_t m = (cell >> 2) - 1;
        for (std::uint32_t j = first[m]; j < first[m + 1]; ++j) {
          const Edge& e = listed[j];
          const double elo0 = std::min(e[0], e[2]), elo1 = std::min(e[1], e[3]);
          if (std::max(e[0], e[2]) < lo[0] || elo0 > hi[0] || std::max(e[1], e[3]) < lo[1] || elo1 > hi[1]) continue;
          if ((x != x0 && meeting(elo0, elo0).first != x) || (y != y0 && meeting(elo1, elo1).first != y)) continue;
          if (f(e)) return true;
        }
      }
    return false;
  }
};

struct WaterRings::Tree {
  bgi::rtree<Entry, bgi::quadratic<16>> tree;
  WaterGrid grid;
};

void WaterGrid::build(std::vector<Edge> all, PredicateCounters& pc) {
  clear();
  for (const Edge& e : all)
    for (double x : e)
      if (!(x >= 0 && x <= 1)) return;  // the rings lie in the unit box; else no grid
  // About four cells per edge: a cell on the shore holds a few tens of edges, and at most 4 MB of cells.
  bits = 4;
  while (bits < 10 && double(std::size_t(1) << (2 * bits)) < 4.0 * double(all.size())) ++bits;
  const std::size_t g = side();
  const std::vector<Edge> edges = std::move(all);
  // The cells each edge meets (its box's: a superset), counted, then listed in edge order.
  cells.assign(g * g, 0);
  std::vector<std::uint32_t> count(g * g, 0);
  auto for_each_cell = [&](const Edge& e, auto&& f) {
    const auto [x0, x1] = meeting(std::min(e[0], e[2]), std::max(e[0], e[2]));
    const auto [y0, y1] = meeting(std::min(e[1], e[3]), std::max(e[1], e[3]));
    for (std::size_t y = y0; y <= y1; ++y)
      for (std::size_t x = x0; x <= x1; ++x) f(y * g + x);
  };
  for (const Edge& e : edges) for_each_cell(e, [&](std::size_t c) { ++count[c]; });
  std::uint32_t lists = 0;
  for (std::size_t c = 0; c < g * g; ++c)
    if (count[c] != 0) cells[c] = (1 + lists++) << 2;
  first.assign(std::size_t(lists) + 1, 0);
  for (std::size_t c = 0; c < g * g; ++c)
    if (count[c] != 0) first[(cells[c] >> 2)] = count[c];
  for (std::size_t m = 1; m <= lists; ++m) first[m] += first[m - 1];
  listed.resize(first[lists]);
  std::vector<std::uint32_t>().swap(count);
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::size_t k = 0; k < edges.size(); ++k)
    for_each_cell(edges[k], [&](std::size_t c) { listed[fill[(cells[c] >> 2) - 1]++] = edges[k]; });
  // The centres' parities, row by row: an edge that crosses row y's line (half-open, as in odd_crossings)
  // crosses it left of the centres from some column on; flips[x] marks that column, and the prefix
  // parities along the row are the leftward rays' parities. A centre on a crossing edge is marked.
  std::vector<std::uint8_t> flips(g + 1);
  std::vector<std::vector<std::uint32_t>> crossing(g);
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Edge& e = edges[k];
    const auto [y0, y1] = meeting(std::min(e[1], e[3]), std::max(e[1], e[3]));
    for (std::size_t y = y0; y <= y1; ++y)
      if ((e[1] > centre(y)) != (e[3] > centre(y))) crossing[y].push_back(std::uint32_t(k));
  }
  for (std::size_t y = 0; y < g; ++y) {
    std::fill(flips.begin(), flips.end(), 0);
    const double cy = centre(y);
    for (std::uint32_t k : crossing[y]) {
      const Edge& e = edges[k];
      const Point2 a{e[0], e[1]}, b{e[2], e[3]};
      const bool up = b[1] > a[1];
      // -1: the crossing lies left of centre x (the leftward ray from it meets the edge), +1 right, 0 on it.
      auto where = [&](std::size_t x) {
        const int o = orient2d(pc, a, b, Point2{centre(x), cy});
        return o == 0 ? 0 : ((up ? o > 0 : o < 0) ? 1 : -1);
      };
      // The column of the crossing, near enough to walk from.
      const double t = (cy - a[1]) / (b[1] - a[1]);
      const double cx = a[0] + t * (b[0] - a[0]);
      std::size_t x = std::size_t(std::clamp(std::floor(cx * double(g)), 0.0, double(g - 1)));
      while (x > 0 && where(x - 1) <= 0) --x;
      while (x < g && where(x) > 0) ++x;
      // x: the first centre not right of the crossing.
      if (x < g && where(x) == 0) {
        cells[y * g + x] |= kOnEdge;
        ++x;
      }
      flips[x] ^= 1;
    }
    std::uint8_t odd = 0;
    for (std::size_t x = 0; x < g; ++x) {
      odd ^= flips[x];
      if (odd) cells[y * g + x] |= kOdd;
    }
  }
  // A centre on an edge that does not cross its row's line (along it, or ending on it).
  for (std::size_t c = 0; c < g * g; ++c) {
    if ((cells[c] >> 2) == 0) continue;
    const Point2 q{centre(c % g), centre(c / g)};
    const std::size_t m = (cells[c] >> 2) - 1;
    for (std::uint32_t j = first[m]; j < first[m + 1]; ++j)
      if (segment_meets_box(listed[j], q, q, pc)) cells[c] |= kOnEdge;
  }
}

int WaterGrid::parity(const Point2& p, PredicateCounters& pc) const {
  if (empty() || !(p[0] >= 0 && p[0] <= 1 && p[1] >= 0 && p[1] <= 1)) return -1;
  const std::size_t g = side();
  const std::size_t x = std::min(g - 1, std::size_t(p[0] * double(g))), y = std::min(g - 1, std::size_t(p[1] * double(g)));
  const std::uint32_t cell = cells[y * g + x];
  if (cell & kOnEdge) return -1;
  int odd = int(cell & kOdd);
  if ((cell >> 2) == 0) return odd;  // no edge meets the cell: all of it lies on the centre's side
  const Point2 c{centre(x), centre(y)};
  const double lo0 = std::min(c[0], p[0]), hi0 = std::max(c[0], p[0]), lo1 = std::min(c[1], p[1]), hi1 = std::max(c[1], p[1]);
  const std::size_t m = (cell >> 2) - 1;
  for (std::uint32_t j = first[m]; j < first[m + 1]; ++j) {
    const Edge& e = listed[j];
    if (std::max(e[0], e[2]) < lo0 || std::min(e[0], e[2]) > hi0 || std::max(e[1], e[3]) < lo1 || std::min(e[1], e[3]) > hi1)
      continue;
    const Point2 a{e[0], e[1]}, b{e[2], e[3]};
    // c and p lie on no edge: a zero here puts one of them on ab's line outside ab, which the segment then
    // meets only there.
    const int oc = orient2d(pc, a, b, c), op = orient2d(pc, a, b, p);
    if (oc == 0 && op == 0) return -1;  // along ab's line
    if (oc * op >= 0) continue;
    const int oa = orient2d(pc, c, p, a), ob = orient2d(pc, c, p, b);
    if (oa == 0 || ob == 0) return -1;  // through an end of ab
    if (oa != ob) odd ^= 1;
  }
  return odd;
}

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
  std::vector<Edge> edges;
  edges.reserve(all.size());
  for (const Entry& x : all) edges.push_back(x.second);
  std::vector<Entry>().swap(all);
  PredicateCounters pc;
  tree_->grid.build(std::move(edges), pc);
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
  tree_->grid.clear();
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
  if (const int odd = tree_->grid.parity(p, pc); odd >= 0) return odd == 1;
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
  bool done = false;
  if (tree_->grid.for_each_edge_meeting(lo, hi, done, [&](const Edge& e) { return segment_meets_box(e, lo, hi, pc); }))
    return true;
  if (done) return odd_crossings(inside, pc);
  const BBox box(Corner(lo[0], lo[1]), Corner(hi[0], hi[1]));
  for (auto it = tree_->tree.qbegin(bgi::intersects(box)); it != tree_->tree.qend(); ++it)
    if (segment_meets_box(it->second, lo, hi, pc)) return true;
  return odd_crossings(inside, pc);
}

// The edges come in the grid's or the R-tree's order, which an edit may change: the callers (shore_wedge)
// decide on the set alone.
void WaterRings::edges_meeting(const Point2& lo, const Point2& hi, PredicateCounters& pc,
                               std::vector<std::array<Point2, 2>>& out) const {
  bool done = false;
  tree_->grid.for_each_edge_meeting(lo, hi, done, [&](const Edge& e) {
    if (segment_meets_box(e, lo, hi, pc)) out.push_back({Point2{e[0], e[1]}, Point2{e[2], e[3]}});
    return false;
  });
  if (done) return;
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
