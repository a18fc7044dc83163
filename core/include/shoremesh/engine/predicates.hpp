#pragma once
// One predicates module. Every geometric decision is the sign of a polynomial in double coordinates,
// written once as a generic lambda and evaluated first in interval arithmetic (CGAL::Interval_nt, a
// filter that costs a few doubles) and, only when the interval contains zero, exactly in GMP rationals.
// Interval_nt<false> requires the FPU to round upwards: callers hold a RoundingGuard while deciding.
#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>

#include <array>
#include <cstdint>

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

// sign(|a-b|^2 - |c-d|^2), exact.
template <int D>
int compare_squared_distances(PredicateCounters& counters, const Point<D>& a, const Point<D>& b, const Point<D>& c,
                              const Point<D>& d) {
  return filtered_sign(counters, [&](auto zero) {
    using NT = decltype(zero);
    return squared_distance<NT, D>(a, b) - squared_distance<NT, D>(c, d);
  });
}

// sign(|a-b|^2 - k |c-d|^2) for a double k (rho^2, beta^2), exact.
template <int D>
int compare_squared_distance_scaled(PredicateCounters& counters, const Point<D>& a, const Point<D>& b, double k,
                                    const Point<D>& c, const Point<D>& d) {
  return filtered_sign(counters, [&](auto zero) {
    using NT = decltype(zero);
    return squared_distance<NT, D>(a, b) - NT(k) * squared_distance<NT, D>(c, d);
  });
}

// sign(|a-b|^2 - t) for a double threshold t, exact.
template <int D>
int compare_squared_distance_to(PredicateCounters& counters, const Point<D>& a, const Point<D>& b, double t) {
  return filtered_sign(counters, [&](auto zero) {
    using NT = decltype(zero);
    return squared_distance<NT, D>(a, b) - NT(t);
  });
}

}  // namespace shoremesh::engine
