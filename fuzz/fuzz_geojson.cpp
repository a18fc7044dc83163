// libFuzzer target: GeoJSON through nlohmann::json, projection, ring checks.
#include "fuzz_common.hpp"
#include "shoremesh/io/geojson_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return run_parser(data, size, [](std::string_view text) {
    shoremesh::io::GeoJsonOptions opt;
    opt.spacing = 1000;
    opt.max_points = kFuzzMaxPoints;
    (void)shoremesh::io::parse_geojson_text(text, "fuzz.geojson", opt);
  });
}
