#include "edit_session.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <sstream>

#include "shoremesh/error.hpp"
#include "shoremesh/io/point_set_csv.hpp"
#include "shoremesh/ring_edge_index.hpp"
#include "shoremesh/io/ring_file.hpp"

namespace shoremesh::tool {

namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double parse_number(const std::string& word) {
  double v = 0;
  const char* first = word.data();
  if (!word.empty() && word[0] == '+') ++first;
  const auto [end, ec] = std::from_chars(first, word.data() + word.size(), v);
  if (ec != std::errc{} || end != word.data() + word.size() || first == word.data() + word.size())
    throw InputError("'" + word + "' is not a number");
  if (!std::isfinite(v)) throw InputError("'" + word + "' is not a finite number");
  return v;
}

template <int D>
typename ShoreSession<D>::Options session_options(double rho, std::optional<BoxTransform<D>> box, bool keep_hull,
                                                  std::optional<SizeTerms> size) {
  typename ShoreSession<D>::Options o;
  o.size = std::move(size);
  o.rho = rho;
  o.box = box;
  o.keep_hull = keep_hull;
  return o;
}

}  // namespace

std::vector<std::string> split_words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// The text after the first word, trimmed: a path may contain blanks.
std::string rest_after_op(const std::string& text) {
  const std::size_t start = text.find_first_not_of(" \t");
  const std::size_t op_end = text.find_first_of(" \t", start);
  if (op_end == std::string::npos) return {};
  const std::size_t a = text.find_first_not_of(" \t", op_end);
  if (a == std::string::npos) return {};
  const std::size_t b = text.find_last_not_of(" \t\r");
  return text.substr(a, b - a + 1);
}

template <int D>
EditSession<D>::EditSession(const io::InputSet& set, double rho, std::optional<BoxTransform<D>> box, bool keep_hull,
                            PreviewArgs preview, bool lonlat_edits, std::optional<SizeTerms> size)
    : frame_(UserFrame::of(set)),
      lonlat_edits_(lonlat_edits),
      preview_(std::move(preview)),
      session_([&] {
        try {
          return ShoreSession<D>(session_input<D>(set), session_options<D>(rho, box, keep_hull, std::move(size)));
        } catch (const PointInputError& e) {
          rethrow_with_origin(e, set);
        }
      }()) {
  preview_.rho = rho;
}

template <int D>
json EditSession<D>::build_reply(double ms) const {
  json r = {{"line", 0}, {"ok", true}, {"op", "build"}};
  r["input_points"] = session_.input_count();
  r["shore_splits"] = session_.split_count();
  r["size_seeds"] = session_.seed_count();
  r["steiner_points"] = session_.steiner_count();
  r["elements"] = session_.mesh().element_count();
  std::vector<double> box(session_.box().origin.begin(), session_.box().origin.end());
  box.push_back(session_.box().side);
  r["box"] = box;
  r["units"] = io::to_string(frame_.units);
  if (!frame_.projection.is_none()) r["projection"] = frame_.projection.describe();
  r["ms"] = ms;
  return r;
}

template <int D>
std::optional<json> EditSession<D>::run(std::size_t line, const std::string& text) {
  const std::vector<std::string> words = split_words(text);
  if (words.empty() || words[0][0] == '#') return std::nullopt;
  const std::string& op = words[0];
  json reply;
  try {
    if (op == "add") reply = add(words);
    else if (op == "remove") reply = remove(words);
    else if (op == "move") reply = move(words);
    else if (op == "add-ring" || op == "add-line") reply = add_ring(words, rest_after_op(text));
    else if (op == "remove-ring") reply = remove_ring(words);
    else if (op == "size") reply = set_size(words);
    else if (op == "export") reply = export_to({op, rest_after_op(text)});
    else if (op == "preview") reply = preview({op, rest_after_op(text)});
    else if (op == "preview-change") reply = preview_change({op, rest_after_op(text)});
    else if (op == "stats") {
      if (words.size() != 1) throw InputError("stats takes no arguments");
      reply = stats();
    } else {
      throw InputError("unknown edit '" + op +
                       "' (add, remove, move, add-ring, add-line, remove-ring, size, export, preview, preview-change, stats)");
    }
  } catch (const InputError& e) {
    return json{{"line", line}, {"ok", false}, {"op", op}, {"error", e.what()}};
  } catch (const ParameterError& e) {
    return json{{"line", line}, {"ok", false}, {"op", op}, {"error", e.what()}};
  }
  json out = {{"line", line}, {"ok", true}, {"op", op}};
  out.update(reply);
  return out;
}

template <int D>
Point<D> EditSession<D>::user_point(Point<D> p) const {
  if constexpr (D == 2) {
    if (lonlat_edits_) {
      try {
        p = frame_.projection.forward({p[0], p[1]});
      } catch (const std::domain_error& e) {
        throw InputError(e.what());
      }
    }
  }
  if (!session_.box().contains(p)) {
    Point<D> hi = session_.box().origin;
    for (auto& x : hi) x += session_.box().side;
    throw InputError("the point " + frame_.point(p) + " is outside the session's box, " +
                     frame_.point(session_.box().origin) + " to " + frame_.point(hi) +
                     "; the box never grows (start the session with a larger --box)");
  }
  return p;
}

template <int D>
Point<D> EditSession<D>::parse_point(const std::vector<std::string>& words, std::size_t first) const {
  const std::size_t given = words.size() - first;
  if (given != std::size_t(D))
    throw InputError(words[0] + " takes " + (first == 2 ? "ID " : "") + (D == 2 ? "X Y" : "X Y Z") +
                     (words[0] == "add" && D == 2 ? " [after ID]" : "") + " in a " + std::to_string(D) + "D session");
  Point<D> p;
  for (int i = 0; i < D; ++i) p[std::size_t(i)] = parse_number(words[first + std::size_t(i)]);
  return user_point(p);
}

template <int D>
std::size_t EditSession<D>::parse_id(const std::string& word) const {
  std::size_t id = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), id);
  if (ec != std::errc{} || end != word.data() + word.size()) throw InputError("'" + word + "' is not an id");
  return id;
}

template <int D>
void EditSession<D>::record(const SessionEdit<D>& edit, json& reply) {
  last_delta_ = edit.mesh;
  last_edit_ = edit;
  reply["rings_ms"] = edit.rings_ms;
  reply["engine_ms"] = edit.engine_ms;
  reply["steiner_added"] = edit.engine.steiner_added.size();
  reply["steiner_removed"] = edit.engine.steiner_removed.size();
  reply["operations"] = edit.engine.operations_touched();
  reply["elements_removed"] = edit.mesh.removed.size();
  reply["elements_added"] = edit.mesh.added.size();
  reply["elements_changed"] = edit.mesh.removed.size() + edit.mesh.added.size();
  reply["elements"] = session_.mesh().element_count();
  reply["input_points"] = session_.input_count();
  reply["shore_splits"] = session_.split_count();
  reply["size_seeds"] = session_.seed_count();
  reply["steiner_points"] = session_.steiner_count();
  reply["mesh_ms"] = edit.mesh_ms;
  reply["ms"] = edit.ms;
}

template <int D>
json EditSession<D>::point_json(const Point<D>& p) const {
  return json(std::vector<double>(p.begin(), p.end()));
}

template <int D>
json EditSession<D>::add(const std::vector<std::string>& words) {
  // add X Y [Z] [after ID]: with `after`, the point joins ID's shoreline, between ID and the vertex after it.
  std::vector<std::string> point_words = words;
  std::optional<std::size_t> after;
  if (point_words.size() >= 3 && point_words[point_words.size() - 2] == "after") {
    if constexpr (D != 2) throw InputError("add X Y Z after ID: shorelines are for 2D sessions");
    after = parse_id(point_words.back());
    point_words.resize(point_words.size() - 2);
  }
  const Point<D> p = parse_point(point_words, 1);
  if (after) {
    session_.check_id(*after);
    if (!session_.ring_of(*after))
      throw InputError("input point " + std::to_string(*after) +
                       " is on no shoreline (a loose point); 'add X Y' without 'after' adds a loose point");
  }
  const SessionEdit<D> edit = after ? session_.add_after(*after, p) : session_.add(p);
  json reply = {{"id", edit.id}, {"point", point_json(p)}, {"at", frame_.point(p)}};
  if (after) {
    reply["after"] = *after;
    reply["ring"] = *edit.ring + 1;
  }
  record(edit, reply);
  return reply;
}

template <int D>
json EditSession<D>::remove(const std::vector<std::string>& words) {
  if (words.size() != 2) throw InputError("remove takes one ID");
  const std::size_t id = parse_id(words[1]);
  const Point<D> old = session_.input_point(id);
  const SessionEdit<D> edit = session_.remove(id);
  json reply = {{"id", id}, {"point", point_json(old)}, {"at", frame_.point(old)}};
  record(edit, reply);
  return reply;
}

template <int D>
json EditSession<D>::move(const std::vector<std::string>& words) {
  if (words.size() < 2) throw InputError(std::string("move takes ID ") + (D == 2 ? "X Y" : "X Y Z"));
  const std::size_t id = parse_id(words[1]);
  session_.check_id(id);  // before the point: an id that does not exist is the first thing to say
  const Point<D> p = parse_point(words, 2);
  const Point<D> old = session_.input_point(id);
  const SessionEdit<D> edit = session_.move(id, p);
  json reply = {{"id", id}, {"point", point_json(p)}, {"at", frame_.point(p)}, {"from", frame_.point(old)}};
  record(edit, reply);
  return reply;
}

template <int D>
json EditSession<D>::add_ring(const std::vector<std::string>& words, const std::string& rest) {
  // add-ring X1 Y1 X2 Y2 X3 Y3 ... (closed implicitly), or add-ring FILE (a ring file holding one ring);
  // add-line X1 Y1 X2 Y2 ... (an open chain of constraints).
  const bool line = words[0] == "add-line";
  if constexpr (D != 2) {
    (void)words, (void)rest, (void)line;
    throw InputError(words[0] + ": rings and lines are for 2D sessions");
  } else {
    std::vector<Point2> points;
    if (line) {
      if (words.size() < 5 || (words.size() - 1) % 2 != 0)
        throw InputError("add-line takes X1 Y1 X2 Y2 ... (at least two points)");
      for (std::size_t i = 1; i + 1 < words.size(); i += 2)
        points.push_back(user_point({parse_number(words[i]), parse_number(words[i + 1])}));
    } else if (words.size() == 2 || (words.size() > 2 && !std::isdigit(static_cast<unsigned char>(rest[0])) &&
                                     rest[0] != '-' && rest[0] != '+' && rest[0] != '.')) {
      const io::RingFile file = io::read_ring_file(rest);
      if (file.rings.size() != 1)
        throw InputError("add-ring takes a ring file with one ring; it holds " + std::to_string(file.rings.size()), rest);
      for (const Point2& p : file.rings.front()) points.push_back(user_point(p));
    } else {
      if (words.size() < 7 || (words.size() - 1) % 2 != 0)
        throw InputError("add-ring takes X1 Y1 X2 Y2 X3 Y3 ... (at least three points, closed implicitly) or a FILE");
      for (std::size_t i = 1; i + 1 < words.size(); i += 2)
        points.push_back(user_point({parse_number(words[i]), parse_number(words[i + 1])}));
      if (points.size() > 3 && points.front() == points.back()) points.pop_back();  // closed explicitly
    }
    const SessionEdit<D> edit = session_.add_ring(points, line);
    json reply = {{"id", edit.id}, {"ring", *edit.ring + 1}, {"ids", edit.ring_ids}, {"points", points.size()}};
    const RingRole role = session_.ring_role(*edit.ring);
    reply["role"] = role == RingRole::Island ? "island" : role == RingRole::Line ? "line" : "shore";
    record(edit, reply);
    return reply;
  }
}

template <int D>
json EditSession<D>::remove_ring(const std::vector<std::string>& words) {
  if (words.size() != 2) throw InputError("remove-ring takes a ring NUMBER (1 for the first ring)");
  const std::size_t number = parse_id(words[1]);
  if (number == 0) throw InputError("rings are numbered from 1");
  const SessionEdit<D> edit = session_.remove_ring(number - 1);
  json reply = {{"ring", number}, {"ids", edit.ring_ids}, {"points", edit.ring_ids.size()}};
  record(edit, reply);
  return reply;
}

template <int D>
json EditSession<D>::export_to(const std::vector<std::string>& words) {
  if (words.size() != 2 || words[1].empty())
    throw InputError("export takes a PATH (.csv for the point set, .rings for the shoreline, or a mesh)");
  const std::filesystem::path path = words[1];
  const auto start = Clock::now();
  json reply = {{"path", path.string()}};
  std::string ext = path.extension().string();
  // As `mesh` writes: never over an input, and all the files (Triangle's two) or none.
  io::OutputBatch batch(inputs_);
  if (ext == ".rings") {
    if (!session_.has_rings()) throw InputError("export PATH.rings: this session has no shoreline");
    const Domain2 rings = session_.rings();
    io::write_ring_file(batch.add(path, "export"), rings);
    reply["rings"] = rings.rings.size();
  } else if (is_point_set_path(path)) {
    const auto points = session_.canonical_points();
    io::write_point_set_csv<D>(batch.add(path, "export"), session_.box(), points);
    reply["points"] = points.size();
  } else {
    // Numbered like a fresh run's export on the current input: its canonical point list.
    const io::ExportFormat format = io::export_format_from_path(path);
    export_mesh_file<D>(session_.mesh(), stage_output(batch, path, format, "export"), format, frame_,
                        session_.canonical_points());
    reply["elements"] = session_.mesh().element_count();
  }
  batch.commit();
  reply["ms"] = ms_since(start);
  return reply;
}

template <int D>
json EditSession<D>::preview(const std::vector<std::string>& words) {
  if (words.size() != 2 || words[1].empty()) throw InputError("preview takes a PATH (.png)");
  const auto start = Clock::now();
  io::OutputBatch batch(inputs_);
  PreviewArgs args = preview_;
  // The size colouring reads h as the session holds it now (a size edit replaces it); not owned.
  if (const SizeField* field = session_.size_field()) args.size = std::shared_ptr<const SizeField>(field, [](const SizeField*) {});
  write_preview<D>(session_.mesh(), batch.add(words[1], "preview"), args);
  batch.commit();
  return {{"path", words[1]}, {"ms", ms_since(start)}};
}

template <int D>
json EditSession<D>::preview_change(const std::vector<std::string>& words) {
  if (words.size() != 2 || words[1].empty()) throw InputError("preview-change takes a PATH (.png)");
  if constexpr (D != 2) {
    throw InputError("preview-change is for 2D sessions");
  } else {
    const auto start = Clock::now();
    // The neighbourhood of the change: the elements within the change's extent grown 3 times.
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const auto* list : {&last_delta_.removed, &last_delta_.added})
      for (const auto& e : *list)
        for (const auto& p : e)
          for (int i = 0; i < 2; ++i) {
            lo[i] = std::min(lo[i], p[i]);
            hi[i] = std::max(hi[i], p[i]);
          }
    const auto elements = session_.mesh().elements();
    std::vector<Element<2>> near;
    if (last_delta_.empty()) {
      near = elements;
    } else {
      const double grow = std::max(hi[0] - lo[0], hi[1] - lo[1]);
      for (const auto& e : elements) {
        bool inside = false;
        for (auto v : e) {
          const Point2& p = session_.mesh().points()[v];
          inside = inside || (p[0] >= lo[0] - grow && p[0] <= hi[0] + grow && p[1] >= lo[1] - grow && p[1] <= hi[1] + grow);
        }
        if (inside) near.push_back(e);
      }
    }
    // Only the points those elements use, so that the picture frames the neighbourhood.
    std::vector<std::uint32_t> used;
    for (const auto& e : near) used.insert(used.end(), e.begin(), e.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::vector<Point2> points;
    std::vector<PointKind> kinds;
    for (auto v : used) {
      points.push_back(session_.mesh().points()[v]);
      kinds.push_back(session_.mesh().kinds()[v]);
    }
    for (auto& e : near)
      for (auto& v : e) v = static_cast<std::uint32_t>(std::lower_bound(used.begin(), used.end(), v) - used.begin());
    const io::MeshSnapshot<2> snapshot(std::move(points), std::move(near), std::move(kinds));
    io::OutputBatch batch(inputs_);
    io::render_delta_preview(batch.add(words[1], "preview-change"), snapshot.view(), last_delta_, preview_options(preview_));
    batch.commit();
    return {{"path", words[1]}, {"elements_changed", last_delta_.removed.size() + last_delta_.added.size()},
            {"ms", ms_since(start)}};
  }
}

// size POLYGON H: size polygon POLYGON (0-based, in the file's order) takes size H.
template <int D>
json EditSession<D>::set_size(const std::vector<std::string>& words) {
  if (words.size() != 3) throw InputError("size takes POLYGON H (a size polygon's number from 0, and its new size)");
  const std::size_t polygon = parse_id(words[1]);
  const double size = parse_number(words[2]);
  const SessionEdit<D> edit = session_.set_polygon_size(polygon, size);
  json reply = {{"polygon", polygon}, {"size", size}};
  record(edit, reply);
  return reply;
}

template <int D>
json EditSession<D>::stats() const {
  const auto start = Clock::now();
  const Domain2 input_rings = session_.rings();  // the sharp corners' reach: the rings before their splits
  const QualityNumbers q = quality_numbers<D>(session_.mesh(), session_.rho(), session_.box(), frame_, &input_rings);
  json r;
  r["input_points"] = session_.input_count();
  r["shore_splits"] = session_.split_count();
  r["size_seeds"] = session_.seed_count();
  r["steiner_points"] = session_.steiner_count();
  r["next_id"] = session_.next_id();
  r["elements"] = q.elements;
  r["min_angle"] = q.min_angle;
  r["max_angle"] = q.max_angle;
  r["min_angle_bound"] = q.min_angle_bound;
  r["covered"] = q.covered;
  r["covered_meeting_bound"] = q.covered_meeting_bound;
  r["covered_max_radius_edge"] = q.covered_max_radius_edge;
  r["rho"] = q.rho;
  if (q.left_out_at_box_edge) r["left_out_at_box_edge"] = *q.left_out_at_box_edge;
  if (q.shore_segments) {
    r["shore_below_bound"] = q.shore_below_bound;
    r["below_bound_at_sharp_corners"] = q.below_bound_at_sharp_corners;  // docs/conforming.md
    r["sharp_corners"] = q.sharp_corners;
    r["shore_splits"] = session_.split_count();
    r["shore_segments"] = *q.shore_segments;
    r["shore_covered"] = *q.shore_covered;
    r["shore_conforming"] = *q.shore_covered == *q.shore_segments;
  }
  r["ms"] = ms_since(start);
  return r;
}

namespace {
std::string count(const json& r, const char* key) { return r.contains(key) ? r[key].dump() : "?"; }
std::string millis(const json& r) { return approx(r.value("ms", 0.0), 3) + " ms"; }
}  // namespace

std::string reply_text(const json& r) {
  const std::string line = "line " + r["line"].dump() + ": ";
  const std::string op = r.value("op", "");
  if (!r.value("ok", false)) return line + "error: " + r.value("error", "");
  auto change = [&] {
    return ": +" + count(r, "steiner_added") + " Steiner, -" + count(r, "steiner_removed") + " Steiner, " +
           count(r, "elements_changed") + " elements changed, " + millis(r);
  };
  if (op == "build")
    return "built: " + count(r, "input_points") + " input points, " + count(r, "steiner_points") + " Steiner points, " +
           count(r, "elements") + " elements, " + millis(r) + "; box " + r["box"].dump() + " (" +
           r.value("units", "") + ")";
  if (op == "add")
    return line + "added id " + count(r, "id") + " at " + r.value("at", "") +
           (r.contains("after") ? " to ring " + count(r, "ring") + " after id " + count(r, "after") : std::string()) +
           change();
  if (op == "remove") return line + "removed id " + count(r, "id") + change();
  // A run of new ids as a range; otherwise (a line's end shared with a ring keeps the ring's id) each.
  auto id_range = [&] {
    const auto& ids = r["ids"];
    if (ids.empty()) return std::string();
    bool run = true;
    for (std::size_t k = 1; k < ids.size(); ++k) run = run && ids[k].get<long long>() == ids[k - 1].get<long long>() + 1;
    if (run) return ", ids " + ids.front().dump() + ".." + ids.back().dump();
    std::string each;
    for (const auto& id : ids) {
      if (!each.empty()) each += ' ';
      each += id.dump();
    }
    return ", ids " + each;
  };
  if (op == "add-ring" || op == "add-line")
    return line + "added ring " + count(r, "ring") + " (" + r.value("role", "") + ", " + count(r, "points") + " points" +
           id_range() + ")" + change();
  if (op == "remove-ring")
    return line + "removed ring " + count(r, "ring") + " (" + count(r, "points") + " points" + id_range() + ")" + change();
  if (op == "move") return line + "moved id " + count(r, "id") + " to " + r.value("at", "") + change();
  if (op == "size")
    return line + "size polygon " + count(r, "polygon") + " is now " + approx(r.value("size", 0.0)) + " (" +
           count(r, "size_seeds") + " size seeds)" + change();
  if (op == "export" || op == "preview" || op == "preview-change")
    return line + "wrote " + r.value("path", "") + ", " + millis(r);
  if (op == "stats")
    return line + "stats: " + count(r, "input_points") + " input points, " + count(r, "steiner_points") +
           " Steiner points, " + count(r, "elements") + " elements, angles " + approx(r.value("min_angle", 0.0), 4) +
           ".." + approx(r.value("max_angle", 0.0), 4) + " deg, bound met by " + count(r, "covered_meeting_bound") +
           " of " + count(r, "covered") + " covered elements" +
           (r.contains("shore_segments")
                ? std::string("; shoreline: ") +
                      (r.value("shore_conforming", false) ? "all " + count(r, "shore_segments") + " shore segments are mesh edges"
                                                          : count(r, "shore_covered") + " of " + count(r, "shore_segments") +
                                                                " shore segments are mesh edges") +
                      " (" + count(r, "shore_splits") + " canonical splits; " + count(r, "shore_below_bound") +
                      " triangles at the shore below the bound)"
                : std::string());
  return line + r.dump();
}

template class EditSession<2>;
template class EditSession<3>;

}  // namespace shoremesh::tool
