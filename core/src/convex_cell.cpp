#include "shoremesh/engine/convex_cell.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
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
    case Kind::Through:
      // s orient2d(v, x, v + y) = s (d0 y1 - d1 y0) >= 0, d = x - v  <=>  (s d1, -s d0).y <= 0.
      if constexpr (D == 2) {
        const NT s(c.value);
        const NT d0 = NT(c.other_point[0]) - NT(v[0]), d1 = NT(c.other_point[1]) - NT(v[1]);
        n[0] = s * d1;
        n[1] = -(s * d0);
        b = NT(0);
      }
      break;
  }
}

// A nonnegative double whose difference is a sum: Cramer's rule evaluated in it is the permanent of the
// magnitudes, every term counted positive, which bounds what rounding does to the determinant.
struct Magnitude {
  double x = 0;
  friend Magnitude operator*(Magnitude a, Magnitude b) { return {a.x * b.x}; }
  friend Magnitude operator+(Magnitude a, Magnitude b) { return {a.x + b.x}; }
  friend Magnitude operator-(Magnitude a, Magnitude b) { return {a.x + b.x}; }
};

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

// Cramer's rule for the D x D system rows n_k . y = b_k, before the division: y_i = num[i] / det
// (generic in the number type).
template <class NT>
void cramer(const std::array<std::array<NT, 2>, 2>& n, const std::array<NT, 2>& b, NT& det, std::array<NT, 2>& num) {
  det = n[0][0] * n[1][1] - n[0][1] * n[1][0];
  num = {b[0] * n[1][1] - n[0][1] * b[1], n[0][0] * b[1] - b[0] * n[1][0]};
}

template <class NT>
void cramer(const std::array<std::array<NT, 3>, 3>& n, const std::array<NT, 3>& b, NT& det, std::array<NT, 3>& num) {
  // Columns of the system matrix are (n[0][j], n[1][j], n[2][j]).
  std::array<NT, 3> c0{n[0][0], n[1][0], n[2][0]}, c1{n[0][1], n[1][1], n[2][1]}, c2{n[0][2], n[1][2], n[2][2]};
  // det(c0, c1, c2) and det(b, c1, c2) share the minors of (c1, c2).
  const std::array<NT, 3> m12 = minors(c1, c2);
  det = expand(c0, m12);
  num = {expand(b, m12), det3(c0, b, c2), det3(c0, c1, b)};
}

template <class NT, std::size_t D>
std::array<NT, D> solve(const std::array<std::array<NT, D>, D>& n, const std::array<NT, D>& b) {
  NT det;
  std::array<NT, D> num;
  cramer(n, b, det, num);
  for (NT& x : num) x = x / det;
  return num;
}

// The vertex of planes n_k . y = b_k enclosed without interval arithmetic (which took a quarter of a
// 3D update's instructions): Cramer's rule in doubles from the lower ends of the planes' intervals, its
// error bounded by the same rule on magnitudes (Magnitude: the permanent). Under upward rounding (a
// RoundingGuard), eps = 2^-52 bounds one operation's error relative to its result, and:
//  - each exact coefficient lies in its interval, within the interval's width w of the lower end x,
//    and w <= 2^-50 |x| (Constraint::narrow); m = |x| + w bounds both. A product of D coefficients
//    then moves by at most D 2^-50 times the product of their m: the determinant and the numerators
//    of the lower ends differ from the exact ones by at most D 2^-50 perm(m);
//  - evaluating them in doubles errs by at most 5 eps perm(m) (products, minors, expansion);
//  - gamma perm(m) with gamma = 2e-14 bounds both (over four times their sum), and the division adds
//    (A + |y| B) / (|det| - B) + 2 eps |y| for numerator and determinant errors A and B.
// Returns false, and the caller solves in intervals, for a wide plane, a determinant not clearly away
// from zero, or magnitudes small enough to underflow (0.1 % of the 3D vertices in a test run).
template <int D>
bool solve_semi_static(const std::array<const Constraint<D>*, D>& planes, std::array<Interval, D>& y) {
  std::array<std::array<double, D>, D> nv;
  std::array<std::array<Magnitude, D>, D> nm;
  std::array<double, D> bv;
  std::array<Magnitude, D> bm;
  for (int k = 0; k < D; ++k) {
    const Constraint<D>& c = *planes[k];
    if (!c.narrow) return false;
    for (int i = 0; i < D; ++i) {
      nv[k][i] = c.n[i].inf();
      nm[k][i].x = c.n_magnitude[i];
    }
    bv[k] = c.b.inf();
    bm[k].x = c.b_magnitude;
  }
  double det;
  std::array<double, D> num;
  cramer(nv, bv, det, num);
  Magnitude det_bound;
  std::array<Magnitude, D> num_bound;
  cramer(nm, bm, det_bound, num_bound);
  constexpr double gamma = 2e-14, tiny = 1e-200;
  const double det_error = gamma * det_bound.x;
  if (!(det_bound.x > tiny) || !(std::abs(det) > 2 * det_error) || !std::isfinite(det_bound.x)) return false;
  const double below = -(det_error - std::abs(det));  // at most |det| - det_error (rounding is upward)
  for (int i = 0; i < D; ++i) {
    if (num_bound[i].x != 0 && !(num_bound[i].x > tiny)) return false;
    const double yi = num[i] / det, a = std::abs(yi);
    const double e = (gamma * num_bound[i].x + a * det_error * (1 + 0x1p-50)) / below + 0x1p-51 * a;
    y[i] = Interval(-(e - yi), yi + e);
  }
  return true;
}

// 3D: the same rule on a double and its Magnitude side by side, the two lanes of one SSE2 register
// (x86-64's baseline): each lane rounds as the scalar operation would (a difference is the sum with the
// negated operand, which IEEE 754 defines it to be; the magnitude lane adds), so the bits are those of
// the two scalar evaluations above, at half the instructions.
using Lanes = double __attribute__((vector_size(16)));
using LaneBits = std::uint64_t __attribute__((vector_size(16)));
struct ValueAndMagnitude {
  Lanes x;
  friend ValueAndMagnitude operator*(ValueAndMagnitude a, ValueAndMagnitude b) { return {a.x * b.x}; }
  friend ValueAndMagnitude operator+(ValueAndMagnitude a, ValueAndMagnitude b) { return {a.x + b.x}; }
  friend ValueAndMagnitude operator-(ValueAndMagnitude a, ValueAndMagnitude b) {
    const LaneBits value_sign = {std::uint64_t(1) << 63, 0};
    return {a.x + Lanes(LaneBits(b.x) ^ value_sign)};
  }
};

template <>
bool solve_semi_static<3>(const std::array<const Constraint<3>*, 3>& planes, std::array<Interval, 3>& y) {
  constexpr int D = 3;
  std::array<std::array<ValueAndMagnitude, D>, D> n;
  std::array<ValueAndMagnitude, D> b;
  for (int k = 0; k < D; ++k) {
    const Constraint<D>& c = *planes[k];
    if (!c.narrow) return false;
    for (int i = 0; i < D; ++i) n[k][i].x = Lanes{c.n[i].inf(), c.n_magnitude[i]};
    b[k].x = Lanes{c.b.inf(), c.b_magnitude};
  }
  ValueAndMagnitude det_pair;
  std::array<ValueAndMagnitude, D> num;
  cramer(n, b, det_pair, num);
  const double det = det_pair.x[0], det_bound = det_pair.x[1];
  constexpr double gamma = 2e-14, tiny = 1e-200;
  const double det_error = gamma * det_bound;
  if (!(det_bound > tiny) || !(std::abs(det) > 2 * det_error) || !std::isfinite(det_bound)) return false;
  for (int i = 0; i < D; ++i)
    if (num[i].x[1] != 0 && !(num[i].x[1] > tiny)) return false;
  const double below = -(det_error - std::abs(det));  // at most |det| - det_error (rounding is upward)
  // Coordinates 0 and 1 in one register, 2 alone: the same operations per coordinate as in 2D.
  const Lanes yv = Lanes{num[0].x[0], num[1].x[0]} / det;
  const LaneBits magnitude_bits = {~(std::uint64_t(1) << 63), ~(std::uint64_t(1) << 63)};
  const Lanes av = Lanes(LaneBits(yv) & magnitude_bits);
  const Lanes ev = (gamma * Lanes{num[0].x[1], num[1].x[1]} + av * det_error * (1 + 0x1p-50)) / below + 0x1p-51 * av;
  for (int i = 0; i < 2; ++i) y[i] = Interval(-(ev[i] - yv[i]), yv[i] + ev[i]);
  const double y2 = num[2].x[0] / det, a2 = std::abs(y2);
  const double e2 = (gamma * num[2].x[1] + a2 * det_error * (1 + 0x1p-50)) / below + 0x1p-51 * a2;
  y[2] = Interval(-(e2 - y2), y2 + e2);
  return true;
}

double midpoint(const Interval& x) { return 0.5 * (x.inf() + x.sup()); }

}  // namespace

template <int D>
std::uint16_t ConvexCell<D>::add_constraint(const Constraint<D>& c) {
  if (constraints_.size() >= 0xFFFF) throw std::logic_error("convex cell: too many constraints");
  constraints_.push_back(c);
  Constraint<D>& k = constraints_.back();
  plane_of<Interval, D>(k, v_, k.n, k.b);
  set_magnitudes(k);
  return std::uint16_t(constraints_.size() - 1);
}

// Only the vertex solve reads them: a bisector that cuts nothing (two in three in 3D) never needs them.
template <int D>
void ConvexCell<D>::set_magnitudes(Constraint<D>& k) {
  // Magnitudes rounded upward (the caller holds a RoundingGuard): each bounds the exact coefficient.
  k.narrow = true;
  auto magnitude = [&](const Interval& x) {
    const double width = x.sup() - x.inf();
    k.narrow = k.narrow && width <= 0x1p-50 * std::abs(x.inf());
    return std::abs(x.inf()) + width;
  };
  for (int i = 0; i < D; ++i) k.n_magnitude[i] = magnitude(k.n[i]);
  k.b_magnitude = magnitude(k.b);
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
void ConvexCell<D>::make_vertex(const std::array<std::uint16_t, D>& planes, Vertex& vtx) {
  vtx.planes = planes;
  // A 3D vertex is solved from its planes in distance order, whatever their orientation: the order in
  // which a from-scratch run numbers them (plane order), also between the out-of-order cuts.
  std::array<std::uint16_t, D> order = planes;
  if constexpr (D == 3) {
    vtx.serial = vtx.place = next_serial_++;
    auto sort3 = [&](auto&& less) {
      if (less(order[1], order[0])) std::swap(order[0], order[1]);
      if (less(order[2], order[1])) std::swap(order[1], order[2]);
      if (less(order[1], order[0])) std::swap(order[0], order[1]);
    };
    if (out_of_order_)
      sort3([&](std::uint16_t a, std::uint16_t b) { return before_in_distance_order(a, b); });
    else
      sort3(std::less<std::uint16_t>());
  }
  std::array<const Constraint<D>*, D> rows;
  for (int k = 0; k < D; ++k) rows[k] = &constraints_[order[k]];
  if (!solve_semi_static<D>(rows, vtx.y)) {
    std::array<std::array<Interval, D>, D> n;
    std::array<Interval, D> b;
    for (int k = 0; k < D; ++k) {
      n[k] = rows[k]->n;
      b[k] = rows[k]->b;
    }
    vtx.y = solve(n, b);
  }
  // Nearly dependent planes (grids: two bisectors mirror images across a third, up to the rounding of
  // the points) give an enclosure far wider than the point: every filter on this vertex then goes exact,
  // and a construction that reads its midpoint (the Steiner point's direction) aims at nothing near it.
  // Such a vertex is solved exactly and enclosed tightly; the exact solution depends on the planes only.
  // Wide: any coordinate's enclosure wider than 2^-20 of the vertex's largest coordinate (relative to the
  // vertex, not to each coordinate: one near 0 is solved as tightly as the others, in absolute terms).
  double scale = 0;
  for (int i = 0; i < D; ++i) scale = std::max({scale, std::abs(vtx.y[i].inf()), std::abs(vtx.y[i].sup())});
  bool wide = false;
  for (int i = 0; i < D; ++i)
    if (!(vtx.y[i].sup() - vtx.y[i].inf() <= 0x1p-20 * scale)) wide = true;
  if (wide) {
    ++counters_.exact;
    const std::array<Exact, D>& exact = exact_position(vtx);
    for (int i = 0; i < D; ++i) {
      const std::pair<double, double> r = CGAL::to_interval(exact[i]);
      vtx.y[i] = Interval(r.first, r.second);
    }
  }
  // Rounded upward (the caller holds a RoundingGuard): an upper bound.
  for (int i = 0; i < D; ++i) {
    const double m = std::max(std::abs(vtx.y[i].inf()), std::abs(vtx.y[i].sup()));
    vtx.r2 += m * m;
  }
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
bool ConvexCell<D>::same_point(std::size_t i, std::size_t j) {
  for (int k = 0; k < D; ++k)
    if (verts_[i].y[k].sup() < verts_[j].y[k].inf() || verts_[j].y[k].sup() < verts_[i].y[k].inf()) return false;
  ++counters_.exact;
  exact_position(verts_[i]);
  exact_position(verts_[j]);  // may grow exact_: compare by index, after both
  return exact_[std::size_t(verts_[i].exact)] == exact_[std::size_t(verts_[j].exact)];
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
  balls_stale_ = true;
  next_serial_ = 0;
  using Kind = typename Constraint<D>::Kind;
  // Constraint 2*axis is x[axis] >= lo, 2*axis+1 is x[axis] <= hi.
  for (int a = 0; a < D; ++a) {
    Constraint<D> mn;
    mn.kind = Kind::AxisMin;
    mn.axis = std::uint8_t(a);
    mn.value = lo[a];
    add_constraint(mn);
    Constraint<D> mx;
    mx.kind = Kind::AxisMax;
    mx.axis = std::uint8_t(a);
    mx.value = hi[a];
    add_constraint(mx);
  }
  auto corner = [&](int bits) {
    std::array<std::uint16_t, D> planes;
    for (int a = 0; a < D; ++a) planes[a] = std::uint16_t(2 * a + ((bits >> a) & 1));
    // 3D: (x, y, z) is counter-clockwise seen from outside when the outward normals (+-e_x, +-e_y,
    // +-e_z) have a positive determinant, that is when an even number of them point down; else (x, z, y).
    if (D == 3 && std::popcount(unsigned(bits)) % 2 == 0) std::swap(planes[1], planes[2]);
    make_vertex(planes, verts_.emplace_back());
  };
  if constexpr (D == 2) {
    // Counter-clockwise; edge i runs from vertex i to vertex i+1.
    for (int bits : {0, 1, 3, 2}) corner(bits);
    edges_ = {2, 1, 3, 0};  // y >= lo, x <= hi, y <= hi, x >= lo
  } else {
    for (int bits = 0; bits < 8; ++bits) corner(bits);
  }
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
    // Scratch kept between calls (the cache updates cells this way all through a propagation).
    auto& order = order_scratch_;
    auto& renamed = renamed_scratch_;
    auto& sorted = sorted_scratch_;
    order.resize(m);
    for (std::size_t k = 0; k < m; ++k) order[k] = std::uint16_t(k);
    std::sort(order.begin(), order.end(), [&](std::uint16_t a, std::uint16_t b) { return before_in_distance_order(a, b); });
    renamed.resize(m);
    sorted.resize(m);
    for (std::size_t k = 0; k < m; ++k) {
      renamed[order[k]] = std::uint16_t(k);
      sorted[k] = constraints_[order[k]];
    }
    constraints_.swap(sorted);
    // A vertex keeps its planes' orientation; its coordinates were solved in distance order already.
    for (Vertex& vtx : verts_)
      for (std::uint16_t& plane : vtx.planes) plane = renamed[plane];
  }
}

template <int D>
bool ConvexCell<D>::clip(VertexId w, const Point<D>& wp, double d2) {
  if (constraints_.size() >= 0xFFFF) throw std::logic_error("convex cell: too many constraints");
  // Built in place, and forgotten again when it cuts nothing (it bounds nothing then).
  Constraint<D>& c = constraints_.emplace_back();
  c.kind = Constraint<D>::Kind::Bisector;
  c.other = w;
  c.other_point = wp;
  c.order_d2 = d2;
  plane_of<Interval, D>(c, v_, c.n, c.b);
  return cut_by_last();
}

template <int D>
bool ConvexCell<D>::cut_by_last() {
  const std::uint16_t plane = std::uint16_t(constraints_.size() - 1);
  if (!mark_sides(plane)) {
    constraints_.pop_back();
    return false;
  }
  set_magnitudes(constraints_[plane]);
  if constexpr (D == 2)
    clip_polygon(plane);
  else
    clip_polyhedron(plane);
  balls_stale_ = true;
  return true;
}

template <int D>
bool ConvexCell<D>::clip_through_site(const Point<D>& x, int side) {
  if constexpr (D != 2) {
    (void)x, (void)side;
    throw std::logic_error("convex cell: a half-plane through the site is for 2D cells");
  } else {
    if (constraints_.size() >= 0xFFFF) throw std::logic_error("convex cell: too many constraints");
    Constraint<D>& c = constraints_.emplace_back();
    c.kind = Constraint<D>::Kind::Through;
    c.other_point = x;
    c.value = side > 0 ? 1.0 : -1.0;
    c.order_d2 = std::numeric_limits<double>::infinity();
    plane_of<Interval, D>(c, v_, c.n, c.b);
    return cut_by_last();
  }
}

namespace {
// A plane's bounds on n.y - b for a vertex's interval box y, as side() would compute them (the caller holds
// a RoundingGuard, so each product's largest corner and the sum are rounded upward): the upper end of
// side()'s interval, at a quarter of its cost. The largest corner of n_k y_k lies at y_k's upper end where
// n_k >= 0 (both ends of n_k's interval), at its lower end where n_k <= 0: two products per coordinate
// instead of four, the same maximum (the products are rounded upward, which keeps their order). An n_k
// whose interval holds zero inside (none: it is twice a difference of doubles, rounded outward) takes all
// four. A vertex nearer to v than half of |w - v| lies strictly inside a bisector's half-space
// (2 d.y <= 2 |d| |y| < |d|^2): no predicate needed. b encloses |d|^2 for a bisector; the axis planes of
// the initial box are never offered again.
template <int D>
struct SideBounds {
  std::array<double, D> n0, n1;
  std::array<bool, D> upper_end;
  bool by_sign = true;
  double inside_below = 0;
  double minus_b, b_sup;
  explicit SideBounds(const Constraint<D>& c) : minus_b(-c.b.inf()), b_sup(c.b.sup()) {
    inside_below = c.kind == Constraint<D>::Kind::Bisector ? 0.25 * c.b.inf() : 0.0;
    for (int i = 0; i < D; ++i) {
      n0[i] = c.n[i].inf();
      n1[i] = c.n[i].sup();
      upper_end[i] = n0[i] >= 0;
      by_sign = by_sign && (n0[i] >= 0 || n1[i] <= 0);
    }
  }
  // An upper bound on n.y - b: the upper end of side()'s interval.
  double upper(const std::array<Interval, D>& y) const {
    double s = minus_b;
    if (by_sign) {
      for (int k = 0; k < D; ++k) {
        const double yk = upper_end[k] ? y[k].sup() : y[k].inf();
        s += std::max(n0[k] * yk, n1[k] * yk);
      }
    } else {
      for (int k = 0; k < D; ++k) {
        const double y0 = y[k].inf(), y1 = y[k].sup();
        s += std::max(std::max(n0[k] * y0, n0[k] * y1), std::max(n1[k] * y0, n1[k] * y1));
      }
    }
    return s;
  }
  // By sign only: an upper bound on b - n.y, the negated lower end of side()'s interval (each product's
  // smallest corner and the sum, negated so that upward rounding rounds the lower end down).
  double upper_of_negation(const std::array<Interval, D>& y) const {
    double t = b_sup;
    for (int k = 0; k < D; ++k) {
      const double yk = upper_end[k] ? y[k].inf() : y[k].sup();
      t += std::max(-n0[k] * yk, -n1[k] * yk);
    }
    return t;
  }
};
}  // namespace

// signs_[i]: the side of vertex i; whether any lies strictly outside. The plane's coefficients and the
// counters are read into locals first: a store to signs_ (bytes) may alias anything, and would make the
// compiler read them again for every vertex.
template <int D>
bool ConvexCell<D>::mark_sides(std::uint16_t plane) {
  const std::size_t m = verts_.size();
  signs_.resize(m);
  std::int8_t* const signs = signs_.data();
  bool any_outside = false, on_plane = false;
  const SideBounds<D> bound(constraints_[plane]);
  std::uint64_t bounded = 0;  // decided by the upper bound: counted as the interval filter's calls
  for (std::size_t i = 0; i < m; ++i) {
    Vertex& vtx = verts_[i];
    if (vtx.r2 < bound.inside_below) {
      signs[i] = -1;
      continue;
    }
    // When the upper bound is negative, the vertex is strictly inside, which is what most vertices are.
    if (bound.upper(vtx.y) < 0) {
      ++bounded;
      signs[i] = -1;
      continue;
    }
    const int sign = side(vtx, plane);
    signs[i] = std::int8_t(sign);
    on_plane = on_plane || sign == 0;
    any_outside = any_outside || sign > 0;
  }
  counters_.calls += bounded;
  vertex_on_plane_ = vertex_on_plane_ || on_plane;
  return any_outside;
}

// 3D: the same signs as above, with a lower bound on n.y - b beside the upper one. A vertex beyond the
// plane (a cut removes about five) is then decided without side(): the bound is, operation for
// operation, the lower end of the interval side() computes (each product's smallest corner and the sum
// rounded down, here as the negated upper bound of -(n.y - b) under upward rounding), so it decides
// exactly when side()'s filter would, with the same sign and the same count.
template <>
bool ConvexCell<3>::mark_sides(std::uint16_t plane) {
  constexpr int D = 3;
  const std::size_t m = verts_.size();
  signs_.resize(m);
  std::int8_t* const signs = signs_.data();
  bool any_outside = false, on_plane = false;
  const SideBounds<D> bound(constraints_[plane]);
  std::uint64_t bounded = 0;  // decided by a bound: counted as the interval filter's calls
  // Most vertices lie inside the ball test (a clip that cuts nothing is two in three): a first pass
  // without branches lists the others, in chunks, and only those are bounded (a branch per vertex on
  // the ball test went the wrong way often enough to cost more than the test).
  constexpr std::size_t kChunk = 64;
  std::array<std::uint16_t, kChunk> open;
  for (std::size_t first = 0; first < m; first += kChunk) {
    const std::size_t last = std::min(m, first + kChunk);
    std::size_t count = 0;
    for (std::size_t i = first; i < last; ++i) {
      signs[i] = -1;
      open[count] = std::uint16_t(i - first);
      count += verts_[i].r2 < bound.inside_below ? 0 : 1;
    }
    for (std::size_t j = 0; j < count; ++j) {
      const std::size_t i = first + open[j];
      Vertex& vtx = verts_[i];
      if (bound.by_sign) {
        if (bound.upper(vtx.y) < 0) {
          ++bounded;
          continue;
        }
        if (bound.upper_of_negation(vtx.y) < 0) {
          ++bounded;
          signs[i] = 1;
          any_outside = true;
          continue;
        }
      } else if (bound.upper(vtx.y) < 0) {
        ++bounded;
        continue;
      }
      const int sign = side(vtx, plane);
      signs[i] = std::int8_t(sign);
      on_plane = on_plane || sign == 0;
      any_outside = any_outside || sign > 0;
    }
  }
  counters_.calls += bounded;
  vertex_on_plane_ = vertex_on_plane_ || on_plane;
  return any_outside;
}

template <int D>
void ConvexCell<D>::clip_polygon(std::uint16_t plane) {
  if constexpr (D == 2) {
    const std::size_t m = verts_.size();
    next_verts_.clear();
    next_edges_.clear();
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = i + 1 == m ? 0 : i + 1;
      const int si = signs_[i], sj = signs_[j];
      const std::uint16_t e = edges_[i];
      if (si <= 0) {
        next_verts_.push_back(verts_[i]);
        if (sj <= 0) {
          next_edges_.push_back(e);
        } else if (si < 0) {  // leaves the half-plane inside edge e
          next_edges_.push_back(e);
          make_vertex({e, plane}, next_verts_.emplace_back());
          next_edges_.push_back(plane);
        } else {  // vertex i lies on the new line: the boundary continues along it
          next_edges_.push_back(plane);
        }
      } else if (sj < 0) {  // re-enters inside edge e
        make_vertex({plane, e}, next_verts_.emplace_back());
        next_edges_.push_back(e);
      }
    }
    verts_.swap(next_verts_);
    edges_.swap(next_edges_);
  }
}

// rim_: the edges of cut_edges_ whose reverse is not among them. The planes met are numbered 0, 1, ... in
// the order they come (plane_local_, valid where plane_stamp_ holds this cut's stamp), and with at most 64
// of them (every cut seen in the tests) each one's outgoing edges are a bit row: a reverse is one bit
// test, with no table to clear or probe. More planes: an open-addressing table of the edges.
template <int D>
void ConvexCell<D>::find_rim() {
  rim_.clear();
  if (out_bits_.empty()) out_bits_.resize(64);
  if (plane_stamp_.size() < constraints_.size()) {
    plane_stamp_.resize(constraints_.size(), 0);
    plane_local_.resize(constraints_.size(), 0);
  }
  if (++stamp_ == 0) {  // wrapped: no stale stamp may equal a new one
    std::fill(plane_stamp_.begin(), plane_stamp_.end(), 0);
    stamp_ = 1;
  }
  std::uint32_t count = 0;
  auto local = [&](std::uint16_t p) {
    if (plane_stamp_[p] != stamp_) {
      plane_stamp_[p] = stamp_;
      plane_local_[p] = count < 64 ? std::uint8_t(count) : std::uint8_t(64);
      if (count < 64) out_bits_[count] = 0;
      ++count;
    }
    return plane_local_[p];
  };
  bool small = true;
  for (const PlanePair& e : cut_edges_) {
    const std::uint8_t a = local(e.a), b = local(e.b);
    if (a == 64 || b == 64) {
      small = false;
      break;
    }
    out_bits_[a] |= std::uint64_t(1) << b;
  }
  if (small) {
    std::uint64_t starts = 0;  // the rim's edges' first planes: a cycle has each once
    for (const PlanePair& e : cut_edges_) {
      const std::uint8_t a = plane_local_[e.a], b = plane_local_[e.b];
      if (!(out_bits_[b] >> a & 1)) {
        if (starts >> a & 1) throw std::logic_error("convex cell: the cut face is not one cycle");
        starts |= std::uint64_t(1) << a;
        rim_.push_back(e);
      }
    }
  } else {
    // The edges in a small open-addressing table (at most half full), so that finding each one's reverse
    // is O(1): pairwise it was a quarter of the cut's time.
    std::size_t slots = 32;
    while (slots < 2 * cut_edges_.size()) slots *= 2;
    edge_table_.assign(slots, kNoEdge);
    auto code = [](std::uint16_t a, std::uint16_t b) { return std::uint32_t(a) << 16 | b; };
    auto slot_of = [&](std::uint32_t c) {
      std::size_t k = std::size_t((c * 0x9E3779B1u) >> 16) & (slots - 1);
      while (edge_table_[k] != kNoEdge && edge_table_[k] != c) k = (k + 1) & (slots - 1);
      return k;
    };
    for (const PlanePair& e : cut_edges_) edge_table_[slot_of(code(e.a, e.b))] = code(e.a, e.b);
    for (const PlanePair& e : cut_edges_)
      if (edge_table_[slot_of(code(e.b, e.a))] == kNoEdge) rim_.push_back(e);
    for (const PlanePair& e : rim_)
      if (std::count_if(rim_.begin(), rim_.end(), [&](const PlanePair& f) { return f.a == e.a; }) != 1)
        throw std::logic_error("convex cell: the cut face is not one cycle");
  }
  // A cut of a convex cell removes a disc of triangles: its rim is one simple cycle.
  if (rim_.size() < 3) throw std::logic_error("convex cell: the cut face has fewer than three edges");
}

// The triangles of the vertices beyond the plane go; the directed edges among them whose reverse
// belongs to a kept triangle form the rim, a cycle around the plane's new face, and each rim edge a -> b
// gives the new vertex (a, b, plane) on the cell's edge it crosses, oriented as the triangle it replaces.
// signs_ holds the side of every vertex.
template <int D>
void ConvexCell<D>::clip_polyhedron(std::uint16_t plane) {
  if constexpr (D == 3) {
    // The vertices beyond go, the last one taking each one's slot (the cell's answers do not depend on
    // the vertices' order), their triangles' edges listed.
    cut_edges_.clear();
    for (std::size_t i = 0; i < verts_.size();) {
      if (signs_[i] <= 0) {
        ++i;
        continue;
      }
      const auto& p = verts_[i].planes;
      cut_edges_.push_back({p[0], p[1]});
      cut_edges_.push_back({p[1], p[2]});
      cut_edges_.push_back({p[2], p[0]});
      verts_[i] = verts_.back();
      signs_[i] = signs_[verts_.size() - 1];
      verts_.pop_back();
    }
    const std::size_t kept = verts_.size();
    find_rim();
    for (const PlanePair& e : rim_) make_vertex({e.a, e.b, plane}, verts_.emplace_back());
    // Treating a vertex on the plane as inside is the plane moved outward by an infinitesimal larger
    // than every earlier plane's: the triangles stay those of a simple polytope, and the rim one cycle.
    // Geometrically a new vertex may then be a kept vertex on the plane, or, once a cut met a vertex
    // (edges of length zero since), another new one: it names that place, so that each point counts
    // once (vertex_count, faces in bisector_neighbours).
    if (vertex_on_plane_)
      for (std::size_t j = kept; j < verts_.size(); ++j)
        for (std::size_t i = 0; i < j; ++i)
          if ((i >= kept || signs_[i] == 0) && verts_[i].first_at_its_point() && same_point(i, j)) {
            verts_[j].place = verts_[i].place;
            break;
          }
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
    if (!vtx.first_at_its_point()) continue;  // another vertex is the same point
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
bool ConvexCell<D>::vertex_boxes_hold_exact_positions() {
  for (Vertex& vtx : verts_) {
    const auto exact = exact_position(vtx);  // a copy: exact_ may grow for the next vertex
    for (int i = 0; i < D; ++i)
      if (exact[i] < Exact(vtx.y[i].inf()) || exact[i] > Exact(vtx.y[i].sup())) return false;
  }
  return true;
}

template <int D>
Point<D> ConvexCell<D>::farthest_vertex_offset() const {
  Point<D> best{};
  double best_d2 = -1;
  for (const Vertex& vtx : verts_) {
    if (!vtx.first_at_its_point()) continue;  // another vertex is the same point
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
    if (vtx.first_at_its_point()) best = std::max(best, vtx.r2);
  return best;
}

// The vertices' balls as surely_uncut_by_box reads them, and the box widened by the slack: whether the
// box keeps clear of vertex j's ball by the margin, from the squared distance between it and the vertex's
// interval box against the vertex's r2 (rounded upward under the caller's RoundingGuard; monotone in the
// box whatever the rounding: a smaller box's gap is never smaller).
namespace {
template <int D>
struct BallTest {
  const double* inf;
  const double* sup;
  const double* r2;
  std::size_t m;
  std::array<double, D> wide_lo, wide_hi;
  BallTest(const std::vector<double>& balls, std::size_t count, const Point<D>& lo, const Point<D>& hi)
      : inf(balls.data()), sup(balls.data() + D * count), r2(balls.data() + 2 * D * count), m(count) {
    // Differences of coordinates in [0, 1] err by at most an ulp of 1: the box is widened by four.
    constexpr double slack = 0x1p-50;
    for (int i = 0; i < D; ++i) {
      wide_lo[i] = lo[i] - slack;
      wide_hi[i] = hi[i] + slack;
    }
  }
  bool clear(std::size_t j) const {
    double gap2 = 0;  // the squared distance from the box to the vertex's interval box
    for (int i = 0; i < D; ++i) {
      const double above = wide_lo[i] - sup[std::size_t(i) * m + j];
      const double below = inf[std::size_t(i) * m + j] - wide_hi[i];
      const double gap = std::max(std::max(0.0, above), below);
      gap2 += gap * gap;
    }
    // Rounded upward, gap2 may exceed the true distance by a few ulps: far inside the margin.
    return gap2 > r2[j] * (1 + 1e-3);
  }
};
}  // namespace

template <int D>
void ConvexCell<D>::refresh_balls() const {
  const std::size_t m = verts_.size();
  balls_.resize((2 * D + 1) * m);
  for (std::size_t j = 0; j < m; ++j) {
    for (int i = 0; i < D; ++i) {
      balls_[std::size_t(i) * m + j] = verts_[j].y[i].inf();
      balls_[std::size_t(D + i) * m + j] = verts_[j].y[i].sup();
    }
    balls_[2 * D * m + j] = verts_[j].r2;
  }
  balls_stale_ = false;
  last_meeting_ = 0;
}

template <int D>
bool ConvexCell<D>::surely_uncut_by_box(const Point<D>& lo, const Point<D>& hi) const {
  if (balls_stale_) refresh_balls();
  const std::size_t m = verts_.size();
  const BallTest<D> test(balls_, m, lo, hi);
  // Which vertex is tried first changes nothing but the work: the box is let off only when it keeps
  // clear of every ball. The one that met the last box is tried first (the next box, a nearby point of
  // the same search, mostly meets it too).
  if (last_meeting_ < m && !test.clear(last_meeting_)) return false;
  for (std::size_t j = 0; j < m; ++j)
    if (!test.clear(j)) {
      last_meeting_ = std::uint32_t(j);
      return false;
    }
  return true;
}

// 2D: the constraints of the edges. 3D: the planes of the triangles; where a clip met a vertex exactly,
// only those planes that meet the cell in three or more distinct points (a face, not an edge or a point).
template <int D>
void ConvexCell<D>::bisector_neighbours(std::vector<VertexId>& out) const {
  out.clear();
  auto add = [&](std::uint16_t p) {
    if (constraints_[p].kind == Constraint<D>::Kind::Bisector) out.push_back(constraints_[p].other);
  };
  if constexpr (D == 2) {
    for (std::uint16_t p : edges_) add(p);
  } else if (!vertex_on_plane_) {
    // Each plane once (it is in every triangle around its face).
    auto& seen = plane_seen_;
    seen.assign(constraints_.size(), 0);
    for (const Vertex& vtx : verts_)
      for (std::uint16_t p : vtx.planes)
        if (!seen[p]) {
          seen[p] = 1;
          add(p);
        }
  } else {
    // (plane, place) pairs, sorted: a plane with three distinct places bounds a face.
    auto& pairs = plane_places_;
    pairs.clear();
    for (const Vertex& vtx : verts_)
      for (std::uint16_t p : vtx.planes) pairs.push_back(std::uint64_t(p) << 32 | vtx.place);
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    for (std::size_t k = 0; k + 2 < pairs.size(); ++k)
      if ((pairs[k] >> 32) == (pairs[k + 2] >> 32) && (k == 0 || (pairs[k - 1] >> 32) != (pairs[k] >> 32)))
        add(std::uint16_t(pairs[k] >> 32));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

template <int D>
void ConvexCell<D>::assign_geometry(const ConvexCell& other) {
  v_ = other.v_;
  constraints_ = other.constraints_;
  exact_ = other.exact_;
  verts_ = other.verts_;
  balls_stale_ = true;
  vertex_on_plane_ = other.vertex_on_plane_;
  edges_ = other.edges_;
  next_serial_ = other.next_serial_;
}

template <int D>
std::size_t ConvexCell<D>::memory_bytes() const {
  return constraints_.capacity() * sizeof(Constraint<D>) + exact_.capacity() * sizeof(exact_[0]) +
         (verts_.capacity() + next_verts_.capacity()) * sizeof(Vertex) + signs_.capacity() +
         (edges_.capacity() + next_edges_.capacity()) * sizeof(std::uint16_t) +
         (cut_edges_.capacity() + rim_.capacity()) * sizeof(PlanePair) + plane_places_.capacity() * sizeof(std::uint64_t) +
         plane_seen_.capacity() + edge_table_.capacity() * sizeof(std::uint32_t) +
         (order_scratch_.capacity() + renamed_scratch_.capacity()) * sizeof(std::uint16_t) +
         sorted_scratch_.capacity() * sizeof(Constraint<D>) + plane_stamp_.capacity() * sizeof(std::uint32_t) + plane_local_.capacity() + out_bits_.capacity() * sizeof(std::uint64_t) +
         balls_.capacity() * sizeof(double);
}

static_assert(sizeof(Constraint<2>) == 112 && sizeof(Constraint<3>) == 144);

template class ConvexCell<2>;
template class ConvexCell<3>;

}  // namespace shoremesh::engine
