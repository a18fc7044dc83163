// The engine's quadtree build alone (issue 38): Quadtree<D>::build on one input, timed.
//
//   bench_quadtree --dim 2|3 --n N [--family uniform|clusters|...] [--seed S] [--repeats K] [--verify]
//   bench_quadtree --csv FILE [--repeats K] [--verify]
//
// --csv reads "x,y" lines (lon/lat, say; '#' lines and blank lines skipped) and scales them into the
// unit box as the engine would (one scale for both axes, a margin of 1/64 of the extent): the Superior
// shore file gives a tree shaped like the engine's on Superior. The inputs are numbered along the curve
// first, as the engine numbers them. Prints the medians over the repeats of the build's wall and thread
// CPU seconds, the tree's size, and two hashes: of its leaf cells (the tree) and of every node in id
// order with its parent, children and vertices (the tree as the engine reads it, numbering included).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "shoremesh/engine/quadtree.hpp"
#include "shoremesh/engine/spatial_order.hpp"
#include "shoremesh/families.hpp"

using namespace shoremesh;
using engine::NodeId;
using engine::VertexId;

namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Hash {
  std::uint64_t h = 1469598103934665603ull;
  void add(std::uint64_t x) {
    for (int b = 0; b < 8; ++b) {
      h ^= (x >> (8 * b)) & 0xff;
      h *= 1099511628211ull;
    }
  }
};

std::vector<Point<2>> read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<Point<2>> raw;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    Point<2> p;
    if (s >> p[0] >> p[1]) raw.push_back(p);
  }
  if (raw.size() < 2) throw std::runtime_error(path + ": fewer than two points");
  Point<2> lo = raw[0], hi = raw[0];
  for (const Point<2>& p : raw)
    for (int i = 0; i < 2; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  const double margin = extent / 64;
  std::vector<Point<2>> out;
  for (const Point<2>& p : raw) out.push_back({(p[0] - lo[0] + margin) / (extent + 2 * margin), (p[1] - lo[1] + margin) / (extent + 2 * margin)});
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());  // a closed ring repeats its first point
  return out;
}

template <int D>
int run(std::vector<Point<D>> raw, int repeats, bool verify, const std::string& label) {
  const std::vector<std::size_t> order = engine::spatial_order<D>(raw);
  std::vector<Point<D>> points(raw.size());
  std::vector<VertexId> ids(raw.size());
  for (std::size_t v = 0; v < raw.size(); ++v) {
    points[v] = raw[order[v]];
    ids[v] = VertexId(v);
  }
  std::vector<double> wall, cpu;
  engine::Quadtree<D> tree;
  for (int r = 0; r < repeats; ++r) {
    engine::Quadtree<D> t;
    const auto w0 = std::chrono::steady_clock::now();
    const double c0 = thread_cpu_seconds();
    t.build(points, ids);
    cpu.push_back(thread_cpu_seconds() - c0);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
    if (r + 1 == repeats) tree = std::move(t);
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  if (verify) tree.check_valid(points);
  Hash cells, nodes;
  for (const auto& [level, c] : tree.leaf_cells()) {
    cells.add(std::uint64_t(level));
    for (int i = 0; i < D; ++i) cells.add(c[std::size_t(i)]);
  }
  std::size_t internal = 0;
  for (NodeId n = 0; n < tree.node_capacity(); ++n) {
    const auto nd = tree.node(n);
    nodes.add(std::uint64_t(std::int64_t(nd.level)));
    if (nd.level < 0) continue;
    nodes.add(nd.parent);
    nodes.add(nd.first_child);
    for (int i = 0; i < D; ++i) nodes.add(nd.coords[std::size_t(i)]);
    nodes.add(nd.input_count);
    nodes.add(nd.input_vertex);
    if (!nd.is_leaf()) {
      ++internal;
      continue;
    }
    nodes.add(nd.vertices.size());
    for (const auto& e : nd.vertices) nodes.add(e.id);
  }
  std::printf("%s n=%zu build_wall=%.4f s build_cpu=%.4f s leaves=%zu internal=%zu node_slots=%zu bytes=%zu cells=%016llx nodes=%016llx%s\n",
              label.c_str(), points.size(), wall[wall.size() / 2], cpu[cpu.size() / 2], tree.leaf_count(), internal,
              tree.node_capacity(), tree.memory_bytes(), (unsigned long long)cells.h, (unsigned long long)nodes.h,
              verify ? " valid" : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int dim = 2, repeats = 3;
  std::size_t n = 100000;
  std::uint64_t seed = 1;
  std::string family = "uniform", csv;
  bool verify = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error("missing value after " + a);
      return argv[++i];
    };
    if (a == "--dim") dim = std::stoi(next());
    else if (a == "--n") n = std::stoull(next());
    else if (a == "--seed") seed = std::stoull(next());
    else if (a == "--repeats") repeats = std::max(1, std::stoi(next()));
    else if (a == "--family") family = next();
    else if (a == "--csv") csv = next();
    else if (a == "--verify") verify = true;
    else {
      std::fprintf(stderr, "bench_quadtree: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  try {
    if (!csv.empty()) return run<2>(read_csv(csv), repeats, verify, "csv");
    const auto fam = families::parse_family(family);
    std::string label = family;
    label += dim == 2 ? " 2D" : " 3D";
    if (dim == 2) return run<2>(families::generate<2>(fam, n, seed), repeats, verify, label);
    if (dim == 3) return run<3>(families::generate<3>(fam, n, seed), repeats, verify, label);
    std::fprintf(stderr, "bench_quadtree: --dim 2 or 3\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_quadtree: %s\n", e.what());
    return 1;
  }
}
