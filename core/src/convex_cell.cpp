#include "shoremesh/engine/convex_cell.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shoremesh::engine {

namespace {

// The plane of constraint c in the number type NT: n.y <= b with y = x - v.
template <class NT, int D>
void plane_of(const Constraint<D>& c, const Point<D>& v, std::array<NT, D>& n, NT& b) {
  using Kind = typename Constraint<D>::Kind;
  for (int i = 0; i < D; ++i) n[i] = NT(0);
  switch (c.kind) {
    case Kind::Bisector: {
      // |y|^2 <= |y - d|^2  <=>  2 d.y <= |d|^2, d = w - v.
      b = NT(0);
      for (int i = 0; i < D; ++i) {
        const NT d = NT(c.other_point[i]) - NT(v[i]);
        n[i] = d + d;
        b += d * d;
      }
      break;
    }
    case Kind::AxisMax:
      n[c.axis] = NT(1);
      b = NT(c.value) - NT(v[c.axis]);
      break;
    case Kind::AxisMin:
      n[c.axis] = NT(-1);
      b = NT(v[c.axis]) - NT(c.value);
      break;
  }
}

// Solves the D x D system rows n_k . y = b_k by Cramer's rule (generic in the number type).
template <class NT>
std::array<NT, 2> solve(const std::array<std::array<NT, 2>, 2>& n, const std::array<NT, 2>& b) {
  const NT det = n[0][0] * n[1][1] - n[0][1] * n[1][0];
  return {(b[0] * n[1][1] - n[0][1] * b[1]) / det, (n[0][0] * b[1] - b[0] * n[1][0]) / det};
}

// The 2 x 2 minors of columns b, c that expand a determinant det(a, b, c) along a.
template <class NT>
std::array<NT, 3> minors(const std::array<NT, 3>& b, const std::array<NT, 3>& c) {
  return {b[1] * c[2] - b[2] * c[1], b[0] * c[2] - b[2] * c[0], b[0] * c[1] - b[1] * c[0]};
}

template <class NT>
NT expand(const std::array<NT, 3>& a, const std::array<NT, 3>& m) {
  return a[0] * m[0] - a[1] * m[1] + a[2] * m[2];
}

template <class NT>
NT det3(const std::array<NT, 3>& a, const std::array<NT, 3>& b, const std::array<NT, 3>& c) {
  return expand(a, minors(b, c));
}

template <class NT>
std::array<NT, 3> solve(const std::array<std::array<NT, 3>, 3>& n, const std::array<NT, 3>& b) {
  // Columns of the system matrix are (n[0][j], n[1][j], n[2][j]).
  std::array<NT, 3> c0{n[0][0], n[1][0], n[2][0]}, c1{n[0][1], n[1][1], n[2][1]}, c2{n[0][2], n[1][2], n[2][2]};
  // det(c0, c1, c2) and det(b, c1, c2) share the minors of (c1, c2): computed once, the same operations
  // in the same order, so the intervals are bit for bit those of two separate expansions.
  const std::array<NT, 3> m12 = minors(c1, c2);
  const NT det = expand(c0, m12);
  return {expand(b, m12) / det, det3(c0, b, c2) / det, det3(c0, c1, b) / det};
}

double midpoint(const Interval& x) { return 0.5 * (x.inf() + x.sup()); }

}  // namespace

template <int D>
std::uint16_t ConvexCell<D>::add_constraint(const Constraint<D>& c) {
  if (constraints_.size() >= 0xFFFF) throw std::logic_error("convex cell: too many constraints");
  constraints_.push_back(c);
  Constraint<D>& k = constraints_.back();
  plane_of<Interval, D>(k, v_, k.n, k.b);
  return std::uint16_t(constraints_.size() - 1);
}

// The order clipping from scratch numbers planes in: the box's planes first, then bisectors by
// distance, ties by position.
template <int D>
bool ConvexCell<D>::before_in_distance_order(std::uint16_t a, std::uint16_t b) const {
  const Constraint<D>& ca = constraints_[a];
  const Constraint<D>& cb = constraints_[b];
  const bool bisector_a = ca.kind == Constraint<D>::Kind::Bisector, bisector_b = cb.kind == Constraint<D>::Kind::Bisector;
  if (bisector_a != bisector_b) return bisector_b;
  if (!bisector_a) return a < b;
  if (ca.order_d2 != cb.order_d2) return ca.order_d2 < cb.order_d2;
  return ca.other_point < cb.other_point;
}

template <int D>
typename ConvexCell<D>::Vertex ConvexCell<D>::make_vertex(const std::array<std::uint16_t, D>& planes) {
  Vertex vtx;
  vtx.planes = planes;
  if (D == 3 && out_of_order_)
    std::sort(vtx.planes.begin(), vtx.planes.end(),
              [&](std::uint16_t a, std::uint16_t b) { return before_in_distance_order(a, b); });
  std::array<std::array<Interval, D>, D> n;
  std::array<Interval, D> b;
  for (int k = 0; k < D; ++k) {
    n[k] = constraints_[vtx.planes[k]].n;
    b[k] = constraints_[vtx.planes[k]].b;
  }
  vtx.y = solve(n, b);
  // Rounded upward (the caller holds a RoundingGuard): an upper bound.
  for (int i = 0; i < D; ++i) {
    const double m = std::max(std::abs(vtx.y[i].inf()), std::abs(vtx.y[i].sup()));
    vtx.r2 += m * m;
  }
  return vtx;
}

template <int D>
const std::array<Exact, D>& ConvexCell<D>::exact_position(Vertex& vtx) {
  if (vtx.exact < 0) {
    std::array<std::array<Exact, D>, D> n;
    std::array<Exact, D> b;
    for (int k = 0; k < D; ++k) plane_of<Exact, D>(constraints_[vtx.planes[k]], v_, n[k], b[k]);
    exact_.push_back(solve(n, b));
    vtx.exact = std::int32_t(exact_.size() - 1);
  }
  return exact_[std::size_t(vtx.exact)];
}

template <int D>
int ConvexCell<D>::side(Vertex& vtx, std::uint16_t plane) {
  ++counters_.calls;
  const Constraint<D>& c = constraints_[plane];
  Interval s = -c.b;
  for (int i = 0; i < D; ++i) s += c.n[i] * vtx.y[i];
  const int sign = interval_sign(s);
  if (sign != kUndecided) return sign;
  ++counters_.exact;
  const auto& y = exact_position(vtx);
  std::array<Exact, D> n;
  Exact b;
  plane_of<Exact, D>(c, v_, n, b);
  Exact e = -b;
  for (int i = 0; i < D; ++i) e += n[i] * y[i];
  return int(CGAL::sign(e));
}

template <int D>
void ConvexCell<D>::reset(const Point<D>& v, const Point<D>& lo, const Point<D>& hi) {
  v_ = v;
  vertex_on_plane_ = false;
  out_of_order_ = false;
  constraints_.clear();
  exact_.clear();
  verts_.clear();
  free_verts_.clear();
  using Kind = typename Constraint<D>::Kind;
  // Constraint 2*axis is x[axis] >= lo, 2*axis+1 is x[axis] <= hi.
  for (int a = 0; a < D; ++a) {
    Constraint<D> mn;
    mn.kind = Kind::AxisMin;
    mn.axis = a;
    mn.value = lo[a];
    add_constraint(mn);
    Constraint<D> mx;
    mx.kind = Kind::AxisMax;
    mx.axis = a;
    mx.value = hi[a];
    add_constraint(mx);
  }
  auto corner = [&](int bits) {
    std::array<std::uint16_t, D> planes;
    for (int a = 0; a < D; ++a) planes[a] = std::uint16_t(2 * a + ((bits >> a) & 1));
    return make_vertex(planes);
  };
  if constexpr (D == 2) {
    // Counter-clockwise; edge i runs from vertex i to vertex i+1.
    for (int bits : {0, 1, 3, 2}) verts_.push_back(corner(bits));
    edges_ = {2, 1, 3, 0};  // y >= lo, x <= hi, y <= hi, x >= lo
  } else {
    for (int bits = 0; bits < 8; ++bits) verts_.push_back(corner(bits));
    // Faces with their vertices counter-clockwise seen from outside.
    face_plane_ = {0, 1, 2, 3, 4, 5};
    face_verts_ = {0, 4, 6, 2, /**/ 1, 3, 7, 5, /**/ 0, 1, 5, 4, /**/ 2, 6, 7, 3, /**/ 0, 2, 3, 1, /**/ 4, 5, 7, 6};
    face_begin_ = {0, 4, 8, 12, 16, 20};
    face_len_ = {4, 4, 4, 4, 4, 4};
  }
  live_vertices_ = verts_.size();
}

template <int D>
void ConvexCell<D>::begin_out_of_order_cuts() {
  out_of_order_ = true;
}

template <int D>
void ConvexCell<D>::end_out_of_order_cuts() {
  out_of_order_ = false;
  if constexpr (D == 3) {
    const std::size_t m = constraints_.size();
    std::vector<std::uint16_t> order(m);
    for (std::size_t k = 0; k < m; ++k) order[k] = std::uint16_t(k);
    std::sort(order.begin(), order.end(), [&](std::uint16_t a, std::uint16_t b) { return before_in_distance_order(a, b); });
    std::vector<std::uint16_t> renamed(m);
    std::vector<Constraint<D>> sorted(m);
    for (std::size_t k = 0; k < m; ++k) {
      renamed[order[k]] = std::uint16_t(k);
      sorted[k] = constraints_[order[k]];
    }
    constraints_.swap(sorted);
    // The renaming keeps the distance order, in which every vertex already lists its planes.
    for (Vertex& vtx : verts_)
      for (std::uint16_t& plane : vtx.planes) plane = renamed[plane];
    // Faces back in increasing plane order (clip_polyhedron takes a cut edge's faces in that order).
    std::vector<std::size_t> faces(face_plane_.size());
    for (std::size_t f = 0; f < faces.size(); ++f) faces[f] = f;
    std::sort(faces.begin(), faces.end(), [&](std::size_t a, std::size_t b) {
      return renamed[face_plane_[a]] < renamed[face_plane_[b]];
    });
    std::vector<std::uint16_t> plane(faces.size());
    std::vector<std::uint32_t> begin(faces.size()), len(faces.size());
    for (std::size_t k = 0; k < faces.size(); ++k) {
      plane[k] = renamed[face_plane_[faces[k]]];
      begin[k] = face_begin_[faces[k]];
      len[k] = face_len_[faces[k]];
    }
    face_plane_.swap(plane);
    face_begin_.swap(begin);
    face_len_.swap(len);
  }
}

template <int D>
bool ConvexCell<D>::clip(VertexId w, const Point<D>& wp, double d2) {
  Constraint<D> c;
  c.kind = Constraint<D>::Kind::Bisector;
  c.other = w;
  c.other_point = wp;
  c.order_d2 = d2;
  const std::uint16_t plane = add_constraint(c);
  if (clip_by(plane)) return true;
  constraints_.pop_back();  // did not cut: forget it (it bounds nothing)
  return false;
}

// An upper bound on n.y - b (the caller holds a RoundingGuard, so each product's largest corner and the
// sum are rounded upward): when it is negative, the vertex is strictly inside, which is what most vertices
// are. The bound is the upper end of the interval side() computes, at a quarter of the cost.
namespace {

template <int D>
double upper_side_bound(const Constraint<D>& c, const std::array<Interval, D>& y) {
  double s = -c.b.inf();
  for (int i = 0; i < D; ++i) {
    const double n0 = c.n[i].inf(), n1 = c.n[i].sup(), y0 = y[i].inf(), y1 = y[i].sup();
    s += std::max(std::max(n0 * y0, n0 * y1), std::max(n1 * y0, n1 * y1));
  }
  return s;
}

}  // namespace

template <int D>
bool ConvexCell<D>::clip_by(std::uint16_t plane) {
  const std::size_t m = verts_.size();
  signs_.resize(m);
  bool any_outside = false;
  // A vertex nearer to v than half of |w - v| lies strictly inside the bisector's half-space
  // (2 d.y <= 2 |d| |y| < |d|^2): no predicate needed. b encloses |d|^2 for a bisector; the axis
  // planes of the initial box are never offered again.
  const Constraint<D>& c = constraints_[plane];
  const double inside_below = c.kind == Constraint<D>::Kind::Bisector ? 0.25 * c.b.inf() : 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    Vertex& vtx = verts_[i];
    if (!vtx.alive || vtx.r2 < inside_below) {
      signs_[i] = -1;
      continue;
    }
    if (upper_side_bound<D>(c, vtx.y) < 0) {
      ++counters_.calls;  // the same decision side() would take from its interval
      signs_[i] = -1;
      continue;
    }
    signs_[i] = std::int8_t(side(vtx, plane));
    vertex_on_plane_ = vertex_on_plane_ || signs_[i] == 0;
    any_outside = any_outside || signs_[i] > 0;
  }
  if (!any_outside) return false;
  if constexpr (D == 2)
    clip_polygon(plane);
  else
    clip_polyhedron(plane);
  return true;
}

template <int D>
void ConvexCell<D>::clip_polygon(std::uint16_t plane) {
  if constexpr (D == 2) {
    const std::size_t m = verts_.size();
    next_verts_.clear();
    next_edges_.clear();
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = (i + 1) % m;
      const int si = signs_[i], sj = signs_[j];
      const std::uint16_t e = edges_[i];
      if (si <= 0) {
        next_verts_.push_back(verts_[i]);
        if (sj <= 0) {
          next_edges_.push_back(e);
        } else if (si < 0) {  // leaves the half-plane inside edge e
          next_edges_.push_back(e);
          next_verts_.push_back(make_vertex({e, plane}));
          next_edges_.push_back(plane);
        } else {  // vertex i lies on the new line: the boundary continues along it
          next_edges_.push_back(plane);
        }
      } else if (sj < 0) {  // re-enters inside edge e
        next_verts_.push_back(make_vertex({plane, e}));
        next_edges_.push_back(e);
      }
    }
    verts_.swap(next_verts_);
    edges_.swap(next_edges_);
    live_vertices_ = verts_.size();
  }
}

template <int D>
std::uint32_t ConvexCell<D>::new_vertex_slot() {
  if (!free_verts_.empty()) {
    const std::uint32_t slot = free_verts_.back();
    free_verts_.pop_back();
    return slot;
  }
  verts_.emplace_back();
  return std::uint32_t(verts_.size() - 1);
}

template <int D>
void ConvexCell<D>::compact_face_arena() {
  arena_scratch_.clear();
  for (std::size_t f = 0; f < face_plane_.size(); ++f) {
    const std::uint32_t begin = face_begin_[f];
    face_begin_[f] = std::uint32_t(arena_scratch_.size());
    arena_scratch_.insert(arena_scratch_.end(), face_verts_.begin() + begin, face_verts_.begin() + begin + face_len_[f]);
  }
  face_verts_.swap(arena_scratch_);
}

// Only the faces with a vertex on or beyond the plane change; the others keep their cycles where they
// are. signs_ holds the side of every vertex slot (dead slots -1).
template <int D>
void ConvexCell<D>::clip_polyhedron(std::uint16_t plane) {
  if constexpr (D == 3) {
    const std::size_t m = verts_.size();
    const std::size_t nf = face_plane_.size();
    // New vertices on edges whose ends lie strictly on opposite sides; each such edge is shared by two
    // faces, whose planes (in face order, which is plane order) with the new plane define the vertex.
    std::vector<CutEdge>& cuts = cuts_;  // few: a cut of a convex cell crosses a handful of edges
    cuts.clear();
    auto cut_of = [&](std::uint32_t a, std::uint32_t b) -> CutEdge& {
      const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
      for (CutEdge& e : cuts)
        if (e.a == lo && e.b == hi) return e;
      cuts.push_back(CutEdge{lo, hi, {0, 0}, 0, 0});
      return cuts.back();
    };
    // face_cuts_ lists, face by face and edge by edge, which cut each touched face crosses: the rewrite
    // below walks the same edges in the same order and takes them from it without a search.
    touched_faces_.clear();
    face_cuts_.clear();
    bool on_plane_old = false;
    for (std::size_t f = 0; f < nf; ++f) {
      const std::uint32_t* cycle = face_verts_.data() + face_begin_[f];
      const std::uint32_t len = face_len_[f];
      int most = -1;
      for (std::uint32_t k = 0; k < len; ++k) most = std::max(most, int(signs_[cycle[k]]));
      if (most < 0) continue;
      touched_faces_.push_back(std::uint32_t(f));
      for (std::uint32_t k = 0; k < len; ++k) {
        const std::uint32_t a = cycle[k], b = cycle[k + 1 == len ? 0 : k + 1];
        on_plane_old = on_plane_old || signs_[a] == 0;
        if (signs_[a] * signs_[b] < 0) {
          CutEdge& e = cut_of(a, b);
          if (e.count < 2) e.faces[e.count] = face_plane_[f];
          ++e.count;
          face_cuts_.push_back(std::uint32_t(&e - cuts.data()));
        }
      }
    }
    // Slots freed by earlier clips only: this clip's outside vertices are still read below.
    for (CutEdge& e : cuts) {
      if (e.count != 2) throw std::logic_error("convex cell: a cut edge not shared by two faces");
      const Vertex vtx = make_vertex({e.faces[0], e.faces[1], plane});
      e.vertex = new_vertex_slot();
      verts_[e.vertex] = vtx;
    }
    signs_.resize(verts_.size());
    for (const CutEdge& e : cuts) signs_[e.vertex] = 0;  // new vertices lie on the new plane

    // The touched faces' clipped cycles, and the edges of the new plane's face from them.
    rim_.clear();
    bool face_dropped = false;
    std::size_t next_cut = 0;
    for (std::uint32_t f : touched_faces_) {
      const std::uint32_t begin = face_begin_[f], len = face_len_[f];
      const std::uint32_t start = std::uint32_t(face_verts_.size());
      for (std::uint32_t k = 0; k < len; ++k) {
        const std::uint32_t a = face_verts_[begin + k], b = face_verts_[begin + (k + 1 == len ? 0 : k + 1)];
        if (signs_[a] <= 0) face_verts_.push_back(a);
        if (signs_[a] * signs_[b] < 0) face_verts_.push_back(cuts[face_cuts_[next_cut++]].vertex);
      }
      const std::uint32_t flen = std::uint32_t(face_verts_.size()) - start;
      if (flen < 3) {  // the face was cut away, or only touches the new plane
        face_verts_.resize(start);
        face_len_[f] = 0;
        face_dropped = true;
        continue;
      }
      // The face's edge on the new plane, p -> q in this face, is q -> p in the new face (one per q).
      for (std::uint32_t k = 0; k < flen; ++k) {
        const std::uint32_t p = face_verts_[start + k], q = face_verts_[start + (k + 1 == flen ? 0 : k + 1)];
        if (signs_[p] != 0 || signs_[q] != 0) continue;
        auto same_to = std::find_if(rim_.begin(), rim_.end(), [&](const RimEdge& r) { return r.from == q; });
        if (same_to != rim_.end())
          same_to->to = p;
        else
          rim_.push_back(RimEdge{q, p});
      }
      face_begin_[f] = start;
      face_len_[f] = flen;
    }
    if (face_dropped) {
      std::size_t kept = 0;
      for (std::size_t f = 0; f < nf; ++f)
        if (face_len_[f] != 0) {
          face_plane_[kept] = face_plane_[f];
          face_begin_[kept] = face_begin_[f];
          face_len_[kept] = face_len_[f];
          ++kept;
        }
      face_plane_.resize(kept);
      face_begin_.resize(kept);
      face_len_.resize(kept);
    }
    // The new face: follow the chain of on-plane edges.
    const std::size_t chain = rim_.size();
    if (chain < 3) throw std::logic_error("convex cell: the cut face has fewer than three edges");
    const std::uint32_t start = std::uint32_t(face_verts_.size());
    const std::uint32_t startv = rim_.front().from;
    std::size_t walked = 0;
    std::uint32_t cur = startv;
    do {
      face_verts_.push_back(cur);
      auto r = std::find_if(rim_.begin(), rim_.end(), [&](const RimEdge& e) { return e.from == cur; });
      if (r == rim_.end() || ++walked > chain) throw std::logic_error("convex cell: the cut face is not a cycle");
      cur = r->to;
    } while (cur != startv);
    if (walked != chain) throw std::logic_error("convex cell: the cut face has two cycles");
    face_plane_.push_back(plane);
    face_begin_.push_back(start);
    face_len_.push_back(std::uint32_t(face_verts_.size()) - start);

    // Free the vertices cut away, and old vertices on the plane no kept face uses (their faces all went).
    for (std::size_t i = 0; i < m; ++i)
      if (signs_[i] > 0) {
        verts_[i].alive = false;
        free_verts_.push_back(std::uint32_t(i));
      }
    if (on_plane_old) {
      used_.assign(verts_.size(), 0);
      for (std::size_t f = 0; f < face_plane_.size(); ++f)
        for (std::uint32_t k = 0; k < face_len_[f]; ++k) used_[face_verts_[face_begin_[f] + k]] = 1;
      for (std::size_t i = 0; i < m; ++i)
        if (signs_[i] == 0 && !used_[i]) {
          verts_[i].alive = false;
          free_verts_.push_back(std::uint32_t(i));
        }
    }
    live_vertices_ = verts_.size() - free_verts_.size();
    // The arena holds every cycle a face ever had in this cell: compact it once it is mostly garbage.
    std::size_t live_entries = 0;
    for (std::uint32_t len : face_len_) live_entries += len;
    if (face_verts_.size() > 4096 && face_verts_.size() > 4 * live_entries) compact_face_arena();
  }
}

template <int D>
bool ConvexCell<D>::within_scaled_distance(double k, const Point<D>& u) {
  // |u - v|^2 in both number types, once.
  Interval r2i(0);
  for (int i = 0; i < D; ++i) {
    const Interval d = Interval(u[i]) - Interval(v_[i]);
    r2i += d * d;
  }
  r2i *= Interval(k);
  for (Vertex& vtx : verts_) {
    if (!vtx.alive) continue;
    ++counters_.calls;
    Interval s = -r2i;
    for (int i = 0; i < D; ++i) s += CGAL::square(vtx.y[i]);
    int sign = interval_sign(s);
    if (sign == kUndecided) {
      ++counters_.exact;
      const auto& y = exact_position(vtx);
      Exact e = -Exact(k) * squared_distance<Exact, D>(u, v_);
      for (int i = 0; i < D; ++i) e += y[i] * y[i];
      sign = int(CGAL::sign(e));
    }
    if (sign > 0) return false;
  }
  return true;
}

template <int D>
Point<D> ConvexCell<D>::farthest_vertex_offset() const {
  Point<D> best{};
  double best_d2 = -1;
  for (const Vertex& vtx : verts_) {
    if (!vtx.alive) continue;
    Point<D> y;
    double d2 = 0;
    for (int i = 0; i < D; ++i) {
      y[i] = midpoint(vtx.y[i]);
      d2 += y[i] * y[i];
    }
    if (d2 > best_d2 || (d2 == best_d2 && y < best)) {
      best_d2 = d2;
      best = y;
    }
  }
  return best;
}

template <int D>
double ConvexCell<D>::max_vertex_distance2() const {
  double best = 0;
  for (const Vertex& vtx : verts_)
    if (vtx.alive) best = std::max(best, vtx.r2);
  return best;
}

template <int D>
void ConvexCell<D>::bisector_neighbours(std::vector<VertexId>& out) const {
  out.clear();
  const auto& planes = (D == 2) ? edges_ : face_plane_;
  for (std::uint16_t p : planes)
    if (constraints_[p].kind == Constraint<D>::Kind::Bisector) out.push_back(constraints_[p].other);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

template <int D>
void ConvexCell<D>::assign_geometry(const ConvexCell& other) {
  v_ = other.v_;
  constraints_ = other.constraints_;
  exact_ = other.exact_;
  verts_ = other.verts_;
  live_vertices_ = other.live_vertices_;
  vertex_on_plane_ = other.vertex_on_plane_;
  edges_ = other.edges_;
  face_plane_ = other.face_plane_;
  face_begin_ = other.face_begin_;
  face_len_ = other.face_len_;
  face_verts_ = other.face_verts_;
  free_verts_ = other.free_verts_;
}

template <int D>
std::size_t ConvexCell<D>::memory_bytes() const {
  return constraints_.capacity() * sizeof(Constraint<D>) + exact_.capacity() * sizeof(exact_[0]) +
         (verts_.capacity() + next_verts_.capacity()) * sizeof(Vertex) + signs_.capacity() +
         (edges_.capacity() + next_edges_.capacity() + face_plane_.capacity()) * sizeof(std::uint16_t) +
         (face_begin_.capacity() + face_len_.capacity() + face_verts_.capacity() + arena_scratch_.capacity() +
          free_verts_.capacity() + touched_faces_.capacity() + face_cuts_.capacity()) *
             sizeof(std::uint32_t) +
         used_.capacity() + cuts_.capacity() * sizeof(CutEdge) + rim_.capacity() * sizeof(RimEdge);
}

template class ConvexCell<2>;
template class ConvexCell<3>;

}  // namespace shoremesh::engine
