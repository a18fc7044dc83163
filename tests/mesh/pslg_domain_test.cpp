// A .poly's segments as the water domain (shoremesh/pslg.hpp): water is the bounded faces without a hole
// seed; segments with water on one side become rings, with water on both sides lines, with land on both
// sides nothing; the result does not depend on the segments' order or direction; the rings and lines pass
// the domain check with shared vertices, and the mesh of them conforms with the water's area.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include "mesh_test_util.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/io/poly_file.hpp"
#include "shoremesh/pslg.hpp"
#include "shoremesh/shore_refinement.hpp"

namespace shoremesh {
namespace {

using Edge = std::pair<Point2, Point2>;

// Each segment of the domain (its ends in order) with what it is: 0 shore, 1 island, 2 line.
std::map<Edge, int> edge_roles(const PslgDomain& d) {
  std::map<Edge, int> out;
  for (const Ring& r : d.domain.rings)
    for (std::size_t k = 0; k < r.segment_count(); ++k) {
      const Point2 &a = r.points[k], &b = r.points[(k + 1) % r.points.size()];
      EXPECT_TRUE(out.emplace(std::minmax(a, b), static_cast<int>(r.role)).second) << "a segment in two rings";
    }
  return out;
}

TEST(PslgDomain, FishAndRectangleWaterIsTheFacesWithoutSeedsWhateverTheSegmentOrder) {
  const io::PslgFile p = io::read_poly_file(mesh_test::samples("pslg/fish-and-rectangle.poly"));
  const PslgDomain d = pslg_domain(p.points, p.segments, p.holes);
  // The three hole faces touch one another along 4 segments (left out) and the outer outline at 4 vertices
  // (the input's own pinch vertices); 10 segments part water from water.
  EXPECT_EQ(d.boundary_segments, 30u);
  EXPECT_EQ(d.line_segments, 10u);
  EXPECT_EQ(d.dropped_segments, 4u);
  EXPECT_EQ(d.pinch_vertices.size(), 4u);
  EXPECT_TRUE(d.holes_outside.empty());
  EXPECT_FALSE(find_ring_defect(d.domain, true));
  EXPECT_TRUE(find_ring_defect(d.domain, false)) << "the rings share vertices";
  for (std::size_t r = 0; r < d.domain.rings.size(); ++r) {
    ASSERT_EQ(d.vertices[r].size(), d.domain.rings[r].points.size());
    for (std::size_t k = 0; k < d.vertices[r].size(); ++k) EXPECT_EQ(p.points[d.vertices[r][k]], d.domain.rings[r].points[k]);
  }
  const auto roles = edge_roles(d);
  EXPECT_EQ(roles.size(), 40u);

  std::mt19937 rng(7);
  for (int round = 0; round < 5; ++round) {
    auto segments = p.segments;
    std::shuffle(segments.begin(), segments.end(), rng);
    for (auto& s : segments)
      if (rng() % 2) std::swap(s[0], s[1]);
    const PslgDomain e = pslg_domain(p.points, segments, p.holes);
    EXPECT_EQ(edge_roles(e), roles) << "round " << round;
    auto pinch = e.pinch_vertices;
    std::sort(pinch.begin(), pinch.end());
    EXPECT_EQ(pinch, d.pinch_vertices);
  }
}

TEST(PslgDomain, NestedPartsOpenChainsAndSeedsOutsideEverything) {
  // A square with a square island (a hole seed in it) and in the island a pond (no seed: water again);
  // a free chain in the water, a dangling segment from the outline inward, a chain in the island (land
  // on both sides) and a seed outside everything.
  const std::vector<Point2> pts{{0, 0},  {10, 0}, {10, 10}, {0, 10},  // outline 0-3
                                {3, 3},  {7, 3},  {7, 7},   {3, 7},   // island 4-7
                                {4, 4},  {5, 4},  {5, 5},             // pond 8-10
                                {1, 1},  {1, 2},  {2, 2},             // free chain 11-13
                                {10, 5}, {9, 5},                      // outline vertex 14 and a dangling end 15
                                {6, 4},  {6, 6}};                     // a segment in the island 16-17
  const std::vector<std::array<std::size_t, 2>> segs{{0, 1},  {1, 14}, {14, 2},  {2, 3},  {3, 0},  {4, 5},
                                                     {5, 6},  {6, 7},  {7, 4},   {8, 9},  {9, 10}, {10, 8},
                                                     {11, 12}, {12, 13}, {14, 15}, {16, 17}};
  const PslgDomain d = pslg_domain(pts, segs, std::vector<Point2>{{3.5, 6}, {20, 20}});
  EXPECT_EQ(d.holes_outside, (std::vector<std::size_t>{1}));
  EXPECT_EQ(d.boundary_segments, 12u);
  EXPECT_EQ(d.line_segments, 3u);
  EXPECT_EQ(d.dropped_segments, 1u);
  const auto roles = edge_roles(d);
  EXPECT_EQ(roles.at(std::minmax(pts[0], pts[1])), 0);   // the outline bounds water
  EXPECT_EQ(roles.at(std::minmax(pts[4], pts[5])), 1);   // the island land
  EXPECT_EQ(roles.at(std::minmax(pts[8], pts[9])), 0);   // the pond water
  EXPECT_EQ(roles.at(std::minmax(pts[14], pts[15])), 2); // the dangling segment is a line
  EXPECT_EQ(roles.at(std::minmax(pts[11], pts[12])), 2);
  EXPECT_FALSE(roles.count(std::minmax(pts[16], pts[17])));
  EXPECT_FALSE(find_ring_defect(d.domain, true));
  // The even-odd water of the rings is the water: the pond's inside is water, the island's land.
  EXPECT_TRUE(ring_contains(d.domain.rings[0].points, {5, 1}));

  // Without any cycle: every segment a line, no rings.
  const PslgDomain lines = pslg_domain(pts, std::vector<std::array<std::size_t, 2>>{{11, 12}, {12, 13}, {14, 15}}, {});
  EXPECT_FALSE(lines.bounded_faces);
  EXPECT_EQ(lines.line_segments, 3u);
  EXPECT_TRUE(std::all_of(lines.domain.rings.begin(), lines.domain.rings.end(), [](const Ring& r) { return !r.closed(); }));
}

TEST(PslgDomain, SegmentsThatMeetOtherThanAtTheirEndsAreFound) {
  const std::vector<Point2> pts{{0, 0}, {10, 0}, {5, 0}, {5, 5}, {0, 5}, {10, 5}};
  // 2-3 starts on segment 0-1 (a T); 4-1 crosses 0-5, while 0-4 and 0-1 share only their ends.
  EXPECT_EQ(first_segment_crossing(pts, std::vector<std::array<std::size_t, 2>>{{0, 1}, {2, 3}}),
            (std::array<std::size_t, 2>{0, 1}));
  EXPECT_EQ(first_segment_crossing(pts, std::vector<std::array<std::size_t, 2>>{{0, 4}, {0, 1}, {4, 1}, {0, 5}}),
            (std::array<std::size_t, 2>{2, 3}));
  EXPECT_FALSE(first_segment_crossing(pts, std::vector<std::array<std::size_t, 2>>{{0, 1}, {0, 3}, {3, 1}}));
  // The same segment twice (in either direction) overlaps itself.
  EXPECT_TRUE(first_segment_crossing(pts, std::vector<std::array<std::size_t, 2>>{{0, 1}, {1, 0}}));
}

}  // namespace
}  // namespace shoremesh
