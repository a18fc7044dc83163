#pragma once
// Element size control (docs/sizing.md): a size function h(x) over the engine's box, composed as gmsh and
// OceanMesh2D compose theirs (the minimum of the terms given, clamped to [min, max], then graded to be
// G-Lipschitz as limgrad does), and the canonical "size seeds" through which the engine honours it.
//
// h lives on a grid of 2^k x 2^k cells aligned with the engine's box; h(x) is the bilinear interpolant of
// the node values, so the quadtree of the seeds reads exact minima from a pyramid. Terms that come from
// files (a raster of sizes, depths, slopes) are sampled by the caller at the grid's nodes (no file I/O
// here). Everything is a deterministic function of the terms, the box and the rings.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/point.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/shore_segments.hpp"

namespace shoremesh {

// A polygon with a size (a GeoJSON Polygon's `size` property): h <= size inside its outer ring and
// outside its holes.
struct SizePolygon {
  std::vector<std::vector<Point2>> rings;  // outer ring, then holes
  double size = 0;
  std::string name;  // for messages: "polygon 3 (file.geojson feature 3)"
};

// A term sampled by the caller at points (a raster, the depth or the slope): its size there, or NaN / +inf
// where it sets none. `name` is the option it came from ("--size-raster sizes.tif").
struct SampledSizeTerm {
  std::string name;
  std::function<double(const Point2&)> size;
};

struct SizeTerms {
  std::optional<double> max_size, min_size, grade;
  std::optional<double> shore_size, shore_rate;  // --size-from-shore H0 RATE
  std::vector<SizePolygon> polygons;
  std::vector<SampledSizeTerm> sampled;
  std::size_t point_cap = 10'000'000;  // refused when a term alone would ask for more points
  bool empty() const {
    return !max_size && !min_size && !shore_size && polygons.empty() && sampled.empty();
  }
};

// What the summary reports about h and the mesh.
struct SizeSummary {
  double min = 0, max = 0;  // h over the water's grid nodes
  double grading = 0;       // max |h(u) - h(v)| / |uv| over grid neighbours
  std::size_t grid_cells = 0;  // per side
};

// What an update of h changed (SizeField::set_rings, set_polygon_size): the grid nodes whose value changed
// lie in [i0, i1] x [j0, j1] (grid indices, none when !changed), and the nodes the update read or wrote.
struct SizeChange {
  bool changed = false;
  std::size_t i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  std::size_t visited = 0;  // (n + 1)^2 when the update recomputed the grid whole
  bool whole = false;       // the grid was recomputed whole (the local repair's preconditions failed)
  explicit operator bool() const { return changed; }
};

// What an update of the field overwrote (SizeField::set_rings or set_polygon_size given a fresh one): to
// read h as it was (update_size_seeds) and to take the update back (SizeField::take_back), without a copy
// of the field.
struct SizeUndo {
  std::vector<std::pair<std::size_t, double>> h, shore, shore_src;  // (node, value before)
  std::size_t water_box[4] = {0, 0, 0, 0};                           // i0, j0, i1, j1
  std::vector<std::uint8_t> water;                                   // the box's nodes before, row-major
  std::unordered_map<std::uint64_t, double> pyramid;                 // (level << 56 | block): the minimum before
  std::optional<std::pair<std::size_t, double>> polygon;             // a polygon's size before
  std::optional<Domain2> rings;                                      // the rings before (set_rings of a Domain2)
  // set_rings of stretches: their inverses (applied last first) and the ring edges that went and came.
  std::vector<RingStretch> stretches;
  std::vector<ShoreSegment> edges_gone, edges_came;
  // The grid recomputed whole: the arrays before.
  std::optional<std::vector<double>> whole_h, whole_shore, whole_src;
  std::optional<std::vector<std::uint8_t>> whole_water;
  std::optional<std::vector<std::vector<double>>> whole_pyramid;
};

class SizeField {
 public:
  // ParameterError naming the option for a bad value (non-positive, NaN, min > max, grade <= 0) and
  // InputError naming the term whose sizes alone would exceed terms.point_cap points in the water.
  SizeField(SizeTerms terms, const BoxTransform<2>& box, const Domain2& rings);

  double at(const Point2& p) const;  // h(p), bilinear; clamped to the box
  // A lower bound of h over the axis-aligned square [x0, x0 + side] x [y0, y0 + side] (exact for squares
  // aligned with the grid).
  double min_over(const Point2& lo, double side) const;
  // A lower bound of h over the segment's bounding box.
  double min_over_segment(const Point2& a, const Point2& b) const;

  // Whether the shore term reads the rings (then a shore edit changes h).
  bool depends_on_rings() const { return terms_.shore_size.has_value(); }
  // The rings changed: updates h (the shore term and the water) where the changed segments reach, equal to
  // a fresh SizeField on the new rings (docs/sizing.md). Returns where h changed.
  SizeChange set_rings(const Domain2& rings, SizeUndo* undo = nullptr);
  // The same for the rings edited by `edits` (apply_stretch, one per ring at most), with no pass over the
  // rings: the changed segments come from the stretches, and the segments near them (the shore term's
  // sources, the water's crossings) from an R-tree of the ring edges (built at the first such update).
  SizeChange set_rings(std::span<const RingStretch> edits, SizeUndo* undo = nullptr);
  // Polygon `index` (0-based) takes size `size`; ParameterError for a bad size, InputError for no such
  // polygon. Updates h where the polygon's nodes reach; returns where it changed.
  SizeChange set_polygon_size(std::size_t index, double size, SizeUndo* undo = nullptr);
  // The field as it was before the update that filled `undo`.
  void take_back(SizeUndo&& undo);
  // min_over as it was before the update that filled `undo`.
  double min_over_before(const SizeUndo& undo, const Point2& lo, double side) const;
  // Whether min_over_segment(a, b) reads a grid node of `change` (a subsegment's max_length may differ).
  bool reads(const Point2& a, const Point2& b, const SizeChange& change) const;
  // reads(a, b, change) holds only for segments whose bounding box grown by half its longer side meets
  // this box (lo, hi): min_over_segment reads at most a quarter of the longer side and three cells beyond
  // the box (docs/sizing.md).
  std::pair<Point2, Point2> reach_of(const SizeChange& change) const;
  const SizeTerms& terms() const { return terms_; }

  SizeSummary summary() const;
  const BoxTransform<2>& box() const { return box_; }
  int levels() const { return k_; }
  std::size_t cells() const { return n_; }
  const std::vector<double>& nodes() const { return h_; }  // (n + 1)^2, row-major from the box's origin
  // Per node, as nodes(): in the water (WaterTest::in_water at the node, decided exactly).
  const std::vector<std::uint8_t>& water() const { return water_; }

  bool operator==(const SizeField& o) const { return h_ == o.h_; }

 private:
  void compute();
  void build_pyramid();
  void update_pyramid(std::size_t i0, std::size_t j0, std::size_t i1, std::size_t j1);
  // The water at the nodes [i0, i1] x [j0, j1].
  // With `indexed`, the edges are found in the edge tree (set_rings of stretches), else in the rings.
  void water_mask(std::size_t i0, std::size_t j0, std::size_t i1, std::size_t j1, bool indexed = false);
  // The update of h once the rings changed by the segments `segs` (both sides) and `emptiness` (whether
  // the rings went from none to some or back).
  SizeChange rings_changed(const std::vector<std::pair<Point2, Point2>>& segs, bool emptiness, bool indexed);
  // Calls f(a, b, closed) for every ring edge whose box meets [lo, hi] (the tree: a superset of those).
  template <class F>
  void edges_meeting(const Point2& lo, const Point2& hi, bool indexed, F&& f) const;
  // `before`: the pyramid's blocks as they were (level, block), for min_over_before.
  double min_over_box(const Point2& lo, const Point2& hi,
                      const std::function<double(std::size_t, std::size_t)>& before = {}) const;
  // The least-pyramid-level block range min_over_box reads, as grid cells [c0, c1] per axis.
  void read_cells(const Point2& lo, const Point2& hi, std::size_t c[4]) const;
  // The cells [i0, i1] x [j0, j1] the box [lo, hi] meets (clamped to the grid) and the pyramid level whose
  // blocks min_over_box reads for it.
  struct CellSpan {
    std::size_t level, i0, i1, j0, j1;
  };
  CellSpan cell_span(const Point2& lo, const Point2& hi) const;
  // h before grading at node v, with the shore term's value `shore` there.
  double raw(std::size_t v, double shore) const;
  // An upper bound of every finite value of the graded terms (the local repair's precondition).
  double finite_bound() const;
  double shore_bound() const;
  void clamp_shore();
  SizeChange recompute_whole();
  // After the terms changed at `nodes` (their pre-grading values before: `before`), h there and where
  // the grading carries the change; the pyramid along.
  SizeChange update_h(const std::vector<std::size_t>& nodes, const std::vector<double>& before);
  std::size_t node(std::size_t i, std::size_t j) const { return j * (n_ + 1) + i; }

  SizeTerms terms_;
  BoxTransform<2> box_;
  Domain2 rings_;
  int k_ = 0;
  std::size_t n_ = 0;
  double cell_ = 0;
  std::shared_ptr<const std::vector<double>> sampled_;  // min of the sampled terms at the nodes (computed once)
  double sampled_top_ = 0;              // the largest finite one
  std::vector<std::uint8_t> water_;     // per node: in the water (for the estimates and the summary)
  std::vector<std::vector<std::size_t>> polygon_nodes_;  // per polygon: the nodes inside it
  std::vector<double> shore_src_;       // the shore term's values beside the segments, before its sweeps
  std::vector<double> shore_;           // the shore term at the nodes (empty without it; at most --max-size)
  std::vector<double> h_;
  std::vector<std::vector<double>> pyramid_;  // level l: min over blocks of 2^l x 2^l cells (their nodes)
  SizeUndo* undo_ = nullptr;                  // during an update: where it records what it overwrites
  // The rings' edges by their boxes (set_rings of stretches), shared by copies until one changes it.
  struct EdgeTree;
  std::shared_ptr<EdgeTree> edge_tree_;
};

// The canonical seeds of h (docs/sizing.md): the centres of the leaves of the quadtree of the box split
// while a leaf's side exceeds kSeedFactor times the least h over the leaf grown by its side on every side,
// moved off the centre by a canonical jitter of at most kSeedJitter times the side (a grid of seeds would
// put four points on every circle), kept where they lie in the water, at least a quarter of their leaf's
// side from every segment of `refined`, and outside every segment's diametral circle grown by gamma.
// Sorted. kSeedFactor * 2 * (1/sqrt 2 + sqrt 2 * kSeedJitter) <= 1: docs/sizing.md.
inline constexpr double kSeedFactor = 0.66;
inline constexpr double kSeedJitter = 0.03;
// A leaf whose seed is dropped (on land or too near the shore) is split again, this many levels at most,
// and its quarters' seeds are tried: the gap along the shore stays a fraction of h.
inline constexpr int kSeedRetries = 2;
// The shore's subsegments are halved while longer than kShoreFactor times the least h near them
// (RefinementRule::max_length).
inline constexpr double kShoreFactor = 0.7;
std::vector<Point2> size_seeds(const SizeField& field, const Domain2& refined, double gamma = 1.25);
// The seeds after a change of h (old_field to field) or of the refined rings (old_refined to refined),
// recomputing only the quadtree's nodes the change reaches (docs/sizing.md): equal to
// size_seeds(field, refined, gamma). `old_seeds` are size_seeds(old_field, old_refined, gamma).
struct SeedUpdate {
  std::size_t visited = 0, recomputed = 0, removed = 0, added = 0;  // nodes walked, subtrees redone, seeds
};
std::vector<Point2> update_size_seeds(const SizeField& old_field, const std::vector<Point2>& old_seeds,
                                      const Domain2& old_refined, const SizeField& field, const Domain2& refined,
                                      double gamma = 1.25, SeedUpdate* stats = nullptr);
// The same with where h changed (as SizeField's update returned it; old_field is the field before it) and
// the refined segments that went and came: no pass over the grid or the rings.
std::vector<Point2> update_size_seeds(const SizeField& old_field, const std::vector<Point2>& old_seeds,
                                      const SizeChange& h_change, const ShoreChange& refined_change,
                                      const SizeField& field, const Domain2& refined, double gamma = 1.25,
                                      SeedUpdate* stats = nullptr);
// The same with the field updated in place: `before` what its update overwrote.
std::vector<Point2> update_size_seeds(const SizeField& field, const SizeUndo& before, const std::vector<Point2>& old_seeds,
                                      const SizeChange& h_change, const ShoreChange& refined_change,
                                      const Domain2& refined, double gamma = 1.25, SeedUpdate* stats = nullptr);
// The refined rings as the seeds' tests read them (the water, decided exactly as WaterTest decides it, and
// the segments by the boxes where a seed would be too near them), kept across edits: an edit gives it the
// refined segments that went and came, so that no pass over the refined rings is made.
class SeedShoreIndex {
 public:
  explicit SeedShoreIndex(const Domain2& refined, double gamma = 1.25);
  ~SeedShoreIndex();
  SeedShoreIndex(SeedShoreIndex&&) noexcept;
  SeedShoreIndex& operator=(SeedShoreIndex&&) noexcept;
  // The refined rings lose change.removed and gain change.added (take_back: the other way).
  void apply(const ShoreChange& change);
  void take_back(const ShoreChange& change);
  double gamma() const;
  struct Impl;  // size_function.cpp's

 private:
  friend struct SeedShoreAccess;
  std::unique_ptr<Impl> impl_;
};
// update_size_seeds with the refined rings kept in `shore` (already given the change).
std::vector<Point2> update_size_seeds(const SizeField& field, const SizeUndo& before, const std::vector<Point2>& old_seeds,
                                      const SizeChange& h_change, const ShoreChange& refined_change,
                                      const SeedShoreIndex& shore, SeedUpdate* stats = nullptr);
// The seeds' test against one refined segment ab, exact (the engine's filtered predicates): p is at least
// `near` from the segment and not strictly inside its diametral circle grown by gamma.
bool seed_clear_of_segment(const Point2& p, const Point2& a, const Point2& b, double near, double gamma);

// The rule's max_length for this field: kShoreFactor times the least h over the subsegment's bounding box.
// The field is shared: the refinement that holds the rule keeps it alive.
std::function<double(const Point2&, const Point2&)> shore_max_length(std::shared_ptr<const SizeField> field);

// The worst ratio of an element's longest edge to h at its centroid, over 2D elements.
struct SizeRatio {
  double worst = 0, mean = 0;
  Point2 worst_at{};
};
SizeRatio size_ratio(const SizeField& field, const std::vector<Point2>& points,
                     const std::vector<std::array<std::uint32_t, 3>>& triangles);

}  // namespace shoremesh
