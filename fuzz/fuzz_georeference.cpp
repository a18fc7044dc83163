// libFuzzer target: world files and coordinate systems (.prj WKT and short forms).
#include "fuzz_common.hpp"
#include "shoremesh/io/georeference.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return run_parser(data, size, [](std::string_view text) {
    try {
      (void)shoremesh::io::parse_world_file_text(text, "fuzz.wld");
    } catch (const shoremesh::InputError&) {
    }
    (void)shoremesh::io::parse_coordinate_system(text, "fuzz.prj");
  });
}
