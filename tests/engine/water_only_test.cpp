// Work only where the water is (docs/water_only.md): fills whose cell cannot meet the water are skipped,
// and a dynamic set whose rings are edited (vertices moved, added, removed; islands added and removed)
// equals a fresh run on the edited input after every edit.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/engine/engine.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/well_spaced.hpp"

using namespace shoremesh;

namespace {

constexpr double kTau = 6.283185307179586;

// A wavy lake (ring 0) in [0, 100]^2 with two islands; ring vertices are input points.
struct Lake {
  Domain2 domain;
  std::vector<std::vector<std::size_t>> ids;  // ring r's vertices as input ids
  std::vector<Point2> points;                 // by input id (a removed id keeps its place)
  std::vector<bool> alive;

  std::size_t add_point(const Point2& p) {
    points.push_back(p);
    alive.push_back(true);
    return points.size() - 1;
  }
  void add_ring(const std::vector<Point2>& ring, RingRole role) {
    domain.rings.push_back({{}, role});
    ids.emplace_back();
    for (const Point2& p : ring) {
      domain.rings.back().points.push_back(p);
      ids.back().push_back(add_point(p));
    }
  }
  std::vector<Point2> live_points() const {
    std::vector<Point2> out;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (alive[i]) out.push_back(points[i]);
    return out;
  }
};

std::vector<Point2> polygon(const Point2& c, double radius, int n, double wave, double phase) {
  std::vector<Point2> out;
  for (int i = 0; i < n; ++i) {
    const double t = kTau * i / n;
    const double r = radius * (1 + wave * std::sin(5 * t + phase));
    out.push_back({c[0] + r * std::cos(t), c[1] + r * std::sin(t)});
  }
  return out;
}

// `splits`: the shore's ring 0 also has input points inside its edges (as the shore's refinement makes
// them: a point of the edge, rounded), at k/8 of every other edge (k = 1..7: the middle ones are no
// neighbours of the edge's ends, so an edit that moves an end changes their wedge and nothing else near).
constexpr int kSplitsPerEdge = 7;

Lake make_lake(bool splits = false) {
  Lake lake;
  lake.add_ring(polygon({50, 50}, 38, 48, 0.12, 0.3), RingRole::Shore);
  lake.add_ring(polygon({40, 45}, 5, 7, 0.1, 1.0), RingRole::Island);
  lake.add_ring(polygon({62, 58}, 4, 6, 0.1, 2.0), RingRole::Island);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(20, 80);
  for (int i = 0; i < 12; ++i) lake.add_point({u(rng), u(rng)});
  if (splits) {
    const auto& ring = lake.domain.rings[0].points;
    for (std::size_t k = 0; k < ring.size(); k += 2) {
      const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
      for (int j = 1; j < kSplitsPerEdge + 1; ++j) {
        const double t = j / (kSplitsPerEdge + 1.0);
        lake.add_point({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])});
      }
    }
  }
  return lake;
}

// Whole cells: the skip on land alone (shore cells, the 2D default, leave the land without points, so
// that fewer fills are on land to skip).
Parameters<2> whole_cells() {
  Parameters<2> p;
  p.shore_cells = false;
  return p;
}

// Land all around the lake: the box reaches well beyond it.
const BoxTransform<2> kBox{{-60, -60}, 220};

// The Steiner points, sorted (DynamicWellSpaced::points lists them sorted after the inputs).
std::vector<Point2> steiner_of(const DynamicWellSpaced<2>& set) {
  const auto all = set.points();
  return {all.begin() + static_cast<std::ptrdiff_t>(set.input_count()), all.end()};
}

// A shore vertex's water wedge as the test knows it from the lake: the lines through v and prev, v and
// next, water on side `side` of prev -> v -> next (ring 0 counter-clockwise with the water inside, the
// islands counter-clockwise with it outside).
struct Wedge {
  Point2 prev, next;
  int side;
};

// The vertices in the closed water whose cell, restricted to their wedge when they have one, reaches
// beyond rho NN, rho^2 = 2 (1 + slack) (a fill enforces slack 2^-32). Exact: CGAL's Delaunay triangulation with
// exact constructions; the restricted cell's vertices are the circumcentres in the wedge and the points
// where its Voronoi edges cross the wedge's lines inside it. Hull vertices are left out.
std::size_t water_vertices_not_well_spaced_in_wedges(const std::vector<Point2>& points, const engine::WaterRings& water,
                                                     const std::map<Point2, Wedge>& wedges, std::size_t& checked,
                                                     std::size_t& wedged, double slack = 0x1p-32) {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  using DT = CGAL::Delaunay_triangulation_2<K>;
  DT dt;
  for (const Point2& p : points) dt.insert(K::Point_2(p[0], p[1]));
  engine::PredicateCounters pc;
  std::size_t bad = 0;
  checked = wedged = 0;
  const K::FT bound = K::FT(2) * (K::FT(1) + K::FT(slack));
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    const Point2 p{CGAL::to_double(v->point().x()), CGAL::to_double(v->point().y())};
    if (!water.in_closed_water(p, pc)) continue;
    const auto it = wedges.find(p);
    const Wedge* w = it == wedges.end() ? nullptr : &it->second;
    K::Point_2 prev, next;
    bool convex = true;
    if (w) {
      prev = K::Point_2(w->prev[0], w->prev[1]);
      next = K::Point_2(w->next[0], w->next[1]);
      convex = w->side * int(CGAL::orientation(prev, v->point(), next)) >= 0;
    }
    auto inside = [&](const K::Point_2& y) {
      if (!w) return true;
      const bool a = w->side * int(CGAL::orientation(prev, v->point(), y)) >= 0;
      const bool b = w->side * int(CGAL::orientation(v->point(), next, y)) >= 0;
      return convex ? a && b : a || b;
    };
    bool hull = false;
    K::FT nn2 = -1, far2 = 0;
    auto u = dt.incident_vertices(v), uend = u;
    do {
      if (dt.is_infinite(u)) hull = true;
      else if (const K::FT d2 = CGAL::squared_distance(v->point(), u->point()); nn2 < 0 || d2 < nn2) nn2 = d2;
    } while (++u != uend);
    if (hull) continue;
    std::vector<K::Point_2> centres;
    auto f = dt.incident_faces(v), fend = f;
    do centres.push_back(dt.circumcenter(f));
    while (++f != fend);
    auto reach = [&](const K::Point_2& y) {
      if (inside(y)) far2 = std::max(far2, CGAL::squared_distance(v->point(), y));
    };
    for (std::size_t k = 0; k < centres.size(); ++k) {
      reach(centres[k]);
      if (!w) continue;
      const K::Segment_2 edge(centres[k], centres[(k + 1) % centres.size()]);
      if (edge.is_degenerate()) continue;
      for (const K::Point_2& x : {prev, next})
        if (const auto hit = CGAL::intersection(edge, K::Line_2(v->point(), x)))
          if (const K::Point_2* y = boost::get<K::Point_2>(&*hit)) reach(*y);
    }
    ++checked;
    wedged += w != nullptr;
    bad += far2 > bound * nn2;
  }
  return bad;
}

// The vertices in the closed water whose whole Voronoi cell in `points` reaches beyond rho NN, rho^2 = 2
// exactly; hull vertices (an unbounded cell the box would clip) are left out.
std::size_t water_vertices_not_well_spaced(const std::vector<Point2>& points, const engine::WaterRings& water,
                                           std::size_t& checked) {
  std::size_t wedged = 0;
  return water_vertices_not_well_spaced_in_wedges(points, water, {}, checked, wedged, 0);
}

}  // namespace

// Whole cells (shore_cells off): the skip alone keeps every water vertex well-spaced in its whole cell.
TEST(WaterOnly, FillsOnLandAreSkippedAndNoneInTheWater) {
  const Lake lake = make_lake();
  const auto points = lake.live_points();
  const Parameters<2> whole = whole_cells();
  const DynamicWellSpaced<2> everywhere(points, whole, kBox);
  const DynamicWellSpaced<2> water(points, whole, kBox, BuildFor::Updates, [&] { return &lake.domain; });
  const auto& engine = water.set().engine();
  ASSERT_NE(engine.water(), nullptr);
  EXPECT_GT(engine.counters().fills_on_land, 0u);
  EXPECT_EQ(everywhere.set().engine().counters().fills_on_land, 0u);
  EXPECT_LT(water.steiner_count(), everywhere.steiner_count());
  // Every skipped vertex lies strictly on land, and every vertex in the closed water is as well-spaced as
  // without the skip: no fill of a vertex there was skipped.
  engine::PredicateCounters pc;
  const auto skipped = engine.vertices_skipped_on_land();
  EXPECT_FALSE(skipped.empty());
  for (const auto v : skipped) EXPECT_FALSE(engine.water()->in_closed_water(engine.positions()[v], pc));
  // What the water mesh needs: every vertex in the water is rho-well-spaced in the whole output.
  std::vector<Point2> unit;
  for (engine::VertexId v = 0; v < engine.vertex_count(); ++v)
    if (engine.vertex(v).alive) unit.push_back(engine.positions()[v]);
  std::size_t checked = 0;
  EXPECT_EQ(water_vertices_not_well_spaced(unit, *engine.water(), checked), 0u);
  EXPECT_GT(checked, 100u);
  // A one-shot build makes the same points.
  const StableResult<2> once = stable_well_spaced<2>(points, whole, kBox, &lake.domain);
  std::vector<Point2> once_steiner(once.points.begin() + static_cast<std::ptrdiff_t>(once.input_count), once.points.end());
  std::sort(once_steiner.begin(), once_steiner.end());
  EXPECT_EQ(once_steiner, steiner_of(water));
  EXPECT_EQ(once.counters.fills_on_land, engine.counters().fills_on_land);
}

// Random edits of the rings and the loose points; after each, the output and the operations equal a fresh
// run's on the edited input with the edited rings. `stretches`: two edits in three give the engine the
// edit of the rings as a stretch (as the edit session does), the third none (it compares the rings).
void ring_edits_equal_a_fresh_run(bool stretches, const Parameters<2>& parameters = whole_cells(), bool splits = false) {
  Lake lake = make_lake(splits);
  DynamicWellSpaced<2> set(lake.points, parameters, kBox, BuildFor::Updates, [&] { return &lake.domain; });
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0, 1);
  int made = 0, island_adds = 0, island_removals = 0, skipped_runs = 0;
  for (int attempt = 0; made < 60 && attempt < 1000; ++attempt) {
    const double what = u(rng);
    std::vector<Edit<2>> edits;
    // The stretch of this edit: its points before and after, kept alive until the apply.
    std::vector<Point2> before, after;
    std::optional<WaterStretch> stretch;
    // Ring 0 or a live island, and one of its vertices.
    std::vector<std::size_t> live;
    for (std::size_t r = 0; r < lake.ids.size(); ++r)
      if (!lake.ids[r].empty()) live.push_back(r);
    const std::size_t r = live[rng() % live.size()];
    auto& ring = lake.domain.rings[r].points;
    auto& ids = lake.ids[r];
    const std::size_t k = rng() % ring.size();
    const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
    if (what < 0.35) {  // move a ring vertex a little toward its next one and off
      const Point2 p{a[0] + 0.3 * (b[0] - a[0]) + 0.2 * (u(rng) - 0.5) * (b[1] - a[1]),
                     a[1] + 0.3 * (b[1] - a[1]) - 0.2 * (u(rng) - 0.5) * (b[0] - a[0])};
      before = {ring[k]}, after = {p};
      stretch = WaterStretch{r, k, ring.size() - k - 1, before, after, false};
      ring[k] = p;
      lake.points[ids[k]] = p;
      edits.push_back({Edit<2>::Kind::Move, ids[k], p});
    } else if (what < 0.55) {  // a vertex after it
      const Point2 p{0.5 * (a[0] + b[0]) + 0.1 * (u(rng) - 0.5) * (b[1] - a[1]),
                     0.5 * (a[1] + b[1]) - 0.1 * (u(rng) - 0.5) * (b[0] - a[0])};
      after = {p};
      stretch = WaterStretch{r, k + 1, ring.size() - k - 1, before, after, false};
      ring.insert(ring.begin() + static_cast<std::ptrdiff_t>(k + 1), p);
      ids.insert(ids.begin() + static_cast<std::ptrdiff_t>(k + 1), lake.add_point(p));
      edits.push_back({Edit<2>::Kind::Add, 0, p});
    } else if (what < 0.7) {  // remove it
      if (ring.size() <= 5) continue;
      before = {ring[k]};
      stretch = WaterStretch{r, k, ring.size() - k - 1, before, after, false};
      edits.push_back({Edit<2>::Kind::Remove, ids[k], {}});
      lake.alive[ids[k]] = false;
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
      ids.erase(ids.begin() + static_cast<std::ptrdiff_t>(k));
    } else if (what < 0.82) {  // an island in the lake
      const Point2 c{35 + 30 * u(rng), 35 + 30 * u(rng)};
      lake.add_ring(polygon(c, 1.5 + 2 * u(rng), 6, 0.05, u(rng) * kTau), RingRole::Island);
      after = lake.domain.rings.back().points;
      stretch = WaterStretch{lake.domain.rings.size() - 1, 0, 0, before, after, true};
      for (std::size_t id : lake.ids.back()) edits.push_back({Edit<2>::Kind::Add, 0, lake.points[id]});
      ++island_adds;
    } else if (what < 0.92) {  // an island removed (its number stays, without points)
      if (live.size() < 2) continue;
      const std::size_t gone = live[1 + rng() % (live.size() - 1)];
      for (std::size_t id : lake.ids[gone]) {
        edits.push_back({Edit<2>::Kind::Remove, id, {}});
        lake.alive[id] = false;
      }
      lake.ids[gone].clear();
      before = lake.domain.rings[gone].points;
      stretch = WaterStretch{gone, 0, 0, before, after, true};
      lake.domain.rings[gone].points.clear();
      ++island_removals;
    } else {  // a loose point, in the water or on land
      edits.push_back({Edit<2>::Kind::Add, 0, Point2{100 * u(rng), 100 * u(rng)}});
      lake.add_point(edits.back().point);
    }
    // The ids the set gives added points are the next ones: as the lake numbers them.
    try {
      const bool given = stretches && made % 3 != 2;
      const auto added = given ? set.apply(edits, nullptr, stretch ? std::span<const WaterStretch>(&*stretch, 1)
                                                                   : std::span<const WaterStretch>())
                               : set.apply(edits);
      for (std::size_t j = 0; j < added.size(); ++j) ASSERT_EQ(added[j], lake.points.size() - added.size() + j);
    } catch (const InputError& e) {
      FAIL() << "edit " << made + 1 << " refused: " << e.what();
    }
    ++made;
    const DynamicWellSpaced<2> fresh(lake.live_points(), parameters, kBox, BuildFor::Updates, [&] { return &lake.domain; });
    ASSERT_EQ(steiner_of(set), steiner_of(fresh)) << "after edit " << made;
    ASSERT_EQ(set.set().engine().operation_signature(), fresh.set().engine().operation_signature())
        << "after edit " << made;
    skipped_runs += fresh.set().engine().counters().fills_on_land > 0;
    if (made % 10 == 0) set.set().check_valid();
  }
  EXPECT_EQ(made, 60);
  EXPECT_GT(island_adds, 0);
  EXPECT_GT(island_removals, 0);
  EXPECT_EQ(skipped_runs, made);  // every fresh run skipped some fills: the rule was exercised
}

TEST(WaterOnly, RingEditsEqualAFreshRun) { ring_edits_equal_a_fresh_run(false); }

// The session's way (the edit's stretch, no ring compared), mixed with edits that compare the rings after
// catching the engine's copy up with the stretches given before.
TEST(WaterOnly, RingEditsGivenAsStretchesEqualAFreshRun) { ring_edits_equal_a_fresh_run(true); }

// Cells that stop at the shore (docs/water_only.md): the same identity with shore_cells on, on a lake whose
// shore has splits inside its edges too.
TEST(ShoreCells, RingEditsWithShoreCellsEqualAFreshRun) {
  Parameters<2> parameters;
  parameters.shore_cells = true;
  ring_edits_equal_a_fresh_run(true, parameters, true);
}

// What a fill with shore_cells enforces, checked from the output alone: every vertex in the water is
// rho-well-spaced in its Voronoi cell restricted to its water wedge (the whole cell off the shore), and
// the rule inserted fewer points than the whole cells do.
TEST(ShoreCells, WaterVerticesAreWellSpacedInTheirWaterWedges) {
  const Lake lake = make_lake(true);
  const auto points = lake.live_points();
  Parameters<2> parameters;
  parameters.shore_cells = true;
  const DynamicWellSpaced<2> whole(points, whole_cells(), kBox, BuildFor::Updates, [&] { return &lake.domain; });
  const DynamicWellSpaced<2> set(points, parameters, kBox, BuildFor::Updates, [&] { return &lake.domain; });
  EXPECT_LT(set.steiner_count(), whole.steiner_count());
  std::map<Point2, Wedge> wedges;
  for (std::size_t r = 0; r < lake.domain.rings.size(); ++r) {
    const auto& ring = lake.domain.rings[r].points;
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < n; ++k)
      wedges[kBox.to_unit(ring[k])] = {kBox.to_unit(ring[(k + n - 1) % n]), kBox.to_unit(ring[(k + 1) % n]), r == 0 ? 1 : -1};
  }
  // The splits: the points after the loose ones, made as make_lake makes them.
  {
    const auto& ring = lake.domain.rings[0].points;
    std::size_t id = lake.points.size() - kSplitsPerEdge * ((ring.size() + 1) / 2);
    for (std::size_t k = 0; k < ring.size(); k += 2)
      for (int j = 0; j < kSplitsPerEdge; ++j, ++id)
        wedges[kBox.to_unit(lake.points[id])] = {kBox.to_unit(ring[k]), kBox.to_unit(ring[(k + 1) % ring.size()]), 1};
  }
  const auto& engine = set.set().engine();
  std::vector<Point2> unit;
  for (engine::VertexId v = 0; v < engine.vertex_count(); ++v)
    if (engine.vertex(v).alive) unit.push_back(engine.positions()[v]);
  std::size_t checked = 0, wedged = 0;
  EXPECT_EQ(water_vertices_not_well_spaced_in_wedges(unit, *engine.water(), wedges, checked, wedged), 0u);
  EXPECT_GT(checked, 100u);
  EXPECT_GT(wedged, 50u);
  // Not every shore vertex is well-spaced in its whole cell: the wedge made a difference.
  std::size_t whole_checked = 0;
  EXPECT_GT(water_vertices_not_well_spaced(unit, *engine.water(), whole_checked), 0u);
}

namespace {
// The same rings twice: `gridded` as assign leaves them (the grid of cell parities), `by_ray` after an edit
// that takes one edge out and in again (an edit drops the grid: every parity from a ray).
struct TwoWaters {
  engine::WaterRings gridded, by_ray;
  explicit TwoWaters(const std::vector<std::vector<Point2>>& rings) {
    gridded.assign(rings);
    by_ray.assign(rings);
    const std::vector<Point2> edge{rings[0][0], rings[0][1]};
    Point2 lo{1, 1}, hi{0, 0};
    EXPECT_TRUE(by_ray.apply({edge, edge, false}, lo, hi));
  }
};
}  // namespace

// The grid decides a point's parity in its cell; where that is not clear-cut (a segment from the cell's
// centre through an edge's end, a centre on an edge) the ray does. Both must give the same water
// everywhere: random points, the cells' centres and corners, points on the rings and beside them, on rings
// with vertices at cell centres and edges along the centres' rows and columns (128 x 128 cells here).
TEST(WaterRings, GridParityEqualsTheRayEverywhere) {
  std::vector<std::vector<Point2>> rings;
  rings.push_back(polygon({0.5, 0.5}, 0.35, 3000, 0.1, 0.3));
  rings.push_back(polygon({0.45, 0.55}, 0.05, 200, 0.2, 1.0));
  constexpr double g = 128;
  auto centre = [&](double i) { return (i + 0.5) / g; };
  // A square island with its corners at centres (its edges along centre rows and columns), and a triangle
  // with a vertex at a centre and a slanted edge through two.
  rings.push_back({{centre(70), centre(40)}, {centre(80), centre(40)}, {centre(80), centre(50)}, {centre(70), centre(50)}});
  rings.push_back({{centre(60), centre(80)}, {centre(66), centre(86)}, {centre(60), centre(90)}});
  TwoWaters w(rings);
  std::vector<Point2> probes;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int k = 0; k < 40000; ++k) probes.push_back({unit(rng), unit(rng)});
  for (int i = 0; i < 128; ++i)
    for (int j = 0; j < 128; ++j) {
      probes.push_back({centre(i), centre(j)});
      probes.push_back({i / g, j / g});
      probes.push_back({centre(i), j / g});
    }
  for (const auto& ring : rings)
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const Point2& a = ring[k];
      const Point2& b = ring[(k + 1) % ring.size()];
      probes.push_back(a);
      probes.push_back({0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])});
      probes.push_back({a[0], std::nextafter(a[1], 2.0)});
      probes.push_back({std::nextafter(a[0], -1.0), a[1]});
      probes.push_back({a[0] + 1e-4, a[1]});
      probes.push_back({a[0], a[1] - 1e-4});
    }
  std::size_t water = 0;
  engine::PredicateCounters pc;
  for (const Point2& p : probes) {
    const bool in = w.gridded.in_closed_water(p, pc);
    ASSERT_EQ(in, w.by_ray.in_closed_water(p, pc)) << "at (" << p[0] << ", " << p[1] << ")";
    water += in;
  }
  EXPECT_GT(water, probes.size() / 5);
  EXPECT_LT(water, probes.size() * 4 / 5);
}

// A point of a cell no edge meets takes the cell's parity without a predicate; the ray from it crosses the shore.
TEST(WaterRings, GridDecidesACellWithoutEdgesAlone) {
  TwoWaters w({polygon({0.5, 0.5}, 0.35, 3000, 0.1, 0.3)});
  engine::PredicateCounters gridded, by_ray;
  EXPECT_TRUE(w.gridded.in_closed_water({0.5, 0.5}, gridded));
  EXPECT_TRUE(w.by_ray.in_closed_water({0.5, 0.5}, by_ray));
  EXPECT_EQ(gridded.calls, 0u);
  EXPECT_GT(by_ray.calls, 0u);
  EXPECT_FALSE(w.gridded.in_closed_water({0.02, 0.03}, gridded));
  EXPECT_EQ(gridded.calls, 0u);
}

// Boxes against the shore by the grid's cell lists (each edge taken once, in the first cell of the box
// that lists it) must find the R-tree's edges: every one, none twice. Random boxes from a point to a few
// cells wide (about the grid's limit), boxes with their sides on cell borders, point boxes at ring
// vertices, boxes reaching past the unit box beside rings that touch its sides, and boxes too large for
// the grid (the R-tree answers both).
TEST(WaterRings, GridEdgesMeetingEqualTheTreesEdges) {
  std::vector<std::vector<Point2>> rings;
  rings.push_back(polygon({0.5, 0.5}, 0.35, 3000, 0.1, 0.3));
  rings.push_back(polygon({0.45, 0.55}, 0.05, 200, 0.2, 1.0));
  rings.push_back({{0.0, 0.2}, {0.03, 0.25}, {0.0, 0.3}});      // on the left side of the unit box
  rings.push_back({{0.6, 1.0}, {0.65, 0.97}, {0.7, 1.0}});      // on the top side
  rings.push_back({{1.0, 0.0}, {1.0, 0.04}, {0.96, 0.0}});      // in the corner (1, 0)
  TwoWaters w(rings);
  constexpr double g = 128;  // the grid of 3,406 edges
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-0.02, 1.02), width(0, 3 / g);
  std::uniform_int_distribution<int> cell(-1, 129), cells(0, 4);
  std::vector<std::pair<Point2, Point2>> boxes;
  for (int k = 0; k < 20000; ++k) {
    const Point2 lo{unit(rng), unit(rng)};
    boxes.push_back({lo, {lo[0] + width(rng), lo[1] + width(rng)}});
    const Point2 on{cell(rng) / g, cell(rng) / g};  // sides on cell borders
    boxes.push_back({on, {on[0] + cells(rng) / g, on[1] + cells(rng) / g}});
    boxes.push_back({lo, {lo[0] + 0.2, lo[1] + 0.1}});  // too many cells
  }
  for (const auto& ring : rings)
    for (const Point2& a : ring) {
      boxes.push_back({a, a});
      boxes.push_back({{a[0] - 0x1p-48, a[1] - 0x1p-48}, {a[0] + 0x1p-48, a[1] + 0x1p-48}});
    }
  boxes.push_back({{-1, -1}, {-0.5, 2}});
  boxes.push_back({{1, 1}, {1, 1}});
  engine::PredicateCounters pc;
  std::size_t met = 0;
  for (const auto& [lo, hi] : boxes) {
    std::vector<std::array<Point2, 2>> by_grid, by_tree;
    w.gridded.edges_meeting(lo, hi, pc, by_grid);
    w.by_ray.edges_meeting(lo, hi, pc, by_tree);
    std::sort(by_grid.begin(), by_grid.end());
    std::sort(by_tree.begin(), by_tree.end());
    ASSERT_EQ(by_grid, by_tree) << "box (" << lo[0] << ", " << lo[1] << ") - (" << hi[0] << ", " << hi[1] << ")";
    const Point2 inside{0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])};
    ASSERT_EQ(w.gridded.may_meet_water(inside, lo, hi, pc), w.by_ray.may_meet_water(inside, lo, hi, pc));
    met += !by_tree.empty();
  }
  EXPECT_GT(met, boxes.size() / 10);
}
