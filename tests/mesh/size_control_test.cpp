// Element size control (docs/sizing.md): the size function, its seeds and the session's edits under it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <set>

#include "mesh_test_util.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/mesh_water.hpp"
#include "shoremesh/shore_session.hpp"
#include "shoremesh/size_function.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

using Mesh2 = Mesh<2>;

using mesh_test::session_input;

// A square lake of side `side` (metres) with its four corners as the only shore points.
Domain2 square_lake(double side) {
  return {{Ring{{{0, 0}, {side, 0}, {side, side}, {0, side}}, RingRole::Shore}}};
}


SizePolygon square_polygon(double x0, double y0, double side, double size) {
  return {{{{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}}}, size, "test polygon"};
}

// A fresh run as `shoremesh mesh` makes it, without the session's code: h, the shore's splits under it,
// the seeds, the engine on all of them in the fixed box, the constrained mesh.
Mesh2 fresh_sized(const SessionInput<2>& in, const BoxTransform<2>& box, const SizeTerms& terms) {
  const auto field = std::make_shared<const SizeField>(terms, box, in.rings);
  const auto refinement = refine_input(in, box, field);
  std::vector<Point2> points = in.points;
  Domain2 refined;
  if (refinement) {
    for (const Point2& p : refinement->split_points()) points.push_back(p);
    refined = refinement->refined();
  }
  for (const Point2& p : size_seeds(*field, refined)) points.push_back(p);
  const StableResult<2> ws = stable_well_spaced<2>(points, session_parameters<2>(std::sqrt(2.0)), box, &in.rings);
  return Mesh2(ws.points, ws.input_count, refined);
}

ShoreSession<2>::Options sized(const SizeTerms& terms) {
  ShoreSession<2>::Options o;
  o.size = terms;
  return o;
}

double longest_edge(const Mesh2& mesh, const Element<2>& e) {
  const auto& p = mesh.points();
  double l = 0;
  for (int i = 0; i < 3; ++i) {
    const Point2 &a = p[e[i]], &b = p[e[(i + 1) % 3]];
    l = std::max(l, std::hypot(a[0] - b[0], a[1] - b[1]));
  }
  return l;
}

// Per mesh point: the mean length of its edges (the local size); and the mesh's edges.
struct LocalSizes {
  std::vector<double> size;
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
};
LocalSizes local_sizes(const Mesh2& mesh) {
  LocalSizes out;
  for (const auto& e : mesh.elements())
    for (int i = 0; i < 3; ++i) out.edges.insert(std::minmax(e[i], e[(i + 1) % 3]));
  std::vector<double> sum(mesh.points().size(), 0);
  std::vector<int> count(mesh.points().size(), 0);
  for (const auto& [a, b] : out.edges) {
    const auto &p = mesh.points()[a], &q = mesh.points()[b];
    const double l = std::hypot(p[0] - q[0], p[1] - q[1]);
    sum[a] += l, sum[b] += l, ++count[a], ++count[b];
  }
  out.size.resize(sum.size(), 0);
  for (std::size_t i = 0; i < sum.size(); ++i) out.size[i] = count[i] ? sum[i] / count[i] : 0;
  return out;
}

TEST(SizeFunction, BadSizesAreRefusedNamingTheTerm) {
  const Domain2 lake = square_lake(1000);
  const BoxTransform<2> box{{-50, -50}, 1100};
  auto message = [&](SizeTerms t) -> std::string {
    try {
      SizeField f(t, box, lake);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "accepted";
  };
  SizeTerms t;
  t.max_size = 0;
  EXPECT_NE(message(t).find("--max-size must be a positive"), std::string::npos) << message(t);
  t.max_size = std::nan("");
  EXPECT_NE(message(t).find("--max-size"), std::string::npos);
  t.max_size = -3;
  EXPECT_NE(message(t).find("--max-size"), std::string::npos);
  t.max_size = 10;
  t.min_size = 20;
  EXPECT_NE(message(t).find("--min-size 20 is larger than --max-size 10"), std::string::npos) << message(t);
  t.min_size.reset();
  t.grade = 0;
  EXPECT_NE(message(t).find("--grade must be above 0"), std::string::npos) << message(t);
  t.grade.reset();
  t.polygons.push_back(square_polygon(100, 100, 100, -1));
  EXPECT_NE(message(t).find("test polygon: size must be a positive"), std::string::npos) << message(t);
  t.polygons.clear();
  t.shore_size = 5;
  t.shore_rate = -1;
  EXPECT_NE(message(t).find("--size-from-shore RATE"), std::string::npos) << message(t);
  // The cap, term by term: 0.1 m over a square kilometre is about 2e8 points.
  SizeTerms cap;
  cap.max_size = 100;
  cap.shore_size = 0.1;
  cap.shore_rate = 0;
  EXPECT_NE(message(cap).find("--size-from-shore 0.1 0 asks for about"), std::string::npos) << message(cap);
  SizeTerms small_max;
  small_max.max_size = 0.2;
  EXPECT_NE(message(small_max).find("--max-size 0.2 asks for about"), std::string::npos) << message(small_max);
  SizeTerms sampled;
  sampled.max_size = 100;
  sampled.sampled.push_back({"--size-raster r.tif", [](const Point2&) { return 0.0; }});
  EXPECT_NE(message(sampled).find("--size-raster r.tif: size 0 at"), std::string::npos) << message(sampled);
}

// The water mask of the estimates and the summary is WaterTest's exact answer at every node, also where a
// ring passes through nodes (the box's square: on the ring, not water) or a hair beside them (an edge one
// ulp off a node, an edge one ulp off the horizontal along a row of nodes). Plain doubles (the crossing's x
// against the node's) put the square's nodes in the water.
TEST(SizeFunction, WaterMaskIsTheExactWaterTestAtEveryNode) {
  const BoxTransform<2> box{{0, 0}, 1024};
  Domain2 rings{{Ring{{{0, 0}, {1024, 0}, {1024, 1024}, {0, 1024}}, RingRole::Shore},
                 Ring{{{64, 64}, {256, 160}, {64, 256}}, RingRole::Shore},  // an edge through nodes
                 // the first edge a hair off the line through the nodes (512, 512), (640, 576), (768, 640)
                 Ring{{{512, 512}, {std::nextafter(768.0, 0.0), 640}, {512, 640}}, RingRole::Shore},
                 // an edge one ulp off the row y = 800, from a node
                 Ring{{{512, 800}, {900, std::nextafter(800.0, 1e9)}, {900, 900}, {512, 900}}, RingRole::Shore}}};
  SizeTerms t;
  t.max_size = 64;  // a grid of 32 x 32 cells of 32
  const SizeField field(t, box, rings);
  ASSERT_EQ(field.cells(), 32u);
  const WaterTest exact(rings);
  const std::size_t w = field.cells() + 1;
  std::size_t water = 0, on_ring = 0;
  for (std::size_t v = 0; v < w * w; ++v) {
    const Point2 p{box.origin[0] + double(v % w) * 32, box.origin[1] + double(v / w) * 32};
    ASSERT_EQ(field.water()[v] != 0, exact.in_water(p)) << "node " << p[0] << ", " << p[1];
    water += field.water()[v];
    on_ring += exact.classify(p) == WaterSide::OnRing;
  }
  EXPECT_GT(water, w * w / 2);
  EXPECT_GT(on_ring, 4 * 32u);  // the square's nodes and the island's
}

// The seeds' test against a shore segment is exact: a point at distance exactly `near` from a segment (the
// doubles' projection gives 0.9999999999999999 for 1) is clear, one a hair nearer is not; on the grown
// diametral circle is clear, a hair inside is not.
TEST(SizeSeeds, ClearOfShoreDecidesExactly) {
  EXPECT_TRUE(seed_clear_of_segment({1, 2}, {0, 0}, {4, 3}, 1.0, 0.0));
  EXPECT_FALSE(seed_clear_of_segment({1, 2}, {0, 0}, {4, 3}, std::nextafter(1.0, 2.0), 0.0));
  EXPECT_TRUE(seed_clear_of_segment({100007, 300014}, {100000, 300000}, {100028, 300021}, 7.0, 0.0));
  EXPECT_FALSE(seed_clear_of_segment({100007, std::nextafter(300014.0, 0.0)}, {100000, 300000}, {100028, 300021}, 7.0, 0.0));
  // The end of the segment decides beyond it.
  EXPECT_TRUE(seed_clear_of_segment({-3, -4}, {0, 0}, {4, 3}, 5.0, 0.0));
  EXPECT_FALSE(seed_clear_of_segment({-3, std::nextafter(-4.0, 0.0)}, {0, 0}, {4, 3}, 5.0, 0.0));
  // The diametral circle of (0,0)-(4,0) grown by 1.25: radius 2.5 about (2, 0).
  EXPECT_TRUE(seed_clear_of_segment({2, 2.5}, {0, 0}, {4, 0}, 0.5, 1.25));
  EXPECT_FALSE(seed_clear_of_segment({2, std::nextafter(2.5, 0.0)}, {0, 0}, {4, 0}, 0.5, 1.25));
}

// In size_seeds: a seed candidate exactly a quarter of its leaf from the corner of an island is kept; the
// island moved one ulp nearer, the seed goes (and its leaf's quarters fill in).
TEST(SizeSeeds, ACandidateExactlyAQuarterLeafFromTheShoreIsKept) {
  const double side = 100000, H = 8000;
  // The shore as its refinement would leave it: segments of 4 km (a segment's grown diametral circle
  // keeps seeds away, so the square's four sides alone would leave none).
  Domain2 lake{{Ring{{}, RingRole::Shore}}};
  for (int k = 0; k < 100; ++k) {
    const double t = 4000.0 * (k % 25);
    const std::array<Point2, 4> at{Point2{t, 0}, Point2{side, t}, Point2{side - t, side}, Point2{0, side - t}};
    lake.rings[0].points.push_back(at[static_cast<std::size_t>(k / 25)]);
  }
  const BoxTransform<2> box = BoxTransform<2>::fit(session_input(lake).points);
  SizeTerms t;
  t.max_size = H;
  const SizeField field(t, box, lake);
  const std::vector<Point2> open = size_seeds(field, lake);
  ASSERT_GT(open.size(), 100u);
  // The seed nearest the middle; where H binds its leaf's side is kSeedFactor * H.
  const Point2 p = *std::min_element(open.begin(), open.end(), [&](const Point2& a, const Point2& b) {
    return std::hypot(a[0] - side / 2, a[1] - side / 2) < std::hypot(b[0] - side / 2, b[1] - side / 2);
  });
  const double near = 0.25 * (kSeedFactor * H);
  auto with_island = [&](double x) {
    // A triangle with its corner (x, p_y) right of p; its edges leave that corner away from p, short
    // enough that p is outside their grown diametral circles.
    const Point2 a{x, p[1]};
    Domain2 d = lake;
    d.rings.push_back(Ring{{a, {a[0], a[1] + near}, {a[0] + near, a[1] + 0.5 * near}}, RingRole::Shore});
    return d;
  };
  const double x = p[0] + near;
  ASSERT_EQ(x - p[0], near);  // the corner is exactly `near` away
  const Domain2 exactly = with_island(x);
  const std::vector<Point2> kept = size_seeds(SizeField(t, box, exactly), exactly);
  EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), p));
  const Domain2 nearer = with_island(std::nextafter(x, p[0]));
  const std::vector<Point2> dropped = size_seeds(SizeField(t, box, nearer), nearer);
  EXPECT_FALSE(std::binary_search(dropped.begin(), dropped.end(), p));
  EXPECT_GT(dropped.size(), kept.size() - 1);  // the quarters of p's leaf
}

// limgrad's contract: the graded h is G-Lipschitz between grid neighbours, never above the ungraded one,
// and equal to it where that one already was graded (here: the constant far from the polygon).
TEST(SizeFunction, GradedFieldIsGLipschitzAndNeverAboveTheTerms) {
  const Domain2 lake = square_lake(100000);
  const BoxTransform<2> box = BoxTransform<2>::fit(session_input(lake).points);
  SizeTerms t;
  t.max_size = 8000;
  t.polygons.push_back(square_polygon(45000, 45000, 10000, 500));
  const SizeField raw(t, box, lake);
  t.grade = 0.2;
  const SizeField graded(t, box, lake);
  EXPECT_GT(raw.summary().grading, 1.0);
  EXPECT_LE(graded.summary().grading, 0.2 * (1 + 1e-9));
  for (std::size_t v = 0; v < raw.nodes().size(); ++v) ASSERT_LE(graded.nodes()[v], raw.nodes()[v]);
  EXPECT_EQ(graded.at({2000, 2000}), 8000);
  EXPECT_EQ(graded.at({50000, 50000}), 500);
  EXPECT_NEAR(graded.at({50000, 50000 + 5000 + 10000}), 500 + 0.2 * 10000, 0.2 * raw.box().side / double(raw.cells()) * 2);
}

// Grading: a 500 m polygon in an 8 km sea. Without --grade the mesh coarsens from the polygon as fast as
// the engine's well-spacing allows: a sharp jump of the local size s (mean incident edge length) away from
// the polygon; with --grade 0.2 the change is spread: 3 to 6 km from the polygon s is
// h there, about 1 to 2 km, not the sea's. With it, across every edge uv the ratio of local sizes stays
// within 1 + 2 G |uv| / min(h(u), h(v)) + C (C = 1.25, docs/sizing.md). Quantities of one edge (the ratio
// of local sizes, |s(u) - s(v)| / |uv|) do not show the jump: the engine's well-spacing bounds them with or
// without --grade, and the leaves' steps of two set their maxima (recorded, not asserted).
TEST(SizeControl, GradeSpreadsASizeJump) {
  const Domain2 lake = square_lake(100000);
  SizeTerms t;
  t.max_size = 8000;
  t.polygons.push_back(square_polygon(45000, 45000, 10000, 500));
  const double G = 0.2, C = 1.25;
  struct Measured {
    double near = 0, excess = 0, ratio = 0, gradient = 0;
  };
  auto measure = [&](const SizeTerms& terms) {
    const ShoreSession<2> session(session_input(lake), sized(terms));
    const LocalSizes s = local_sizes(session.mesh());
    Measured m;
    double sum = 0;
    int count = 0;
    for (std::size_t i = 0; i < s.size.size(); ++i) {
      const Point2& p = session.mesh().points()[i];
      const double dx = std::max({45000 - p[0], p[0] - 55000, 0.0}), dy = std::max({45000 - p[1], p[1] - 55000, 0.0});
      const double d = std::hypot(dx, dy);
      if (s.size[i] > 0 && d > 3000 && d < 6000) sum += s.size[i], ++count;
    }
    m.near = sum / count;
    for (const auto& [a, b] : s.edges) {
      const auto &p = session.mesh().points()[a], &q = session.mesh().points()[b];
      const double ratio = std::max(s.size[a], s.size[b]) / std::min(s.size[a], s.size[b]);
      const double h = std::min(session.size_field()->at(p), session.size_field()->at(q));
      m.ratio = std::max(m.ratio, ratio);
      m.gradient = std::max(m.gradient, std::abs(s.size[a] - s.size[b]) / std::hypot(p[0] - q[0], p[1] - q[1]));
      m.excess = std::max(m.excess, ratio - (1 + 2 * G * std::hypot(p[0] - q[0], p[1] - q[1]) / h));
    }
    return m;
  };
  const Measured sharp = measure(t);
  t.grade = G;
  const Measured graded = measure(t);
  RecordProperty("local size 3-6 km from the polygon without --grade", std::to_string(sharp.near));
  RecordProperty("local size 3-6 km from the polygon with --grade 0.2", std::to_string(graded.near));
  RecordProperty("largest ratio of local sizes across an edge without --grade", std::to_string(sharp.ratio));
  RecordProperty("largest ratio of local sizes across an edge with --grade 0.2", std::to_string(graded.ratio));
  RecordProperty("worst excess over 1 + 2G|uv|/h without --grade", std::to_string(sharp.excess));
  RecordProperty("worst excess over 1 + 2G|uv|/h with --grade 0.2", std::to_string(graded.excess));
  EXPECT_GT(sharp.near, 2 * graded.near);
  EXPECT_LT(graded.near, 500 + G * 6000);
  RecordProperty("largest |s(u) - s(v)| / |uv| without --grade", std::to_string(sharp.gradient));
  RecordProperty("largest |s(u) - s(v)| / |uv| with --grade 0.2", std::to_string(graded.gradient));
  EXPECT_LE(graded.excess, C);
}

// Each term changes the mesh where it should and nowhere else: against a run with --max-size alone,
// elements farther than `reach` from where the term is below the maximum are the same elements, and
// where the term binds, the elements honour it.
TEST(SizeControl, EachTermChangesTheMeshOnlyWhereItBinds) {
  const double side = 200000, H = 8000;
  const Domain2 lake = square_lake(side);
  const SessionInput<2> in = session_input(lake);
  const BoxTransform<2> box = BoxTransform<2>::fit(in.points);
  SizeTerms base;
  base.max_size = H;
  const auto before = mesh_test::corner_list(fresh_sized(in, box, base));
  // Where each term is below H: a box, and the distance from it beyond which nothing may change (the
  // seeds' leaves reach 1.5 leaf sides, the engine's Steiner points a few sizes more).
  struct Case {
    std::string what;
    SizeTerms terms;
    std::array<double, 4> binds;  // x0 y0 x1 y1
    double inner;                 // the size the term sets inside `binds`
  };
  std::vector<Case> cases;
  {
    Case c{"polygon", base, {20000, 20000, 50000, 50000}, 1500};
    c.terms.polygons.push_back(square_polygon(20000, 20000, 30000, 1500));
    cases.push_back(c);
  }
  {
    Case c{"sampled (raster)", base, {120000, 30000, 160000, 70000}, 2000};
    c.terms.sampled.push_back({"raster", [](const Point2& p) {
                                 return p[0] >= 120000 && p[0] <= 160000 && p[1] >= 30000 && p[1] <= 70000 ? 2000.0
                                                                                                            : std::nan("");
                               }});
    cases.push_back(c);
  }
  {
    // From the shore: 1000 m growing by 0.5 per metre passes H 14 km out.
    Case c{"shore", base, {0, 0, side, side}, 0};
    c.terms.shore_size = 1000;
    c.terms.shore_rate = 0.5;
    cases.push_back(c);
  }
  for (const Case& c : cases) {
    const Mesh2 mesh = fresh_sized(in, box, c.terms);
    const auto after = mesh_test::corner_list(mesh);
    const double reach = 5 * H;
    auto far = [&](const ElementCorners<2>& e) {
      for (const Point2& p : e) {
        if (c.what == "shore") {
          const double to_shore = std::min({p[0], p[1], side - p[0], side - p[1]});
          if (to_shore < 14000 + reach) return false;
        } else if (p[0] > c.binds[0] - reach && p[0] < c.binds[2] + reach && p[1] > c.binds[1] - reach &&
                   p[1] < c.binds[3] + reach) {
          return false;
        }
      }
      return true;
    };
    std::set<ElementCorners<2>> b, a;
    for (const auto& e : before)
      if (far(e)) b.insert(e);
    for (const auto& e : after)
      if (far(e)) a.insert(e);
    EXPECT_GT(b.size(), 20u) << c.what;
    EXPECT_EQ(a, b) << c.what << ": the mesh changed far from where the term binds";
    EXPECT_NE(after, before) << c.what << ": the term changed nothing";
    // Where it binds, h is the term's (to the grid's interpolation) and the longest edges honour h.
    const SizeField field(c.terms, box, lake);
    std::size_t inside = 0;
    for (const auto& e : mesh.elements()) {
      const auto &p = mesh.points()[e[0]], &q = mesh.points()[e[1]], &r = mesh.points()[e[2]];
      const Point2 g{(p[0] + q[0] + r[0]) / 3, (p[1] + q[1] + r[1]) / 3};
      const double term = c.what == "shore" ? 1000 + 0.5 * std::min({g[0], g[1], side - g[0], side - g[1]})
                          : g[0] > c.binds[0] && g[0] < c.binds[2] && g[1] > c.binds[1] && g[1] < c.binds[3]
                              ? c.inner
                              : H;
      if (term >= H) continue;
      ++inside;
      // h is the bilinear interpolant of the grid: within a cell of a polygon's edge it mixes both sides.
      const double cell = field.box().side / double(field.cells());
      const bool deep = c.what == "shore" || (g[0] > c.binds[0] + 2 * cell && g[0] < c.binds[2] - 2 * cell &&
                                              g[1] > c.binds[1] + 2 * cell && g[1] < c.binds[3] - 2 * cell);
      if (deep) {
        EXPECT_LE(field.at(g), 1.2 * term + cell) << c.what;
      }
      EXPECT_LE(longest_edge(mesh, e), 1.01 * field.at(g)) << c.what << " near " << g[0] << ", " << g[1];
    }
    EXPECT_GT(inside, 10u) << c.what;
  }
}

// Lemma 7.2 under size control: random shore edits (moves, additions, removals) and `size` edits of a
// polygon's size, on Superior with every kind of term, each compared with a fresh run on the edited input
// in the session's box, triangle for triangle. A size edit changes elements only within the reach of its
// polygon (where h can change: the graded cone from it).
// A random shore point of the session moved 0.3 of the way to its next vertex, a point added after it near its
// segment's midpoint, or the point removed; `wobble` (of the segment's length) moves each off the line.
void random_shore_edit(ShoreSession<2>& session, const std::string& kind, double wobble, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::size_t id = 0;
  do id = rng() % session.next_id();
  while (!session.contains(id) || !session.ring_of(id));
  const auto [r, k] = *session.ring_of(id);
  const auto& ring = session.ring(r);
  const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
  if (kind == "move")
    session.move(id, {a[0] + 0.3 * (b[0] - a[0]) + wobble * (u(rng) - 0.5) * (b[1] - a[1]),
                      a[1] + 0.3 * (b[1] - a[1]) - wobble * (u(rng) - 0.5) * (b[0] - a[0])});
  else if (kind == "add after")
    session.add_after(id, {0.5 * (a[0] + b[0]) + 0.5 * wobble * (u(rng) - 0.5) * (b[1] - a[1]),
                           0.5 * (a[1] + b[1]) - 0.5 * wobble * (u(rng) - 0.5) * (b[0] - a[0])});
  else
    session.remove(id);
}

TEST(SizeControl, RandomEditsUnderEveryTermEqualAFreshRunAfterEach) {
  const int edits = std::getenv("SHOREMESH_SANITIZER_BUILD") ? 5 : 16;
  SizeTerms t;
  t.max_size = 25000;
  t.shore_size = 10000;
  t.shore_rate = 0.5;
  t.grade = 0.5;
  t.polygons.push_back(square_polygon(-60000, 0, 40000, 8000));
  t.polygons.push_back(square_polygon(100000, -20000, 30000, 12000));
  t.sampled.push_back({"sampled", [](const Point2& p) { return p[0] < -200000 ? 15000.0 : std::nan(""); }});
  const SessionInput<2> start = session_input(mesh_test::superior());
  ShoreSession<2> session(start, sized(t));
  ASSERT_EQ(mesh_test::corner_list(session.mesh()), mesh_test::corner_list(fresh_sized(start, session.box(), t)));
  std::mt19937 rng(35);
  std::uniform_real_distribution<double> u(0, 1);
  int made = 0, size_edits = 0;
  std::string last;
  for (int attempt = 0; made < edits && attempt < 20 * edits; ++attempt) {
    const double what = u(rng);
    last = what < 0.3 ? "size" : what < 0.6 ? "move" : what < 0.8 ? "add after" : "remove";
    try {
      if (what < 0.3) {
        const std::size_t q = rng() % 2;
        const double size = 6000 + 15000 * u(rng);
        const SessionEdit<2> e = session.set_polygon_size(q, size);
        t.polygons[q].size = size;
        ++size_edits;
        // Where h may change: the polygon grown by (max - min size) / grade.
        const SizePolygon& p = t.polygons[q];
        const double reach = (*t.max_size - 6000) / *t.grade + 3 * *t.max_size;
        for (const auto* list : {&e.mesh.removed, &e.mesh.added})
          for (const auto& corners : *list)
            for (const Point2& c : corners)
              ASSERT_TRUE(c[0] > p.rings[0][0][0] - reach && c[0] < p.rings[0][2][0] + reach &&
                          c[1] > p.rings[0][0][1] - reach && c[1] < p.rings[0][2][1] + reach)
                  << "a size edit changed an element beyond its polygon's reach";
      } else {
        random_shore_edit(session, what < 0.6 ? "move" : what < 0.8 ? "add after" : "remove", 0.1, rng);
      }
    } catch (const InputError&) {
      continue;
    }
    ++made;
    ASSERT_EQ(mesh_test::corner_list(session.mesh()), mesh_test::corner_list(fresh_sized(session.current_input(), session.box(), t)))
        << "after edit " << made << " (" << last << ")";
  }
  EXPECT_EQ(made, edits);
  if (edits >= 16) {  // the sanitizer build's 5 edits may draw none
    EXPECT_GE(size_edits, 2);
  }
  EXPECT_THROW(session.set_polygon_size(7, 1000), InputError);
  EXPECT_THROW(session.set_polygon_size(0, -1), ParameterError);
}

using mesh_test::wobbly_lake;

SizeTerms wobbly_terms() {
  SizeTerms t;
  t.max_size = 8000;
  t.shore_size = 1500;
  t.shore_rate = 0.3;
  t.grade = 0.3;
  t.polygons.push_back(square_polygon(-30000, -10000, 20000, 2000));
  t.polygons.push_back(square_polygon(0, 20000, 15000, 3000));
  return t;
}

// Lemma 7.2 with the seeds updated locally: 100 random edits on a small lake under every kind of term (shore
// moves, additions and removals, which move h through --size-from-shore, and `size` edits), each compared
// with a fresh run, triangle for triangle. The session's seeds come from update_size_seeds, the fresh
// run's from size_seeds over the whole box.
TEST(SizeControl, RandomShoreAndSizeEditsWithLocalSeedsEqualAFreshRunAfterEach) {
  const int edits = std::getenv("SHOREMESH_SANITIZER_BUILD") ? 12 : 100;
  SizeTerms t = wobbly_terms();
  t.max_size = 12000, t.shore_size = 3000;  // a few hundred points: each fresh run is quick
  const SessionInput<2> start = session_input(wobbly_lake(90));
  ShoreSession<2> session(start, sized(t));
  ASSERT_EQ(mesh_test::corner_list(session.mesh()), mesh_test::corner_list(fresh_sized(start, session.box(), t)));
  std::mt19937 rng(3535);
  std::uniform_real_distribution<double> u(0, 1);
  int made = 0;
  std::map<std::string, int> kinds;
  for (int attempt = 0; made < edits && attempt < 10 * edits; ++attempt) {
    const double what = u(rng);
    const std::string kind = what < 0.35 ? "size" : what < 0.7 ? "move" : what < 0.85 ? "add after" : "remove";
    try {
      if (kind == "size") {
        const std::size_t q = rng() % 2;
        const double size = 1000 + 6000 * u(rng);
        session.set_polygon_size(q, size);
        t.polygons[q].size = size;
      } else {
        random_shore_edit(session, kind, 0.2, rng);
      }
    } catch (const InputError&) {
      continue;
    }
    ++made;
    ++kinds[kind];
    ASSERT_EQ(mesh_test::corner_list(session.mesh()), mesh_test::corner_list(fresh_sized(session.current_input(), session.box(), t)))
        << "after edit " << made << " (" << kind << ")";
  }
  EXPECT_EQ(made, edits);
  if (edits >= 100) {  // the sanitizer build's few edits may not meet every kind
    for (const char* k : {"size", "move", "add after", "remove"}) EXPECT_GE(kinds[k], 5) << k;
  }
}

// update_size_seeds equals size_seeds after every change and recomputes only near it: a `size` edit of a
// small polygon far from the other terms' detail and a shore move redo a small part of the quadtree.
TEST(SizeSeeds, LocalUpdateEqualsAFreshWalkAndStaysLocal) {
  const SizeTerms t = wobbly_terms();
  Domain2 lake = wobbly_lake(90);
  const SessionInput<2> in = session_input(lake);
  const BoxTransform<2> box = BoxTransform<2>::fit(in.points);
  auto refined_of = [&](const Domain2& d, const std::shared_ptr<const SizeField>& f) {
    return refine_input(session_input(d), box, f)->refined();
  };
  auto field = std::make_shared<const SizeField>(t, box, lake);
  Domain2 refined = refined_of(lake, field);
  std::vector<Point2> seeds = size_seeds(*field, refined);
  std::mt19937 rng(35);
  std::uniform_real_distribution<double> u(0, 1);
  std::size_t local_changes = 0;
  double redone = 0;
  for (int edit = 0; edit < 60; ++edit) {
    auto next = std::make_shared<SizeField>(*field);
    Domain2 next_lake = lake;
    if (edit % 2 == 0) {
      next->set_polygon_size(static_cast<std::size_t>(edit / 2 % 2), 1000 + 6000 * u(rng));
    } else {
      auto& ring = next_lake.rings[0].points;
      const std::size_t k = rng() % ring.size();
      const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
      ring[k] = {a[0] + 0.2 * (b[0] - a[0]), a[1] + 0.2 * (b[1] - a[1])};
      next->set_rings(next_lake);
    }
    const Domain2 next_refined = refined_of(next_lake, next);
    SeedUpdate stats;
    const std::vector<Point2> local = update_size_seeds(*field, seeds, refined, *next, next_refined, 1.25, &stats);
    seeds = size_seeds(*next, next_refined);
    ASSERT_EQ(local, seeds) << "edit " << edit;
    local_changes += stats.removed + stats.added;
    // A shore move changes h within (8000 - 1500) / 0.3 m of it (the shore term's cone): a part of the lake.
    if (edit % 2 == 1) {
      EXPECT_LT(stats.removed, seeds.size() / 2) << "edit " << edit;
    }
    redone = std::max(redone, double(stats.removed) / double(seeds.size()));
    field = next;
    lake = next_lake;
    refined = next_refined;
  }
  EXPECT_GT(local_changes, 0u);
  RecordProperty("largest share of the seeds walked again in one edit", std::to_string(redone));
}

}  // namespace
}  // namespace shoremesh
