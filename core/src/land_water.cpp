// Land and water in one mesh (`shoremesh mesh --dem FILE --land-up-to Z`, docs/terrain.md): the shoreline's
// pieces kept as constraint lines inside the domain below Z, and the counts the summary gives.
#include "shoremesh/land_water.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <deque>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>

#include "shoremesh/mesh_water.hpp"

namespace shoremesh {

namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BSegment = bg::model::segment<BPoint>;
using BBox = bg::model::box<BPoint>;

BPoint bp(const Point2& p) { return BPoint(p[0], p[1]); }

}  // namespace

// The shoreline's pieces that lie clear of the domain's rings: a vertex at least `clearance` from every
// ring segment, a segment at least half of it. Where the land between the shoreline and Z is narrower
// than that (a cliff at the DEM's resolution), the domain's ring is the shoreline there, and the piece is
// left out. A closed piece becomes two lines sharing their ends (the domain accepts shared vertices).

std::function<bool(const Point2&)> contour_cut(const HeightGrid& grid, int every) {
  const double x0 = grid.x0, y0 = grid.y0, dx = grid.dx, dy = grid.dy;
  const long m = std::max(1, every);
  return [=](const Point2& p) {
    // A vertex is (col, row + 1/2) on a horizontal cell edge, (col + 1/2, row) on a vertical one.
    const double c = (p[0] - x0) / dx, r = (p[1] - y0) / dy;
    const double rc = std::round(c), rr = std::round(r);
    const long line = std::abs(c - rc) < 0.25 ? static_cast<long>(rc) : static_cast<long>(rr);
    return line % m == 0;
  };
}

ShoreLines shoreline_lines(const Domain2& shore, const Domain2& domain, double clearance,
                           const std::function<bool(const Point2&)>& cut) {
  std::vector<std::pair<BBox, std::size_t>> boxes;
  std::vector<BSegment> segments;
  for (const Ring& r : domain.rings)
    for (std::size_t k = 0; k < r.segment_count(); ++k) {
      const BSegment s(bp(r.points[k]), bp(r.points[(k + 1) % r.points.size()]));
      BBox b;
      bg::envelope(s, b);
      boxes.push_back({b, segments.size()});
      segments.push_back(s);
    }
  const bgi::rtree<std::pair<BBox, std::size_t>, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
  auto nearest_within = [&](const auto& geometry, double d) {
    BBox b;
    bg::envelope(geometry, b);
    const BBox grown(BPoint(b.min_corner().get<0>() - d, b.min_corner().get<1>() - d),
                     BPoint(b.max_corner().get<0>() + d, b.max_corner().get<1>() + d));
    double best = std::numeric_limits<double>::infinity();
    for (auto it = tree.qbegin(bgi::intersects(grown)); it != tree.qend(); ++it)
      best = std::min(best, static_cast<double>(bg::distance(geometry, segments[it->second])));
    return best;
  };
  ShoreLines out;
  for (const Ring& r : shore.rings) {
    const std::size_t n = r.points.size();
    if (n < 3) continue;
    std::vector<char> vertex_clear(n), segment_clear(n);
    for (std::size_t k = 0; k < n; ++k) vertex_clear[k] = nearest_within(bp(r.points[k]), clearance) >= clearance;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t j = (k + 1) % n;
      segment_clear[k] = vertex_clear[k] && vertex_clear[j] &&
                         nearest_within(BSegment(bp(r.points[k]), bp(r.points[j])), clearance) >= 0.5 * clearance;
      out.dropped_segments += !segment_clear[k];
    }
    std::vector<char> cut_at(n, 0);
    std::size_t cuts = 0;
    if (cut)
      for (std::size_t k = 0; k < n; ++k) cuts += cut_at[k] = cut(r.points[k]);
    const auto first_gap = std::find(segment_clear.begin(), segment_clear.end(), 0);
    if (first_gap == segment_clear.end() && cuts >= 2) {
      // Closed and clear: a line from each cut vertex to the next.
      const std::size_t first = static_cast<std::size_t>(std::find(cut_at.begin(), cut_at.end(), 1) - cut_at.begin());
      Ring line{{r.points[first]}, RingRole::Line};
      for (std::size_t i = 1; i <= n; ++i) {
        const std::size_t k = (first + i) % n;
        line.points.push_back(r.points[k]);
        if (cut_at[k]) {
          out.segments += line.points.size() - 1;
          out.lines.push_back(line);
          line.points = {r.points[k]};
        }
      }
      continue;
    }
    if (first_gap == segment_clear.end()) {
      // Closed and clear: two lines, 0 .. n/2 and n/2 .. n (= 0).
      Ring a{{}, RingRole::Line}, b{{}, RingRole::Line};
      for (std::size_t k = 0; k <= n / 2; ++k) a.points.push_back(r.points[k]);
      for (std::size_t k = n / 2; k <= n; ++k) b.points.push_back(r.points[k % n]);
      out.segments += n;
      out.lines.push_back(std::move(a));
      out.lines.push_back(std::move(b));
      continue;
    }
    // Runs of clear segments, starting after a gap so that none wraps. A run goes on into the segments
    // beside it as far as the clearance holds (bisection), so that it stops about `clearance` from the
    // domain's ring rather than a whole segment before.
    auto clip = [&](const Point2& v, const Point2& w) -> std::optional<Point2> {
      auto at = [&](double t) { return Point2{v[0] + t * (w[0] - v[0]), v[1] + t * (w[1] - v[1])}; };
      auto ok = [&](double t) {
        const Point2 p = at(t);
        return nearest_within(bp(p), clearance) >= clearance &&
               nearest_within(BSegment(bp(v), bp(p)), clearance) >= 0.5 * clearance;
      };
      double lo = 0, hi = 1;
      for (int i = 0; i < 30; ++i) {
        const double mid = 0.5 * (lo + hi);
        (ok(mid) ? lo : hi) = mid;
      }
      if (lo * std::hypot(w[0] - v[0], w[1] - v[1]) < 0.1 * clearance) return std::nullopt;
      return at(lo);
    };
    const std::size_t start = static_cast<std::size_t>(first_gap - segment_clear.begin());
    Ring line{{}, RingRole::Line};
    auto flush = [&] {
      if (line.points.size() >= 2) out.segments += line.points.size() - 1, out.lines.push_back(line);
      line.points.clear();
    };
    for (std::size_t i = 1; i <= n; ++i) {
      const std::size_t k = (start + i) % n, next = (k + 1) % n, previous = (k + n - 1) % n;
      if (!segment_clear[k]) {
        if (!line.points.empty())
          if (const auto p = clip(r.points[k], r.points[next])) line.points.push_back(*p);
        flush();
        continue;
      }
      if (line.points.empty()) {
        if (!segment_clear[previous])
          if (const auto p = clip(r.points[k], r.points[previous])) line.points.push_back(*p);
        line.points.push_back(r.points[k]);
      }
      line.points.push_back(r.points[next]);
      if (cut_at[next] && segment_clear[next]) {  // the run goes on: a new line from here
        flush();
        line.points.push_back(r.points[next]);
      }
    }
    flush();
  }
  return out;
}


// ---- Local contours (land_water.hpp) ----

namespace {

constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);

// Cell-edge directions: right, down, left, up in (col, row); the next direction (d + 1) % 4 turns toward
// the water, which lies on the same side of every edge.
constexpr int kDx[4] = {1, 0, -1, 0}, kDy[4] = {0, 1, 0, -1};

struct Loop {
  std::vector<std::array<int, 2>> mid;  // doubled lattice midpoints (X, Y) = (2 i + dx, 2 j + dy) of corner (i, j)
  std::vector<char> keep;
  long long twice_area = 0;             // of the corner loop, in cells x 2; > 0: water inside
  int water = -1, land = -1;            // component labels either side of the first edge
};

}  // namespace

Domain2 TracedContours::domain() const {
  Domain2 d;
  for (const ContourRing& r : rings) d.rings.push_back(r.ring);
  return d;
}

TracedContours trace_contours(const HeightGrid& grid, const ContourOptions& o) {
  TracedContours out;
  const int W = grid.width, H = grid.height;
  const int stride = std::max(1, o.stride);
  std::size_t below = 0;
  for (float z : grid.z) below += z < o.level;
  out.none_below = below == 0;
  out.all_below = below == grid.z.size();
  if (out.none_below) return out;
  // Water on a grid framed by one cell of land (index (c + 1, r + 1)).
  const int PW = W + 2, PH = H + 2;
  std::vector<char> wet(static_cast<std::size_t>(PW) * PH, 0);
  auto at = [&](int c, int r) { return static_cast<std::size_t>(r + 1) * PW + static_cast<std::size_t>(c + 1); };
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c) wet[at(c, r)] = grid.at(c, r) < o.level;
  // Components: water 4-connected, land 8-connected (the frame is land: label 0 is the frame's).
  std::vector<int> label(wet.size(), -1);
  {
    int next = 0;
    std::vector<std::size_t> stack;
    for (std::size_t s = 0; s < wet.size(); ++s) {
      if (label[s] >= 0) continue;
      const char kind = wet[s];
      label[s] = next;
      stack.push_back(s);
      while (!stack.empty()) {
        const std::size_t v = stack.back();
        stack.pop_back();
        const int vc = static_cast<int>(v % PW), vr = static_cast<int>(v / PW);
        for (int dr = -1; dr <= 1; ++dr)
          for (int dc = -1; dc <= 1; ++dc) {
            if ((dr == 0 && dc == 0) || (kind && dr != 0 && dc != 0)) continue;
            const int nc = vc + dc, nr = vr + dr;
            if (nc < 0 || nr < 0 || nc >= PW || nr >= PH) continue;
            const std::size_t u = static_cast<std::size_t>(nr) * PW + nc;
            if (label[u] < 0 && wet[u] == kind) label[u] = next, stack.push_back(u);
          }
      }
      ++next;
    }
  }
  // Boundary edges, water on one side: per corner (i, j) of the cells, i in [0, W], j in [0, H] (corner (i, j)
  // is the upper-left one of cell (i, j)), the directions leaving it.
  const int CW = W + 1;
  std::vector<std::uint8_t> out_dirs(static_cast<std::size_t>(CW) * (H + 1), 0);
  auto corner = [&](int i, int j) { return static_cast<std::size_t>(j) * CW + static_cast<std::size_t>(i); };
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c) {
      if (!wet[at(c, r)]) continue;
      if (!wet[at(c, r - 1)]) out_dirs[corner(c, r)] |= 1;              // top: (c, r) -> (c + 1, r)
      if (!wet[at(c + 1, r)]) out_dirs[corner(c + 1, r)] |= 2;          // right: (c + 1, r) -> (c + 1, r + 1)
      if (!wet[at(c, r + 1)]) out_dirs[corner(c + 1, r + 1)] |= 4;      // bottom: (c + 1, r + 1) -> (c, r + 1)
      if (!wet[at(c - 1, r)]) out_dirs[corner(c, r + 1)] |= 8;          // left: (c, r + 1) -> (c, r)
    }
  // The cells either side of an edge leaving corner (i, j) in direction d: water, land.
  auto sides = [&](int i, int j, int d) -> std::array<std::size_t, 2> {
    switch (d) {
      case 0: return {at(i, j), at(i, j - 1)};
      case 1: return {at(i - 1, j), at(i, j)};
      case 2: return {at(i - 1, j - 1), at(i - 1, j)};
      default: return {at(i, j - 1), at(i - 1, j - 1)};
    }
  };
  const std::vector<std::uint8_t> all_dirs = out_dirs;  // the successor rule reads every edge, taken or not
  std::vector<Loop> loops;
  std::vector<int> dirs;
  for (int j = 0; j <= H; ++j)
    for (int i = 0; i <= W; ++i)
      while (out_dirs[corner(i, j)]) {
        int d = 0;
        while (!(out_dirs[corner(i, j)] >> d & 1)) ++d;
        Loop loop;
        const auto [w0, l0] = sides(i, j, d);
        loop.water = label[w0], loop.land = label[l0];
        dirs.clear();
        const int d0 = d;
        int ci = i, cj = j;
        while (true) {
          out_dirs[corner(ci, cj)] &= static_cast<std::uint8_t>(~(1u << d));
          dirs.push_back(d);
          loop.mid.push_back({2 * ci + kDx[d], 2 * cj + kDy[d]});
          const int ni = ci + kDx[d], nj = cj + kDy[d];
          loop.twice_area += static_cast<long long>(ci) * nj - static_cast<long long>(ni) * cj;
          ci = ni, cj = nj;
          const std::uint8_t there = all_dirs[corner(ci, cj)];
          // Toward the water first: at a saddle the ring goes round its own water cell (water 4-connected).
          int next = -1;
          for (int turn : {1, 0, 3})
            if (there >> ((d + turn) % 4) & 1) {
              next = (d + turn) % 4;
              break;
            }
          if (ci == i && cj == j && next == d0) break;  // closed
          d = next;
        }
        const std::size_t n = dirs.size();
        loop.keep.resize(n);
        for (std::size_t k = 0; k < n; ++k) {
          // A midpoint lies on the line through its neighbours exactly when the edges before and after it
          // go the same way (straight on, or a staircase).
          const bool turn = dirs[(k + n - 1) % n] != dirs[(k + 1) % n];
          const auto& m = loop.mid[k];
          const int line = (dirs[k] % 2 == 0 ? m[0] - 1 : m[1] - 1) / 2;  // the cell column or row of the edge
          loop.keep[k] = turn || line % stride == 0;
        }
        loops.push_back(std::move(loop));
      }
  // Nesting: an outer ring (water inside) lies in the island ring of the land outside it, an island ring in
  // the outer ring of its water.
  const std::size_t L = loops.size();
  std::map<int, std::size_t> outer_of_water, outer_of_land;
  for (std::size_t k = 0; k < L; ++k)
    (loops[k].twice_area > 0 ? outer_of_water[loops[k].water] : outer_of_land[loops[k].land]) = k;
  std::vector<long> parent(L, -1);
  for (std::size_t k = 0; k < L; ++k) {
    if (loops[k].twice_area > 0) {
      if (loops[k].land != label[at(-1, -1)]) parent[k] = static_cast<long>(outer_of_land.at(loops[k].land));
    } else {
      parent[k] = static_cast<long>(outer_of_water.at(loops[k].water));
    }
  }
  std::vector<int> depth(L, -1);
  for (std::size_t k = 0; k < L; ++k) {
    std::vector<std::size_t> chain;
    std::size_t v = k;
    while (depth[v] < 0 && parent[v] >= 0) chain.push_back(v), v = static_cast<std::size_t>(parent[v]);
    if (depth[v] < 0) depth[v] = 0;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) depth[*it] = depth[static_cast<std::size_t>(parent[*it])] + 1;
  }
  std::vector<std::size_t> order(L);
  for (std::size_t k = 0; k < L; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });
  std::vector<char> kept(L, 0);
  auto area = [&](std::size_t k) { return 0.5 * static_cast<double>(std::llabs(loops[k].twice_area)); };
  for (std::size_t k : order) {
    if (parent[k] >= 0 && !kept[static_cast<std::size_t>(parent[k])]) continue;  // inside a dropped ring
    if (area(k) < o.min_area) {
      (depth[k] % 2 == 0 ? out.dropped_small_water : out.dropped_small_islands)++;
      continue;
    }
    kept[k] = 1;
  }
  auto anchor_of = [&](std::size_t k) {
    std::array<int, 2> best{std::numeric_limits<int>::max(), std::numeric_limits<int>::max()};
    for (std::size_t v = 0; v < loops[k].mid.size(); ++v)
      if (loops[k].keep[v]) best = std::min(best, std::array<int, 2>{loops[k].mid[v][1], loops[k].mid[v][0]});
    return best;
  };
  if (o.largest_water_only) {
    long best = -1;
    for (std::size_t k = 0; k < L; ++k)
      if (kept[k] && depth[k] == 0 &&
          (best < 0 || area(k) > area(static_cast<std::size_t>(best)) ||
           (area(k) == area(static_cast<std::size_t>(best)) && anchor_of(k) < anchor_of(static_cast<std::size_t>(best)))))
        best = static_cast<long>(k);
    for (std::size_t k : order) {
      if (!kept[k]) continue;
      const bool keep = depth[k] == 0 ? static_cast<long>(k) == best : depth[k] == 1 && parent[k] == best;
      if (!keep) {
        if (depth[k] % 2 == 0 && (depth[k] == 0 || kept[static_cast<std::size_t>(parent[k])])) ++out.dropped_other_water;
        kept[k] = 0;
      }
    }
  }
  // Kept rings from their anchors, in the anchors' order.
  std::vector<std::size_t> index(L, 0);
  std::vector<std::pair<std::array<int, 2>, std::size_t>> sorted;
  for (std::size_t k = 0; k < L; ++k)
    if (kept[k]) sorted.push_back({anchor_of(k), k});
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t s = 0; s < sorted.size(); ++s) index[sorted[s].second] = s;
  for (const auto& [anchor, k] : sorted) {
    const Loop& loop = loops[k];
    const std::size_t n = loop.mid.size();
    std::size_t start = 0;
    while (!(loop.keep[start] && loop.mid[start][1] == anchor[0] && loop.mid[start][0] == anchor[1])) ++start;
    ContourRing r;
    r.anchor = anchor;
    r.depth = depth[k];
    r.parent = parent[k] >= 0 ? static_cast<int>(index[static_cast<std::size_t>(parent[k])]) : -1;
    r.area = area(k);
    r.ring.role = depth[k] % 2 == 0 ? RingRole::Shore : RingRole::Island;
    for (std::size_t v = 0; v < n; ++v) {
      const std::size_t q = (start + v) % n;
      if (!loop.keep[q]) continue;
      // Cell (col, row) = (X - 1) / 2, (Y - 1) / 2 in the centre convention: a function of the midpoint alone.
      r.ring.points.push_back({grid.x0 + 0.5 * (loop.mid[q][0] - 1) * grid.dx, grid.y0 + 0.5 * (loop.mid[q][1] - 1) * grid.dy});
    }
    out.rings.push_back(std::move(r));
  }
  return out;
}

std::vector<Point2> domain_vertices(const Domain2& domain) {
  std::vector<Point2> v;
  for (const Ring& r : domain.rings) v.insert(v.end(), r.points.begin(), r.points.end());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

ContourFollow follow_contours(const Domain2& slots, const Domain2& traced) {
  ContourFollow f;
  f.next = slots;
  std::map<Point2, std::size_t> closed_at, line_at;  // a slot's vertices (closed rings), a line's first vertex
  for (std::size_t r = 0; r < slots.rings.size(); ++r) {
    const Ring& ring = slots.rings[r];
    if (ring.points.empty()) continue;
    if (ring.closed())
      for (const Point2& p : ring.points) closed_at.emplace(p, r);
    else
      line_at.emplace(ring.points.front(), r);
  }
  {
    // The vertices that went or came, whatever ring or line holds them.
    const std::vector<Point2> was = domain_vertices(slots), now = domain_vertices(traced);
    std::set_symmetric_difference(was.begin(), was.end(), now.begin(), now.end(), std::back_inserter(f.moved));
  }
  std::vector<char> taken(slots.rings.size(), 0);
  std::vector<const Ring*> fresh;  // traced rings that continue none
  for (const Ring& t : traced.rings) {
    std::size_t slot = kNoSlot;
    if (t.closed()) {
      for (const Point2& p : t.points) {
        const auto it = closed_at.find(p);
        if (it != closed_at.end() && !taken[it->second] && slots.rings[it->second].role == t.role) {
          slot = it->second;
          break;
        }
      }
    } else {
      const auto it = line_at.find(t.points.front());
      if (it != line_at.end() && !taken[it->second]) slot = it->second;
    }
    if (slot == kNoSlot) {
      fresh.push_back(&t);
      continue;
    }
    taken[slot] = 1;
    const std::vector<Point2>& o = slots.rings[slot].points;
    std::vector<Point2> n = t.points;
    if (t.closed()) {
      const auto first = std::find(n.begin(), n.end(), o.front());
      if (first != n.end()) std::rotate(n.begin(), first, n.end());
    }
    if (n == o) continue;
    RingStretch e{slot, 0, 0, {}, !t.closed() || n.front() != o.front(), t.role};
    if (e.whole) {
      e.middle = n;
    } else {
      const std::size_t common = std::min(o.size(), n.size());
      while (e.prefix < common && o[e.prefix] == n[e.prefix]) ++e.prefix;
      while (e.suffix < common - e.prefix && o[o.size() - 1 - e.suffix] == n[n.size() - 1 - e.suffix]) ++e.suffix;
      e.middle.assign(n.begin() + static_cast<std::ptrdiff_t>(e.prefix), n.end() - static_cast<std::ptrdiff_t>(e.suffix));
    }
    f.edits.push_back(e);
    f.next.rings[slot].points = std::move(n);
  }
  // A ring that went leaves its place empty; a new ring takes a place that was empty already (so that no
  // place takes two edits), else one past the last.
  std::vector<std::size_t> free_slots;
  for (std::size_t r = 0; r < slots.rings.size(); ++r) {
    if (taken[r]) continue;
    if (slots.rings[r].points.empty()) {
      free_slots.push_back(r);
      continue;
    }
    f.edits.push_back({r, 0, 0, {}, true, slots.rings[r].role});
    f.next.rings[r].points.clear();
  }
  std::size_t used = 0;
  for (const Ring* t : fresh) {
    const std::size_t slot = used < free_slots.size() ? free_slots[used++] : f.next.rings.size();
    if (slot == f.next.rings.size()) f.next.rings.push_back({});
    f.next.rings[slot] = *t;
    f.edits.push_back({slot, 0, 0, t->points, true, t->role});
  }
  std::sort(f.edits.begin(), f.edits.end(), [](const RingStretch& x, const RingStretch& y) { return x.ring < y.ring; });
  return f;
}

LandWaterCounts land_water_counts(const std::vector<Point2>& points,
                                  const std::vector<Element<2>>& triangles, const Domain2& shore,
                                  bool all_below, bool none_below, const std::vector<Ring>& lines, double tol) {
  std::size_t water = 0;
  if (all_below) {
    water = triangles.size();
  } else if (!none_below) {
    const WaterTest wet(shore);
    for (const auto& t : triangles) {
      const Point2 c{(points[t[0]][0] + points[t[1]][0] + points[t[2]][0]) / 3,
                     (points[t[0]][1] + points[t[1]][1] + points[t[2]][1]) / 3};
      water += wet.classify(c) != WaterSide::Land;  // on the contour: counted as water
    }
  }
  // Mesh edges along the shoreline's lines: both ends on one segment of a line (the refinement's splits
  // are midpoints, on the segment to rounding).
  std::size_t shore_edges = 0;
  {
    std::vector<std::pair<BBox, std::size_t>> boxes;
    std::vector<BSegment> segs;
    for (const Ring& l : lines)
      for (std::size_t k = 0; k + 1 < l.points.size(); ++k) {
        const BSegment s(bp(l.points[k]), bp(l.points[k + 1]));
        BBox b;
        bg::envelope(s, b);
        boxes.push_back({b, segs.size()});
        segs.push_back(s);
      }
    const bgi::rtree<std::pair<BBox, std::size_t>, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
    std::vector<std::vector<std::size_t>> on(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const BBox b(BPoint(points[i][0] - tol, points[i][1] - tol), BPoint(points[i][0] + tol, points[i][1] + tol));
      for (auto it = tree.qbegin(bgi::intersects(b)); it != tree.qend(); ++it)
        if (bg::distance(bp(points[i]), segs[it->second]) <= tol) on[i].push_back(it->second);
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    for (const auto& [u, v] : edges)
      for (std::size_t s : on[u])
        if (std::find(on[v].begin(), on[v].end(), s) != on[v].end()) {
          ++shore_edges;
          break;
        }
  }

  return {water, shore_edges};
}

}  // namespace shoremesh
