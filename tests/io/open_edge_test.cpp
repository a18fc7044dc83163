// Open water in traced images: ring points where the water reaches the image's edge are the open points,
// and only those.
#include "io_test_util.hpp"
#include "shoremesh/io/image_trace.hpp"

namespace shoremesh::io {
namespace {

TEST(OpenEdge, WaterReachingTheLeftEdgeGivesOpenPointsThereOnly) {
  // 40 x 30 pixels: water in the left 20 columns (touching the left, top and bottom edges) with an island.
  WaterMask mask;
  mask.width = 40, mask.height = 30;
  for (int r = 0; r < 30; ++r)
    for (int c = 0; c < 40; ++c) mask.water.push_back(c < 20 && !(c >= 8 && c < 12 && r >= 12 && r < 16));
  ImageTraceOptions o;
  o.spacing = 2;
  const TracedImage t = trace_water_mask(mask, o);
  const InputSet& set = t.input;
  ASSERT_FALSE(set.open_points.empty());
  // Pixel units: x = col + 0.5, y = 30 - row - 0.5. Open points lie beyond the outermost pixel centres,
  // on the left, top or bottom edge, never at the shore (x near 20) or on the island.
  std::size_t left = 0;
  for (const Point2& p : set.open_points) {
    const bool on_edge = p[0] < 0.5 || p[1] < 0.5 || p[1] > 29.5;
    EXPECT_TRUE(on_edge) << p[0] << ", " << p[1];
    EXPECT_LT(p[0], 20) << p[0] << ", " << p[1];
    left += p[0] < 0.5;
  }
  EXPECT_GE(left, 10u);  // the whole left edge, 30 pixels at spacing 2
  EXPECT_TRUE(std::is_sorted(set.open_points.begin(), set.open_points.end()));
  // A lake inside the image has none.
  WaterMask lake;
  lake.width = 30, lake.height = 30;
  for (int r = 0; r < 30; ++r)
    for (int c = 0; c < 30; ++c) lake.water.push_back(c > 5 && c < 25 && r > 5 && r < 25);
  EXPECT_TRUE(trace_water_mask(lake, o).input.open_points.empty());
}

}  // namespace
}  // namespace shoremesh::io
