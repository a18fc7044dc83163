#pragma once
// Internal: GDAL's drivers registered once per process, its own stderr messages silenced (ours name the file).
#include <gdal_priv.h>

#include <mutex>

namespace shoremesh::io::detail {

inline void register_gdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
  });
}

}  // namespace shoremesh::io::detail
