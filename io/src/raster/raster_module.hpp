#pragma once
// Internal: the calls of shoremesh::io that need GDAL, OpenImageIO or OpenCV (docs/raster_module.md).
//
// They are the only code in io/src/raster. Every other io source calls them by these names, and the name
// resolves at link time:
//   shoremesh_io         (tests, benchmarks, examples) links io/src/raster in: the calls are direct.
//   shoremesh_raster     (libshoremesh_raster.so) is the same plus the module entry (module.cpp).
//   shoremesh_io_lazy    (the tool) links io/src/loader instead: each call goes through RasterModule to the
//                        module, loaded with dlopen at the first call. The tool then starts without those
//                        libraries (and the 260 shared objects behind them).
// Same function, same messages either way: the module runs this very code.
#include <memory>
#include <optional>
#include <string>

#include "shoremesh/io/dem.hpp"
#include "shoremesh/io/georeference.hpp"
#include "shoremesh/io/image_trace.hpp"
#include "shoremesh/io/preview.hpp"

namespace shoremesh::io::detail {

// A PROJ transformation (through OGR) of one point in place; false where PROJ has no answer. Not safe to
// share between threads.
class PointTransform {
 public:
  virtual ~PointTransform() = default;
  virtual bool transform(double& x, double& y) = 0;
};

// Both ways between WGS 84 lon/lat (lon first) and a projected system, and the system as a PROJ string
// (empty when OGR cannot export one).
struct CrsTransforms {
  std::unique_ptr<PointTransform> forward, reverse;
  std::string proj4;
};
// InputError naming `file`: "not a projected coordinate system: NAME" / "PROJ cannot transform NAME ...".
CrsTransforms crs_transforms(const std::string& wkt, const std::string& name, const std::string& file);
// WKT 1 of a system given as any WKT (ESRI's .prj readers know no WKT 2); empty when OGR cannot read it.
std::string crs_wkt1(const std::string& wkt);
// WGS 84 lon/lat -> the DEM's coordinate system; InputError naming the DEM when there is none to make.
std::unique_ptr<PointTransform> dem_transform(const Dem& dem);

// trace_image / trace_water_mask without their last step, the ring check (check_rings, which needs the
// engine library: image_trace.cpp in io/src/input does it on the result).
TracedImage trace_image_unchecked(const std::string& path, const ImageTraceOptions& options);
TracedImage trace_water_mask_unchecked(const WaterMask& mask, const ImageTraceOptions& options,
                                       const std::optional<Georeference>& georeference, const std::string& name);

// The calls above and the public ones of georeference.hpp, dem.hpp and preview.hpp that need the three
// libraries, as the module serves them. Both sides are built from the same sources in the same build: the
// interface is checked by kRasterModuleInterface only, and the module is never unloaded (its objects, such as
// a PointTransform, live until the process ends).
class RasterModule {
 public:
  virtual ~RasterModule() = default;
  virtual CoordinateSystem parse_coordinate_system(std::string_view text, const std::string& file) const = 0;
  virtual std::function<Point2(const Point2&)> lonlat_transform(const CoordinateSystem& crs,
                                                                const std::string& file) const = 0;
  virtual std::optional<Georeference> read_geotiff_tags(const std::string& path) const = 0;
  virtual CrsTransforms crs_transforms(const std::string& wkt, const std::string& name,
                                       const std::string& file) const = 0;
  virtual std::string crs_wkt1(const std::string& wkt) const = 0;
  virtual Dem read_dem(const std::string& path, std::size_t max_cells) const = 0;
  virtual std::unique_ptr<PointTransform> dem_transform(const Dem& dem) const = 0;
  virtual TracedImage trace_image_unchecked(const std::string& path, const ImageTraceOptions& options) const = 0;
  virtual TracedImage trace_water_mask_unchecked(const WaterMask& mask, const ImageTraceOptions& options,
                                                 const std::optional<Georeference>& georeference,
                                                 const std::string& name) const = 0;
  virtual void write_image(const std::filesystem::path& path, const PreviewImage& image) const = 0;
  virtual PreviewImage read_image(const std::filesystem::path& path) const = 0;
};

// Raised whenever RasterModule (or a type crossing it) changes: a module of another build is refused.
inline constexpr int kRasterModuleInterface = 1;
inline constexpr const char* kRasterModuleFile = "libshoremesh_raster.so";
inline constexpr const char* kRasterModuleEntry = "shoremesh_raster_module";
// The module's one exported symbol: its RasterModule, or null when `interface` is not kRasterModuleInterface.
using RasterModuleEntry = const RasterModule* (*)(int interface);

}  // namespace shoremesh::io::detail
