#include "shoremesh/pslg.hpp"

#include <algorithm>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "ring_geometry.hpp"
#include "shoremesh/ring_edge_index.hpp"

namespace shoremesh {

namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

// The planar graph of the segments: at each vertex its outgoing half-edges in counter-clockwise order.
// Half-edge 2s runs segment s from its first end to its second, 2s + 1 back.
struct HalfEdges {
  std::span<const Point2> points;
  std::vector<std::array<std::size_t, 2>> segments;
  std::vector<std::vector<std::size_t>> out;  // per vertex, outgoing half-edges, counter-clockwise
  std::vector<std::size_t> place;             // per half-edge, its place in its origin's `out`

  std::size_t from(std::size_t h) const { return segments[h / 2][h % 2]; }
  std::size_t to(std::size_t h) const { return segments[h / 2][1 - h % 2]; }

  HalfEdges(std::span<const Point2> pts, std::vector<std::array<std::size_t, 2>> segs)
      : points(pts), segments(std::move(segs)), out(pts.size()), place(2 * segments.size()) {
    for (std::size_t h = 0; h < 2 * segments.size(); ++h) out[from(h)].push_back(h);
    for (std::size_t v = 0; v < out.size(); ++v) {
      const Point2& o = points[v];
      // Upper half-plane first (angle in [0, pi)), then by orientation: exact comparisons only.
      auto upper = [&](const Point2& w) { return w[1] > o[1] || (w[1] == o[1] && w[0] > o[0]); };
      std::sort(out[v].begin(), out[v].end(), [&](std::size_t a, std::size_t b) {
        const Point2 &pa = points[to(a)], &pb = points[to(b)];
        const bool ua = upper(pa), ub = upper(pb);
        if (ua != ub) return ua;
        return detail::orient(o, pa, pb) > 0;
      });
      for (std::size_t k = 0; k < out[v].size(); ++k) place[out[v][k]] = k;
    }
  }

  // The half-edge after h on the face to h's left: at h's end, the next one clockwise from h's twin.
  std::size_t next(std::size_t h) const {
    const auto& around = out[to(h)];
    const std::size_t k = place[h ^ 1];
    return around[(k + around.size() - 1) % around.size()];
  }
};

// Points of a closed walk of half-edges, for the exact crossing-number test.
std::vector<Point2> walk_points(const HalfEdges& g, const std::vector<std::size_t>& walk) {
  std::vector<Point2> out;
  out.reserve(walk.size());
  for (std::size_t h : walk) out.push_back(g.points[g.from(h)]);
  return out;
}

struct Box2 {
  Point2 lo{}, hi{};
  bool holds(const Point2& p) const { return lo[0] <= p[0] && p[0] <= hi[0] && lo[1] <= p[1] && p[1] <= hi[1]; }
};

Box2 box_of(const std::vector<Point2>& pts) {
  Box2 b{pts.front(), pts.front()};
  for (const Point2& p : pts)
    for (int i = 0; i < 2; ++i) b.lo[i] = std::min(b.lo[i], p[i]), b.hi[i] = std::max(b.hi[i], p[i]);
  return b;
}

}  // namespace

std::optional<std::array<std::size_t, 2>> first_segment_crossing(std::span<const Point2> points,
                                                                std::span<const std::array<std::size_t, 2>> segments) {
  Domain2 lines;
  lines.rings.reserve(segments.size());
  for (const auto& s : segments) lines.rings.push_back({{points[s[0]], points[s[1]]}, RingRole::Line});
  const auto crossing = RingEdgeIndex(lines).first_crossing(lines, true);
  if (!crossing) return std::nullopt;
  return std::array<std::size_t, 2>{crossing->ring_a, crossing->ring_b};
}

PslgDomain pslg_domain(std::span<const Point2> points, std::span<const std::array<std::size_t, 2>> segments,
                       std::span<const Point2> holes) {
  PslgDomain result;
  // One segment per pair of vertices (a segment given twice is one constraint).
  std::vector<std::array<std::size_t, 2>> segs;
  for (auto s : segments) {
    if (s[0] == s[1]) throw std::invalid_argument("pslg_domain: a segment joins a vertex to itself");
    if (s[1] < s[0]) std::swap(s[0], s[1]);
    segs.push_back(s);
  }
  std::sort(segs.begin(), segs.end());
  segs.erase(std::unique(segs.begin(), segs.end()), segs.end());
  result.duplicate_segments = segments.size() - segs.size();
  const HalfEdges g(points, std::move(segs));
  const std::size_t halves = 2 * g.segments.size();

  // Faces: the closed walks of `next`.
  std::vector<std::size_t> face_of(halves, kNone);
  std::vector<std::vector<std::size_t>> faces;
  for (std::size_t h0 = 0; h0 < halves; ++h0) {
    if (face_of[h0] != kNone) continue;
    faces.emplace_back();
    for (std::size_t h = h0; face_of[h] == kNone; h = g.next(h)) {
      face_of[h] = faces.size() - 1;
      faces.back().push_back(h);
    }
  }

  // Connected parts, and each part's outer face: at its lowest-leftmost vertex v every neighbour lies at an
  // angle in (-90, 90] degrees, and the face through the corner that holds the direction west (from the
  // last neighbour of the upper half-plane, or the last of all, round to the next) is the outer one.
  std::vector<std::size_t> part(points.size());
  std::iota(part.begin(), part.end(), 0);
  auto root = [&](std::size_t v) {
    while (part[v] != v) v = part[v] = part[part[v]];
    return v;
  };
  for (const auto& s : g.segments) part[root(s[0])] = root(s[1]);
  std::vector<std::size_t> lowest(points.size(), kNone);  // per part root: its lowest-leftmost vertex
  for (std::size_t v = 0; v < points.size(); ++v) {
    if (g.out[v].empty()) continue;
    std::size_t& l = lowest[root(v)];
    if (l == kNone || points[v] < points[l]) l = v;
  }
  std::vector<bool> outer(faces.size(), false);
  std::vector<std::pair<std::size_t, std::size_t>> parts;  // each part's lowest vertex and outer face
  for (std::size_t r = 0; r < points.size(); ++r) {
    if (lowest[r] == kNone) continue;
    const std::size_t v = lowest[r];
    const auto& around = g.out[v];
    std::size_t a = around.size() - 1;
    for (std::size_t k = 0; k < around.size(); ++k) {
      const Point2& w = points[g.to(around[k])];
      if (w[1] > points[v][1] || (w[1] == points[v][1] && w[0] > points[v][0])) a = k;
    }
    parts.emplace_back(v, face_of[around[a]]);
    outer[face_of[around[a]]] = true;
  }

  // The bounded faces, and which of them holds a point: the innermost one (faces of one part do not
  // overlap, so those holding the point come from different parts, nested: the innermost one's part lies
  // inside all the others).
  std::vector<std::size_t> bounded;
  std::vector<std::vector<Point2>> polygon(faces.size());
  std::vector<Box2> box(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (outer[f]) continue;
    bounded.push_back(f);
    polygon[f] = walk_points(g, faces[f]);
    box[f] = box_of(polygon[f]);
  }
  result.bounded_faces = !bounded.empty();
  auto lowest_of_face = [&](std::size_t f) { return lowest[root(g.from(faces[f].front()))]; };
  auto face_holding = [&](const Point2& p, std::size_t skip_part) -> std::size_t {
    std::vector<std::size_t> holding;
    for (std::size_t f : bounded)
      if (root(g.from(faces[f].front())) != skip_part && box[f].holds(p) && ring_contains(polygon[f], p))
        holding.push_back(f);
    for (std::size_t f : holding) {
      const Point2& inner = points[lowest_of_face(f)];
      if (std::all_of(holding.begin(), holding.end(),
                      [&](std::size_t e) { return e == f || ring_contains(polygon[e], inner); }))
        return f;
    }
    return kNone;
  };

  // Water: bounded faces without a hole seed; a part's outer face is the water of the face holding the
  // part (none: the unbounded region, land).
  std::vector<bool> seeded(faces.size(), false);
  for (std::size_t i = 0; i < holes.size(); ++i) {
    const std::size_t f = face_holding(holes[i], kNone);
    if (f == kNone) result.holes_outside.push_back(i);
    else seeded[f] = true;
  }
  std::vector<bool> water(faces.size(), false);
  for (std::size_t f : bounded) water[f] = !seeded[f];
  for (const auto& [v, outer_face] : parts) {
    const std::size_t f = face_holding(points[v], root(v));
    water[outer_face] = f != kNone && water[f];
  }
  if (!result.bounded_faces) std::fill(water.begin(), water.end(), true);  // lines only

  // Segments by the water on their sides.
  auto water_left = [&](std::size_t h) { return water[face_of[h]]; };
  auto boundary = [&](std::size_t h) { return water_left(h) != water_left(h ^ 1); };
  std::vector<std::size_t> line_degree(points.size(), 0), boundary_degree(points.size(), 0);
  for (std::size_t s = 0; s < g.segments.size(); ++s) {
    const bool l = water_left(2 * s), r = water_left(2 * s + 1);
    if (l && r) {
      ++result.line_segments;
      for (std::size_t v : g.segments[s]) ++line_degree[v];
    } else if (l || r) {
      ++result.boundary_segments;
      for (std::size_t v : g.segments[s]) ++boundary_degree[v];
    } else {
      ++result.dropped_segments;
    }
  }
  for (std::size_t v = 0; v < points.size(); ++v)
    if (boundary_degree[v] >= 4) result.pinch_vertices.push_back(v);

  // Rings: the boundary walked with the water on the left; at a vertex the next boundary half-edge
  // clockwise from the one we came along (the same water sector). A walk that comes back to a vertex is
  // cut there into simple cycles.
  auto add_ring = [&](std::vector<std::size_t> cycle) {
    std::vector<Point2> pts;
    for (std::size_t v : cycle) pts.push_back(points[v]);
    const std::size_t low = static_cast<std::size_t>(std::min_element(pts.begin(), pts.end()) - pts.begin());
    const std::size_t n = pts.size();
    const bool ccw = detail::orient(pts[(low + n - 1) % n], pts[low], pts[(low + 1) % n]) > 0;
    result.domain.rings.push_back({std::move(pts), ccw ? RingRole::Shore : RingRole::Island});
    result.vertices.push_back(std::move(cycle));
  };
  std::vector<bool> walked(halves, false);
  std::vector<std::size_t> depth_at(points.size(), kNone);  // a vertex's place on the current walk's stack
  for (std::size_t h0 = 0; h0 < halves; ++h0) {
    if (walked[h0] || !boundary(h0) || !water_left(h0)) continue;
    std::vector<std::size_t> stack;
    std::size_t h = h0;
    do {
      walked[h] = true;
      const std::size_t v = g.from(h);
      if (depth_at[v] != kNone) {  // back at v: the loop since v is a cycle of its own
        std::vector<std::size_t> cycle(stack.begin() + static_cast<std::ptrdiff_t>(depth_at[v]), stack.end());
        for (std::size_t u : cycle) depth_at[u] = kNone;
        stack.resize(stack.size() - cycle.size());
        add_ring(std::move(cycle));
      }
      depth_at[v] = stack.size();
      stack.push_back(v);
      // The next boundary half-edge clockwise at h's end, skipping lines through the water sector.
      const auto& around = g.out[g.to(h)];
      std::size_t k = g.place[h ^ 1];
      do k = (k + around.size() - 1) % around.size();
      while (!boundary(around[k]));
      h = around[k];
      if (!water_left(h)) throw std::logic_error("pslg_domain: the water's boundary does not alternate at a vertex");
    } while (h != h0);
    for (std::size_t u : stack) depth_at[u] = kNone;
    add_ring(std::move(stack));
  }

  // Lines: chains of water-water segments, ending where a ring passes or where other than two of them meet.
  auto stop = [&](std::size_t v) { return line_degree[v] != 2 || boundary_degree[v] > 0; };
  auto is_line = [&](std::size_t h) { return water_left(h) && water_left(h ^ 1); };
  std::vector<bool> used(g.segments.size(), false);
  // A chain that comes back to its start is cut in two at its middle: a line's vertices are distinct.
  std::function<void(std::vector<std::size_t>)> add_line = [&](std::vector<std::size_t> chain) {
    if (chain.front() == chain.back()) {
      const auto mid = static_cast<std::ptrdiff_t>(chain.size() / 2);
      add_line(std::vector<std::size_t>(chain.begin(), chain.begin() + mid + 1));
      add_line(std::vector<std::size_t>(chain.begin() + mid, chain.end()));
      return;
    }
    std::vector<Point2> pts;
    for (std::size_t v : chain) pts.push_back(points[v]);
    result.domain.rings.push_back({std::move(pts), RingRole::Line});
    result.vertices.push_back(std::move(chain));
  };
  // From `h` on until a stop vertex (or back at the start, for a closed chain).
  auto chain_from = [&](std::size_t h) {
    std::vector<std::size_t> chain{g.from(h)};
    while (true) {
      used[h / 2] = true;
      const std::size_t v = g.to(h);
      chain.push_back(v);
      if (stop(v) || v == chain.front()) return chain;
      const auto it = std::find_if(g.out[v].begin(), g.out[v].end(),
                                   [&](std::size_t e) { return is_line(e) && !used[e / 2]; });
      if (it == g.out[v].end()) return chain;
      h = *it;
    }
  };
  for (std::size_t v = 0; v < points.size(); ++v) {
    if (!stop(v)) continue;
    for (std::size_t h : g.out[v])
      if (is_line(h) && !used[h / 2]) add_line(chain_from(h));
  }
  for (std::size_t h = 0; h < halves; h += 2)  // closed chains through no stop vertex
    if (is_line(h) && !used[h / 2]) add_line(chain_from(h));
  return result;
}

}  // namespace shoremesh
