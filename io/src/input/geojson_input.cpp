#include "shoremesh/io/geojson_input.hpp"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <functional>
#include <set>
#include <stdexcept>

#include "input_builder.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/georeference.hpp"
#include "shoremesh/domain.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

namespace {

using json = nlohmann::json;

constexpr int kMaxDepth = 256;

std::size_t line_of_offset(std::string_view text, std::size_t offset) {
  std::size_t line = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

// nlohmann's messages start with "[json.exception.parse_error.101] ": keep what follows.
std::string without_id(const std::string& what) {
  const auto p = what.find("] ");
  return p == std::string::npos ? what : what.substr(p + 2);
}

// Depth of [ and { nesting outside strings; refuses deep documents before the recursive parser sees them.
void check_depth(std::string_view text, const std::string& name) {
  int depth = 0;
  bool in_string = false, escape = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escape) escape = false;
      else if (c == '\\') escape = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == '[' || c == '{') {
      if (++depth > kMaxDepth)
        throw InputError("JSON nested deeper than " + std::to_string(kMaxDepth) + " levels", name, line_of_offset(text, i));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

struct Geometry {
  struct Position {
    Point2 p;
    std::size_t element;
    std::string path;
  };
  std::vector<std::vector<Position>> rings;
  std::vector<std::vector<Position>> lines;  // LineStrings (sampled)
  std::vector<Position> points;
};

class Reader {
 public:
  Reader(const std::string& name) : name_(name) {}

  void object(const json& j, const std::string& path) {
    if (!j.is_object()) fail(path, "expected a GeoJSON object");
    const auto type = member_string(j, "type", path);
    if (type == "FeatureCollection") {
      const auto& features = member(j, "features", path);
      if (!features.is_array()) fail(path + ".features", "expected an array");
      for (std::size_t i = 0; i < features.size(); ++i) {
        const std::string fp = path + "features[" + std::to_string(i) + "]";
        if (!features[i].is_object() || member_string(features[i], "type", fp) != "Feature") fail(fp, "expected a Feature");
        object(features[i], fp + ".");
      }
    } else if (type == "Feature") {
      const auto& g = member(j, "geometry", path);
      if (!g.is_null()) geometry(g, path + "geometry", 0);
    } else {
      geometry(j, path.empty() ? std::string("(root)") : path.substr(0, path.size() - 1), 0);
    }
  }

  Geometry result;
  std::size_t elements = 0;

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError((path.empty() ? std::string() : path + ": ") + what, name_);
  }
  const json& member(const json& j, const char* key, const std::string& path) const {
    const auto it = j.find(key);
    if (it == j.end()) fail(path.empty() ? "(root)" : path, std::string("missing \"") + key + "\"");
    return *it;
  }
  std::string member_string(const json& j, const char* key, const std::string& path) const {
    const auto& v = member(j, key, path);
    if (!v.is_string()) fail(path, std::string("\"") + key + "\" must be a string");
    return v.get<std::string>();
  }

  Geometry::Position position(const json& j, const std::string& path) {
    if (!j.is_array() || j.size() < 2 || j.size() > 3) fail(path, "a position must be an array of 2 or 3 numbers");
    Point2 p{};
    for (std::size_t k = 0; k < 2; ++k) {
      if (!j[k].is_number()) fail(path + "[" + std::to_string(k) + "]", "not a number");
      p[k] = j[k].get<double>();
      if (!std::isfinite(p[k])) fail(path + "[" + std::to_string(k) + "]", "not a finite number");
    }
    if (j.size() == 3 && !j[2].is_number()) fail(path + "[2]", "elevation is not a number");
    return {p, ++elements, path};
  }

  std::vector<Geometry::Position> positions(const json& j, const std::string& path) {
    if (!j.is_array()) fail(path, "expected an array of positions");
    std::vector<Geometry::Position> out;
    for (std::size_t i = 0; i < j.size(); ++i) out.push_back(position(j[i], path + "[" + std::to_string(i) + "]"));
    return out;
  }

  void ring(const json& j, const std::string& path) {
    auto pts = positions(j, path);
    if (pts.size() >= 2 && pts.front().p == pts.back().p) pts.pop_back();
    if (pts.size() < 3) fail(path, "polygon ring has fewer than three points");
    result.rings.push_back(std::move(pts));
  }

  void polygon(const json& j, const std::string& path) {
    if (!j.is_array() || j.empty()) fail(path, "a Polygon needs at least one ring");
    const std::size_t outer = result.rings.size();
    for (std::size_t r = 0; r < j.size(); ++r) ring(j[r], path + "[" + std::to_string(r) + "]");
    // A hole (ring 1, 2, ...) lies inside its outer ring (RFC 7946, 3.1.6); one outside it would become a
    // second lake under the even-odd rule. Rings that cross are refused later (check_rings), so one vertex
    // of the hole decides.
    std::vector<Point2> shell;
    for (const auto& q : result.rings[outer]) shell.push_back(q.p);
    for (std::size_t r = 1; r < j.size(); ++r)
      if (!ring_contains(shell, result.rings[outer + r].front().p))
        fail(path + "[" + std::to_string(r) + "]",
             "hole " + std::to_string(r) + " lies outside the polygon's outer ring (ring 0); a hole must be inside it");
  }

  void geometry(const json& g, const std::string& path, int depth) {
    if (!g.is_object()) fail(path, "expected a geometry object");
    const auto type = member_string(g, "type", path);
    if (type == "GeometryCollection") {
      const auto& gs = member(g, "geometries", path);
      if (!gs.is_array()) fail(path + ".geometries", "expected an array");
      for (std::size_t i = 0; i < gs.size(); ++i) geometry(gs[i], path + ".geometries[" + std::to_string(i) + "]", depth + 1);
      return;
    }
    const auto& c = member(g, "coordinates", path);
    const std::string cp = path + ".coordinates";
    if (type == "Point") {
      result.points.push_back(position(c, cp));
    } else if (type == "MultiPoint") {
      for (auto& p : positions(c, cp)) result.points.push_back(std::move(p));
    } else if (type == "LineString") {
      auto pts = positions(c, cp);
      if (pts.size() < 2) fail(cp, "a LineString needs at least two positions");
      result.lines.push_back(std::move(pts));
    } else if (type == "MultiLineString") {
      if (!c.is_array()) fail(cp, "expected an array of LineStrings");
      for (std::size_t i = 0; i < c.size(); ++i) {
        auto pts = positions(c[i], cp + "[" + std::to_string(i) + "]");
        if (pts.size() < 2) fail(cp + "[" + std::to_string(i) + "]", "a LineString needs at least two positions");
        result.lines.push_back(std::move(pts));
      }
    } else if (type == "Polygon") {
      polygon(c, cp);
    } else if (type == "MultiPolygon") {
      if (!c.is_array()) fail(cp, "expected an array of Polygons");
      for (std::size_t i = 0; i < c.size(); ++i) polygon(c[i], cp + "[" + std::to_string(i) + "]");
    } else {
      fail(path, "unknown geometry type " + detail::quoted(type));
    }
  }

  const std::string& name_;
};

// The "crs" member of 2008 GeoJSON (RFC 7946 dropped it: positions are WGS 84 lon/lat, its default). A
// named system is PROJ's to read ("EPSG:32616", "urn:ogc:def:crs:EPSG::32616", OGC's CRS84), positions
// being x (easting or longitude) first whatever the system's own axis order, as the 2008 text says.
// `"crs": null` (2008: no system can be assumed) is map units; a linked system, a malformed member and a
// name PROJ cannot read are refused naming the member.
struct LegacyCrs {
  bool map_units = false;     // "crs": null, or a local (engineering) system
  std::string name;           // as given
  CoordinateSystem system;    // Kind::Geographic for WGS 84-like lon/lat
};
std::optional<LegacyCrs> legacy_crs(const json& root, const std::string& name) {
  if (!root.is_object()) return std::nullopt;
  const auto it = root.find("crs");
  if (it == root.end()) return std::nullopt;
  LegacyCrs out;
  if (it->is_null()) {
    out.map_units = true;
    out.name = "\"crs\": null";
    return out;
  }
  auto refuse = [&](const std::string& what) -> void { throw InputError("crs: " + what, name); };
  if (!it->is_object()) refuse("expected an object {\"type\": \"name\", \"properties\": {\"name\": ...}}");
  const auto type = it->find("type");
  if (type != it->end() && type->is_string() && type->get<std::string>() == "link")
    refuse("a linked coordinate system (\"type\": \"link\") is not read; name it (\"type\": \"name\", e.g. "
           "\"EPSG:32616\")");
  const auto props = it->find("properties");
  if (type == it->end() || !type->is_string() || type->get<std::string>() != "name" || props == it->end() ||
      !props->is_object() || props->find("name") == props->end() || !(*props)["name"].is_string())
    refuse("expected {\"type\": \"name\", \"properties\": {\"name\": \"EPSG:n\" or an OGC URN}}");
  out.name = (*props)["name"].get<std::string>();
  try {
    out.system = parse_coordinate_system(out.name, name);
  } catch (const InputError& e) {
    throw InputError("crs: " + e.message(), name);
  }
  out.map_units = out.system.kind == CoordinateSystem::Kind::Unknown;
  return out;
}

}  // namespace

InputSet parse_geojson_text(std::string_view text, const std::string& name, const GeoJsonOptions& options) {
  check_depth(text, name);
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    throw InputError("malformed JSON: " + without_id(e.what()), name, line_of_offset(text, e.byte > 0 ? e.byte - 1 : 0));
  } catch (const json::exception& e) {  // e.g. out_of_range: a number too large for a double
    throw InputError("malformed JSON: " + without_id(e.what()), name);
  }
  Reader reader(name);
  reader.object(root, "");
  Geometry& g = reader.result;
  if (g.rings.empty() && g.lines.empty() && g.points.empty()) throw InputError("no points", name);

  InputSet set;
  const auto crs = legacy_crs(root, name);
  // The positions' own system, when a crs names one: projected (kept or reprojected by the projection
  // rule) or another datum's lon/lat (through PROJ).
  std::optional<Projection> source;
  std::function<Point2(const Point2&)> to_lonlat;
  if (crs && !crs->map_units) {
    if (crs->system.kind == CoordinateSystem::Kind::Utm) source = Projection::utm_ups(crs->system.zone, crs->system.north);
    else if (crs->system.kind == CoordinateSystem::Kind::Other && crs->system.projected)
      source = Projection::crs(crs->system.wkt, crs->system.name, name);
    else if (crs->system.kind == CoordinateSystem::Kind::Other) to_lonlat = lonlat_transform(crs->system, name);
  }
  auto lonlat = [&](const Geometry::Position& p) -> LonLat {
    if (source) return source->reverse(p.p);
    if (to_lonlat) {
      const Point2 ll = to_lonlat(p.p);
      return {ll[0], ll[1]};
    }
    return {p.p[0], p.p[1]};
  };
  if (crs && crs->map_units) {
    set.units = Units::MapUnits;
    set.notes.push_back("coordinates in " + (crs->system.name.empty() ? crs->name : crs->system.name) +
                        " read as map units");
  } else {
    set.units = Units::Metres;
    std::vector<LonLat> all;
    auto add = [&](const std::vector<Geometry::Position>& v) {
      for (const auto& p : v) {
        LonLat ll;
        try {
          ll = lonlat(p);
        } catch (const std::domain_error& e) {
          throw InputError(p.path + ": " + e.what(), name);
        }
        if (!(std::abs(ll.lon) <= 180) || !(std::abs(ll.lat) <= 90))
          throw InputError(p.path + ": position " + readable(p.p[0]) + ", " + readable(p.p[1]) +
                               (crs ? " is outside " + crs->system.name + "'s range of lon/lat"
                                    : std::string(" is not lon/lat in degrees (GeoJSON is WGS84 lon/lat; name a \"crs\" "
                                                  "for projected data)")),
                           name);
        all.push_back(ll);
      }
    };
    for (const auto& r : g.rings) add(r);
    for (const auto& l : g.lines) add(l);
    add(g.points);
    if (crs) set.notes.push_back("coordinates in " + crs->system.name + " (the GeoJSON's crs " + detail::quoted(crs->name) + ")");
    if (options.projection && !options.projection->is_none()) {
      set.projection = *options.projection;
      set.notes.push_back("projected to metres with " + set.projection.describe());
    } else {
      ChosenProjection chosen = choose_projection(source, all, options.choice, name);
      set.projection = chosen.projection;
      set.notes.push_back(chosen.note);
    }
  }
  auto convert = [&](const Geometry::Position& p) -> Point2 {
    if (set.units == Units::MapUnits) return p.p;
    if (source && *source == set.projection) return p.p;
    try {
      return set.projection.forward(lonlat(p));
    } catch (const std::domain_error& e) {
      throw InputError(p.path + ": " + e.what(), name);
    }
  };
  auto converted = [&](const std::vector<Geometry::Position>& positions) {
    std::vector<Point2> pts;
    for (const auto& p : positions) pts.push_back(convert(p));
    return pts;
  };
  std::vector<std::vector<Point2>> rings, lines;
  for (const auto& r : g.rings) rings.push_back(converted(r));
  for (const auto& l : g.lines) lines.push_back(converted(l));
  double count = static_cast<double>(g.points.size());  // the points the spacing gives, checked before sampling any
  for (const auto& r : rings) count += detail::subdivided_count(r, true, options.spacing);
  for (const auto& l : lines) count += detail::subdivided_count(l, false, options.spacing);
  detail::check_sampled_count(count, options.spacing, options.max_points, name);

  detail::InputBuilder builder(set, name, Source::Location::Element);
  for (std::size_t r = 0; r < rings.size(); ++r) {
    std::vector<std::size_t> elements;
    for (const auto& p : g.rings[r]) elements.push_back(p.element);
    builder.add_ring(rings[r], RingRole::Shore, elements, options.spacing, options.max_points);
  }
  // LineStrings are open chains of constraints (a breakwater, a channel's edge): mesh edges in the water
  // that bound nothing. A position repeated right after itself is one vertex.
  std::size_t repeated_in_lines = 0;
  for (const auto& l : g.lines) {
    std::vector<Point2> pts;
    std::vector<std::size_t> elements;
    for (const auto& p : l) {
      const Point2 q = convert(p);
      if (!pts.empty() && pts.back() == q) {
        ++repeated_in_lines;
        continue;
      }
      pts.push_back(q);
      elements.push_back(p.element);
    }
    if (pts.size() < 2) throw InputError(l.front().path + ": a LineString needs two distinct positions", name);
    builder.add_ring(pts, RingRole::Line, elements, options.spacing, options.max_points);
  }
  if (repeated_in_lines) set.notes.push_back("dropped " + std::to_string(repeated_in_lines) + " position(s) repeated along a LineString");
  if (!g.lines.empty())
    set.notes.push_back(std::to_string(g.lines.size()) + " LineString(s) kept as constraint lines (chains of mesh edges)");
  assign_roles_by_nesting(set.domain);
  check_rings(set);
  std::set<Point2> seen(set.points.begin(), set.points.end());
  std::size_t repeats = 0;
  auto loose = [&](const Point2& p, std::size_t element) {
    if (seen.insert(p).second) builder.add_point(p, element);
    else ++repeats;
  };
  for (const auto& p : g.points) loose(convert(p), p.element);
  if (repeats) set.notes.push_back("dropped " + std::to_string(repeats) + " repeated position(s)");
  return set;
}

InputSet read_geojson(const std::string& path, const GeoJsonOptions& options) {
  return parse_geojson_text(detail::read_text_file(path), path, options);
}

}  // namespace shoremesh::io
