#pragma once
// Shared by the libFuzzer targets: run a parser on the input bytes; shoremesh::InputError is the expected
// outcome for malformed input, anything else that escapes (another exception, a crash, a sanitizer report)
// is a bug that libFuzzer reports.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "shoremesh/error.hpp"

// The targets' cap on the points a spacing may cut (the readers' default is 10^7): a mutated coordinate
// far from the others asks for millions, which the reader must refuse (that path is fuzzed all the same,
// at a count the sanitizers get through in milliseconds, not in more than libFuzzer's 10 s timeout).
constexpr std::size_t kFuzzMaxPoints = 20'000;

template <class F>
int run_parser(const std::uint8_t* data, std::size_t size, F&& parse) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    parse(text);
  } catch (const shoremesh::InputError&) {
  }
  return 0;
}
