#pragma once
// The Delaunay mesh of the engine's output points: triangles (2D) or tetrahedra (3D), kept alive in a CGAL
// triangulation so that a dynamic update of the point set changes the mesh only where the points changed.
// In 2D, a domain (a lake shore and its islands) keeps only the elements inside the water. A box (the
// engine's) keeps only the elements whose circumcentre lies in it: those whose quality rho-well-spacing
// guarantees (mesh_coverage.hpp); the rest are slivers along the box's edge.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/mesh_element.hpp"
#include "shoremesh/mesh_quality.hpp"
#include "shoremesh/mesh_shoreline.hpp"
#include "shoremesh/point.hpp"
#include "shoremesh/shore_segments.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {

// A change of the engine's output, in the form the dynamic engine reports it. Removals happen first.
template <int D>
struct PointChange {
  std::vector<Point<D>> removed;
  std::vector<Point<D>> added;
  std::size_t added_input_count = 0;  // the first added_input_count points of `added` are input points

  // What an engine update changed in its output: the input points it removed and added (the caller
  // knows them: the edit), then the Steiner points of its report.
  static PointChange from_update(const UpdateReport<D>& report, std::vector<Point<D>> inputs_removed,
                                 std::vector<Point<D>> inputs_added) {
    PointChange change{std::move(inputs_removed), std::move(inputs_added), 0};
    change.added_input_count = change.added.size();
    change.removed.insert(change.removed.end(), report.steiner_removed.begin(), report.steiner_removed.end());
    change.added.insert(change.added.end(), report.steiner_added.begin(), report.steiner_added.end());
    return change;
  }
};

// What a change did to the mesh (elements inside the water only): the elements that disappeared and the
// ones that appeared, each once, corners sorted. An element removed and recreated by the same change is
// in neither list.
template <int D>
struct MeshDelta {
  std::vector<ElementCorners<D>> removed;
  std::vector<ElementCorners<D>> added;
  bool empty() const { return removed.empty() && added.empty(); }
};

template <int D>
class MeshTriangulation;  // core/src/mesh.cpp: the CGAL triangulation with its vertex map

template <int D>
class Mesh {
  static_assert(D == 2 || D == 3);

 public:
  // The Delaunay mesh of `points`, of which the first `input_count` are input points and the rest Steiner
  // points. Points must be finite and pairwise distinct (InputError naming the first duplicate otherwise).
  // With `covered_box`, only the elements whose circumcentre lies in that box (closed) are kept.
  Mesh(std::span<const Point<D>> points, std::size_t input_count,
       std::optional<BoxTransform<D>> covered_box = {});
  // The same, keeping only the triangles inside the water of `domain` (even-odd rule over its rings).
  Mesh(std::span<const Point2> points, std::size_t input_count, const Domain2& domain,
       std::optional<BoxTransform<2>> covered_box = {})
    requires(D == 2);
  ~Mesh();
  Mesh(Mesh&&) noexcept;
  Mesh& operator=(Mesh&&) noexcept;

  // The current points. A dynamic update renumbers them: a removed point's slot takes the last point.
  const std::vector<Point<D>>& points() const { return points_; }
  const std::vector<PointKind>& kinds() const { return kinds_; }
  // The rings (after an apply with a ShoreChange: asked of the source it gave, once, when first needed).
  const Domain2& domain() const;
  const std::optional<BoxTransform<D>>& covered_box() const { return covered_box_; }

  // The elements inside the water (all finite Delaunay elements without a domain), positively oriented.
  std::vector<Element<D>> elements() const;
  // Their number, kept up to date by apply (O(1): an edit's reply asks for it).
  std::size_t element_count() const { return element_count_; }
  // The Delaunay elements in the water left out because their circumcentre lies outside the covered box
  // (by visiting every element).
  std::size_t uncovered_count() const;

  // Applies a change of the point set with CGAL's incremental removal and insertion; afterwards the mesh
  // is the Delaunay mesh of the new point set. Throws InputError (and changes nothing) when a removed
  // point is not in the mesh or an added point already is (or is given twice).
  MeshDelta<D> apply(const PointChange<D>& change);
  // The same, and the rings become those of `domain` (a shore point moved, added or removed): only the
  // elements near the rings' changed stretches are classified again, and the mesh equals a fresh one on
  // the new points and domain.
  MeshDelta<D> apply(const PointChange<D>& change, const Domain2& domain)
    requires(D == 2);
  // The same with the rings' change given as the refined segments that went and came
  // (ShoreRefinement::update): O(the change), no pass over the shore. `domain` gives the rings as they
  // are after the change; domain() calls it only when asked (and not once an edit later replaced it).
  MeshDelta<D> apply(const PointChange<D>& change, const ShoreChange& shore, std::function<Domain2()> domain)
    requires(D == 2);

  // The constrained edges, ends sorted, the list sorted (tests: the constraints against a fresh run's).
  std::vector<std::pair<Point2, Point2>> constrained_edges() const
    requires(D == 2);

  // The elements whose bounding box meets the box [lo, hi], corners sorted: a walk from the box's centre,
  // O(those elements) when the centre lies in the mesh's hull.
  std::vector<ElementCorners<2>> elements_meeting(const Point2& lo, const Point2& hi) const
    requires(D == 2);

  // From now on (and at once) co-circular ties are broken canonically: among the Delaunay meshes of
  // co-circular points the one of a symbolic perturbation (lexicographic rank; docs/terrain.md), so that
  // the elements are a function of the points and rings, whatever the history of updates (lattice points).
  void canonicalize_ties()
    requires(D == 2);

  // Element quality against the bound that rho-well-spacedness guarantees. The guarantee covers the
  // elements whose circumcentre lies in `box` (the engine's box; the points' bounding box by default).
  QualityReport<D> quality(double rho, std::optional<BoxTransform<D>> box = {}) const;

  // Whether the mesh respects the domain's rings: each ring segment must be a chain of mesh edges.
  ShorelineReport shoreline_crossings() const
    requires(D == 2);

  // CGAL's structural and Delaunay validity check plus the point bookkeeping; throws std::logic_error
  // naming the first broken invariant.
  void check_valid() const;

 private:
  void build(std::span<const Point<D>> points, std::size_t input_count);
  std::size_t count_elements() const;  // by visiting every element
  MeshDelta<D> apply_with_water(const PointChange<D>& change, const Domain2* domain, const ShoreChange* shore);

  std::vector<Point<D>> points_;
  std::vector<PointKind> kinds_;
  std::size_t element_count_ = 0;
  // The rings, and while they are stale the function that gives them (single-threaded, as every use of
  // a mesh that an edit changes).
  mutable Domain2 domain_;
  mutable std::function<Domain2()> domain_source_;
  std::optional<BoxTransform<D>> covered_box_;
  std::unique_ptr<MeshTriangulation<D>> triangulation_;
};

using Mesh2 = Mesh<2>;
using Mesh3 = Mesh<3>;

}  // namespace shoremesh
