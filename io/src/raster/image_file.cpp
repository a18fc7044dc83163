// Image files through OpenImageIO: 8-bit output in any format it writes (chosen by extension), written
// to a temporary file with the same extension and renamed; input of any format it reads.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <stdexcept>

#include "shoremesh/error.hpp"
#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/preview.hpp"

namespace shoremesh::io {

void write_image(const std::filesystem::path& path, const PreviewImage& image) {
  AtomicFile file(path, /*open_stream=*/false);
  auto out = OIIO::ImageOutput::create(file.temporary_path().string());
  if (!out) throw InputError("OpenImageIO cannot write this image format: " + OIIO::geterror(), path.string());
  const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  if (!out->open(file.temporary_path().string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, image.rgb.data()) ||
      !out->close())
    throw std::runtime_error("writing " + path.string() + " failed: " + out->geterror());
  file.commit();
}

PreviewImage read_image(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw InputError("cannot read the image: " + OIIO::geterror(), path.string());
  const OIIO::ImageSpec& spec = in->spec();
  const int channels = std::min(spec.nchannels, 3);
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw InputError("cannot read the image: " + in->geterror(), path.string());
  PreviewImage image;
  image.width = spec.width;
  image.height = spec.height;
  image.rgb.resize(static_cast<std::size_t>(spec.width) * spec.height * 3);
  for (std::size_t i = 0; i < static_cast<std::size_t>(spec.width) * spec.height; ++i)
    for (int c = 0; c < 3; ++c) image.rgb[i * 3 + c] = pixels[i * channels + std::min(c, channels - 1)];
  return image;
}

}  // namespace shoremesh::io
