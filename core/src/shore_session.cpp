#include "shoremesh/shore_session.hpp"

#include <algorithm>
#include <iterator>
#include <string>
#include <unordered_map>
#include <utility>

#include "shoremesh/error.hpp"
#include "shoremesh/ring_edge_index.hpp"

namespace shoremesh {

namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Exact coordinates as a key.
struct ExactHash {
  std::size_t operator()(const Point2& p) const {
    return std::hash<double>{}(p[0] + 0.0) * 0x9E3779B97F4A7C15ull ^ std::hash<double>{}(p[1] + 0.0);
  }
};

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
std::string describe_point(const Point<D>& p) {
  std::string s = "(";
  for (int i = 0; i < D; ++i) s += (i ? ", " : "") + std::to_string(p[std::size_t(i)]);
  return s + ")";
}

// An edit's ring stretch as the engine's water takes it: the chains' old middle (from the undo) and new
// middle; none when the edit has no stretch.
std::optional<WaterStretch> water_stretch(const RingStretch* stretch, const RingStretch* undo) {
  if (!stretch || !undo) return std::nullopt;
  return WaterStretch{stretch->ring, stretch->prefix, stretch->suffix, undo->middle, stretch->middle, stretch->whole};
}

}  // namespace

template <int D>
Parameters<D> session_parameters(double rho) {
  Parameters<D> parameters;
  parameters.rho = rho;
  if (parameters.beta <= rho) parameters.beta = 1.5 * rho;  // keep the picking region non-empty
  return parameters;
}

BoxTransform<2> run_box(const SessionInput<2>& input, const std::optional<BoxTransform<2>>& box) {
  return box ? *box : BoxTransform<2>::fit(input.points);
}

std::optional<ShoreRefinement> refine_input(const SessionInput<2>& input, const std::optional<BoxTransform<2>>& box,
                                            std::shared_ptr<const SizeField> size) {
  if (input.rings.empty()) return std::nullopt;
  const std::size_t n = input.points.size();
  if (input.ring_ids.size() != input.rings.rings.size())
    throw InputError("session input: " + std::to_string(input.rings.rings.size()) + " rings but ids for " +
                     std::to_string(input.ring_ids.size()));
  std::vector<bool> on_ring(n, false);
  for (std::size_t r = 0; r < input.rings.rings.size(); ++r) {
    const auto& pts = input.rings.rings[r].points;
    if (input.ring_ids[r].size() != pts.size())
      throw InputError("session input: ring " + std::to_string(r + 1) + " has " + std::to_string(pts.size()) +
                       " points but " + std::to_string(input.ring_ids[r].size()) + " ids");
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const std::size_t id = input.ring_ids[r][k];
      if (id >= n || input.points[id] != pts[k])
        throw InputError("session input: ring " + std::to_string(r + 1) + " vertex " + std::to_string(k + 1) +
                         " is not input point " + std::to_string(id));
      on_ring[id] = true;  // a vertex that rings share is one input point
    }
  }
  std::vector<Point2> loose;
  for (std::size_t i = 0; i < n; ++i)
    if (!on_ring[i]) loose.push_back(input.points[i]);
  // No split below 2^-32 of the engine's box: the given one, or the one the engine fits to the input.
  RefinementRule rule = RefinementRule::for_box(run_box(input, box).side);
  if (size) rule.max_length = shore_max_length(std::move(size));
  return ShoreRefinement(input.rings, loose, rule);
}

template <int D>
Mesh<D> well_spaced_mesh(std::span<const Point<D>> points, std::size_t input_count, const Domain2& domain,
                         const BoxTransform<D>& box, bool keep_hull) {
  const std::optional<BoxTransform<D>> covered = keep_hull ? std::nullopt : std::optional(box);
  if constexpr (D == 2) {
    if (!domain.empty()) {
      // Lines alone bound no water: the mesh is then the box's, with the lines' segments in it.
      const bool water = std::any_of(domain.rings.begin(), domain.rings.end(),
                                     [](const Ring& r) { return r.closed() && !r.points.empty(); });
      return water ? Mesh<2>(points, input_count, domain) : Mesh<2>(points, input_count, domain, covered);
    }
  }
  return Mesh<D>(points, input_count, covered);
}

template <int D>
struct ShoreSession<D>::Impl {
  static constexpr std::size_t kRemoved = static_cast<std::size_t>(-1);

  Options options;
  std::optional<ShoreRefinement> refinement;  // 2D with rings: the user's rings and their canonical splits
  std::optional<DynamicWellSpaced<D>> set;
  std::unordered_map<Point2, std::size_t, ExactHash> split_id;  // a split point's engine id
  std::shared_ptr<const SizeField> size;  // 2D with size control: h (the refinement's rule shares it)
  std::vector<Point2> seeds;              // the size seeds, sorted
  // The refined rings as the seeds' update reads them, given each edit's refined segments (made at the
  // first edit under size control, from the refined rings as they were).
  std::optional<SeedShoreIndex> seed_shore;
  std::unordered_map<Point2, std::size_t, ExactHash> seed_id;  // a seed's engine id
  std::vector<std::size_t> engine_of_user;  // by user id: the engine's input id (kRemoved once removed)
  std::optional<RingEdgeIndex> ring_index;  // the edges of the user's rings
  std::vector<std::vector<std::size_t>> ring_ids;  // ring r's vertices as input ids (empty: removed)
  // id -> (ring, a position near its place): locate() finds the place from there, so that a vertex
  // added or removed does not renumber the vertices after it (O(the ring) an edit).
  mutable std::unordered_map<std::size_t, std::pair<std::size_t, std::size_t>> ring_of;
  // Rings and lines may share a vertex: a line's end on a closed ring's vertex (a jetty on the shore), a
  // .poly's pinch vertex or segments meeting there. It is one input point; ring_of names the ring that
  // holds it first (closed rings before lines), shared_by the others. It can be neither moved nor
  // removed, nor the ring that holds it first removed, while they share it (one edit of it would change
  // several rings at once, which the ring index and the ids take one ring at a time). The closed rings'
  // vertices by point, to find a jetty's root.
  std::unordered_map<Point2, std::size_t, ExactHash> vertex_id;
  std::unordered_map<std::size_t, std::vector<std::size_t>> shared_by;
  std::optional<Mesh<D>> mesh;
  // 2D with rings: the user's rings as the refinement holds them, except while an edit is checked and
  // applied: that edit is then made here in place (the ring index checks it here), and taken back if it
  // is refused. No copy of the rings an edit.
  Domain2 rings_now;
  // The refined segments the last edit changed, for the mesh (unset: the mesh takes the refined rings).
  std::optional<ShoreChange> shore_change;

  std::size_t engine_id(std::size_t id) const { return engine_of_user.at(id); }

  // The ring of input point `id` (on one, live) and its place in it: searched outward from the position
  // last found, which is off by as many vertices as came or went before it since (each edit one).
  std::pair<std::size_t, std::size_t> locate(std::size_t id) const {
    auto& [r, hint] = ring_of.at(id);
    if constexpr (D == 2) {
      const Point2 p = set->input_point(engine_id(id));
      const auto& pts = rings_now.rings.at(r).points;
      const std::size_t n = pts.size();
      for (std::size_t d = 0; d <= n; ++d) {
        if (hint + d < n && pts[hint + d] == p) return {r, hint += d};
        if (d <= hint && hint - d < n && pts[hint - d] == p) return {r, hint -= d};
      }
      throw std::logic_error("shore session: input point " + std::to_string(id) + " is not on its ring");
    }
    return {r, hint};
  }

  // A vertex rings share (id `id`).
  bool shared_end(std::size_t id) const {
    const auto it = shared_by.find(id);
    return it != shared_by.end() && !it->second.empty();
  }
  std::string ring_name(std::size_t r) const {
    return (rings_now.rings.at(r).closed() ? "ring " : "line ") + std::to_string(r + 1);
  }
  void refuse_shared_end(std::size_t id, const std::string& what) const {
    if (!shared_end(id)) return;
    std::string rings = ring_name(ring_of.at(id).first);
    for (std::size_t r : shared_by.at(id)) rings += ", " + ring_name(r);
    std::string where;
    if constexpr (D == 2) {
      const Point2 p = set->input_point(engine_id(id));
      where = " (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ")";
    }
    throw InputError(what + " is refused: input point " + std::to_string(id) + where + " is a vertex of " + rings +
                     ", which share it; a shared vertex can be neither moved nor removed, nor the " +
                     ring_name(ring_of.at(id).first) + " removed, while they do (edit the vertices beside it, or " +
                     "remove the other rings and lines first)");
  }
  // A new or moved vertex on another vertex is refused (only a new line's end may be one: a jetty).
  void refuse_vertex_at(const Point2& p, const std::string& what) const {
    if (ring_index->has_vertex(p))
      throw InputError(what + " would break the shoreline: the point (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) +
                       ") is a vertex of a ring or line already (a new or moved vertex may not be one; only a new "
                       "line's end may, on a closed ring's vertex: a jetty)");
  }

  // A change of the user's rings, checked, as the refinement, the index and the ids take it; made in
  // rings_now (`undo_now` takes it back there).
  struct RingChange {
    std::optional<RingVertexEdit> edit;  // one vertex's edit of a closed ring (nullopt: a line's edit)
    std::size_t ring = 0;
    std::size_t position = 0;  // the edited vertex's place in its ring before the edit
    Ring line_before;  // a line's edit: the line as it was
    RingStretch stretch, undo;  // the edit as the refinement takes it, and the edit that undoes it there
    RingStretch undo_now;
  };

  // The index takes a checked change: one vertex's edit of a ring, or a line replaced as a whole.
  void commit_index(const RingChange& change) {
    if (change.edit) {
      ring_index->commit(rings_now, *change.edit);
    } else {
      ring_index->erase_ring(change.ring, change.line_before);
      ring_index->insert_ring(change.ring, rings_now.rings[change.ring]);
    }
  }

  // The rings after a vertex edit at input `id`: moved to `p`, removed, or a new vertex at `p` after it,
  // made in rings_now. InputError (rings_now as it was) when they would be invalid; nullopt when `id` is
  // on no ring.
  std::optional<RingChange> vertex_change(RingVertexEdit::Kind kind, std::size_t id, const Point<D>& p) {
    using Kind = RingVertexEdit::Kind;
    if constexpr (D != 2) {
      return std::nullopt;
    } else {
      if (!ring_of.count(id)) return std::nullopt;
      const auto [r, k] = locate(id);
      const Ring& now = rings_now.rings[r];
      const std::size_t count = now.points.size();
      const bool line = !now.closed();
      const std::string what = kind == Kind::Move     ? "moving input point " + std::to_string(id)
                               : kind == Kind::Insert ? "adding a point after input point " + std::to_string(id)
                                                      : "removing input point " + std::to_string(id);
      if (kind == Kind::Remove || kind == Kind::Move) refuse_shared_end(id, what);
      if (kind != Kind::Remove && p != now.points[k]) refuse_vertex_at(p, what);
      if (kind == Kind::Remove && count <= (line ? 2u : 3u))
        throw InputError("input point " + std::to_string(id) + " is one of the last " + (line ? "two" : "three") +
                         " points of " + (line ? "line " : "ring ") + std::to_string(r + 1) +
                         "; it cannot be removed (remove the " + (line ? "line" : "ring") + " instead)");
      RingChange change;
      change.ring = r;
      change.position = k;
      change.edit = RingVertexEdit{kind, r, k, now.points[k]};
      if (line) change.line_before = now;
      // The rings were valid before: only the edges at the changed vertex (or across the gap the removed
      // one leaves, from the vertex before it) are new, and only they need a look (the ring index).
      RingStretch s{r, k, count - k - 1, {}, false, now.role};
      if (kind == Kind::Move) {
        s.middle = {p};
      } else if (kind == Kind::Insert) {
        s.prefix = k + 1;
        s.middle = {p};
        change.edit->vertex = k + 1;
      } else {
        change.edit->vertex = (k + count - 2) % (count - 1);
      }
      change.undo_now = apply_stretch(rings_now, s);
      const Ring& after = rings_now.rings[r];
      std::optional<RingDefect> defect;
      if (!line) {
        defect = ring_index->defect_at(rings_now, *change.edit);
        change.stretch = std::move(s);
        change.undo = change.undo_now;
      } else {  // a line is checked as a whole, against the index without it, and taken whole
        change.edit.reset();
        ring_index->erase_ring(r, change.line_before);
        defect = ring_index->defect_of_new_ring(rings_now, r);
        ring_index->insert_ring(r, change.line_before);
        change.stretch = RingStretch{r, 0, 0, after.points, true, RingRole::Line};
        change.undo = RingStretch{r, 0, 0, change.line_before.points, true, RingRole::Line};
      }
      if (defect) {
        apply_stretch(rings_now, change.undo_now);
        throw InputError(what + " would break the shoreline: " + defect->describe());
      }
      return change;
    }
  }

  // Takes a committed change into the ids: `id` removed from its ring, or inserted as the new vertex.
  void commit_vertex_ids(const RingChange& change, RingVertexEdit::Kind kind, std::size_t id) {
    using Kind = RingVertexEdit::Kind;
    const std::size_t r = change.ring;
    auto& ids = ring_ids[r];
    const bool closed = rings_now.rings[r].closed();
    if (kind == Kind::Insert) {
      const std::size_t first = change.position + 1;
      ids.insert(ids.begin() + static_cast<std::ptrdiff_t>(first), id);
      ring_of[id] = {r, first};
      if (closed) vertex_id[rings_now.rings[r].points[first]] = id;
    } else if (kind == Kind::Remove) {
      ring_of.erase(id);
      ids.erase(ids.begin() + static_cast<std::ptrdiff_t>(change.position));
      if (closed) vertex_id.erase(change.edit->gone);
    }
  }

  // Applies the user's edits of the engine's input (engine ids) together with what they do to the shore's
  // canonical splits, in one propagation: `rings` the user's rings' edit (null: unchanged; made in
  // rings_now already) and `undo` its inverse, `loose_removed`/`loose_added` the loose points the edit
  // takes and gives. The input points that went and came (splits included) are added to
  // `removed`/`added`; returns the engine ids of the edits' added points, in order. On an error nothing
  // changed (but rings_now, which the caller takes back).
  std::vector<std::size_t> apply_edits(std::vector<Edit<D>> edits, const RingStretch* rings, const RingStretch* undo,
                                       std::vector<Point<D>> loose_removed, std::vector<Point<D>> loose_added,
                                       std::vector<Point<D>>& removed, std::vector<Point<D>>& added,
                                       UpdateReport<D>& report) {
    const std::size_t user_adds = static_cast<std::size_t>(
        std::count_if(edits.begin(), edits.end(), [](const Edit<D>& e) { return e.kind == Edit<D>::Kind::Add; }));
    shore_change.reset();
    if constexpr (D == 2) {
      // Size control: h, the splits under its rule and the seeds, in apply_sized.
      if (size)
        return apply_sized(std::move(edits), rings, undo, loose_removed, loose_added, {}, nullptr, removed, added, report);
      if (refinement) {
        const auto one = [](const RingStretch* s) { return s ? std::span<const RingStretch>(s, 1) : std::span<const RingStretch>(); };
        SplitChange change = refinement->update(one(rings), loose_removed, loose_added);
        for (const Point2& p : change.removed) {
          edits.push_back({Edit<D>::Kind::Remove, split_id.at(p), {}});
          removed.push_back(p);
        }
        for (const Point2& p : change.added) {
          edits.push_back({Edit<D>::Kind::Add, 0, p});
          added.push_back(p);
        }
        // The engine takes in the water's edges in the stretch alone (the refinement's rings have the edit).
        const std::optional<WaterStretch> water = water_stretch(rings, undo);
        std::vector<std::size_t> ids;
        try {
          ids = set->apply(edits, &report, water ? std::span<const WaterStretch>(&*water, 1) : std::span<const WaterStretch>());
        } catch (...) {
          refinement->update(one(undo), loose_added, loose_removed);  // the inverse edit: the same splits as before
          throw;
        }
        for (const Point2& p : change.removed) split_id.erase(p);
        for (std::size_t j = 0; j < change.added.size(); ++j) split_id.emplace(change.added[j], ids[user_adds + j]);
        ids.resize(user_adds);
        shore_change = std::move(change.segments);
        return ids;
      }
    }
    (void)rings, (void)undo, (void)loose_removed, (void)loose_added;
    return set->apply(edits, &report);
  }

  // apply_edits for a vertex edit (`change` made in rings_now), which it takes back there on an error.
  std::vector<std::size_t> apply_vertex_edits(std::vector<Edit<D>> edits, const std::optional<RingChange>& change,
                                              std::vector<Point<D>> loose_removed, std::vector<Point<D>> loose_added,
                                              std::vector<Point<D>>& removed, std::vector<Point<D>>& added,
                                              UpdateReport<D>& report) {
    try {
      return apply_edits(std::move(edits), change ? &change->stretch : nullptr, change ? &change->undo : nullptr,
                         std::move(loose_removed), std::move(loose_added), removed, added, report);
    } catch (...) {
      if (change) apply_stretch(rings_now, change->undo_now);
      throw;
    }
  }

  // The session's field, which its updates change in place (it was made mutable; the refinement's rule
  // shares it).
  SizeField& size_field() { return *std::const_pointer_cast<SizeField>(size); }

  // apply_edits under size control: h follows the rings (--size-from-shore: `stretch` made in rings_now,
  // `undo` its inverse) or a size edit (already made in the field, which changed h at `size_change` and
  // recorded what it overwrote in `size_undo`), updated in place only where the change reaches; when h
  // changed, the refinement resets the edges whose rule reads a changed node of h as well as those the edit
  // reaches, and closes again; the seeds are updated where h or the refined rings changed. All the
  // differences go to the engine in one propagation. On an error nothing changed.
  std::vector<std::size_t> apply_sized(std::vector<Edit<D>> edits, const RingStretch* stretch, const RingStretch* undo,
                                       const std::vector<Point<D>>& loose_removed,
                                       const std::vector<Point<D>>& loose_added, SizeChange size_change,
                                       SizeUndo* size_undo, std::vector<Point<D>>& removed,
                                       std::vector<Point<D>>& added, UpdateReport<D>& report) {
    if constexpr (D != 2) {
      (void)stretch, (void)undo, (void)loose_removed, (void)loose_added, (void)size_change, (void)size_undo,
          (void)removed, (void)added;
      return set->apply(edits, &report);
    } else {
      const std::size_t user_adds = static_cast<std::size_t>(
          std::count_if(edits.begin(), edits.end(), [](const Edit<D>& e) { return e.kind == Edit<D>::Kind::Add; }));
      SizeUndo ring_undo;
      if (!size_undo) size_undo = &ring_undo;
      const auto one = [](const RingStretch* s) { return s ? std::span<const RingStretch>(s, 1) : std::span<const RingStretch>(); };
      // The field holds the new rings even where h did not change: a later size edit reads them. It takes
      // the stretch (rings_now has it already): no pass over the rings.
      if (stretch && size->depends_on_rings()) size_change = size_field().set_rings(one(stretch), size_undo);
      const bool h_changed = size_change.changed;
      // The rule reads h over a subsegment's box: it may differ only where that reads a changed node.
      const std::function<bool(const Point2&, const Point2&)> rule_changed = [&](const Point2& a, const Point2& b) {
        return size->reads(a, b, size_change);
      };
      // The edges it may hold for, found by their reach (ShoreRefinement::update).
      const std::optional<std::pair<Point2, Point2>> near =
          h_changed ? std::optional(size->reach_of(size_change)) : std::nullopt;
      auto rule_of = [&](const std::shared_ptr<const SizeField>& field) {
        RefinementRule rule = RefinementRule::for_box(set->box().side);
        rule.max_length = shore_max_length(field);
        return rule;
      };
      if (!seed_shore) seed_shore.emplace(refinement ? refinement->refined() : Domain2{});
      SplitChange splits;
      try {
        if (refinement)
          splits = h_changed ? refinement->update(one(stretch), loose_removed, loose_added, rule_of(size), rule_changed, near)
                             : refinement->update(one(stretch), loose_removed, loose_added);
      } catch (...) {
        size_field().take_back(std::move(*size_undo));
        throw;
      }
      seed_shore->apply(splits.segments);
      auto take_back = [&] {
        seed_shore->take_back(splits.segments);
        size_field().take_back(std::move(*size_undo));
        if (refinement) {
          if (h_changed) refinement->update(one(undo), loose_added, loose_removed, rule_of(size), rule_changed, near);
          else refinement->update(one(undo), loose_added, loose_removed);
        }
      };
      std::vector<Point2> new_seeds;
      try {
        // Only the quadtree's nodes that the change of h or of the refined rings reaches (update_size_seeds).
        new_seeds = update_size_seeds(*size, *size_undo, seeds, size_change, splits.segments, *seed_shore);
      } catch (...) {
        take_back();
        throw;
      }
      std::vector<Point2> seeds_removed, seeds_added;
      std::set_difference(seeds.begin(), seeds.end(), new_seeds.begin(), new_seeds.end(), std::back_inserter(seeds_removed));
      std::set_difference(new_seeds.begin(), new_seeds.end(), seeds.begin(), seeds.end(), std::back_inserter(seeds_added));
      for (const Point2& p : splits.removed) edits.push_back({Edit<D>::Kind::Remove, split_id.at(p), {}});
      for (const Point2& p : seeds_removed) edits.push_back({Edit<D>::Kind::Remove, seed_id.at(p), {}});
      for (const Point2& p : splits.added) edits.push_back({Edit<D>::Kind::Add, 0, p});
      for (const Point2& p : seeds_added) edits.push_back({Edit<D>::Kind::Add, 0, p});
      // The engine takes in the water's edges in the stretch alone (the refinement's rings have the edit),
      // as apply_edits gives them without size control.
      const std::optional<WaterStretch> water = water_stretch(stretch, undo);
      std::vector<std::size_t> ids;
      try {
        ids = refinement ? set->apply(edits, &report, water ? std::span<const WaterStretch>(&*water, 1) : std::span<const WaterStretch>())
                         : set->apply(edits, &report);
      } catch (...) {
        take_back();
        throw;
      }
      shore_change = std::move(splits.segments);
      for (const Point2& p : splits.removed) split_id.erase(p), removed.push_back(p);
      for (const Point2& p : seeds_removed) seed_id.erase(p), removed.push_back(p);
      std::size_t next = user_adds;
      for (const Point2& p : splits.added) split_id.emplace(p, ids[next++]), added.push_back(p);
      for (const Point2& p : seeds_added) seed_id.emplace(p, ids[next++]), added.push_back(p);
      seeds = new_seeds;
      ids.resize(user_adds);
      return ids;
    }
  }

  // After the engine took an edit: the mesh takes the engine's Steiner changes plus the input points that
  // went and came, and the refined rings (any edit near the shore may change its splits), and the edit
  // its counts and times.
  void update_mesh(std::vector<Point<D>> removed, std::vector<Point<D>> added, Clock::time_point edit_start,
                   Clock::time_point engine_start, SessionEdit<D>& out) {
    const auto mesh_start = Clock::now();
    out.rings_ms = ms_between(edit_start, engine_start);
    out.engine_ms = ms_between(engine_start, mesh_start);
    out.inputs_removed = removed.size();
    out.inputs_added = added.size();
    const auto change = PointChange<D>::from_update(out.engine, std::move(removed), std::move(added));
    std::optional<ShoreChange> shore = std::move(shore_change);
    shore_change.reset();
    try {
      if constexpr (D == 2) {
        if (refinement && shore)  // the refined rings only when someone asks for them
          out.mesh = mesh->apply(change, *shore, [this] { return refinement->refined(); });
        else if (refinement)
          out.mesh = mesh->apply(change, refinement->refined());
        else
          out.mesh = mesh->apply(change);
      } else {
        out.mesh = mesh->apply(change);
      }
    } catch (const InputError&) {
      // The mesh and the engine disagree (the mesh changed nothing): rebuild from the engine's points.
      out.rebuilt = true;
      Domain2 refined;
      if constexpr (D == 2)
        if (refinement) refined = refinement->refined();
      const auto before = sorted_corners<D>(*mesh);
      const auto points = set->points();
      mesh = well_spaced_mesh<D>(points, set->input_count(), refined, set->box(), options.keep_hull);
      const auto after = sorted_corners<D>(*mesh);
      out.mesh = {};
      std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(out.mesh.removed));
      std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(out.mesh.added));
    }
    const auto end = Clock::now();
    out.mesh_ms = ms_between(mesh_start, end);
    out.ms = ms_between(edit_start, end);
  }

  void check_in_box(const Point<D>& p) const {
    if (set->box().contains(p)) return;
    Point<D> hi = set->box().origin;
    for (auto& x : hi) x += set->box().side;
    throw InputError("the point " + describe_point<D>(p) + " is outside the session's box, " +
                     describe_point<D>(set->box().origin) + " to " + describe_point<D>(hi) +
                     "; the box never grows (start the session with a larger box)");
  }

  // Closed rings not removed: the water needs one.
  std::size_t live_closed_rings() const {
    std::size_t n = 0;
    for (std::size_t r = 0; r < ring_ids.size(); ++r) n += !ring_ids[r].empty() && refinement->rings().rings[r].closed();
    return n;
  }
};

template <int D>
ShoreSession<D>::ShoreSession(const SessionInput<D>& input, const Options& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.options = options;
  const std::size_t n = input.points.size();
  std::optional<BoxTransform<D>> box = options.box;
  if constexpr (D != 2)
    if (options.size) throw InputError("size control is for 2D inputs");
  if constexpr (D == 2) {
    if (!input.rings.empty()) {
      // Closed rings first: a vertex rings share is held first by a closed ring where one has it.
      if (input.ring_ids.size() != input.rings.rings.size())
        throw InputError("session input: " + std::to_string(input.rings.rings.size()) + " rings but ids for " +
                         std::to_string(input.ring_ids.size()));
      m.ring_ids = input.ring_ids;
      for (const bool lines : {false, true})
        for (std::size_t r = 0; r < input.ring_ids.size(); ++r) {
          const Ring& ring = input.rings.rings[r];
          if (ring.closed() == lines) continue;
          for (std::size_t k = 0; k < input.ring_ids[r].size(); ++k) {
            const std::size_t id = input.ring_ids[r][k];
            const auto it = m.ring_of.find(id);
            if (it == m.ring_of.end()) {
              m.ring_of[id] = {r, k};
              if (!lines && k < ring.points.size()) m.vertex_id[ring.points[k]] = id;
            } else {
              m.shared_by[id].push_back(r);
            }
          }
        }
      if (const auto defect = find_ring_defect(input.rings, !m.shared_by.empty()))
        throw InputError("invalid rings: " + defect->describe());
    }
    if (options.size) {
      // The box is fixed before the seeds join the input (a fresh run fits it to the input points alone).
      box = run_box(input, options.box);
      m.size = std::make_shared<SizeField>(*options.size, *box, input.rings);  // mutable: edits update it in place
    }
    if (!input.rings.empty()) {
      m.refinement = refine_input(input, options.box, m.size);  // checks that the ring ids name the rings' points
      m.ring_index.emplace(input.rings);
      m.rings_now = input.rings;
    }
  }
  // As a fresh run gives them to the engine: the input points, then the shore's splits.
  std::vector<Point<D>> engine_points = input.points;
  std::vector<Point2> splits;
  if constexpr (D == 2)
    if (m.refinement) splits = m.refinement->split_points();
  if constexpr (D == 2) engine_points.insert(engine_points.end(), splits.begin(), splits.end());
  if constexpr (D == 2)
    if (m.size) {
      m.seeds = size_seeds(*m.size, m.refinement ? m.refinement->refined() : Domain2{});
      engine_points.insert(engine_points.end(), m.seeds.begin(), m.seeds.end());
    }
  WaterSource water;  // work only where the water is (docs/water_only.md): the user's rings, as they are now
  if constexpr (D == 2)
    if (m.refinement) water = [&m]() -> const Domain2* { return &m.refinement->rings(); };
  m.set.emplace(engine_points, session_parameters<D>(options.rho), box, BuildFor::Updates, std::move(water));
  for (std::size_t id = 0; id < n; ++id) m.engine_of_user.push_back(id);
  for (std::size_t j = 0; j < splits.size(); ++j) m.split_id.emplace(splits[j], n + j);
  for (std::size_t j = 0; j < m.seeds.size(); ++j) m.seed_id.emplace(m.seeds[j], n + splits.size() + j);
  Domain2 refined;
  if constexpr (D == 2)
    if (m.refinement) refined = m.refinement->refined();
  const auto points = m.set->points();
  m.mesh.emplace(well_spaced_mesh<D>(points, m.set->input_count(), refined, m.set->box(), options.keep_hull));
}

template <int D>
ShoreSession<D>::~ShoreSession() = default;
template <int D>
ShoreSession<D>::ShoreSession(ShoreSession&&) noexcept = default;
template <int D>
ShoreSession<D>& ShoreSession<D>::operator=(ShoreSession&&) noexcept = default;

template <int D>
SessionEdit<D> ShoreSession<D>::add(const Point<D>& p) {
  Impl& m = *impl_;
  m.check_in_box(p);
  SessionEdit<D> out;
  const auto start = Clock::now();
  std::vector<Point<D>> removed, added{p};
  const auto ids = m.apply_edits({{Edit<D>::Kind::Add, 0, p}}, nullptr, nullptr, {}, {p}, removed, added, out.engine);
  out.id = m.engine_of_user.size();
  m.engine_of_user.push_back(ids.at(0));
  m.update_mesh(std::move(removed), std::move(added), start, start, out);
  return out;
}

template <int D>
SessionEdit<D> ShoreSession<D>::add_after(std::size_t after, const Point<D>& p) {
  Impl& m = *impl_;
  if constexpr (D != 2) throw InputError("a point after another is a shoreline edit, for 2D sessions");
  check_id(after);
  m.check_in_box(p);
  const auto edit_start = Clock::now();
  auto rings = m.vertex_change(RingVertexEdit::Kind::Insert, after, p);
  if (!rings)
    throw InputError("input point " + std::to_string(after) +
                     " is on no shoreline (a loose point); a point after it would be on none either");
  SessionEdit<D> out;
  const auto start = Clock::now();
  std::vector<Point<D>> removed, added{p};
  const auto ids = m.apply_vertex_edits({{Edit<D>::Kind::Add, 0, p}}, rings, {}, {}, removed, added, out.engine);
  out.id = m.engine_of_user.size();
  out.ring = rings->ring;
  m.engine_of_user.push_back(ids.at(0));
  m.commit_vertex_ids(*rings, RingVertexEdit::Kind::Insert, out.id);
  m.commit_index(*rings);
  m.update_mesh(std::move(removed), std::move(added), edit_start, start, out);
  return out;
}

template <int D>
SessionEdit<D> ShoreSession<D>::move(std::size_t id, const Point<D>& p) {
  Impl& m = *impl_;
  check_id(id);
  m.check_in_box(p);
  const Point<D> old = m.set->input_point(m.engine_id(id));
  const auto edit_start = Clock::now();
  auto rings = m.vertex_change(RingVertexEdit::Kind::Move, id, p);
  SessionEdit<D> out;
  out.id = id;
  const auto start = Clock::now();
  std::vector<Point<D>> removed{old}, added{p};
  m.apply_vertex_edits({{Edit<D>::Kind::Move, m.engine_id(id), p}}, rings,
                       rings ? std::vector<Point<D>>{} : std::vector<Point<D>>{old},
                       rings ? std::vector<Point<D>>{} : std::vector<Point<D>>{p}, removed, added, out.engine);
  if (rings) {
    out.ring = rings->ring;
    m.commit_index(*rings);
    if constexpr (D == 2)
      if (m.rings_now.rings[rings->ring].closed()) {
        m.vertex_id.erase(old);
        m.vertex_id[p] = id;
      }
  }
  m.update_mesh(std::move(removed), std::move(added), edit_start, start, out);
  return out;
}

template <int D>
SessionEdit<D> ShoreSession<D>::remove(std::size_t id) {
  Impl& m = *impl_;
  check_id(id);
  const Point<D> old = m.set->input_point(m.engine_id(id));
  const auto edit_start = Clock::now();
  auto rings = m.vertex_change(RingVertexEdit::Kind::Remove, id, old);
  SessionEdit<D> out;
  out.id = id;
  const auto start = Clock::now();
  std::vector<Point<D>> removed{old}, added;
  m.apply_vertex_edits({{Edit<D>::Kind::Remove, m.engine_id(id), {}}}, rings,
                       rings ? std::vector<Point<D>>{} : std::vector<Point<D>>{old}, {}, removed, added, out.engine);
  m.engine_of_user[id] = Impl::kRemoved;
  if (rings) {
    out.ring = rings->ring;
    m.commit_vertex_ids(*rings, RingVertexEdit::Kind::Remove, id);
    m.commit_index(*rings);
  }
  m.update_mesh(std::move(removed), std::move(added), edit_start, start, out);
  return out;
}

template <int D>
SessionEdit<D> ShoreSession<D>::add_ring(std::span<const Point2> points, bool line) {
  Impl& m = *impl_;
  if constexpr (D != 2) {
    (void)points;
    throw InputError("rings are for 2D sessions");
  } else {
    if (!m.refinement) throw InputError("this session has no shoreline: a ring needs rings to join");
    const std::size_t r = m.ring_ids.size();
    const std::string what = std::string("the new ") + (line ? "line" : "ring") + " (ring " + std::to_string(r + 1) + ")";
    // A line's end may be a closed ring's vertex (a jetty on the shore): that point is shared, not new.
    std::vector<std::optional<std::size_t>> shared(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      m.check_in_box(points[k]);
      const bool end = line && (k == 0 || k + 1 == points.size());
      if (const auto it = m.vertex_id.find(points[k]); end && it != m.vertex_id.end()) shared[k] = it->second;
      else m.refuse_vertex_at(points[k], what);
    }
    const auto edit_start = Clock::now();
    Domain2& after = m.rings_now;
    after.rings.resize(r);
    after.rings.push_back({std::vector<Point2>(points.begin(), points.end()), line ? RingRole::Line : RingRole::Shore});
    if (const auto defect = m.ring_index->defect_of_new_ring(after, r)) {
      after.rings.resize(r);
      throw InputError(what + " would break the shoreline: " + defect->describe());
    }
    // A ring's role from its nesting: inside an odd number of rings it bounds land (an island).
    if (!line) after.rings[r].role = m.ring_index->inside(points.front()) ? RingRole::Island : RingRole::Shore;
    const RingStretch stretch{r, 0, 0, after.rings[r].points, true, after.rings[r].role};
    const RingStretch undo{r, 0, 0, {}, true, after.rings[r].role};
    SessionEdit<D> out;
    const auto start = Clock::now();
    std::vector<Edit<D>> edits;
    std::vector<Point<D>> removed, added;
    for (std::size_t k = 0; k < points.size(); ++k)
      if (!shared[k]) {
        edits.push_back({Edit<D>::Kind::Add, 0, points[k]});
        added.push_back(points[k]);
      }
    std::vector<std::size_t> ids;
    try {
      ids = m.apply_edits(std::move(edits), &stretch, &undo, {}, {}, removed, added, out.engine);
    } catch (...) {
      after.rings.resize(r);
      throw;
    }
    std::vector<std::size_t> user_ids;
    for (std::size_t k = 0, j = 0; k < points.size(); ++k) {
      if (shared[k]) {
        user_ids.push_back(*shared[k]);
        m.shared_by[*shared[k]].push_back(r);
        continue;
      }
      const std::size_t id = m.engine_of_user.size();
      m.engine_of_user.push_back(ids[j++]);
      m.ring_of[id] = {r, k};
      if (!line) m.vertex_id[points[k]] = id;
      user_ids.push_back(id);
    }
    m.ring_ids.push_back(user_ids);
    m.ring_index->insert_ring(r, after.rings[r]);
    out.id = user_ids.front();
    out.ring = r;
    out.ring_ids = std::move(user_ids);
    m.update_mesh(std::move(removed), std::move(added), edit_start, start, out);
    return out;
  }
}

template <int D>
SessionEdit<D> ShoreSession<D>::remove_ring(std::size_t r) {
  Impl& m = *impl_;
  if constexpr (D != 2) {
    (void)r;
    throw InputError("rings are for 2D sessions");
  } else {
    if (!m.refinement) throw InputError("this session has no shoreline");
    if (r >= m.ring_ids.size()) throw InputError("no ring " + std::to_string(r + 1) + " (rings 1.." + std::to_string(m.ring_ids.size()) + ")");
    if (m.ring_ids[r].empty()) throw InputError("ring " + std::to_string(r + 1) + " was removed");
    if (m.refinement->rings().rings[r].closed() && m.live_closed_rings() == 1)
      throw InputError("ring " + std::to_string(r + 1) + " is the last ring; without one the water is undefined");
    // Its vertices that other rings share too stay (they are the other rings'), unless it holds them first.
    for (std::size_t id : m.ring_ids[r])
      if (m.ring_of.at(id).first == r) m.refuse_shared_end(id, "removing " + m.ring_name(r));
    // The water flips inside a closed ring that goes: a line there would be left on land.
    if (m.refinement->rings().rings[r].closed())
      for (std::size_t l = 0; l < m.ring_ids.size(); ++l) {
        const Ring& line = m.refinement->rings().rings[l];
        if (!line.closed() && !line.points.empty() && ring_contains(m.refinement->rings().rings[r].points, line.points.front()))
          throw InputError("removing ring " + std::to_string(r + 1) + " would leave line " + std::to_string(l + 1) +
                           " on land; remove the line first");
      }
    const auto edit_start = Clock::now();
    const Ring gone_ring = m.rings_now.rings[r];
    const std::vector<Point2>& gone = gone_ring.points;
    m.rings_now.rings[r].points.clear();
    const RingStretch stretch{r, 0, 0, {}, true, gone_ring.role};
    const RingStretch undo{r, 0, 0, gone, true, gone_ring.role};
    SessionEdit<D> out;
    out.ring = r;
    out.id = m.ring_ids[r].front();
    const auto start = Clock::now();
    // A line's end on a ring stays: it is the ring's vertex.
    const bool closed = gone_ring.closed();
    auto kept = [&](std::size_t id) { return m.ring_of.at(id).first != r; };
    std::vector<Edit<D>> edits;
    std::vector<Point<D>> removed, added;
    for (std::size_t k = 0; k < gone.size(); ++k)
      if (!kept(m.ring_ids[r][k])) {
        edits.push_back({Edit<D>::Kind::Remove, m.engine_id(m.ring_ids[r][k]), {}});
        removed.push_back(gone[k]);
      }
    try {
      m.apply_edits(std::move(edits), &stretch, &undo, {}, {}, removed, added, out.engine);
    } catch (...) {
      m.rings_now.rings[r] = gone_ring;
      throw;
    }
    for (std::size_t k = 0; k < gone.size(); ++k) {
      const std::size_t id = m.ring_ids[r][k];
      if (kept(id)) {
        std::erase(m.shared_by.at(id), r);
        continue;
      }
      m.engine_of_user[id] = Impl::kRemoved;
      m.ring_of.erase(id);
      if (closed) m.vertex_id.erase(gone[k]);
    }
    out.ring_ids = std::move(m.ring_ids[r]);
    m.ring_ids[r].clear();
    m.ring_index->erase_ring(r, gone_ring);
    m.update_mesh(std::move(removed), std::move(added), edit_start, start, out);
    return out;
  }
}

template <int D>
SessionEdit<D> ShoreSession<D>::set_polygon_size(std::size_t polygon, double size) {
  Impl& m = *impl_;
  if constexpr (D != 2) {
    (void)polygon, (void)size;
    throw InputError("size control is for 2D sessions");
  } else {
    if (!m.size || m.size->terms().polygons.empty())
      throw InputError("this session has no size polygons (--size-polygons FILE.geojson)");
    const auto edit_start = Clock::now();
    SizeUndo undo;
    const SizeChange change = m.size_field().set_polygon_size(polygon, size, &undo);
    SessionEdit<D> out;
    out.id = polygon;
    const auto start = Clock::now();
    std::vector<Point<D>> removed, added;
    m.shore_change.reset();
    m.apply_sized({}, nullptr, nullptr, {}, {}, change, &undo, removed, added, out.engine);
    m.update_mesh(std::move(removed), std::move(added), edit_start, start, out);
    return out;
  }
}

template <int D>
std::size_t ShoreSession<D>::seed_count() const { return impl_->seed_id.size(); }
template <int D>
const SizeField* ShoreSession<D>::size_field() const { return impl_->size.get(); }

template <int D>
const Mesh<D>& ShoreSession<D>::mesh() const { return *impl_->mesh; }
template <int D>
const BoxTransform<D>& ShoreSession<D>::box() const { return impl_->set->box(); }
template <int D>
double ShoreSession<D>::rho() const { return impl_->options.rho; }
template <int D>
bool ShoreSession<D>::has_rings() const { return impl_->refinement.has_value(); }

template <int D>
bool ShoreSession<D>::contains(std::size_t id) const {
  return id < impl_->engine_of_user.size() && impl_->engine_of_user[id] != Impl::kRemoved;
}

template <int D>
void ShoreSession<D>::check_id(std::size_t id) const {
  if (contains(id)) return;
  const std::size_t next = next_id();
  if (id < next) throw InputError("input point " + std::to_string(id) + " was removed");
  throw InputError("no input point " + std::to_string(id) +
                   (next ? " (ids so far: 0.." + std::to_string(next - 1) + ")" : std::string(" (no ids yet)")));
}

template <int D>
Point<D> ShoreSession<D>::input_point(std::size_t id) const {
  check_id(id);
  return impl_->set->input_point(impl_->engine_id(id));
}

template <int D>
std::optional<std::pair<std::size_t, std::size_t>> ShoreSession<D>::ring_of(std::size_t id) const {
  const auto it = impl_->ring_of.find(id);
  if (it == impl_->ring_of.end()) return std::nullopt;
  if (contains(id)) return impl_->locate(id);
  return it->second;
}

template <int D>
std::size_t ShoreSession<D>::next_id() const { return impl_->engine_of_user.size(); }
template <int D>
std::size_t ShoreSession<D>::input_count() const {
  return impl_->set->input_count() - impl_->split_id.size() - impl_->seed_id.size();
}
template <int D>
std::size_t ShoreSession<D>::split_count() const { return impl_->split_id.size(); }
template <int D>
std::size_t ShoreSession<D>::steiner_count() const { return impl_->set->steiner_count(); }

template <int D>
Domain2 ShoreSession<D>::rings() const {
  Domain2 out;
  if (impl_->refinement)
    for (const Ring& r : impl_->refinement->rings().rings)
      if (!r.points.empty()) out.rings.push_back(r);
  return out;
}

template <int D>
std::size_t ShoreSession<D>::ring_count() const { return impl_->ring_ids.size(); }

template <int D>
const std::vector<Point2>& ShoreSession<D>::ring(std::size_t r) const {
  if (!impl_->refinement || r >= impl_->refinement->rings().rings.size())
    throw InputError("no ring " + std::to_string(r + 1));
  return impl_->refinement->rings().rings[r].points;
}

template <int D>
RingRole ShoreSession<D>::ring_role(std::size_t r) const {
  if (!impl_->refinement || r >= impl_->refinement->rings().rings.size())
    throw InputError("no ring " + std::to_string(r + 1));
  return impl_->refinement->rings().rings[r].role;
}

template <int D>
const Domain2& ShoreSession<D>::refined_rings() const { return impl_->mesh->domain(); }

template <int D>
std::vector<Point<D>> ShoreSession<D>::canonical_points() const {
  const Impl& m = *impl_;
  const std::vector<Point<D>> all = m.set->points();
  std::vector<Point<D>> out;
  out.reserve(all.size());
  for (std::size_t eid : m.engine_of_user)
    if (eid != Impl::kRemoved) out.push_back(m.set->input_point(eid));
  if constexpr (D == 2)
    if (m.refinement)
      for (const Point2& p : m.refinement->split_points()) out.push_back(p);
  if constexpr (D == 2) out.insert(out.end(), m.seeds.begin(), m.seeds.end());
  out.insert(out.end(), all.begin() + static_cast<std::ptrdiff_t>(m.set->input_count()), all.end());
  return out;
}

template <int D>
SessionInput<D> ShoreSession<D>::current_input() const {
  const Impl& m = *impl_;
  SessionInput<D> in;
  std::vector<std::size_t> renumbered(m.engine_of_user.size(), Impl::kRemoved);
  for (std::size_t id = 0; id < m.engine_of_user.size(); ++id)
    if (m.engine_of_user[id] != Impl::kRemoved) {
      renumbered[id] = in.points.size();
      in.points.push_back(m.set->input_point(m.engine_of_user[id]));
    }
  if constexpr (D == 2) {
    // Rings as runs of ids: a fresh run reads each ring's points in ring order, so the points move
    // there: ring vertices first (ring by ring), then the loose points, each group in id order.
    if (m.refinement) {
      SessionInput<D> ringed;
      std::vector<bool> on_ring(m.engine_of_user.size(), false);
      std::vector<std::size_t> placed(m.engine_of_user.size(), Impl::kRemoved);
      for (std::size_t r = 0; r < m.ring_ids.size(); ++r) {
        if (m.ring_ids[r].empty()) continue;
        Ring ring{{}, m.refinement->rings().rings[r].role};
        std::vector<std::size_t> ids;
        for (std::size_t id : m.ring_ids[r]) {
          ring.points.push_back(in.points[renumbered[id]]);
          if (!on_ring[id]) {  // a line's end on a ring is one point, the ring's
            on_ring[id] = true;
            placed[id] = ringed.points.size();
            ringed.points.push_back(ring.points.back());
          }
          ids.push_back(placed[id]);
        }
        ringed.ring_ids.push_back(std::move(ids));
        ringed.rings.rings.push_back(std::move(ring));
      }
      for (std::size_t id = 0; id < m.engine_of_user.size(); ++id)
        if (renumbered[id] != Impl::kRemoved && !on_ring[id]) ringed.points.push_back(in.points[renumbered[id]]);
      return ringed;
    }
  }
  return in;
}

template <int D>
ShorelineStatus ShoreSession<D>::shoreline() const {
  ShorelineStatus s;
  if constexpr (D == 2) {
    if (!impl_->refinement) return s;
    const ShorelineReport r = impl_->mesh->shoreline_crossings();
    s.segments = r.segments;
    s.covered = r.covered;
    s.splits = split_count();
  }
  return s;
}

template Parameters<2> session_parameters<2>(double);
template Parameters<3> session_parameters<3>(double);
template Mesh<2> well_spaced_mesh<2>(std::span<const Point<2>>, std::size_t, const Domain2&, const BoxTransform<2>&, bool);
template Mesh<3> well_spaced_mesh<3>(std::span<const Point<3>>, std::size_t, const Domain2&, const BoxTransform<3>&, bool);
template class ShoreSession<2>;
template class ShoreSession<3>;

}  // namespace shoremesh
