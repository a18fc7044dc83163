#pragma once
// Internal: GDAL's drivers registered once per process, its own stderr messages silenced (ours name the file);
// OGR's transformations as raster_module.hpp's PointTransform.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <memory>
#include <mutex>

#include "raster_module.hpp"

namespace shoremesh::io::detail {

inline void register_gdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
  });
}

class OgrTransform final : public PointTransform {
 public:
  explicit OgrTransform(OGRCoordinateTransformation* t) : t_(t) {}
  bool transform(double& x, double& y) override { return t_->Transform(1, &x, &y) != 0; }

 private:
  std::unique_ptr<OGRCoordinateTransformation> t_;
};

// Takes ownership of `t`; null for null (OGRCreateCoordinateTransformation's failure).
inline std::unique_ptr<PointTransform> ogr_transform(OGRCoordinateTransformation* t) {
  if (!t) return nullptr;
  return std::make_unique<OgrTransform>(t);
}

}  // namespace shoremesh::io::detail
