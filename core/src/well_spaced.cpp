#include "shoremesh/well_spaced.hpp"

#include <algorithm>
#include <cmath>
#include <string>

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
void WellSpacedSet<D>::build(std::span<const Point<D>> unit_points) {
  engine_->build(unit_points);
}
template <int D>
std::size_t WellSpacedSet<D>::input_count() const {
  return engine_->input_count();
}
template <int D>
std::size_t WellSpacedSet<D>::steiner_count() const {
  return engine_->vertex_count() - engine_->input_count();
}
template <int D>
std::vector<Point<D>> WellSpacedSet<D>::output_points() const {
  const auto all = engine_->positions();
  const std::size_t n = engine_->input_count();
  std::vector<Point<D>> out(all.begin(), all.end());
  std::sort(out.begin() + long(n), out.end());
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

template <int D>
StableResult<D> stable_well_spaced(std::span<const Point<D>> user_points, const Parameters<D>& parameters,
                                   std::optional<BoxTransform<D>> box) {
  if (user_points.empty()) throw InputError("no input points");
  for (std::size_t i = 0; i < user_points.size(); ++i)
    for (int k = 0; k < D; ++k)
      if (!std::isfinite(user_points[i][k]))
        throw PointInputError("point " + std::to_string(i) + " has a coordinate that is not a finite number", {i});
  StableResult<D> result;
  if (box) {
    if (!(box->side > 0) || !std::isfinite(box->side)) throw InputError("the box side must be a positive number");
    for (std::size_t i = 0; i < user_points.size(); ++i)
      if (!box->contains(user_points[i]))
        throw PointInputError("point " + std::to_string(i) + " lies outside the given box", {i});
    result.box = *box;
  } else {
    result.box = BoxTransform<D>::fit(user_points);
  }
  std::vector<Point<D>> unit(user_points.size());
  for (std::size_t i = 0; i < unit.size(); ++i) unit[i] = result.box.to_unit(user_points[i]);

  WellSpacedSet<D> set(parameters);
  set.build(unit);
  // Input points come back exactly as the user gave them; only Steiner points are mapped back.
  std::vector<Point<D>> out = set.output_points();
  result.points.assign(user_points.begin(), user_points.end());
  for (std::size_t i = user_points.size(); i < out.size(); ++i) result.points.push_back(result.box.to_user(out[i]));
  result.input_count = user_points.size();
  result.counters = set.counters();
  result.memory_bytes = set.memory_bytes();
  return result;
}

template class WellSpacedSet<2>;
template class WellSpacedSet<3>;
template StableResult<2> stable_well_spaced<2>(std::span<const Point<2>>, const Parameters<2>&,
                                               std::optional<BoxTransform<2>>);
template StableResult<3> stable_well_spaced<3>(std::span<const Point<3>>, const Parameters<3>&,
                                               std::optional<BoxTransform<3>>);

}  // namespace shoremesh
