// Hostile input (issue 36): every bad file, option and edit line gets the documented exit code (2 command
// line, 1 bad input, never 3), a message naming the file, line, option or id, and leaves every file that
// existed before byte for byte as it was (a run writes all its outputs or none).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "cli_test_util.hpp"

namespace shoremesh::cli_test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const char* const kLake =
    R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"lake"},"geometry":)"
    R"({"type":"Polygon","coordinates":[[[-80.9,26.8],[-80.7,26.8],[-80.6,27.0],[-80.8,27.2],[-81.0,27.0],[-80.9,26.8]],)"
    R"([[-80.85,26.95],[-80.75,26.95],[-80.8,27.05],[-80.85,26.95]]]}}]})";
const char* const kPoints = "x,y\n0,0\n4,0\n4,3\n0,3\n1,1\n2.5,1.5\n3,2.2\n";

// The inputs every case may name, written into its folder, and the files that exist before it runs.
const std::map<std::string, std::string>& inputs() {
  static const std::map<std::string, std::string> files = {
      {"lake.geojson", kLake},
      {"pts.csv", kPoints},
      {"pts3.csv", "0,0,0\n1,0,0\n0,1,0\n0,0,1\n1,1,1\n"},
      {"edits.txt", "stats\n"},
  };
  return files;
}
const std::map<std::string, std::string> kBefore = {
    {"keep.msh", "an earlier mesh\n"}, {"keep.png", "an earlier preview\n"}, {"keep.csv", "# an earlier point set\n"}};

struct Case {
  std::string name;                            // what the case is
  std::map<std::string, std::string> files;    // extra inputs written before it runs
  std::string args;                            // shell text after `shoremesh`
  int code;                                    // expected exit code
  std::vector<std::string> says;               // substrings of stdout + stderr (file, line, option, id)
  std::string stdin_text = {};
};

void run_case(const Case& c) {
  SCOPED_TRACE(c.name + ": shoremesh " + c.args);
  TempDir dir;
  for (const auto& [name, text] : inputs()) write_file(dir / name, text);
  for (const auto& [name, text] : c.files) {
    fs::create_directories((dir / name).parent_path());
    write_file(dir / name, text);
  }
  for (const auto& [name, text] : kBefore) write_file(dir / name, text);
  const RunResult r = shoremesh(dir, c.args, c.stdin_text);
  EXPECT_EQ(r.code, c.code) << r.out << r.err;
  for (const std::string& s : c.says) EXPECT_THAT(r.out + r.err, HasSubstr(s));
  EXPECT_THAT(r.err, Not(HasSubstr("internal error")));
  for (const auto& [name, text] : kBefore) EXPECT_EQ(read_file(dir / name), text) << name << " changed";
  for (const auto& [name, text] : inputs()) EXPECT_EQ(read_file(dir / name), text) << name << " changed";
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr(".tmp-"))) << "a temporary file was left";
}

// Runs `shoremesh ARGS` in `dir` and expects bad input: exit 1 and `message` on standard error.
RunResult expect_refused(const TempDir& dir, const std::string& args, const std::string& message) {
  const RunResult r = shoremesh(dir, args);
  EXPECT_EQ(r.code, 1) << args << ": " << r.err;
  EXPECT_THAT(r.err, HasSubstr(message)) << args;
  return r;
}

std::string lake_with(const std::string& coordinates) {
  return R"({"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":)" + coordinates + "}}";
}

std::vector<Case> matrix() {
  const std::string mesh = "mesh -q ";
  return {
      // Point files.
      {"empty point file", {{"e.csv", ""}}, mesh + "e.csv -o keep.msh", 1, {"e.csv"}},
      {"word in a number column", {{"w.csv", "x,y\n0,0\n1,abc\n"}}, mesh + "w.csv -o keep.msh", 1, {"w.csv:3", "abc"}},
      {"NaN coordinate", {{"n.csv", "x,y\n0,0\nnan,1\n2,2\n"}}, mesh + "n.csv -o keep.msh", 1, {"n.csv:3"}},
      {"four columns", {{"f.csv", "1,2,3,4\n"}}, mesh + "f.csv -o keep.msh", 1, {"f.csv:1", "columns"}},
      {"mixed 2 and 3 columns", {{"m.csv", "0,0\n1,1,1\n"}}, mesh + "m.csv -o keep.msh", 1, {"m.csv:2", "mixed"}},
      {"quoted number with a comma", {{"q.csv", "x,y\n\"1,5\",2\n0,0\n"}}, mesh + "q.csv -o keep.msh", 1, {"q.csv:2", "column 1"}},
      {"duplicate point", {{"d.csv", "0,0\n1,0\n0,1\n1,0\n"}}, mesh + "d.csv -o keep.msh", 1, {"d.csv", "line 4"}},
      {"coordinate near 1e300", {{"b.csv", "x,y\n1e300,1e300\n1.0000000000001e300,1e300\n1e300,1.0000000000001e300\n"}},
       mesh + "b.csv -o keep.msh", 1, {"b.csv:2", "1e+100"}},
      {"extent under 1e-100", {{"s.csv", "x,y\n1e-300,1e-300\n2e-300,1e-300\n1e-300,3e-300\n"}}, mesh + "s.csv -o keep.msh",
       1, {"s.csv: the input points span 2e-300", "1e-100"}},
      {"one point to a mesh", {{"one.csv", "x,y\n1,2\n"}}, mesh + "one.csv -o keep.msh", 1, {"keep.msh", "no triangle"}},
      {"3D input asked in 2D", {}, mesh + "pts.csv --dim 3 -o keep.msh", 1, {"--dim 3"}},
      // GPS, GeoJSON, PSLG, images.
      {"GPX that is not XML", {{"t.gpx", "<gpx><trk>"}}, mesh + "t.gpx -o keep.msh", 1, {"t.gpx"}},
      {"GPX latitude out of range", {{"t.gpx", R"(<gpx version="1.1"><wpt lat="95" lon="14"/></gpx>)"}},
       mesh + "t.gpx -o keep.msh", 1, {"t.gpx", "95"}},
      {"one-point GPX", {{"t.gpx", R"(<gpx version="1.1"><wpt lat="45" lon="14"/></gpx>)"}}, mesh + "t.gpx -o keep.msh", 1,
       {"keep.msh", "no triangle"}},
      {"GeoJSON that is not JSON", {{"g.geojson", "{\"type\":"}}, mesh + "g.geojson -o keep.msh", 1, {"g.geojson"}},
      {"GeoJSON Point alone", {{"g.geojson", R"({"type":"Point","coordinates":[14,45]})"}}, mesh + "g.geojson -o keep.msh", 1,
       {"keep.msh", "no triangle"}},
      {"GeoJSON lon 1e300", {{"g.geojson", lake_with("[[[14,45],[1e300,45],[14.1,45.1],[14,45]]]")}},
       mesh + "g.geojson -o keep.msh", 1, {"g.geojson", "1e+300"}},
      {"GeoJSON hole outside its ring",
       {{"g.geojson", lake_with("[[[0,0],[1,0],[1,1],[0,1],[0,0]],[[2,2],[3,2],[3,3],[2,2]]]")}}, mesh + "g.geojson -o keep.msh",
       1, {"g.geojson", "coordinates[1]", "hole 1"}},
      {"GeoJSON ring of two points", {{"g.geojson", lake_with("[[[0,0],[1,0],[0,0]]]")}}, mesh + "g.geojson -o keep.msh", 1,
       {"g.geojson", "coordinates[0]"}},
      {"poly with a bad vertex count", {{"p.poly", "x 2 0 0\n"}}, mesh + "p.poly -o keep.msh", 1, {"p.poly"}},
      {"PNG that is not an image", {{"i.png", "not a png at all"}}, mesh + "i.png -o keep.msh", 1, {"i.png"}},
      {"image cut short", {}, mesh + "cut.png -o keep.msh", 1, {"cut.png"}},
      // Options (exit 2, the option named).
      {"box side 0", {}, mesh + "pts.csv --box 0 0 0 -o keep.msh", 2, {"--box", "above 0"}},
      {"box of NaN", {}, mesh + "pts.csv --box nan 0 10 -o keep.msh", 2, {"--box", "nan"}},
      {"box with the wrong count", {}, mesh + "pts.csv --box 0 0 0 10 -o keep.msh", 2, {"--box takes 3"}},
      {"spacing NaN", {}, mesh + "lake.geojson --spacing nan -o keep.msh", 2, {"--spacing", "nan"}},
      {"spacing negative", {}, mesh + "lake.geojson --spacing -3 -o keep.msh", 2, {"--spacing", "-3"}},
      {"spacing that cuts too many points", {}, mesh + "lake.geojson --spacing 1e-3 -o keep.msh", 1,
       {"lake.geojson: --spacing 0.001 would cut the rings and segments into", "more than the 10000000 allowed"}},
      {"box side under 1e-100", {}, mesh + "pts.csv --box 0 0 1e-200 -o keep.msh", 2, {"--box", "1e-200", "1e-100"}},
      {"min-area NaN", {}, mesh + "pts.csv --min-area nan -o keep.msh", 2, {"--min-area", "nan"}},
      {"threshold NaN", {}, mesh + "pts.csv --threshold nan -o keep.msh", 2, {"--threshold", "nan"}},
      {"colour tolerance negative", {}, mesh + "pts.csv --colour-tolerance -1 -o keep.msh", 2, {"--colour-tolerance", "-1"}},
      {"rho 1e9", {}, mesh + "pts.csv --rho 1e9 -o keep.msh", 2, {"rho 1000000000", "smaller rho"}},
      {"rho barely above 1", {}, mesh + "pts.csv --rho 1.0000001 -o keep.msh", 2, {"1.0000001"}},
      {"rho NaN", {}, mesh + "pts.csv --rho nan -o keep.msh", 2, {"--rho", "nan"}},
      {"dim 4", {}, mesh + "pts.csv --dim 4 -o keep.msh", 2, {"--dim"}},
      {"unknown format", {}, mesh + "pts.csv --format xyz -o keep.msh", 2, {"--format"}},
      {"missing input file", {}, mesh + "nothere.csv -o keep.msh", 2, {"nothere.csv"}},
      {"unknown command", {}, "frobnicate pts.csv", 2, {"frobnicate"}},
      {"point outside the given box", {}, mesh + "pts.csv --box 1 1 10 -o keep.msh", 1, {"pts.csv:2", "outside"}},
      // Outputs.
      {"unknown output extension", {}, mesh + "pts.csv -o keep.xyz", 1, {"keep.xyz"}},
      {"preview in a missing folder", {}, mesh + "lake.geojson -o keep.msh --preview /nonexistent/p.png", 1,
       {"--preview /nonexistent/p.png", "does not exist"}},
      {"output in a missing folder", {}, mesh + "lake.geojson -o /nonexistent/x.msh --preview keep.png", 1, {"/nonexistent/x.msh"}},
      {"output that is a folder", {{"sub.msh/.keep", ""}}, mesh + "lake.geojson -o sub.msh --preview keep.png", 1,
       {"sub.msh", "folder"}},
      {"output that is the input", {}, mesh + "lake.geojson -o ./lake.geojson", 1, {"lake.geojson", "input"}},
      {"output in /proc", {}, mesh + "lake.geojson -o /proc/x.msh --preview keep.png", 1, {"/proc/x.msh"}},
      {"the same output twice", {}, mesh + "lake.geojson -o keep.msh --preview ./keep.msh", 1, {"keep.msh", "twice"}},
      // Edit lines (exit 1 at the end, the line and id named; the session goes on).
      {"edit: move a missing id", {}, "edit -q pts.csv --edits -", 1, {"line 1", "no input point 99999"}, "move 99999 1 2\n"},
      {"edit: add far away", {}, "edit -q lake.geojson --edits -", 1, {"line 1", "1e+300"}, "add 1e300 1e300\n"},
      {"edit: remove a word", {}, "edit -q pts.csv --edits -", 1, {"line 1", "'abc' is not an id"}, "remove abc\n"},
      {"edit: unknown edit", {}, "edit -q pts.csv --edits -", 1, {"line 2", "frob"}, "stats\nfrob 1\n"},
      {"edit: add without coordinates", {}, "edit -q pts.csv --edits -", 1, {"line 1", "add takes"}, "add 1\n"},
      {"edit: export to a missing folder", {}, "edit -q pts.csv --edits -", 1, {"line 1", "/nonexistent/x.csv"},
       "export /nonexistent/x.csv\n"},
      {"edit: move to NaN", {}, "edit -q pts.csv --edits -", 1, {"line 1", "nan"}, "move 1 nan 2\n"},
      {"edit: missing edits file", {}, "edit -q pts.csv --edits nothere.txt", 1, {"nothere.txt"}},
  };
}

TEST(HostileInput, EveryCaseExitsAsDocumentedNamesTheCulpritAndKeepsEarlierFiles) {
  const std::vector<Case> cases = matrix();
  ASSERT_GE(cases.size(), 40u);
  // cut.png: the bundled Superior mask, cut to a quarter of its bytes.
  const std::string mask = read_file(superior_mask());
  std::vector<Case> with_image = cases;
  for (Case& c : with_image)
    if (c.name == "image cut short") c.files["cut.png"] = mask.substr(0, mask.size() / 4);
  for (const Case& c : with_image) run_case(c);
}

// Item 2: the preview fails after the mesh was made; the mesh file that existed is left as it was.
TEST(HostileInput, AFailedRunLeavesAnEarlierOutputAsItWas) {
  TempDir dir;
  write_file(dir / "lake.geojson", kLake);
  write_file(dir / "keep.msh", "earlier\n");
  const RunResult r = shoremesh(dir, "mesh -q lake.geojson -o keep.msh --preview /nonexistent/p.png");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(read_file(dir / "keep.msh"), "earlier\n");
  // And a good run writes both.
  const RunResult ok = shoremesh(dir, "mesh -q lake.geojson -o keep.msh --preview p.png");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_THAT(read_file(dir / "keep.msh"), HasSubstr("$MeshFormat"));
  EXPECT_TRUE(fs::exists(dir / "p.png"));
}

// Item 3: the shoreline is not replaced by its own mesh, whatever path names it.
TEST(HostileInput, AnOutputThatIsAnInputIsRefused) {
  TempDir dir;
  fs::create_directories(dir / "sub");
  write_file(dir / "lake.geojson", kLake);
  for (const std::string& out : {std::string("lake.geojson"), std::string("./sub/../lake.geojson"), (dir / "lake.geojson").string()}) {
    const RunResult r = shoremesh(dir, "mesh -q lake.geojson -o " + quote(out));
    EXPECT_EQ(r.code, 1) << out << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr("is also an input"));
  }
  EXPECT_EQ(read_file(dir / "lake.geojson"), kLake);
}

// Item 3 in the edit session: export, preview and preview-change replace no file the session read, through
// any path (relative, absolute, a symbolic link), nor the edit lines' own file; a refused line leaves
// every file as it was, and the lines after it still write. A .poly's vertices may live in its .node:
// that file is an input of `mesh` and `edit` too.
TEST(HostileInput, AnEditSessionWritesOverNoInput) {
  TempDir dir;
  fs::create_directories(dir / "sub");
  write_file(dir / "pts.csv", kPoints);
  fs::create_symlink("pts.csv", dir / "link.png");
  const std::string edits = "export pts.csv\nexport ./sub/../pts.csv\nexport " + (dir / "pts.csv").string() +
                            "\npreview link.png\npreview-change pts.csv\nexport edits.csv\nexport ok.csv\npreview ok.png\n";
  write_file(dir / "edits.csv", edits);
  const RunResult r = shoremesh(dir, "edit -q pts.csv --edits edits.csv");
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  for (const std::string& line : std::vector<std::string>{
           "line 1: error: export pts.csv: is also an input", "line 2: error: export ./sub/../pts.csv: is also an input",
           "line 3: error: export " + (dir / "pts.csv").string() + ": is also an input",
           "line 4: error: preview link.png: is also an input", "line 5: error: preview-change pts.csv: is also an input",
           "line 6: error: export edits.csv: is also an input"})
    EXPECT_THAT(r.out, HasSubstr(line));
  EXPECT_THAT(r.out, HasSubstr("line 7: wrote ok.csv"));
  EXPECT_THAT(r.out, HasSubstr("line 8: wrote ok.png"));
  EXPECT_EQ(read_file(dir / "pts.csv"), kPoints);
  EXPECT_EQ(read_file(dir / "edits.csv"), edits);

  // A .poly that declares no vertex reads them from its .node; the Triangle export would replace it.
  const std::string node = "4 2 0 0\n1 0 0\n2 4 0\n3 4 3\n4 0 3\n";
  write_file(dir / "sq.node", node);
  write_file(dir / "sq.poly", "0 2 0 0\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n");
  const RunResult poly = shoremesh(dir, "edit -q sq.poly --edits -", "export sq.node\nexport sq.ele\n");
  EXPECT_THAT(poly.out, HasSubstr("line 1: error: export sq.node: is also an input"));
  EXPECT_THAT(poly.out, HasSubstr("line 2: error: export sq.node: is also an input"));
  expect_refused(dir, "mesh -q sq.poly -o sq.ele", "-o sq.node: is also an input");
  EXPECT_EQ(read_file(dir / "sq.node"), node);
  EXPECT_FALSE(fs::exists(dir / "sq.ele"));
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr(".tmp-"))) << "a temporary file was left";
}

// Item 4: a JPEG cut to a quarter is refused, naming the file; the whole JPEG meshes.
TEST(HostileInput, AJpegCutShortIsAnErrorNamingTheFile) {
  TempDir dir;
  write_file(dir / "lake.geojson", kLake);
  ASSERT_EQ(shoremesh(dir, "mesh -q lake.geojson -o a.msh --preview whole.jpg").code, 0);
  const std::string jpeg = read_file(dir / "whole.jpg");
  ASSERT_GT(jpeg.size(), 1000u);
  write_file(dir / "cut.jpg", jpeg.substr(0, jpeg.size() / 4));
  expect_refused(dir, "mesh -q cut.jpg -o b.msh", "cut.jpg: the JPEG is cut short");
  EXPECT_FALSE(fs::exists(dir / "b.msh"));
  EXPECT_THAT(shoremesh(dir, "mesh -q whole.jpg -o c.msh").err, Not(HasSubstr("cut short")));
}

// Item 5: absurd coordinates are refused naming the limit; numbers print readably everywhere.
TEST(HostileInput, CoordinatesTheEngineCannotRepresentAreRefusedNamingTheLimit) {
  TempDir dir;
  write_file(dir / "b.csv", "x,y\n1e300,1e300\n-1e300,1e300\n1e300,-1e300\n");
  expect_refused(dir, "mesh -q b.csv -o b.msh",
                 "b.csv:2: point 0 has a coordinate of 1e+300, beyond the largest the engine represents (1e+100)");
  write_file(dir / "lake.geojson", kLake);
  const RunResult e = shoremesh(dir, "edit -q lake.geojson --edits -", "add 1e300 1e300\n");
  EXPECT_EQ(e.code, 1);
  EXPECT_THAT(e.out, HasSubstr("(1e+300, 1e+300) m is outside"));
  EXPECT_THAT(e.out, Not(HasSubstr("nan")));
}

// Item 6: a mesh output with no element is an error; the point set of one point is still written.
TEST(HostileInput, AMeshWithNoElementIsAnError) {
  TempDir dir;
  write_file(dir / "one.csv", "x,y\n1,2\n");
  expect_refused(dir, "mesh -q one.csv -o one.msh", "one.msh: the mesh has no triangle: 1 points span no triangle");
  EXPECT_FALSE(fs::exists(dir / "one.msh"));
  EXPECT_EQ(shoremesh(dir, "mesh -q one.csv -o one_ws.csv").code, 0);
}

// Item 7: the README's exit codes: NaN options are command-line mistakes, an unwritable place bad input.
TEST(HostileInput, ExitCodesFollowTheReadme) {
  TempDir dir;
  write_file(dir / "pts.csv", kPoints);
  for (const char* bad : {"--box 0 0 0", "--spacing nan", "--min-area nan", "--threshold nan", "--colour-tolerance -1"})
    EXPECT_EQ(shoremesh(dir, std::string("mesh -q pts.csv -o a.msh ") + bad).code, 2) << bad;
  expect_refused(dir, "mesh -q pts.csv -o /proc/a.msh", "-o /proc/a.msh: cannot write here: ");
}

// Item 8: messages speak the user's language: options that exist, numbers as given, the id first.
TEST(HostileInput, MessagesNameOptionsAndNumbersAsTheUserGaveThem) {
  TempDir dir;
  write_file(dir / "pts.csv", kPoints);
  const RunResult big = shoremesh(dir, "mesh -q pts.csv -o a.msh --rho 1e9");
  EXPECT_THAT(big.err, Not(HasSubstr("beta")));
  EXPECT_THAT(shoremesh(dir, "mesh -q pts.csv -o a.msh --rho 1.0000001").err, HasSubstr("(got 1.0000001)"));
  EXPECT_THAT(shoremesh(dir, "mesh -q pts.csv -o a.msh --min-area nan").err, Not(HasSubstr("width_fraction")));
  EXPECT_THAT(shoremesh(dir, "mesh -q pts.csv -o a.msh --box nan 0 10").err, Not(HasSubstr("point 0")));
  EXPECT_THAT(shoremesh(dir, "mesh -q pts.csv -o a.msh --threshold nan").err, Not(HasSubstr("all land")));
  const RunResult move = shoremesh(dir, "edit -q pts.csv --edits -", "move 99999 1e9 2\n");
  EXPECT_THAT(move.out, HasSubstr("no input point 99999"));
  EXPECT_THAT(move.out, Not(HasSubstr("outside the session's box")));
}

// Item 10: the two Steiner counts of one run say which is which.
TEST(HostileInput, SteinerCountsSayInTheBoxAndInTheMesh) {
  TempDir dir;
  write_file(dir / "lake.geojson", kLake);
  const RunResult r = shoremesh(dir, "mesh -q lake.geojson -o a.msh --spacing 2000");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::ContainsRegex("[0-9]+ Steiner points in the box \\([0-9]+ of them in the mesh\\)"));
}

// Item 11: a 2D mesh's $Entities boxes are finite (z from 0 to 0).
TEST(HostileInput, GmshEntitiesOfA2DMeshHaveFiniteBoxes) {
  TempDir dir;
  write_file(dir / "lake.geojson", kLake);
  ASSERT_EQ(shoremesh(dir, "mesh -q lake.geojson -o a.msh").code, 0);
  const std::string msh = read_file(dir / "a.msh");
  const auto from = msh.find("$Entities"), to = msh.find("$EndEntities");
  ASSERT_NE(from, std::string::npos);
  const std::string entities = msh.substr(from, to - from);
  EXPECT_THAT(entities, Not(HasSubstr("inf")));
  EXPECT_THAT(entities, Not(HasSubstr("nan")));
}

// Item 12: a quoted CSV field holding a comma stays one field (a GPS track with a quoted name column).
TEST(HostileInput, AQuotedCsvFieldWithACommaStaysOneField) {
  TempDir dir;
  write_file(dir / "track.csv",
             "time,lat,lon,name\n1,45.0,14.0,\"start, north\"\n2,45.001,14.001,plain\n3,45.002,14.0005,\"x, y, z\"\n"
             "4,45.0005,14.002,\"\"\"quoted\"\"\"\n");
  const RunResult r = shoremesh(dir, "mesh -q track.csv -o t.csv");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("input: 4 2D points"));
}

}  // namespace
}  // namespace shoremesh::cli_test
