#pragma once
// StableWS (paper, Figure 3): a size-optimal rho-well-spaced superset of a point set, built so that
// every operation and every square it read is recorded for dynamic updates (PropagateWS).
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/parameters.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

template <int D>
class WellSpacedEngine;  // core/src: quadtree, operations, clipped Voronoi cells

// The live result of StableWS on points in the unit box.
template <int D>
class WellSpacedSet {
 public:
  explicit WellSpacedSet(const Parameters<D>& parameters = {});
  ~WellSpacedSet();
  WellSpacedSet(WellSpacedSet&&) noexcept;
  WellSpacedSet& operator=(WellSpacedSet&&) noexcept;

  // Runs StableWS on `unit_points` (all in [0,1]^D, finite, pairwise distinct; otherwise InputError
  // naming the point's index). Replaces any previous state.
  void build(std::span<const Point<D>> unit_points);

  std::size_t input_count() const;
  std::size_t steiner_count() const;
  // Input points in the order given, then the Steiner points in canonical order (sorted by coordinates,
  // so the list does not depend on the order of the input).
  std::vector<Point<D>> output_points() const;
  const Counters& counters() const;
  // Bytes held by the live structures (quadtree, vertices, operations, read lists), measured by capacity.
  std::size_t memory_bytes() const;
  // Structural self-check of the quadtree, vertex lists and operation graph; throws std::logic_error
  // describing the first broken invariant.
  void check_valid() const;

  WellSpacedEngine<D>& engine();
  const WellSpacedEngine<D>& engine() const;

 private:
  std::unique_ptr<WellSpacedEngine<D>> engine_;
};

// StableWS on points in the user's coordinates: maps them into the unit box (the given box, or
// BoxTransform::fit), runs the engine and maps the output back. Input points come back exactly as given.
template <int D>
struct StableResult {
  BoxTransform<D> box;
  std::vector<Point<D>> points;  // input points first, in input order, then Steiner points
  std::size_t input_count = 0;
  Counters counters;
  std::size_t memory_bytes = 0;
};

template <int D>
StableResult<D> stable_well_spaced(std::span<const Point<D>> user_points, const Parameters<D>& parameters = {},
                                   std::optional<BoxTransform<D>> box = {});

}  // namespace shoremesh
