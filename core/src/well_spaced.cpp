#include "shoremesh/well_spaced.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "shoremesh/domain.hpp"
#include "shoremesh/engine/engine.hpp"
#include "shoremesh/error.hpp"

namespace shoremesh {

template <int D>
WellSpacedSet<D>::WellSpacedSet(const Parameters<D>& parameters)
    : engine_(std::make_unique<WellSpacedEngine<D>>(parameters)) {}
template <int D>
WellSpacedSet<D>::~WellSpacedSet() = default;
template <int D>
WellSpacedSet<D>::WellSpacedSet(WellSpacedSet&&) noexcept = default;
template <int D>
WellSpacedSet<D>& WellSpacedSet<D>::operator=(WellSpacedSet&&) noexcept = default;

template <int D>
void WellSpacedSet<D>::build(std::span<const Point<D>> unit_points, BuildFor purpose) {
  bind_inputs(engine_->build(unit_points, purpose == BuildFor::Updates), purpose);
}

template <int D>
void WellSpacedSet<D>::build(std::vector<Point<D>>&& unit_points, BuildFor purpose) {
  bind_inputs(engine_->build(std::move(unit_points), purpose == BuildFor::Updates), purpose);
}

template <int D>
void WellSpacedSet<D>::bind_inputs(std::vector<std::uint32_t> vertex_of_point, BuildFor purpose) {
  if (purpose == BuildFor::OutputOnly) {
    // Nothing will be edited: no vertex -> id map (8 bytes per output vertex, allocated while the
    // engine is at its largest) and no room to grow.
    input_vertex_ = std::move(vertex_of_point);
    return;
  }
  // Both arrays get room to grow. Each add takes a new id, and a vertex numbered past the end of
  // input_id_ made it copy itself whole in the middle of that update: 51 ms at 2D n = 1e6, after about
  // 3,600 changes (bench/RESULTS.md). Room never written takes no physical memory.
  const std::size_t n = vertex_of_point.size();
  input_vertex_.reserve(n + n / 2 + 1024);
  input_vertex_.assign(vertex_of_point.begin(), vertex_of_point.end());
  input_id_.reserve(engine_->vertex_count() + engine_->vertex_count() / 2 + 1024);
  input_id_.resize(engine_->vertex_count());  // Steiner vertices may be numbered among the inputs
  for (std::size_t i = 0; i < n; ++i) input_id_[vertex_of_point[i]] = i;
}

template <int D>
std::uint32_t WellSpacedSet<D>::vertex_of(std::size_t id) const {
  if (id >= input_vertex_.size() || input_vertex_[id] == engine::kNoVertex)
    throw InputError("no input point has id " + std::to_string(id));
  return input_vertex_[id];
}

template <int D>
bool WellSpacedSet<D>::has_input(std::size_t id) const {
  return id < input_vertex_.size() && input_vertex_[id] != engine::kNoVertex;
}

template <int D>
Point<D> WellSpacedSet<D>::input_point(std::size_t id) const {
  return engine_->positions()[vertex_of(id)];
}

template <int D>
std::vector<std::size_t> WellSpacedSet<D>::input_ids() const {
  std::vector<std::size_t> ids;
  for (std::size_t id = 0; id < input_vertex_.size(); ++id)
    if (input_vertex_[id] != engine::kNoVertex) ids.push_back(id);
  return ids;
}

// A point may join the input if it is finite, in the box, not an input point already (unless that one
// is being removed in the same batch) and not closer to one than the quadtree's resolution allows.
template <int D>
void WellSpacedSet<D>::check_new_point(const Point<D>& p, std::span<const std::size_t> removed_ids,
                                       std::span<const Point<D>> added) const {
  for (int i = 0; i < D; ++i) {
    if (!std::isfinite(p[i])) throw InputError("the point has a coordinate that is not a finite number");
    if (p[i] < 0 || p[i] > 1) throw InputError("the point lies outside the box");
  }
  for (const auto& q : added)
    if (q == p) throw InputError("the same point is added twice");
  const double resolution = 0x1p-36;  // inputs closer than this would need quadtree levels beyond 40
  const auto& tree = engine_->quadtree();
  using Box = typename engine::Quadtree<D>::Box;
  Box box;
  for (int i = 0; i < D; ++i) {
    box.lo[i] = p[i] - resolution;
    box.hi[i] = p[i] + resolution;
  }
  tree.for_each_occupied_leaf(box, Box::empty(), [&](engine::NodeId n, auto) {
    const auto v = tree.node(n).input_vertex;
    if (v == engine::kNoVertex) return;
    const std::size_t id = input_id_[v];
    if (std::find(removed_ids.begin(), removed_ids.end(), id) != removed_ids.end()) return;
    const auto& q = engine_->positions()[v];
    double d = 0;
    for (int i = 0; i < D; ++i) d = std::max(d, std::abs(q[i] - p[i]));
    if (d == 0) throw InputError("the point equals input point " + std::to_string(id));
    if (d < resolution)
      throw InputError("the point is closer to input point " + std::to_string(id) +
                       " than the engine's resolution (2^-36 of the box side)");
  });
}

template <int D>
std::vector<std::size_t> WellSpacedSet<D>::apply(std::span<const Edit<D>> edits, UpdateReport<D>* report,
                                                 std::span<const engine::WaterEdit> water) {
  if (!engine_->updatable()) throw std::logic_error("the set was built for its output only: it cannot be updated");
  // Check everything first, in order, as if applied one by one: an error leaves the set untouched.
  std::vector<std::size_t> removed;
  std::vector<Point<D>> added;
  std::size_t live = input_count();
  std::size_t next_id = input_vertex_.size();
  auto alive = [&](std::size_t id) {
    return (has_input(id) && std::find(removed.begin(), removed.end(), id) == removed.end()) ||
           (id >= input_vertex_.size() && id < next_id);
  };
  for (std::size_t k = 0; k < edits.size(); ++k) {
    const Edit<D>& e = edits[k];
    try {
      if (e.kind != Edit<D>::Kind::Add) {
        if (!alive(e.id)) throw InputError("no input point has id " + std::to_string(e.id));
        if (e.id >= input_vertex_.size())
          throw InputError("point " + std::to_string(e.id) + " was added in the same batch: edit it in the next one");
      }
      if (e.kind == Edit<D>::Kind::Remove && live == 1) throw InputError("the last input point cannot be removed");
      if (e.kind != Edit<D>::Kind::Add) removed.push_back(e.id);
      if (e.kind != Edit<D>::Kind::Remove) check_new_point(e.point, removed, added);
      if (e.kind != Edit<D>::Kind::Remove) added.push_back(e.point);
      if (e.kind == Edit<D>::Kind::Add) ++live, ++next_id;
      if (e.kind == Edit<D>::Kind::Remove) --live;
    } catch (const InputError& err) {
      if (edits.size() == 1) throw;
      throw InputError("edit " + std::to_string(k + 1) + ": " + err.message());
    }
  }
  // Removals first (a move is a removal and an addition), then the additions in order.
  using InputEdit = typename WellSpacedEngine<D>::InputEdit;
  std::vector<InputEdit> engine_edits;
  for (const Edit<D>& e : edits)
    if (e.kind != Edit<D>::Kind::Add) engine_edits.push_back(InputEdit{false, {}, input_vertex_[e.id]});
  for (const Edit<D>& e : edits)
    if (e.kind != Edit<D>::Kind::Remove) engine_edits.push_back(InputEdit{true, e.point, engine::kNoVertex});
  typename WellSpacedEngine<D>::PropagationStats stats;
  const auto vertices = engine_->apply(engine_edits, &stats, water);
  std::vector<std::size_t> new_ids;
  std::size_t k = 0;
  auto bind = [&](std::size_t id, std::uint32_t v) {
    if (input_id_.size() <= v) input_id_.resize(engine_->vertex_count());
    input_id_[v] = id;
  };
  for (const Edit<D>& e : edits) {
    if (e.kind == Edit<D>::Kind::Remove) input_vertex_[e.id] = engine::kNoVertex;
    else if (e.kind == Edit<D>::Kind::Move) {
      input_vertex_[e.id] = vertices[k++];
      bind(e.id, input_vertex_[e.id]);
    } else {
      new_ids.push_back(input_vertex_.size());
      input_vertex_.push_back(vertices[k++]);
      bind(new_ids.back(), input_vertex_.back());
    }
  }
  if (report) {
    report->steiner_removed = std::move(stats.steiner_removed);
    report->steiner_added = std::move(stats.steiner_added);
    report->operations_undone = stats.undone;
    report->operations_executed = stats.executed;
  }
  return new_ids;
}

template <int D>
std::size_t WellSpacedSet<D>::add(const Point<D>& unit_point, UpdateReport<D>* report) {
  const Edit<D> e{Edit<D>::Kind::Add, 0, unit_point};
  return apply(std::span<const Edit<D>>(&e, 1), report).front();
}

template <int D>
void WellSpacedSet<D>::remove(std::size_t id, UpdateReport<D>* report) {
  const Edit<D> e{Edit<D>::Kind::Remove, id, {}};
  apply(std::span<const Edit<D>>(&e, 1), report);
}

template <int D>
void WellSpacedSet<D>::move(std::size_t id, const Point<D>& unit_point, UpdateReport<D>* report) {
  const Edit<D> e{Edit<D>::Kind::Move, id, unit_point};
  apply(std::span<const Edit<D>>(&e, 1), report);
}
template <int D>
std::size_t WellSpacedSet<D>::input_count() const {
  return engine_->input_count();
}
template <int D>
std::size_t WellSpacedSet<D>::steiner_count() const {
  return engine_->live_vertex_count() - engine_->input_count();
}
template <int D>
std::vector<Point<D>> WellSpacedSet<D>::output_points() const {
  const auto all = engine_->positions();
  std::vector<Point<D>> out;
  out.reserve(input_count() + steiner_count());
  for (std::uint32_t v : input_vertex_)
    if (v != engine::kNoVertex) out.push_back(all[v]);
  append_steiner_points(out);
  return out;
}

template <int D>
void WellSpacedSet<D>::append_steiner_points(std::vector<Point<D>>& out) const {
  const auto all = engine_->positions();
  const std::size_t before = out.size();
  for (engine::VertexId v = 0; v < all.size(); ++v)
    if (engine_->vertex(v).alive && !engine_->vertex(v).is_input) out.push_back(all[v]);
  std::sort(out.begin() + long(before), out.end());
}
template <int D>
const Counters& WellSpacedSet<D>::counters() const {
  return engine_->counters();
}
template <int D>
std::size_t WellSpacedSet<D>::memory_bytes() const {
  return engine_->memory_bytes();
}
template <int D>
void WellSpacedSet<D>::check_valid() const {
  engine_->check_valid();
}
template <int D>
WellSpacedEngine<D>& WellSpacedSet<D>::engine() {
  return *engine_;
}
template <int D>
const WellSpacedEngine<D>& WellSpacedSet<D>::engine() const {
  return *engine_;
}

// The static entry point is the dynamic set, built once: one place checks the input and maps the box.
template <int D>
StableResult<D> stable_well_spaced(std::span<const Point<D>> user_points, const Parameters<D>& parameters,
                                   std::optional<BoxTransform<D>> box, const Domain2* water) {
  WaterSource source;
  if (water) source = [water] { return water; };
  const DynamicWellSpaced<D> dynamic(user_points, parameters, box, BuildFor::OutputOnly, std::move(source));
  StableResult<D> result;
  result.box = dynamic.box();
  result.points = dynamic.points();
  result.input_count = user_points.size();
  result.counters = dynamic.set().counters();
  result.memory_bytes = dynamic.set().memory_bytes();
  return result;
}

template <int D>
DynamicWellSpaced<D>::DynamicWellSpaced(std::span<const Point<D>> user_points, const Parameters<D>& parameters,
                                        std::optional<BoxTransform<D>> box, BuildFor purpose, WaterSource water)
    : water_(std::move(water)), set_(parameters) {
  if (user_points.empty()) throw InputError("no input points");
  for (std::size_t i = 0; i < user_points.size(); ++i)
    for (int k = 0; k < D; ++k)
      if (!std::isfinite(user_points[i][k]))
        throw PointInputError("point " + std::to_string(i) + " has a coordinate that is not a finite number", {i});
  // Coordinates and box sides the engine and the measures after it can represent: squared distances and
  // areas in the user's units must stay finite and above the smallest normal double.
  for (std::size_t i = 0; i < user_points.size(); ++i)
    for (int k = 0; k < D; ++k)
      if (std::abs(user_points[i][k]) > kLargestCoordinate)
        throw PointInputError("point " + std::to_string(i) + " has a coordinate of " + readable(user_points[i][k]) +
                                  ", beyond the largest the engine represents (" + readable(kLargestCoordinate) + ")",
                              {i});
  if (box) {
    if (!(box->side > 0) || !std::isfinite(box->side)) throw InputError("the box side must be a positive number");
    if (box->side < kSmallestSide || box->side > 2 * kLargestCoordinate)
      throw InputError("the box side " + readable(box->side) + " is outside what the engine represents (" +
                       readable(kSmallestSide) + " to " + readable(2 * kLargestCoordinate) + ")");
    for (std::size_t i = 0; i < user_points.size(); ++i)
      if (!box->contains(user_points[i]))
        throw PointInputError("point " + std::to_string(i) + " lies outside the given box", {i});
  }
  box_ = box ? *box : BoxTransform<D>::fit(user_points);  // a fitted box holds every point
  // About the points as a whole (no index): the caller names the files they came from.
  if (box_.side < kSmallestSide)
    throw PointInputError("the input points span " + readable(box_.side / 1.1) +
                              ", less than the smallest extent the engine represents (" + readable(kSmallestSide) +
                              "): give them in a smaller unit",
                          {});
  std::vector<Point<D>> unit(user_points.size());
  for (std::size_t i = 0; i < unit.size(); ++i) unit[i] = box_.to_unit(user_points[i]);
  if constexpr (D == 2) {
    water_rings_ = water_now();
    if (std::any_of(water_rings_.begin(), water_rings_.end(), [](const auto& r) { return !r.empty(); })) {
      std::vector<std::vector<Point2>> rings(water_rings_.size());
      for (std::size_t r = 0; r < rings.size(); ++r) {
        rings[r].reserve(water_rings_[r].size());
        for (const Point2& p : water_rings_[r]) rings[r].push_back(box_.to_unit(p));
      }
      set_.engine().set_water(std::move(rings));
    }
    // Only edits compare the rings with this copy.
    if (purpose == BuildFor::OutputOnly) std::vector<std::vector<Point2>>().swap(water_rings_);
  }
  set_.build(std::move(unit), purpose);
  user_inputs_.assign(user_points.begin(), user_points.end());
}

template <int D>
Point<D> DynamicWellSpaced<D>::to_unit_checked(const Point<D>& p) const {
  for (int i = 0; i < D; ++i)
    if (!std::isfinite(p[i])) throw InputError("the point has a coordinate that is not a finite number");
  if (!box_.contains(p)) {
    std::string where, lo, hi;
    for (int i = 0; i < D; ++i) {
      for (std::string* s : {&where, &lo, &hi})
        if (i) s->append(", ");
      where.append(readable(p[i]));
      lo.append(readable(box_.origin[i]));
      hi.append(readable(box_.origin[i] + box_.side));
    }
    throw InputError("the point (" + where + ") lies outside the box (" + lo + ") .. (" + hi + ")");
  }
  return box_.to_unit(p);
}

template <int D>
void DynamicWellSpaced<D>::to_user(UpdateReport<D>* report) const {
  if (!report) return;
  for (auto& p : report->steiner_removed) p = box_.to_user(p);
  for (auto& p : report->steiner_added) p = box_.to_user(p);
}

template <int D>
std::vector<std::vector<Point<2>>> DynamicWellSpaced<D>::water_now() const {
  std::vector<std::vector<Point<2>>> out;
  const Domain2* domain = water_ ? water_() : nullptr;
  if (!domain) return out;
  out.resize(domain->rings.size());
  for (std::size_t r = 0; r < out.size(); ++r) {
    const Ring& ring = domain->rings[r];
    if (ring.closed() && ring.points.size() >= 3) out[r] = ring.points;
  }
  return out;
}

namespace {

// The open chains of one ring's edit: the edges from the vertex kept before the stretch, through its old
// (new) points, to the vertex kept after it, where `ring` is the ring after the edit, the stretch
// `before` -> `after` between its first `prefix` and last `suffix` points. Points the old and new
// stretch share at either end stay (their edges are unchanged): the chains are the edges that changed,
// as the longest common prefix and suffix of the old and new ring give them. Both empty when nothing
// changed; nullopt when no vertex stays (the ring changed as a whole).
using Chains = std::pair<std::vector<Point2>, std::vector<Point2>>;
std::optional<Chains> stretch_chains(const std::vector<Point2>& ring, std::size_t prefix, std::size_t suffix,
                                     std::span<const Point2> before, std::span<const Point2> after) {
  std::size_t a = 0, b = 0;
  const std::size_t m = std::min(before.size(), after.size());
  while (a < m && before[a] == after[a]) ++a;
  while (a + b < m && before[before.size() - 1 - b] == after[after.size() - 1 - b]) ++b;
  if (a == before.size() && a == after.size()) return Chains{};
  prefix += a;
  suffix += b;
  if (prefix + suffix == 0) return std::nullopt;
  const std::size_t n = ring.size();
  const Point2& from = prefix > 0 ? ring[prefix - 1] : ring[n - 1];
  const Point2& to = suffix > 0 ? ring[n - suffix] : ring[0];
  Chains out;
  for (auto [chain, middle] : {std::pair{&out.first, before.subspan(a, before.size() - a - b)},
                               std::pair{&out.second, after.subspan(a, after.size() - a - b)}}) {
    chain->reserve(middle.size() + 2);
    chain->push_back(from);
    chain->insert(chain->end(), middle.begin(), middle.end());
    chain->push_back(to);
  }
  return out;
}

// Ring `ring` had `before` between its first `prefix` and last `suffix` points and has `after` there now.
void replace_stretch(std::vector<Point2>& ring, std::size_t prefix, std::size_t suffix, std::span<const Point2> after) {
  const auto first = ring.begin() + static_cast<std::ptrdiff_t>(prefix);
  const auto last = ring.end() - static_cast<std::ptrdiff_t>(suffix);
  ring.insert(ring.erase(first, last), after.begin(), after.end());
}

constexpr std::size_t kPendingStretches = 4096;  // then the copy is refreshed: O(shore) per that many edits

}  // namespace

template <int D>
std::optional<engine::WaterEdit> DynamicWellSpaced<D>::water_edit(const Domain2& domain, const WaterStretch& s) const {
  if constexpr (D != 2) {
    (void)domain, (void)s;
    return std::nullopt;
  } else {
    const Ring& ring = domain.rings.at(s.ring);
    if (!ring.closed()) return std::nullopt;  // a line bounds no water
    engine::WaterEdit edit;
    auto to_unit = [&](std::span<const Point2> chain, std::vector<Point2>& out) {
      out.reserve(chain.size());
      for (const Point2& p : chain) out.push_back(box_.to_unit(p));
    };
    const std::size_t n = ring.points.size(), old_n = n - s.after.size() + s.before.size();
    std::optional<Chains> chains;
    if (!s.whole && n >= 3 && old_n >= 3) chains = stretch_chains(ring.points, s.prefix, s.suffix, s.before, s.after);
    if (!chains) {
      // A whole ring went and came (a ring with fewer than 3 points bounds nothing and has no edge).
      std::vector<Point2> old_ring;
      if (s.whole) {
        old_ring.assign(s.before.begin(), s.before.end());
      } else {
        old_ring.assign(ring.points.begin(), ring.points.begin() + static_cast<std::ptrdiff_t>(s.prefix));
        old_ring.insert(old_ring.end(), s.before.begin(), s.before.end());
        old_ring.insert(old_ring.end(), ring.points.end() - static_cast<std::ptrdiff_t>(s.suffix), ring.points.end());
      }
      if (old_ring == ring.points) return std::nullopt;
      edit.cyclic = true;
      if (old_ring.size() >= 3) to_unit(old_ring, edit.gone);
      if (n >= 3) to_unit(ring.points, edit.came);
      return edit;
    }
    if (chains->first.empty()) return std::nullopt;
    to_unit(chains->first, edit.gone);
    to_unit(chains->second, edit.came);
    return edit;
  }
}

// The rings as the source has them now against those the engine has: O(ring points) comparisons, a few
// hundred microseconds at 200k shore points, and only the changed stretches mapped to the unit box.
template <int D>
std::vector<engine::WaterEdit> DynamicWellSpaced<D>::water_changes(
    std::vector<std::pair<std::size_t, std::vector<Point<2>>>>& user) {
  std::vector<engine::WaterEdit> out;
  user.clear();
  if constexpr (D != 2) {
    return out;
  } else {
    if (!set_.engine().water()) return out;
    for (const PendingStretch& s : water_pending_) {  // the copy catches up with the engine
      if (water_rings_.size() <= s.ring) water_rings_.resize(s.ring + 1);
      if (s.whole) water_rings_[s.ring] = s.after;
      else replace_stretch(water_rings_[s.ring], s.prefix, s.suffix, s.after);
    }
    water_pending_.clear();
    const Domain2* domain = water_();
    const std::size_t n = std::max(water_rings_.size(), domain ? domain->rings.size() : 0);
    static const std::vector<Point2> kNone;
    for (std::size_t r = 0; r < n; ++r) {
      const Ring* ring = domain && r < domain->rings.size() ? &domain->rings[r] : nullptr;
      const bool bounds = ring && ring->closed() && ring->points.size() >= 3;
      const std::vector<Point2>& now = bounds ? ring->points : kNone;
      const std::vector<Point2>& was = r < water_rings_.size() ? water_rings_[r] : kNone;
      if (now == was) continue;
      // The longest common prefix and suffix stay (a ring that came or went: none).
      const std::size_t m = std::min(was.size(), now.size());
      std::size_t a = 0, b = 0;
      while (a < m && was[a] == now[a]) ++a;
      while (a + b < m && was[was.size() - 1 - b] == now[now.size() - 1 - b]) ++b;
      engine::WaterEdit edit;
      const std::span<const Point2> before(was.data() + a, was.size() - a - b), after(now.data() + a, now.size() - a - b);
      const std::optional<Chains> chains = stretch_chains(now, a, b, before, after);
      edit.cyclic = !chains;
      for (const Point2& p : chains ? chains->first : was) edit.gone.push_back(box_.to_unit(p));
      for (const Point2& p : chains ? chains->second : now) edit.came.push_back(box_.to_unit(p));
      out.push_back(std::move(edit));
      user.emplace_back(r, now);
    }
    return out;
  }
}

template <int D>
std::vector<std::size_t> DynamicWellSpaced<D>::apply_unit(std::span<const Edit<D>> edits, UpdateReport<D>* report,
                                                          std::span<const engine::WaterEdit> water) {
  std::vector<Edit<D>> unit(edits.begin(), edits.end());
  for (std::size_t k = 0; k < unit.size(); ++k)
    if (unit[k].kind != Edit<D>::Kind::Remove) {
      try {
        unit[k].point = to_unit_checked(edits[k].point);
      } catch (const InputError& e) {
        if (edits.size() == 1) throw;
        throw InputError("edit " + std::to_string(k + 1) + ": " + e.message());
      }
    }
  const std::vector<std::size_t> ids = set_.apply(unit, report, water);
  std::size_t next = 0;
  for (const Edit<D>& e : edits) {
    if (e.kind == Edit<D>::Kind::Move) user_inputs_[e.id] = e.point;
    if (e.kind == Edit<D>::Kind::Add) {
      user_inputs_.resize(ids[next] + 1);
      user_inputs_[ids[next++]] = e.point;
    }
  }
  to_user(report);
  return ids;
}

template <int D>
std::vector<std::size_t> DynamicWellSpaced<D>::apply(std::span<const Edit<D>> edits, UpdateReport<D>* report) {
  std::vector<engine::WaterEdit> water;
  std::vector<std::pair<std::size_t, std::vector<Point<2>>>> user_rings;
  if constexpr (D == 2) water = water_changes(user_rings);
  const std::vector<std::size_t> ids = apply_unit(edits, report, water);
  for (auto& [r, points] : user_rings) {
    if (water_rings_.size() <= r) water_rings_.resize(r + 1);
    water_rings_[r] = std::move(points);
  }
  return ids;
}

template <int D>
std::vector<std::size_t> DynamicWellSpaced<D>::apply(std::span<const Edit<D>> edits, UpdateReport<D>* report,
                                                     std::span<const WaterStretch> stretches) {
  std::vector<engine::WaterEdit> water;
  std::vector<PendingStretch> pending;
  if constexpr (D == 2) {
    const Domain2* domain = set_.engine().water() && water_ ? water_() : nullptr;
    if (domain)
      for (const WaterStretch& s : stretches)
        if (auto edit = water_edit(*domain, s)) {
          water.push_back(std::move(*edit));
          // As water_now() has the ring: its points when it bounds water, none otherwise.
          const Ring& ring = domain->rings[s.ring];
          if (s.whole || ring.points.size() < 3 || ring.points.size() - s.after.size() + s.before.size() < 3)
            pending.push_back({s.ring, 0, 0, ring.points.size() >= 3 ? ring.points : std::vector<Point2>{}, true});
          else
            pending.push_back({s.ring, s.prefix, s.suffix, std::vector<Point2>(s.after.begin(), s.after.end()), false});
        }
  } else {
    (void)stretches;
  }
  const std::vector<std::size_t> ids = apply_unit(edits, report, water);
  if constexpr (D == 2) {
    if (water_pending_.size() + pending.size() > kPendingStretches) {
      water_rings_ = water_now();
      water_pending_.clear();
    } else {
      water_pending_.insert(water_pending_.end(), std::make_move_iterator(pending.begin()),
                            std::make_move_iterator(pending.end()));
    }
  }
  return ids;
}

template <int D>
std::size_t DynamicWellSpaced<D>::add(const Point<D>& p, UpdateReport<D>* report) {
  const Edit<D> e{Edit<D>::Kind::Add, 0, p};
  return apply(std::span<const Edit<D>>(&e, 1), report).front();
}

template <int D>
void DynamicWellSpaced<D>::remove(std::size_t id, UpdateReport<D>* report) {
  const Edit<D> e{Edit<D>::Kind::Remove, id, {}};
  apply(std::span<const Edit<D>>(&e, 1), report);
}

template <int D>
void DynamicWellSpaced<D>::move(std::size_t id, const Point<D>& p, UpdateReport<D>* report) {
  const Edit<D> e{Edit<D>::Kind::Move, id, p};
  apply(std::span<const Edit<D>>(&e, 1), report);
}

template <int D>
Point<D> DynamicWellSpaced<D>::input_point(std::size_t id) const {
  set_.input_point(id);  // throws for an unknown id
  return user_inputs_[id];
}

template <int D>
std::vector<Point<D>> DynamicWellSpaced<D>::points() const {
  // One array of the output's size, the Steiner points mapped in place: the engine is at its largest
  // while this runs (a one-shot build's peak was here, with three copies of the output).
  std::vector<Point<D>> out;
  out.reserve(set_.input_count() + set_.steiner_count());
  for (std::size_t id = 0; id < user_inputs_.size(); ++id)
    if (set_.has_input(id)) out.push_back(user_inputs_[id]);
  const std::size_t inputs = out.size();
  set_.append_steiner_points(out);
  for (std::size_t k = inputs; k < out.size(); ++k) out[k] = box_.to_user(out[k]);
  return out;
}

template class DynamicWellSpaced<2>;
template class DynamicWellSpaced<3>;
template class WellSpacedSet<2>;
template class WellSpacedSet<3>;
template StableResult<2> stable_well_spaced<2>(std::span<const Point<2>>, const Parameters<2>&,
                                               std::optional<BoxTransform<2>>, const Domain2*);
template StableResult<3> stable_well_spaced<3>(std::span<const Point<3>>, const Parameters<3>&,
                                               std::optional<BoxTransform<3>>, const Domain2*);

}  // namespace shoremesh
