#include "shoremesh/io/georeference.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

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

#include "gdal_setup.hpp"
#include "shoremesh/error.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

namespace {

std::string upper(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// WGS 84, NAD83 and ETRS89 agree within a metre: their lon/lat is taken as WGS 84's.
bool wgs84_like(const OGRSpatialReference& srs) {
  const char* datum = srs.GetAttrValue("DATUM");
  const std::string d = upper(datum ? datum : "");
  const char* code = srs.GetAuthorityCode("GEOGCS");
  const std::string c = code ? code : "";
  return c == "4326" || c == "4269" || c == "4258" || d.find("WGS_1984") != std::string::npos ||
         d.find("WGS 1984") != std::string::npos || d.find("WORLD GEODETIC SYSTEM 1984") != std::string::npos ||
         d.find("NORTH_AMERICAN_DATUM_1983") != std::string::npos || d.find("NORTH AMERICAN DATUM 1983") != std::string::npos ||
         d.find("EUROPEAN_TERRESTRIAL_REFERENCE_SYSTEM_1989") != std::string::npos ||
         d.find("EUROPEAN TERRESTRIAL REFERENCE SYSTEM 1989") != std::string::npos;
}

// The short forms PROJ does not read itself, as EPSG codes: "lonlat", "UTM 16N", "utm5s", "UTM zone 16 S".
std::optional<std::string> short_form(const std::string& text, const std::string& file) {
  const std::string up = upper(text);
  if (up == "LONLAT" || up == "LON/LAT" || up == "WGS 84" || up == "CRS84") return std::string("EPSG:4326");
  if (up.rfind("UTM", 0) != 0) return std::nullopt;
  std::size_t i = 3;
  auto blanks = [&] {
    while (i < up.size() && (up[i] == ' ' || up[i] == '_')) ++i;
  };
  blanks();
  if (up.compare(i, 4, "ZONE") == 0) i += 4, blanks();
  const std::size_t z0 = i;
  while (i < up.size() && i - z0 < 3 && std::isdigit(static_cast<unsigned char>(up[i]))) ++i;
  const std::string zone = up.substr(z0, i - z0);
  blanks();
  if (zone.empty() || i + 1 != up.size() || (up[i] != 'N' && up[i] != 'S')) return std::nullopt;
  const int z = std::stoi(zone);
  if (z < 1 || z > 60) throw InputError("UTM zone " + zone + " is not 1..60", file);
  return "EPSG:" + std::to_string((up[i] == 'N' ? 32600 : 32700) + z);
}

CoordinateSystem from_srs(OGRSpatialReference& srs) {
  CoordinateSystem cs;
  cs.name = srs.GetName() ? srs.GetName() : "unnamed";
  if (srs.IsLocal()) return cs;  // Kind::Unknown: map units, with its name
  int north = 1;
  const int zone = srs.IsProjected() ? srs.GetUTMZone(&north) : 0;
  if (srs.IsGeographic() && wgs84_like(srs)) {
    cs.kind = CoordinateSystem::Kind::Geographic;
  } else if (zone >= 1 && zone <= 60 && wgs84_like(srs)) {
    cs.kind = CoordinateSystem::Kind::Utm;
    cs.zone = zone;
    cs.north = north != 0;
  } else {
    cs.kind = CoordinateSystem::Kind::Other;
    cs.projected = srs.IsProjected() != 0;
    char* wkt = nullptr;
    const char* options[] = {"FORMAT=WKT2_2019", nullptr};
    srs.exportToWkt(&wkt, options);
    cs.wkt = wkt ? wkt : "";
    CPLFree(wkt);
  }
  return cs;
}

}  // namespace

CoordinateSystem parse_coordinate_system(std::string_view text_in, const std::string& file) {
  detail::register_gdal();
  const std::string text(detail::trim(detail::strip_bom(text_in)));
  const std::optional<std::string> code = short_form(text, file);
  OGRSpatialReference srs;
  CPLErrorReset();
  // Without file names and URLs: the text is the system itself, never a path PROJ would open.
  if (text.empty() ||
      srs.SetFromUserInput(code ? code->c_str() : text.c_str(), OGRSpatialReference::SET_FROM_USER_INPUT_LIMITATIONS) !=
          OGRERR_NONE)
    throw InputError("PROJ does not know the coordinate system " + detail::quoted(text.substr(0, 200)) +
                         " (expected EPSG:n, WKT, a PROJ string, lonlat or \"UTM 16N\")",
                     file);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return from_srs(srs);
}

std::function<Point2(const Point2&)> lonlat_transform(const CoordinateSystem& crs, const std::string& file) {
  detail::register_gdal();
  OGRSpatialReference src, ll;
  if (crs.wkt.empty() || src.importFromWkt(crs.wkt.c_str()) != OGRERR_NONE)
    throw InputError("cannot read the coordinate system " + detail::quoted(crs.name), file);
  ll.SetWellKnownGeogCS("WGS84");
  for (auto* s : {&src, &ll}) s->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::shared_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&src, &ll));
  if (!t) throw InputError("PROJ cannot transform " + detail::quoted(crs.name) + " to WGS 84 lon/lat", file);
  return [t](const Point2& m) {
    double x = m[0], y = m[1];
    if (!t->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y))
      throw std::domain_error("PROJ cannot take a point to lon/lat");
    return Point2{x, y};
  };
}

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

std::optional<Georeference> read_geotiff_tags(const std::string& path) {
  detail::register_gdal();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) return std::nullopt;
  double t[6];
  if (ds->GetGeoTransform(t) != CE_None) return std::nullopt;
  Georeference g;
  g.source = Georeference::Source::GeoTiff;
  // GDAL's transform is from the upper-left corner; ours from the upper-left pixel's centre.
  g.pixel_to_map = {t[1], t[2], t[0] + 0.5 * (t[1] + t[2]), t[4], t[5], t[3] + 0.5 * (t[4] + t[5])};
  if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
    OGRSpatialReference copy(*srs);
    copy.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    g.crs = from_srs(copy);
  } else {
    g.crs.name = "unknown";
  }
  g.description = "GeoTIFF keys of " + std::filesystem::path(path).filename().string() + " (" + g.crs.name + ")";
  return g;
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
      w.replace_extension(up ? upper(we) : we);
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
