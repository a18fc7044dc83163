// `shoremesh edit` end to end: replies (text and JSON), ids, bad lines that leave the state intact, and
// the pin of the dynamic engine at the tool's level: after any edits, `export PATH.csv` equals what
// `shoremesh mesh FINAL_INPUT --box BOX -o OUT.csv` writes for the final input and the session's box.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "cli_test_util.hpp"
#include "dem_test_util.hpp"
#include "shoremesh/io/point_file.hpp"
#include "shoremesh/io/point_set_csv.hpp"

namespace shoremesh::cli_test {
namespace {

using ::testing::HasSubstr;
using json = nlohmann::json;

std::vector<json> json_lines(const std::string& out) {
  std::vector<json> replies;
  for (const auto& l : lines_of(out)) replies.push_back(json::parse(l));
  return replies;
}

// The final input of a session by increasing id, as a point file, and the box of the session's export.
void write_final_input(const fs::path& path, const std::map<std::size_t, Point2>& by_id) {
  std::string text = "x,y\n";
  for (const auto& [id, p] : by_id) text += io::format_double(p[0]) + "," + io::format_double(p[1]) + "\n";
  write_file(path, text);
}

std::string box_of(const fs::path& point_set_csv) {
  const std::string first = lines_of(read_file(point_set_csv)).at(0);
  EXPECT_EQ(first.rfind("# box ", 0), 0u);
  return first.substr(6);
}

std::map<std::size_t, Point2> read_by_id(const fs::path& point_file) {
  const auto f = io::read_point_file(point_file.string());
  std::map<std::size_t, Point2> by_id;
  for (std::size_t i = 0; i < f.points2.size(); ++i) by_id[i] = f.points2[i];
  return by_id;
}

TEST(EditCommand, SessionEqualsAFreshRunOnTheFinalInput) {
  TempDir dir;
  write_file(dir / "p.csv", random_points(300, 100, 50, 11));
  auto input = read_by_id(dir / "p.csv");
  const std::string edits =
      "# a comment, then edits\n"
      "add 10 10\n"
      "move 3 50 25\n"
      "remove 5\n"
      "\n"
      "add 60.5 12.25\n"
      "move 300 11 12\n"
      "remove 17\n"
      "stats\n"
      "export final.csv\n"
      "export final.msh\n"
      "export final.vtu\n"
      "export final.node\n";
  const RunResult r = shoremesh(dir, "edit p.csv --edits -", edits);
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  input[300] = {11, 12};
  input[3] = {50, 25};
  input.erase(5);
  input[301] = {60.5, 12.25};
  input.erase(17);
  write_final_input(dir / "final_input.csv", input);
  const RunResult fresh = shoremesh(dir, "mesh final_input.csv --box " + box_of(dir / "final.csv") + " -o fresh.csv");
  ASSERT_EQ(fresh.code, 0) << fresh.err;
  EXPECT_EQ(read_file(dir / "final.csv"), read_file(dir / "fresh.csv"));
  // The mesh exports too, byte for byte: the same points and elements, numbered the same way, although
  // the session's mesh went through the edits (its points renumbered, its elements stored anew).
  for (const std::string ext : {".msh", ".vtu", ".node", ".ele"}) {
    if (ext != ".ele") {
      const RunResult m = shoremesh(dir, "mesh -q final_input.csv --box " + box_of(dir / "final.csv") + " -o fresh" + ext);
      ASSERT_EQ(m.code, 0) << m.err;
    }
    EXPECT_EQ(read_file(dir / ("final" + ext)), read_file(dir / ("fresh" + ext))) << ext;
  }

  // Text replies: one per edit line, naming the line, with the change and its time.
  EXPECT_THAT(r.out, HasSubstr("line 2: added id 300 at (10, 10): +"));
  EXPECT_THAT(r.out, ::testing::ContainsRegex(R"(line 3: moved id 3 to \(50, 25\): \+[0-9]+ Steiner, -[0-9]+ Steiner, [0-9]+ elements changed, [0-9.e+-]+ ms)"));
  EXPECT_THAT(r.out, HasSubstr("line 6: added id 301"));
  EXPECT_THAT(r.out, HasSubstr("line 9: stats: 300 input points"));
  EXPECT_THAT(r.out, HasSubstr("line 10: wrote final.csv"));
}

TEST(EditCommand, JsonRepliesIdsAndBadLinesThatKeepTheState) {
  TempDir dir;
  write_file(dir / "p.csv", random_points(120, 40, 40, 5));
  const std::string good = "add 1 1\nremove 120\nadd 2 2\nmove 0 20 20\nexport good.csv\nstats\n";
  const std::string bad_mixed =
      "add 1 1\n"
      "remove 999\n"        // no such id
      "remove 120\n"
      "remove 120\n"        // already removed
      "add 2 2\n"
      "add 1e9 1e9\n"       // outside the box
      "add 2 2\n"           // repeats an input point
      "move 0 x 20\n"       // not a number
      "move 0 20 20 20\n"   // a 2D session
      "frob 1\n"            // unknown edit
      "stats extra\n"
      "move 0 20 20\n"
      "export good.csv.d/none.csv\n"  // cannot write there
      "export mixed.csv\n";
  const RunResult g = shoremesh(dir, "edit p.csv --json --edits -", good);
  ASSERT_EQ(g.code, 0) << g.err;
  // A point file has no shore: the session's mesh is clipped to the box, every element within the bound.
  const json stats = json_lines(g.out).back();
  EXPECT_GT(stats["left_out_at_box_edge"].get<std::size_t>(), 0u) << stats;
  EXPECT_EQ(stats["covered"], stats["elements"]);
  EXPECT_EQ(stats["covered_meeting_bound"], stats["elements"]);
  fs::rename(dir / "good.csv", dir / "expected.csv");
  write_file(dir / "edits.txt", bad_mixed);
  const RunResult r = shoremesh(dir, "edit p.csv --json --edits edits.txt");
  EXPECT_EQ(r.code, 1);  // some lines failed
  const auto replies = json_lines(r.out);
  ASSERT_EQ(replies.size(), 15u) << r.out;
  EXPECT_EQ(replies[0]["op"], "build");
  EXPECT_EQ(replies[0]["input_points"], 120);
  EXPECT_EQ(replies[0]["box"].size(), 3u);
  for (std::size_t i = 1; i < replies.size(); ++i) EXPECT_EQ(replies[i]["line"], i) << replies[i];
  const std::vector<int> ok = {1, 0, 1, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 1};
  for (std::size_t i = 0; i < ok.size(); ++i) {
    EXPECT_EQ(replies[i + 1]["ok"].get<bool>(), ok[i] == 1) << replies[i + 1];
    if (!ok[i]) {
      EXPECT_FALSE(replies[i + 1]["error"].get<std::string>().empty());
    }
  }
  EXPECT_EQ(replies[1]["id"], 120);
  EXPECT_EQ(replies[5]["id"], 121);  // ids are never reused
  EXPECT_THAT(replies[2]["error"].get<std::string>(), HasSubstr("no input point 999"));
  EXPECT_THAT(replies[4]["error"].get<std::string>(), HasSubstr("120 was removed"));
  EXPECT_THAT(replies[6]["error"].get<std::string>(), HasSubstr("outside the session's box"));
  EXPECT_EQ(replies[7]["error"], "the point equals input point 121");
  EXPECT_THAT(replies[8]["error"].get<std::string>(), HasSubstr("'x' is not a number"));
  EXPECT_THAT(replies[9]["error"].get<std::string>(), HasSubstr("2D session"));
  EXPECT_THAT(replies[10]["error"].get<std::string>(), HasSubstr("unknown edit 'frob'"));
  for (const char* key : {"steiner_added", "steiner_removed", "elements_changed", "ms", "rings_ms", "engine_ms", "mesh_ms"})
    EXPECT_TRUE(replies[1].contains(key)) << key;
  // The failed lines changed nothing: the same result as the good lines alone.
  EXPECT_EQ(read_file(dir / "mixed.csv"), read_file(dir / "expected.csv"));
}

std::vector<std::array<std::string, 3>> off_triangles(const fs::path& off);  // below

TEST(EditCommand, SuperiorShorelineEditsFollowTheRingsAndEqualAFreshRun) {
  TempDir dir;
  const std::string image = quote(superior_mask());
  const std::string read = image + " --largest-water --spacing 8000";
  // The traced input points, by id, from the point set `mesh` writes.
  const RunResult start = shoremesh(dir, "mesh -q " + read + " -o start.csv");
  ASSERT_EQ(start.code, 0) << start.err;
  const RunResult first = shoremesh(dir, "edit " + read + " --json --edits -", "stats\n");
  ASSERT_EQ(first.code, 0) << first.err;
  const std::size_t n = json_lines(first.out).at(0)["input_points"].get<std::size_t>();
  const auto all = io::read_point_set_csv<2>(dir / "start.csv");
  std::map<std::size_t, Point2> input;
  for (std::size_t i = 0; i < n; ++i) input[i] = all.points[i];

  // Shore vertex 40 a little toward its neighbour 41, vertex 60 far across the lake (breaks the ring).
  const Point2 a = input[40], b = input[41];
  const Point2 moved{a[0] + 0.3 * (b[0] - a[0]), a[1] + 0.3 * (b[1] - a[1])};
  const Point2 far = input[400];
  const Point2 added{0.5 * (input[100][0] + input[300][0]), 0.5 * (input[100][1] + input[300][1])};
  auto xy = [](const Point2& p) { return io::format_double(p[0]) + " " + io::format_double(p[1]); };
  const std::string edits = "move 40 " + xy(moved) + "\n" +
                            "move 60 " + xy(far) + "\n" +
                            "preview-change change.png\n"
                            "add " + xy(added) + "\n" +
                            "remove 70\n"
                            "export final.csv\nexport final.msh\nexport final.geojson\nexport final.off\nexport final.rings\n"
                            "preview final.png\nstats\n";
  const RunResult r = shoremesh(dir, "edit " + read + " --json --edits -", edits);
  EXPECT_EQ(r.code, 1) << r.err;  // the second move is refused
  const auto replies = json_lines(r.out);
  ASSERT_EQ(replies.size(), 13u) << r.out;
  EXPECT_TRUE(replies[1]["ok"].get<bool>()) << replies[1];
  EXPECT_GT(replies[1]["elements_changed"].get<int>(), 0);
  EXPECT_FALSE(replies[2]["ok"].get<bool>());
  EXPECT_THAT(replies[2]["error"].get<std::string>(), HasSubstr("would break the shoreline"));
  for (std::size_t i = 3; i < replies.size(); ++i) EXPECT_TRUE(replies[i]["ok"].get<bool>()) << replies[i];
  EXPECT_EQ(replies[4]["id"], n);
  const json& stats = replies.back();
  // The shore is the mesh's boundary; every element below the bound has a shore edge.
  EXPECT_EQ(stats["shore_covered"], stats["shore_segments"]);
  EXPECT_EQ(stats["covered"].get<std::size_t>() - stats["covered_meeting_bound"].get<std::size_t>(),
            stats["shore_below_bound"].get<std::size_t>());
  for (const char* f : {"change.png", "final.msh", "final.geojson", "final.png"}) EXPECT_TRUE(fs::exists(dir / f)) << f;

  // A fresh run on the edited input: the session's rings as it exports them, the added loose point, the same
  // box. It makes its own splits and skips the same fills on land (docs/water_only.md), so the point sets
  // (land Steiner points included) and the meshes agree.
  write_file(dir / "added.csv", "x,y\n" + io::format_double(added[0]) + "," + io::format_double(added[1]) + "\n");
  const std::string fresh_input = "final.rings added.csv --box " + box_of(dir / "final.csv");
  for (const char* out : {"fresh.csv", "fresh.off"}) {
    const RunResult fresh = shoremesh(dir, "mesh -q " + fresh_input + " -o " + out);
    ASSERT_EQ(fresh.code, 0) << fresh.err;
  }
  auto sorted_points = [&](const char* file) {
    auto lines = lines_of(read_file(dir / file));
    lines.erase(lines.begin());  // the box line
    std::sort(lines.begin(), lines.end());
    return lines;
  };
  const auto session_points = sorted_points("final.csv");
  EXPECT_GT(session_points.size(), n);
  EXPECT_EQ(session_points, sorted_points("fresh.csv"));
  const auto edited_mesh = off_triangles(dir / "final.off");
  EXPECT_GT(edited_mesh.size(), 100u);
  EXPECT_EQ(edited_mesh, off_triangles(dir / "fresh.off"));
}

}  // namespace
}  // namespace shoremesh::cli_test

namespace shoremesh::cli_test {
namespace {

// The triangles of an OFF export as sorted corner coordinates (the text of each number): a mesh compared
// by place, whatever its numbering.
std::vector<std::array<std::string, 3>> off_triangles(const fs::path& off) {
  std::istringstream in(read_file(off));
  std::string magic;
  std::size_t points = 0, faces = 0, edges = 0;
  in >> magic >> points >> faces >> edges;
  EXPECT_EQ(magic, "OFF");
  std::vector<std::string> corner(points);
  for (auto& c : corner) {
    std::string x, y, z;
    in >> x >> y >> z;
    c = x + " " + y;
  }
  std::vector<std::array<std::string, 3>> out;
  for (std::size_t f = 0; f < faces; ++f) {
    std::size_t three = 0, a = 0, b = 0, c = 0;
    in >> three >> a >> b >> c;
    EXPECT_EQ(three, 3u);
    std::array<std::string, 3> t{corner.at(a), corner.at(b), corner.at(c)};
    std::sort(t.begin(), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(EditCommand, APointAddedAfterAShorePointJoinsItsShoreline) {
  TempDir dir;
  // A lake (a 16-gon of radius 100) with a square island, as a ring file in map units.
  std::vector<Point2> shore;
  for (int i = 0; i < 16; ++i) {
    const double t = 2 * 3.141592653589793 * i / 16;
    shore.push_back({200 + 100 * std::cos(t), 200 + 100 * std::sin(t)});
  }
  const std::vector<Point2> island{{170, 190}, {190, 190}, {190, 210}, {170, 210}};
  auto ring_text = [](const std::vector<Point2>& ring) {
    std::string text;
    for (std::size_t i = 0; i <= ring.size(); ++i)
      text += io::format_double(ring[i % ring.size()][0]) + "," + io::format_double(ring[i % ring.size()][1]) + "\n";
    return text;
  };
  write_file(dir / "lake.txt", ring_text(shore) + "\n" + ring_text(island));
  auto xy = [](const Point2& p) { return io::format_double(p[0]) + " " + io::format_double(p[1]); };
  // Out into the land between shore vertices 3 and 4 (so the water grows), then a little further.
  const Point2 a = shore[3], b = shore[4];
  const Point2 bay{(a[0] + b[0]) / 2 + 0.05 * (a[0] + b[0] - 400), (a[1] + b[1]) / 2 + 0.05 * (a[1] + b[1] - 400)};
  const Point2 bay2{bay[0] + 1, bay[1] + 0.5};
  const std::string edits = "add " + xy(bay) + " after 3\n" +  // id 20
                            "add 180 200 after 5\n" +           // into the island: the shore would cross it
                            "add 230 230\n" +                   // a loose point, id 21
                            "add 231 229 after 21\n" +          // after a loose point: no shoreline
                            "move 20 " + xy(bay2) + "\n" +     // the new shore vertex moves with its ring
                            "export final.off\nexport final.csv\nstats\n";
  const RunResult r = shoremesh(dir, "edit lake.txt --json --edits -", edits);
  EXPECT_EQ(r.code, 1) << r.err;
  const auto replies = json_lines(r.out);
  ASSERT_EQ(replies.size(), 9u) << r.out;  // the build's, then one a line
  ASSERT_TRUE(replies[1]["ok"].get<bool>()) << replies[1];
  EXPECT_EQ(replies[1]["id"], 20);
  EXPECT_EQ(replies[1]["after"], 3);
  EXPECT_EQ(replies[1]["ring"], 1);
  EXPECT_FALSE(replies[2]["ok"].get<bool>());
  EXPECT_THAT(replies[2]["error"].get<std::string>(),
              HasSubstr("adding a point after input point 5 would break the shoreline: ring 1 edge"));
  EXPECT_EQ(replies[3]["id"], 21);
  EXPECT_FALSE(replies[4]["ok"].get<bool>());
  EXPECT_THAT(replies[4]["error"].get<std::string>(), HasSubstr("input point 21 is on no shoreline"));
  for (std::size_t i : {5u, 6u, 7u, 8u}) EXPECT_TRUE(replies[i]["ok"].get<bool>()) << replies[i];
  EXPECT_EQ(replies[8]["shore_segments"], 16 + 4 + 1);  // the shore has one vertex, one segment more

  // A fresh run on the shoreline with the vertex in place and the loose point: the same mesh, clipped
  // to the same water.
  std::vector<Point2> edited = shore;
  edited.insert(edited.begin() + 4, bay2);
  write_file(dir / "lake2.txt", ring_text(edited) + "\n" + ring_text(island));
  write_file(dir / "loose.csv", "x,y\n230,230\n");
  const RunResult fresh =
      shoremesh(dir, "mesh -q lake2.txt loose.csv --box " + box_of(dir / "final.csv") + " -o fresh.off");
  ASSERT_EQ(fresh.code, 0) << fresh.err;
  const auto edited_mesh = off_triangles(dir / "final.off");
  EXPECT_GT(edited_mesh.size(), 30u);
  EXPECT_EQ(edited_mesh, off_triangles(dir / "fresh.off"));
  // And not the mesh of the old shoreline: the bay is water now.
  write_file(dir / "lake_old.txt", ring_text(shore) + "\n" + ring_text(island));
  ASSERT_EQ(shoremesh(dir, "mesh -q lake_old.txt loose.csv --box " + box_of(dir / "final.csv") + " -o old.off").code, 0);
  EXPECT_NE(edited_mesh, off_triangles(dir / "old.off"));
}

// Islands added (inline coordinates, a ring file) and removed by ring number: the replies say the ring,
// its ids and its role; a ring that would cross the shore and a ring that does not exist are refused;
// the session's mesh equals a fresh run on the shoreline it exports.
TEST(EditCommand, RingsAddedAndRemovedEqualAFreshRunOnTheExportedShoreline) {
  TempDir dir;
  std::string lake;
  for (int i = 0; i <= 16; ++i) {
    const double t = 2 * 3.141592653589793 * (i % 16) / 16;
    lake += io::format_double(200 + 100 * std::cos(t)) + "," + io::format_double(200 + 100 * std::sin(t)) + "\n";
  }
  write_file(dir / "lake.txt", lake + "\n170,190\n190,190\n190,210\n170,210\n170,190\n");
  write_file(dir / "islet.txt", "240,160\n250,160\n245,170\n240,160\n");
  const std::string edits =
      "add-ring 230 230 245 230 245 245 230 245\n"  // ring 3, an island: ids 20..23
      "add-ring islet.txt\n"                        // ring 4, from a file: ids 24..26
      "add-ring 150 150 300 150 250 180\n"          // crosses the shore: refused
      "remove-ring 2\n"                             // the square island goes
      "remove-ring 2\n"                             // again: refused
      "remove-ring 9\n"                             // no such ring: refused
      "move 21 246 229\n"                           // the new island's vertex moves with its ring
      "stats\nexport final.off\nexport final.rings\n";
  const RunResult r = shoremesh(dir, "edit lake.txt --json --edits -", edits);
  EXPECT_EQ(r.code, 1) << r.err;
  const auto replies = json_lines(r.out);
  ASSERT_EQ(replies.size(), 11u) << r.out;
  ASSERT_TRUE(replies[1]["ok"].get<bool>()) << replies[1];
  EXPECT_EQ(replies[1]["ring"], 3);
  EXPECT_EQ(replies[1]["ids"], json({20, 21, 22, 23}));
  EXPECT_EQ(replies[1]["role"], "island");
  ASSERT_TRUE(replies[2]["ok"].get<bool>()) << replies[2];
  EXPECT_EQ(replies[2]["ring"], 4);
  EXPECT_EQ(replies[2]["ids"], json({24, 25, 26}));
  EXPECT_FALSE(replies[3]["ok"].get<bool>());
  EXPECT_THAT(replies[3]["error"].get<std::string>(), HasSubstr("the new ring (ring 5) would break the shoreline: ring 1 edge"));
  ASSERT_TRUE(replies[4]["ok"].get<bool>()) << replies[4];
  EXPECT_EQ(replies[4]["ids"], json({16, 17, 18, 19}));
  EXPECT_THAT(replies[5]["error"].get<std::string>(), HasSubstr("ring 2 was removed"));
  EXPECT_THAT(replies[6]["error"].get<std::string>(), HasSubstr("no ring 9"));
  ASSERT_TRUE(replies[7]["ok"].get<bool>()) << replies[7];
  EXPECT_EQ(replies[8]["shore_segments"].get<std::size_t>(), replies[8]["shore_covered"].get<std::size_t>());
  EXPECT_TRUE(replies[8]["shore_conforming"].get<bool>());
  // The exported shoreline: the lake, the moved island, the islet (the square island gone).
  const std::string rings = read_file(dir / "final.rings");
  EXPECT_THAT(rings, HasSubstr("246,229"));
  EXPECT_THAT(rings, HasSubstr("250,160"));
  EXPECT_EQ(rings.find("190,210"), std::string::npos);
  const RunResult fresh = shoremesh(dir, "mesh -q final.rings --box " + replies[0]["box"][0].dump() + " " +
                                             replies[0]["box"][1].dump() + " " + replies[0]["box"][2].dump() +
                                             " -o fresh.off");
  ASSERT_EQ(fresh.code, 0) << fresh.err;
  const auto edited_mesh = off_triangles(dir / "final.off");
  EXPECT_GT(edited_mesh.size(), 30u);
  EXPECT_EQ(edited_mesh, off_triangles(dir / "fresh.off"));
}

// A constraint line (a breakwater) added to a session: each of its segments is a chain of edges of the
// exported mesh (through the points the mesh has on it), the water's area stays the lake's, a line on
// land and a line across the shore are refused, and moving one of its points keeps it a chain.
TEST(EditCommand, ALineAddedInTheWaterIsAChainOfMeshEdges) {
  TempDir dir;
  std::string lake;
  for (int i = 0; i <= 16; ++i) {
    const double t = 2 * 3.141592653589793 * (i % 16) / 16;
    lake += io::format_double(200 + 100 * std::cos(t)) + "," + io::format_double(200 + 100 * std::sin(t)) + "\n";
  }
  write_file(dir / "lake.txt", lake);
  const std::string edits =
      "add-line 150 200 200 225 250 200\n"  // ring 2, ids 16..18
      "add-line 95 95 100 100\n"            // on land (outside the lake): refused
      "add-line 250 250 305 250\n"          // across the shore: refused
      "move 17 200 230\n"
      "stats\nexport final.off\n";
  const RunResult r = shoremesh(dir, "edit lake.txt --json --edits -", edits);
  EXPECT_EQ(r.code, 1) << r.err;
  const auto replies = json_lines(r.out);
  ASSERT_EQ(replies.size(), 7u) << r.out;
  ASSERT_TRUE(replies[1]["ok"].get<bool>()) << replies[1];
  EXPECT_EQ(replies[1]["role"], "line");
  EXPECT_EQ(replies[1]["ids"], json({16, 17, 18}));
  EXPECT_THAT(replies[2]["error"].get<std::string>(), HasSubstr("line 3 lies on land"));
  EXPECT_THAT(replies[3]["error"].get<std::string>(), HasSubstr("crosses"));
  ASSERT_TRUE(replies[4]["ok"].get<bool>()) << replies[4];
  EXPECT_EQ(replies[5]["shore_segments"], 16 + 2);
  EXPECT_TRUE(replies[5]["shore_conforming"].get<bool>());

  std::set<std::pair<Point2, Point2>> edges;
  std::set<Point2> vertices;
  double area = 0;
  for (const auto& t : off_triangles(dir / "final.off")) {
    std::array<Point2, 3> c;
    for (int i = 0; i < 3; ++i) {
      std::istringstream in(t[std::size_t(i)]);
      in >> c[std::size_t(i)][0] >> c[std::size_t(i)][1];
      vertices.insert(c[std::size_t(i)]);
    }
    for (int i = 0; i < 3; ++i) edges.insert(std::minmax(c[std::size_t(i)], c[std::size_t(i + 1) % 3]));
    area += 0.5 * std::abs((c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) - (c[1][1] - c[0][1]) * (c[2][0] - c[0][0]));
  }
  EXPECT_NEAR(area, 16 * 0.5 * 100 * 100 * std::sin(2 * 3.141592653589793 / 16), 1e-6);
  const std::vector<Point2> line{{150, 200}, {200, 230}, {250, 200}};
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const Point2 a = line[k], b = line[k + 1];
    // The mesh's points on the segment, in order from a to b: consecutive ones must be mesh edges.
    std::vector<std::pair<double, Point2>> on;
    for (const Point2& p : vertices) {
      const double cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
      const double t = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) /
                       ((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]));
      if (std::abs(cross) < 1e-9 * 100 * 100 && t >= 0 && t <= 1) on.push_back({t, p});
    }
    std::sort(on.begin(), on.end());
    ASSERT_GE(on.size(), 2u);
    EXPECT_EQ(on.front().second, a);
    EXPECT_EQ(on.back().second, b);
    for (std::size_t j = 0; j + 1 < on.size(); ++j)
      EXPECT_TRUE(edges.count(std::minmax(on[j].second, on[j + 1].second))) << "segment " << k << " piece " << j;
  }
}

TEST(EditCommand, LonLatEditsAreProjectedLikeTheInput) {
  TempDir dir;
  const std::string read = quote(superior_mask()) + " --largest-water --spacing 8000";
  const RunResult r = shoremesh(dir, "edit " + read + " --lonlat-edits --edits -", "add -86.5 47.5\nadd -200 40\n");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("m = 47.50000N 86.50000W: +"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("line 2: error: "));
  // The error names the session's projection (lon/lat input: a transverse Mercator centred on it).
  EXPECT_THAT(r.out, ::testing::HasSubstr("of local transverse Mercator at 47.732699N 88.250000W"));
  write_file(dir / "p.csv", random_points(20, 10, 10, 4));
  const RunResult plain = shoremesh(dir, "edit p.csv --lonlat-edits --edits -", "add 1 1\n");
  EXPECT_EQ(plain.code, 1);
  EXPECT_THAT(plain.err, ::testing::HasSubstr("--lonlat-edits needs 2D lon/lat input"));
}

// Lemma 7.2 with depths: after each random edit the session's fort.14 (depths from the DEM at every node,
// moved and new ones included) equals a fresh run's on the edited input, byte for byte.
TEST(EditCommand, DepthsFollowRandomEditsAndEqualAFreshRunAfterEach) {
  TempDir dir;
  std::vector<float> z;  // a sloping sea floor with a trench, heights in metres on 100 x 50 unit cells
  for (int r = 0; r < 50; ++r)
    for (int c = 0; c < 100; ++c) z.push_back(static_cast<float>(-5 - 0.4 * c - 30 * std::exp(-0.02 * (r - 25) * (r - 25))));
  write_dem(dir / "floor.tif", 100, 50, z, std::nullopt, {0, 1, 0, 50, 0, -1});
  write_file(dir / "p.csv", random_points(200, 100, 50, 5));
  auto input = read_by_id(dir / "p.csv");
  std::mt19937 rng(34);
  std::uniform_real_distribution<double> x(1, 99), y(1, 49);
  std::string edits;
  std::size_t next_id = input.size();
  std::vector<std::map<std::size_t, Point2>> after;
  for (int k = 0; k < 6; ++k) {
    auto it = input.begin();
    std::advance(it, static_cast<long>(rng() % input.size()));
    const Point2 p{std::round(x(rng) * 100) / 100, std::round(y(rng) * 100) / 100};
    switch (k % 3) {
      case 0: edits += "add " + io::format_double(p[0]) + " " + io::format_double(p[1]) + "\n", input[next_id++] = p; break;
      case 1: edits += "move " + std::to_string(it->first) + " " + io::format_double(p[0]) + " " + io::format_double(p[1]) + "\n", it->second = p; break;
      default: edits += "remove " + std::to_string(it->first) + "\n", input.erase(it); break;
    }
    edits += "export e" + std::to_string(k) + ".14\nexport e" + std::to_string(k) + ".csv\n";
    after.push_back(input);
  }
  const RunResult r = shoremesh(dir, "edit p.csv --depth-from floor.tif --edits -", edits);
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  for (int k = 0; k < 6; ++k) {
    const std::string n = std::to_string(k);
    write_final_input(dir / ("in" + n + ".csv"), after[static_cast<std::size_t>(k)]);
    const RunResult fresh = shoremesh(dir, "mesh -q in" + n + ".csv --depth-from floor.tif --box " +
                                               box_of(dir / ("e" + n + ".csv")) + " -o f" + n + ".14");
    ASSERT_EQ(fresh.code, 0) << fresh.err;
    const std::string edited = read_file(dir / ("e" + n + ".14"));
    EXPECT_EQ(edited, read_file(dir / ("f" + n + ".14"))) << "after edit " << k;
    // The depths are the DEM's (5 to 75 m here), not the zeros of a fort.14 without a depth source.
    const auto lines = lines_of(edited);
    std::istringstream node(lines.at(2));
    double id = 0, nx = 0, ny = 0, depth = 0;
    node >> id >> nx >> ny >> depth;
    EXPECT_GT(depth, 4.9) << lines.at(2);
  }
}

}  // namespace
}  // namespace shoremesh::cli_test
