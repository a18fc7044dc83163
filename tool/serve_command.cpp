// shoremesh serve INPUT...: one edit session behind a local HTTP server (cpp-httplib), and the browser
// editor (web/, bundled at build time and embedded in the binary) on it. POST /edit runs edit lines through
// the same EditSession as `shoremesh edit --json`; the server also keeps the mesh's triangles in stable
// slots so that a page redraws only the slots an edit changed (docs/editor.md).
#include <httplib.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <unordered_map>
#include <unordered_set>
#include <variant>
#include <vector>

#include "commands.hpp"
#include "edit_session.hpp"
#include "input_args.hpp"
#include "pipeline.hpp"
#include "progress.hpp"
#include "serve_stats.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/export.hpp"

namespace shoremesh::tool {

// web_assets.cpp: the page's files, embedded at build time.
std::string_view web_index_html();
std::string_view web_app_js();

namespace {

using json = nlohmann::json;

struct ServeOptions {
  InputArgs in;
  EngineArgs engine;
  PreviewArgs preview;
  int port = 0;
  std::string host = "127.0.0.1";
  std::string export_dir;
  std::string log, resume;  // the accepted edit lines, appended as they are accepted
  std::size_t max_body = std::size_t(1) << 20;
};

std::size_t hash_point(const Point2& p) {
  std::uint64_t a, b;
  std::memcpy(&a, &p[0], 8);
  std::memcpy(&b, &p[1], 8);
  return std::hash<std::uint64_t>{}(a * 0x9E3779B97F4A7C15ull ^ (b + 0x7F4A7C159E3779B9ull + (a << 6) + (a >> 2)));
}
struct PointHash {
  std::size_t operator()(const Point2& p) const noexcept { return hash_point(p); }
};
struct CornersHash {
  std::size_t operator()(const ElementCorners<2>& c) const noexcept {
    std::size_t h = 0;
    for (const auto& p : c) h = h * 1000003u ^ hash_point(p);
    return h;
  }
};

// How the page draws a mesh point.
enum DrawKind : std::uint8_t { kSteiner = 0, kSplit = 1, kShore = 2, kLoose = 3 };

// The page's view of the mesh: each triangle in a slot that stays put until the triangle goes (a mesh
// update renumbers the mesh's points, so indices cannot name triangles across edits; corners can), and
// the input points by id with their ring neighbours. Updated from each edit's delta in O(change).
class DrawState {
 public:
  // `frame`: where depths come from (--dem, --depth-from, soundings); without a depth source none are drawn.
  explicit DrawState(const UserFrame& frame) : frame_(frame) {}

  void reset(const ShoreSession<2>& s) {
    slot_of_.clear();
    free_.clear();
    slot_count_ = 0;
    point_of_id_.assign(s.next_id(), std::nullopt);
    id_of_.clear();
    for (std::size_t id = 0; id < s.next_id(); ++id)
      if (s.contains(id)) set_id(id, s.input_point(id));
    reset_steiner(s.mesh());
    // Slots numbered along a Z-order curve of the triangles' centroids: consecutive slots are near each
    // other, so the page can skip whole runs of slots outside its view (ties: by corners).
    const auto& points = s.mesh().points();
    const BoxTransform<2>& box = s.box();
    std::vector<std::pair<std::uint64_t, ElementCorners<2>>> order;
    for (const auto& e : s.mesh().elements()) {
      ElementCorners<2> c{points[e[0]], points[e[1]], points[e[2]]};
      std::sort(c.begin(), c.end());
      std::uint64_t code = 0;
      for (int axis = 0; axis < 2; ++axis) {
        const double t = ((c[0][axis] + c[1][axis] + c[2][axis]) / 3 - box.origin[axis]) / box.side;
        const auto cell = static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * 65535.0);
        for (int bit = 0; bit < 16; ++bit) code |= ((cell >> bit) & 1u) << (2 * bit + axis);
      }
      order.emplace_back(code, c);
    }
    std::sort(order.begin(), order.end());
    for (const auto& [code, c] : order) slot_of_.emplace(c, slot_count_++);
    if (has_depths()) {
      depth_.assign(std::size_t(slot_count_) * 3, 0.0f);
      update_depths(s, {});
    }
  }

  bool has_depths() const { return frame_.depth != nullptr; }

  // The change of one accepted edit that touched the input points `ids`, as the page applies it.
  json apply(const ShoreSession<2>& s, const SessionEdit<2>& edit, const std::vector<std::size_t>& ids) {
    point_of_id_.resize(s.next_id());
    for (std::size_t id : ids) {
      if (point_of_id_[id]) id_of_.erase(*point_of_id_[id]);
      point_of_id_[id].reset();
      if (s.contains(id)) set_id(id, s.input_point(id));
    }
    if (edit.rebuilt) {
      reset_steiner(s.mesh());
    } else {
      for (const auto& p : edit.engine.steiner_removed) steiner_.erase(p);
      for (const auto& p : edit.engine.steiner_added) steiner_.insert(p);
    }
    json cleared = json::array(), added = json::array(), inputs = json::array();
    for (const auto& c : edit.mesh.removed) {
      const auto it = slot_of_.find(c);
      if (it == slot_of_.end()) throw std::logic_error("serve: a removed triangle has no slot");
      cleared.push_back(it->second);
      free_.push_back(it->second);
      slot_of_.erase(it);
    }
    const Point2 o = s.box().origin;
    std::unordered_set<std::uint32_t> added_slots;
    for (const auto& c : edit.mesh.added) {
      std::uint32_t slot = slot_count_;
      if (free_.empty()) ++slot_count_;
      else slot = free_.back(), free_.pop_back();
      slot_of_.emplace(c, slot);
      added_slots.insert(slot);
      added.push_back({slot, c[0][0] - o[0], c[0][1] - o[1], c[1][0] - o[0], c[1][1] - o[1], c[2][0] - o[0],
                       c[2][1] - o[1], kind(s, c[0]), kind(s, c[1]), kind(s, c[2])});
    }
    for (std::size_t id : ids) inputs.push_back(input_json(s, id));
    json change = {{"cleared", cleared}, {"added", added}, {"inputs", inputs}, {"slots", slot_count_},
                   {"triangles", s.mesh().element_count()}};
    if (has_depths()) {
      depth_.resize(std::size_t(slot_count_) * 3, 0.0f);
      change["depths"] = update_depths(s, added_slots);
    }
    return change;
  }

  // The whole view: "SMSH", a little-endian u32 length, that much JSON (rings, loose points, counts),
  // spaces to a multiple of 4, then float32 x y of each slot's 3 corners (relative to the box's origin;
  // an empty slot is all zeros) and a u8 kind per corner (255: empty slot).
  std::string binary(const ShoreSession<2>& s, const json& extra) const {
    const Point2 o = s.box().origin;
    json head = extra;
    head["origin"] = {o[0], o[1]};
    head["side"] = s.box().side;
    head["slots"] = slot_count_;
    head["triangles"] = s.mesh().element_count();
    head["depths"] = has_depths();
    json rings = json::array();
    for (std::size_t r = 0; r < s.ring_count(); ++r) {
      if (s.ring(r).empty()) continue;  // removed
      json ids = json::array(), xy = json::array();
      for (const Point2& p : s.ring(r)) {
        ids.push_back(id_of_.at(p));
        xy.push_back(p[0]);
        xy.push_back(p[1]);
      }
      rings.push_back({{"ring", r}, {"role", role_name(s, r)}, {"ids", ids}, {"xy", xy}});
    }
    head["rings"] = rings;
    json loose_ids = json::array(), loose_xy = json::array();
    for (std::size_t id = 0; id < point_of_id_.size(); ++id)
      if (point_of_id_[id] && !s.ring_of(id)) {
        loose_ids.push_back(id);
        loose_xy.push_back((*point_of_id_[id])[0]);
        loose_xy.push_back((*point_of_id_[id])[1]);
      }
    head["loose"] = {{"ids", loose_ids}, {"xy", loose_xy}};
    std::string text = head.dump();
    text.append((4 - text.size() % 4) % 4, ' ');
    std::string out = "SMSH";
    const std::uint32_t length = static_cast<std::uint32_t>(text.size());
    out.append(reinterpret_cast<const char*>(&length), 4);
    out += text;
    std::vector<float> xy(std::size_t(slot_count_) * 6, 0.0f);
    std::vector<std::uint8_t> kinds(std::size_t(slot_count_) * 3, 255);
    for (const auto& [c, slot] : slot_of_)
      for (int k = 0; k < 3; ++k) {
        xy[slot * 6 + k * 2] = static_cast<float>(c[k][0] - o[0]);
        xy[slot * 6 + k * 2 + 1] = static_cast<float>(c[k][1] - o[1]);
        kinds[slot * 3 + k] = kind(s, c[k]);
      }
    out.append(reinterpret_cast<const char*>(xy.data()), xy.size() * sizeof(float));
    out.append(reinterpret_cast<const char*>(kinds.data()), kinds.size());
    if (has_depths()) {  // then float32 depths per corner (positive down), from the next multiple of 4
      out.append((4 - out.size() % 4) % 4, '\0');
      out.append(reinterpret_cast<const char*>(depth_.data()), depth_.size() * sizeof(float));
    }
    return out;
  }

 private:
  void set_id(std::size_t id, const Point2& p) {
    point_of_id_[id] = p;
    id_of_[p] = id;
  }
  static std::string role_name(const ShoreSession<2>& s, std::size_t r) {
    const RingRole role = s.ring_role(r);
    return role == RingRole::Island ? "island" : role == RingRole::Line ? "line" : "shore";
  }

  // The corners' depths as an export gives them (the same nodes, numbered the same: Lemma 7.2 makes them
  // a fresh run's). A node's depth depends on its neighbours (the DEM cells nearest to it), so an edit
  // changes depths beyond its triangles: every slot is compared, and those whose depths changed (besides
  // the `added` ones, whose depths are new) are sent as [slot, d0, d1, d2]. O(mesh) per edit, like the
  // depths themselves, and only for sessions with depths.
  json update_depths(const ShoreSession<2>& s, const std::unordered_set<std::uint32_t>& added) {
    const auto order = s.canonical_points();
    const io::MeshSnapshot<2> snapshot(s.mesh(), order);
    const io::MeshView<2> view = snapshot.view();
    const std::vector<double> depths = mesh_depths(view, frame_);
    std::unordered_map<Point2, float, PointHash> depth_at;
    depth_at.reserve(depths.size());
    for (std::size_t i = 0; i < depths.size(); ++i) depth_at.emplace(view.points[i], static_cast<float>(depths[i]));
    json changed = json::array();
    for (const auto& [c, slot] : slot_of_) {
      bool differs = added.contains(slot);
      std::array<float, 3> d;
      for (int k = 0; k < 3; ++k) {
        d[k] = depth_at.at(c[k]);
        differs = differs || d[k] != depth_[slot * 3 + k];
        depth_[slot * 3 + k] = d[k];
      }
      if (differs) changed.push_back({slot, d[0], d[1], d[2]});
    }
    return changed;
  }

  void reset_steiner(const Mesh<2>& mesh) {
    steiner_.clear();
    for (std::size_t i = 0; i < mesh.points().size(); ++i)
      if (mesh.kinds()[i] == PointKind::Steiner) steiner_.insert(mesh.points()[i]);
  }
  std::uint8_t kind(const ShoreSession<2>& s, const Point2& p) const {
    if (steiner_.contains(p)) return kSteiner;
    const auto it = id_of_.find(p);
    if (it == id_of_.end()) return kSplit;  // an engine input point that no id names: a shore split
    return s.ring_of(it->second) ? kShore : kLoose;
  }
  // An input point as the page keeps it: where it is and its ring neighbours, or that it is gone.
  json input_json(const ShoreSession<2>& s, std::size_t id) const {
    if (!s.contains(id)) return {{"id", id}, {"gone", true}};
    const Point2 p = s.input_point(id);
    json j = {{"id", id}, {"x", p[0]}, {"y", p[1]}};
    if (const auto at = s.ring_of(id)) {
      const auto& ring = s.ring(at->first);
      const bool open = s.ring_role(at->first) == RingRole::Line;
      j["ring"] = at->first;
      j["role"] = role_name(s, at->first);
      if (!open || at->second > 0) j["prev"] = id_of_.at(ring[(at->second + ring.size() - 1) % ring.size()]);
      if (!open || at->second + 1 < ring.size()) j["next"] = id_of_.at(ring[(at->second + 1) % ring.size()]);
    }
    return j;
  }

  std::unordered_map<ElementCorners<2>, std::uint32_t, CornersHash> slot_of_;
  std::vector<std::uint32_t> free_;
  std::uint32_t slot_count_ = 0;
  std::vector<std::optional<Point2>> point_of_id_;
  std::unordered_map<Point2, std::size_t, PointHash> id_of_;
  std::unordered_set<Point2, PointHash> steiner_;
  const UserFrame& frame_;
  std::vector<float> depth_;  // per slot corner, when the session has depths
};

// Server-sent events: each accepted edit's change goes to every open /events stream. A stream that
// falls more than kKept messages behind is told to reload the whole mesh.
class Events {
 public:
  static constexpr std::size_t kKept = 256;

  void publish(const std::string& event, const json& data) {
    {
      std::lock_guard lock(mutex_);
      log_.push_back({++last_, "event: " + event + "\ndata: " + data.dump() + "\n\n"});
      if (log_.size() > kKept) log_.pop_front();
    }
    cv_.notify_all();
  }
  std::uint64_t last() {
    std::lock_guard lock(mutex_);
    return last_;
  }
  // The next message after `seen` (waiting up to `wait`): false when none came (or the server stops).
  bool next(std::uint64_t& seen, std::string& out, std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    cv_.wait_for(lock, wait, [&] { return closed_ || last_ > seen; });
    if (closed_ || last_ <= seen) return false;
    if (log_.empty() || log_.front().first > seen + 1) {
      out = "event: reload\ndata: {}\n\n";
      seen = last_;
      return true;
    }
    out = log_[seen + 1 - log_.front().first].second;
    ++seen;
    return true;
  }
  void close() {
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
    }
    cv_.notify_all();
  }
  bool closed() {
    std::lock_guard lock(mutex_);
    return closed_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::pair<std::uint64_t, std::string>> log_;
  std::uint64_t last_ = 0;
  bool closed_ = false;
};

std::vector<std::string> words_of(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

std::string trimmed_rest(const std::string& text, const std::string& op) {
  const std::size_t at = text.find(op);
  std::string rest = text.substr(at + op.size());
  const std::size_t a = rest.find_first_not_of(" \t");
  const std::size_t b = rest.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : rest.substr(a, b - a + 1);
}

// Why `name` is not a plain file name for --export-dir, or empty when it is.
std::string bad_export_name(const std::string& name) {
  if (name.empty()) return "a file NAME";
  if (name == "." || name == ".." || name[0] == '.') return "a file name not starting with '.'";
  for (unsigned char ch : name)
    if (ch == '/' || ch == '\\' || ch < 0x20 || ch == 0x7f) return "a file name without path separators or control characters";
  return {};
}

bool is_edit_op(const std::string& op) {
  return op == "add" || op == "remove" || op == "move" || op == "add-ring" || op == "add-line" || op == "remove-ring";
}

class EditServer {
 public:
  EditServer(EditSession<2>& session, StatsReplica& summary, std::filesystem::path export_dir, std::ofstream* log)
      : session_(session), summary_(summary), draw_(session.frame()), export_dir_(std::move(export_dir)), log_(log) {
    draw_.reset(session_.session());
  }

  // Runs the edit lines of one request (1-based line numbers, like `edit --edits FILE`). `lock_ms`: how
  // long it waited for the session (for the Server-Timing header).
  json run(const std::string& body, double* lock_ms = nullptr) {
    const auto asked = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    if (lock_ms) *lock_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - asked).count();
    json replies = json::array(), changes = json::array();
    std::istringstream in(body);
    std::size_t line_no = 0;
    for (std::string line; std::getline(in, line);) {
      ++line_no;
      const auto checked = check_line(line);
      std::optional<json> reply;
      if (const auto* error = std::get_if<json>(&checked)) {
        reply = *error;
        (*reply)["line"] = line_no;
      } else {
        reply = session_.run(line_no, std::get<std::string>(checked));
      }
      if (!reply) continue;
      if (reply->value("ok", false) && is_edit_op(reply->value("op", ""))) {
        std::vector<std::size_t> ids;
        if (reply->contains("ids")) ids = (*reply)["ids"].get<std::vector<std::size_t>>();
        if (reply->contains("id") && !reply->contains("ids")) ids.push_back((*reply)["id"].get<std::size_t>());
        if (log_) *log_ << line << std::endl;  // flushed: a killed server resumes from it
        summary_.accepted(line);
        json change = draw_.apply(session_.session(), session_.last_edit(), ids);
        change["version"] = ++version_;
        change["reply"] = *reply;
        events_.publish("change", change);
        changes.push_back(std::move(change));
      }
      replies.push_back(std::move(*reply));
    }
    return {{"version", version_}, {"replies", replies}, {"changes", changes}};
  }

  std::string mesh_binary() {
    std::lock_guard lock(mutex_);
    return draw_.binary(session_.session(), {{"version", version_}, {"units", session_.build_reply(0)["units"]}});
  }

  // GET /stats: from the summary's own session, never under the edit lock (serve_stats.hpp).
  json stats() {
    std::uint64_t version = 0;
    json r = summary_.stats(version);
    r["version"] = version;
    r["exports"] = !export_dir_.empty();
    return r;
  }

  Events& events() { return events_; }

 private:
  // A line as the session runs it, or the error reply of a line that HTTP may not run: paths are file
  // names inside --export-dir, and no line reads a file on the server.
  std::variant<std::string, json> check_line(const std::string& line) const {
    const auto words = words_of(line);
    if (words.empty()) return line;
    const std::string& op = words[0];
    auto refuse = [&](const std::string& why) { return json{{"ok", false}, {"op", op}, {"error", why}}; };
    if (op == "export" || op == "preview" || op == "preview-change") {
      if (export_dir_.empty())
        return refuse(op + " over HTTP writes into --export-dir; this server was started without one");
      const std::string name = trimmed_rest(line, op);
      if (const std::string why = bad_export_name(name); !why.empty())
        return refuse(op + " over HTTP takes " + why + " (it writes into --export-dir), not '" + name + "'");
      return op + " " + (export_dir_ / name).string();
    }
    if (op == "add-ring" && words.size() >= 2) {
      const unsigned char c = static_cast<unsigned char>(words[1][0]);
      if (words.size() == 2 || !(std::isdigit(c) || c == '-' || c == '+' || c == '.'))
        return refuse("add-ring FILE reads a file on the server; over HTTP give the ring: add-ring X1 Y1 X2 Y2 X3 Y3 ...");
    }
    return line;
  }

  std::mutex mutex_;  // one edit (or read of the session) at a time
  EditSession<2>& session_;
  StatsReplica& summary_;
  DrawState draw_;
  std::uint64_t version_ = 0;
  std::filesystem::path export_dir_;
  std::ofstream* log_;
  Events events_;
};

// --resume LOG: its edit lines again, in order (ids are never reused, so the same lines give the same ids
// and, Lemma 7.2, the same state as the killed server's); each must be accepted again. Returns them.
std::vector<std::string> replay(EditSession<2>& session, const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read the edit log to resume", path);
  std::size_t line_no = 0;
  std::vector<std::string> edits;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto words = words_of(line);
    if (!words.empty() && words[0][0] != '#' && !is_edit_op(words[0]))
      throw InputError("line " + std::to_string(line_no) + " of the edit log is not an edit (" + words[0] +
                           "): a log holds add, remove, move, add-ring, add-line and remove-ring lines", path);
    const auto reply = session.run(line_no, line);
    if (!reply) continue;
    if (!reply->value("ok", false))
      throw InputError("line " + std::to_string(line_no) + " of the edit log is refused now: " +
                           reply->value("error", "") + " (was it written for these inputs and options?)",
                       path);
    edits.push_back(line);
  }
  std::cout << "resumed " << edits.size() << " edit(s) from " << path << '\n';
  return edits;
}

// SHOREMESH_SERVE_TRACE=FILE: a line per edit answer and per change event when its last byte was handed
// to the socket (ms since the server started, steady clock), to tell a late answer's time on the server
// from its time in the browser (docs/editor.md, "Connections"). Off by default.
class Trace {
 public:
  Trace() {
    if (const char* path = std::getenv("SHOREMESH_SERVE_TRACE"); path && *path) {
      out_.open(path, std::ios::app);
      if (!out_) throw InputError("cannot write SHOREMESH_SERVE_TRACE", path);
    }
  }
  bool on() const { return out_.is_open(); }
  double now() const { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count(); }
  void line(const std::string& what) {
    std::lock_guard lock(mutex_);
    out_ << what << std::endl;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::mutex mutex_;
  std::ofstream out_;
};

// The version a change event's text carries ("version":N), or -1.
long long event_version(const std::string& text) {
  const auto at = text.find("\"version\":");
  return at == std::string::npos ? -1 : std::atoll(text.c_str() + at + 10);
}

// The JSON answers' type. With a charset it is not one that cpp-httplib compresses: a browser asks for
// brotli, which cpp-httplib runs at quality 11, and an edit's answer of a few kB then reached the socket
// ~100 ms after the edit on the loaded VM (SHOREMESH_SERVE_TRACE), after the change event with the same
// edit; on loopback compression only costs.
constexpr const char* kJson = "application/json; charset=utf-8";

bool is_loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

void json_error(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(json{{"error", message}}.dump(), kJson);
}

int run_serve(const ServeOptions& opt) {
  if (opt.port < 0 || opt.port > 65535) throw ParameterError("--port must be 0..65535 (0: a free port)");
  if (opt.engine.dim == 3) throw ParameterError("serve draws 2D meshes; --dim 3 is for mesh and edit");
  std::filesystem::path export_dir;
  if (!opt.export_dir.empty()) {
    export_dir = std::filesystem::absolute(opt.export_dir);
    if (!std::filesystem::is_directory(export_dir)) throw InputError("--export-dir is not a folder", opt.export_dir);
  }
  Progress progress(!opt.in.quiet && Progress::stderr_is_terminal(), opt.in.files.size() + 1);
  const io::InputSet set = read_user_inputs(opt.in, progress);
  if (set.dimension == 3 && opt.engine.dim != 2)
    throw InputError("serve draws 2D meshes; this input is 3D (--dim 2 reads x, y and drops z)");
  progress.stage("StableWS and mesh of " + std::to_string(set.size()) + " points");
  const auto start = std::chrono::steady_clock::now();
  EditSession<2> session(set, opt.engine.rho, parse_box<2>(opt.engine.box), opt.engine.keep_hull, opt.preview);
  session.set_inputs(input_paths(opt.in, set));  // exports never replace an input
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  progress.finish();
  std::cout << reply_text(session.build_reply(ms)) << '\n';
  if (!opt.log.empty() && !opt.resume.empty()) throw ParameterError("--log and --resume: give one (--resume keeps logging)");
  std::ofstream log;
  std::vector<std::string> resumed;
  if (!opt.resume.empty()) {
    resumed = replay(session, opt.resume);
    log.open(opt.resume, std::ios::app);
  } else if (!opt.log.empty()) {
    if (std::filesystem::exists(opt.log)) throw InputError("the edit log exists: --resume it, or remove it", opt.log);
    log.open(opt.log);
  }
  const std::string log_path = opt.resume.empty() ? opt.log : opt.resume;
  if (!log_path.empty() && !log) throw InputError("cannot write the edit log", log_path);
  // The summary's session, built meanwhile (stopping waits for it).
  StatsReplica summary(
      [&] {
        return std::make_unique<EditSession<2>>(set, opt.engine.rho, parse_box<2>(opt.engine.box), opt.engine.keep_hull,
                                                opt.preview);
      },
      std::move(resumed));
  EditServer editor(session, summary, export_dir, log_path.empty() ? nullptr : &log);

  // SIGINT and SIGTERM stop the server from a thread of their own (the handlers' threads inherit the mask).
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  httplib::Server http;
  http.set_payload_max_length(opt.max_body);
  http.set_tcp_nodelay(true);  // an edit's answer is small: without it, Nagle and delayed ACKs add ~40 ms
  // A page posts a move every few frames while dragging: cpp-httplib's default closes a connection after 5
  // requests, so every fifth move waited for a new connection. A connection (and the event stream) holds one
  // of the pool's threads while open (5 s idle at most): room for a page's 6 and the event stream, twice.
  http.set_keep_alive_max_count(100000);
  http.new_task_queue = [] { return new httplib::ThreadPool(16); };
  Trace trace;
  if (trace.on())
    http.set_logger([&trace](const httplib::Request& req, const httplib::Response& res) {
      if (req.path == "/edit")
        trace.line("answer " + res.get_header_value("X-Shoremesh-Version") + " written " + std::to_string(trace.now()) +
                   " handled " + res.get_header_value("X-Shoremesh-Handled"));
    });
  http.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(web_index_html()), "text/html; charset=utf-8");
  });
  http.Get("/app.js", [](const httplib::Request&, httplib::Response& res) {
    // Not a type cpp-httplib compresses (kJson): brotli at quality 11 took 1.8 s for the 543 kB bundle.
    res.set_content(std::string(web_app_js()), "application/javascript; charset=utf-8");
  });
  http.Get("/mesh", [&](const httplib::Request&, httplib::Response& res) {
    res.set_content(editor.mesh_binary(), "application/octet-stream");
  });
  http.Get("/stats", [&](const httplib::Request&, httplib::Response& res) {
    res.set_content(editor.stats().dump(), kJson);
  });
  http.Post("/edit", [&](const httplib::Request& req, httplib::Response& res) {
    if (words_of(req.body).empty())
      return json_error(res, 400, "POST /edit takes edit lines in the body (as 'shoremesh edit --edits' reads them)");
    using Ms = std::chrono::duration<double, std::milli>;
    const auto received = std::chrono::steady_clock::now();
    double lock_ms = 0;
    const json out = editor.run(req.body, &lock_ms);
    const auto ran = std::chrono::steady_clock::now();
    if (req.get_param_value("replies") == "lines") {
      std::string text;  // exactly what `shoremesh edit --json` prints for these lines
      for (const auto& r : out["replies"]) text += r.dump() + "\n";
      res.set_content(text, "application/x-ndjson");
    } else {
      res.set_content(out.dump(), kJson);
    }
    // Where the request's time went on the server, for the page's profile (Resource Timing's serverTiming).
    const auto done = std::chrono::steady_clock::now();
    std::ostringstream timing;
    timing << "lock;dur=" << lock_ms << ", edit;dur=" << Ms(ran - received).count() - lock_ms
           << ", json;dur=" << Ms(done - ran).count() << ", total;dur=" << Ms(done - received).count();
    res.set_header("Server-Timing", timing.str());
    if (trace.on()) {
      res.set_header("X-Shoremesh-Version", std::to_string(out["version"].get<std::uint64_t>()));
      res.set_header("X-Shoremesh-Handled", std::to_string(trace.now()));
    }
  });
  http.Get("/events", [&](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
    const std::uint64_t from = editor.events().last();
    res.set_chunked_content_provider("text/event-stream", [&editor, &trace, seen = from, first = true](std::size_t, httplib::DataSink& sink) mutable {
      std::string out;
      if (first) {
        out = "event: hello\ndata: {}\n\n";
        first = false;
      } else if (!editor.events().next(seen, out, std::chrono::seconds(10))) {
        if (editor.events().closed()) return false;
        out = ": keep-alive\n\n";  // finds streams whose page went away
      }
      const bool written = sink.write(out.data(), out.size());
      if (trace.on() && out.rfind("event: change", 0) == 0)
        trace.line("event " + std::to_string(event_version(out)) + " written " + std::to_string(trace.now()));
      return written;
    });
  });
  http.set_error_handler([&](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    if (res.status == 413)
      return json_error(res, 413, "request body over " + std::to_string(opt.max_body) + " bytes");
    if (res.status == 404)
      return json_error(res, 404, "no endpoint " + req.method + " " + req.path +
                                      " (GET /, /mesh, /stats, /events; POST /edit)");
    json_error(res, res.status, "HTTP error " + std::to_string(res.status));
  });
  http.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
    try {
      std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      json_error(res, 500, std::string("internal error: ") + e.what());
    } catch (...) {
      json_error(res, 500, "internal error");
    }
  });

  int port = opt.port;
  if (port == 0) port = http.bind_to_any_port(opt.host);
  else if (!http.bind_to_port(opt.host, port)) port = -1;
  if (port <= 0)
    throw InputError("cannot listen on " + opt.host + ":" + std::to_string(opt.port) + " (in use, or not this machine's)");
  if (!is_loopback(opt.host))
    std::cerr << "shoremesh: warning: serving on " << opt.host
              << ", not loopback: anyone who can reach this address can edit the session and write exports\n";
  const std::string host = opt.host.find(':') != std::string::npos ? "[" + opt.host + "]" : opt.host;
  std::cout << "serving http://" << host << ":" << port << "/ (Ctrl-C stops)" << std::endl;

  std::thread stopper([&] {
    int signal = 0;
    sigwait(&stop_signals, &signal);
    editor.events().close();
    http.stop();
  });
  const bool ok = http.listen_after_bind();
  editor.events().close();
  if (stopper.joinable()) {
    pthread_kill(stopper.native_handle(), SIGTERM);  // ends its sigwait when listen ended on its own
    stopper.join();
  }
  return ok ? kExitOk : kExitInternal;
}

}  // namespace

Command add_serve_command(CLI::App& app) {
  auto opt = std::make_shared<ServeOptions>();
  CLI::App* cmd = app.add_subcommand("serve", "Serve a browser editor on one edit session: drag shore points, watch the mesh update");
  add_input_options(cmd, opt->in);
  add_engine_options(cmd, opt->engine);
  add_preview_options(cmd, opt->preview);
  cmd->add_option("--port", opt->port, "TCP port (default 0: a free one, printed)");
  cmd->add_option("--host", opt->host, "Address to listen on (default 127.0.0.1; others are warned about)");
  cmd->add_option("--export-dir", opt->export_dir,
                  "Folder that export, preview and preview-change lines write into (they take file names only)");
  cmd->add_option("--log", opt->log, "Append every accepted edit line to LOG (a new file), for --resume");
  cmd->add_option("--resume", opt->resume,
                  "Replay the edit log LOG (of a server on the same inputs and options), then keep appending to it");
  cmd->add_option("--max-body", opt->max_body, "Largest request body in bytes (default 1 MiB)");
  cmd->footer(
      "Endpoints: GET / (the editor), GET /mesh (the triangles in slots, binary), GET /stats,\n"
      "GET /events (server-sent events: each edit's change), POST /edit (edit lines as 'shoremesh edit' reads\n"
      "them; the JSON replies of 'edit --json' and the changed triangles; ?replies=lines: only the replies,\n"
      "one a line, exactly as 'edit --json' prints them).\n"
      "\n"
      "Example:\n"
      "  shoremesh serve samples/superior/superior_watermask_h.png --largest-water --spacing 4000 --export-dir out\n"
      "  curl -s --data-binary 'move 600 654323.446 5180688.135' 'http://127.0.0.1:PORT/edit?replies=lines'");
  return [opt]() { return run_serve(*opt); };
}

}  // namespace shoremesh::tool
