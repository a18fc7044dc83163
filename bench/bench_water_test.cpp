// The mesh's water test (slab lists of the ring edges) against the domain's R-tree of ring edges
// (RingEdgeIndex::inside) on the same rings: build time and 10^6 point queries, uniform in the rings'
// bounding box. Why the mesh keeps the slabs (docs/conforming.md). Prints one line; both must agree.
//   bench_water_test RINGS_FILE   (a ring file, e.g. the Superior rings cut by bench/superior_conforming.py)
#include <chrono>
#include <cstdio>
#include <random>

#include "shoremesh/io/ring_file.hpp"
#include "shoremesh/mesh_water.hpp"
#include "shoremesh/ring_edge_index.hpp"

using namespace shoremesh;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: bench_water_test RINGS_FILE\n");
    return 2;
  }
  const io::RingFile file = io::read_ring_file(argv[1]);
  Domain2 d;
  std::size_t edges = 0;
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (const auto& r : file.rings) {
    d.rings.push_back({r, RingRole::Shore});
    edges += r.size();
    for (const auto& p : r)
      for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
  }
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> ux(lo[0], hi[0]), uy(lo[1], hi[1]);
  std::vector<Point2> queries(1000000);
  for (auto& p : queries) p = {ux(rng), uy(rng)};
  using Clock = std::chrono::steady_clock;
  auto ms = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  const auto t0 = Clock::now();
  const WaterTest slabs(d);
  const auto t1 = Clock::now();
  const RingEdgeIndex tree(d);
  const auto t2 = Clock::now();
  std::size_t in_slabs = 0, in_tree = 0;
  for (const auto& p : queries) in_slabs += slabs.in_water(p);
  const auto t3 = Clock::now();
  for (const auto& p : queries) in_tree += tree.inside(p);
  const auto t4 = Clock::now();
  std::printf("%zu rings, %zu edges: build slabs %.1f ms, R-tree %.1f ms; 10^6 queries: slabs %.0f ms, R-tree %.0f ms"
              " (%zu and %zu in water)\n",
              d.rings.size(), edges, ms(t0, t1), ms(t1, t2), ms(t2, t3), ms(t3, t4), in_slabs, in_tree);
  return in_slabs == in_tree ? 0 : 1;
}
