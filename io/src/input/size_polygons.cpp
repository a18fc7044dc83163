#include "shoremesh/io/size_polygons.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "shoremesh/error.hpp"

namespace shoremesh::io {

namespace {

using json = nlohmann::json;

std::vector<Point2> read_ring(const json& coordinates, const Projection& projection, const std::string& path,
                              const std::string& where) {
  if (!coordinates.is_array()) throw InputError(where + ": a ring must be an array of positions", path);
  std::vector<Point2> ring;
  for (const json& position : coordinates) {
    if (!position.is_array() || position.size() < 2 || !position[0].is_number() || !position[1].is_number())
      throw InputError(where + ": a position must be [x, y]", path);
    const double x = position[0].get<double>(), y = position[1].get<double>();
    if (!std::isfinite(x) || !std::isfinite(y)) throw InputError(where + ": a coordinate is not finite", path);
    ring.push_back(projection.is_none() ? Point2{x, y} : projection.forward(LonLat{x, y}));
  }
  if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) throw InputError(where + ": a ring needs at least three distinct points", path);
  return ring;
}

}  // namespace

std::vector<SizePolygon> read_size_polygons(const std::string& path, const Projection& projection) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open the size polygons", path);
  std::stringstream text;
  text << in.rdbuf();
  json doc;
  try {
    doc = json::parse(text.str());
  } catch (const json::exception& e) {
    throw InputError(std::string("not JSON: ") + e.what(), path);
  }
  json features;
  if (doc.is_object() && doc.value("type", "") == "FeatureCollection" && doc.contains("features") && doc["features"].is_array())
    features = doc["features"];
  else if (doc.is_object() && doc.value("type", "") == "Feature")
    features = json::array({doc});
  else
    throw InputError("size polygons must be a GeoJSON FeatureCollection or Feature", path);
  std::vector<SizePolygon> out;
  for (std::size_t f = 0; f < features.size(); ++f) {
    const json& feature = features[f];
    const std::string where = "feature " + std::to_string(f + 1);
    if (!feature.is_object() || !feature.contains("geometry") || !feature["geometry"].is_object())
      throw InputError(where + " has no geometry", path);
    const json& geometry = feature["geometry"];
    const std::string type = geometry.value("type", "");
    const json* properties = feature.contains("properties") && feature["properties"].is_object() ? &feature["properties"] : nullptr;
    if (!properties || !properties->contains("size") || !(*properties)["size"].is_number())
      throw InputError(where + " has no numeric 'size' property", path);
    const double size = (*properties)["size"].get<double>();
    if (!(std::isfinite(size) && size > 0))
      throw InputError(where + ": size " + readable(size) + " is not a positive finite size", path);
    std::vector<json> polygons;
    if (type == "Polygon") polygons.push_back(geometry["coordinates"]);
    else if (type == "MultiPolygon" && geometry["coordinates"].is_array())
      for (const json& p : geometry["coordinates"]) polygons.push_back(p);
    else
      throw InputError(where + ": a size polygon must be a Polygon or MultiPolygon, not '" + type + "'", path);
    for (const json& p : polygons) {
      if (!p.is_array() || p.empty()) throw InputError(where + ": a polygon needs an outer ring", path);
      SizePolygon poly;
      poly.size = size;
      poly.name = "size polygon " + std::to_string(out.size()) + " (" + path + " " + where + ")";
      for (const json& ring : p) poly.rings.push_back(read_ring(ring, projection, path, where));
      out.push_back(std::move(poly));
    }
  }
  if (out.empty()) throw InputError("no size polygons", path);
  return out;
}

}  // namespace shoremesh::io
