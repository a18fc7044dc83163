#pragma once
// An edit session of the library: the dynamic well-spaced set of a shoreline and its points, the shore's
// canonical splits (ShoreRefinement) and the water mesh, kept equal to a fresh run on the current input
// after every edit (Lemma 7.2; docs/conforming.md for the splits). One edit at a time: a point added
// (loose, or into a ring after a given point), moved or removed, a ring added or removed. Each returns
// what changed (the engine's report, the mesh's delta, timings); an edit that would make the rings
// invalid, or that the engine refuses, throws InputError and changes nothing.
//
// Ids: the input points are numbered 0..n-1 as given; every added point takes the next id; ids are never
// reused. Rings are numbered as given, and an added ring takes the next number; a removed ring's number
// is not reused (it stays as a ring without points, which bounds nothing).
#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/parameters.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/size_function.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {

// What a session (or a fresh run) starts from.
template <int D>
struct SessionInput {
  std::vector<Point<D>> points;  // the input points: id i is points[i]
  // 2D: the rings (valid: find_ring_defect finds nothing); ring r's vertex k is input point
  // ring_ids[r][k]. Rings may share a vertex (one input point on several rings: a .poly's segments meeting
  // there, a pinch vertex, a line's end on a ring); an edit session refuses to move or remove such a
  // vertex, or to remove the ring that holds it first (closed rings before lines), naming the point and
  // its rings, and edits every other vertex. The other points are loose.
  Domain2 rings;
  std::vector<std::vector<std::size_t>> ring_ids;
};

// The engine's parameters for rho, with a picking region that is never empty.
template <int D>
Parameters<D> session_parameters(double rho);

// The shore's canonical splits of a 2D input's rings (valid ones) for the engine's box: the given one, or
// the one the engine fits to the input points; nullopt without rings. InputError when the ring ids do
// not name the rings' points.
// With a size field, subsegments are also halved while longer than it allows (shore_max_length).
std::optional<ShoreRefinement> refine_input(const SessionInput<2>& input, const std::optional<BoxTransform<2>>& box,
                                            std::shared_ptr<const SizeField> size = nullptr);

// The box a run uses: the given one, or the one the engine fits to the input points (before any split or
// size seed is added, so that those never move it).
BoxTransform<2> run_box(const SessionInput<2>& input, const std::optional<BoxTransform<2>>& box);

// The mesh of `points` (the first `input_count` are input points): with rings, every segment of `domain`
// is a constraint and the mesh is all of the water (not clipped to the box: the box is fitted to the
// input, so the shore may touch it); without, the Delaunay mesh of the points, keeping only the elements
// whose circumcentre lies in `box` unless `keep_hull` (the others are slivers along the box's edge).
template <int D>
Mesh<D> well_spaced_mesh(std::span<const Point<D>> points, std::size_t input_count, const Domain2& domain,
                         const BoxTransform<D>& box, bool keep_hull);

// Whether the mesh's boundary is the shoreline: every segment of the refined rings a chain of mesh edges.
struct ShorelineStatus {
  std::size_t segments = 0, covered = 0, splits = 0;
  bool conforming() const { return covered == segments; }
};

template <int D>
struct SessionEdit {
  std::size_t id = 0;                 // the point added, moved or removed (the first of an added ring)
  std::optional<std::size_t> ring;    // the ring the edit changed, when it changed one
  std::vector<std::size_t> ring_ids;  // add_ring: the new ring's vertex ids, in ring order
  UpdateReport<D> engine;             // the well-spaced set's change (Steiner points)
  MeshDelta<D> mesh;                  // the water mesh's change
  std::size_t inputs_removed = 0, inputs_added = 0;  // input points that went and came, splits included
  bool rebuilt = false;  // the mesh was rebuilt from the engine's points (it refused the change)
  double rings_ms = 0, engine_ms = 0, mesh_ms = 0, ms = 0;
};

template <int D>
class ShoreSession {
 public:
  struct Options {
    double rho = 1.4142135623730951;
    std::optional<BoxTransform<D>> box;  // fitted to the input when not given; never grows
    bool keep_hull = false;              // without rings: keep the slivers along the box's edge
    // Element size control (2D, docs/sizing.md): the size seeds join the engine's input after the splits.
    std::optional<SizeTerms> size;
  };

  // InputError (PointInputError for the engine's refusals, naming input ids) when the input is invalid.
  ShoreSession(const SessionInput<D>& input, const Options& options);
  ~ShoreSession();
  ShoreSession(ShoreSession&&) noexcept;
  ShoreSession& operator=(ShoreSession&&) noexcept;

  // A loose point at p.
  SessionEdit<D> add(const Point<D>& p);
  // A new vertex at p in the ring of input point `after`, between it and the vertex after it (2D).
  SessionEdit<D> add_after(std::size_t after, const Point<D>& p);
  SessionEdit<D> move(std::size_t id, const Point<D>& p);
  SessionEdit<D> remove(std::size_t id);
  // A new ring (an island, a breakwater, a lake) of new points, closed implicitly (2D, a session with
  // rings). Its role (shore or island) follows from its nesting among the rings. `line`: an open chain
  // instead (RingRole::Line: constraints in the water that bound nothing), numbered like a ring; each of
  // its ends may be a vertex of a closed ring (a jetty on the shore), which it then shares: that vertex
  // can be neither moved nor removed, nor its ring removed, while the line ends there. No other point of
  // a new ring or line, and no moved or added vertex, may be a vertex already.
  SessionEdit<D> add_ring(std::span<const Point2> points, bool line = false);
  // Ring (or line) `ring` and all of its points go, but those other rings share (they stay theirs); the
  // last closed ring cannot (the water would be undefined).
  SessionEdit<D> remove_ring(std::size_t ring);
  // Size polygon `polygon` (0-based, as read) takes size `size`: h, the shore's size splits and the size
  // seeds are recomputed and their difference applied as one edit. InputError/ParameterError, changing
  // nothing, without size polygons or for a bad size.
  SessionEdit<D> set_polygon_size(std::size_t polygon, double size);

  const Mesh<D>& mesh() const;
  const BoxTransform<D>& box() const;
  double rho() const;
  bool has_rings() const;
  // Whether `id` names a live input point, and InputError saying why not (removed, or never given).
  bool contains(std::size_t id) const;
  void check_id(std::size_t id) const;
  Point<D> input_point(std::size_t id) const;
  // The ring (its number) and the place in it of input point `id`; nullopt for a loose point.
  std::optional<std::pair<std::size_t, std::size_t>> ring_of(std::size_t id) const;
  std::size_t next_id() const;
  std::size_t input_count() const;  // live input points the user gave (splits not counted)
  std::size_t split_count() const;
  std::size_t seed_count() const;  // size seeds among the engine's input points
  std::size_t steiner_count() const;
  // The size field (null without size control).
  const SizeField* size_field() const;
  // Ring numbers given so far (removed ones included), and ring r's points now (none once removed).
  std::size_t ring_count() const;
  const std::vector<Point2>& ring(std::size_t r) const;
  RingRole ring_role(std::size_t r) const;
  // The rings as they are now, removed ones left out (in ring order), and the rings with their splits as
  // the mesh conforms to them (removed ones as rings without points; built when first asked after an
  // edit, O(the shore)).
  Domain2 rings() const;
  const Domain2& refined_rings() const;
  // The point set as a fresh run on the current input lists it: the input points by id, the shore's
  // splits (sorted), the size seeds (sorted), then the Steiner points.
  std::vector<Point<D>> canonical_points() const;
  // The input a fresh run would take now (removed points and rings left out, ids renumbered in order).
  SessionInput<D> current_input() const;
  ShorelineStatus shoreline() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shoremesh
