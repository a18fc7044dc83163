// `shoremesh serve` over HTTP: POST /edit answers exactly what `shoremesh edit --json` answers for the
// same lines; the changes it sends (the slots a page rewrites) rebuild GET /mesh; the session then equals a
// fresh run on its exported shoreline; requests that may not run (bad lines, oversized bodies, export paths
// outside --export-dir, files read on the server) are refused and change nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <thread>

#include "cli_test_util.hpp"
#include "dem_test_util.hpp"
#include "shoremesh/io/point_set_csv.hpp"

namespace shoremesh::cli_test {
namespace {

using ::testing::HasSubstr;
using json = nlohmann::json;

// A `shoremesh serve` process on a free loopback port, stopped (SIGTERM) at the end of the test.
class ServeProcess {
 public:
  ServeProcess(const TempDir& dir, const std::string& args) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe");
    const std::string cmd = "cd " + quote(dir.path().string()) + " && exec " + quote(SHOREMESH_BINARY) + " serve " +
                            args + " 2>" + quote((dir / ".serve_stderr").string());
    pid_ = fork();
    if (pid_ == 0) {
      dup2(fds[1], STDOUT_FILENO);
      close(fds[0]);
      close(fds[1]);
      execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    FILE* out = fdopen(fds[0], "r");
    char buf[4096];
    while (std::fgets(buf, sizeof buf, out)) {  // the build's summary, then the URL
      const std::string line = buf;
      const auto at = line.find("serving http://");
      if (at == std::string::npos) continue;
      const auto colon = line.find(':', at + 15);
      host_ = line.substr(at + 15, colon - at - 15);
      port_ = std::stoi(line.substr(colon + 1));
      break;
    }
    std::fclose(out);
    if (port_ == 0) throw std::runtime_error("serve printed no URL: " + read_file(dir / ".serve_stderr"));
  }
  ~ServeProcess() { stop(SIGTERM); }
  void stop(int signal) {
    if (pid_ <= 0) return;
    kill(pid_, signal);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
  }
  httplib::Client client() const {
    httplib::Client c(host_, port_);
    c.set_read_timeout(120, 0);
    return c;
  }
  int port() const { return port_; }

 private:
  pid_t pid_ = -1;
  std::string host_;
  int port_ = 0;
};

std::vector<json> json_lines(const std::string& out) {
  std::vector<json> replies;
  for (const auto& l : lines_of(out)) replies.push_back(json::parse(l));
  return replies;
}

// A reply without its times (which differ from run to run).
json untimed(json r) {
  for (const char* k : {"ms", "rings_ms", "engine_ms", "mesh_ms"}) r.erase(k);
  return r;
}

// GET /mesh: the JSON head and each slot's corners (float x y, 3 corners), kinds and (with depths) the
// corners' depths; empty slots as empty.
struct Slots {
  json head;
  std::vector<std::array<float, 6>> xy;
  std::vector<std::array<int, 3>> kinds;
  std::vector<std::array<float, 3>> depth;
};
Slots get_mesh(httplib::Client& c) {
  const auto res = c.Get("/mesh");
  EXPECT_TRUE(res && res->status == 200);
  const std::string& b = res->body;
  EXPECT_EQ(b.substr(0, 4), "SMSH");
  std::uint32_t length = 0;
  std::memcpy(&length, b.data() + 4, 4);
  Slots s;
  s.head = json::parse(b.substr(8, length));
  const std::size_t n = s.head["slots"].get<std::size_t>();
  const std::size_t depths_at = (8 + length + n * 27 + 3) / 4 * 4;
  EXPECT_EQ(b.size(), s.head.value("depths", false) ? depths_at + n * 12 : 8 + length + n * 27);
  s.xy.resize(n);
  s.kinds.resize(n);
  std::memcpy(s.xy.data(), b.data() + 8 + length, n * 24);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) s.kinds[i][k] = static_cast<unsigned char>(b[8 + length + n * 24 + i * 3 + k]);
  if (s.head.value("depths", false) && b.size() == depths_at + n * 12) {
    s.depth.resize(n);
    std::memcpy(s.depth.data(), b.data() + depths_at, n * 12);
  }
  return s;
}

// The drawn nodes' depths (one per place), sorted.
std::vector<float> drawn_depths(const Slots& s) {
  std::map<std::pair<float, float>, float> at;
  for (std::size_t i = 0; i < s.xy.size(); ++i)
    if (s.kinds[i][0] != 255)
      for (int k = 0; k < 3; ++k) at[{s.xy[i][2 * k], s.xy[i][2 * k + 1]}] = s.depth.at(i)[k];
  std::vector<float> out;
  for (const auto& [p, d] : at) out.push_back(d);
  std::sort(out.begin(), out.end());
  return out;
}

// The non-empty slots' triangles as sorted corner triples (what is drawn, whatever the slots).
std::vector<std::array<std::pair<float, float>, 3>> drawn(const Slots& s) {
  std::vector<std::array<std::pair<float, float>, 3>> out;
  for (std::size_t i = 0; i < s.xy.size(); ++i) {
    if (s.kinds[i][0] == 255) continue;
    std::array<std::pair<float, float>, 3> t{{{s.xy[i][0], s.xy[i][1]}, {s.xy[i][2], s.xy[i][3]}, {s.xy[i][4], s.xy[i][5]}}};
    std::sort(t.begin(), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The triangles of an OFF export, each corner as float(x - origin) like the server's slots.
std::vector<std::array<std::pair<float, float>, 3>> off_drawn(const fs::path& off, const json& origin) {
  std::istringstream in(read_file(off));
  std::string magic;
  std::size_t points = 0, faces = 0, edges = 0;
  in >> magic >> points >> faces >> edges;
  std::vector<std::pair<float, float>> corner(points);
  const double ox = origin[0].get<double>(), oy = origin[1].get<double>();
  for (auto& c : corner) {
    double x, y, z;
    in >> x >> y >> z;
    c = {static_cast<float>(x - ox), static_cast<float>(y - oy)};
  }
  std::vector<std::array<std::pair<float, float>, 3>> out;
  for (std::size_t f = 0; f < faces; ++f) {
    std::size_t three = 0, a = 0, b = 0, c = 0;
    in >> three >> a >> b >> c;
    std::array<std::pair<float, float>, 3> t{corner.at(a), corner.at(b), corner.at(c)};
    std::sort(t.begin(), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ServeCommand, PostEditAnswersLikeEditJsonAndItsChangesRebuildTheMeshThatEqualsAFreshRun) {
  TempDir dir;
  fs::create_directories(dir / "out");
  const std::string read = quote(superior_mask()) + " --largest-water --spacing 8000";
  const RunResult start = shoremesh(dir, "mesh -q " + read + " -o start.csv");
  ASSERT_EQ(start.code, 0) << start.err;
  const auto all = io::read_point_set_csv<2>(dir / "start.csv");
  auto xy = [](const Point2& p) { return io::format_double(p[0]) + " " + io::format_double(p[1]); };
  auto lerp = [&](std::size_t a, std::size_t b, double t) {
    return Point2{all.points[a][0] + t * (all.points[b][0] - all.points[a][0]),
                  all.points[a][1] + t * (all.points[b][1] - all.points[a][1])};
  };
  const std::string edits = "move 40 " + xy(lerp(40, 41, 0.3)) + "\n" +
                            "move 60 " + xy(all.points[400]) + "\n" +  // across the lake: refused
                            "add " + xy(lerp(100, 101, 0.5)) + " after 100\n" +
                            "\n# a comment\n"
                            "remove 70\n"
                            "move 41 " + xy(lerp(41, 42, 0.2)) + "\n" +
                            "frobnicate 3\n"
                            "stats\n";
  const RunResult cli = shoremesh(dir, "edit " + read + " --json --edits -", edits);
  const auto expected = json_lines(cli.out);
  ASSERT_EQ(expected.size(), 8u) << cli.out << cli.err;  // build + 7 replies

  ServeProcess server(dir, read + " --export-dir out");
  auto c = server.client();
  const Slots before = get_mesh(c);
  EXPECT_EQ(before.head["version"], 0);
  EXPECT_EQ(before.head["triangles"], expected[0]["elements"]);
  EXPECT_EQ(before.head["origin"], json({expected[0]["box"][0], expected[0]["box"][1]}));
  std::size_t ring_points = 0;
  for (const auto& r : before.head["rings"]) ring_points += r["ids"].size();
  EXPECT_EQ(ring_points, expected[0]["input_points"]);  // the lake and its islands: every input point

  const auto res = c.Post("/edit", edits, "text/plain");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  // The page's profile reads where the request's time went on the server (docs/editor.md, "Profile").
  const std::string timing = res->get_header_value("Server-Timing");
  for (const char* part : {"lock;dur=", "edit;dur=", "json;dur=", "total;dur="})
    EXPECT_NE(timing.find(part), std::string::npos) << part << " in '" << timing << "'";
  const json out = json::parse(res->body);
  ASSERT_EQ(out["replies"].size(), expected.size() - 1) << out["replies"];
  for (std::size_t i = 0; i + 1 < expected.size(); ++i)
    EXPECT_EQ(untimed(out["replies"][i]), untimed(expected[i + 1])) << "reply " << i;
  EXPECT_FALSE(out["replies"][1]["ok"].get<bool>());
  EXPECT_EQ(out["version"], 4);  // four accepted edits
  ASSERT_EQ(out["changes"].size(), 4u);

  // The changes, applied slot by slot as the page does, give what GET /mesh now sends.
  Slots page = before;
  for (const auto& change : out["changes"]) {
    const std::size_t slots = change["slots"].get<std::size_t>();
    page.xy.resize(slots, {0, 0, 0, 0, 0, 0});
    page.kinds.resize(slots, {255, 255, 255});
    for (const auto& s : change["cleared"]) page.kinds[s.get<std::size_t>()] = {255, 255, 255};
    const json o = before.head["origin"];
    for (const auto& a : change["added"]) {
      const std::size_t s = a[0].get<std::size_t>();
      for (int k = 0; k < 6; ++k) page.xy[s][k] = static_cast<float>(a[1 + k].get<double>());
      for (int k = 0; k < 3; ++k) page.kinds[s][k] = a[7 + k].get<int>();
    }
  }
  const Slots after = get_mesh(c);
  EXPECT_EQ(after.head["version"], 4);
  EXPECT_EQ(after.head["triangles"], out["replies"].back()["elements"]);
  EXPECT_EQ(drawn(page), drawn(after));
  EXPECT_EQ(drawn(after).size(), after.head["triangles"].get<std::size_t>());
  for (std::size_t i = 0; i < after.kinds.size(); ++i)
    if (after.kinds[i][0] != 255) {
      EXPECT_EQ(page.kinds[i], after.kinds[i]) << "slot " << i;
    }
  // The moved and added shore points are where the edits put them, in ring order (ring 1: the lake's shore).
  const json& ring = after.head["rings"][0];
  const auto ids = ring["ids"].get<std::vector<std::size_t>>();
  const auto at = std::find(ids.begin(), ids.end(), 40) - ids.begin();
  EXPECT_EQ(ring["xy"][2 * at], lerp(40, 41, 0.3)[0]);
  const auto after100 = std::find(ids.begin(), ids.end(), 100) + 1;
  ASSERT_NE(after100, ids.end());
  EXPECT_EQ(*after100, expected[3]["id"].get<std::size_t>());
  EXPECT_EQ(std::find(ids.begin(), ids.end(), 70), ids.end());

  // ?replies=lines: the replies only, one a line, as `edit --json` prints them; then the exports.
  const auto lines = c.Post("/edit?replies=lines", "stats\nexport final.rings\nexport final.off\n", "text/plain");
  ASSERT_TRUE(lines && lines->status == 200);
  const auto exported = json_lines(lines->body);
  ASSERT_EQ(exported.size(), 3u) << lines->body;
  json stats_again = untimed(exported[0]), stats_before = untimed(expected.back());
  EXPECT_EQ(stats_again["line"], 1);  // lines are numbered per request
  stats_again.erase("line"), stats_before.erase("line");
  EXPECT_EQ(stats_again, stats_before);
  EXPECT_EQ(exported[1]["path"], (dir / "out" / "final.rings").string());
  ASSERT_TRUE(exported[2]["ok"].get<bool>()) << exported[2];

  // The session's mesh equals a fresh run on the exported shoreline in the session's box.
  const json& box = expected[0]["box"];
  const RunResult fresh = shoremesh(dir, "mesh -q out/final.rings --box " + box[0].dump() + " " + box[1].dump() + " " +
                                             box[2].dump() + " -o fresh.off");
  ASSERT_EQ(fresh.code, 0) << fresh.err;
  EXPECT_EQ(off_drawn(dir / "out" / "final.off", before.head["origin"]), off_drawn(dir / "fresh.off", before.head["origin"]));
  EXPECT_EQ(off_drawn(dir / "fresh.off", before.head["origin"]), drawn(after));

  // GET /stats: the stats reply and the session's version.
  const auto stats = c.Get("/stats");
  ASSERT_TRUE(stats && stats->status == 200);
  EXPECT_EQ(untimed(json::parse(stats->body)).value("elements", 0), expected.back()["elements"]);
  EXPECT_EQ(json::parse(stats->body)["version"], 4);
}

TEST(ServeCommand, BadRequestsAreRefusedAndChangeNothing) {
  TempDir dir;
  std::string lake;
  for (int i = 0; i <= 16; ++i) {
    const double t = 2 * 3.141592653589793 * (i % 16) / 16;
    lake += io::format_double(200 + 100 * std::cos(t)) + "," + io::format_double(200 + 100 * std::sin(t)) + "\n";
  }
  write_file(dir / "lake.txt", lake);
  fs::create_directories(dir / "out");
  ServeProcess server(dir, "lake.txt --export-dir out --max-body 4096");
  auto c = server.client();
  const std::string before = get_mesh(c).head.dump();

  auto post = [&](const std::string& body) { return c.Post("/edit", body, "text/plain"); };
  const auto empty = post("  \n");
  ASSERT_TRUE(empty);
  EXPECT_EQ(empty->status, 400);
  EXPECT_THAT(json::parse(empty->body)["error"].get<std::string>(), HasSubstr("edit lines"));
  const auto big = post("stats\n" + std::string(5000, '#'));
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  const auto missing = c.Get("/nothing-here");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_THAT(json::parse(missing->body)["error"].get<std::string>(), HasSubstr("POST /edit"));

  const std::string outside = (dir / "outside.off").string();
  const auto res = post("export ../escaped.off\nexport " + outside + "\nexport sub/x.off\nexport .hidden.off\n"
                        "preview ../p.png\nadd-ring lake.txt\nmove 999 1 2\nmove 3 1e6 1e6\nremove x\nfrobnicate\n");
  ASSERT_TRUE(res && res->status == 200);
  const json out = json::parse(res->body);
  ASSERT_EQ(out["replies"].size(), 10u);
  for (const auto& r : out["replies"]) {
    EXPECT_FALSE(r["ok"].get<bool>()) << r;
    EXPECT_TRUE(r.contains("line") && r.contains("error")) << r;
  }
  for (int i = 0; i < 5; ++i)
    EXPECT_THAT(out["replies"][i]["error"].get<std::string>(), HasSubstr("--export-dir")) << out["replies"][i];
  EXPECT_THAT(out["replies"][5]["error"].get<std::string>(), HasSubstr("reads a file on the server"));
  EXPECT_TRUE(out["changes"].empty());
  EXPECT_EQ(out["version"], 0);
  EXPECT_FALSE(fs::exists(dir / "escaped.off"));
  EXPECT_FALSE(fs::exists(outside));
  EXPECT_FALSE(fs::exists(dir / "p.png"));
  EXPECT_EQ(get_mesh(c).head.dump(), before);  // nothing changed

  // A plain name is written into --export-dir.
  const auto ok = post("export good.off");
  ASSERT_TRUE(ok && ok->status == 200);
  EXPECT_TRUE(json::parse(ok->body)["replies"][0]["ok"].get<bool>()) << ok->body;
  EXPECT_TRUE(fs::exists(dir / "out" / "good.off"));
}

TEST(ServeCommand, EventsStreamEachAcceptedEditAndThePageIsServed) {
  TempDir dir;
  write_file(dir / "lake.txt", "0,0\n100,0\n100,100\n0,100\n0,0\n");
  ServeProcess server(dir, "lake.txt");
  auto c = server.client();
  const auto page = c.Get("/");
  ASSERT_TRUE(page && page->status == 200);
  EXPECT_THAT(page->body, HasSubstr("<script src=\"app.js\">"));
  const auto app = c.Get("/app.js");
  ASSERT_TRUE(app && app->status == 200);
  EXPECT_GT(app->body.size(), 10000u);  // three.js and the editor, bundled

  // An event stream open while a script edits: it gets the accepted edit's change, not the refused one.
  std::string stream;
  std::thread reader([&] {
    httplib::Client events("127.0.0.1", server.port());
    events.set_read_timeout(30, 0);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    events.Get("/events", [&](const char* data, std::size_t n) {
      stream.append(data, n);
      return stream.find("event: change") == std::string::npos && std::chrono::steady_clock::now() < until;
    });
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the stream is open
  const auto res = c.Post("/edit", "move 1 400 400\nmove 1 90 10\n", "text/plain");
  ASSERT_TRUE(res && res->status == 200);
  reader.join();
  EXPECT_THAT(stream, HasSubstr("event: hello"));
  const auto at = stream.find("event: change\ndata: ");
  ASSERT_NE(at, std::string::npos) << stream;
  const json change = json::parse(stream.substr(at + 20, stream.find('\n', at + 20) - at - 20));
  EXPECT_EQ(change["version"], 1);
  EXPECT_EQ(change["reply"]["line"], 2);
  EXPECT_EQ(change["inputs"][0]["id"], 1);
  EXPECT_EQ(change["inputs"][0]["x"], 90);
}

TEST(ServeCommand, AKilledServerResumesFromItsEditLogToTheSameState) {
  TempDir dir;
  write_file(dir / "lake.txt", "0,0\n100,0\n100,100\n0,100\n0,0\n");
  fs::create_directories(dir / "out");
  const std::string edits = "move 1 90 10\nadd 50 50\nmove 999 1 1\nadd 60 5 after 0\nremove 4\nexport killed.off\n";
  {
    ServeProcess server(dir, "lake.txt --export-dir out --log edits.log");
    auto c = server.client();
    const auto res = c.Post("/edit?replies=lines", edits, "text/plain");
    ASSERT_TRUE(res && res->status == 200);
    EXPECT_EQ(json_lines(res->body).at(3)["id"], 5);
    server.stop(SIGKILL);  // no chance to write anything more
  }
  // The accepted edit lines only, in order.
  EXPECT_EQ(read_file(dir / "edits.log"), "move 1 90 10\nadd 50 50\nadd 60 5 after 0\nremove 4\n");
  const RunResult over = shoremesh(dir, "serve lake.txt --log edits.log");
  EXPECT_EQ(over.code, 1);
  EXPECT_THAT(over.err, HasSubstr("--resume"));
  {
    ServeProcess resumed(dir, "lake.txt --export-dir out --resume edits.log");
    auto c = resumed.client();
    const auto res = c.Post("/edit?replies=lines", "export resumed.off\nadd 20 20\n", "text/plain");
    ASSERT_TRUE(res && res->status == 200);
    EXPECT_EQ(json_lines(res->body).at(1)["id"], 6);  // the ids go on where the killed server left them
    // The summary's session replays the resumed lines too: its summary is the session's own.
    const auto own = c.Post("/edit?replies=lines", "stats\n", "text/plain");
    const auto summary = c.Get("/stats");
    ASSERT_TRUE(own && own->status == 200 && summary && summary->status == 200);
    json a = untimed(json_lines(own->body).at(0)), b = untimed(json::parse(summary->body));
    EXPECT_EQ(b["version"], 1);  // the edits since the resume
    for (const char* k : {"line", "version", "ring_count", "exports"}) a.erase(k), b.erase(k);
    EXPECT_EQ(a, b);
    EXPECT_EQ(b["next_id"], 7);
  }
  EXPECT_EQ(read_file(dir / "out" / "killed.off"), read_file(dir / "out" / "resumed.off"));
  EXPECT_EQ(read_file(dir / "edits.log"), "move 1 90 10\nadd 50 50\nadd 60 5 after 0\nremove 4\nadd 20 20\n");
  // A log that these inputs refuse is an error naming its line, not a different state.
  write_file(dir / "bad.log", "move 1 90 10\nmove 77 1 1\n");
  const RunResult bad = shoremesh(dir, "serve lake.txt --resume bad.log");
  EXPECT_EQ(bad.code, 1);
  EXPECT_THAT(bad.err, HasSubstr("line 2 of the edit log is refused"));
  write_file(dir / "export.log", "move 1 90 10\nexport ../elsewhere.off\n");
  const RunResult not_edit = shoremesh(dir, "serve lake.txt --resume export.log");
  EXPECT_EQ(not_edit.code, 1);
  EXPECT_THAT(not_edit.err, HasSubstr("line 2 of the edit log is not an edit"));
  EXPECT_FALSE(fs::exists(dir / "elsewhere.off"));
}

TEST(ServeCommand, ChangesCarryTheNodesDepthsAsExportsGiveThemAndLinesKeepTheirEnds) {
  TempDir dir;
  fs::create_directories(dir / "out");
  // A round basin, 24 x 24 cells of 1 km: -60 m at the centre, rising 8 m a cell (water within ~7 km).
  std::vector<float> z(24 * 24);
  for (int r = 0; r < 24; ++r)
    for (int c = 0; c < 24; ++c) z[r * 24 + c] = static_cast<float>(std::hypot(r - 11.5, c - 11.5) * 8 - 60);
  write_dem(dir / "basin.tif", 24, 24, z);
  ServeProcess server(dir, "--dem basin.tif --export-dir out");
  auto c = server.client();
  const Slots before = get_mesh(c);
  ASSERT_TRUE(before.head.value("depths", false));
  ASSERT_EQ(before.depth.size(), before.xy.size());
  auto export_depths = [&](const std::string& name) {
    const auto r = c.Post("/edit?replies=lines", "export " + name, "text/plain");
    EXPECT_TRUE(r && r->status == 200);
    std::vector<float> out;
    for (const auto& [id, n] : parse_fort14(read_file(dir / "out" / name)).nodes) out.push_back(static_cast<float>(n.depth));
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_EQ(drawn_depths(before), export_depths("before.14"));

  // A shore point moved along its edge, and a breakwater line across the basin's middle.
  const json& ring = before.head["rings"][0];
  const double x0 = ring["xy"][6].get<double>(), y0 = ring["xy"][7].get<double>();
  const double x1 = ring["xy"][8].get<double>(), y1 = ring["xy"][9].get<double>();
  const std::string edits = "move " + ring["ids"][3].dump() + " " + io::format_double(x0 + 0.3 * (x1 - x0)) + " " +
                            io::format_double(y0 + 0.3 * (y1 - y0)) + "\nadd-line 410000 5388500 413000 5388000 414500 5387000\n";
  const auto res = c.Post("/edit", edits, "text/plain");
  ASSERT_TRUE(res && res->status == 200);
  const json out = json::parse(res->body);
  ASSERT_EQ(out["changes"].size(), 2u) << out["replies"];

  Slots page = before;
  for (const auto& change : out["changes"]) {
    const std::size_t slots = change["slots"].get<std::size_t>();
    page.xy.resize(slots, {0, 0, 0, 0, 0, 0});
    page.kinds.resize(slots, {255, 255, 255});
    page.depth.resize(slots, {0, 0, 0});
    for (const auto& s : change["cleared"]) page.kinds[s.get<std::size_t>()] = {255, 255, 255};
    for (const auto& a : change["added"]) {
      const std::size_t s = a[0].get<std::size_t>();
      for (int k = 0; k < 6; ++k) page.xy[s][k] = static_cast<float>(a[1 + k].get<double>());
      for (int k = 0; k < 3; ++k) page.kinds[s][k] = a[7 + k].get<int>();
    }
    for (const auto& d : change["depths"])
      for (int k = 0; k < 3; ++k) page.depth[d[0].get<std::size_t>()][k] = d[1 + k].get<float>();
  }
  const Slots after = get_mesh(c);
  EXPECT_EQ(drawn(page), drawn(after));
  for (std::size_t i = 0; i < after.kinds.size(); ++i)
    if (after.kinds[i][0] != 255) {
      EXPECT_EQ(page.depth[i], after.depth[i]) << "slot " << i;
    }
  EXPECT_EQ(drawn_depths(after), export_depths("after.14"));
  EXPECT_NE(drawn_depths(after), drawn_depths(before));

  // The line's points: in order, the first without a previous point and the last without a next one.
  const json& line = out["changes"][1];
  EXPECT_EQ(out["replies"][1]["role"], "line");
  const json& inputs = line["inputs"];
  ASSERT_EQ(inputs.size(), 3u) << line["inputs"];
  EXPECT_FALSE(inputs[0].contains("prev"));
  EXPECT_EQ(inputs[0]["next"], inputs[1]["id"]);
  EXPECT_EQ(inputs[1]["prev"], inputs[0]["id"]);
  EXPECT_FALSE(inputs[2].contains("next"));
  EXPECT_EQ(inputs[2]["role"], "line");
  const json& head_line = after.head["rings"].back();
  EXPECT_EQ(head_line["role"], "line");
  EXPECT_EQ(head_line["ids"].size(), 3u);
}

// The JSON answers and the page's bundle go uncompressed even to a client that asks for brotli or gzip
// as browsers do: on loopback compression only delays them (cpp-httplib's brotli at quality 11; docs/editor.md, "Connections").
TEST(ServeCommand, JsonAnswersAreNotCompressed) {
  TempDir dir;
  write_file(dir / "lake.txt", "0,0\n100,0\n100,100\n0,100\n0,0\n");
  ServeProcess server(dir, "lake.txt");
  auto c = server.client();
  const httplib::Headers browser = {{"Accept-Encoding", "gzip, deflate, br"}};
  std::string edits;
  for (int k = 0; k < 40; ++k) edits += "move 1 " + std::to_string(90 - k % 2) + " 10\n";  // a long answer
  const auto edit = c.Post("/edit", browser, edits, "text/plain");
  ASSERT_TRUE(edit && edit->status == 200);
  EXPECT_EQ(edit->get_header_value("Content-Encoding"), "");
  EXPECT_GT(edit->body.size(), 4000u);
  EXPECT_EQ(json::parse(edit->body)["version"], 40);
  const auto stats = c.Get("/stats", browser);
  ASSERT_TRUE(stats && stats->status == 200);
  EXPECT_EQ(stats->get_header_value("Content-Encoding"), "");
  EXPECT_EQ(json::parse(stats->body)["version"], 40);
  const auto app = c.Get("/app.js", browser);  // the page's bundle
  ASSERT_TRUE(app && app->status == 200);
  EXPECT_EQ(app->get_header_value("Content-Encoding"), "");
  EXPECT_GT(app->body.size(), 10000u);
}

// The summary (GET /stats) comes from a second session that replays the accepted lines (serve_stats.hpp):
// after random edits, some of them refused, and summaries asked for in between, it equals the served
// session's own `stats` line and a fresh session's that ran the same lines.
TEST(ServeCommand, TheSummaryAfterRandomEditsEqualsTheServedAndAFreshSessions) {
  TempDir dir;
  const std::string read = quote(superior_mask()) + " --largest-water --spacing 8000";
  ServeProcess server(dir, read);
  auto c = server.client();
  // Edits along the lake's shore as it was: a point moved toward its successor, a point added between
  // two, a point removed (a line refused, if any, changes nothing and is not replayed).
  const json shore = get_mesh(c).head["rings"][0];
  const std::size_t n = shore["ids"].size();
  ASSERT_GT(n, 100u);
  auto at = [&](std::size_t k, double t) {
    const double x0 = shore["xy"][2 * k].get<double>(), y0 = shore["xy"][2 * k + 1].get<double>();
    const double x1 = shore["xy"][2 * k + 2].get<double>(), y1 = shore["xy"][2 * k + 3].get<double>();
    return io::format_double(x0 + t * (x1 - x0)) + " " + io::format_double(y0 + t * (y1 - y0));
  };
  std::mt19937 rng(39);
  std::string posted;
  std::size_t accepted = 0, refused = 0;
  for (int round = 0; round < 6; ++round) {
    std::string body;
    for (int k = 0; k < 4; ++k) {
      const std::size_t i = std::uniform_int_distribution<std::size_t>(0, n - 2)(rng);
      const std::string id = shore["ids"][i].dump();
      const int what = std::uniform_int_distribution<int>(0, 9)(rng);
      const double t = std::uniform_real_distribution<double>(0.1, 0.4)(rng);
      if (what < 6) body += "move " + id + " " + at(i, t) + "\n";
      else if (what < 8) body += "add " + at(i, 0.5) + " after " + id + "\n";
      else body += "remove " + id + "\n";
    }
    const auto res = c.Post("/edit?replies=lines", body, "text/plain");
    ASSERT_TRUE(res && res->status == 200);
    for (const auto& r : json_lines(res->body)) ++(r.value("ok", false) ? accepted : refused);
    posted += body;
    if (round % 2 == 1) {  // the summary's session catches up in steps
      const auto mid = c.Get("/stats");
      ASSERT_TRUE(mid && mid->status == 200) << (mid ? mid->body : "");
      EXPECT_EQ(json::parse(mid->body)["version"], accepted);
    }
  }
  EXPECT_GE(accepted, 12u);
  const auto stats = c.Get("/stats");
  ASSERT_TRUE(stats && stats->status == 200);
  json summary = untimed(json::parse(stats->body));
  EXPECT_EQ(summary["version"], accepted);
  EXPECT_GT(summary.value("ring_count", 0), 0);
  EXPECT_EQ(summary["exports"], false);
  for (const char* k : {"version", "ring_count", "exports", "line"}) summary.erase(k);
  EXPECT_TRUE(summary.contains("shore_segments")) << summary;

  const auto own = c.Post("/edit?replies=lines", "stats\n", "text/plain");
  ASSERT_TRUE(own && own->status == 200);
  json served = untimed(json_lines(own->body).at(0));
  served.erase("line");
  EXPECT_EQ(summary, served);

  const RunResult fresh = shoremesh(dir, "edit " + read + " --json --edits -", posted + "stats\n");
  const auto fresh_replies = json_lines(fresh.out);  // exits 1 when a line was refused
  ASSERT_EQ(fresh_replies.size(), 2 + accepted + refused) << fresh.err;
  json expected = untimed(fresh_replies.back());
  EXPECT_EQ(expected["op"], "stats");
  expected.erase("line");
  EXPECT_EQ(summary, expected);
}

// An edit is not held up by a summary: edits posted while GET /stats is under way are answered before
// it, and they are edits after the version that summary reports. With the summary under the edit lock
// no such edit can exist (an edit answered before the summary's answer ran before it, so the summary's
// version counts it). An ordering, not a time: the summary's session has 200 edits to replay first.
TEST(ServeCommand, EditsGoOnWhileASummaryIsComputed) {
  TempDir dir;
  const std::string read = quote(superior_mask()) + " --largest-water --spacing 8000";
  const RunResult start = shoremesh(dir, "mesh -q " + read + " -o start.csv");
  ASSERT_EQ(start.code, 0) << start.err;
  const auto all = io::read_point_set_csv<2>(dir / "start.csv");
  auto move = [&](std::size_t id, double t) {
    const Point2 &a = all.points[id], &b = all.points[id + 1];
    return "move " + std::to_string(id) + " " + io::format_double(a[0] + t * (b[0] - a[0])) + " " +
           io::format_double(a[1] + t * (b[1] - a[1])) + "\n";
  };
  ServeProcess server(dir, read);
  auto c = server.client();
  const auto first = c.Get("/stats");  // the summary's session is built
  ASSERT_TRUE(first && first->status == 200);
  std::string body;
  for (int k = 0; k < 200; ++k) body += move(40, k % 2 ? 0.3 : 0.25);
  const auto pre = c.Post("/edit", body, "text/plain");
  ASSERT_TRUE(pre && pre->status == 200);
  ASSERT_EQ(json::parse(pre->body)["version"], 200);

  std::atomic<bool> answered{false};
  json summary;
  std::thread asker([&] {
    auto s = server.client();
    const auto res = s.Get("/stats");
    if (res && res->status == 200) summary = json::parse(res->body);
    answered = true;
  });
  std::vector<std::uint64_t> before_answer;  // the versions of the edits answered before the summary's answer
  for (int k = 0; k < 2000 && !answered; ++k) {
    const auto res = c.Post("/edit", move(60, k % 2 ? 0.3 : 0.25), "text/plain");
    ASSERT_TRUE(res && res->status == 200);
    const json out = json::parse(res->body);
    ASSERT_TRUE(out["replies"][0]["ok"].get<bool>()) << out;
    if (!answered) before_answer.push_back(out["version"].get<std::uint64_t>());
  }
  asker.join();
  ASSERT_TRUE(summary.contains("version")) << "GET /stats failed";
  const auto version = summary["version"].get<std::uint64_t>();
  EXPECT_GE(version, 200u);
  const auto after = std::count_if(before_answer.begin(), before_answer.end(), [&](auto v) { return v > version; });
  EXPECT_GE(after, 3) << before_answer.size() << " edits answered before the summary (version " << version << ")";
}

}  // namespace
}  // namespace shoremesh::cli_test
