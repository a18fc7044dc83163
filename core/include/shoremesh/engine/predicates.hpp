#pragma once
// One predicates module. Every geometric decision is the sign of a polynomial in double coordinates,
// written once as a generic lambda and evaluated first in interval arithmetic (CGAL::Interval_nt, a
// filter that costs a few doubles) and, only when the interval contains zero, exactly in GMP rationals.
// The distance comparisons try plain doubles with an error bound first (semi_static_sign).
// Interval_nt<false> requires the FPU to round upwards: callers hold a RoundingGuard while deciding.
#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "shoremesh/point.hpp"

namespace shoremesh::engine {

using Interval = CGAL::Interval_nt<false>;
using Exact = CGAL::Gmpq;
using RoundingGuard = CGAL::Protect_FPU_rounding<true>;

struct PredicateCounters {
  std::uint64_t calls = 0;
  std::uint64_t exact = 0;
};

inline constexpr int kUndecided = 2;

inline int interval_sign(const Interval& x) {
  if (x.inf() > 0) return 1;
  if (x.sup() < 0) return -1;
  if (x.inf() == 0 && x.sup() == 0) return 0;
  return kUndecided;
}

// Sign of f(NT(0)) where f is generic in its number type: the interval filter, then exact rationals.
template <class F>
int filtered_sign(PredicateCounters& counters, F&& f) {
  ++counters.calls;
  const int s = interval_sign(f(Interval(0)));
  if (s != kUndecided) return s;
  ++counters.exact;
  return int(CGAL::sign(f(Exact(0))));
}

template <class NT, int D>
NT squared_distance(const Point<D>& a, const Point<D>& b) {
  NT s(0);
  for (int i = 0; i < D; ++i) {
    const NT d = NT(a[i]) - NT(b[i]);
    s += d * d;
  }
  return s;
}

// A first, cheaper filter for the distance comparisons: the sign of p - q, where p and q >= 0 were
// computed in doubles, each from at most D rounded differences of coordinates in [0, 1], their rounded
// squares and sums, and at most one more rounded product by a constant. Whatever the rounding mode, each
// operation errs by at most 2^-52 of its result, so the computed p - q is within (D + 5) 2^-52 (p + q)
// of the true difference: a margin of 1e-14 (p + q) is over ten times that. Below 1e-200 the squares
// may have lost precision to underflow, and the filter abstains.
inline int semi_static_sign(double p, double q) {
  const double sum = p + q;
  if (!(sum > 1e-200)) return kUndecided;
  const double s = p - q, margin = 1e-14 * sum;
  if (s > margin) return 1;
  if (s < -margin) return -1;
  return kUndecided;
}

// The same, after the semi-static stage: its sign when it decided, else the filtered one.
template <class F>
int filtered_sign(PredicateCounters& counters, int semi_static, F&& f) {
  if (semi_static == kUndecided) return filtered_sign(counters, f);
  ++counters.calls;
  return semi_static;
}

// sign(|a-b|^2 - |c-d|^2), exact.
template <int D>
int compare_squared_distances(PredicateCounters& counters, const Point<D>& a, const Point<D>& b, const Point<D>& c,
                              const Point<D>& d) {
  const int fast = semi_static_sign(squared_distance<double, D>(a, b), squared_distance<double, D>(c, d));
  return filtered_sign(counters, fast, [&](auto zero) {
    using NT = decltype(zero);
    return squared_distance<NT, D>(a, b) - squared_distance<NT, D>(c, d);
  });
}

// sign(|a-b|^2 - k |c-d|^2) for a double k (rho^2, beta^2), exact.
template <int D>
int compare_squared_distance_scaled(PredicateCounters& counters, const Point<D>& a, const Point<D>& b, double k,
                                    const Point<D>& c, const Point<D>& d) {
  const int fast = k >= 0 ? semi_static_sign(squared_distance<double, D>(a, b), k * squared_distance<double, D>(c, d))
                          : kUndecided;
  return filtered_sign(counters, fast, [&](auto zero) {
    using NT = decltype(zero);
    return squared_distance<NT, D>(a, b) - NT(k) * squared_distance<NT, D>(c, d);
  });
}

// sign(|a-b|^2 - t) for a double threshold t, exact.
template <int D>
int compare_squared_distance_to(PredicateCounters& counters, const Point<D>& a, const Point<D>& b, double t) {
  const int fast = t >= 0 ? semi_static_sign(squared_distance<double, D>(a, b), t) : kUndecided;
  return filtered_sign(counters, fast, [&](auto zero) {
    using NT = decltype(zero);
    return squared_distance<NT, D>(a, b) - NT(t);
  });
}

// sign((a - c) x (b - c)): +1 when a, b, c turn counter-clockwise, -1 clockwise, 0 collinear; exact.
// Plain doubles decide first with Shewchuk's static error bound (orient2dfast; no rounding mode needed), then
// intervals under a RoundingGuard of its own, then rationals.
inline int orient2d(PredicateCounters& counters, const Point2& a, const Point2& b, const Point2& c) {
  ++counters.calls;
  const double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  const double detright = (a[1] - c[1]) * (b[0] - c[0]);
  const double det = detleft - detright;
  const double errbound = 3.3306690738754716e-16 * (std::abs(detleft) + std::abs(detright));  // (3 + 16 eps) eps
  // The bound is relative: it holds only while no product underflows.
  if (errbound > 1e-280) {
    if (det > errbound) return 1;
    if (-det > errbound) return -1;
  }
  --counters.calls;
  const RoundingGuard guard;
  return filtered_sign(counters, [&](auto zero) {
    using NT = decltype(zero);
    return (NT(a[0]) - NT(c[0])) * (NT(b[1]) - NT(c[1])) - (NT(a[1]) - NT(c[1])) * (NT(b[0]) - NT(c[0]));
  });
}

// The circumcentre of the simplex `corners` (D + 1 points) in number type NT: exact in Exact, an
// enclosure in Interval (under a RoundingGuard). With u_i = corners[i] - corners[0], it is
// corners[0] + n / (2 det), det = det(u_1 .. u_D) and n a polynomial in the u_i (Cramer's rule).
// False, with c unset, when det is zero (a flat simplex has none) or, in intervals, may be.
template <class NT, int D>
bool circumcentre(const std::array<Point<D>, D + 1>& corners, std::array<NT, D>& c) {
  static_assert(D == 2 || D == 3);
  std::array<std::array<NT, D>, D> u;
  std::array<NT, D> uu;
  for (int i = 0; i < D; ++i) {
    uu[i] = NT(0);
    for (int k = 0; k < D; ++k) {
      u[i][k] = NT(corners[i + 1][k]) - NT(corners[0][k]);
      uu[i] += u[i][k] * u[i][k];
    }
  }
  std::array<NT, D> n;
  NT det;
  if constexpr (D == 2) {
    n = {u[1][1] * uu[0] - u[0][1] * uu[1], u[0][0] * uu[1] - u[1][0] * uu[0]};
    det = u[0][0] * u[1][1] - u[0][1] * u[1][0];
  } else {
    auto cross = [](const std::array<NT, 3>& a, const std::array<NT, 3>& b) {
      return std::array<NT, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    };
    const auto vw = cross(u[1], u[2]), wu = cross(u[2], u[0]), uv = cross(u[0], u[1]);
    for (int k = 0; k < 3; ++k) n[k] = uu[0] * vw[k] + uu[1] * wu[k] + uu[2] * uv[k];
    det = u[0][0] * vw[0] + u[0][1] * vw[1] + u[0][2] * vw[2];
  }
  if constexpr (std::is_same_v<NT, Interval>) {
    if (interval_sign(det) == 0 || interval_sign(det) == kUndecided) return false;
  } else {
    if (CGAL::sign(det) == CGAL::ZERO) return false;
  }
  const NT twice = NT(2) * det;
  for (int k = 0; k < D; ++k) c[k] = NT(corners[0][k]) + n[k] / twice;
  return true;
}

}  // namespace shoremesh::engine
