// libshoremesh_raster.so's entry: the raster calls of raster_module.hpp behind the RasterModule interface.
// The module exports this one symbol (raster_module.map); everything else in it is local, so its copies of
// io's code never meet the tool's.
#include "raster_module.hpp"

namespace shoremesh::io::detail {

namespace {

class Module final : public RasterModule {
 public:
  CoordinateSystem parse_coordinate_system(std::string_view text, const std::string& file) const override {
    return io::parse_coordinate_system(text, file);
  }
  std::function<Point2(const Point2&)> lonlat_transform(const CoordinateSystem& crs,
                                                        const std::string& file) const override {
    return io::lonlat_transform(crs, file);
  }
  std::optional<Georeference> read_geotiff_tags(const std::string& path) const override {
    return io::read_geotiff_tags(path);
  }
  CrsTransforms crs_transforms(const std::string& wkt, const std::string& name,
                               const std::string& file) const override {
    return detail::crs_transforms(wkt, name, file);
  }
  std::string crs_wkt1(const std::string& wkt) const override { return detail::crs_wkt1(wkt); }
  Dem read_dem(const std::string& path, std::size_t max_cells) const override { return io::read_dem(path, max_cells); }
  std::unique_ptr<PointTransform> dem_transform(const Dem& dem) const override { return detail::dem_transform(dem); }
  TracedImage trace_image_unchecked(const std::string& path, const ImageTraceOptions& options) const override {
    return detail::trace_image_unchecked(path, options);
  }
  TracedImage trace_water_mask_unchecked(const WaterMask& mask, const ImageTraceOptions& options,
                                         const std::optional<Georeference>& georeference,
                                         const std::string& name) const override {
    return detail::trace_water_mask_unchecked(mask, options, georeference, name);
  }
  void write_image(const std::filesystem::path& path, const PreviewImage& image) const override {
    io::write_image(path, image);
  }
  PreviewImage read_image(const std::filesystem::path& path) const override { return io::read_image(path); }
};

}  // namespace

}  // namespace shoremesh::io::detail

extern "C" const shoremesh::io::detail::RasterModule* shoremesh_raster_module(int interface) {
  static const shoremesh::io::detail::Module module;
  return interface == shoremesh::io::detail::kRasterModuleInterface ? &module : nullptr;
}
