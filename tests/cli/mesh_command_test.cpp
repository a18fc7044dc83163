// `shoremesh mesh` end to end: the point-set CSV contract (equal to the library's StableWS), every mesh
// format, the bundled Lake Superior image to a mesh and preview with a quality summary within the bound.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "cli_test_util.hpp"
#include "shoremesh/io/point_file.hpp"
#include "shoremesh/io/point_set_csv.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh::cli_test {
namespace {

using ::testing::HasSubstr;

// The numbers of the summary's first line: "quality: E triangles, P points (...); bound met by M of C covered".
struct Summary {
  std::size_t elements = 0, met = 0, covered = 0;
  double min_angle = 0, bound = 0;
};

Summary parse_summary(const std::string& out) {
  Summary s;
  std::smatch m;
  const std::regex first(R"(quality: (\d+) \w+, .*bound met by (\d+) of (\d+) covered)");
  EXPECT_TRUE(std::regex_search(out, m, first)) << out;
  if (m.empty()) return s;
  s.elements = std::stoul(m[1]);
  s.met = std::stoul(m[2]);
  s.covered = std::stoul(m[3]);
  const std::regex angles(R"(angles ([0-9.e+-]+)\.\.[0-9.e+-]+ deg \(guaranteed >= ([0-9.]+) deg)");
  if (std::regex_search(out, m, angles)) {
    s.min_angle = std::stod(m[1]);
    s.bound = std::stod(m[2]);
  }
  return s;
}

TEST(MeshCommand, PointFileToCsvEqualsTheLibrary) {
  TempDir dir;
  write_file(dir / "p.csv", random_points(400, 100, 60, 7));
  const RunResult r = shoremesh(dir, "mesh p.csv -o out.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("shoremesh: 400 input points, "));
  const auto file = io::read_point_set_csv<2>(dir / "out.csv");
  const auto input = io::read_point_file((dir / "p.csv").string());
  const auto expected = stable_well_spaced<2>(input.points2);
  EXPECT_EQ(file.box.origin, expected.box.origin);
  EXPECT_EQ(file.box.side, expected.box.side);
  EXPECT_EQ(file.points, expected.points);  // input points first, in file order, then the Steiner points

  // --box and --rho are honoured the same way.
  const RunResult b = shoremesh(dir, "mesh p.csv -o box.csv --box -10 -10 130 --rho 1.6");
  ASSERT_EQ(b.code, 0) << b.err;
  Parameters<2> p;
  p.rho = 1.6;
  const auto boxed = stable_well_spaced<2>(input.points2, p, BoxTransform<2>{{-10, -10}, 130});
  EXPECT_EQ(io::read_point_set_csv<2>(dir / "box.csv").points, boxed.points);
  EXPECT_EQ(read_file(dir / "box.csv").rfind("# box -10 -10 130\n", 0), 0u);
}

// n distinct integer points, one "x y z" line each: i -> (37 i mod x_cells, 17 i mod 53, 29 i mod 47).
std::string scrambled_lattice_3d(int n, int x_cells) {
  std::string text;
  for (int i = 0; i < n; ++i)
    text += std::to_string((i * 37) % x_cells) + " " + std::to_string((i * 17) % 53) + " " + std::to_string((i * 29) % 47) + "\n";
  return text;
}

// A point file has no shore: the mesh is clipped to the box, and every element meets the bound (the
// slivers along the box's edge are left out and counted); --keep-hull keeps them, and then some fail it.
TEST(MeshCommand, MeshIsClippedToTheBoxUnlessKeepHull) {
  TempDir dir;
  write_file(dir / "p.csv", random_points(300, 100, 60, 11));
  for (const std::string dim : {"2", "3"}) {
    if (dim == "3") write_file(dir / "p.csv", scrambled_lattice_3d(150, 101));
    const RunResult clipped = shoremesh(dir, "mesh p.csv -o clipped.vtu");
    ASSERT_EQ(clipped.code, 0) << clipped.err;
    const Summary c = parse_summary(clipped.out);
    std::smatch m;
    ASSERT_TRUE(std::regex_search(clipped.out, m, std::regex(R"(clipped to the box: (\d+) \w+ whose circumcentre)")))
        << clipped.out;
    const std::size_t left_out = std::stoul(m[1]);
    EXPECT_GT(left_out, 0u) << dim << "D";
    EXPECT_EQ(c.met, c.elements) << dim << "D";
    EXPECT_EQ(c.covered, c.elements) << dim << "D";
    if (dim == "2") {
      EXPECT_GE(c.min_angle, c.bound);
    }

    const RunResult whole = shoremesh(dir, "mesh p.csv -o whole.vtu --keep-hull");
    ASSERT_EQ(whole.code, 0) << whole.err;
    const Summary w = parse_summary(whole.out);
    EXPECT_EQ(w.elements, c.elements + left_out) << dim << "D";
    EXPECT_EQ(w.covered, c.elements) << dim << "D";
    EXPECT_THAT(whole.out, HasSubstr("meet it overall"));
    EXPECT_LT(read_file(dir / "clipped.vtu").size(), read_file(dir / "whole.vtu").size());
  }
}

TEST(MeshCommand, ThreeColumnPointFileIsSoundingsIn2DAndPointsIn3DWithDim3) {
  TempDir dir;
  write_file(dir / "p3.xyz", scrambled_lattice_3d(60, 61));
  const RunResult r = shoremesh(dir, "mesh p3.xyz --dim 3 -o p3.vtu");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("tetrahedra"));
  EXPECT_GT(fs::file_size(dir / "p3.vtu"), 1000u);
  const RunResult c = shoremesh(dir, "mesh p3.xyz --dim 3 -o p3.csv");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(io::read_point_set_csv<3>(dir / "p3.csv").points.size() >= 60, true);
  // By default the third column is a depth: a 2D mesh, said in the summary.
  const RunResult flat = shoremesh(dir, "mesh p3.xyz -o flat.msh");
  EXPECT_EQ(flat.code, 0) << flat.err;
  EXPECT_THAT(flat.out, HasSubstr("triangles"));
  EXPECT_THAT(flat.out, HasSubstr("third column: depths"));
}

// Soundings x, y, depth: each sounding node keeps its depth exactly; Steiner nodes interpolate linearly, so
// a planar sea floor (depth = 2 + x/10 + y/20) is reproduced at every node of the fort.14.
TEST(MeshCommand, SoundingsCarryTheirDepthsOntoTheNodes) {
  TempDir dir;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> u(0, 10000);
  std::string text = "x,y,depth\n";
  std::map<std::pair<double, double>, double> given;
  for (int i = 0; i < 200; ++i) {
    const double x = u(rng) / 100.0, y = u(rng) / 200.0, d = 2 + x / 10 + y / 20;
    if (!given.emplace(std::pair{x, y}, d).second) continue;
    text += io::format_double(x) + "," + io::format_double(y) + "," + io::format_double(d) + "\n";
  }
  write_file(dir / "soundings.csv", text);
  const RunResult r = shoremesh(dir, "mesh soundings.csv -o s.14");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("depths: "));
  std::istringstream in(read_file(dir / "s.14"));
  std::string line;
  std::getline(in, line);
  std::size_t ne = 0, np = 0, at_soundings = 0;
  in >> ne >> np;
  std::getline(in, line);
  for (std::size_t i = 0; i < np; ++i) {
    std::size_t id;
    double x, y, depth;
    in >> id >> x >> y >> depth;
    const auto it = given.find({x, y});
    if (it != given.end()) {
      ++at_soundings;
      EXPECT_EQ(depth, it->second) << x << ", " << y;
    } else if (x >= 5 && x <= 95 && y >= 3 && y <= 47) {  // well inside the soundings' hull
      EXPECT_NEAR(depth, 2 + x / 10 + y / 20, 1e-9) << x << ", " << y;
    }
  }
  EXPECT_EQ(at_soundings, given.size());
}

TEST(MeshCommand, EveryMeshFormatByExtensionOrFormat) {
  TempDir dir;
  write_file(dir / "p.csv", random_points(150, 50, 30, 3));
  for (const char* out : {"m.msh", "m.vtu", "m.node", "fort.14", "m.obj", "m.ply", "m.off"}) {
    const RunResult r = shoremesh(dir, std::string("mesh -q p.csv -o ") + out);
    EXPECT_EQ(r.code, 0) << out << r.err;
    EXPECT_TRUE(fs::exists(dir / out)) << out;
    EXPECT_THAT(r.out, HasSubstr(std::string("wrote ") + out));
  }
  EXPECT_TRUE(fs::exists(dir / "m.ele"));
  EXPECT_EQ(read_file(dir / "m.msh").rfind("$MeshFormat\n4.1", 0), 0u);
  const RunResult f = shoremesh(dir, "mesh p.csv -o mesh.txt --format vtu");
  EXPECT_EQ(f.code, 0) << f.err;
  EXPECT_THAT(read_file(dir / "mesh.txt"), HasSubstr("<VTKFile"));
  const Summary s = parse_summary(f.out);
  EXPECT_GT(s.covered, 0u);
  EXPECT_EQ(s.met, s.covered);
}

TEST(MeshCommand, SuperiorImageToMeshPreviewAndGeoJson) {
  TempDir dir;
  const std::string image = quote(superior_mask());
  const RunResult r =
      shoremesh(dir, "mesh " + image + " --largest-water --spacing 8000 -o superior.msh --preview superior.png");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(fs::file_size(dir / "superior.msh"), 10000u);
  EXPECT_EQ(read_file(dir / "superior.png").substr(1, 3), "PNG");
  EXPECT_THAT(r.out, HasSubstr("local transverse Mercator at 47.7"));  // lon/lat: centred on the data
  EXPECT_THAT(r.out, HasSubstr("shoreline: "));
  EXPECT_EQ(r.err.find('\033'), std::string::npos) << "a progress bar on a stderr that is not a terminal";
  // The summary: every covered triangle meets the radius-edge bound (angles >= 20.7 degrees) except those
  // the shore's constraints make, which the summary counts apart (docs/conforming.md: in the transverse
  // Mercator centred on the lake, 1 of 8,906 here; none in UTM 16N metres, which the mesh used before).
  const Summary s = parse_summary(r.out);
  EXPECT_GT(s.elements, 1000u);
  EXPECT_GT(s.covered, s.elements * 9 / 10);
  EXPECT_NEAR(s.bound, 20.7, 0.01);
  const std::size_t below = s.covered - s.met;
  EXPECT_LE(below, s.covered / 1000);
  if (below == 0)
    EXPECT_GE(s.min_angle, s.bound);
  else
    EXPECT_THAT(r.out, HasSubstr("at the shore: " + std::to_string(below) +
                                 " triangles below the bound are made by the shore's constraints (a point across the "
                                 "shore lies in their circumcircle); others below the bound: 0"));
  // Messages give lon/lat beside metres, never the unit box (the worst triangle: somewhere on the lake,
  // 84 to 92.5 W).
  EXPECT_THAT(r.out, ::testing::ContainsRegex(R"(worst triangle near .* m = 4[6-9]\.[0-9]+N (8[4-9]|9[0-2])\.[0-9]+W)"));

  const RunResult g = shoremesh(dir, "mesh -q " + image + " --largest-water --spacing 8000 -o superior.geojson");
  ASSERT_EQ(g.code, 0) << g.err;
  const auto geo = nlohmann::json::parse(read_file(dir / "superior.geojson"));
  double lon_min = 1e9, lon_max = -1e9;
  std::function<void(const nlohmann::json&)> walk = [&](const nlohmann::json& j) {
    if (j.is_array() && j.size() >= 2 && j[0].is_number() && j[1].is_number()) {
      lon_min = std::min(lon_min, j[0].get<double>());
      lon_max = std::max(lon_max, j[0].get<double>());
      EXPECT_GT(j[1].get<double>(), 46.0);
      EXPECT_LT(j[1].get<double>(), 49.3);
      return;
    }
    if (j.is_structured())
      for (const auto& c : j) walk(c);
  };
  walk(geo);
  EXPECT_GT(lon_min, -92.6);
  EXPECT_LT(lon_max, -83.9);
}

// The outputs and the summary are made at the same time (and their parts on every thread): the same
// bytes on one thread as on two; --timings adds one line on stderr and changes nothing else.
TEST(MeshCommand, SameOutputsOnOneThreadAndTwoAndATimingsLine) {
  TempDir dir;
  const std::string args = "mesh " + quote(superior_mask()) + " --largest-water --spacing 8000 --preview-colour quality";
  const RunResult one = shoremesh(dir, args + " -o one.msh --preview one.png --threads 1");
  ASSERT_EQ(one.code, 0) << one.err;
  const RunResult two = shoremesh(dir, args + " -o two.msh --preview two.png --threads 2 --timings");
  ASSERT_EQ(two.code, 0) << two.err;
  EXPECT_EQ(read_file(dir / "one.msh"), read_file(dir / "two.msh"));
  EXPECT_EQ(read_file(dir / "one.png"), read_file(dir / "two.png"));
  auto without_names = [](std::string text) {
    for (const char* name : {"one", "two"}) text = std::regex_replace(text, std::regex(name), "X");
    return text;
  };
  EXPECT_EQ(without_names(one.out), without_names(two.out));
  EXPECT_THAT(one.err, ::testing::Not(HasSubstr("timings")));
  EXPECT_THAT(two.err, HasSubstr("timings (wall): read "));
  for (const char* phase : {"read", "shore", "engine", "mesh", "write", "preview", "quality", "total"})
    EXPECT_THAT(two.err, ::testing::ContainsRegex(std::string(" ") + phase + " [0-9]+\\.[0-9]+ s")) << phase;
}

TEST(MeshCommand, ColourMapImageWithAUserBox) {
  TempDir dir;
  const std::string map = quote(samples("superior/superior_map_gmt.png"));
  const RunResult r = shoremesh(dir, "mesh " + map +
                                         " --water lightsteelblue --close-radius 1 --largest-water --map-box -92.5 46.2 "
                                         "-84 49.2 --crs lonlat --spacing 8000 -o map.ply");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("local transverse Mercator at 47.7"));  // lon/lat: centred on the data
  const Summary s = parse_summary(r.out);
  EXPECT_GT(s.covered, 500u);
  EXPECT_EQ(s.met, s.covered);
  EXPECT_EQ(read_file(dir / "map.ply").rfind("ply\n", 0), 0u);
}

TEST(MeshCommand, GpsWalkClosedByGuessCanBeKeptOpen) {
  TempDir dir;
  // One Cerknica walk ends within twice the spacing (40 m) of its start, so the reader closes it into a
  // shore ring, and that ring crosses itself: the error says why the walk was closed and how not to.
  const std::string gpx = quote(samples("cerknica/cerknicko-jezero.gpx"));
  const RunResult closed = shoremesh(dir, "mesh -q " + gpx + " --spacing 20 -o walk.msh");
  EXPECT_EQ(closed.code, 1);
  EXPECT_THAT(closed.err, HasSubstr("self-intersecting rings"));
  EXPECT_THAT(closed.err, HasSubstr("--track-close-distance 0 keeps every walk as loose points"));
  EXPECT_FALSE(std::filesystem::exists(dir / "walk.msh"));

  const RunResult open = shoremesh(dir, "mesh -q " + gpx + " --spacing 20 --track-close-distance 0 -o walk.msh");
  ASSERT_EQ(open.code, 0) << open.err;
  const Summary s = parse_summary(open.out);
  EXPECT_GT(s.covered, 1000u);
  EXPECT_EQ(s.met, s.covered);
  // The walks are sampled 20 m apart at most: the gaps between sparse fixes are cut, so there are more
  // input points than the file's 303 fixes, though the dense stretches are thinned.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(open.out, m, std::regex(R"(\(([0-9]+) input, )"))) << open.out;
  EXPECT_GT(std::stoul(m[1]), 303u);

  EXPECT_EQ(shoremesh(dir, "mesh -q " + gpx + " --track-close-distance nan -o walk.msh").code, 2);  // a usage mistake
}

}  // namespace
}  // namespace shoremesh::cli_test

namespace shoremesh::cli_test {
namespace {

// Checked from the exported mesh alone: each given segment a-b is a chain of mesh edges whose inner vertices
// lie on it (to rounding), and the triangles' area is `area`.
void expect_conforming_export(const TriangleFiles& t, const std::vector<std::vector<Point2>>& rings, double area,
                              const std::string& what) {
  std::set<std::pair<Point2, Point2>> edges;
  double sum = 0;
  std::map<Point2, std::vector<Point2>> next;
  for (const auto& tri : t.triangles) {
    const Point2 &a = t.nodes.at(tri[0]), &b = t.nodes.at(tri[1]), &c = t.nodes.at(tri[2]);
    sum += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      if (edges.insert(std::minmax(p, q)).second) {
        next[p].push_back(q);
        next[q].push_back(p);
      }
    }
  }
  EXPECT_NEAR(sum, area, 1e-9 * area) << what;
  std::size_t segments = 0, chained = 0;
  for (const auto& ring : rings)
    for (std::size_t k = 0; k < ring.size(); ++k, ++segments) {
      const Point2 a = ring[k], b = ring[(k + 1) % ring.size()];
      const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
      // Walk from a toward b along mesh edges whose far end lies on the segment and is nearer to b.
      Point2 at = a;
      for (int steps = 0; at != b && steps < 100000; ++steps) {
        std::optional<Point2> step;
        for (const Point2& q : next[at]) {
          const double off = std::abs((b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0])) / length;
          const double ahead = std::hypot(b[0] - q[0], b[1] - q[1]);
          if (off <= 1e-9 * length && ahead < std::hypot(b[0] - at[0], b[1] - at[1])) step = q;
        }
        if (!step) break;
        at = *step;
      }
      chained += at == b;
    }
  EXPECT_EQ(chained, segments) << what << ": shore segments that are chains of mesh edges";
}

double ring_area(const std::vector<Point2>& r) {
  double a = 0;
  for (std::size_t k = 0; k < r.size(); ++k) a += 0.5 * (r[k][0] * r[(k + 1) % r.size()][1] - r[(k + 1) % r.size()][0] * r[k][1]);
  return std::abs(a);
}

TEST(MeshCommand, ExportedMeshHasTheShoreAsItsBoundaryAndTheRingsArea) {
  TempDir dir;
  // A letter A as Triangle's A.poly draws it (sharp serifs, a triangular hole), as a ring file.
  const std::vector<std::vector<Point2>> letter{
      {{0, 0}, {1.2, 0}, {1.6, 1.2}, {3.4, 1.2}, {3.8, 0}, {5, 0}, {3.1, 6}, {1.9, 6}},
      {{2.0, 2.2}, {3.0, 2.2}, {2.5, 4.2}}};
  std::string text;
  for (const auto& r : letter) {
    for (std::size_t k = 0; k <= r.size(); ++k)
      text += io::format_double(r[k % r.size()][0]) + "," + io::format_double(r[k % r.size()][1]) + "\n";
    text += "\n";
  }
  write_file(dir / "letter.rings", text);
  const RunResult r = shoremesh(dir, "mesh letter.rings -o letter.node");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("shore segments are mesh edges (the shore is the mesh's boundary"));
  expect_conforming_export(read_triangle_files(dir / "letter.node"), letter,
                           ring_area(letter[0]) - ring_area(letter[1]), "letter A");
}

// A .poly as the test reads it (no code of the tool's): vertices, segments (0-based), hole seeds.
struct Pslg {
  std::vector<Point2> points;
  std::vector<std::array<std::size_t, 2>> segments;
  std::vector<Point2> holes;
};

Pslg read_pslg(const std::string& text) {
  std::istringstream in;
  std::string body;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) body += line.substr(0, line.find('#')) + "\n";
  in.str(body);
  Pslg g;
  std::size_t n = 0, dim = 0, attributes = 0, markers = 0;
  in >> n >> dim >> attributes >> markers;
  long first = 0;
  for (std::size_t i = 0; i < n; ++i) {
    long id = 0;
    Point2 p;
    double skip = 0;
    in >> id >> p[0] >> p[1];
    for (std::size_t k = 0; k < attributes + markers; ++k) in >> skip;
    if (i == 0) first = id;
    g.points.push_back(p);
  }
  std::size_t m = 0;
  in >> m >> markers;
  for (std::size_t i = 0; i < m; ++i) {
    long id = 0, a = 0, b = 0, marker = 0;
    in >> id >> a >> b;
    if (markers) in >> marker;
    g.segments.push_back({std::size_t(a - first), std::size_t(b - first)});
  }
  std::size_t h = 0;
  in >> h;
  for (std::size_t i = 0; i < h; ++i) {
    long id = 0;
    Point2 p;
    in >> id >> p[0] >> p[1];
    g.holes.push_back(p);
  }
  return g;
}

bool in_polygon(const std::vector<Point2>& poly, const Point2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Point2 &a = poly[j], &b = poly[i];
    if ((a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1])) in = !in;
  }
  return in;
}

double signed_area(const std::vector<Point2>& poly) {
  double a = 0;
  for (std::size_t k = 0; k < poly.size(); ++k)
    a += 0.5 * (poly[k][0] * poly[(k + 1) % poly.size()][1] - poly[(k + 1) % poly.size()][0] * poly[k][1]);
  return a;
}

// The water as Triangle's -p defines it, computed here on its own (floating point, for these small
// inputs): the faces of the segments (walks that keep each face on their left, neighbours sorted by
// angle); a face of positive area is bounded, and is water unless it holds a hole seed; a face of
// negative area is a connected part's outside, water when the bounded face holding the part is. Returns
// the water's area and the segments with water on at least one side.
struct PslgWater {
  double area = 0;
  std::vector<std::vector<Point2>> wet_segments;
};

PslgWater pslg_water(const Pslg& g) {
  std::map<std::size_t, std::vector<std::size_t>> around;
  for (const auto& s : g.segments) around[s[0]].push_back(s[1]), around[s[1]].push_back(s[0]);
  auto angle = [&](std::size_t v, std::size_t w) {
    return std::atan2(g.points[w][1] - g.points[v][1], g.points[w][0] - g.points[v][0]);
  };
  for (auto& [v, ws] : around) std::sort(ws.begin(), ws.end(), [&](std::size_t a, std::size_t b) { return angle(v, a) < angle(v, b); });
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> face_of;
  std::vector<std::vector<Point2>> faces;
  for (const auto& s : g.segments)
    for (auto [u, v] : {std::pair{s[0], s[1]}, std::pair{s[1], s[0]}}) {
      if (face_of.count({u, v})) continue;
      faces.emplace_back();
      while (face_of.emplace(std::pair{u, v}, faces.size() - 1).second) {
        faces.back().push_back(g.points[u]);
        const auto& ws = around[v];
        const std::size_t k = std::size_t(std::find(ws.begin(), ws.end(), u) - ws.begin());
        const std::size_t w = ws[(k + ws.size() - 1) % ws.size()];
        u = v, v = w;
      }
    }
  // The bounded face holding p, other than those through p: the smallest (nested faces are smaller).
  auto holding = [&](const Point2& p) -> std::optional<std::size_t> {
    std::optional<std::size_t> best;
    for (std::size_t f = 0; f < faces.size(); ++f)
      if (signed_area(faces[f]) > 0 && in_polygon(faces[f], p) &&
          std::find(faces[f].begin(), faces[f].end(), p) == faces[f].end() &&
          (!best || signed_area(faces[f]) < signed_area(faces[*best])))
        best = f;
    return best;
  };
  std::vector<bool> water(faces.size(), false);
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (signed_area(faces[f]) > 0)
      water[f] = std::none_of(g.holes.begin(), g.holes.end(), [&](const Point2& h) { return holding(h) == f; });
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (signed_area(faces[f]) <= 0) {  // zero: a part without cycles (a free chain)
      const auto outer = holding(faces[f].front());
      water[f] = outer && water[*outer];
    }
  PslgWater out;
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (water[f]) out.area += signed_area(faces[f]);
  for (const auto& s : g.segments)
    if (water[face_of.at({s[0], s[1]})] || water[face_of.at({s[1], s[0]})])
      out.wet_segments.push_back({g.points[s[0]], g.points[s[1]]});
  return out;
}

// Triangle's A.poly redrawn for this test: the letter's outline with a triangular hole (a seed in it), the
// top edge split at its middle with a segment down to the hole's apex (water on both sides, vertices of
// three segments), and a free chain of two segments in the left leg.
const char* kLetterA = R"(12 2 0 0
1 0 0
2 1.2 0
3 1.6 1.2
4 3.4 1.2
5 3.8 0
6 5 0
7 3.1 6
8 2.5 6
9 1.9 6
10 2.0 2.2
11 3.0 2.2
12 2.5 4.2
15 0
1 1 2
2 2 3
3 3 4
4 4 5
5 5 6
6 6 7
7 7 8
8 8 9
9 9 1
10 10 11
11 11 12
12 12 10
13 12 8
14 13 14
15 14 15
1
1 2.5 3.0
)";

TEST(MeshCommand, PslgSegmentsAreMeshEdgesHolesAreEmptyAndTheAreaIsTheWaters) {
  TempDir dir;
  // The letter needs its free chain's vertices: appended to its vertex list here.
  std::string letter = kLetterA;
  letter.replace(0, 2, "15");
  const std::size_t segments_at = letter.find("15 0\n");
  letter.insert(segments_at, "13 1.0 2.0\n14 1.3 3.0\n15 1.5 3.6\n");
  write_file(dir / "A.poly", letter);
  const std::vector<std::tuple<std::string, std::string, std::string>> cases{
      {"fish-and-rectangle", samples("pslg/fish-and-rectangle.poly"), "--spacing 0.1"},
      {"double_hex", samples("pslg/double_hex.poly"), ""},
      {"letter A", (dir / "A.poly").string(), ""},
      {"letter A at a spacing", (dir / "A.poly").string(), "--spacing 0.4"},
  };
  for (const auto& [what, path, options] : cases) {
    const Pslg g = read_pslg(read_file(path));
    const RunResult r = shoremesh(dir, "mesh " + quote(path) + " " + options + " -o out.node");
    ASSERT_EQ(r.code, 0) << what << ": " << r.err;
    EXPECT_THAT(r.out, HasSubstr("shore segments are mesh edges (the shore is the mesh's boundary")) << what;
    const TriangleFiles t = read_triangle_files(dir / "out.node");
    // Every segment with water beside it is a chain of mesh edges (a two-point ring: both ways); those
    // with land on both sides (between two hole faces) bound nothing.
    const PslgWater water = pslg_water(g);
    EXPECT_GT(water.area, 0) << what;
    expect_conforming_export(t, water.wet_segments, water.area, what);
    // Holes are empty: no triangle holds a hole seed.
    for (const Point2& h : g.holes)
      for (const auto& tri : t.triangles) {
        const Point2 &a = t.nodes[tri[0]], &b = t.nodes[tri[1]], &c = t.nodes[tri[2]];
        auto side = [&](const Point2& p, const Point2& q) { return (q[0] - p[0]) * (h[1] - p[1]) - (q[1] - p[1]) * (h[0] - p[0]); };
        EXPECT_FALSE(side(a, b) > 0 && side(b, c) > 0 && side(c, a) > 0) << what << ": a triangle holds hole seed " << h[0] << "," << h[1];
      }
  }
}

}  // namespace
}  // namespace shoremesh::cli_test
