// libFuzzer target: GPX through pugixml, then projection, resampling and ring checks.
#include "fuzz_common.hpp"
#include "shoremesh/io/gps_track.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return run_parser(data, size, [](std::string_view text) {
    const auto gpx = shoremesh::io::parse_gpx_text(text, "fuzz.gpx");
    shoremesh::io::TrackOptions opt;
    opt.spacing = 5;
    opt.max_points = kFuzzMaxPoints;
    opt.smooth_window = 1;
    (void)shoremesh::io::gps_to_input(gpx, "fuzz.gpx", opt);
  });
}
