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
#include <tuple>
#include <utility>

#include "mesh_test_util.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/mesh_quality.hpp"
#include "shoremesh/mesh_water.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/shore_session.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/poly_file.hpp"
#include "shoremesh/pslg.hpp"
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
    if (!d.rings[i].closed()) continue;  // lines bound nothing
    int depth = 0;
    for (std::size_t j = 0; j < d.rings.size(); ++j)
      depth += j != i && d.rings[j].closed() && WaterTest(Domain2{{d.rings[j]}}).in_water(d.rings[i].points[0]);
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
  const StableResult<2> ws = stable_well_spaced<2>(input, {}, box, &rings);
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
    for (std::size_t k = 0; k < rings.rings[r].segment_count(); ++k) {
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
  return mesh_test::below_bound_all_hidden(mesh, what);
}

using mesh_test::superior;

// A letter A drawn as Triangle's A.poly is: an outer outline with a triangular hole, sharp serifs.
Domain2 letter_a() {
  return {{Ring{{{0, 0}, {1.2, 0}, {1.6, 1.2}, {3.4, 1.2}, {3.8, 0}, {5, 0}, {3.1, 6}, {1.9, 6}}, RingRole::Shore},
           Ring{{{2.0, 2.2}, {3.0, 2.2}, {2.5, 4.2}}, RingRole::Island}}};
}

TEST(ConformingMesh, ShoreSegmentsAreChainsOfMeshEdgesAndTheAreaIsTheRings) {
  const std::vector<std::pair<std::string, Domain2>> cases{
      {"double_hex.poly", mesh_test::rings_from_poly(mesh_test::samples("pslg/double_hex.poly"))},
      {"letter A", letter_a()},
      {"letter A with a breakwater line", [] {
         Domain2 d = letter_a();
         d.rings.push_back({{{1.0, 1.5}, {2.5, 1.9}, {4.0, 1.5}}, RingRole::Line});
         return d;
       }()},
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

// A fresh run on a session's current input, as `shoremesh mesh` makes it and without the session's code:
// the shore's splits, the engine on the input points and the splits, the constrained mesh.
FreshRun fresh_run(const SessionInput<2>& in, const BoxTransform<2>& box) {
  std::vector<bool> on_ring(in.points.size(), false);
  for (const auto& ids : in.ring_ids)
    for (std::size_t id : ids) on_ring[id] = true;  // a line's end on a ring is one point
  std::vector<Point2> loose;
  for (std::size_t i = 0; i < in.points.size(); ++i)
    if (!on_ring[i]) loose.push_back(in.points[i]);
  const ShoreRefinement refinement(in.rings, loose, RefinementRule::for_box(box.side));
  std::vector<Point2> input = in.points;
  for (const Point2& p : refinement.split_points()) input.push_back(p);
  const StableResult<2> ws = stable_well_spaced<2>(input, {}, box, &in.rings);
  Domain2 refined = refinement.refined();
  return {Mesh2(ws.points, ws.input_count, refined), refined};
}

// After edit `made`: whether the session's mesh equals a fresh run on its current input, triangle for
// triangle; with `full`, also valid and conforming (checked from its elements).
bool equals_a_fresh_run(const ShoreSession<2>& session, int made, bool full) {
  const SessionInput<2> now = session.current_input();
  const FreshRun fresh = fresh_run(now, session.box());
  const bool equal = mesh_test::corner_list(session.mesh()) == mesh_test::corner_list(fresh.mesh);
  EXPECT_TRUE(equal) << "after edit " << made;
  // The constraints too: a segment the edit took away that stayed a constraint (a stale one) can leave
  // the triangles as they are where it is a Delaunay edge anyway, but not the constrained edges.
  const bool same_constraints = session.mesh().constrained_edges() == fresh.mesh.constrained_edges();
  EXPECT_TRUE(same_constraints) << "after edit " << made << ": the constrained edges differ from a fresh run's";
  if (full) {
    session.mesh().check_valid();
    check_conforming(session.mesh(), now.rings, fresh.refined, "after edit " + std::to_string(made));
    EXPECT_TRUE(session.shoreline().conforming());
  }
  return equal && same_constraints;
}

// A jetty from shore point a: three segments of about `step` toward angle t, a little zigzag.
std::vector<Point2> jetty_from(const Point2& a, double t, double step) {
  std::vector<Point2> jetty{a};
  for (int i = 1; i < 4; ++i)
    jetty.push_back({a[0] + step * i * std::cos(t) + (i % 2 ? 0.3 * step : 0), a[1] + step * i * std::sin(t)});
  return jetty;
}

using mesh_test::session_input;

// Random edits of Lake Superior's GSHHG rings through the library's ShoreSession, as `shoremesh edit`
// makes them: shore points moved, added after a vertex and removed, loose points added and removed,
// islands (small hexagons) and constraint lines (zigzags, some of them jetties from a shore vertex, which
// they share) added and removed, and the lines' points edited like the shore's. After each edit the mesh equals a fresh run on the edited
// input, triangle for triangle, and conforms; an edit the session refuses changes nothing.
TEST(ConformingMesh, RandomEditsThroughTheLibrarySessionOnSuperiorEqualAFreshRun) {
  const int edits = std::getenv("SHOREMESH_SANITIZER_BUILD") ? 30 : 300;
  ShoreSession<2> session(session_input(superior()), {});
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0, 1);
  // A live ring vertex, uniformly among the ids given so far.
  auto ring_vertex = [&]() -> std::optional<std::size_t> {
    for (int tries = 0; tries < 1000; ++tries) {
      const std::size_t id = rng() % session.next_id();
      if (session.contains(id) && session.ring_of(id)) return id;
    }
    return std::nullopt;
  };
  int made = 0, refused = 0, island_adds = 0, island_removals = 0, loose_edits = 0, line_adds = 0, jetty_adds = 0;
  std::vector<std::size_t> loose_ids;
  for (int attempt = 0; made < edits && attempt < 20 * edits; ++attempt) {
    const double what = u(rng);
    const std::size_t elements_before = session.mesh().element_count();
    try {
      if (what < 0.82) {
        const auto id = ring_vertex();
        ASSERT_TRUE(id);
        const auto [r, k] = *session.ring_of(*id);
        const auto& ring = session.ring(r);
        const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
        if (what < 0.4) {  // move toward the next vertex and a little off
          session.move(*id, {a[0] + 0.3 * (b[0] - a[0]) + 0.1 * (u(rng) - 0.5) * (b[1] - a[1]),
                             a[1] + 0.3 * (b[1] - a[1]) - 0.1 * (u(rng) - 0.5) * (b[0] - a[0])});
        } else if (what < 0.62) {  // add after it, near the middle of its segment
          session.add_after(*id, {0.5 * (a[0] + b[0]) + 0.05 * (u(rng) - 0.5) * (b[1] - a[1]),
                                  0.5 * (a[1] + b[1]) - 0.05 * (u(rng) - 0.5) * (b[0] - a[0])});
        } else {
          session.remove(*id);
        }
      } else if (what < 0.9) {  // a loose point near the shore, or one removed
        if (!loose_ids.empty() && u(rng) < 0.4) {
          const std::size_t j = rng() % loose_ids.size();
          session.remove(loose_ids[j]);
          loose_ids.erase(loose_ids.begin() + static_cast<std::ptrdiff_t>(j));
        } else {
          const auto id = ring_vertex();
          ASSERT_TRUE(id);
          const Point2 a = session.input_point(*id);
          const double d = 200 + 3000 * u(rng), t = 6.283185307179586 * u(rng);
          loose_ids.push_back(session.add({a[0] + d * std::cos(t), a[1] + d * std::sin(t)}).id);
        }
        ++loose_edits;
      } else if (what < 0.92) {  // a constraint line: a zigzag of four points a little off a shore point
        const auto id = ring_vertex();
        ASSERT_TRUE(id);
        const Point2 a = session.input_point(*id);
        const double d = 1500 + 4000 * u(rng), t = 6.283185307179586 * u(rng), step = 200 + 500 * u(rng);
        std::vector<Point2> zigzag;
        for (int i = 0; i < 4; ++i)
          zigzag.push_back({a[0] + d * std::cos(t) + step * i, a[1] + d * std::sin(t) + (i % 2 ? step : 0)});
        session.add_ring(zigzag, /*line=*/true);
        ++line_adds;
      } else if (what < 0.935) {  // a jetty: a line from a shore vertex out into the water, which it shares
        const auto id = ring_vertex();
        ASSERT_TRUE(id);
        const Point2 a = session.input_point(*id);
        const double t = 6.283185307179586 * u(rng), step = 300 + 600 * u(rng);
        session.add_ring(jetty_from(a, t, step), /*line=*/true);
        ++jetty_adds;
      } else if (what < 0.95) {  // an island: a small hexagon a little off a shore point
        const auto id = ring_vertex();
        ASSERT_TRUE(id);
        const Point2 a = session.input_point(*id);
        const double d = 1500 + 4000 * u(rng), t = 6.283185307179586 * u(rng), radius = 150 + 600 * u(rng);
        const Point2 c{a[0] + d * std::cos(t), a[1] + d * std::sin(t)};
        std::vector<Point2> hexagon;
        for (int i = 0; i < 6; ++i)
          hexagon.push_back({c[0] + radius * std::cos(1.0471975511965976 * i + t),
                             c[1] + radius * std::sin(1.0471975511965976 * i + t)});
        session.add_ring(hexagon);
        ++island_adds;
      } else {  // an island or a line removed (any live ring but the first, the lake's shore)
        std::vector<std::size_t> live;
        for (std::size_t r = 1; r < session.ring_count(); ++r)
          if (!session.ring(r).empty()) live.push_back(r);
        if (live.empty()) continue;
        session.remove_ring(live[rng() % live.size()]);
        ++island_removals;
      }
    } catch (const InputError&) {
      ++refused;  // invalid rings or a point already there: nothing changed
      ASSERT_EQ(session.mesh().element_count(), elements_before);
      continue;
    }
    ++made;
    ASSERT_TRUE(equals_a_fresh_run(session, made, made % 25 == 0 || made == edits));
  }
  EXPECT_EQ(made, edits);
  // The mix the test is for: every kind of edit happened (in the full run; the sanitizer build's 30 edits
  // are too few to meet every kind).
  if (edits >= 300) {
    EXPECT_GT(island_adds, 0);
    EXPECT_GT(island_removals, 0);
    EXPECT_GT(loose_edits, 0);
    EXPECT_GT(line_adds, 0);
    EXPECT_GT(jetty_adds, 0);
  }
  RecordProperty("refused edits", std::to_string(refused));
  std::printf("%d edits (%d islands added, %d lines and %d jetties added, %d rings or lines removed, %d loose "
              "points), %d refused\n",
              made, island_adds, line_adds, jetty_adds, island_removals, loose_edits, refused);
}

// Jetties: lines that end on a shore vertex, which they share (docs/conforming.md, "Shared vertices"),
// through random edits of a small wavy lake with an island: jetties added from ring vertices and removed,
// vertices added after a jetty's root and beside it, the shore and the jetties' points moved and removed.
// A jetty's root can be neither moved nor removed, nor its ring removed, while the jetty is there. After
// each edit the mesh equals a fresh run on the edited input and conforms.
TEST(ConformingMesh, JettiesThroughRandomEditsEqualAFreshRun) {
  Domain2 lake;
  for (const auto& [centre, radius, n, wave] :
       {std::tuple{Point2{0, 0}, 1000.0, 40, 0.12}, std::tuple{Point2{250, 100}, 180.0, 9, 0.0}}) {
    Ring ring{{}, lake.rings.empty() ? RingRole::Shore : RingRole::Island};
    for (int i = 0; i < n; ++i) {
      const double t = 6.283185307179586 * i / n, r = radius * (1 + wave * std::sin(5 * t));
      ring.points.push_back({centre[0] + r * std::cos(t), centre[1] + r * std::sin(t)});
    }
    lake.rings.push_back(std::move(ring));
  }
  ShoreSession<2>::Options options;
  options.box = BoxTransform<2>{{-1500, -1500}, 3000};
  ShoreSession<2> session(session_input(lake), options);
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<bool> closed_ring{true, true};  // by ring number: the lake, the island, then added ones
  std::size_t island = 1;  // the island's ring number while it is there
  bool island_there = true;
  auto vertex_of = [&](bool closed) -> std::optional<std::size_t> {
    for (int tries = 0; tries < 1000; ++tries) {
      const std::size_t id = rng() % session.next_id();
      if (!session.contains(id) || !session.ring_of(id)) continue;
      if (closed_ring.at(session.ring_of(id)->first) == closed) return id;
    }
    return std::nullopt;
  };
  int made = 0, jetties = 0, root_refusals = 0, removed_lines = 0;
  std::vector<std::size_t> roots;  // the first id of each jetty added (its root)
  for (int attempt = 0; made < 120 && attempt < 2000; ++attempt) {
    const double what = u(rng);
    const std::size_t elements_before = session.mesh().element_count();
    try {
      if (what < 0.3) {  // a jetty of three segments from a ring vertex, in a random direction
        const auto id = vertex_of(true);
        ASSERT_TRUE(id);
        const Point2 a = session.input_point(*id);
        const double t = 6.283185307179586 * u(rng), step = 40 + 60 * u(rng);
        session.add_ring(jetty_from(a, t, step), /*line=*/true);
        closed_ring.push_back(false);
        roots.push_back(*id);
        ++jetties;
      } else if (what < 0.45 && !roots.empty()) {  // beside a jetty's root: a vertex after it, or the root moved
        const std::size_t root = roots[rng() % roots.size()];
        if (!session.contains(root)) continue;
        const auto [r, k] = *session.ring_of(root);
        const auto& ring = session.ring(r);
        const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
        if (u(rng) < 0.7) {
          session.add_after(root, {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])});
        } else {
          try {
            session.move(root, {a[0] + 0.2 * (b[0] - a[0]), a[1] + 0.2 * (b[1] - a[1])});
          } catch (const InputError&) {
            ++root_refusals;  // the root of a live jetty
            throw;
          }
        }
      } else if (what < 0.75) {  // a vertex of a ring or a jetty moved, added after, or removed
        const auto id = vertex_of(u(rng) < 0.7);
        if (!id) continue;
        const auto [r, k] = *session.ring_of(*id);
        const auto& ring = session.ring(r);
        const bool closed = closed_ring.at(r);
        const Point2 a = ring[k], b = closed || k + 1 < ring.size() ? ring[(k + 1) % ring.size()] : ring[k - 1];
        const double c = u(rng);
        if (c < 0.45) session.move(*id, {a[0] + 0.3 * (b[0] - a[0]) + 0.05 * (b[1] - a[1]), a[1] + 0.3 * (b[1] - a[1])});
        else if (c < 0.8 && (closed || k + 1 < ring.size())) session.add_after(*id, {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])});
        else session.remove(*id);
      } else if (what < 0.9) {  // a jetty removed
        std::vector<std::size_t> live;
        for (std::size_t r = 0; r < session.ring_count(); ++r)
          if (!closed_ring[r] && !session.ring(r).empty()) live.push_back(r);
        if (live.empty()) continue;
        session.remove_ring(live[rng() % live.size()]);
        ++removed_lines;
      } else if (island_there) {  // the island removed (refused while a jetty ends on it)
        session.remove_ring(island);
        island_there = false;
      } else {  // and put back (refused where a line lies now)
        island = session.add_ring(lake.rings[1].points).ring.value();
        island_there = true;
        closed_ring.push_back(true);
      }
    } catch (const InputError&) {
      ASSERT_EQ(session.mesh().element_count(), elements_before);
      continue;
    }
    ++made;
    ASSERT_TRUE(equals_a_fresh_run(session, made, made % 10 == 0));
  }
  EXPECT_GE(made, 120);
  EXPECT_GT(jetties, 10);
  EXPECT_GT(root_refusals, 0);
  EXPECT_GT(removed_lines, 0);
  std::printf("%d edits, %d jetties added, %d removed, %d moves of a jetty's root refused\n", made, jetties, removed_lines,
              root_refusals);
}

// A .poly PSLG whose rings share vertices (fish-and-rectangle: the hole faces touch the outline at four
// pinch vertices; lines between water faces end on ring vertices and on one another) through random
// edits of the vertices no other ring shares: after each the mesh equals a fresh run and conforms; an
// edit of a shared vertex is refused, naming the point and its rings, and changes nothing.
TEST(ConformingMesh, PslgWithSharedVerticesThroughRandomEditsEqualsAFreshRun) {
  const io::PslgFile p = io::read_poly_file(mesh_test::samples("pslg/fish-and-rectangle.poly"));
  const PslgDomain d = pslg_domain(p.points, p.segments, p.holes);
  ASSERT_EQ(d.pinch_vertices.size(), 4u);
  SessionInput<2> in{p.points, d.domain, d.vertices};
  ShoreSession<2> session(in, {});
  std::mt19937 rng(61);
  std::uniform_real_distribution<double> u(0, 1);
  int made = 0, shared_refusals = 0, other_refusals = 0;
  const int edits = std::getenv("SHOREMESH_SANITIZER_BUILD") ? 20 : 80;
  for (int attempt = 0; made < edits && attempt < 40 * edits; ++attempt) {
    const std::size_t id = rng() % session.next_id();
    if (!session.contains(id) || !session.ring_of(id)) continue;
    const auto [r, k] = *session.ring_of(id);
    const auto& ring = session.ring(r);
    const bool closed = session.ring_role(r) != RingRole::Line;
    if (!closed && k + 1 == ring.size()) continue;
    const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
    const std::size_t elements_before = session.mesh().element_count();
    const double what = u(rng);
    try {
      if (what < 0.45) session.move(id, {a[0] + 0.25 * (b[0] - a[0]) + 0.03 * (u(rng) - 0.5) * (b[1] - a[1]),
                                         a[1] + 0.25 * (b[1] - a[1]) - 0.03 * (u(rng) - 0.5) * (b[0] - a[0])});
      else if (what < 0.75) session.add_after(id, {0.5 * (a[0] + b[0]) + 0.02 * (u(rng) - 0.5) * (b[1] - a[1]),
                                                   0.5 * (a[1] + b[1]) - 0.02 * (u(rng) - 0.5) * (b[0] - a[0])});
      else session.remove(id);
    } catch (const InputError& e) {
      const std::string message = e.what();
      if (message.find("which share it") != std::string::npos) {
        ++shared_refusals;
        EXPECT_NE(message.find("input point " + std::to_string(id) + " ("), std::string::npos) << message;
        EXPECT_NE(message.find((closed ? "ring " : "line ") + std::to_string(r + 1) + ", "), std::string::npos) << message;
      } else {
        ++other_refusals;
      }
      ASSERT_EQ(session.mesh().element_count(), elements_before);
      continue;
    }
    ++made;
    ASSERT_TRUE(equals_a_fresh_run(session, made, false));
    ASSERT_TRUE(session.shoreline().conforming()) << "after edit " << made;
  }
  EXPECT_EQ(made, edits);
  EXPECT_GT(shared_refusals, 0);
  std::printf("%d edits, %d refused at a shared vertex, %d refused otherwise\n", made, shared_refusals, other_refusals);
}

}  // namespace
}  // namespace shoremesh
