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

template <class NT>
NT det3(const std::array<NT, 3>& a, const std::array<NT, 3>& b, const std::array<NT, 3>& c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

template <class NT>
std::array<NT, 3> solve(const std::array<std::array<NT, 3>, 3>& n, const std::array<NT, 3>& b) {
  // Columns of the system matrix are (n[0][j], n[1][j], n[2][j]).
  std::array<NT, 3> c0{n[0][0], n[1][0], n[2][0]}, c1{n[0][1], n[1][1], n[2][1]}, c2{n[0][2], n[1][2], n[2][2]};
  const NT det = det3(c0, c1, c2);
  return {det3(b, c1, c2) / det, det3(c0, b, c2) / det, det3(c0, c1, b) / det};
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

template <int D>
typename ConvexCell<D>::Vertex ConvexCell<D>::make_vertex(const std::array<std::uint16_t, D>& planes) {
  Vertex vtx;
  vtx.planes = planes;
  std::array<std::array<Interval, D>, D> n;
  std::array<Interval, D> b;
  for (int k = 0; k < D; ++k) {
    n[k] = constraints_[planes[k]].n;
    b[k] = constraints_[planes[k]].b;
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
  constraints_.clear();
  exact_.clear();
  verts_.clear();
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
    face_begin_ = {0, 4, 8, 12, 16, 20, 24};
  }
}

template <int D>
bool ConvexCell<D>::clip(VertexId w, const Point<D>& wp) {
  Constraint<D> c;
  c.kind = Constraint<D>::Kind::Bisector;
  c.other = w;
  c.other_point = wp;
  const std::uint16_t plane = add_constraint(c);
  if (clip_by(plane)) return true;
  constraints_.pop_back();  // did not cut: forget it (it bounds nothing)
  return false;
}

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
    signs_[i] = verts_[i].r2 < inside_below ? std::int8_t(-1) : std::int8_t(side(verts_[i], plane));
    any_outside = any_outside || signs_[i] > 0;
  }
  if (!any_outside) return false;

  if constexpr (D == 2) {
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
    return true;
  } else {
    // New vertices on edges whose ends lie strictly on opposite sides; each such edge is shared by two
    // faces, whose planes with the new plane define the new vertex.
    std::vector<CutEdge>& cuts = cuts_;  // few: a cut of a convex cell crosses a handful of edges
    cuts.clear();
    const std::size_t nf = face_plane_.size();
    auto cut_of = [&](std::uint32_t a, std::uint32_t b) -> CutEdge& {
      const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
      for (CutEdge& c : cuts)
        if (c.a == lo && c.b == hi) return c;
      cuts.push_back(CutEdge{lo, hi, {0, 0}, 0, 0});
      return cuts.back();
    };
    for (std::size_t f = 0; f < nf; ++f) {
      const std::uint32_t begin = face_begin_[f], end = face_begin_[f + 1], len = end - begin;
      for (std::uint32_t k = 0; k < len; ++k) {
        const std::uint32_t a = face_verts_[begin + k], b = face_verts_[begin + (k + 1) % len];
        if (signs_[a] * signs_[b] < 0) {
          CutEdge& c = cut_of(a, b);
          if (c.count < 2) c.faces[c.count] = face_plane_[f];
          ++c.count;
        }
      }
    }
    // Renumber: kept old vertices first, then the new ones.
    std::vector<std::uint32_t>& renumber = scratch_a_;
    renumber.assign(m, 0xFFFFFFFFu);
    next_verts_.clear();
    for (std::size_t i = 0; i < m; ++i)
      if (signs_[i] <= 0) {
        renumber[i] = std::uint32_t(next_verts_.size());
        next_verts_.push_back(verts_[i]);
      }
    std::vector<std::uint32_t>& on_plane_next = scratch_b_;  // new index -> next vertex on the new face
    for (CutEdge& c : cuts) {
      if (c.count != 2) throw std::logic_error("convex cell: a cut edge not shared by two faces");
      c.vertex = std::uint32_t(next_verts_.size());
      next_verts_.push_back(make_vertex({c.faces[0], c.faces[1], plane}));
    }
    const std::size_t nv = next_verts_.size();
    on_plane_next.assign(nv, 0xFFFFFFFFu);
    std::vector<std::uint32_t>& on_plane = scratch_c_;  // 1 if the new vertex lies on the new plane
    on_plane.assign(nv, 0);
    for (std::size_t i = 0; i < m; ++i)
      if (signs_[i] == 0) on_plane[renumber[i]] = 1;
    for (const CutEdge& c : cuts) on_plane[c.vertex] = 1;

    next_face_plane_.clear();
    next_face_begin_.assign(1, 0);
    next_face_verts_.clear();
    for (std::size_t f = 0; f < nf; ++f) {
      const std::uint32_t begin = face_begin_[f], end = face_begin_[f + 1], len = end - begin;
      const std::size_t start = next_face_verts_.size();
      for (std::uint32_t k = 0; k < len; ++k) {
        const std::uint32_t a = face_verts_[begin + k], b = face_verts_[begin + (k + 1) % len];
        if (signs_[a] <= 0) next_face_verts_.push_back(renumber[a]);
        if (signs_[a] * signs_[b] < 0) next_face_verts_.push_back(cut_of(a, b).vertex);
      }
      const std::size_t flen = next_face_verts_.size() - start;
      if (flen < 3) {  // the face was cut away, or only touches the new plane
        next_face_verts_.resize(start);
        continue;
      }
      // The face's edge on the new plane, p -> q in this face, is q -> p in the new face.
      for (std::size_t k = 0; k < flen; ++k) {
        const std::uint32_t p = next_face_verts_[start + k], q = next_face_verts_[start + (k + 1) % flen];
        if (on_plane[p] && on_plane[q]) on_plane_next[q] = p;
      }
      next_face_plane_.push_back(face_plane_[f]);
      next_face_begin_.push_back(std::uint32_t(next_face_verts_.size()));
    }
    // The new face: follow the chain of on-plane edges.
    std::uint32_t startv = 0xFFFFFFFFu;
    std::size_t chain = 0;
    for (std::uint32_t i = 0; i < nv; ++i)
      if (on_plane_next[i] != 0xFFFFFFFFu) {
        ++chain;
        if (startv == 0xFFFFFFFFu) startv = i;
      }
    if (chain < 3) throw std::logic_error("convex cell: the cut face has fewer than three edges");
    std::size_t walked = 0;
    std::uint32_t cur = startv;
    do {
      next_face_verts_.push_back(cur);
      cur = on_plane_next[cur];
      if (cur == 0xFFFFFFFFu || ++walked > chain) throw std::logic_error("convex cell: the cut face is not a cycle");
    } while (cur != startv);
    if (walked != chain) throw std::logic_error("convex cell: the cut face has two cycles");
    next_face_plane_.push_back(plane);
    next_face_begin_.push_back(std::uint32_t(next_face_verts_.size()));

    // Drop old vertices no kept face uses (a sign-0 vertex whose faces all went away).
    std::vector<std::uint32_t>& used = scratch_a_;
    used.assign(nv, 0);
    for (std::uint32_t x : next_face_verts_) used[x] = 1;
    std::vector<std::uint32_t>& compact = scratch_b_;
    compact.assign(nv, 0);
    verts_.clear();
    for (std::uint32_t i = 0; i < nv; ++i)
      if (used[i]) {
        compact[i] = std::uint32_t(verts_.size());
        verts_.push_back(next_verts_[i]);
      }
    for (std::uint32_t& x : next_face_verts_) x = compact[x];
    face_plane_.swap(next_face_plane_);
    face_begin_.swap(next_face_begin_);
    face_verts_.swap(next_face_verts_);
    return true;
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
  for (const Vertex& vtx : verts_) best = std::max(best, vtx.r2);
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

template class ConvexCell<2>;
template class ConvexCell<3>;

}  // namespace shoremesh::engine
