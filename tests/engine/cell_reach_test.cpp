// An operation's cell reach never says "cannot cut" of a vertex that cuts the cell (the operation would
// keep a result the new vertex changed), also when the bisector only touches a vertex of the cell; and it
// says "may cut" of far fewer vertices that do not than the radius test it refines.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "shoremesh/engine/cell_reach.hpp"
#include "shoremesh/engine/convex_cell.hpp"

namespace shoremesh::engine {
namespace {

struct Lcg {
  std::uint64_t x;
  double operator()() {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    return double(x >> 11) * 0x1p-53;
  }
};

template <int D>
CellReach<D> reach_of(const ConvexCell<D>& cell) {
  return CellReach<D>::of([&](auto&& f) { cell.for_each_vertex_box(f); });
}

// v's cell among 30 D random neighbours within 0.3 s of it (none nearer than 0.1 s, so that the cell
// keeps some size), cut to the box of half-side 0.2 s around v, as compute_cell makes it. id counts the
// neighbours.
template <int D>
void random_cell(Lcg& rnd, const Point<D>& v, double s, ConvexCell<D>& cell, VertexId& id) {
  Point<D> lo, hi;
  for (int i = 0; i < D; ++i) {
    lo[i] = v[i] - 0.2 * s;
    hi[i] = v[i] + 0.2 * s;
  }
  cell.reset(v, lo, hi);
  id = 0;
  for (int k = 0; k < 30 * D; ++k) {
    Point<D> w;
    double d2 = 0;
    for (int i = 0; i < D; ++i) {
      w[i] = v[i] + 0.3 * s * (2 * rnd() - 1);
      d2 += (w[i] - v[i]) * (w[i] - v[i]);
    }
    if (d2 > 0.01 * s * s) cell.clip(id++, w, d2);
  }
}

template <int D>
void never_misses_a_cut_and_rarely_says_maybe(std::uint64_t seed) {
  RoundingGuard guard;
  Lcg rnd{seed};
  std::size_t cuts = 0, reach_false = 0, radius_false = 0;
  for (int trial = 0; trial < 40; ++trial) {
    ConvexCell<D> cell;
    Point<D> v;
    for (int i = 0; i < D; ++i) v[i] = 0.5;
    VertexId id = 0;
    random_cell<D>(rnd, v, 1.0, cell, id);
    const CellReach<D> reach = reach_of(cell);
    const double radius = std::sqrt(cell.max_vertex_distance2());
    for (int k = 0; k < 500; ++k) {
      // Offsets within twice the cell's radius: the ones the radius test lets through.
      Point<D> w, d;
      double d2 = 0;
      do {
        d2 = 0;
        for (int i = 0; i < D; ++i) {
          d[i] = 2 * radius * (2 * rnd() - 1);
          d2 += d[i] * d[i];
        }
      } while (d2 > 4 * radius * radius);
      for (int i = 0; i < D; ++i) w[i] = v[i] + d[i];
      ConvexCell<D> copy;
      copy.assign_geometry(cell);
      const bool cuts_it = copy.clip(id, w, d2);
      if (cuts_it) {
        ++cuts;
        ASSERT_TRUE(reach.may_be_cut_by(d)) << "trial " << trial << " offset " << k;
      } else {
        ++radius_false;
        if (reach.may_be_cut_by(d)) ++reach_false;
      }
    }
  }
  ASSERT_GT(cuts, 1000u);
  // Measured: 0.18 of the radius test's false "may cut", in 2D and in 3D.
  EXPECT_LT(double(reach_false), 0.5 * double(radius_false)) << reach_false << " of " << radius_false;
}

// The same cells shrunk by 2^-300 about the origin: below the least unit the byte holds, whose coarser
// unit must still bound every cut.
template <int D>
void tiny_cells_never_miss_a_cut(std::uint64_t seed) {
  RoundingGuard guard;
  Lcg rnd{seed};
  const double s = std::ldexp(1.0, -300);
  std::size_t cuts = 0;
  for (int trial = 0; trial < 20; ++trial) {
    ConvexCell<D> cell;
    VertexId id = 0;
    random_cell<D>(rnd, Point<D>{}, s, cell, id);
    const CellReach<D> reach = reach_of(cell);
    for (int k = 0; k < 300; ++k) {
      Point<D> d;
      double d2 = 0;
      for (int i = 0; i < D; ++i) {
        d[i] = 0.6 * s * (2 * rnd() - 1);
        d2 += d[i] * d[i];
      }
      ConvexCell<D> copy;
      copy.assign_geometry(cell);
      if (copy.clip(id, d, d2)) {
        ++cuts;
        ASSERT_TRUE(reach.may_be_cut_by(d)) << "trial " << trial << " offset " << k;
      }
    }
  }
  ASSERT_GT(cuts, 100u);
}

TEST(CellReach, NeverMissesACutAndRarelySaysMaybe2D) { never_misses_a_cut_and_rarely_says_maybe<2>(11); }
TEST(CellReach, TinyCellsNeverMissACut2D) { tiny_cells_never_miss_a_cut<2>(13); }
TEST(CellReach, TinyCellsNeverMissACut3D) { tiny_cells_never_miss_a_cut<3>(14); }
TEST(CellReach, NeverMissesACutAndRarelySaysMaybe3D) { never_misses_a_cut_and_rarely_says_maybe<3>(12); }

// A grid point's cell is a cube whose corners the diagonal neighbours' bisectors pass through exactly:
// such a vertex does not cut, but it is on the cell, and must count as "may cut".
TEST(CellReach, ABisectorThroughACornerMayCut3D) {
  RoundingGuard guard;
  ConvexCell<3> cell;
  cell.reset({0.5, 0.5, 0.5}, {0.3, 0.3, 0.3}, {0.7, 0.7, 0.7});
  VertexId id = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int s = -1; s <= 1; s += 2) {
      Point<3> w{0.5, 0.5, 0.5};
      w[axis] += 0.125 * s;
      cell.clip(id++, w, 0.015625);
    }
  const CellReach<3> reach = reach_of(cell);
  EXPECT_TRUE(reach.may_be_cut_by({0.125, 0.125, 0.125}));    // through the corner (1/16, 1/16, 1/16)
  EXPECT_TRUE(reach.may_be_cut_by({-0.125, 0.125, 0.0}));     // through an edge of the cube
  EXPECT_FALSE(reach.may_be_cut_by({0.25, 0.25, 0.25}));      // bisector twice as far as the corner
  EXPECT_TRUE(CellReach<3>::unbounded().may_be_cut_by({1.0, 1.0, 1.0}));
}

}  // namespace
}  // namespace shoremesh::engine
