#pragma once
// The algorithm's parameters (paper, section 9) and their validation.
#include <cmath>
#include <cstdint>
#include <limits>

namespace shoremesh {

template <int D>
struct Parameters {
  static_assert(D == 2 || D == 3);
  // Quality: every output vertex's Voronoi cell (clipped to the box) lies within rho * NN of it.
  double rho = std::sqrt(2.0);
  // Picking region outer radius: Steiner points go at distance in [rho*NN, beta*NN).
  double beta = D == 2 ? 2.0 : 2.0 * std::sqrt(2.0) / std::sqrt(3.0);
  // Colours per axis; 0 derives the smallest kappa that satisfies Lemma 6.1 (16 for the defaults).
  int kappa = 0;
  // Figure 3 to the letter: a dispatch asks each of its beta-clipped Voronoi neighbours for a fill at
  // the rank of their distance, and for its own vertex; every fill computes its vertex's cell. By
  // default the dispatch leaves out the fills that provably insert nothing (a neighbour's, see
  // WellSpacedEngine::already_below_rank; its vertex's own when it is well-spaced already), and a fill
  // whose vertex already has a neighbour nearer than its rank stops there (record_idle_fill): the same
  // output with far less work. For the tests that check that claim, and to measure it.
  bool literal_stable_ws = false;
  // Where a fill's Steiner point aims: at the vertex of the cell nearest v among those farther than
  // steiner_aim * rho * NN(v), or at the farthest vertex when none is. Any point of the picking region
  // keeps every guarantee (Fact 1); this choice only changes how many points the output has
  // (docs/picking_region.md). Infinity aims at the farthest vertex always: the 3D default, where the
  // nearest vertex beyond 1.15 rho NN measured 1% more points. At least 1.
  double steiner_aim = D == 2 ? 1.15 : std::numeric_limits<double>::infinity();
  // 2D with water (docs/water_only.md, "Cells that stop at the shore"): the fill of an input vertex on
  // the shore tests well-spacedness on its cell restricted to its water wedge, and picks its Steiner
  // points there (no points on land; the water triangles keep their bound where the shore is not
  // encroached). False: whole cells, the land side too.
  bool shore_cells = D == 2;
};

// The derived constants every part of the engine agrees on. Construct through `derive`, which refuses
// parameters the theory does not support (throws ParameterError with the reason).
template <int D>
struct DerivedParameters {
  double rho = 0;         // as given
  double rho_squared = 0; // the canonical value every exact test uses (2 exactly for the default)
  // The bound a fill enforces: v needs a Steiner point only when its cell reaches beyond
  // rho_squared * (1 + 2^-32) NN^2 (exact test). Then the picking region holds points that doubles can
  // represent; without the margin a degenerate cell (grids: a vertex co-spherical with v's nearest
  // neighbour at exactly rho NN, pushed out by the rounding of the input) leaves a region thinner than an
  // ulp, with no double in it. Every output vertex is rho (1 + 2^-33)-well-spaced (docs/picking_region.md).
  double fill_rho_squared = 0;
  double beta = 0;
  double beta_squared = 0;
  int kappa = 0;          // colours per axis: kappa^D periodic tiles (Lemma 6.1)
  bool literal_stable_ws = false;  // as given
  double steiner_aim_squared = 0;  // steiner_aim^2 rho^2: the squared distance, in NN^2, beyond which a cell vertex is aimed at
  bool shore_cells = false;        // as given
  static DerivedParameters derive(const Parameters<D>& p);
  // l(r) = rho^(r - 1/2) / sqrt(D): side of the rank-r colour tiles.
  double tile_side(int rank) const;
};

// Counters for benchmarks and for spotting broken invariants (a growing leaves-per-query means trouble).
struct Counters {
  std::uint64_t dispatches = 0;
  std::uint64_t fills = 0;
  std::uint64_t fills_idle_by_rank = 0;     // fills whose vertex's nearest neighbour was already below their rank
  std::uint64_t fills_on_land = 0;          // fills skipped: their vertex's cell cannot meet the water (docs/water_only.md)
  std::uint64_t clipped_voronoi_calls = 0;  // cells computed (searched and clipped)
  std::uint64_t cells_reused = 0;          // cells a propagation took from its cache instead
  std::uint64_t neighbourhoods_reused = 0; // cells computed from the cache's vertex lists, not a search
  std::uint64_t cells_updated = 0;         // of those, cut from the cached cell by the new vertices only
  std::uint64_t steiner_points = 0;
  std::uint64_t predicate_calls = 0;   // sign decisions made by the filtered predicates
  std::uint64_t exact_fallbacks = 0;   // of those, decided by exact rational arithmetic
  std::uint64_t neighbour_searches = 0; // box queries to the tree (a cell's search grows in steps)
  std::uint64_t leaves_visited = 0;    // leaves holding a vertex that neighbour searches read
  std::uint64_t candidates = 0;        // vertices those searches looked at
  std::uint64_t clips = 0;             // half-spaces offered to the clipper
  std::uint64_t delaunay_cells = 0;     // 2D one-shot: cells clipped from a walk of the triangulation
  std::uint64_t delaunay_fallbacks = 0; // of the cells it was asked for, those left to the tree search
  std::uint64_t operations_undone = 0; // by dynamic updates
  std::uint64_t operations() const { return dispatches + fills; }
};

}  // namespace shoremesh
