// What an operation of a build for updates keeps in packed fields, at their limits: the insertion radius
// as a fraction of depends2 in one byte (never below the radius asked for, the least such fraction, and
// exact whatever the rounding mode), and the count of nodes read in four bits.
#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "shoremesh/engine/engine.hpp"

namespace shoremesh {
namespace {

template <int D>
void insertion_radius_is_the_least_fraction_at_least_asked(int rounding) {
  using Op = typename WellSpacedEngine<D>::RecordedOp;
  const int saved = std::fegetround();
  std::fesetround(rounding);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20000; ++trial) {
    Op op;
    const float depends2 = float(std::ldexp(0.5 + unit(rng), -int(rng() % 60)));
    op.set_depends2(depends2);
    ASSERT_EQ(op.inserted_depends2(), double(depends2));
    // Fractions anywhere, near the steps, and a float below all of depends2.
    float asked = float(double(depends2) * unit(rng));
    if (trial % 3 == 1) asked = float(double(depends2) * double(rng() % 256) / 256);
    if (trial % 7 == 2) asked = std::nextafter(depends2, 0.0f);
    op.set_inserted_depends2(asked);
    ASSERT_EQ(op.depends2, depends2);
    ASSERT_GE(op.inserted_depends2(), double(asked)) << depends2 << " " << asked;
    ASSERT_LE(op.inserted_depends2(), double(depends2));
    // The least: one step below would be too small.
    if (op.inserted_256ths > 0) {
      Op less = op;
      --less.inserted_256ths;
      ASSERT_LT(less.inserted_depends2(), double(asked));
    }
  }
  std::fesetround(saved);
}

TEST(OpPacking, InsertionRadiusIsTheLeastFractionAtLeastAsked2D) {
  insertion_radius_is_the_least_fraction_at_least_asked<2>(FE_TONEAREST);
  insertion_radius_is_the_least_fraction_at_least_asked<2>(FE_UPWARD);
}
TEST(OpPacking, InsertionRadiusIsTheLeastFractionAtLeastAsked3D) {
  insertion_radius_is_the_least_fraction_at_least_asked<3>(FE_UPWARD);
}

TEST(OpPacking, InsertionRadiusEdges) {
  using Op = WellSpacedEngine<2>::RecordedOp;
  Op op;
  op.set_depends2(0.25f);
  op.set_inserted_depends2(0);  // only a vertex exactly at the operation's vertex
  EXPECT_EQ(op.inserted_depends2(), 0.0);
  op.set_inserted_depends2(0.25f);
  EXPECT_EQ(op.inserted_depends2(), 0.25);
  // Larger than depends2: depends2 grows with it (a rerun more, never one fewer).
  op.set_inserted_depends2(0.5f);
  EXPECT_EQ(op.depends2, 0.5f);
  EXPECT_EQ(op.inserted_depends2(), 0.5);
  op.set_depends2(0);
  op.set_inserted_depends2(0);
  EXPECT_EQ(op.inserted_depends2(), 0.0);
}

TEST(OpPacking, ReadsCountHoldsEveryCountUpToItsLimit) {
  using Op = WellSpacedEngine<3>::RecordedOp;
  static_assert(Op::kMaxReads >= 8);
  for (std::size_t count = 0; count <= Op::kMaxReads; ++count) {
    Op op;
    op.flags = 0x7F;
    op.shore_read = true;
    op.reads_count = std::uint8_t(count);
    EXPECT_EQ(std::size_t(op.reads_count), count);
    EXPECT_TRUE(op.shore_read);  // its neighbours in the byte keep their bits
    EXPECT_EQ(op.flags, 0x7F);
  }
}

}  // namespace
}  // namespace shoremesh
