// The shore is the mesh's boundary (docs/conforming.md): the engine on the input points and the shore's
// canonical splits, the constrained Delaunay mesh of its output with the split rings as constraints.
// Checked from the mesh's elements alone: every ring segment as given is a chain of mesh edges (through
// the split points, which lie on it up to rounding), the water's area is the rings' even-odd area, and
// every element below the quality bound has a shore edge. Then random shore edits, each compared with a
// fresh run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <set>
#include <utility>

#include "mesh_test_util.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/mesh_quality.hpp"
#include "shoremesh/mesh_water.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

using Segment = std::pair<Point2, Point2>;

double signed_area(const std::vector<Point2>& ring) {
  double a = 0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const Point2 &p = ring[k], &q = ring[(k + 1) % ring.size()];
    a += 0.5 * (p[0] * q[1] - q[0] * p[1]);
  }
  return a;
}

// The even-odd area of the rings: each ring's area, signed by how many other rings enclose it.
double water_area(const Domain2& d) {
  double total = 0;
  for (std::size_t i = 0; i < d.rings.size(); ++i) {
    int depth = 0;
    for (std::size_t j = 0; j < d.rings.size(); ++j)
      depth += j != i && WaterTest(Domain2{{d.rings[j]}}).in_water(d.rings[i].points[0]);
    total += (depth % 2 ? -1 : 1) * std::abs(signed_area(d.rings[i].points));
  }
  return total;
}

double distance_to_line(const Point2& a, const Point2& b, const Point2& p) {
  const double cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
  return std::abs(cross) / std::hypot(b[0] - a[0], b[1] - a[1]);
}

struct FreshRun {
  Mesh2 mesh;
  Domain2 refined;
};

std::vector<Point2> ring_points(const Domain2& d) {
  std::vector<Point2> out;
  std::set<Point2> seen;
  for (const Ring& r : d.rings)
    for (const Point2& p : r.points)
      if (seen.insert(p).second) out.push_back(p);
  return out;
}

// A fresh run, as `shoremesh mesh` makes it: the engine on the ring points and the splits.
FreshRun fresh_run(const Domain2& rings, std::optional<BoxTransform<2>> box = {}) {
  const ShoreRefinement refinement(rings);
  std::vector<Point2> input = ring_points(rings);
  for (const Point2& p : refinement.split_points()) input.push_back(p);
  const StableResult<2> ws = stable_well_spaced<2>(input, {}, box);
  Domain2 refined = refinement.refined();
  return {Mesh2(ws.points, ws.input_count, refined), refined};
}

// What the issue asks of the mesh, checked from its elements: every segment of `rings` (as given) is a
// chain of mesh edges through points on it; the area is the rings'; elements below the bound have a shore
// edge. Returns the number of those.
std::size_t check_conforming(const Mesh2& mesh, const Domain2& rings, const Domain2& refined, const std::string& what) {
  std::set<Segment> edges;
  double area = 0;
  for (const auto& e : mesh.elements()) {
    const Point2 &a = mesh.points()[e[0]], &b = mesh.points()[e[1]], &c = mesh.points()[e[2]];
    for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) edges.insert(std::minmax(p, q));
    area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  }
  // Each refined ring holds its given ring's vertices in order, the splits between them.
  EXPECT_EQ(refined.rings.size(), rings.rings.size()) << what;
  std::size_t segments = 0, chained = 0;
  for (std::size_t r = 0; r < rings.rings.size(); ++r) {
    const auto& given = rings.rings[r].points;
    const auto& fine = refined.rings[r].points;
    std::size_t at = 0;
    for (std::size_t k = 0; k < given.size(); ++k) {
      const Point2 &a = given[k], &b = given[(k + 1) % given.size()];
      EXPECT_EQ(fine.at(at), a) << what;
      bool chain = true;
      std::size_t j = at;
      do {
        const Point2 &p = fine[j % fine.size()], &q = fine[(j + 1) % fine.size()];
        chain = chain && edges.count(std::minmax(p, q));
        if (q != b) {
          EXPECT_LE(distance_to_line(a, b, q), 1e-9 * std::hypot(b[0] - a[0], b[1] - a[1])) << what;
        }
        ++j;
      } while (fine[j % fine.size()] != b && j < at + fine.size());
      at = j % fine.size();
      ++segments;
      chained += chain;
    }
  }
  EXPECT_EQ(chained, segments) << what << ": shore segments that are chains of mesh edges";
  const double expect = water_area(rings);
  EXPECT_NEAR(area, expect, 1e-9 * expect) << what << ": the water's area";
  // Quality: below the bound only where the constrained triangulation is not Delaunay, i.e. the element's
  // circumcircle holds a mesh point (one the shore hides from it).
  std::size_t below = 0;
  for (const auto& e : mesh.elements()) {
    ElementCorners<2> c{mesh.points()[e[0]], mesh.points()[e[1]], mesh.points()[e[2]]};
    const ElementShape<2> shape = element_shape<2>(c);
    if (shape.radius_edge <= std::sqrt(2.0) * (1 + 1e-12)) continue;
    ++below;
    const double r = std::hypot(c[0][0] - shape.circumcentre[0], c[0][1] - shape.circumcentre[1]);
    bool hides = false;
    for (const Point2& p : mesh.points())
      hides = hides || std::hypot(p[0] - shape.circumcentre[0], p[1] - shape.circumcentre[1]) < r * (1 - 1e-9);
    EXPECT_TRUE(hides) << what << ": a Delaunay element below the bound at " << shape.centroid[0] << ","
                       << shape.centroid[1];
  }
  return below;
}

Domain2 superior(double scale = 1) {
  const auto lonlat = mesh_test::read_rings(mesh_test::samples("superior/lake_superior_lonlat.csv"));
  const mesh_test::Equirectangular projection;
  Domain2 d;
  for (std::size_t r = 0; r < lonlat.size(); ++r) {
    Ring ring{{}, r == 0 ? RingRole::Shore : RingRole::Island};
    for (const Point2& ll : lonlat[r]) {
      const Point2 p = projection.forward(ll);
      ring.points.push_back({p[0] * scale, p[1] * scale});
    }
    d.rings.push_back(std::move(ring));
  }
  return d;
}

// A letter A drawn as Triangle's A.poly is: an outer outline with a triangular hole, sharp serifs.
Domain2 letter_a() {
  return {{Ring{{{0, 0}, {1.2, 0}, {1.6, 1.2}, {3.4, 1.2}, {3.8, 0}, {5, 0}, {3.1, 6}, {1.9, 6}}, RingRole::Shore},
           Ring{{{2.0, 2.2}, {3.0, 2.2}, {2.5, 4.2}}, RingRole::Island}}};
}

TEST(ConformingMesh, ShoreSegmentsAreChainsOfMeshEdgesAndTheAreaIsTheRings) {
  const std::vector<std::pair<std::string, Domain2>> cases{
      {"double_hex.poly", mesh_test::rings_from_poly(mesh_test::samples("pslg/double_hex.poly"))},
      {"letter A", letter_a()},
      {"Lake Superior (GSHHG, 46 rings)", superior()},
  };
  for (const auto& [what, rings] : cases) {
    ASSERT_FALSE(find_ring_defect(rings)) << what;
    const FreshRun run = fresh_run(rings);
    run.mesh.check_valid();
    EXPECT_TRUE(run.mesh.shoreline_crossings().ok()) << what;
    const std::size_t below = check_conforming(run.mesh, rings, run.refined, what);
    RecordProperty(what + ": elements", std::to_string(run.mesh.element_count()));
    RecordProperty(what + ": below the bound at the shore", std::to_string(below));
  }
}

// Random shore edits (moves, points added after a vertex, removals) on Lake Superior's GSHHG rings, the
// engine and the mesh updated as `shoremesh edit` updates them: after each edit the mesh equals a fresh run
// on the edited rings, triangle for triangle, and conforms.
TEST(ConformingMesh, RandomShoreEditsOnSuperiorEqualAFreshRun) {
  const int edits = std::getenv("SHOREMESH_SANITIZER_BUILD") ? 30 : 300;
  Domain2 rings = superior();
  ShoreRefinement refinement(rings);
  std::vector<Point2> input = ring_points(rings);
  for (const Point2& p : refinement.split_points()) input.push_back(p);
  DynamicWellSpaced<2> engine(input);
  std::map<Point2, std::size_t> id_of;
  for (std::size_t i = 0; i < input.size(); ++i) id_of[input[i]] = i;
  Mesh2 mesh(engine.points(), engine.input_count(), refinement.refined());

  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0, 1);
  int made = 0;
  for (int attempt = 0; made < edits && attempt < 20 * edits; ++attempt) {
    Domain2 edited = rings;
    auto& ring = edited.rings[rng() % edited.rings.size()].points;
    const std::size_t k = rng() % ring.size();
    const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
    const double what = u(rng);
    std::vector<Edit<2>> edit;
    std::vector<Point2> removed, added;
    if (what < 0.5) {  // move toward the next vertex and a little off
      const Point2 p{a[0] + 0.3 * (b[0] - a[0]) + 0.1 * (u(rng) - 0.5) * (b[1] - a[1]),
                     a[1] + 0.3 * (b[1] - a[1]) - 0.1 * (u(rng) - 0.5) * (b[0] - a[0])};
      ring[k] = p;
      edit.push_back({Edit<2>::Kind::Move, 0, p});
      removed.push_back(a);
      added.push_back(p);
    } else if (what < 0.75) {  // add after k, near the middle of its segment
      const Point2 p{0.5 * (a[0] + b[0]) + 0.05 * (u(rng) - 0.5) * (b[1] - a[1]),
                     0.5 * (a[1] + b[1]) - 0.05 * (u(rng) - 0.5) * (b[0] - a[0])};
      ring.insert(ring.begin() + static_cast<std::ptrdiff_t>(k) + 1, p);
      edit.push_back({Edit<2>::Kind::Add, 0, p});
      added.push_back(p);
    } else {  // remove
      if (ring.size() <= 3) continue;
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
      edit.push_back({Edit<2>::Kind::Remove, 0, {}});
      removed.push_back(a);
    }
    if (find_ring_defect(edited) || id_of.count(added.empty() ? Point2{} : added.front())) continue;
    if (!edit.empty() && edit[0].kind != Edit<2>::Kind::Add) edit[0].id = id_of.at(a);

    // The splits follow the rings; the engine takes the edit and the splits' change in one update.
    const SplitChange splits = refinement.update(edited);
    for (const Point2& p : splits.removed) {
      edit.push_back({Edit<2>::Kind::Remove, id_of.at(p), {}});
      removed.push_back(p);
    }
    for (const Point2& p : splits.added) {
      edit.push_back({Edit<2>::Kind::Add, 0, p});
      added.push_back(p);
    }
    UpdateReport<2> report;
    const std::vector<std::size_t> ids = engine.apply(edit, &report);
    for (const Point2& p : removed) id_of.erase(p);
    std::size_t next = 0;
    for (const auto& e : edit)
      if (e.kind == Edit<2>::Kind::Add) id_of[e.point] = ids.at(next++);
    if (edit[0].kind == Edit<2>::Kind::Move) id_of[edit[0].point] = edit[0].id;
    mesh.apply(PointChange<2>::from_update(report, removed, added), refinement.refined());
    rings = edited;
    ++made;

    const FreshRun fresh = fresh_run(rings, engine.box());
    ASSERT_EQ(mesh_test::corner_list(mesh), mesh_test::corner_list(fresh.mesh)) << "after edit " << made;
    if (made % 25 == 0 || made == edits) {
      mesh.check_valid();
      check_conforming(mesh, rings, refinement.refined(), "after edit " + std::to_string(made));
    }
  }
  EXPECT_EQ(made, edits);
}

}  // namespace
}  // namespace shoremesh
