// Georeferences of images (georeference.hpp): world files, user boxes, and the order they are looked for in.
// What needs GDAL (coordinate systems, GeoTIFF keys) is io/src/raster/crs.cpp.
#include "shoremesh/io/georeference.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "shoremesh/error.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

Point2 PixelToMap::inverse(const Point2& xy) const {
  const double det = a * e - b * d;
  if (det == 0 || !std::isfinite(det)) throw std::domain_error("singular pixel-to-map transform");
  const double x = xy[0] - c, y = xy[1] - f;
  return {(e * x - b * y) / det, (-d * x + a * y) / det};
}

PixelToMap parse_world_file_text(std::string_view text, const std::string& name) {
  std::vector<double> v;
  std::size_t last_line = 0;
  detail::for_each_line(text, [&](std::string_view raw, std::size_t line) {
    const auto t = detail::trim(raw);
    if (t.empty()) return;
    last_line = line;
    if (v.size() == 6) throw InputError("a world file has six numbers; found more", name, line);
    double x = 0;
    const auto st = detail::parse_double(t, x);
    if (st != detail::NumberStatus::Ok)
      throw InputError(detail::quoted(t) + (st == detail::NumberStatus::NotFinite ? " is not a finite number" : " is not a number"),
                       name, line);
    v.push_back(x);
  });
  if (v.size() != 6)
    throw InputError("a world file has six numbers (A D B E C F), found " + std::to_string(v.size()), name,
                     last_line ? std::optional<std::size_t>(last_line) : std::nullopt);
  PixelToMap t{v[0], v[2], v[4], v[1], v[3], v[5]};
  if (t.a * t.e - t.b * t.d == 0) throw InputError("world file maps the image to a line (zero pixel size)", name);
  return t;
}

namespace {

// Other systems reach lon/lat through PROJ: the tracer keeps a projected one or reprojects it (the
// projection rule, projection.hpp), and projects any other like geographic input.
Georeference with_lonlat(Georeference g, const std::string& file) {
  if (g.crs.kind == CoordinateSystem::Kind::Other) g.map_to_lonlat = lonlat_transform(g.crs, file);
  return g;
}

Georeference find_georeference_of(const std::string& image_path, int width, int height, const GeoreferenceOptions& options);

}  // namespace

Georeference find_georeference(const std::string& image_path, int width, int height, const GeoreferenceOptions& options) {
  return with_lonlat(find_georeference_of(image_path, width, height, options), image_path);
}

namespace {

Georeference find_georeference_of(const std::string& image_path, int width, int height, const GeoreferenceOptions& options) {
  namespace fs = std::filesystem;
  Georeference g;
  if (options.box) {
    const MapBox& b = *options.box;
    if (!(b.xmax > b.xmin) || !(b.ymax > b.ymin) || !std::isfinite(b.xmin + b.xmax + b.ymin + b.ymax))
      throw InputError("bounding box must have xmin < xmax and ymin < ymax", image_path);
    const double sx = (b.xmax - b.xmin) / width, sy = (b.ymax - b.ymin) / height;
    g.source = Georeference::Source::UserBox;
    g.pixel_to_map = {sx, 0, b.xmin + 0.5 * sx, 0, -sy, b.ymax - 0.5 * sy};
    if (!options.crs.empty()) g.crs = parse_coordinate_system(options.crs);
    g.description = "bounding box given by the user" + (g.crs.name.empty() ? std::string() : " (" + g.crs.name + ")");
    return g;
  }
  const fs::path img(image_path);
  std::string ext = img.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::vector<std::string> world_exts{".wld"};
  if (ext.size() >= 3) {
    // .png -> .pgw and .pngw; .jpeg -> .jgw (.jpegw); .tif/.tiff -> .tfw (.tifw/.tiffw)
    world_exts.push_back(std::string(".") + ext[1] + ext.back() + "w");
    world_exts.push_back(ext + "w");
    if (ext == ".jpeg") world_exts.push_back(".jgw");
    if (ext == ".tiff") world_exts.push_back(".tfw");
  }
  for (const auto& we : world_exts) {
    for (const bool up : {false, true}) {
      fs::path w = img;
      w.replace_extension(up ? detail::upper(we) : we);
      std::error_code ec;
      if (!fs::is_regular_file(w, ec)) continue;
      g.source = Georeference::Source::WorldFile;
      g.pixel_to_map = parse_world_file_text(detail::read_text_file(w.string()), w.string());
      fs::path prj = img;
      prj.replace_extension(up ? ".PRJ" : ".prj");
      g.description = "world file " + w.filename().string();
      if (fs::is_regular_file(prj, ec)) {
        g.crs = parse_coordinate_system(detail::read_text_file(prj.string()), prj.string());
        g.description += " with " + prj.filename().string() + " (" + g.crs.name + ")";
      } else if (!options.crs.empty()) {
        g.crs = parse_coordinate_system(options.crs);
        g.description += " (" + g.crs.name + ", given by the user)";
      } else {
        g.description += " without a .prj: map units of unknown coordinate system";
      }
      return g;
    }
  }
  if (ext == ".tif" || ext == ".tiff") {
    if (auto t = read_geotiff_tags(image_path)) {
      if (t->crs.kind == CoordinateSystem::Kind::Unknown && !options.crs.empty()) t->crs = parse_coordinate_system(options.crs);
      return *t;
    }
  }
  g.source = Georeference::Source::None;
  g.pixel_to_map = {1, 0, 0.5, 0, -1, height - 0.5};
  g.description = "no georeference (no world file, GeoTIFF tags or bounding box): coordinates are pixels";
  return g;
}

}  // namespace

}  // namespace shoremesh::io
