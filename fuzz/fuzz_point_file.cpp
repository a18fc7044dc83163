// libFuzzer target: plain point files (CSV / whitespace, 2 or 3 columns) and ring files.
#include "fuzz_common.hpp"
#include "shoremesh/io/point_file.hpp"
#include "shoremesh/io/ring_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return run_parser(data, size, [](std::string_view text) {
    try {
      (void)shoremesh::io::parse_point_file_text(text, "fuzz.csv");
    } catch (const shoremesh::InputError&) {
    }
    if (shoremesh::io::looks_like_ring_file(text)) {
      const auto rings = shoremesh::io::parse_ring_file_text(text, "fuzz.csv");
      (void)shoremesh::io::ring_file_to_input(rings, "fuzz.csv", false);
    }
  });
}
