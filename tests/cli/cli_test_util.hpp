#pragma once
// Running the built shoremesh binary from tests: a temporary folder per test, the command's exit code,
// stdout and stderr, and the bundled data.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../io/io_test_util.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::cli_test {

namespace fs = std::filesystem;

struct RunResult {
  int code = -1;
  std::string out, err;
};

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// A fresh folder under the system's temporary directory, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = fs::temp_directory_path() / ("shoremesh_cli_" + std::to_string(rd()) + std::to_string(rd()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    if (!::testing::Test::HasFailure()) fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

// Runs `shoremesh ARGS` (ARGS is shell text) in `dir`, with `stdin_text` on standard input.
inline RunResult shoremesh(const TempDir& dir, const std::string& args, const std::string& stdin_text = {}) {
  const fs::path in = dir / ".stdin", out = dir / ".stdout", err = dir / ".stderr";
  write_file(in, stdin_text);
  const std::string cmd = "cd " + quote(dir.path().string()) + " && " + quote(SHOREMESH_BINARY) + " " + args + " <" +
                          quote(in.string()) + " >" + quote(out.string()) + " 2>" + quote(err.string());
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

// Data files shipped in samples/ (real third-party data with its license note).
using io::test::samples;
inline std::string superior_mask() { return samples("superior/superior_watermask_h.png"); }

// A reproducible 2D point file ("x,y" header, 4 decimals) of n points in [0, w] x [0, h].
inline std::string random_points(std::size_t n, double w, double h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> x(0, static_cast<int>(w * 1e4)), y(0, static_cast<int>(h * 1e4));
  std::ostringstream s;
  s << "x,y\n";
  for (std::size_t i = 0; i < n; ++i) s << x(rng) / 1e4 << ',' << y(rng) / 1e4 << '\n';
  return s.str();
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// Triangle's .node/.ele as written by `mesh -o X.node`, read here line by line (1-based numbering).
struct TriangleFiles {
  std::vector<Point2> nodes;
  std::vector<std::array<std::size_t, 3>> triangles;
};

inline TriangleFiles read_triangle_files(const fs::path& node) {
  TriangleFiles t;
  std::istringstream n(read_file(node));
  std::size_t count = 0, dim = 0, attributes = 0, markers = 0;
  n >> count >> dim >> attributes >> markers;
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t id = 0, marker = 0;
    Point2 p;
    n >> id >> p[0] >> p[1];
    if (markers) n >> marker;
    t.nodes.push_back(p);
  }
  fs::path ele = node;
  ele.replace_extension(".ele");
  std::istringstream e(read_file(ele));
  std::size_t corners = 0;
  e >> count >> corners >> attributes;
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t id = 0;
    std::array<std::size_t, 3> tri{};
    e >> id >> tri[0] >> tri[1] >> tri[2];
    for (auto& v : tri) --v;
    t.triangles.push_back(tri);
  }
  return t;
}

}  // namespace shoremesh::cli_test
