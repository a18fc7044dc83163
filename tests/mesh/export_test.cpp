// Every export is read back by a reader this project did not write (meshio, Debian's gmsh, nlohmann's
// JSON parser) and compared with the mesh: counts, coordinates, groups.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "mesh_test_util.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/mesh.hpp"

namespace shoremesh {
namespace {

using io::ExportFormat;
using io::MeshSnapshot;
using mesh_test::ScratchDir;
using nlohmann::json;

// Runs a command and returns its standard output; fails the test on a non-zero exit.
std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  char buffer[65536];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  const int status = ::pclose(pipe);
  EXPECT_EQ(status, 0) << command;
  return out;
}

json meshio_read(const std::filesystem::path& file, const std::string& format = "") {
  const auto script = std::filesystem::path(SHOREMESH_SAMPLES_DIR).parent_path() / "tests/mesh/read_back.py";
  return json::parse(run("/usr/bin/python3 '" + script.string() + "' '" + file.string() + "' " + format));
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A lake (10 x 10 square) with a square island, sampled at spacing 1, and its mesh.
Mesh2 lake_mesh() {
  Domain2 domain = mesh_test::subdivide({{Ring{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, RingRole::Shore},
                                          Ring{{{4, 4}, {6, 4}, {6, 6}, {4, 6}}, RingRole::Island}}},
                                         1.0);
  std::size_t input_count = 0;
  const auto points = mesh_test::sample_domain(domain, 1.0, 0.4, 3, input_count);
  return Mesh2(points, input_count, domain);
}

// Points and elements read back must be the mesh's (meshio pads 2D points with z = 0; some readers drop it).
template <int D>
void expect_same_mesh(const json& read, const io::MeshView<D>& view, const std::string& cell_type,
                      std::size_t expected_cells) {
  ASSERT_EQ(read["points"].size(), view.points.size());
  for (std::size_t i = 0; i < view.points.size(); ++i)
    for (int k = 0; k < D; ++k) ASSERT_EQ(read["points"][i][k].get<double>(), view.points[i][k]) << "point " << i;
  ASSERT_TRUE(read["cells"].contains(cell_type)) << read["cells"].dump().substr(0, 200);
  const auto& cells = read["cells"][cell_type];
  ASSERT_EQ(cells.size(), expected_cells);
  if (expected_cells != view.elements.size()) return;
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (int k = 0; k <= D; ++k) ASSERT_EQ(cells[i][k].get<std::uint32_t>(), view.elements[i][k]) << "element " << i;
}

// The 2D exports all start from the lake mesh, its snapshot and a scratch folder.
class MeshExport : public ::testing::Test {
 protected:
  ScratchDir dir;
  const Mesh2 mesh = lake_mesh();
  const MeshSnapshot<2> snap{mesh};
};

std::size_t loop_edges(const io::MeshView<2>& view, RingRole role) {
  std::size_t n = 0;
  for (const auto& loop : view.boundary) n += loop.role == role ? loop.nodes.size() : 0;
  return n;
}

TEST_F(MeshExport, SnapshotKeepsUsedPointsAndOneShoreAndOneIslandLoop) {
  const auto view = snap.view();
  // The grid points outside the shore and on the island belong to no kept triangle and are left out.
  EXPECT_LT(view.points.size(), mesh.points().size());
  std::vector<bool> used(view.points.size(), false);
  for (const auto& e : view.elements)
    for (auto i : e) used[i] = true;
  EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
  EXPECT_EQ(std::count(view.kinds.begin(), view.kinds.end(), PointKind::Input), 40 + 8);
  ASSERT_EQ(view.boundary.size(), 2u);
  EXPECT_EQ(view.boundary[0].role, RingRole::Shore);
  EXPECT_EQ(view.boundary[1].role, RingRole::Island);
  EXPECT_EQ(loop_edges(view, RingRole::Shore), 40u);  // the shore subdivided at 1
  EXPECT_EQ(loop_edges(view, RingRole::Island), 8u);
}

TEST_F(MeshExport, VtuReadsBackSameCountsAndCoordinates) {
  io::export_mesh<2>(dir.path("lake.vtu"), snap.view());
  const json read = meshio_read(dir.path("lake.vtu"));
  expect_same_mesh<2>(read, snap.view(), "triangle", mesh.element_count());
  EXPECT_EQ(read["point_data"], json::array({"input"}));
  EXPECT_EQ(read["cell_data"], json::array({"min_angle", "radius_edge"}));

  const auto points3 = mesh_test::random_points<3>(80, 4);
  const Mesh3 mesh3(points3, 40);
  const MeshSnapshot<3> snap3(mesh3);
  io::export_mesh<3>(dir.path("cube.vtu"), snap3.view());
  expect_same_mesh<3>(meshio_read(dir.path("cube.vtu")), snap3.view(), "tetra", mesh3.element_count());
}

TEST_F(MeshExport, GmshMsh41ReadsBackWithPhysicalGroups) {
  const auto view = snap.view();
  io::export_mesh<2>(dir.path("lake.msh"), view);
  ASSERT_EQ(slurp(dir.path("lake.msh")).substr(0, 23), "$MeshFormat\n4.1 0 8\n$En");
  const json read = meshio_read(dir.path("lake.msh"));
  expect_same_mesh<2>(read, view, "triangle", mesh.element_count());
  EXPECT_EQ(read["cells"]["line"].size(), loop_edges(view, RingRole::Shore) + loop_edges(view, RingRole::Island));
  EXPECT_EQ(read["groups"]["shore"], loop_edges(view, RingRole::Shore));
  EXPECT_EQ(read["groups"]["island"], loop_edges(view, RingRole::Island));
  EXPECT_EQ(read["groups"]["water"], mesh.element_count());
}

// Debian's gmsh reads our MSH 4.1 and writes it again as MSH 2.2; meshio reads that copy. Counts and
// coordinates that survive the round trip through Gmsh's own reader show it understood the file.
TEST_F(MeshExport, GmshReadsBackSameCounts) {
  io::export_mesh<2>(dir.path("lake.msh"), snap.view());
  run("gmsh -v 0 '" + dir.path("lake.msh") + "' -save -format msh22 -o '" + dir.path("copy.msh") + "'");
  const json read = meshio_read(dir.path("copy.msh"));
  ASSERT_EQ(read["cells"]["triangle"].size(), mesh.element_count());
  EXPECT_EQ(read["groups"]["water"], mesh.element_count());
  EXPECT_EQ(read["groups"]["shore"], loop_edges(snap.view(), RingRole::Shore));
  EXPECT_EQ(read["groups"]["island"], loop_edges(snap.view(), RingRole::Island));
  // Gmsh may renumber nodes, and prints 16 significant digits: compare the sorted corner coordinates.
  std::vector<Point2> ours, theirs;
  for (const auto& e : mesh.elements())
    for (auto n : e) ours.push_back(mesh.points()[n]);
  for (const auto& t : read["cells"]["triangle"])
    for (const auto& n : t) {
      const auto& p = read["points"][n.get<std::size_t>()];
      theirs.push_back({p[0].get<double>(), p[1].get<double>()});
    }
  std::sort(ours.begin(), ours.end());
  std::sort(theirs.begin(), theirs.end());
  ASSERT_EQ(ours.size(), theirs.size());
  for (std::size_t i = 0; i < ours.size(); ++i)
    for (int k = 0; k < 2; ++k) ASSERT_NEAR(ours[i][k], theirs[i][k], 1e-14) << "corner " << i;

  const auto points3 = mesh_test::random_points<3>(60, 5);
  const Mesh3 mesh3(points3, 60);
  const MeshSnapshot<3> snap3(mesh3);
  io::export_mesh<3>(dir.path("cube.msh"), snap3.view());
  run("gmsh -v 0 '" + dir.path("cube.msh") + "' -save -format msh22 -o '" + dir.path("copy3.msh") + "'");
  const json read3 = meshio_read(dir.path("copy3.msh"));
  EXPECT_EQ(read3["cells"]["tetra"].size(), mesh3.element_count());
  EXPECT_EQ(read3["groups"]["domain"], mesh3.element_count());
  EXPECT_EQ(read3["groups"]["boundary"], boundary_faces(mesh3.elements()).size());
}

TEST_F(MeshExport, ObjPlyOffReadBackSameTriangles) {
  for (const std::string name : {"lake.obj", "lake.ply", "lake.off"}) {
    io::export_mesh<2>(dir.path(name), snap.view());
    expect_same_mesh<2>(meshio_read(dir.path(name)), snap.view(), "triangle", mesh.element_count());
  }
  // 3D: the boundary surface, outward, closed: every edge in exactly two faces.
  const Mesh3 mesh3(mesh_test::random_points<3>(70, 6), 70);
  const MeshSnapshot<3> snap3(mesh3);
  io::export_mesh<3>(dir.path("hull.off"), snap3.view());
  const json read = meshio_read(dir.path("hull.off"));
  const auto faces = boundary_faces(mesh3.elements());
  ASSERT_EQ(read["cells"]["triangle"].size(), faces.size());
  std::map<std::pair<int, int>, int> edges;
  for (const auto& f : read["cells"]["triangle"])
    for (int k = 0; k < 3; ++k) ++edges[std::minmax(f[k].get<int>(), f[(k + 1) % 3].get<int>())];
  for (const auto& [e, n] : edges) EXPECT_EQ(n, 2);
}

TEST_F(MeshExport, TetgenNodeEleReadsBack3D) {
  const Mesh3 mesh3(mesh_test::random_points<3>(90, 7), 45);
  const MeshSnapshot<3> snap3(mesh3);
  io::export_mesh<3>(dir.path("cube.node"), snap3.view());
  ASSERT_TRUE(std::filesystem::exists(dir.path("cube.ele")));
  expect_same_mesh<3>(meshio_read(dir.path("cube.node")), snap3.view(), "tetra", mesh3.element_count());
}

// 2D Triangle files have no reader in Debian's Python; the layout is checked line by line here.
TEST_F(MeshExport, TriangleNodeEleHaveMarkersAndOneBasedElements) {
  const auto view = snap.view();
  io::export_mesh<2>(dir.path("lake.node"), view);
  std::istringstream node(slurp(dir.path("lake.node"))), ele(slurp(dir.path("lake.ele")));
  std::size_t n, dim, attributes, markers;
  node >> n >> dim >> attributes >> markers;
  EXPECT_EQ(n, view.points.size());
  EXPECT_EQ(dim, 2u);
  std::map<int, int> marker_count;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t id;
    double x, y;
    int m;
    node >> id >> x >> y >> m;
    ASSERT_EQ(id, i + 1);
    ASSERT_EQ(x, view.points[i][0]);
    ASSERT_EQ(y, view.points[i][1]);
    ++marker_count[m];
  }
  EXPECT_EQ(marker_count[1], 40);
  EXPECT_EQ(marker_count[2], 8);
  std::size_t m, corners;
  ele >> m >> corners >> attributes;
  EXPECT_EQ(m, mesh.element_count());
  EXPECT_EQ(corners, 3u);
  const auto elements = view.elements;
  for (std::size_t i = 0; i < m; ++i) {
    std::size_t id, a, b, c;
    ele >> id >> a >> b >> c;
    ASSERT_EQ(id, i + 1);
    ASSERT_EQ((std::array<std::size_t, 3>{a - 1, b - 1, c - 1}),
              (std::array<std::size_t, 3>{elements[i][0], elements[i][1], elements[i][2]}));
  }
}

// GeoJSON through a projection callback: parsed with nlohmann::json, one closed Polygon per triangle,
// coordinates equal to the callback's longitude/latitude.
TEST_F(MeshExport, GeoJsonIsFeatureCollectionInLonLat) {
  const auto to_lonlat = [](const Point2& p) { return Point2{14.3 + p[0] * 1e-3, 45.7 + p[1] * 1e-3}; };
  io::export_mesh<2>(dir.path("lake.geojson"), snap.view(to_lonlat));
  const json g = json::parse(slurp(dir.path("lake.geojson")));
  EXPECT_EQ(g["type"], "FeatureCollection");
  ASSERT_EQ(g["features"].size(), mesh.element_count());
  const auto elements = snap.view().elements;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const auto& ring = g["features"][i]["geometry"]["coordinates"][0];
    ASSERT_EQ(g["features"][i]["geometry"]["type"], "Polygon");
    ASSERT_EQ(ring.size(), 4u);
    ASSERT_EQ(ring[0], ring[3]);
    for (int k = 0; k < 3; ++k) {
      const Point2 ll = to_lonlat(snap.view().points[elements[i][k]]);
      ASSERT_EQ(ring[k][0].get<double>(), ll[0]);
      ASSERT_EQ(ring[k][1].get<double>(), ll[1]);
    }
  }
  // Without a projection there are no longitudes to write.
  EXPECT_THROW(io::export_mesh<2>(dir.path("plain.geojson"), snap.view()), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.path("plain.geojson")));
}

TEST_F(MeshExport, Fort14ListsShoreAndIslandBoundariesClosed) {
  io::export_mesh<2>(dir.path("fort.14"), snap.view());
  std::istringstream in(slurp(dir.path("fort.14")));
  std::string line;
  std::getline(in, line);
  std::size_t ne, np;
  in >> ne >> np;
  std::getline(in, line);
  EXPECT_EQ(ne, mesh.element_count());
  EXPECT_EQ(np, snap.view().points.size());
  for (std::size_t i = 0; i < np + ne; ++i) std::getline(in, line);
  auto count = [&] {
    std::size_t v;
    in >> v;
    std::getline(in, line);
    return v;
  };
  EXPECT_EQ(count(), 0u);  // NOPE
  EXPECT_EQ(count(), 0u);  // NETA
  ASSERT_EQ(count(), 2u);  // NBOU
  EXPECT_EQ(count(), 41u + 9u);  // NVEL: each closed loop repeats its first node
  for (const auto& [size, type] : {std::pair{41u, 20}, std::pair{9u, 21}}) {  // ADCIRC IBTYPE 20 mainland, 21 island
    std::size_t nvell;
    int ibtype;
    in >> nvell >> ibtype;
    std::getline(in, line);
    EXPECT_EQ(nvell, size);
    EXPECT_EQ(ibtype, type);
    std::vector<std::size_t> nodes(nvell);
    for (auto& v : nodes) in >> v;
    EXPECT_EQ(nodes.front(), nodes.back());
  }
}

TEST_F(MeshExport, FailedWriteLeavesExistingFileUntouched) {
  std::ofstream(dir.path("fort.14")) << "old contents";
  auto view = snap.view();
  view.depth = [](const Point2& p) -> double {
    if (p[0] > 5) throw std::runtime_error("no bathymetry here");
    return 10;
  };
  try {
    io::export_mesh<2>(dir.path("fort.14"), view);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir.path("fort.14")), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(dir.path("fort.14")), "old contents");
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path(""))) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u) << "a temporary file was left behind";
  EXPECT_THROW(io::export_mesh<2>(dir.path("missing-folder/lake.vtu"), snap.view()), InputError);
  EXPECT_THROW(io::export_mesh<2>(dir.path("lake.xyz"), snap.view()), InputError);
}

TEST_F(MeshExport, ExplicitFormatOverridesTheFileName) {
  io::export_mesh<2>(dir.path("lake.dat"), snap.view(), ExportFormat::Vtu);
  expect_same_mesh<2>(meshio_read(dir.path("lake.dat"), "vtu"), snap.view(), "triangle", mesh.element_count());
  const Mesh3 mesh3(mesh_test::random_points<3>(30, 8), 30);
  EXPECT_THROW(io::export_mesh<3>(dir.path("cube.geojson"), MeshSnapshot<3>(mesh3).view()), InputError);
}

TEST_F(MeshExport, FormatFromPath) {
  EXPECT_EQ(io::export_format_from_path("a/b.MSH"), ExportFormat::Gmsh);
  EXPECT_EQ(io::export_format_from_path("fort.14"), ExportFormat::Adcirc);
  EXPECT_EQ(io::export_format_from_path("lake.fort14"), ExportFormat::Adcirc);
  EXPECT_EQ(io::export_format_from_path("m.ele"), ExportFormat::Triangle);
  EXPECT_EQ(io::export_format_from_path("m.json"), ExportFormat::GeoJson);
  EXPECT_EQ(io::export_format_from_path("m.ply"), ExportFormat::Ply);
}

// A snapshot numbers points in the order asked for and lists each element from its smallest index, with
// its orientation kept, in sorted order: what makes an export independent of the mesh's history.
template <int D>
void check_canonical_snapshot(std::uint32_t seed) {
  const auto points = mesh_test::random_points<D>(200, seed);
  const Mesh<D> mesh(points, 50);
  std::vector<Point<D>> order = mesh.points();
  std::reverse(order.begin(), order.end());
  const MeshSnapshot<D> snap(mesh, order);
  const io::MeshView<D> v = snap.view();
  ASSERT_EQ(v.points.size(), order.size());
  EXPECT_TRUE(std::equal(v.points.begin(), v.points.end(), order.begin()));
  for (std::size_t i = 0; i < order.size(); ++i)  // kinds follow their points: the first 50 are inputs
    EXPECT_EQ(v.kinds[i], (std::find(points.begin(), points.begin() + 50, order[i]) != points.begin() + 50)
                              ? PointKind::Input
                              : PointKind::Steiner);
  ASSERT_EQ(v.elements.size(), mesh.element_count());
  EXPECT_TRUE(std::is_sorted(v.elements.begin(), v.elements.end()));
  auto corners = [](const auto& pts, const Element<D>& e) {
    ElementCorners<D> c;
    for (int k = 0; k <= D; ++k) c[k] = pts[e[k]];
    std::sort(c.begin(), c.end());
    return c;
  };
  std::vector<ElementCorners<D>> expected, got;
  for (const auto& e : mesh.elements()) expected.push_back(corners(mesh.points(), e));
  for (const auto& e : v.elements) {
    EXPECT_EQ(*std::min_element(e.begin(), e.end()), e[0]);
    // Positively oriented, as the mesh lists them (random points: the double determinant is far from 0).
    const Point<D>& a = v.points[e[0]];
    double det = 0;
    if constexpr (D == 2) {
      const Point2 &b = v.points[e[1]], &c = v.points[e[2]];
      det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    } else {
      Point3 u, w, x;
      for (int k = 0; k < 3; ++k) u[k] = v.points[e[1]][k] - a[k], w[k] = v.points[e[2]][k] - a[k], x[k] = v.points[e[3]][k] - a[k];
      det = u[0] * (w[1] * x[2] - w[2] * x[1]) - u[1] * (w[0] * x[2] - w[2] * x[0]) + u[2] * (w[0] * x[1] - w[1] * x[0]);
    }
    EXPECT_GT(det, 0);
    got.push_back(corners(v.points, e));
  }
  std::sort(expected.begin(), expected.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, expected);

  order.pop_back();
  EXPECT_THROW(MeshSnapshot<D>(mesh, order), std::logic_error);
  order.push_back(Point<D>{});
  EXPECT_THROW(MeshSnapshot<D>(mesh, order), std::logic_error);
}

TEST(MeshSnapshot, NumbersInTheOrderAskedAndListsElementsCanonically2D) { check_canonical_snapshot<2>(3); }
TEST(MeshSnapshot, NumbersInTheOrderAskedAndListsElementsCanonically3D) { check_canonical_snapshot<3>(4); }

}  // namespace
}  // namespace shoremesh
