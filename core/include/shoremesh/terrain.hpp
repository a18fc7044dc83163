#pragma once
// Terrain TINs (docs/terrain.md): a triangulated irregular network of a height grid (a DEM) whose
// piecewise-linear surface lies within a vertical error bound of every sample, whose triangles meet the
// engine's quality bound in the plane, and which follows edits of the grid (a window of new heights)
// through the dynamic engine, ending equal to a fresh run on the edited grid.
//
// The input points are a canonical function of the grid, in three steps:
//  1. Seeds (off by default): the corners of the leaves of a quadtree over the samples, a node being split
//     while the samples of its window (the node grown by half its side) lie farther than
//     seed_fraction * max_error from their least-squares plane. A node's decision reads only its window: an
//     edit re-decides the nodes whose window it meets.
//  2. Block picks: fixed blocks of block_cells cells, each edge approximated on its own, each block by a
//     Garland-Heckbert greedy TIN of its own; an edit re-decides the blocks it meets.
//  3. Greedy rounds (in canonical batches): while a triangle of the TIN has a sample farther than
//     max_error from it, the sample of largest error of such triangles (ties: the smallest row-major
//     index; thinned to local maxima, pick_spacing) becomes an input point, all of one round together.
//     A round is a function of the TIN, the TIN of the points. The same rounds halve every boundary edge
//     whose triangle's third corner lies in its diametral circle (Ruppert's rule): then every triangle is
//     Delaunay, and the angle bound covers it. On the rectangle every round's TIN is kept in an engine and
//     a mesh of its own (a level), so that an edit updates each round where its TIN changed.
// The TIN is the constrained Delaunay triangulation of the engine's output inside the grid's rectangle
// (whose sides are canonically split, shore_refinement.hpp), co-circular ties broken by a symbolic
// perturbation so that it is one triangulation whatever the history. Nodes take the grid's heights:
// exact at samples, bilinear elsewhere.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/mesh_element.hpp"
#include "shoremesh/parameters.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

// Heights at the samples of a regular grid: sample (c, r) lies at (x0 + c dx, y0 + r dy) in the plane in
// which the angles are measured (metres for a projected DEM).
struct HeightGrid {
  int width = 0, height = 0;
  double x0 = 0, y0 = 0, dx = 1, dy = 1;
  std::vector<float> z;               // row-major, finite everywhere (nodata filled by the reader)
  std::vector<std::uint8_t> valid;    // empty: every sample; else 0 where the raster had nodata

  Point2 position(int c, int r) const { return {x0 + c * dx, y0 + r * dy}; }
  std::size_t index(int c, int r) const { return static_cast<std::size_t>(r) * static_cast<std::size_t>(width) + c; }
  bool is_valid(std::size_t i) const { return valid.empty() || valid[i] != 0; }
  float at(int c, int r) const { return z[index(c, r)]; }
  // Plane point -> fractional (column, row).
  Point2 to_grid(const Point2& p) const { return {(p[0] - x0) / dx, (p[1] - y0) / dy}; }
  // Bilinear between samples, clamped to the outermost ones.
  double bilinear(const Point2& p) const;
};

struct TerrainOptions {
  double max_error = 1;                  // vertical, in the grid's height units; > 0
  Parameters<2> engine;                  // rho: angles >= arcsin(1 / (2 rho)), 20.7 degrees by default
  // Seeds' plane-fit tolerance over max_error; 0: no seeds (the fewest triangles). Seeds cost triangles:
  // on the Salish Sea DEM 0.5 gives 2 to 2.6 times the triangles of 0 (bench/RESULTS.md); patches are
  // local without them (block picks and levels).
  double seed_fraction = 0;
  // Land and water in one TIN (`mesh --dem --land-up-to`, docs/terrain.md): instead of the grid's rectangle
  // the TIN covers the water of these rings (even-odd rule), their lines (the shoreline) chains of edges
  // inside it, all in the grid's plane; rings and lines may share vertices. Empty: the rectangle. With a
  // domain, max_error may be infinite (no greedy rounds: the mesh of the rings alone), seeds are refused,
  // and a patch brings the new rings along. The rings must lie within a cell of the samples' rectangle.
  Domain2 domain;
  // The error bound holds at the valid samples at or above this height (the land of a land-and-water TIN);
  // samples below it are neither measured nor picked.
  double bound_from = -std::numeric_limits<double>::infinity();
  // A round picks the worst sample of a triangle over the bound only if no other triangle's worst sample
  // within pick_spacing times that triangle's longest edge has a larger error (ties: the smaller row-major
  // index); 0: every such triangle's worst sample (clustered picks: on a smooth 1000 x 1000 DEM 3.1 times
  // the triangles of 0.5, docs/terrain.md "Where the Steiner points come from"). A function of the TIN
  // either way; the round's overall worst sample is always picked. Must be finite and >= 0.
  double pick_spacing = 0.5;
  // Block picks (docs/terrain.md "One setting for both targets"): the raster cut into fixed blocks of
  // block_cells cells; each block edge approximated on its own (Douglas-Peucker), each block by greedy
  // (Garland-Heckbert) insertion on its own Delaunay triangulation, both within block_fraction *
  // max_error. Their union is the input of the first round, a function of the grid in which a patch
  // changes only the blocks it touches; the greedy rounds then only correct what the engine's quality TIN
  // leaves over the bound.
  // 0: none (rounds from the corners alone: exact patches too, but a patch moves picks far from it and
  // costs about 14x more on a 10^6-sample DEM, bench/RESULTS.md). Ignored with a domain.
  int block_cells = 16;
  double block_fraction = 1;  // in (0, 1]
};

// The error of the TIN measured sample by sample (valid samples only).
struct TerrainError {
  double max = 0, rms = 0;
  std::size_t samples = 0;       // valid samples measured
  std::size_t over = 0;          // of them farther than max_error from the TIN
  std::size_t worst_sample = 0;  // row-major index of the largest error
};

// What a build or a patch did.
struct TerrainUpdate {
  std::size_t seeds_added = 0, seeds_removed = 0;   // quadtree seeds
  std::size_t block_picks_added = 0, block_picks_removed = 0;
  std::size_t picks_added = 0, picks_removed = 0;   // greedy round picks, over all levels
  std::size_t boundary_splits = 0;                  // midpoints of encroached boundary edges (in the rounds)
  std::size_t rounds = 0;                           // greedy rounds (levels below the first)
  std::size_t steiner_added = 0, steiner_removed = 0;
  std::size_t triangles_measured = 0;               // triangles whose error was computed
  std::size_t operations = 0;                       // engine operations undone + executed
  double seed_ms = 0, engine_ms = 0, mesh_ms = 0, error_ms = 0;
};

class TerrainSession {
 public:
  // InputError: a grid under 2 x 2, heights not finite, no valid sample. ParameterError: max_error not > 0
  // or not finite, seed_fraction outside [0, 1].
  TerrainSession(HeightGrid grid, const TerrainOptions& options);
  ~TerrainSession();
  TerrainSession(TerrainSession&&) noexcept;
  TerrainSession& operator=(TerrainSession&&) noexcept;

  // New heights in the window [col, col + w) x [row, row + h) (row-major; `valid` empty: every patched
  // sample holds data, nodata there before included).
  // Afterwards the session equals a fresh TerrainSession on the patched grid. InputError (nothing
  // changed) for a window outside the grid, sizes that do not match, or heights that are not finite.
  TerrainUpdate patch(int col, int row, int w, int h, std::span<const float> z,
                      std::span<const std::uint8_t> valid = {});
  // A TIN with a domain (land and water): the same, and the domain becomes `domain` (its rings and lines
  // traced on the patched grid by the caller). The session then equals a fresh TerrainSession on the
  // patched grid with `domain`. InputError (nothing changed) also for rings with a defect or reaching
  // more than a cell outside the grid; ParameterError for a session without a domain.
  TerrainUpdate patch(int col, int row, int w, int h, std::span<const float> z, std::span<const std::uint8_t> valid,
                      const Domain2& domain);

  // Builds what patches need that a build does not make (the rounds' levels, docs/terrain.md "One
  // setting for both targets"); the first patch does it otherwise (about a build's time). Idempotent.
  void prepare_patches();

  const HeightGrid& grid() const;
  const TerrainOptions& options() const;
  const TerrainUpdate& build_stats() const;

  // The TIN, canonical: points sorted by coordinates, each triangle counter-clockwise from its smallest
  // index, triangles sorted. Points are the nodes the triangles use.
  const std::vector<Point2>& points() const;
  const std::vector<double>& heights() const;        // per point
  const std::vector<PointKind>& kinds() const;       // Input: a sample (seed, pick, corner); else Steiner
  const std::vector<Element<2>>& triangles() const;

  // Measures every valid sample at or above bound_from against the TIN (O(samples)). With a domain,
  // samples outside every triangle (outside the domain) are skipped; without one they count as infinite.
  TerrainError error() const;
  std::size_t seed_count() const;
  std::size_t pick_count() const;        // the greedy (correction) rounds' picks
  std::size_t block_pick_count() const;  // the block picks (corners of blocks included)
  std::size_t input_count() const;     // the (deepest level's) engine's input points (samples, splits)
  std::size_t steiner_count() const;   // the engine's Steiner points (the whole box, not only the TIN's)
  std::size_t rounds() const;          // greedy rounds (levels below the first; inside rings: of the last build or patch)

  // Recomputes the canonical TIN from the engine's mesh and the seeds from the grid, and throws
  // std::logic_error when either differs from what the session holds (tests).
  void check_valid() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Angles of a triangle list, degrees: {min, max} over all triangles.
std::array<double, 2> angle_range(std::span<const Point2> points, std::span<const Element<2>> triangles);

}  // namespace shoremesh
