// The tool's side of the raster calls (raster_module.hpp): each one goes to libshoremesh_raster.so, loaded at
// the first call, so that a run that reads and writes no raster never loads GDAL, OpenImageIO or OpenCV.
//
// Where the module is: $SHOREMESH_RASTER_MODULE when set (that file only), else beside the executable (the
// build tree: build/tool), else ../lib/shoremesh from the executable's folder (`cmake --install`). Never
// unloaded: objects it made (a PointTransform, a shared_ptr's control block) live until the process ends.
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "../raster/raster_module.hpp"

namespace shoremesh::io {

namespace detail {

namespace {

std::vector<std::string> module_candidates() {
  if (const char* path = std::getenv("SHOREMESH_RASTER_MODULE"); path && *path) return {path};
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {kRasterModuleFile};  // the dynamic loader's search path
  const std::filesystem::path dir = exe.parent_path();
  return {(dir / kRasterModuleFile).string(), (dir.parent_path() / "lib" / "shoremesh" / kRasterModuleFile).string()};
}

const RasterModule& load_module() {
  std::string failures;
  for (const std::string& path : module_candidates()) {
    // Lazy binding, as the libraries had when the tool linked them (binding all 260 now cost 0.05 s); the
    // module's own references are all resolved at its link (-z defs).
    void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!handle) {
      const char* error = dlerror();
      failures += "\n  ";
      failures += error ? error : path + ": unknown dlopen error";
      continue;
    }
    const auto entry = reinterpret_cast<RasterModuleEntry>(dlsym(handle, kRasterModuleEntry));
    if (!entry) {
      const char* error = dlerror();
      failures += "\n  " + path + ": not shoremesh's raster module (" + (error ? error : "no entry") + ")";
      continue;
    }
    if (const RasterModule* module = entry(kRasterModuleInterface)) return *module;
    failures += "\n  " + path + ": a raster module of another shoremesh build (interface " +
                std::to_string(kRasterModuleInterface) + " expected)";
  }
  throw std::runtime_error(std::string("the raster module ") + kRasterModuleFile +
                           " (GDAL, OpenImageIO and OpenCV: images, DEMs, coordinate systems, previews) cannot be loaded:" +
                           failures + "\n(it is installed beside the tool or in lib/shoremesh; SHOREMESH_RASTER_MODULE may name it)");
}

// Loaded once; a failure is thrown to each caller (the static stays unset and the next call tries again).
const RasterModule& module() {
  static const RasterModule& loaded = load_module();
  return loaded;
}

}  // namespace

CrsTransforms crs_transforms(const std::string& wkt, const std::string& name, const std::string& file) {
  return module().crs_transforms(wkt, name, file);
}
std::string crs_wkt1(const std::string& wkt) { return module().crs_wkt1(wkt); }
std::unique_ptr<PointTransform> dem_transform(const Dem& dem) { return module().dem_transform(dem); }
TracedImage trace_image_unchecked(const std::string& path, const ImageTraceOptions& options) {
  return module().trace_image_unchecked(path, options);
}
TracedImage trace_water_mask_unchecked(const WaterMask& mask, const ImageTraceOptions& options,
                                       const std::optional<Georeference>& georeference, const std::string& name) {
  return module().trace_water_mask_unchecked(mask, options, georeference, name);
}

}  // namespace detail

CoordinateSystem parse_coordinate_system(std::string_view text, const std::string& file) {
  return detail::module().parse_coordinate_system(text, file);
}
std::function<Point2(const Point2&)> lonlat_transform(const CoordinateSystem& crs, const std::string& file) {
  return detail::module().lonlat_transform(crs, file);
}
std::optional<Georeference> read_geotiff_tags(const std::string& path) { return detail::module().read_geotiff_tags(path); }
Dem read_dem(const std::string& path, std::size_t max_cells) { return detail::module().read_dem(path, max_cells); }
void write_image(const std::filesystem::path& path, const PreviewImage& image) { detail::module().write_image(path, image); }
PreviewImage read_image(const std::filesystem::path& path) { return detail::module().read_image(path); }

}  // namespace shoremesh::io
