#pragma once
// The DEM edit language shared by `terrain --edits` and `mesh --dem --land-up-to --edits` (land_water.cpp):
// where a `dem-patch` raster lies in its DEM, and the dispatch of one edit line (terrain_command.cpp).
#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "shoremesh/io/dem.hpp"

namespace shoremesh::tool {

struct PatchWindow {
  int col = 0, row = 0;
};

// The patch's cells must be the DEM's (same size, whole-cell offset, inside it, the same coordinate
// system): InputError naming the patch otherwise.
PatchWindow locate_patch(const io::Dem& dem, const io::Dem& patch);

// What each edit does to the reply it is given.
struct DemEditOps {
  std::function<void(const std::string& file, nlohmann::json& reply)> patch;    // dem-patch FILE
  std::function<void(const std::string& path, nlohmann::json& reply)> export_to;  // export PATH
  std::function<void(nlohmann::json& reply)> stats;                              // stats
};
// One edit line: nothing for a blank line or a comment; an error reply (that changed nothing) for a bad
// line, an unknown edit (`kind` names the language in the message: "terrain", "land-and-water") or an
// InputError / ParameterError of the edit.
std::optional<nlohmann::json> run_dem_edit_line(std::size_t line, const std::string& text, const std::string& kind,
                                                const DemEditOps& ops);

}  // namespace shoremesh::tool
