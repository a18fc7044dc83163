// libFuzzer target: lat/lon CSV tracks, then projection and resampling.
#include "fuzz_common.hpp"
#include "shoremesh/io/gps_track.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return run_parser(data, size, [](std::string_view text) {
    (void)shoremesh::io::csv_header_has_lat_lon(text);
    const auto track = shoremesh::io::parse_track_csv_text(text, "fuzz.csv");
    (void)shoremesh::io::gps_to_input(track, "fuzz.csv");
  });
}
