#include "edit_session.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <sstream>

#include "shoremesh/error.hpp"
#include "shoremesh/io/point_set_csv.hpp"
#include "shoremesh/io/ring_edge_index.hpp"
#include "shoremesh/io/ring_file.hpp"

namespace shoremesh::tool {

namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

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
std::vector<ElementCorners<D>> sorted_corners(const Mesh<D>& mesh) {
  std::vector<ElementCorners<D>> out;
  const auto& points = mesh.points();
  for (const auto& e : mesh.elements()) {
    ElementCorners<D> c;
    for (int i = 0; i <= D; ++i) c[std::size_t(i)] = points[e[std::size_t(i)]];
    std::sort(c.begin(), c.end());
    out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}

template <int D>
MeshDelta<D> diff(const std::vector<ElementCorners<D>>& before, const std::vector<ElementCorners<D>>& after) {
  MeshDelta<D> d;
  std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(d.removed));
  std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(d.added));
  return d;
}

template <int D>
Domain2 initial_domain(const io::InputSet& set) {
  if constexpr (D == 2) return set.domain;
  return {};
}

}  // namespace

template <int D>
EditSession<D>::EditSession(const io::InputSet& set, double rho, std::optional<BoxTransform<D>> box, bool keep_hull,
                            PreviewArgs preview, bool lonlat_edits)
    : frame_(UserFrame::of(set)),
      lonlat_edits_(lonlat_edits),
      rho_(rho),
      keep_hull_(keep_hull),
      preview_(std::move(preview)),
      refinement_([&]() -> std::optional<ShoreRefinement> {
        if constexpr (D == 2) return shore_refinement(set, box);
        return std::nullopt;
      }()),
      set_([&] {
        try {
          // As a fresh `mesh` run gives them to the engine: the input points, then the shore's splits.
          return DynamicWellSpaced<D>(engine_points<D>(set, refinement_ ? &*refinement_ : nullptr),
                                      engine_parameters<D>(rho), box);
        } catch (const PointInputError& e) {
          rethrow_with_origin(e, set);
        }
      }()),
      mesh_(make_mesh<D>(set_.points(), set_.input_count(), refinement_ ? refinement_->refined() : Domain2{},
                         set_.box(), keep_hull_)),
      next_id_(set.size()) {
  preview_.rho = rho;
  for (std::size_t id = 0; id < set.size(); ++id) engine_of_user_.push_back(id);
  if (refinement_) {
    const std::vector<Point2> splits = refinement_->split_points();
    for (std::size_t j = 0; j < splits.size(); ++j) split_id_.emplace(splits[j], set.size() + j);
  }
  const Domain2& domain = initial_domain<D>(set);
  if (!domain.rings.empty()) ring_index_.emplace(domain);
  for (std::size_t r = 0; r < domain.rings.size(); ++r) {
    std::vector<std::size_t> ids;
    for (std::size_t k = 0; k < domain.rings[r].points.size(); ++k) {
      const std::size_t id = set.ring_offsets.at(r) + k;
      ids.push_back(id);
      ring_of_[id] = {r, k};
    }
    ring_ids_.push_back(std::move(ids));
  }
}

template <int D>
std::vector<std::size_t> EditSession<D>::apply_edits(std::vector<Edit<D>> edits, const Domain2* rings,
                                                     std::vector<Point<D>> loose_removed,
                                                     std::vector<Point<D>> loose_added,
                                                     std::vector<Point<D>>& inputs_removed,
                                                     std::vector<Point<D>>& inputs_added, UpdateReport<D>& report) {
  const std::size_t user_adds = static_cast<std::size_t>(
      std::count_if(edits.begin(), edits.end(), [](const Edit<D>& e) { return e.kind == Edit<D>::Kind::Add; }));
  if constexpr (D == 2) {
    if (refinement_) {
      const Domain2 before = refinement_->rings();
      const SplitChange change = refinement_->update(rings ? *rings : before, loose_removed, loose_added);
      for (const Point2& p : change.removed) {
        edits.push_back({Edit<D>::Kind::Remove, split_id_.at(p), {}});
        inputs_removed.push_back(p);
      }
      for (const Point2& p : change.added) {
        edits.push_back({Edit<D>::Kind::Add, 0, p});
        inputs_added.push_back(p);
      }
      std::vector<std::size_t> ids;
      try {
        ids = set_.apply(edits, &report);
      } catch (...) {
        refinement_->update(before, loose_added, loose_removed);  // the inverse edit: the same splits as before
        throw;
      }
      for (const Point2& p : change.removed) split_id_.erase(p);
      for (std::size_t j = 0; j < change.added.size(); ++j) split_id_.emplace(change.added[j], ids[user_adds + j]);
      ids.resize(user_adds);
      return ids;
    }
  }
  (void)rings, (void)loose_removed, (void)loose_added;
  return set_.apply(edits, &report);
}

template <int D>
json EditSession<D>::build_reply(double ms) const {
  json r = {{"line", 0}, {"ok", true}, {"op", "build"}};
  r["input_points"] = user_input_count();
  r["shore_splits"] = split_id_.size();
  r["steiner_points"] = set_.steiner_count();
  r["elements"] = mesh_.element_count();
  std::vector<double> box(set_.box().origin.begin(), set_.box().origin.end());
  box.push_back(set_.box().side);
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
    else if (op == "export") reply = export_to({op, rest_after_op(text)});
    else if (op == "preview") reply = preview({op, rest_after_op(text)});
    else if (op == "preview-change") reply = preview_change({op, rest_after_op(text)});
    else if (op == "stats") {
      if (words.size() != 1) throw InputError("stats takes no arguments");
      reply = stats();
    } else {
      throw InputError("unknown edit '" + op + "' (add, remove, move, export, preview, preview-change, stats)");
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
Point<D> EditSession<D>::parse_point(const std::vector<std::string>& words, std::size_t first) const {
  const std::size_t given = words.size() - first;
  if (given != std::size_t(D))
    throw InputError(words[0] + " takes " + (first == 2 ? "ID " : "") + (D == 2 ? "X Y" : "X Y Z") +
                     (words[0] == "add" && D == 2 ? " [after ID]" : "") + " in a " + std::to_string(D) + "D session");
  Point<D> p;
  for (int i = 0; i < D; ++i) p[std::size_t(i)] = parse_number(words[first + std::size_t(i)]);
  if constexpr (D == 2) {
    if (lonlat_edits_) {
      try {
        p = frame_.projection.forward({p[0], p[1]});
      } catch (const std::domain_error& e) {
        throw InputError(e.what());
      }
    }
  }
  if (!set_.box().contains(p)) {
    Point<D> hi = set_.box().origin;
    for (auto& x : hi) x += set_.box().side;
    throw InputError("the point " + frame_.point(p) + " is outside the session's box, " + frame_.point(set_.box().origin) +
                     " to " + frame_.point(hi) + "; the box never grows (start the session with a larger --box)");
  }
  return p;
}

template <int D>
std::size_t EditSession<D>::parse_id(const std::string& word) const {
  std::size_t id = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), id);
  if (ec != std::errc{} || end != word.data() + word.size()) throw InputError("'" + word + "' is not an id");
  return id;
}

template <int D>
void EditSession<D>::check_id(std::size_t id) const {
  if (id < engine_of_user_.size() && engine_of_user_[id] != kRemoved) return;
  if (id < next_id_) throw InputError("input point " + std::to_string(id) + " was removed");
  throw InputError("no input point " + std::to_string(id) + " (ids so far: 0.." + std::to_string(next_id_ - 1) + ")");
}

template <int D>
std::optional<typename EditSession<D>::RingChange> EditSession<D>::rings_with(io::RingVertexEdit::Kind kind,
                                                                             std::size_t id, const Point<D>& p) const {
  using Kind = io::RingVertexEdit::Kind;
  if constexpr (D != 2) {
    return std::nullopt;
  } else {
    const auto it = ring_of_.find(id);
    if (it == ring_of_.end()) return std::nullopt;
    const auto [r, k] = it->second;
    const Domain2& now = refinement_->rings();
    RingChange change{now, {kind, r, k, now.rings[r].points[k]}};
    auto& ring = change.domain.rings[r].points;
    // The rings were valid before: only the edges at the changed vertex (or across the gap the removed
    // one leaves, from the vertex before it) are new, and only they need a look (the ring index).
    if (kind == Kind::Move) {
      ring[k] = p;
    } else if (kind == Kind::Insert) {
      ring.insert(ring.begin() + static_cast<std::ptrdiff_t>(k + 1), p);
      change.edit.vertex = k + 1;
    } else {
      if (ring.size() <= 3)
        throw InputError("input point " + std::to_string(id) + " is one of the last three points of ring " +
                         std::to_string(r + 1) + "; it cannot be removed");
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
      change.edit.vertex = (k + ring.size() - 1) % ring.size();
    }
    if (const auto defect = ring_index_->defect_at(change.domain, change.edit)) {
      const std::string what = kind == Kind::Move     ? "moving input point " + std::to_string(id)
                               : kind == Kind::Insert ? "adding a point after input point " + std::to_string(id)
                                                      : "removing input point " + std::to_string(id);
      throw InputError(what + " would break the shoreline: " + defect->describe());
    }
    return change;
  }
}

template <int D>
void EditSession<D>::commit_ring_ids(const RingChange& change, std::size_t id) {
  using Kind = io::RingVertexEdit::Kind;
  const std::size_t r = change.edit.ring;
  auto& ids = ring_ids_[r];
  std::size_t first = 0;  // the ids from here on changed position
  if (change.edit.kind == Kind::Insert) {
    first = change.edit.vertex;
    ids.insert(ids.begin() + static_cast<std::ptrdiff_t>(first), id);
  } else if (change.edit.kind == Kind::Remove) {
    first = ring_of_.at(id).second;
    ring_of_.erase(id);
    ids.erase(ids.begin() + static_cast<std::ptrdiff_t>(first));
  } else {
    return;
  }
  for (std::size_t j = first; j < ids.size(); ++j) ring_of_[ids[j]] = {r, j};
}

template <int D>
void EditSession<D>::update_mesh(const UpdateReport<D>& report, std::vector<Point<D>> inputs_removed,
                                 std::vector<Point<D>> inputs_added, std::optional<RingChange> rings,
                                 Clock::time_point edit_start, Clock::time_point engine_start, json& reply) {
  reply["rings_ms"] = std::chrono::duration<double, std::milli>(engine_start - edit_start).count();
  reply["engine_ms"] = ms_since(engine_start);
  reply["steiner_added"] = report.steiner_added.size();
  reply["steiner_removed"] = report.steiner_removed.size();
  reply["operations"] = report.operations_touched();
  const auto change = PointChange<D>::from_update(report, std::move(inputs_removed), std::move(inputs_added));
  const auto start = Clock::now();
  bool rebuilt = false;
  try {
    // A shore point moved, removed or added changes the rings too: the mesh takes them with the points
    // and classifies again only the triangles near the changed stretch.
    if constexpr (D == 2) last_delta_ = refinement_ ? mesh_.apply(change, refinement_->refined()) : mesh_.apply(change);
    else last_delta_ = mesh_.apply(change);
  } catch (const InputError&) {
    rebuilt = true;  // the mesh and the engine disagree (nothing was changed): rebuild from the engine's points
  }
  if (rings) ring_index_->commit(rings->domain, rings->edit);
  if (rebuilt) {
    const auto before = sorted_corners<D>(mesh_);
    Domain2 domain;
    if constexpr (D == 2)
      if (refinement_) domain = refinement_->refined();
    mesh_ = make_mesh<D>(set_.points(), set_.input_count(), domain, set_.box(), keep_hull_);
    last_delta_ = diff<D>(before, sorted_corners<D>(mesh_));
  }
  reply["elements_removed"] = last_delta_.removed.size();
  reply["elements_added"] = last_delta_.added.size();
  reply["elements_changed"] = last_delta_.removed.size() + last_delta_.added.size();
  reply["elements"] = mesh_.element_count();
  reply["input_points"] = user_input_count();
  reply["shore_splits"] = split_id_.size();
  reply["steiner_points"] = set_.steiner_count();
  reply["mesh_ms"] = ms_since(start);
  reply["ms"] = ms_since(edit_start);
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
  const auto edit_start = Clock::now();
  std::optional<RingChange> rings;
  if (after) {
    check_id(*after);
    rings = rings_with(io::RingVertexEdit::Kind::Insert, *after, p);
    if (!rings)
      throw InputError("input point " + std::to_string(*after) +
                       " is on no shoreline (a loose point); 'add X Y' without 'after' adds a loose point");
  }
  const auto start = Clock::now();
  UpdateReport<D> report;
  std::vector<Point<D>> removed, added{p};
  const auto ids = apply_edits({{Edit<D>::Kind::Add, 0, p}}, rings ? &rings->domain : nullptr, {},
                               rings ? std::vector<Point<D>>{} : std::vector<Point<D>>{p}, removed, added, report);
  const std::size_t id = next_id_++;
  engine_of_user_.push_back(ids.at(0));
  json reply = {{"id", id}, {"point", point_json(p)}, {"at", frame_.point(p)}};
  if (rings) {
    commit_ring_ids(*rings, id);
    reply["after"] = *after;
    reply["ring"] = rings->edit.ring + 1;
  }
  update_mesh(report, std::move(removed), std::move(added), std::move(rings), edit_start, start, reply);
  return reply;
}

template <int D>
json EditSession<D>::remove(const std::vector<std::string>& words) {
  if (words.size() != 2) throw InputError("remove takes one ID");
  const std::size_t id = parse_id(words[1]);
  check_id(id);
  const Point<D> old = set_.input_point(engine_id(id));
  const auto edit_start = Clock::now();
  auto rings = rings_with(io::RingVertexEdit::Kind::Remove, id, old);
  const auto start = Clock::now();
  UpdateReport<D> report;
  std::vector<Point<D>> removed{old}, added;
  apply_edits({{Edit<D>::Kind::Remove, engine_id(id), {}}}, rings ? &rings->domain : nullptr,
              rings ? std::vector<Point<D>>{} : std::vector<Point<D>>{old}, {}, removed, added, report);
  engine_of_user_[id] = kRemoved;
  if (rings) commit_ring_ids(*rings, id);
  json reply = {{"id", id}, {"point", point_json(old)}, {"at", frame_.point(old)}};
  update_mesh(report, std::move(removed), std::move(added), std::move(rings), edit_start, start, reply);
  return reply;
}

template <int D>
json EditSession<D>::move(const std::vector<std::string>& words) {
  if (words.size() < 2) throw InputError(std::string("move takes ID ") + (D == 2 ? "X Y" : "X Y Z"));
  const std::size_t id = parse_id(words[1]);
  check_id(id);  // before the point: an id that does not exist is the first thing to say
  const Point<D> p = parse_point(words, 2);
  const Point<D> old = set_.input_point(engine_id(id));
  const auto edit_start = Clock::now();
  auto rings = rings_with(io::RingVertexEdit::Kind::Move, id, p);
  const auto start = Clock::now();
  UpdateReport<D> report;
  std::vector<Point<D>> removed{old}, added{p};
  apply_edits({{Edit<D>::Kind::Move, engine_id(id), p}}, rings ? &rings->domain : nullptr,
              rings ? std::vector<Point<D>>{} : std::vector<Point<D>>{old},
              rings ? std::vector<Point<D>>{} : std::vector<Point<D>>{p}, removed, added, report);
  json reply = {{"id", id}, {"point", point_json(p)}, {"at", frame_.point(p)}, {"from", frame_.point(old)}};
  update_mesh(report, std::move(removed), std::move(added), std::move(rings), edit_start, start, reply);
  return reply;
}

template <int D>
std::vector<Point<D>> EditSession<D>::canonical_points() const {
  const std::vector<Point<D>> all = set_.points();
  std::vector<Point<D>> out;
  out.reserve(all.size());
  for (std::size_t eid : engine_of_user_)
    if (eid != kRemoved) out.push_back(set_.input_point(eid));
  if constexpr (D == 2)
    if (refinement_)
      for (const Point2& p : refinement_->split_points()) out.push_back(p);
  out.insert(out.end(), all.begin() + static_cast<std::ptrdiff_t>(set_.input_count()), all.end());
  return out;
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
    if (!refinement_) throw InputError("export PATH.rings: this session has no shoreline");
    io::write_ring_file(batch.add(path, "export"), refinement_->rings());
    reply["rings"] = refinement_->rings().rings.size();
  } else if (is_point_set_path(path)) {
    const auto points = canonical_points();
    io::write_point_set_csv<D>(batch.add(path, "export"), set_.box(), points);
    reply["points"] = points.size();
  } else {
    // Numbered like a fresh run's export on the current input: its canonical point list.
    const io::ExportFormat format = io::export_format_from_path(path);
    export_mesh_file<D>(mesh_, stage_output(batch, path, format, "export"), format, frame_, canonical_points());
    reply["elements"] = mesh_.element_count();
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
  write_preview<D>(mesh_, batch.add(words[1], "preview"), preview_);
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
    const auto elements = mesh_.elements();
    std::vector<Element<2>> near;
    if (last_delta_.empty()) {
      near = elements;
    } else {
      const double grow = std::max(hi[0] - lo[0], hi[1] - lo[1]);
      for (const auto& e : elements) {
        bool inside = false;
        for (auto v : e) {
          const Point2& p = mesh_.points()[v];
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
      points.push_back(mesh_.points()[v]);
      kinds.push_back(mesh_.kinds()[v]);
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

template <int D>
json EditSession<D>::stats() const {
  const auto start = Clock::now();
  const QualityNumbers q = quality_numbers<D>(mesh_, rho_, set_.box(), frame_);
  json r;
  r["input_points"] = user_input_count();
  r["shore_splits"] = split_id_.size();
  r["steiner_points"] = set_.steiner_count();
  r["next_id"] = next_id_;
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
    r["shore_splits"] = split_id_.size();
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
  if (op == "move") return line + "moved id " + count(r, "id") + " to " + r.value("at", "") + change();
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
