// Static benchmark: ONE algorithm on one generated input, run in this process, printed as one line of
// key=value pairs (bench/run.sh starts one process per configuration, so peak memory is per algorithm).
//
//   bench_static --algo stablews|cgal --dim 2|3 --n N --family uniform --repeats K --seed S [--threads T] [--verify]
//                [--neighbours tree|delaunay|both]
//
// --threads: the engine's thread count (default every core; the output is the same for any count).
// --neighbours: where a 2D one-shot build's cells find their neighbours (engine::set_delaunay_neighbours);
//   both: the two alternately, run after run, one line each (the same output, the same hash).
//
// stablews: shoremesh::stable_well_spaced on the points in the unit box.
// cgal:     the 2D reference: a constrained Delaunay triangulation of the unit square's corners and edges
//           plus the points, refined by CGAL::refine_Delaunay_mesh_2 with shape bound 0.125 = sin^2(20.7°),
//           the minimum angle a sqrt(2)-well-spaced set guarantees, and no size bound.
// Only the algorithm is timed (std::chrono::steady_clock), not the input generation; the time printed is
// the median over the repeats. The process CPU time of the same runs is printed too: on a shared machine
// wall time grows with the load, CPU time much less. Peak RSS is the whole process's (getrusage), input
// included for both.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "shoremesh/engine/delaunay_neighbours.hpp"
#include "shoremesh/engine/engine.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/verify.hpp"
#include "shoremesh/well_spaced.hpp"

namespace {

using namespace shoremesh;

struct Options {
  std::string algo = "stablews";
  int dim = 2;
  std::size_t n = 10000;
  families::FamilyName family = families::FamilyName::Uniform;
  int repeats = 3;
  std::uint64_t seed = 1;
  unsigned threads = 0;  // 0: every core
  std::string neighbours = "default";  // stablews 2D: tree, delaunay, both (alternating runs), or the engine's default
  bool verify = false;
};

template <class T>
T parse_number(std::string_view text, std::string_view option) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size())
    throw InputError("bad value '" + std::string(text) + "' for " + std::string(option));
  return value;
}

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--verify") {
      o.verify = true;
      continue;
    }
    if (i + 1 >= argc) throw InputError("missing value for " + std::string(arg));
    const std::string_view value = argv[++i];
    if (arg == "--algo") o.algo = value;
    else if (arg == "--dim") o.dim = parse_number<int>(value, arg);
    else if (arg == "--n") o.n = static_cast<std::size_t>(parse_number<double>(value, arg));  // accepts 1e6
    else if (arg == "--family") o.family = families::parse_family(value);
    else if (arg == "--repeats") o.repeats = parse_number<int>(value, arg);
    else if (arg == "--seed") o.seed = parse_number<std::uint64_t>(value, arg);
    else if (arg == "--threads") o.threads = parse_number<unsigned>(value, arg);
    else if (arg == "--neighbours") o.neighbours = value;
    else throw InputError("unknown option " + std::string(arg));
  }
  if (o.algo != "stablews" && o.algo != "cgal") throw InputError("--algo must be stablews or cgal");
  if (o.dim != 2 && o.dim != 3) throw InputError("--dim must be 2 or 3");
  if (o.algo == "cgal" && o.dim != 2) throw InputError("--algo cgal is the 2D reference only");
  if (o.repeats < 1) throw InputError("--repeats must be at least 1");
  return o;
}

// What one run produced, for the printed line.
struct RunResult {
  std::size_t output_vertices = 0;
  double operations = -1;          // stablews only
  double engine_memory_bytes = -1; // stablews only
  std::uint64_t output_hash = 0;   // stablews only: FNV-1a of the sorted output's bits (equal outputs, equal hashes)
  bool verified = false;
  std::string verdict;             // when --verify
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Wall and CPU seconds of every run.
struct Timings {
  std::vector<double> wall, cpu;
};

template <class Run>
Timings time_runs(int repeats, Run run) {
  Timings t;
  for (int r = 0; r < repeats; ++r) {
    const double cpu_start = process_cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    run();
    t.wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    t.cpu.push_back(process_cpu_seconds() - cpu_start);
  }
  return t;
}

template <int D>
std::string verdict(const std::vector<Point<D>>& output, const std::vector<Point<D>>& input, const BoxTransform<D>& box) {
  const auto report = verify_well_spaced(output, input, box, std::sqrt(2.0));
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "%s worst_ratio=%.6g violations=%zu size_conformity=%.6g",
                report.ok() ? "ok" : "FAILED", report.worst_ratio, report.violations, report.worst_size_conformity);
  return buffer;
}

template <int D>
std::pair<RunResult, Timings> bench_stablews(const std::vector<Point<D>>& input, const Options& o) {
  BoxTransform<D> box;
  box.origin.fill(0);
  box.side = 1;
  RunResult result;
  StableResult<D> last;
  const Timings timings = time_runs(o.repeats, [&] {
    last = StableResult<D>{};  // free the previous run's output before the next one
    last = stable_well_spaced<D>(input, {}, box);
  });
  result.output_vertices = last.points.size();
  result.operations = static_cast<double>(last.counters.operations());
  result.engine_memory_bytes = static_cast<double>(last.memory_bytes);
  std::vector<Point<D>> sorted = last.points;
  std::sort(sorted.begin(), sorted.end());
  std::uint64_t h = 1469598103934665603ull;
  for (const Point<D>& p : sorted)
    for (double x : p) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &x, sizeof bits);
      for (int k = 0; k < 8; ++k) h = (h ^ ((bits >> (8 * k)) & 0xff)) * 1099511628211ull;
    }
  result.output_hash = h;
  if (o.verify) result.verdict = verdict<D>(last.points, input, box);
  return {result, timings};
}

std::pair<RunResult, Timings> bench_cgal(const std::vector<Point2>& input, const Options& o) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Tds = CGAL::Triangulation_data_structure_2<CGAL::Delaunay_mesh_vertex_base_2<K>, CGAL::Delaunay_mesh_face_base_2<K>>;
  using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
  using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
  std::vector<K::Point_2> points;
  points.reserve(input.size());
  for (const auto& p : input) points.emplace_back(p[0], p[1]);

  RunResult result;
  std::vector<Point2> output;
  const Timings timings = time_runs(o.repeats, [&] {
    Cdt cdt;
    const K::Point_2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    Cdt::Vertex_handle handles[4];
    for (int k = 0; k < 4; ++k) handles[k] = cdt.insert(corners[k]);
    for (int k = 0; k < 4; ++k) cdt.insert_constraint(handles[k], handles[(k + 1) % 4]);
    cdt.insert(points.begin(), points.end());
    CGAL::refine_Delaunay_mesh_2(cdt, Criteria(0.125, 0));
    result.output_vertices = cdt.number_of_vertices();
    if (o.verify) {
      output.clear();
      for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
        output.push_back({v->point().x(), v->point().y()});
    }
  });
  if (o.verify) result.verdict = verdict<2>(output, input, BoxTransform<2>{{0, 0}, 1});
  return {result, timings};
}

std::size_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // kilobytes on Linux
}

template <int D>
void print_line(const Options& o, const char* neighbours, std::size_t n, const RunResult& result, const Timings& timings) {
  const std::size_t rss = peak_rss_bytes();
  const double out = static_cast<double>(result.output_vertices);
  std::printf("algo=%s dim=%d family=%s n=%zu seed=%llu repeats=%d output_vertices=%zu median_seconds=%.6f "
              "median_cpu_seconds=%.6f ops_per_vertex=%.4g peak_rss_bytes=%zu bytes_per_vertex=%.1f "
              "engine_memory_bytes=%.0f",
              o.algo.c_str(), D, std::string(families::family_name(o.family)).c_str(), n,
              static_cast<unsigned long long>(o.seed), o.repeats, result.output_vertices, median(timings.wall),
              median(timings.cpu),
              result.operations < 0 ? NAN : result.operations / out, rss, static_cast<double>(rss) / out,
              result.engine_memory_bytes < 0 ? NAN : result.engine_memory_bytes);
  if (o.algo == "stablews")
    std::printf(" threads=%u neighbours=%s output_hash=%016llx", engine::thread_count(), neighbours,
                static_cast<unsigned long long>(result.output_hash));
  if (o.verify) std::printf(" verify=%s", result.verdict.c_str());
  std::printf("\n");
}

template <int D>
int run(const Options& o) {
  const std::vector<Point<D>> input = families::generate<D>(o.family, o.n, o.seed);
  if (o.threads > 0) engine::set_thread_count(o.threads);
  if (o.neighbours == "tree" || o.neighbours == "delaunay") engine::set_delaunay_neighbours(o.neighbours == "delaunay");
  const char* neighbours = D == 3 ? "tree" : engine::delaunay_neighbours() ? "delaunay" : "tree";
  if (o.algo == "stablews" && o.neighbours == "both") {
    // Alternately, so that both see the same load on a shared machine. Peak RSS is the process's: both.
    Options one = o;
    one.repeats = 1;
    std::pair<RunResult, Timings> paths[2];
    for (int r = 0; r < o.repeats; ++r)
      for (int k = 0; k < 2; ++k) {
        engine::set_delaunay_neighbours(k == 1);
        auto [result, t] = bench_stablews<D>(input, one);
        paths[k].first = result;
        paths[k].second.wall.push_back(t.wall[0]);
        paths[k].second.cpu.push_back(t.cpu[0]);
      }
    print_line<D>(o, "tree", input.size(), paths[0].first, paths[0].second);
    print_line<D>(o, D == 3 ? "tree" : "delaunay", input.size(), paths[1].first, paths[1].second);
    return 0;
  }
  std::pair<RunResult, Timings> measured;
  if constexpr (D == 2)
    measured = o.algo == "cgal" ? bench_cgal(input, o) : bench_stablews<2>(input, o);
  else
    measured = bench_stablews<D>(input, o);  // parse_options refuses cgal in 3D
  print_line<D>(o, neighbours, input.size(), measured.first, measured.second);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse_options(argc, argv);
    return o.dim == 2 ? run<2>(o) : run<3>(o);
  } catch (const InputError& e) {
    std::fprintf(stderr, "bench_static: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_static: internal error: %s\n", e.what());
    return 3;
  }
}
