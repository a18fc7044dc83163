#pragma once
// StableWS (paper, Figure 3): a size-optimal rho-well-spaced superset of a point set, built so that
// every operation and every square it read is recorded for dynamic updates (PropagateWS).
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/engine/water_edit.hpp"
#include "shoremesh/parameters.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

// The coordinates and box sides the engine represents: beyond them, squared distances, areas and
// circumradii in the user's units overflow or underflow. Inputs and boxes outside are refused.
inline constexpr double kLargestCoordinate = 1e100;
inline constexpr double kSmallestSide = 1e-100;

template <int D>
class WellSpacedEngine;  // core/src: quadtree, operations, clipped Voronoi cells
struct Domain2;          // domain.hpp

// One ring's edit as the WaterSource's owner made it (2D, the user's coordinates): ring `ring` had
// `before` between its first `prefix` and its last `suffix` points and has `after` there now (the
// source holds the ring after the edit); `whole`: the ring was `before` and is `after` (prefix and suffix
// unused: a ring that came, went or changed as a whole). A line's edit may be given too: it bounds no water.
struct WaterStretch {
  std::size_t ring = 0;
  std::size_t prefix = 0, suffix = 0;
  std::span<const Point<2>> before, after;
  bool whole = false;
};

// Work only where the water is (2D, docs/water_only.md): the rings the engine's fills work for, as their
// owner holds them now (null or without closed rings: everywhere). Asked at the build and before every
// edit, so that an edit of the rings reaches the engine in the same propagation as its points. A fill
// whose vertex's cell cannot meet the closed water (the rings' even-odd interior) inserts nothing: the
// water mesh (the constrained triangulation with the rings as constraints) sees only points in the
// closed water, and every one of them is filled as without the rings.
using WaterSource = std::function<const Domain2*()>;

// What one dynamic update changed in the output (unit-box coordinates in WellSpacedSet, the user's in
// DynamicWellSpaced): the mesh and export layers update only this.
template <int D>
struct UpdateReport {
  std::vector<Point<D>> steiner_removed;  // Steiner points no longer in the output
  std::vector<Point<D>> steiner_added;    // Steiner points new in the output
  std::size_t operations_undone = 0;      // obsolete or inconsistent operations taken back
  std::size_t operations_executed = 0;    // fresh or inconsistent operations run
  std::size_t operations_touched() const { return operations_undone + operations_executed; }
};

// One edit of the input, for batches.
template <int D>
struct Edit {
  enum class Kind { Add, Remove, Move };
  Kind kind = Kind::Add;
  std::size_t id = 0;   // Remove, Move
  Point<D> point{};     // Add, Move
};

// What a build is for. Updates: the engine then lays its vertices and operations out by place, so that
// an update finds those it reads together in memory (a few per cent of the build; updates at a million
// points about a tenth faster). OutputOnly: the output is read and the set thrown away
// (stable_well_spaced): the build records nothing that only updates read and forgets each operation once
// it has run (less time and memory). The output is the same; updates after an OutputOnly build throw
// std::logic_error.
enum class BuildFor { Updates, OutputOnly };

// The live result of StableWS on points in the unit box, kept up to date under input edits by
// PropagateWS (paper, Figure 4): after every edit the output equals a from-scratch run on the new input.
// Input ids: 0..n-1 in build order; each add takes the next unused id; ids are never reused.
template <int D>
class WellSpacedSet {
 public:
  explicit WellSpacedSet(const Parameters<D>& parameters = {});
  ~WellSpacedSet();
  WellSpacedSet(WellSpacedSet&&) noexcept;
  WellSpacedSet& operator=(WellSpacedSet&&) noexcept;

  // Runs StableWS on `unit_points` (all in [0,1]^D, finite, pairwise distinct; otherwise InputError
  // naming the point's index). Replaces any previous state.
  void build(std::span<const Point<D>> unit_points, BuildFor purpose = BuildFor::Updates);
  // The same, the points' array becoming the engine's positions (one copy fewer during the build).
  void build(std::vector<Point<D>>&& unit_points, BuildFor purpose = BuildFor::Updates);

  // Dynamic updates. add refuses (InputError) a point outside [0,1]^D, non-finite, or equal to an input
  // point; remove and move refuse an unknown id, and remove the last input point. After an error the set
  // is unchanged and valid.
  std::size_t add(const Point<D>& unit_point, UpdateReport<D>* report = nullptr);
  void remove(std::size_t id, UpdateReport<D>* report = nullptr);
  void move(std::size_t id, const Point<D>& unit_point, UpdateReport<D>* report = nullptr);  // keeps the id
  // Several edits, one propagation: returns the ids of the added points (in order). All edits are
  // checked before any is applied.
  // `water`: the changes of the water's edges with these edits (an engine given water, WellSpacedEngine::set_water).
  std::vector<std::size_t> apply(std::span<const Edit<D>> edits, UpdateReport<D>* report = nullptr,
                                 std::span<const engine::WaterEdit> water = {});

  std::size_t input_count() const;
  std::size_t steiner_count() const;
  bool has_input(std::size_t id) const;
  Point<D> input_point(std::size_t id) const;  // InputError for an unknown id
  std::vector<std::size_t> input_ids() const;  // live ids, ascending
  // Input points by increasing id, then the Steiner points in canonical order (sorted by coordinates,
  // so the list does not depend on the order of the input or on the edit history).
  std::vector<Point<D>> output_points() const;
  // Its Steiner points, in that order, at the end of `out` (which the caller sized).
  void append_steiner_points(std::vector<Point<D>>& out) const;
  const Counters& counters() const;
  // Bytes held by the live structures (quadtree, vertices, operations, read lists), measured by capacity.
  std::size_t memory_bytes() const;
  // Structural self-check of the quadtree, vertex lists and operation graph; throws std::logic_error
  // describing the first broken invariant.
  void check_valid() const;

  WellSpacedEngine<D>& engine();
  const WellSpacedEngine<D>& engine() const;

 private:
  void check_new_point(const Point<D>& p, std::span<const std::size_t> removed_ids,
                       std::span<const Point<D>> added) const;
  std::uint32_t vertex_of(std::size_t id) const;  // InputError for an unknown id
  // After a build: the maps between input ids and the engine's vertices.
  void bind_inputs(std::vector<std::uint32_t> vertex_of_point, BuildFor purpose);

  std::unique_ptr<WellSpacedEngine<D>> engine_;
  std::vector<std::uint32_t> input_vertex_;  // by id: the engine's vertex, or none once removed
  std::vector<std::size_t> input_id_;        // by engine vertex: its input id (valid for live inputs)
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

// The dynamic set in the user's coordinates: a fixed box (given, or fitted to the first input), points
// mapped into it, output mapped back. Input points come back exactly as the user gave them.
template <int D>
class DynamicWellSpaced {
 public:
  DynamicWellSpaced(std::span<const Point<D>> user_points, const Parameters<D>& parameters = {},
                    std::optional<BoxTransform<D>> box = {}, BuildFor purpose = BuildFor::Updates,
                    WaterSource water = {});
  const BoxTransform<D>& box() const { return box_; }
  // As WellSpacedSet, in user coordinates; a point outside the box is refused (the box never grows, so
  // that the result always equals `stable_well_spaced` on the same input and box).
  std::size_t add(const Point<D>& p, UpdateReport<D>* report = nullptr);
  void remove(std::size_t id, UpdateReport<D>* report = nullptr);
  void move(std::size_t id, const Point<D>& p, UpdateReport<D>* report = nullptr);
  std::vector<std::size_t> apply(std::span<const Edit<D>> edits, UpdateReport<D>* report = nullptr);
  // As apply, with the source's rings changed by exactly `water` since the last edit (2D): the engine
  // takes in only the edges in those stretches (O(stretch), no ring compared or copied). apply without
  // them finds the changed rings by comparing every ring with the engine's copy (O(shore)).
  std::vector<std::size_t> apply(std::span<const Edit<D>> edits, UpdateReport<D>* report,
                                 std::span<const WaterStretch> water);
  bool has_input(std::size_t id) const { return set_.has_input(id); }
  Point<D> input_point(std::size_t id) const;
  std::vector<std::size_t> input_ids() const { return set_.input_ids(); }
  std::size_t input_count() const { return set_.input_count(); }
  std::size_t steiner_count() const { return set_.steiner_count(); }
  // Live input points by increasing id (exactly as given), then the Steiner points.
  std::vector<Point<D>> points() const;
  const WellSpacedSet<D>& set() const { return set_; }

 private:
  Point<D> to_unit_checked(const Point<D>& p) const;
  void to_user(UpdateReport<D>* report) const;
  // The water's closed rings now, by ring number, in the user's coordinates (empty: none).
  std::vector<std::vector<Point<2>>> water_now() const;
  // The changes of the rings that differ from water_rings_ (after the stretches not yet in it), in the
  // unit box; `user`: those rings as the source has them.
  std::vector<engine::WaterEdit> water_changes(std::vector<std::pair<std::size_t, std::vector<Point<2>>>>& user);
  // The edit of the engine's edges for one stretch of the source's domain (nothing for a line's).
  std::optional<engine::WaterEdit> water_edit(const Domain2& domain, const WaterStretch& s) const;
  std::vector<std::size_t> apply_unit(std::span<const Edit<D>> edits, UpdateReport<D>* report,
                                      std::span<const engine::WaterEdit> water);
  BoxTransform<D> box_;
  WaterSource water_;
  // The closed rings as the engine has them, in the user's coordinates, for apply without stretches.
  // The stretches given since are not in it (`water_pending_`, in order; a ring's points after a whole
  // change, empty for none), so that those edits stay O(stretch); it is refreshed from the source when
  // they pile up, and brought up to date by them before a comparison.
  struct PendingStretch {
    std::size_t ring = 0, prefix = 0, suffix = 0;
    std::vector<Point<2>> after;
    bool whole = false;
  };
  std::vector<std::vector<Point<2>>> water_rings_;
  std::vector<PendingStretch> water_pending_;
  WellSpacedSet<D> set_;
  std::vector<Point<D>> user_inputs_;  // by id; as the user gave them
};

// `water` (2D): work only where its water is (WaterSource).
template <int D>
StableResult<D> stable_well_spaced(std::span<const Point<D>> user_points, const Parameters<D>& parameters = {},
                                   std::optional<BoxTransform<D>> box = {}, const Domain2* water = nullptr);

}  // namespace shoremesh
