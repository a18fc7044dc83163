// The paper's Figure 7 (right): speedup of one unit dynamic change over StableWS from scratch.
// A unit change removes a random input point and updates, then adds a new random point and updates.
//
//   bench_dynamic --dim 2|3 --n N --changes C --inputs K --seed S
//
// Prints one line: operation counts and wall times of the from-scratch run and of the updates (mean
// per unit change, median and 99th percentile per single update), and the speedups in operations and
// in time. Input generation is not timed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "shoremesh/families.hpp"
#include "shoremesh/well_spaced.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Options {
  int dim = 2;
  std::size_t n = 1000, changes = 100, inputs = 1;
  std::uint64_t seed = 1;
};

template <int D>
void run(const Options& opt) {
  double build_seconds = 0, build_ops = 0, unit_seconds = 0, unit_ops = 0;
  std::vector<double> latencies;
  std::size_t output = 0;
  // Per clipped cell: leaves searched, candidate vertices looked at, half-spaces clipped (build, updates).
  shoremesh::Counters build_work, update_work;
  for (std::size_t input = 0; input < opt.inputs; ++input) {
    const auto points = shoremesh::families::uniform<D>(opt.n, opt.seed + input);
    shoremesh::WellSpacedSet<D> set;
    auto t0 = Clock::now();
    set.build(points);
    build_seconds += seconds_since(t0);
    build_ops += double(set.counters().operations());
    const shoremesh::Counters after_build = set.counters();
    build_work.clipped_voronoi_calls += after_build.clipped_voronoi_calls;
    build_work.leaves_visited += after_build.leaves_visited;
    build_work.candidates += after_build.candidates;
    build_work.clips += after_build.clips;
    output += set.input_count() + set.steiner_count();
    std::mt19937_64 rng(opt.seed * 7919 + input);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t c = 0; c < opt.changes; ++c) {
      const auto ids = set.input_ids();
      shoremesh::UpdateReport<D> removed, added;
      auto t1 = Clock::now();
      set.remove(ids[rng() % ids.size()], &removed);
      const double a = seconds_since(t1);
      shoremesh::Point<D> p;
      for (auto& x : p) x = u(rng);
      auto t2 = Clock::now();
      set.add(p, &added);
      const double b = seconds_since(t2);
      latencies.push_back(a);
      latencies.push_back(b);
      unit_seconds += a + b;
      unit_ops += double(removed.operations_touched() + added.operations_touched());
    }
    const shoremesh::Counters& end = set.counters();
    update_work.clipped_voronoi_calls += end.clipped_voronoi_calls - after_build.clipped_voronoi_calls;
    update_work.leaves_visited += end.leaves_visited - after_build.leaves_visited;
    update_work.candidates += end.candidates - after_build.candidates;
    update_work.clips += end.clips - after_build.clips;
  }
  std::sort(latencies.begin(), latencies.end());
  const double k = double(opt.inputs), changes = double(opt.inputs * opt.changes);
  std::printf(
      "dim=%d n=%zu inputs=%zu changes_per_input=%zu output_vertices=%.0f build_seconds=%.6f build_ops=%.0f "
      "unit_change_seconds=%.6g unit_change_ops=%.1f update_median_seconds=%.6g update_p99_seconds=%.6g "
      "speedup_ops=%.1f speedup_time=%.1f\n",
      D, opt.n, opt.inputs, opt.changes, double(output) / k, build_seconds / k, build_ops / k, unit_seconds / changes,
      unit_ops / changes, latencies[latencies.size() / 2], latencies[latencies.size() * 99 / 100],
      (build_ops / k) / (unit_ops / changes), (build_seconds / k) / (unit_seconds / changes));
  auto per_cell = [](const char* what, const shoremesh::Counters& c) {
    const double cells = double(std::max<std::uint64_t>(c.clipped_voronoi_calls, 1));
    std::printf("  %s: cells=%llu leaves_per_cell=%.1f candidates_per_cell=%.1f clips_per_cell=%.1f\n", what,
                (unsigned long long)c.clipped_voronoi_calls, double(c.leaves_visited) / cells,
                double(c.candidates) / cells, double(c.clips) / cells);
  };
  per_cell("build", build_work);
  per_cell("updates", update_work);
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const char* value = argv[i + 1];
    if (key == "--dim") opt.dim = std::atoi(value);
    else if (key == "--n") opt.n = std::size_t(std::atof(value));
    else if (key == "--changes") opt.changes = std::size_t(std::atof(value));
    else if (key == "--inputs") opt.inputs = std::size_t(std::atof(value));
    else if (key == "--seed") opt.seed = std::uint64_t(std::atoll(value));
    else {
      std::fprintf(stderr, "usage: bench_dynamic --dim 2|3 --n N --changes C --inputs K --seed S\n");
      return 2;
    }
  }
  if (opt.dim == 3) run<3>(opt);
  else run<2>(opt);
  return 0;
}
