#pragma once
// Canonical splits of the shoreline, so that the mesh's boundary can be the shoreline itself.
//
// The rule (docs/conforming.md): a subsegment of a ring edge is halved at its midpoint while an input point
// (a ring vertex, a loose point or another split point) lies closer to that midpoint than gamma times half
// the subsegment's length. Points on the same edge never encroach it, nor do points on the edge that meets
// it at a corner sharper than 60 degrees (halving there would never end: such corners are the documented
// exception of every quality mesher), nor a point on its line (where rings touch). A subsegment is also
// halved while it is longer than `grading` times the distance from one of its ends to another point (the
// edge's own points count; one on a sharp corner's other edge or inside the edge does not), so that the
// shore is graded to its points. Splitting only ever adds points, so the result is the least fixed
// point of the rule: one set, whatever the order the rule is applied in, and a function of the input
// alone. The split points become input points of the engine, which therefore keeps Lemma 7.2 unchanged.
//
// update() edits the rings and the loose points and recomputes the splits only where the edit can reach:
// edges whose subsegments (at any level) had a removed point in their test disk are reset and closed again
// with everything else; the result equals a fresh ShoreRefinement of the new input (tests pin it).
// Every decision is an exact predicate (engine/predicates.hpp: intervals, then GMP).
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <span>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/point.hpp"
#include "shoremesh/shore_segments.hpp"

namespace shoremesh {

struct RefinementRule {
  double gamma = 1.25;  // 1 is Ruppert's diametral circle; larger grades the shore more
  // Grading: a subsegment is also halved while it is longer than `grading` times the distance from one of
  // its ends to another point (0: no grading). Below 2 the halving would cascade along a straight shore
  // (a neighbour half as long would split it), so 0 or at least 2.
  double grading = 2.5;
  int max_depth = 24;  // halvings of one ring edge at most
  // No subsegment shorter than this is split (0: none): the callers give a fixed fraction of the engine's
  // box, so that no split comes nearer to a point than the engine resolves.
  double min_length = 0;
  // Size control (size_function.hpp): a subsegment pq is also halved while longer than max_length(p, q)
  // (empty: no limit). A rule of the subsegment alone, so the splits stay one least fixed point.
  std::function<double(const Point2&, const Point2&)> max_length;

  // The rule for a session or run in `box_side`: no split below 2^-32 of the side.
  static RefinementRule for_box(double box_side) {
    RefinementRule r;
    r.min_length = std::ldexp(box_side, -32);
    return r;
  }
};

struct SplitChange {
  std::vector<Point2> removed, added;
  // The refined rings' segments that went and came.
  ShoreChange segments;
  bool empty() const { return removed.empty() && added.empty(); }
};

// One ring's edit: its vertices other than the first `prefix` and the last `suffix` are replaced by
// `middle`. `whole`: the ring (or line) is replaced as a whole by `middle` (prefix and suffix unused): a
// ring that came (a number past the last, or a removed ring's), went (`middle` empty: it stays as a ring
// without points) or a line that changed. `role`: a new ring's.
struct RingStretch {
  std::size_t ring = 0;
  std::size_t prefix = 0, suffix = 0;
  std::vector<Point2> middle;
  bool whole = false;
  RingRole role = RingRole::Shore;
};

// Whether the segments apex-a and apex-b meet at less than 60 degrees (exact): the corners the rule
// exempts from encroachment and grading, and where the summary allows triangles below the bound.
bool corner_sharper_than_60(const Point2& apex, const Point2& a, const Point2& b);

// Applies `s` to `rings` in place (a vector's erase and insert: no pass over other rings) and returns
// the edit that undoes it.
RingStretch apply_stretch(Domain2& rings, const RingStretch& s);

class ShoreRefinement {
 public:
  // `rings` must be valid (find_ring_defect finds nothing); `loose` are the input points on no ring.
  explicit ShoreRefinement(const Domain2& rings, std::span<const Point2> loose = {}, RefinementRule rule = {});
  ~ShoreRefinement();
  ShoreRefinement(ShoreRefinement&&) noexcept;
  ShoreRefinement& operator=(ShoreRefinement&&) noexcept;

  const Domain2& rings() const;
  // The rings with the split points inserted in order: the shoreline the mesh conforms to.
  Domain2 refined() const;
  // The split points, sorted.
  std::vector<Point2> split_points() const;
  std::size_t split_count() const;

  // The rings become `rings` (each ring edited anywhere; a ring past the last is new, and a ring
  // left without points went; rings are matched by their place) and the loose points lose
  // `loose_removed` and gain `loose_added`. Returns the split points that went and came (none in both).
  SplitChange update(const Domain2& rings, std::span<const Point2> loose_removed = {},
                     std::span<const Point2> loose_added = {});
  // The same for rings edited by `edits` (one per ring at most), in O(the edits' reach): no pass over the
  // shore (`rings` above finds each ring's changed stretch by comparing it whole).
  SplitChange update(std::span<const RingStretch> edits, std::span<const Point2> loose_removed = {},
                     std::span<const Point2> loose_added = {});

  // The same under a new rule (size control: h changed) whose max_length differs from the old rule's only
  // for subsegments pq of edges ab with rule_changed(a, b) (it must hold for an edge whenever the rule
  // differs for one of its subsegments): those edges are reset as when a point in their test disks went,
  // and everything closes again under the new rule. Equal to a fresh ShoreRefinement under `rule`.
  // `near` (lo, hi), when given: rule_changed holds only for edges ab whose bounding box grown by half its
  // longer side meets it; those are found in an R-tree (made at the first such update), not by a scan.
  SplitChange update(std::span<const RingStretch> edits, std::span<const Point2> loose_removed,
                     std::span<const Point2> loose_added, RefinementRule rule,
                     const std::function<bool(const Point2&, const Point2&)>& rule_changed,
                     std::optional<std::pair<Point2, Point2>> near = {});

  // Recomputes everything from scratch and throws std::logic_error when it differs (tests).
  void check_valid() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shoremesh
