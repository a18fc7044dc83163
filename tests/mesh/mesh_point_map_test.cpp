// PointMap (the mesh's vertex look-up) against std::map under random puts and erases: every look-up agrees,
// also after the erases' backward shifts and the growths, in a table small enough that runs wrap around.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

#include "shoremesh/mesh_point_map.hpp"

namespace shoremesh {
namespace {

TEST(PointMap, AgreesWithStdMapUnderPutsAndErases) {
  std::mt19937_64 rng(7);
  // Few distinct coordinates: many points collide in their home slots and runs are long.
  std::uniform_int_distribution<int> coord(0, 40);
  PointMap<2, int> map;
  std::map<Point2, int> reference;
  for (int step = 0; step < 200000; ++step) {
    const Point2 p{coord(rng) * 0.25, coord(rng) * 0.5};
    const int action = static_cast<int>(rng() % 3);
    if (action == 0) {
      const bool fresh = reference.emplace(p, step + 1).second;
      ASSERT_EQ(map.emplace(p, step + 1), fresh);
    } else if (action == 1) {
      ASSERT_EQ(map.erase(p), reference.erase(p) == 1);
    } else {
      const int* v = map.find(p);
      const auto it = reference.find(p);
      ASSERT_EQ(v != nullptr, it != reference.end());
      if (v) {
        ASSERT_EQ(*v, it->second);
      }
    }
    ASSERT_EQ(map.size(), reference.size());
  }
  for (const auto& [p, v] : reference) EXPECT_EQ(map.at(p), v);
  EXPECT_THROW(map.at({-1.0, -1.0}), std::out_of_range);
}

TEST(PointMap, NegativeZeroIsZero) {
  PointMap<3, int> map;
  EXPECT_TRUE(map.emplace({0.0, 1.0, 2.0}, 5));
  ASSERT_NE(map.find({-0.0, 1.0, 2.0}), nullptr);
  EXPECT_EQ(*map.find({-0.0, 1.0, 2.0}), 5);
  EXPECT_FALSE(map.emplace({-0.0, 1.0, 2.0}, 6));
  EXPECT_TRUE(map.erase({-0.0, 1.0, 2.0}));
  EXPECT_EQ(map.size(), 0u);
}

}  // namespace
}  // namespace shoremesh
