// The image tracer's last step, the ring check, around the tracer of io/src/raster (raster_module.hpp): the
// check needs the engine library, which the raster module does without.
#include "shoremesh/io/image_trace.hpp"

#include "../raster/raster_module.hpp"
#include "shoremesh/error.hpp"

namespace shoremesh::io {

namespace {

TracedImage checked(TracedImage traced) {
  try {
    check_rings(traced.input);
  } catch (const InputError& e) {
    throw InputError(e.message() + " after sampling the traced rings; use a smaller spacing or clean the image",
                     traced.file);
  }
  return traced;
}

}  // namespace

TracedImage trace_image(const std::string& path, const ImageTraceOptions& options) {
  return checked(detail::trace_image_unchecked(path, options));
}

TracedImage trace_water_mask(const WaterMask& mask, const ImageTraceOptions& options,
                             const std::optional<Georeference>& georeference, const std::string& name) {
  return checked(detail::trace_water_mask_unchecked(mask, options, georeference, name));
}

}  // namespace shoremesh::io
