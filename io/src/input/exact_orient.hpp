#pragma once
// Internal: the exact sign of the 2D orientation determinant of double inputs, header-only.
//
// orient2d(a, b, c) = (a - c) x (b - c). A floating-point evaluation is used when Shewchuk's static error
// bound proves its sign; otherwise the determinant is expanded into its six products of input coordinates
//   ax*by - ax*cy - ay*bx + ay*cx + bx*cy - by*cx,
// each split exactly into two doubles with an FMA (TwoProduct), and the twelve doubles are summed without any
// rounding into a nonoverlapping expansion (Shewchuk's Grow-Expansion with TwoSum). The sign of an expansion
// is the sign of its largest component, so the result is exact for every finite input whose products neither
// overflow nor underflow (coordinates between about 1e-140 and 1e150 in magnitude, or exactly zero).
// Needs IEEE round-to-nearest arithmetic: never compile with -ffast-math.
#include <array>
#include <cmath>

#include "shoremesh/point.hpp"

namespace shoremesh::io::detail {

inline void two_sum(double a, double b, double& s, double& err) {
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
  err = (a - av) + (b - bv);
}

inline void two_product(double a, double b, double& p, double& err) {
  p = a * b;
  err = std::fma(a, b, -p);
}

// Sign of the exact sum of n doubles (n <= 16).
inline int exact_sum_sign(const double* terms, int n) {
  std::array<double, 16> e{};
  int m = 0;  // expansion e[0..m), increasing magnitude, nonoverlapping, no zeros
  for (int t = 0; t < n; ++t) {
    double q = terms[t];
    int k = 0;
    for (int i = 0; i < m; ++i) {
      double h;
      two_sum(q, e[i], q, h);
      if (h != 0) e[k++] = h;
    }
    if (q != 0) e[k++] = q;
    m = k;
  }
  if (m == 0) return 0;
  return e[m - 1] > 0 ? 1 : -1;
}

// +1 when a, b, c turn counter-clockwise, -1 clockwise, 0 collinear; exact.
inline int orient2d_sign(const Point2& a, const Point2& b, const Point2& c) {
  const double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  const double detright = (a[1] - c[1]) * (b[0] - c[0]);
  const double det = detleft - detright;
  const double errbound = 3.3306690738754716e-16 * (std::abs(detleft) + std::abs(detright));  // (3 + 16 eps) eps
  if (det > errbound) return 1;
  if (-det > errbound) return -1;
  std::array<double, 12> t{};
  two_product(a[0], b[1], t[0], t[1]);
  two_product(-a[0], c[1], t[2], t[3]);
  two_product(-a[1], b[0], t[4], t[5]);
  two_product(a[1], c[0], t[6], t[7]);
  two_product(b[0], c[1], t[8], t[9]);
  two_product(-b[1], c[0], t[10], t[11]);
  return exact_sum_sign(t.data(), 12);
}

}  // namespace shoremesh::io::detail
