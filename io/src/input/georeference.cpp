#include "shoremesh/io/georeference.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "shoremesh/error.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

namespace {

std::string upper(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// Digits as an int; -1 when out of range (std::stoi would throw on "EPSG:99999999999").
int small_int(const std::string& digits) {
  const auto v = detail::parse_integer(digits);
  return v && *v >= 0 && *v <= 1000000 ? static_cast<int>(*v) : -1;
}

CoordinateSystem from_epsg(int code, const std::string& name) {
  CoordinateSystem cs;
  cs.name = name;
  if (code == 4326 || code == 4269 || code == 4258) {  // WGS 84, NAD83, ETRS89: within a metre of each other
    cs.kind = CoordinateSystem::Kind::Geographic;
  } else if ((code > 32600 && code <= 32660) || (code > 32700 && code <= 32760)) {
    cs.kind = CoordinateSystem::Kind::Utm;
    cs.zone = code % 100;
    cs.north = code < 32700;
  }
  return cs;
}

// A cursor over upper-cased text for the few fixed grammars of coordinate-system names (no std::regex: its
// libstdc++ implementation recurses per character of the subject).
struct Scan {
  std::string_view s;
  std::size_t i = 0;
  void blanks() {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == '\n')) ++i;
  }
  bool word(std::string_view w) {
    if (s.substr(i, w.size()) != w) return false;
    i += w.size();
    return true;
  }
  bool one_of(std::string_view chars) {
    if (i < s.size() && chars.find(s[i]) != std::string_view::npos) return ++i, true;
    return false;
  }
  std::string digits(std::size_t max) {
    const std::size_t j = i;
    while (i < s.size() && i - j < max && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
    return std::string(s.substr(j, i - j));
  }
  bool end() const { return i == s.size(); }
};

// The code of the outermost AUTHORITY["EPSG","n"] / ID["EPSG",n]: the one that closes the WKT ("...]]" at
// the end).
std::optional<int> wkt_epsg(const std::string& wkt) {
  const std::string up = upper(wkt);
  const auto at = up.rfind("\"EPSG\"");
  if (at == std::string::npos) return std::nullopt;
  Scan c{up, at + 6};
  c.blanks();
  if (!c.word(",")) return std::nullopt;
  c.blanks();
  c.word("\"");
  const std::string code = c.digits(9);
  c.word("\"");
  c.blanks();
  if (code.empty() || !c.word("]")) return std::nullopt;
  c.blanks();
  if (!c.word("]")) return std::nullopt;
  c.blanks();
  if (!c.end()) return std::nullopt;
  const int v = small_int(code);
  return v >= 0 ? std::optional<int>(v) : std::nullopt;
}

// "UTM zone 16N" (also "UTM_Zone_16N", "UTM ZONE 16 N") inside a name: zone and hemisphere.
std::optional<std::pair<int, bool>> utm_in_name(const std::string& name) {
  const std::string up = upper(name);
  for (std::size_t at = up.find("UTM"); at != std::string::npos; at = up.find("UTM", at + 1)) {
    Scan c{up, at + 3};
    if (!c.one_of(" _") || !c.word("ZONE") || !c.one_of(" _")) continue;
    const std::string zone = c.digits(2);
    c.blanks();
    const std::size_t h = c.i;
    if (zone.empty() || !c.one_of("NS")) continue;
    return std::make_pair(small_int(zone), up[h] == 'N');
  }
  return std::nullopt;
}

std::string wkt_name(const std::string& wkt) {
  const auto q = wkt.find('"');
  if (q == std::string::npos) return {};
  const auto q2 = wkt.find('"', q + 1);
  return q2 == std::string::npos ? std::string() : wkt.substr(q + 1, q2 - q - 1);
}

}  // namespace

CoordinateSystem parse_coordinate_system(std::string_view text_in, const std::string& file) {
  const std::string text(detail::trim(detail::strip_bom(text_in)));
  const std::string up = upper(text);
  {
    Scan c{up};  // "EPSG:n"
    if (c.word("EPSG:")) {
      c.blanks();
      const std::string code = c.digits(9);
      if (!code.empty() && c.end()) return from_epsg(small_int(code), text);
    }
  }
  if (up == "WGS84" || up == "WGS 84" || up == "LONLAT" || up == "LON/LAT" || up == "CRS84" || up == "OGC:CRS84")
    return {CoordinateSystem::Kind::Geographic, 0, true, text};
  {
    Scan c{up};  // "UTM 16N", "UTM zone 16 S", "utm5s"
    if (c.word("UTM")) {
      c.blanks();
      if (c.word("ZONE")) c.blanks();
      const std::string zone = c.digits(2);
      c.blanks();
      const std::size_t h = c.i;
      if (!zone.empty() && c.one_of("NS") && c.end()) {
        const int z = small_int(zone);
        if (z < 1 || z > 60) throw InputError("UTM zone " + zone + " is not 1..60", file);
        return {CoordinateSystem::Kind::Utm, z, up[h] == 'N', text};
      }
    }
  }
  const bool projected = up.rfind("PROJCS[", 0) == 0 || up.rfind("PROJCRS[", 0) == 0 || up.rfind("PROJECTEDCRS[", 0) == 0;
  const bool geographic = up.rfind("GEOGCS[", 0) == 0 || up.rfind("GEOGCRS[", 0) == 0 || up.rfind("GEODCRS[", 0) == 0 ||
                          up.rfind("GEOGRAPHICCRS[", 0) == 0;
  if (!projected && !geographic)
    throw InputError("not a coordinate system (expected WKT, EPSG:n, WGS84 or \"UTM 16N\"): " + detail::quoted(text), file);
  const std::string name = wkt_name(text);
  if (const auto code = wkt_epsg(text)) {
    auto cs = from_epsg(*code, name);
    if (cs.kind != CoordinateSystem::Kind::Unknown) return cs;
  }
  if (geographic) {
    if (up.find("WGS") != std::string::npos && up.find("84") != std::string::npos)
      return {CoordinateSystem::Kind::Geographic, 0, true, name};
    if (up.find("NAD83") != std::string::npos || up.find("NORTH_AMERICAN_DATUM_1983") != std::string::npos ||
        up.find("ETRS") != std::string::npos)
      return {CoordinateSystem::Kind::Geographic, 0, true, name};
    return {CoordinateSystem::Kind::Unknown, 0, true, name};
  }
  if (const auto utm = utm_in_name(name); utm && up.find("WGS") != std::string::npos) {
    if (utm->first >= 1 && utm->first <= 60) return {CoordinateSystem::Kind::Utm, utm->first, utm->second, name};
  }
  return {CoordinateSystem::Kind::Unknown, 0, true, name};
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

namespace {

// --- Minimal classic-TIFF directory reader for the three GeoTIFF tags -----------------------------------
class TiffTags {
 public:
  explicit TiffTags(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return;
    data_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (data_.size() < 8) return;
    if (data_[0] == 'I' && data_[1] == 'I') little_ = true;
    else if (data_[0] == 'M' && data_[1] == 'M') little_ = false;
    else return;
    if (u16(2) != 42) return;  // BigTIFF (43) is not read here
    const std::size_t ifd = u32(4);
    if (ifd + 2 > data_.size()) return;
    const std::size_t n = u16(ifd);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t e = ifd + 2 + 12 * i;
      if (e + 12 > data_.size()) return;
      entries_.push_back({u16(e), u16(e + 2), u32(e + 4), e + 8});
    }
    ok_ = true;
  }
  bool ok() const { return ok_; }

  std::vector<double> doubles(unsigned tag) const {
    std::vector<double> out;
    for (std::uint64_t bits : values(tag, 12, 8)) {  // DOUBLE
      double d;
      std::memcpy(&d, &bits, 8);
      out.push_back(d);
    }
    return out;
  }
  std::vector<unsigned> shorts(unsigned tag) const {
    std::vector<unsigned> out;
    for (std::uint64_t v : values(tag, 3, 2)) out.push_back(static_cast<unsigned>(v));  // SHORT
    return out;
  }

 private:
  struct Entry {
    unsigned tag, type;
    std::size_t count, value_pos;
  };
  const Entry* find(unsigned tag) const {
    for (const auto& e : entries_)
      if (e.tag == tag) return &e;
    return nullptr;
  }
  // The values of a tag of TIFF type `type`, `size` bytes each; empty when absent, of another type or truncated.
  std::vector<std::uint64_t> values(unsigned tag, unsigned type, std::size_t size) const {
    const Entry* en = find(tag);
    std::vector<std::uint64_t> out;
    if (!en || en->type != type || en->count > 100000) return out;
    const std::size_t off = en->count * size <= 4 ? en->value_pos : u32(en->value_pos);
    if (off + en->count * size > data_.size()) return out;
    for (std::size_t k = 0; k < en->count; ++k) out.push_back(uint(off + size * k, size));
    return out;
  }
  std::uint64_t uint(std::size_t p, std::size_t bytes) const {
    if (p + bytes > data_.size()) return 0;
    std::uint64_t v = 0;
    for (std::size_t b = 0; b < bytes; ++b)
      v |= static_cast<std::uint64_t>(static_cast<unsigned char>(data_[p + (little_ ? b : bytes - 1 - b)])) << (8 * b);
    return v;
  }
  unsigned u16(std::size_t p) const { return static_cast<unsigned>(uint(p, 2)); }
  std::size_t u32(std::size_t p) const { return static_cast<std::size_t>(uint(p, 4)); }
  std::string data_;
  bool little_ = true, ok_ = false;
  std::vector<Entry> entries_;
};

// GeoTIFF: pixel scale, tie point (raster i,j -> model x,y), raster type (area: raster (0,0) is the corner of
// the upper-left pixel; point: its centre) and the coordinate system keys.
std::optional<Georeference> geotiff_from(const std::vector<double>& scale, const std::vector<double>& tie,
                                         const std::vector<unsigned>& keys, const std::string& path) {
  if (scale.size() < 2 || tie.size() < 6 || scale[0] == 0 || scale[1] == 0) return std::nullopt;
  unsigned model_type = 0, raster_type = 1, geographic = 0, projected = 0;
  if (keys.size() >= 4) {
    const std::size_t n = keys[3];
    for (std::size_t k = 0; k < n && 4 + 4 * k + 3 < keys.size(); ++k) {
      const unsigned id = keys[4 + 4 * k], loc = keys[4 + 4 * k + 1], value = keys[4 + 4 * k + 3];
      if (loc != 0) continue;  // values stored elsewhere are not needed
      if (id == 1024) model_type = value;
      if (id == 1025) raster_type = value;
      if (id == 2048) geographic = value;
      if (id == 3072) projected = value;
    }
  }
  Georeference g;
  g.source = Georeference::Source::GeoTiff;
  const double half = raster_type == 2 ? 0.0 : 0.5;  // PixelIsPoint : PixelIsArea
  g.pixel_to_map = {scale[0], 0, tie[3] + (half - tie[0]) * scale[0], 0, -scale[1], tie[4] - (half - tie[1]) * scale[1]};
  if (model_type == 2 || (model_type == 0 && geographic))
    g.crs = from_epsg(geographic ? static_cast<int>(geographic) : 4326, "EPSG:" + std::to_string(geographic));
  else if (projected)
    g.crs = from_epsg(static_cast<int>(projected), "EPSG:" + std::to_string(projected));
  if (g.crs.kind == CoordinateSystem::Kind::Unknown && g.crs.name.empty()) g.crs.name = "unknown";
  g.description = "GeoTIFF tags of " + std::filesystem::path(path).filename().string() + " (" + g.crs.name + ")";
  return g;
}

}  // namespace

std::optional<Georeference> read_geotiff_tags(const std::string& path) {
  // OpenImageIO exposes GeoTIFF tags as geotiff:* attributes when built to do so.
  if (auto in = OIIO::ImageInput::open(path)) {
    const auto& spec = in->spec();
    auto get = [&](const char* name) {
      std::vector<double> v;
      if (const OIIO::ParamValue* p = spec.find_attribute(name)) {
        if (p->type().basetype == OIIO::TypeDesc::DOUBLE) {
          const auto* d = static_cast<const double*>(p->data());
          v.assign(d, d + p->type().numelements() * p->type().aggregate * p->nvalues());
        }
      }
      return v;
    };
    const auto scale = get("geotiff:ModelPixelScale"), tie = get("geotiff:ModelTiePoint");
    if (!scale.empty() && !tie.empty()) {
      std::vector<unsigned> keys;
      if (const OIIO::ParamValue* p = spec.find_attribute("geotiff:GeoKeyDirectory")) {
        const auto n = p->type().numelements() * p->nvalues();
        if (p->type().basetype == OIIO::TypeDesc::UINT16)
          for (std::size_t i = 0; i < n; ++i) keys.push_back(static_cast<const std::uint16_t*>(p->data())[i]);
      }
      if (auto g = geotiff_from(scale, tie, keys, path)) return g;
    }
    in->close();
  }
  TiffTags tags(path);
  if (!tags.ok()) return std::nullopt;
  return geotiff_from(tags.doubles(33550), tags.doubles(33922), tags.shorts(34735), path);
}

Georeference find_georeference(const std::string& image_path, int width, int height, const GeoreferenceOptions& options) {
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

}  // namespace shoremesh::io
