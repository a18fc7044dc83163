#pragma once
// `mesh --dem FILE --land-up-to Z [--max-error E]`: the water and the land below Z in one TIN
// (land_water.cpp, docs/terrain.md).
#include <optional>
#include <string>

#include "input_args.hpp"

namespace shoremesh::tool {

class Progress;

struct LandWaterRequest {
  const InputArgs& in;
  std::string output, format, preview;
  double rho = 1.4142135623730951;
  std::optional<std::string> other_options;  // a mesh option that does not apply ("--max-size"), to refuse
  std::string edits;  // edit lines (dem-patch FILE, export PATH, stats) after the build, '-' for standard input
  bool json = false;  // one JSON object per edit reply
};

int run_land_water(const LandWaterRequest& request, Progress& progress);

}  // namespace shoremesh::tool
