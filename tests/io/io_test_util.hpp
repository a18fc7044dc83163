#pragma once
// Helpers for the io tests: a scratch directory for generated (often malformed) files, and data paths
// (the real third-party files the tests read are the ones shipped in samples/, with their licenses).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "shoremesh/error.hpp"

namespace shoremesh::io::test {

inline std::string samples(const std::string& rel) { return std::string(SHOREMESH_SAMPLES_DIR) + "/" + rel; }

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A fresh temporary directory removed at the end of the test.
class ScratchDir {
 public:
  ScratchDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() / ("shoremesh-io-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::string write(const std::string& name, const std::string& content) const {
    const auto p = path_ / name;
    std::ofstream(p, std::ios::binary) << content;
    return p.string();
  }
  std::string path(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// Runs f, expects an InputError, and returns it for inspection.
template <class F>
InputError expect_input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected shoremesh::InputError";
  return InputError("no error thrown");
}

// A malformed input, the part of the message it must produce and its line (0: not checked).
struct ErrorCase {
  std::string text, expect;
  std::size_t line = 0;
};

// Runs parse(text) for each case: an InputError naming `file`, with the expected message part and line.
template <class F>
void expect_errors(const std::vector<ErrorCase>& cases, const std::string& file, F&& parse) {
  for (const auto& c : cases) {
    const InputError e = expect_input_error([&] { parse(c.text); });
    EXPECT_EQ(e.file(), file) << c.text.substr(0, 200);
    EXPECT_THAT(e.message(), ::testing::HasSubstr(c.expect)) << c.text.substr(0, 200);
    if (c.line) {
      EXPECT_EQ(e.line(), c.line) << c.text.substr(0, 200);
    }
  }
}

}  // namespace shoremesh::io::test
