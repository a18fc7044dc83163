#pragma once
// Where a `dem-patch` raster lies in its DEM (terrain_command.cpp), shared by `terrain --edits` and
// `mesh --dem --land-up-to --edits` (land_water.cpp).
#include "shoremesh/io/dem.hpp"

namespace shoremesh::tool {

struct PatchWindow {
  int col = 0, row = 0;
};

// The patch's cells must be the DEM's (same size, whole-cell offset, inside it, the same coordinate
// system): InputError naming the patch otherwise.
PatchWindow locate_patch(const io::Dem& dem, const io::Dem& patch);

}  // namespace shoremesh::tool
