// Cells that stop at the shore (docs/water_only.md): with Parameters::shore_cells the water mesh of the
// samples has no more triangles below the bound and no smaller angle, and fewer Steiner points are made
// (those on land). A fresh run as `shoremesh mesh` makes it: the engine on the ring points and the splits,
// the constrained Delaunay mesh with the refined rings as constraints.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "mesh_test_util.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/io/poly_file.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/pslg.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

using mesh_test::degrees_at;
using mesh_test::kBoundDeg;

struct Run {
  std::size_t below = 0, steiner = 0, water_vertices = 0;
  double smallest = 180;
};

Run run(const Domain2& rings, bool shore_cells) {
  const ShoreRefinement refinement(rings);
  const std::vector<Point2> input = mesh_test::ring_input(rings, refinement);
  Parameters<2> parameters;
  parameters.shore_cells = shore_cells;
  const StableResult<2> ws = stable_well_spaced<2>(input, parameters, std::nullopt, &rings);
  const Mesh2 mesh(ws.points, ws.input_count, refinement.refined());
  Run r;
  r.steiner = ws.points.size() - ws.input_count;
  std::set<std::size_t> used;
  for (const auto& e : mesh.elements()) {
    const Point2 &a = mesh.points()[e[0]], &b = mesh.points()[e[1]], &c = mesh.points()[e[2]];
    const double s = std::min({degrees_at(a, b, c), degrees_at(b, c, a), degrees_at(c, a, b)});
    r.below += s < kBoundDeg;
    r.smallest = std::min(r.smallest, s);
    used.insert(e.begin(), e.end());
  }
  r.water_vertices = used.size();
  return r;
}

void no_worse(const Domain2& rings, const std::string& what) {
  const Run whole = run(rings, false), wedge = run(rings, true);
  ::testing::Test::RecordProperty(what + ": below the bound, whole cells / wedges",
                 std::to_string(whole.below) + " / " + std::to_string(wedge.below));
  ::testing::Test::RecordProperty(what + ": Steiner points, whole cells / wedges",
                 std::to_string(whole.steiner) + " / " + std::to_string(wedge.steiner));
  ::testing::Test::RecordProperty(what + ": smallest angle, whole cells / wedges",
                                  std::to_string(whole.smallest) + " / " + std::to_string(wedge.smallest));
  EXPECT_LE(wedge.below, whole.below) << what;
  // With the land emptied, a sliver between a split and its ring edge on the land side can enter the
  // constrained triangulation (this sample: one of 1.2e-13 degrees); the mesh drops it (Mesh::water_side).
  EXPECT_GE(wedge.smallest, whole.smallest) << what;
  EXPECT_LE(wedge.steiner, whole.steiner) << what;
  // The points that went are on land: the water mesh keeps about as many vertices (within 2 %).
  EXPECT_LE(double(wedge.water_vertices), 1.02 * double(whole.water_vertices)) << what;
}

TEST(ShoreCellsMesh, SuperiorSampleHasNoMoreTrianglesBelowTheBoundAndFewerPoints) { no_worse(mesh_test::superior(), "Lake Superior"); }

TEST(ShoreCellsMesh, FishAndRectangleHasNoMoreTrianglesBelowTheBound) {
  const io::PslgFile p = io::read_poly_file(mesh_test::samples("pslg/fish-and-rectangle.poly"));
  no_worse(pslg_domain(p.points, p.segments, p.holes).domain, "fish-and-rectangle");
}

}  // namespace
}  // namespace shoremesh
