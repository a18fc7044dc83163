// libFuzzer target: Triangle .poly and .node files, cycles to rings, segment sampling.
#include "fuzz_common.hpp"
#include "shoremesh/io/poly_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return run_parser(data, size, [](std::string_view text) {
    shoremesh::io::PslgOptions opt;
    opt.spacing = 0.25;
    opt.max_points = kFuzzMaxPoints;
    try {
      (void)shoremesh::io::pslg_to_input(shoremesh::io::parse_node_text(text, "fuzz.node"), opt);
    } catch (const shoremesh::InputError&) {
    }
    // The same text as a .poly, and as the .node beside a .poly without vertices.
    try {
      (void)shoremesh::io::pslg_to_input(shoremesh::io::parse_poly_text(text, "fuzz.poly"), opt);
    } catch (const shoremesh::InputError&) {
    }
    (void)shoremesh::io::parse_poly_text("0 2 0 0\n1 0\n1 1 2\n", "fuzz.poly", text, "fuzz.node");
  });
}
