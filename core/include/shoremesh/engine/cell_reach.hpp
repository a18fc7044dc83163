#pragma once
// How far an operation's cell reaches, direction by direction: whether a vertex inserted at v + d can
// cut the cell of v. Its bisector cuts the cell exactly when h(d) > |d|^2 / 2, h being the cell's
// support function (h(d) = max of y.d over the cell, y relative to v). The test the engine used alone,
// |d| <= 2 max |y|, bounds h(d) by max |y| |d|; in 3D it let 64 % of the inserted vertices it passed
// through rerun an operation that they could not change (2D: 41 %).
//
// This keeps h, rounded up, in the 3^D - 1 directions u of {-1, 0, 1}^D \ {0} (the faces, edges and
// corners of a cube around v). Any d is a nonnegative combination of at most D of them: with the
// |d_i| sorted, a1 >= a2 >= a3, on axes i1, i2, i3 and signs s,
//   d = (a1 - a2) s1 e_i1 + (a2 - a3) (s1 e_i1 + s2 e_i2) + a3 (s1 e_i1 + s2 e_i2 + s3 e_i3),
// and h is sublinear (h(x + y) <= h(x) + h(y), h(l x) = l h(x) for l >= 0), so the same combination of
// the kept values bounds h(d) from above. A round cell's bound is within about 8 % (2D) of h.
// The values are stored in a byte each, rounded up in units of the largest, and the unit as a power of two
// in one byte (its exponent, rounded up: the largest value takes 128 to 254 units): 9 bytes in 2D, 27 in
// 3D, kept in every operation.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "shoremesh/engine/predicates.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::engine {

template <int D>
class CellReach {
 public:
  // Direction u has code sum (u_i + 1) 3^i, kept at slot code, less one above the zero vector's code
  // (never asked: h = 0 there).
  static constexpr int kCodes = D == 2 ? 9 : 27;
  static constexpr int kZeroCode = (kCodes - 1) / 2;

  // A cell of unknown shape: every vertex may cut it.
  static CellReach unbounded() { return CellReach{}; }

  // From the cell's vertices, given as interval boxes relative to v through for_each_vertex(f), which
  // calls f(const std::array<Interval, D>&) once per vertex. Under a RoundingGuard (upward rounding).
  template <class ForEachVertex>
  static CellReach of(ForEachVertex&& for_each_vertex) {
    std::array<double, kCodes> h;
    h.fill(-std::numeric_limits<double>::infinity());
    for_each_vertex([&](const std::array<Interval, D>& y) {
      // y.u rounded up for every u, axis by axis: the codes of the first i axes, then each of them
      // with u_i = -1 (minus inf y_i), 0, +1 (plus sup y_i).
      std::array<double, kCodes> s;
      if constexpr (D == 3) {
        // The same sums in the same order, each of fixed length so that the compiler unrolls and pairs
        // them (a third of a 3D cell's recording): per axis the terms of u_i = -1, 0, +1 (adding the
        // 0 changes at most the sign of a zero, which rounds to the same byte).
        std::array<std::array<double, 3>, D> t;
        for (int i = 0; i < D; ++i) t[i] = {0.0 - y[i].inf(), 0.0, y[i].sup()};
        std::array<double, 9> s01;
        for (int k = 0; k < 3; ++k)
          for (int j = 0; j < 3; ++j) s01[j + 3 * k] = t[0][j] + t[1][k];
        for (int l = 0; l < 3; ++l)
          for (int m = 0; m < 9; ++m) s[m + 9 * l] = s01[m] + t[2][l];
      } else {
        s[0] = 0;
        int size = 1;
        for (int i = 0; i < D; ++i) {
          for (int c = 0; c < size; ++c) {
            s[size + c] = s[c];
            s[2 * size + c] = s[c] + y[i].sup();
            s[c] -= y[i].inf();
          }
          size *= 3;
        }
      }
      for (int k = 0; k < kCodes; ++k) h[k] = std::max(h[k], s[k]);
    });
    CellReach r;
    double largest = 0;
    for (double x : h) largest = std::max(largest, x);
    if (!(largest > 0) || !std::isfinite(largest)) return r;  // no vertices or a degenerate cell
    // One unit of the scale: the least power of two at least largest / 254 (upward rounding is on), or
    // the least the byte holds, coarser; every value rounded up in it: at most 254 units.
    int exponent = 0;
    const double mantissa = std::frexp(largest / 254.0, &exponent);  // largest / 254 = mantissa 2^exponent
    if (mantissa == 0.5) --exponent;                                   // a power of two itself
    if (exponent > kMaxExponent) return r;  // no cell in the unit box reaches this far
    r.unit_code_ = std::uint8_t(std::max(exponent, kMinExponent) - kMinExponent);
    const double u = r.unit();
    for (int k = 0; k < kCodes; ++k)
      if (k != kZeroCode)
        r.q_[slot(k)] = std::uint8_t(std::clamp(std::ceil(std::max(h[k], 0.0) / u), 0.0, 255.0));
    return r;
  }

  // Whether the bisector of v and v + d may cut the cell (surely true when it does). Rounding in
  // doubles here errs far below the margin given.
  bool may_be_cut_by(const Point<D>& d) const {
    if (unit_code_ == kUnbounded) return true;
    std::array<int, D> axis;
    for (int i = 0; i < D; ++i) axis[i] = i;
    std::sort(axis.begin(), axis.end(), [&](int a, int b) { return std::fabs(d[a]) > std::fabs(d[b]); });
    std::array<int, D> u{};
    double bound = 0, d2 = 0;
    for (int j = 0; j < D; ++j) {
      const int i = axis[j];
      u[i] = d[i] < 0 ? -1 : 1;
      const double next = j + 1 < D ? std::fabs(d[axis[j + 1]]) : 0.0;
      bound += (std::fabs(d[i]) - next) * double(q_[slot(code_of(u))]);
      d2 += d[i] * d[i];
    }
    return bound * unit() * (1 + 1e-6) >= 0.5 * d2;
  }

 private:
  static int code_of(const std::array<int, D>& u) {
    int code = 0;
    for (int i = D - 1; i >= 0; --i) code = 3 * code + (u[i] + 1);
    return code;
  }

  static constexpr int slot(int code) { return code < kZeroCode ? code : code - 1; }
  // The unit is 2^(kMinExponent + unit_code_), or kUnbounded: every vertex may cut. Units up to 16 cover
  // any cell of the unit box (a support value is at most D); a cell too small for the least unit keeps
  // it, coarser than its own, which only rounds its values up further.
  static constexpr std::uint8_t kUnbounded = 255;
  static constexpr int kMinExponent = -250;
  static constexpr int kMaxExponent = kMinExponent + 254;
  double unit() const { return std::bit_cast<double>(std::uint64_t(1023 + kMinExponent + unit_code_) << 52); }

  std::array<std::uint8_t, kCodes - 1> q_{};
  std::uint8_t unit_code_ = kUnbounded;
};
static_assert(sizeof(CellReach<2>) == 9 && sizeof(CellReach<3>) == 27);

}  // namespace shoremesh::engine
