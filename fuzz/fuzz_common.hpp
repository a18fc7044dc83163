#pragma once
// Shared by the libFuzzer targets: run a parser on the input bytes; shoremesh::InputError is the expected
// outcome for malformed input, anything else that escapes (another exception, a crash, a sanitizer report)
// is a bug that libFuzzer reports.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "shoremesh/error.hpp"

template <class F>
int run_parser(const std::uint8_t* data, std::size_t size, F&& parse) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    parse(text);
  } catch (const shoremesh::InputError&) {
  }
  return 0;
}
