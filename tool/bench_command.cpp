// shoremesh bench: the standard StableWS benchmark of bench/ (bench/run.sh's StableWS configurations) from
// the installed tool, one key=value line per configuration in bench_static's format, then a table.
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "input_args.hpp"
#include "progress.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/verify.hpp"
#include "shoremesh/well_spaced.hpp"
#include "user_frame.hpp"

namespace shoremesh::tool {

namespace {

struct BenchOptions {
  bool quick = false;
  std::vector<int> dims;
  std::vector<double> sizes;
  std::string family = "uniform";
  int repeats = 0;
  std::uint64_t seed = 1;
  bool verify = false;
  bool quiet = false;
};

struct Config {
  int dim;
  std::size_t n;
  int repeats;
};

// bench/run.sh's StableWS lines.
std::vector<Config> standard_configs(bool quick) {
  if (quick) return {{2, 10000, 3}, {3, 2000, 3}};
  return {{2, 10000, 5}, {2, 100000, 5}, {2, 1000000, 1}, {3, 10000, 5}};
}

std::size_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024;
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

struct Row {
  Config config{};
  std::size_t output = 0;
  double median = 0, median_cpu = 0, ops_per_vertex = 0;
  std::string verdict;
};

template <int D>
Row bench_one(const Config& c, families::FamilyName family, std::uint64_t seed, bool verify) {
  const std::vector<Point<D>> input = families::generate<D>(family, c.n, seed);
  BoxTransform<D> box;
  box.origin.fill(0);
  box.side = 1;
  std::vector<double> wall, cpu;
  StableResult<D> last;
  for (int r = 0; r < c.repeats; ++r) {
    last = StableResult<D>{};
    const double cpu_start = process_cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    last = stable_well_spaced<D>(input, {}, box);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    cpu.push_back(process_cpu_seconds() - cpu_start);
  }
  Row row;
  row.config = c;
  row.median = median(wall);
  row.median_cpu = median(cpu);
  row.output = last.points.size();
  row.ops_per_vertex = static_cast<double>(last.counters.operations()) / static_cast<double>(row.output);
  const std::size_t rss = peak_rss_bytes();
  if (verify) {
    const auto report = verify_well_spaced(last.points, input, box, std::sqrt(2.0));
    row.verdict = std::string(report.ok() ? "ok" : "FAILED") + " worst_ratio=" + approx(report.worst_ratio);
  }
  std::printf("algo=stablews dim=%d family=%s n=%zu seed=%llu repeats=%d output_vertices=%zu median_seconds=%.6f "
              "median_cpu_seconds=%.6f ops_per_vertex=%.4g peak_rss_bytes=%zu bytes_per_vertex=%.1f engine_memory_bytes=%zu%s%s\n",
              D, std::string(families::family_name(family)).c_str(), input.size(), static_cast<unsigned long long>(seed),
              c.repeats, row.output, row.median, row.median_cpu, row.ops_per_vertex, rss,
              static_cast<double>(rss) / static_cast<double>(row.output), last.memory_bytes,
              verify ? " verify=" : "", row.verdict.c_str());
  std::fflush(stdout);
  return row;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto opt = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "The standard StableWS benchmark (bench/run.sh's configurations)");
  cmd->add_flag("--quick", opt->quick, "10,000 points in 2D and 2,000 in 3D, 3 repeats (seconds instead of minutes)");
  cmd->add_option("--dim", opt->dims, "Only these dimensions (2, 3)")->check(CLI::IsMember({2, 3}));
  cmd->add_option("--n", opt->sizes, "Input sizes instead of the standard ones (e.g. --n 1e4 1e5)")
      ->check(CLI::Range(2.0, 1e8));
  cmd->add_option("--family", opt->family, "Input family: " + families::family_names());
  cmd->add_option("--repeats", opt->repeats, "Runs per configuration (median time reported)")->check(CLI::Range(1, 100));
  cmd->add_option("--seed", opt->seed, "Random seed of the family (default 1)");
  add_threads_option(cmd);
  cmd->add_flag("--verify", opt->verify, "Check each output with the independent verifier (slow)");
  add_quiet_option(cmd, opt->quiet);
  cmd->footer(
      "Prints one line per configuration in bench_static's key=value format (peak RSS is the whole process's,\n"
      "so it only grows from one line to the next), then a table. bench/run.sh BUILD_DIR runs the same\n"
      "configurations one process each and against CGAL, and writes bench/RESULTS.md.\n"
      "\n"
      "Example:\n"
      "  shoremesh bench --quick");
  return [opt]() {
    const families::FamilyName family = families::parse_family(opt->family);
    std::vector<Config> configs;
    if (opt->sizes.empty()) {
      configs = standard_configs(opt->quick);
    } else {
      for (int d : {2, 3})
        for (double n : opt->sizes) configs.push_back({d, static_cast<std::size_t>(n), opt->quick ? 3 : 5});
    }
    if (!opt->dims.empty())
      std::erase_if(configs, [&](const Config& c) { return std::find(opt->dims.begin(), opt->dims.end(), c.dim) == opt->dims.end(); });
    if (opt->repeats > 0)
      for (auto& c : configs) c.repeats = opt->repeats;
    Progress progress(!opt->quiet && Progress::stderr_is_terminal(), configs.size());
    std::vector<Row> rows;
    for (const Config& c : configs) {
      progress.stage(std::to_string(c.dim) + "D, n = " + std::to_string(c.n) + ", " + std::to_string(c.repeats) + " runs");
      rows.push_back(c.dim == 2 ? bench_one<2>(c, family, opt->seed, opt->verify)
                                : bench_one<3>(c, family, opt->seed, opt->verify));
    }
    progress.finish();
    std::printf("\n| dim | n | output vertices | median wall s | median CPU s | CPU us / output vertex | ops / output vertex |\n"
                "|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows)
      std::printf("| %d | %zu | %zu | %.3f | %.3f | %.2f | %.3g |\n", r.config.dim, r.config.n, r.output, r.median,
                  r.median_cpu, 1e6 * r.median_cpu / static_cast<double>(r.output), r.ops_per_vertex);
    return kExitOk;
  };
}

}  // namespace shoremesh::tool
