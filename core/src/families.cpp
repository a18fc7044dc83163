// Generated input families (see families.hpp). The random transforms are written here rather than taken
// from <random>'s distributions, whose output the standard leaves to the implementation.
#include "shoremesh/families.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <unordered_set>

#include "shoremesh/error.hpp"

namespace shoremesh::families {
namespace {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  // Uniform in [0, 1): the top 53 bits of one draw.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Standard normal by Box–Muller (one of the pair; simplicity over speed).
  double normal() {
    const double u1 = 1.0 - uniform01();  // (0, 1]: the logarithm stays finite
    const double u2 = uniform01();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  // Uniform in [0, n), n > 0: draws past the last whole multiple of n are rejected (no modulo bias).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % n;
    std::uint64_t x;
    do x = engine_();
    while (x >= limit);
    return x % n;
  }

 private:
  std::mt19937_64 engine_;
};

template <int D>
struct BitsHash {
  std::size_t operator()(const Point<D>& p) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (double x : p) h = (h ^ std::bit_cast<std::uint64_t>(x)) * 0xff51afd7ed558ccdULL;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};

// Draws points from `draw` until n distinct ones are collected, in the order drawn: a repeated point is
// dropped and replaced by the next draw, so the result stays deterministic.
template <int D, class Draw>
std::vector<Point<D>> distinct_points(std::size_t n, Draw draw) {
  std::vector<Point<D>> points;
  points.reserve(n);
  std::unordered_set<Point<D>, BitsHash<D>> seen;
  seen.reserve(n);
  while (points.size() < n) {
    const Point<D> p = draw();
    if (seen.insert(p).second) points.push_back(p);
  }
  return points;
}

template <int D>
bool in_unit_box(const Point<D>& p) {
  return std::all_of(p.begin(), p.end(), [](double x) { return x >= 0.0 && x <= 1.0; });
}

// A uniformly random direction: an angle in 2D, normalised Gaussian vector in 3D.
template <int D>
Point<D> random_direction(Random& random) {
  if constexpr (D == 2) {
    const double angle = 2.0 * std::numbers::pi * random.uniform01();
    return {std::cos(angle), std::sin(angle)};
  } else {
    for (;;) {
      Point<D> g{random.normal(), random.normal(), random.normal()};
      const double length = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      if (length > 1e-12) return {g[0] / length, g[1] / length, g[2] / length};
    }
  }
}

// Smallest k with k^D >= count.
template <int D>
std::size_t per_axis_for(std::size_t count) {
  std::size_t k = 1;
  while (static_cast<double>(std::pow(static_cast<double>(k), D)) < static_cast<double>(count)) ++k;
  return k;
}

}  // namespace

template <int D>
std::vector<Point<D>> uniform(std::size_t n, std::uint64_t seed) {
  Random random(seed);
  return distinct_points<D>(n, [&] {
    Point<D> p;
    for (double& x : p) x = random.uniform01();
    return p;
  });
}

template <int D>
std::vector<Point<D>> gaussian_clusters(std::size_t n, std::size_t clusters, std::uint64_t seed) {
  if (clusters == 0) throw InputError("gaussian_clusters: need at least one cluster");
  Random random(seed);
  std::vector<Point<D>> centres(clusters);
  std::vector<double> sigmas(clusters);
  for (std::size_t c = 0; c < clusters; ++c) {
    for (double& x : centres[c]) x = 0.15 + 0.7 * random.uniform01();
    sigmas[c] = 0.005 * std::pow(10.0, random.uniform01());  // log-uniform in [0.005, 0.05)
  }
  return distinct_points<D>(n, [&] {
    const std::size_t c = random.below(clusters);
    for (;;) {
      Point<D> p;
      for (int k = 0; k < D; ++k) p[k] = centres[c][k] + sigmas[c] * random.normal();
      if (in_unit_box<D>(p)) return p;
    }
  });
}

template <int D>
std::vector<Point<D>> on_circle(std::size_t n) {
  constexpr double radius = 0.4;
  std::vector<Point<D>> points(n);
  for (std::size_t i = 0; i < n; ++i) {
    if constexpr (D == 2) {
      const double angle = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
      points[i] = {0.5 + radius * std::cos(angle), 0.5 + radius * std::sin(angle)};
    } else {
      // Fibonacci lattice: heights evenly spaced, longitudes advancing by the golden angle.
      const double z = 1.0 - (2.0 * static_cast<double>(i) + 1.0) / static_cast<double>(n);
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double longitude = static_cast<double>(i) * std::numbers::pi * (3.0 - std::sqrt(5.0));
      points[i] = {0.5 + radius * r * std::cos(longitude), 0.5 + radius * r * std::sin(longitude), 0.5 + radius * z};
    }
  }
  return points;  // distinct: different angles (2D) or heights (3D), far above rounding for any usable n
}

template <int D>
std::vector<Point<D>> grid(std::size_t per_axis) {
  std::size_t total = 1;
  for (int k = 0; k < D; ++k) total *= per_axis;
  std::vector<Point<D>> points(total);
  const double k_side = static_cast<double>(per_axis);
  for (std::size_t i = 0; i < total; ++i) {
    std::size_t rest = i;
    for (int k = 0; k < D; ++k) {
      points[i][k] = (static_cast<double>(rest % per_axis) + 0.5) / k_side;
      rest /= per_axis;
    }
  }
  return points;
}

template <int D>
std::vector<Point<D>> close_pair(std::size_t n_sparse, double gap, std::uint64_t seed) {
  const std::size_t k = per_axis_for<D>(n_sparse + 1);
  if (!(gap > 0.0 && gap < 0.25 / static_cast<double>(k)))
    throw InputError("close_pair: the gap must be positive and below a quarter of the grid cell");
  std::size_t cells = 1;
  for (int a = 0; a < D; ++a) cells *= k;
  // A random choice of n_sparse + 1 distinct cells (partial Fisher–Yates): the first takes the pair.
  Random random(seed);
  std::vector<std::size_t> order(cells);
  for (std::size_t i = 0; i < cells; ++i) order[i] = i;
  for (std::size_t i = 0; i < n_sparse + 1; ++i) std::swap(order[i], order[i + random.below(cells - i)]);

  const double cell_side = 1.0 / static_cast<double>(k);
  auto corner = [&](std::size_t cell) {
    Point<D> c;
    for (int a = 0; a < D; ++a) {
      c[a] = static_cast<double>(cell % k) * cell_side;
      cell /= k;
    }
    return c;
  };
  std::vector<Point<D>> points;
  points.reserve(n_sparse + 2);
  Point<D> first = corner(order[0]);
  for (double& x : first) x += 0.5 * cell_side;
  Point<D> second = first;
  second[0] += gap;
  points.push_back(first);
  points.push_back(second);
  // One point per other cell, in the middle half of the cell: no two closer than half a cell.
  for (std::size_t i = 1; i <= n_sparse; ++i) {
    Point<D> p = corner(order[i]);
    for (double& x : p) x += (0.25 + 0.5 * random.uniform01()) * cell_side;
    points.push_back(p);
  }
  return points;
}

template <int D>
std::vector<Point<D>> on_line(std::size_t n) {
  std::vector<Point<D>> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i].fill((static_cast<double>(i) + 0.5) / static_cast<double>(n));
  return points;
}

template <int D>
std::vector<Point<D>> kuzmin(std::size_t n, std::uint64_t seed) {
  constexpr double max_radius = 1000.0;
  Random random(seed);
  return distinct_points<D>(n, [&] {
    for (;;) {
      // Inverse of the enclosed mass 1 - 1/sqrt(1 + r^2).
      const double u = random.uniform01();
      const double r = std::sqrt(1.0 / ((1.0 - u) * (1.0 - u)) - 1.0);
      if (!(r < max_radius)) continue;
      const Point<D> direction = random_direction<D>(random);
      Point<D> p;
      for (int a = 0; a < D; ++a) p[a] = 0.5 + 0.5 * (r / max_radius) * direction[a];
      if (in_unit_box<D>(p)) return p;
    }
  });
}

namespace {
constexpr std::array<std::pair<FamilyName, std::string_view>, 7> kNames{{
    {FamilyName::Uniform, "uniform"},
    {FamilyName::GaussianClusters, "clusters"},
    {FamilyName::OnCircle, "circle"},
    {FamilyName::Grid, "grid"},
    {FamilyName::ClosePair, "close-pair"},
    {FamilyName::OnLine, "line"},
    {FamilyName::Kuzmin, "kuzmin"},
}};
}  // namespace

std::string family_names() {
  std::string s;
  for (const auto& [family, name] : kNames) s += (s.empty() ? "" : ", ") + std::string(name);
  return s;
}

FamilyName parse_family(std::string_view name) {
  for (const auto& [family, known] : kNames)
    if (known == name) return family;
  throw InputError("unknown input family '" + std::string(name) + "' (known: " + family_names() + ")");
}

std::string_view family_name(FamilyName family) {
  for (const auto& [f, name] : kNames)
    if (f == family) return name;
  return "unknown";
}

template <int D>
std::vector<Point<D>> generate(FamilyName family, std::size_t n, std::uint64_t seed) {
  switch (family) {
    case FamilyName::Uniform: return uniform<D>(n, seed);
    case FamilyName::GaussianClusters: return gaussian_clusters<D>(n, 10, seed);
    case FamilyName::OnCircle: return on_circle<D>(n);
    case FamilyName::Grid: return grid<D>(static_cast<std::size_t>(std::lround(std::pow(static_cast<double>(n), 1.0 / D))));
    case FamilyName::ClosePair: return close_pair<D>(n >= 2 ? n - 2 : 0, 1e-9, seed);
    case FamilyName::OnLine: return on_line<D>(n);
    case FamilyName::Kuzmin: return kuzmin<D>(n, seed);
  }
  throw InputError("unknown input family");
}

#define SHOREMESH_FAMILIES_INSTANTIATE(D)                                                          \
  template std::vector<Point<D>> uniform<D>(std::size_t, std::uint64_t);                           \
  template std::vector<Point<D>> gaussian_clusters<D>(std::size_t, std::size_t, std::uint64_t);    \
  template std::vector<Point<D>> on_circle<D>(std::size_t);                                        \
  template std::vector<Point<D>> grid<D>(std::size_t);                                             \
  template std::vector<Point<D>> close_pair<D>(std::size_t, double, std::uint64_t);                \
  template std::vector<Point<D>> on_line<D>(std::size_t);                                          \
  template std::vector<Point<D>> kuzmin<D>(std::size_t, std::uint64_t);                            \
  template std::vector<Point<D>> generate<D>(FamilyName, std::size_t, std::uint64_t);
SHOREMESH_FAMILIES_INSTANTIATE(2)
SHOREMESH_FAMILIES_INSTANTIATE(3)
#undef SHOREMESH_FAMILIES_INSTANTIATE

}  // namespace shoremesh::families
