#include "shoremesh/io/open_boundary.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <stdexcept>

#include "shoremesh/error.hpp"
#include "shoremesh/io/georeference.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

namespace {

using json = nlohmann::json;

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

Point2 to_mesh(const Projection& projection, double x, double y, const std::string& file, const std::string& where,
               std::optional<std::size_t> line) {
  if (projection.is_none()) return {x, y};
  if (!(std::abs(x) <= 180) || !(std::abs(y) <= 90))
    throw InputError(where + "position " + readable(x) + ", " + readable(y) + " is not lon/lat in degrees", file, line);
  try {
    return projection.forward({x, y});
  } catch (const std::domain_error& e) {
    throw InputError(where + e.what(), file, line);
  }
}

void read_text(const std::string& path, const Projection& projection, OpenBoundary& out) {
  const std::string text = detail::read_text_file(path);
  OpenBoundary::Line current;
  std::size_t first_line = 0;
  auto finish = [&] {
    if (current.points.empty()) return;
    if (current.points.size() < 2) throw InputError("an open-boundary line needs at least two points", path, first_line);
    out.lines.push_back(std::move(current));
    current = {};
  };
  detail::for_each_line(detail::strip_bom(text), [&](std::string_view raw, std::size_t number) {
    if (raw.find('#') == std::string_view::npos && detail::trim(raw).empty()) return finish();
    const std::string_view line = detail::strip_comment(raw);
    if (line.empty()) return;  // a comment line does not end a polyline
    const auto fields = detail::split_fields(line);
    if (fields.size() != 2)
      throw InputError("expected two numbers (" + std::string(projection.is_none() ? "x,y" : "lon,lat") + "), found " +
                           std::to_string(fields.size()) + " fields",
                       path, number);
    double v[2];
    for (int k = 0; k < 2; ++k) {
      const auto st = detail::parse_double(detail::trim(fields[std::size_t(k)]), v[k]);
      if (st != detail::NumberStatus::Ok)
        throw InputError(detail::quoted(fields[std::size_t(k)]) +
                             (st == detail::NumberStatus::NotFinite ? " is not a finite number" : " is not a number"),
                         path, number);
    }
    if (current.points.empty()) {
      first_line = number;
      current.where = path + ":" + std::to_string(number);
    }
    current.points.push_back(to_mesh(projection, v[0], v[1], path, "", number));
  });
  finish();
}

class GeoJsonLines {
 public:
  GeoJsonLines(const std::string& path, const Projection& projection, std::function<Point2(const Point2&)> to_lonlat,
               OpenBoundary& out)
      : path_(path), projection_(projection), to_lonlat_(std::move(to_lonlat)), out_(out) {}

  void object(const json& j, const std::string& where) {
    if (!j.is_object() || !j.contains("type") || !j["type"].is_string())
      fail(where, "expected a GeoJSON object with a \"type\"");
    const std::string type = j["type"].get<std::string>();
    if (type == "FeatureCollection") {
      if (!j.contains("features") || !j["features"].is_array()) fail(where, "\"features\" must be an array");
      for (std::size_t i = 0; i < j["features"].size(); ++i)
        object(j["features"][i], "features[" + std::to_string(i) + "]");
    } else if (type == "Feature") {
      if (!j.contains("geometry") || !j["geometry"].is_object()) fail(where, "a Feature needs a geometry");
      geometry(j["geometry"], where + ".geometry", where);
    } else {
      geometry(j, where.empty() ? "(root)" : where, where.empty() ? "(root)" : where);
    }
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError((where.empty() ? std::string() : where + ": ") + what, path_);
  }

  void line(const json& c, const std::string& where, const std::string& feature) {
    if (!c.is_array() || c.size() < 2) fail(where, "an open-boundary line needs at least two positions");
    OpenBoundary::Line l;
    l.where = path_ + ", " + feature;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const std::string w = where + "[" + std::to_string(i) + "]";
      const json& p = c[i];
      if (!p.is_array() || p.size() < 2 || p.size() > 3 || !p[0].is_number() || !p[1].is_number())
        fail(w, "a position is [lon, lat] (or [lon, lat, elevation])");
      Point2 ll{p[0].get<double>(), p[1].get<double>()};
      if (to_lonlat_) {
        try {
          ll = to_lonlat_(ll);
        } catch (const std::domain_error& e) {
          fail(w, e.what());
        }
      }
      l.points.push_back(to_mesh(projection_, ll[0], ll[1], path_, w + ": ", std::nullopt));
    }
    out_.lines.push_back(std::move(l));
  }

  void geometry(const json& g, const std::string& where, const std::string& feature) {
    if (!g.contains("type") || !g["type"].is_string()) fail(where, "a geometry needs a \"type\"");
    const std::string type = g["type"].get<std::string>();
    if (type != "LineString" && type != "MultiLineString")
      fail(where, "an open boundary is a LineString or MultiLineString, not a " + type);
    if (!g.contains("coordinates")) fail(where, "missing \"coordinates\"");
    const json& c = g["coordinates"];
    if (type == "LineString") return line(c, where + ".coordinates", feature);
    if (!c.is_array()) fail(where + ".coordinates", "expected an array of lines");
    for (std::size_t i = 0; i < c.size(); ++i)
      line(c[i], where + ".coordinates[" + std::to_string(i) + "]", feature + ".coordinates[" + std::to_string(i) + "]");
  }

  const std::string& path_;
  const Projection& projection_;
  std::function<Point2(const Point2&)> to_lonlat_;  // a legacy crs's positions to lon/lat (empty: lon/lat)
  OpenBoundary& out_;
};

void read_geojson_lines(const std::string& path, const Projection& projection, OpenBoundary& out) {
  if (projection.is_none())
    throw InputError("GeoJSON open boundaries are lon/lat, but the mesh is not projected from lon/lat (give the line "
                     "as x,y in the mesh's units in a text file)",
                     path);
  const std::string text = detail::read_text_file(path);
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {
    const std::string what = e.what();
    const auto p = what.find("] ");
    throw InputError("malformed JSON: " + (p == std::string::npos ? what : what.substr(p + 2)), path);
  }
  // A legacy (2008) "crs" naming the positions' system, as for inputs (geojson_input.hpp): PROJ reads it.
  std::function<Point2(const Point2&)> to_lonlat;
  if (root.is_object() && root.contains("crs")) {
    const json& crs = root["crs"];
    const bool named = crs.is_object() && crs.contains("type") && crs["type"].is_string() && crs["type"] == "name" &&
                       crs.contains("properties") && crs["properties"].is_object() &&
                       crs["properties"].contains("name") && crs["properties"]["name"].is_string();
    if (!named)
      throw InputError("crs: expected {\"type\": \"name\", \"properties\": {\"name\": \"EPSG:n\"}} (or no crs: lon/lat)",
                       path);
    const std::string name = crs["properties"]["name"].get<std::string>();
    CoordinateSystem cs;
    try {
      cs = parse_coordinate_system(name, path);
    } catch (const InputError& e) {
      throw InputError("crs: " + e.message(), path);
    }
    if (cs.kind == CoordinateSystem::Kind::Unknown)
      throw InputError("crs: " + detail::quoted(name) + " is a local system: its positions cannot be placed on the mesh", path);
    if (cs.kind == CoordinateSystem::Kind::Utm) {
      const Projection utm = Projection::utm_ups(cs.zone, cs.north);
      to_lonlat = [utm](const Point2& p) {
        const LonLat ll = utm.reverse(p);
        return Point2{ll.lon, ll.lat};
      };
    } else if (cs.kind == CoordinateSystem::Kind::Other) {
      to_lonlat = lonlat_transform(cs, path);
    }
  }
  GeoJsonLines(path, projection, std::move(to_lonlat), out).object(root, "");
}

double segment_distance2(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  const double ex = a[0] + t * dx - p[0], ey = a[1] + t * dy - p[1];
  return ex * ex + ey * ey;
}

double line_distance2(const Point2& p, const std::vector<Point2>& line) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < line.size(); ++k) best = std::min(best, segment_distance2(p, line[k], line[k + 1]));
  return best;
}

}  // namespace

OpenBoundary read_open_boundary(const std::string& path, const Projection& projection) {
  OpenBoundary out;
  out.file = path;
  const std::string ext = lower_extension(path);
  if (ext == ".geojson" || ext == ".json") read_geojson_lines(path, projection, out);
  else read_text(path, projection, out);
  if (out.lines.empty()) throw InputError("no open-boundary line in the file", path);
  return out;
}

void mark_open_boundary(const OpenBoundary& ob, std::span<const Point2> points, std::span<const BoundaryLoop> boundary,
                        std::span<std::uint8_t> open) {
  const double d2 = ob.distance * ob.distance;
  std::vector<std::uint8_t> near(points.size());
  for (const OpenBoundary::Line& line : ob.lines) {
    std::fill(near.begin(), near.end(), 0);
    double nearest2 = std::numeric_limits<double>::infinity();
    for (const BoundaryLoop& loop : boundary)
      for (std::uint32_t v : loop.nodes) {
        const double e2 = line_distance2(points[v], line.points);
        nearest2 = std::min(nearest2, e2);
        near[v] = e2 <= d2;
      }
    bool reached = false;
    for (const BoundaryLoop& loop : boundary)
      for (std::size_t j = 0; j < loop.nodes.size(); ++j)
        reached = reached || (near[loop.nodes[j]] && near[loop.nodes[(j + 1) % loop.nodes.size()]]);
    if (!reached)
      throw InputError("the open-boundary line " + line.where + " lies along no boundary edge of the mesh: " +
                       (std::isfinite(nearest2) ? "the nearest boundary node is " + readable(std::sqrt(nearest2)) +
                                                      " away, the tolerance " + readable(ob.distance) +
                                                      " (--open-boundary-distance)"
                                                : std::string("the mesh has no boundary")));
    for (std::size_t i = 0; i < near.size(); ++i)
      if (near[i]) open[i] = 1;
  }
}

}  // namespace shoremesh::io
