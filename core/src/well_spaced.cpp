#include "shoremesh/well_spaced.hpp"

#include <algorithm>
#include <cmath>
#include <string>

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
  const std::vector<std::uint32_t> vertex_of_point = engine_->build(unit_points, purpose == BuildFor::Updates);
  // Both arrays get room to grow. Each add takes a new id, and a vertex numbered past the end of
  // input_id_ made it copy itself whole in the middle of that update: 51 ms at 2D n = 1e6, after about
  // 3,600 changes (bench/RESULTS.md). Room never written takes no physical memory.
  input_vertex_.reserve(unit_points.size() + unit_points.size() / 2 + 1024);
  input_vertex_.assign(vertex_of_point.begin(), vertex_of_point.end());
  input_id_.reserve(engine_->vertex_count() + engine_->vertex_count() / 2 + 1024);
  input_id_.resize(engine_->vertex_count());  // Steiner vertices may be numbered among the inputs
  for (std::size_t i = 0; i < unit_points.size(); ++i) input_id_[vertex_of_point[i]] = i;
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
                                                 std::span<const UnitRingChange> rings) {
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
  const auto vertices = engine_->apply(engine_edits, &stats, rings);
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
  for (std::uint32_t v : input_vertex_)
    if (v != engine::kNoVertex) out.push_back(all[v]);
  const std::size_t inputs = out.size();
  for (engine::VertexId v = 0; v < all.size(); ++v)
    if (engine_->vertex(v).alive && !engine_->vertex(v).is_input) out.push_back(all[v]);
  std::sort(out.begin() + long(inputs), out.end());
  return out;
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
      for (std::size_t r = 0; r < rings.size(); ++r)
        for (const Point2& p : water_rings_[r]) rings[r].push_back(box_.to_unit(p));
      set_.engine().set_water(std::move(rings));
    }
  }
  set_.build(unit, purpose);
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

// The rings as the source has them now against those the engine has: O(ring points) comparisons, a few
// hundred microseconds at 200k shore points, and only the changed rings mapped to the unit box.
template <int D>
std::vector<UnitRingChange> DynamicWellSpaced<D>::water_changes(std::vector<UnitRingChange>& user) const {
  std::vector<UnitRingChange> out;
  user.clear();
  if constexpr (D != 2) return out;
  else if (!set_.engine().water()) return out;
  const Domain2* domain = water_();
  const std::size_t n = std::max(water_rings_.size(), domain ? domain->rings.size() : 0);
  static const std::vector<Point2> kNone;
  for (std::size_t r = 0; r < n; ++r) {
    const Ring* ring = domain && r < domain->rings.size() ? &domain->rings[r] : nullptr;
    const bool bounds = ring && ring->closed() && ring->points.size() >= 3;
    const std::vector<Point2>& now = bounds ? ring->points : kNone;
    if (now == (r < water_rings_.size() ? water_rings_[r] : kNone)) continue;
    std::vector<Point2> unit;
    unit.reserve(now.size());
    if constexpr (D == 2)
      for (const Point2& p : now) unit.push_back(box_.to_unit(p));
    out.emplace_back(r, std::move(unit));
    user.emplace_back(r, now);
  }
  return out;
}

template <int D>
std::vector<std::size_t> DynamicWellSpaced<D>::apply(std::span<const Edit<D>> edits, UpdateReport<D>* report) {
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
  std::vector<UnitRingChange> rings, user_rings;
  if constexpr (D == 2) rings = water_changes(user_rings);
  const std::vector<std::size_t> ids = set_.apply(unit, report, rings);
  for (auto& [r, points] : user_rings) {
    if (water_rings_.size() <= r) water_rings_.resize(r + 1);
    water_rings_[r] = std::move(points);
  }
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
  std::vector<Point<D>> out;
  for (std::size_t id : set_.input_ids()) out.push_back(user_inputs_[id]);
  const std::vector<Point<D>> unit = set_.output_points();
  for (std::size_t k = out.size(); k < unit.size(); ++k) out.push_back(box_.to_user(unit[k]));
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
