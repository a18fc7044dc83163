// The paper's Figure 7 (right): speedup of one unit dynamic change over StableWS from scratch.
// A unit change removes a random input point and updates, then adds a new random point and updates.
//
//   bench_dynamic --dim 2|3 --n N --changes C --inputs K --seed S [--window W] [--mesh 1]
//   bench_dynamic --input FILE [--lonlat 1] [--spacing S] [--step H] --changes C --seed S ...
//
// Input k (0 <= k < K) is families::uniform(N, S + k). With --input, the one input is a 2D file read as
// `shoremesh` reads it (--lonlat, --spacing as there; a ring file of a lake shore, say), in the box the
// tool fits to it, and a change moves a random input point by up to H (in the file's units, default
// the spacing, else a thousandth of the box) along each axis: one update, a shore edit. Prints one line of key=value fields: the
// from-scratch run (operations, seconds), the unit changes (mean operations and seconds), the single
// updates (median and 99th percentile latency, median and maximum operations touched), the speedups in
// operations and in time, and the work per clipped cell during the build and the updates. Input
// generation is not timed. With --window W, a line per W changes of each input comes first
// ("window=..."), with the median, 99th percentile and maximum of that window's updates and the engine's memory
// (not timed): how latency and memory evolve over a long edit session. update_steiner_changes_median: the
// Steiner points removed plus added by one update, the median (the size of the output's change).
// With --mesh 1, a Delaunay mesh of the output (core's Mesh, a CGAL triangulation) follows every update
// the way the shoremesh edit session updates it (Mesh::apply: CGAL's incremental removal and insertion
// of the changed points), and the median and 99th percentile of that step are printed too: what an edit
// costs after the engine, and a yardstick for the engine's own time (the same change, applied by CGAL, with
// the elements removed and added worked out).
// update_median_cpu_seconds: the same latencies in the updating thread's CPU time. Last come the engine's
// bytes after the changes (the last input's), in all and per output vertex part by part
// (WellSpacedEngine::memory_breakdown, by capacity), and the process's resident memory then.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/engine/engine.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/io/read_input.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/well_spaced.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
// This thread's CPU seconds (updates run on the calling thread): on a machine loaded by other work, the
// wall-clock latencies grow with the load and these do not.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Options {
  int dim = 2;
  std::size_t n = 1000, changes = 100, inputs = 1, window = 0;
  std::uint64_t seed = 1;
  bool mesh = false;
  std::string input;  // a file instead of the uniform family (2D)
  bool lonlat = false;
  double spacing = 0, step = 0;
};

// The file's points in the unit box (the box `shoremesh` fits), and the step of a move in unit lengths.
std::vector<shoremesh::Point<2>> read_file_points(const Options& opt, double& step) {
  shoremesh::io::InputOptions options;
  options.lonlat = opt.lonlat;
  options.ring_spacing = opt.spacing;
  const shoremesh::io::InputSet set = shoremesh::io::read_input(opt.input, options);
  if (set.dimension != 2) throw shoremesh::InputError(opt.input + ": bench_dynamic --input reads 2D inputs only");
  const auto box = shoremesh::BoxTransform<2>::fit(set.points);
  std::vector<shoremesh::Point<2>> unit;
  for (const auto& p : set.points) unit.push_back(box.to_unit(p));
  step = opt.step > 0 ? opt.step / box.side : opt.spacing > 0 ? opt.spacing / box.side : 1e-3;
  return unit;
}

// Cells computed and taken from the cache; box searches, leaves searched, candidate vertices looked at
// and half-spaces clipped, summed over the cells computed.
struct CellWork {
  double cells = 0, reused = 0, listed = 0, updated = 0, searches = 0, leaves = 0, candidates = 0, clips = 0;
  void add(const shoremesh::Counters& after, const shoremesh::Counters& before) {
    cells += double(after.clipped_voronoi_calls - before.clipped_voronoi_calls);
    reused += double(after.cells_reused - before.cells_reused);
    listed += double(after.neighbourhoods_reused - before.neighbourhoods_reused);
    updated += double(after.cells_updated - before.cells_updated);
    searches += double(after.neighbour_searches - before.neighbour_searches);
    leaves += double(after.leaves_visited - before.leaves_visited);
    candidates += double(after.candidates - before.candidates);
    clips += double(after.clips - before.clips);
  }
};

// The process's resident memory now (Linux: /proc/self/statm), 0 when unknown.
std::size_t resident_bytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long pages = 0, resident = 0;
  const int read = std::fscanf(f, "%lu %lu", &pages, &resident);
  std::fclose(f);
  return read == 2 ? std::size_t(resident) * std::size_t(sysconf(_SC_PAGESIZE)) : 0;
}

template <class T>
T quantile(std::vector<T> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

template <int D>
void run(const Options& opt) {
  double build_seconds = 0, build_ops = 0, unit_seconds = 0, unit_ops = 0, output = 0;
  // The first change after a build, the slower of its two updates, the slowest over the inputs: what the
  // first edit after loading costs (growing a pool or a table then shows here, not in the median).
  double first_update_seconds = 0;
  std::vector<double> latencies, cpu_latencies, update_ops, steiner_changes, mesh_latencies;
  CellWork build_work, update_work;
  // The last input's engine after its changes, and its output then.
  typename shoremesh::WellSpacedEngine<D>::MemoryBreakdown memory;
  double memory_output = 1;
  const std::size_t updates_per_change = opt.input.empty() ? 2 : 1;
  std::size_t n = opt.n;
  for (std::size_t input = 0; input < opt.inputs; ++input) {
    double step = 0;  // a move's largest offset along an axis, with --input
    std::vector<shoremesh::Point<D>> points;
    if constexpr (D == 2) {
      if (!opt.input.empty()) points = read_file_points(opt, step);
    }
    if (opt.input.empty()) points = shoremesh::families::uniform<D>(opt.n, opt.seed + input);
    n = points.size();
    shoremesh::WellSpacedSet<D> set;
    auto t0 = Clock::now();
    set.build(points);
    build_seconds += seconds_since(t0);
    build_ops += double(set.counters().operations());
    output += double(set.input_count() + set.steiner_count());
    const shoremesh::Counters after_build = set.counters();
    std::optional<shoremesh::Mesh<D>> mesh;
    // Clipped to the engine's box (the unit box here), as the edit session's mesh is.
    if (opt.mesh) mesh.emplace(set.output_points(), set.input_count(), shoremesh::BoxTransform<D>{});
    // The engine's report of one update, as the mesh takes it (the input point first, as the edit
    // session passes it), and the time Mesh::apply took.
    auto follow = [&](const shoremesh::UpdateReport<D>& report, const shoremesh::Point<D>* input_removed,
                      const shoremesh::Point<D>* input_added) {
      steiner_changes.push_back(double(report.steiner_removed.size() + report.steiner_added.size()));
      if (!mesh) return;
      std::vector<shoremesh::Point<D>> removed, added;
      if (input_removed) removed.push_back(*input_removed);
      if (input_added) added.push_back(*input_added);
      const auto change = shoremesh::PointChange<D>::from_update(report, std::move(removed), std::move(added));
      const auto t = Clock::now();
      mesh->apply(change);
      mesh_latencies.push_back(seconds_since(t));
    };
    build_work.add(after_build, shoremesh::Counters{});
    std::mt19937_64 rng(opt.seed * 7919 + input);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    // The live ids, kept here in O(1) per change: listing them from the set (O(n)) between updates
    // would also flush the caches before every removal.
    std::vector<std::size_t> ids = set.input_ids();
    for (std::size_t c = 0; c < opt.changes; ++c) {
      if (!opt.input.empty()) {  // a shore edit: one point moved a little, one update
        shoremesh::UpdateReport<D> moved;
        const std::size_t id = ids[rng() % ids.size()];
        const shoremesh::Point<D> from = set.input_point(id);
        shoremesh::Point<D> to;
        for (int i = 0; i < D; ++i) to[i] = std::clamp(from[i] + step * (2 * u(rng) - 1), 0.0, 1.0);
        auto t = Clock::now();
        const double c0 = thread_cpu_seconds();
        set.move(id, to, &moved);
        cpu_latencies.push_back(thread_cpu_seconds() - c0);
        const double a = seconds_since(t);
        follow(moved, &from, &to);
        if (c == 0) first_update_seconds = std::max(first_update_seconds, a);
        latencies.push_back(a);
        update_ops.push_back(double(moved.operations_touched()));
        unit_seconds += a;
        unit_ops += double(moved.operations_touched());
      } else {  // the paper's unit change: a random input point removed, a random point added
        shoremesh::UpdateReport<D> removed, added;
        const std::size_t k = rng() % ids.size();
        const shoremesh::Point<D> gone = set.input_point(ids[k]);
        auto t1 = Clock::now();
        const double c1 = thread_cpu_seconds();
        set.remove(ids[k], &removed);
        cpu_latencies.push_back(thread_cpu_seconds() - c1);
        const double a = seconds_since(t1);
        shoremesh::Point<D> p;
        for (auto& x : p) x = u(rng);
        auto t2 = Clock::now();
        const double c2 = thread_cpu_seconds();
        const std::size_t id = set.add(p, &added);
        cpu_latencies.push_back(thread_cpu_seconds() - c2);
        const double b = seconds_since(t2);
        ids[k] = id;
        follow(removed, &gone, nullptr);
        follow(added, nullptr, &p);
        if (c == 0) first_update_seconds = std::max({first_update_seconds, a, b});
        latencies.push_back(a);
        latencies.push_back(b);
        update_ops.push_back(double(removed.operations_touched()));
        update_ops.push_back(double(added.operations_touched()));
        unit_seconds += a + b;
        unit_ops += double(removed.operations_touched() + added.operations_touched());
      }
      if (opt.window > 0 && (c + 1) % opt.window == 0) {
        const std::vector<double> last(latencies.end() - long(updates_per_change * opt.window), latencies.end());
        std::printf("window=%zu input=%zu changes=%zu..%zu update_median_seconds=%.6g update_p99_seconds=%.6g "
                    "update_max_seconds=%.6g engine_memory_bytes=%zu\n",
                    (c + 1) / opt.window, input, c + 1 - opt.window, c + 1, quantile(last, 0.5), quantile(last, 0.99),
                    *std::max_element(last.begin(), last.end()), set.memory_bytes());
        std::fflush(stdout);
      }
    }
    update_work.add(set.counters(), after_build);
    memory = set.engine().memory_breakdown();
    memory_output = double(set.input_count() + set.steiner_count());
  }
  const double k = double(opt.inputs), changes = double(opt.inputs * opt.changes);
  const double updates = double(updates_per_change) * changes;
  char mesh_fields[128] = "";
  if (opt.mesh)
    std::snprintf(mesh_fields, sizeof mesh_fields, " mesh_update_median_seconds=%.6g mesh_update_p99_seconds=%.6g",
                  quantile(mesh_latencies, 0.5), quantile(mesh_latencies, 0.99));
  std::printf(
      "dim=%d n=%zu inputs=%zu changes_per_input=%zu output_vertices=%.0f build_seconds=%.6f build_ops=%.0f "
      "unit_change_seconds=%.6g unit_change_ops=%.1f update_median_seconds=%.6g update_p99_seconds=%.6g "
      "update_median_ops=%.0f update_max_ops=%.0f first_update_seconds=%.6g speedup_ops=%.1f speedup_time=%.1f "
      "build_leaves_per_cell=%.1f build_candidates_per_cell=%.1f build_clips_per_cell=%.1f "
      "update_cells=%.1f update_leaves_per_cell=%.1f update_candidates_per_cell=%.1f update_clips_per_cell=%.1f build_searches_per_cell=%.2f update_searches_per_cell=%.2f update_cells_reused=%.1f update_cells_from_lists=%.1f update_cells_updated=%.1f "
      "update_steiner_changes_median=%.0f%s update_median_cpu_seconds=%.6g update_p99_cpu_seconds=%.6g engine_memory_bytes=%zu engine_bytes_per_vertex=%.1f "
      "bytes_per_vertex_vertices=%.1f bytes_per_vertex_positions=%.1f bytes_per_vertex_operations=%.1f "
      "bytes_per_vertex_children=%.1f bytes_per_vertex_readers=%.1f "
      "bytes_per_vertex_tree=%.1f bytes_per_vertex_other=%.1f rss_bytes=%zu points=%s\n",
      D, n, opt.inputs, opt.changes, output / k, build_seconds / k, build_ops / k, unit_seconds / changes,
      unit_ops / changes, quantile(latencies, 0.5), quantile(latencies, 0.99), quantile(update_ops, 0.5),
      quantile(update_ops, 1.0), first_update_seconds, (build_ops / k) / (unit_ops / changes), (build_seconds / k) / (unit_seconds / changes),
      build_work.leaves / build_work.cells, build_work.candidates / build_work.cells, build_work.clips / build_work.cells,
      update_work.cells / updates, update_work.leaves / update_work.cells, update_work.candidates / update_work.cells,
      update_work.clips / update_work.cells, build_work.searches / build_work.cells,
      update_work.searches / update_work.cells, update_work.reused / updates, update_work.listed / updates,
      update_work.updated / updates, quantile(steiner_changes, 0.5), mesh_fields, quantile(cpu_latencies, 0.5),
      quantile(cpu_latencies, 0.99), memory.total(),
      double(memory.total()) / memory_output, double(memory.vertices) / memory_output,
      double(memory.positions) / memory_output, double(memory.operations) / memory_output,
      double(memory.children) / memory_output,
      double(memory.readers) / memory_output, double(memory.tree) / memory_output,
      double(memory.other) / memory_output, resident_bytes(),
      opt.input.empty() ? "uniform" : opt.input.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; i += 2) {
    const std::string key = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    if (value && key == "--dim") opt.dim = std::atoi(value);
    else if (value && key == "--n") opt.n = std::size_t(std::atof(value));
    else if (value && key == "--changes") opt.changes = std::size_t(std::atof(value));
    else if (value && key == "--inputs") opt.inputs = std::size_t(std::atof(value));
    else if (value && key == "--seed") opt.seed = std::uint64_t(std::atoll(value));
    else if (value && key == "--window") opt.window = std::size_t(std::atof(value));
    else if (value && key == "--mesh") opt.mesh = std::atoi(value) != 0;
    else if (value && key == "--input") opt.input = value;
    else if (value && key == "--lonlat") opt.lonlat = std::atoi(value) != 0;
    else if (value && key == "--spacing") opt.spacing = std::atof(value);
    else if (value && key == "--step") opt.step = std::atof(value);
    else {
      std::fprintf(stderr,
                   "usage: bench_dynamic --dim 2|3 --n N --changes C --inputs K --seed S [--window W] [--mesh 1]\n"
                   "       bench_dynamic --input FILE [--lonlat 1] [--spacing S] [--step H] --changes C --seed S ...\n");
      return 2;
    }
  }
  if ((opt.dim != 2 && opt.dim != 3) || opt.n < 2 || opt.changes < 1 || opt.inputs < 1 || !(opt.spacing >= 0) || !(opt.step >= 0) ||
      (!opt.input.empty() && (opt.dim != 2 || opt.inputs != 1))) {
    std::fprintf(stderr, "bench_dynamic: need --dim 2 or 3, --n >= 2, --changes >= 1, --inputs >= 1 (with --input: 2D, one input; --spacing, --step >= 0)\n");
    return 2;
  }
  try {
    if (opt.dim == 3) run<3>(opt);
    else run<2>(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_dynamic: %s\n", e.what());
    return 1;
  }
  return 0;
}
