// The local clipped Voronoi cell is exact on degenerate inputs: a grid point's cell is its square/cube,
// with the diagonal neighbours' bisectors passing exactly through its corners and adding nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <vector>

#include "shoremesh/engine/convex_cell.hpp"

namespace shoremesh::engine {
namespace {

// Reproducible numbers in [0, 1) (a 64-bit linear congruential generator).
struct Uniform01 {
  std::uint64_t x;
  double operator()() {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    return double(x >> 11) * 0x1p-53;
  }
};

TEST(ConvexCell, GridPointCellIsASquare2D) {
  RoundingGuard guard;
  ConvexCell<2> cell;
  const Point<2> v{0.5, 0.5};
  cell.reset(v, {0.3, 0.3}, {0.7, 0.7});
  VertexId id = 0;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      if (dx || dy) cell.clip(id++, {0.5 + 0.125 * dx, 0.5 + 0.125 * dy}, 0.015625 * (dx * dx + dy * dy));
  EXPECT_EQ(cell.vertex_count(), 4u);
  std::vector<VertexId> nb;
  cell.bisector_neighbours(nb);
  EXPECT_EQ(nb.size(), 4u);  // the four edge neighbours bound it; the diagonals only touch corners
  // Corners at squared distance 2 (h/2)^2 = NN^2 / 2 exactly (dyadic coordinates): within 0.5 NN^2, the
  // boundary case, and not within 0.49 NN^2.
  EXPECT_TRUE(cell.within_scaled_distance(0.5, {0.625, 0.5}));
  EXPECT_FALSE(cell.within_scaled_distance(0.49, {0.625, 0.5}));
}

TEST(ConvexCell, GridPointCellIsACube3D) {
  RoundingGuard guard;
  ConvexCell<3> cell;
  const Point<3> v{0.5, 0.5, 0.5};
  cell.reset(v, {0.3, 0.3, 0.3}, {0.7, 0.7, 0.7});
  VertexId id = 0;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz)
        if (dx || dy || dz)
          cell.clip(id++, {0.5 + 0.125 * dx, 0.5 + 0.125 * dy, 0.5 + 0.125 * dz}, 0.015625 * (dx * dx + dy * dy + dz * dz));
  EXPECT_EQ(cell.vertex_count(), 8u);
  std::vector<VertexId> nb;
  cell.bisector_neighbours(nb);
  EXPECT_EQ(nb.size(), 6u);
  EXPECT_TRUE(cell.within_scaled_distance(0.75, {0.625, 0.5, 0.5}));  // corners at 3 (h/2)^2 = 0.75 NN^2
  EXPECT_FALSE(cell.within_scaled_distance(0.74, {0.625, 0.5, 0.5}));
}

TEST(ConvexCell, RandomCellVerticesAreEquidistantFromTheirSites3D) {
  RoundingGuard guard;
  ConvexCell<3> cell;
  const Point<3> v{0.5, 0.5, 0.5};
  cell.reset(v, {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  Uniform01 rnd{12345};
  std::vector<Point<3>> sites;
  for (VertexId id = 0; id < 60; ++id) {
    Point<3> w{0.2 + 0.6 * rnd(), 0.2 + 0.6 * rnd(), 0.2 + 0.6 * rnd()};
    sites.push_back(w);
    cell.clip(id, w, squared_distance<double, 3>(w, v));
  }
  // The farthest vertex c of the cell: no site is nearer to c than v (up to rounding of c).
  Point<3> y = cell.farthest_vertex_offset();
  Point<3> c{v[0] + y[0], v[1] + y[1], v[2] + y[2]};
  auto d2 = [](const Point<3>& a, const Point<3>& b) {
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
  };
  for (const auto& w : sites) EXPECT_GE(d2(c, w), d2(c, v) * (1 - 1e-9));
  EXPECT_GE(cell.vertex_count(), 4u);
}

// Lattice cells are full of points on four or more planes, and clipped in a shuffled order their cuts
// meet vertices exactly again and again: the cell must still count each point once and list only the
// sites whose bisector bounds a face. Simple cubic: a cube (8 points, 6 faces). Body-centred cubic: a
// truncated octahedron (24, 14). Face-centred cubic: a rhombic dodecahedron (14, 12), six of whose
// points lie on four faces and on the bisectors of the second neighbours too.
struct LatticeCell {
  const char* name;
  bool (*member)(int, int, int);
  std::size_t vertices, faces;
  int face_distance2_max;  // the sites at squared distance <= this bound faces (lattice units)
};

void lattice_cell_in_shuffled_orders(const LatticeCell& lattice) {
  RoundingGuard guard;
  const double unit = 1.0 / 32;  // dyadic: every bisector and cell vertex is exact
  const Point<3> v{0.5, 0.5, 0.5};
  struct Site {
    Point<3> p;
    VertexId id;
    int d2;
  };
  std::vector<Site> sites;
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j)
      for (int k = -3; k <= 3; ++k)
        if ((i || j || k) && lattice.member(i, j, k))
          sites.push_back({{0.5 + unit * i, 0.5 + unit * j, 0.5 + unit * k}, VertexId(sites.size()), i * i + j * j + k * k});
  std::sort(sites.begin(), sites.end(), [](const Site& a, const Site& b) { return a.d2 != b.d2 ? a.d2 < b.d2 : a.p < b.p; });
  std::vector<VertexId> expected;
  for (const Site& s : sites)
    if (s.d2 <= lattice.face_distance2_max) expected.push_back(s.id);
  std::sort(expected.begin(), expected.end());
  std::uint64_t x = 7;
  for (int order = 0; order < 40; ++order) {
    // Order 0: by distance, as the engine clips; then shuffled.
    if (order > 0)
      for (std::size_t k = sites.size() - 1; k > 0; --k) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        std::swap(sites[k], sites[std::size_t(x >> 33) % (k + 1)]);
      }
    ConvexCell<3> cell;
    cell.reset(v, {0.3, 0.3, 0.3}, {0.7, 0.7, 0.7});
    for (const Site& s : sites) cell.clip(s.id, s.p, unit * unit * s.d2);
    EXPECT_EQ(cell.vertex_count(), lattice.vertices) << lattice.name << ", order " << order;
    std::vector<VertexId> nb;
    cell.bisector_neighbours(nb);
    EXPECT_EQ(nb, expected) << lattice.name << ", order " << order;
  }
}

TEST(ConvexCell, LatticeCellsCountEachPointOnceInAnyCutOrder3D) {
  lattice_cell_in_shuffled_orders({"simple cubic", [](int, int, int) { return true; }, 8, 6, 1});
  lattice_cell_in_shuffled_orders(
      {"body-centred cubic", [](int i, int j, int k) { return (i & 1) == (j & 1) && (j & 1) == (k & 1); }, 24, 14, 4});
  lattice_cell_in_shuffled_orders({"face-centred cubic", [](int i, int j, int k) { return ((i + j + k) & 1) == 0; }, 14, 12, 2});
}

// Vertices are solved in doubles with an error bound (and in intervals where the bound cannot decide):
// every vertex's box must hold its exact position, also for sites nearly on a line or a plane, nearly
// equidistant, 1e-9 apart, or far from v relative to their spacing (ill-conditioned vertices).
template <int D>
void vertex_boxes_hold_exact_positions(std::uint64_t seed) {
  RoundingGuard guard;
  Uniform01 rnd{seed};
  for (int shape = 0; shape < 4; ++shape) {
    Point<D> v, lo, hi;
    for (int i = 0; i < D; ++i) {
      v[i] = 0.3 + 0.4 * rnd();
      lo[i] = v[i] - 0.2;
      hi[i] = v[i] + 0.2;
    }
    ConvexCell<D> cell;
    cell.reset(v, lo, hi);
    std::vector<std::pair<double, Point<D>>> sites;
    for (int k = 0; k < 60; ++k) {
      Point<D> w;
      for (int i = 0; i < D; ++i) {
        switch (shape) {
          case 0: w[i] = v[i] + 0.2 * (rnd() - 0.5); break;                               // uniform
          case 1: w[i] = v[i] + (i == 0 ? 0.1 * (rnd() - 0.5) : 1e-7 * (rnd() - 0.5)); break;  // nearly a line
          case 2: w[i] = v[i] + 1e-9 * (rnd() - 0.5) + (k % 2 ? 1e-3 : -1e-3); break;       // two tight clusters
          default: w[i] = v[i] + (i + 1 < D ? 0.1 * (rnd() - 0.5) : 0.05 + 1e-12 * rnd()); break;  // a plane
        }
      }
      if (w == v) continue;
      sites.push_back({squared_distance<double, D>(w, v), w});
    }
    std::sort(sites.begin(), sites.end());
    VertexId id = 0;
    for (const auto& [d2, w] : sites) {
      cell.clip(id++, w, d2);
      ASSERT_TRUE(cell.vertex_boxes_hold_exact_positions()) << "seed " << seed << ", shape " << shape << ", site " << id;
    }
  }
}

TEST(ConvexCell, VertexBoxesHoldExactPositions2D) {
  for (std::uint64_t seed : {1, 2, 3, 4, 5, 6, 7, 8}) vertex_boxes_hold_exact_positions<2>(seed);
}

TEST(ConvexCell, VertexBoxesHoldExactPositions3D) {
  for (std::uint64_t seed : {1, 2, 3, 4, 5, 6, 7, 8}) vertex_boxes_hold_exact_positions<3>(seed);
}

// A cell cut by some sites in distance order, then by the others in any order between
// begin_out_of_order_cuts and end_out_of_order_cuts, is the cell all sites cut in distance order give,
// bit for bit: how the engine brings a cached cell up to date with the vertices born since.
template <int D>
void out_of_order_cuts_equal_distance_order(std::uint64_t seed) {
  RoundingGuard guard;
  Uniform01 rnd{seed};
  Point<D> v, lo, hi;
  for (int i = 0; i < D; ++i) {
    v[i] = 0.5;
    lo[i] = 0.3;
    hi[i] = 0.7;
  }
  struct Site {
    double d2;
    Point<D> p;
    VertexId id;
  };
  std::vector<Site> sites;
  for (VertexId id = 0; id < 80; ++id) {
    Point<D> w;
    for (int i = 0; i < D; ++i) w[i] = 0.3 + 0.4 * rnd();
    sites.push_back({squared_distance<double, D>(w, v), w, id});
  }
  std::vector<Site> later;  // every third site comes "later", in random order
  std::vector<Site> first;
  for (const Site& s : sites) (s.id % 3 == 0 ? later : first).push_back(s);
  auto by_distance = [](const Site& a, const Site& b) { return a.d2 != b.d2 ? a.d2 < b.d2 : a.p < b.p; };
  std::sort(sites.begin(), sites.end(), by_distance);
  std::sort(first.begin(), first.end(), by_distance);

  ConvexCell<D> fresh, updated;
  fresh.reset(v, lo, hi);
  for (const Site& s : sites) fresh.clip(s.id, s.p, s.d2);
  updated.reset(v, lo, hi);
  for (const Site& s : first) updated.clip(s.id, s.p, s.d2);
  updated.begin_out_of_order_cuts();
  for (const Site& s : later) updated.clip(s.id, s.p, s.d2);
  updated.end_out_of_order_cuts();

  ASSERT_FALSE(fresh.had_vertex_on_plane());
  EXPECT_EQ(updated.vertex_count(), fresh.vertex_count());
  EXPECT_EQ(updated.max_vertex_distance2(), fresh.max_vertex_distance2());
  EXPECT_EQ(updated.farthest_vertex_offset(), fresh.farthest_vertex_offset());
  std::vector<VertexId> a, b;
  updated.bisector_neighbours(a);
  fresh.bisector_neighbours(b);
  EXPECT_EQ(a, b);
  // Cut further in distance order afterwards (a fill's Steiner points), both stay the same.
  const Point<D> extra = sites.front().p;
  Point<D> w;
  for (int i = 0; i < D; ++i) w[i] = 0.5 * (v[i] + extra[i]) + 0.01;
  updated.clip(1000, w, squared_distance<double, D>(w, v));
  fresh.clip(1000, w, squared_distance<double, D>(w, v));
  EXPECT_EQ(updated.vertex_count(), fresh.vertex_count());
  EXPECT_EQ(updated.farthest_vertex_offset(), fresh.farthest_vertex_offset());
  EXPECT_EQ(updated.max_vertex_distance2(), fresh.max_vertex_distance2());
}

TEST(ConvexCell, OutOfOrderCutsEqualDistanceOrder2D) {
  for (std::uint64_t seed : {1, 2, 3, 4, 5}) out_of_order_cuts_equal_distance_order<2>(seed);
}

TEST(ConvexCell, OutOfOrderCutsEqualDistanceOrder3D) {
  for (std::uint64_t seed : {1, 2, 3, 4, 5}) out_of_order_cuts_equal_distance_order<3>(seed);
}

// The bits of every vertex box of random 3D cells, pinned: they fix the Steiner points (the farthest
// vertex's midpoint), so any other enclosure, however valid, changes the output. The vertex solve pairs
// each value with its error bound's magnitude in one register; these are the bits the scalar solve gave.
TEST(ConvexCell, VertexBoxBitsArePinned3D) {
  RoundingGuard guard;
  std::uint64_t hash = 1469598103934665603ull;
  for (std::uint64_t seed : {1, 2, 3, 4, 5, 6, 7, 8}) {
    Uniform01 rnd{seed};
    const Point<3> v{0.3 + 0.4 * rnd(), 0.3 + 0.4 * rnd(), 0.3 + 0.4 * rnd()};
    std::vector<std::pair<double, Point<3>>> sites;
    for (int k = 0; k < 120; ++k) {
      const Point<3> w{v[0] + 0.2 * (rnd() - 0.5), v[1] + 0.2 * (rnd() - 0.5), v[2] + 0.2 * (rnd() - 0.5)};
      sites.push_back({squared_distance<double, 3>(w, v), w});
    }
    std::sort(sites.begin(), sites.end());
    ConvexCell<3> cell;
    cell.reset(v, {v[0] - 0.08, v[1] - 0.08, v[2] - 0.08}, {v[0] + 0.08, v[1] + 0.08, v[2] + 0.08});
    VertexId id = 0;
    for (const auto& [d2, w] : sites) cell.clip(id++, w, d2);
    std::vector<std::array<double, 6>> boxes;  // sorted: the vertices' order is no part of the cell
    cell.for_each_vertex_box([&](const std::array<Interval, 3>& y) {
      boxes.push_back({y[0].inf(), y[0].sup(), y[1].inf(), y[1].sup(), y[2].inf(), y[2].sup()});
    });
    std::sort(boxes.begin(), boxes.end());
    for (const auto& b : boxes)
      for (double x : b) hash = (hash ^ std::bit_cast<std::uint64_t>(x)) * 1099511628211ull;
    hash = (hash ^ boxes.size()) * 1099511628211ull;
  }
  EXPECT_EQ(hash, 0x77a6d463f0aaccf9ull);
}

}  // namespace
}  // namespace shoremesh::engine
