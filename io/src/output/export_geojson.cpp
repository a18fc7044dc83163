// GeoJSON (RFC 7946) for QGIS: a FeatureCollection with one Polygon feature per triangle, coordinates in
// longitude/latitude through the view's to_lonlat, each ring closed and counter-clockwise as the RFC
// recommends (the triangles are counter-clockwise in the projected plane, and a conformal projection keeps
// that), with the triangle's minimum angle, its corners' kinds and (when the view has them) its corners'
// depths, positive down, as properties. A terrain's heights are each position's third coordinate.
#include <string>

#include "shoremesh/error.hpp"
#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/export_text.hpp"
#include "shoremesh/mesh_quality.hpp"

namespace shoremesh::io {

void write_geojson(const std::filesystem::path& path, const MeshView<2>& view) {
  if (!view.to_lonlat)
    throw InputError("GeoJSON needs longitude/latitude: the input was not geographic (no projection)", path.string());
  std::vector<Point2> lonlat;
  lonlat.reserve(view.points.size());
  for (const auto& p : view.points) lonlat.push_back(view.to_lonlat(p));
  write_atomically(path, [&](std::ostream& out) {
    std::string s = "{\"type\":\"FeatureCollection\",\"features\":[\n";
    for (std::size_t i = 0; i < view.elements.size(); ++i) {
      const auto& e = view.elements[i];
      const ElementShape<2> shape = element_shape<2>({view.points[e[0]], view.points[e[1]], view.points[e[2]]});
      s += i ? ",\n" : "";
      append(s, "{\"type\":\"Feature\",\"properties\":{\"element\":", i, ",\"min_angle\":");
      append_number(s, shape.min_angle);
      std::size_t steiner = 0;
      for (auto n : e) steiner += !view.kinds.empty() && view.kinds[n] == PointKind::Steiner;
      append(s, ",\"steiner_corners\":", steiner);
      if (!view.depths.empty()) {
        s += ",\"depths\":[";
        for (int k = 0; k < 3; ++k) s += k ? "," : "", append_number(s, view.depths[e[k]]);
        s += ']';
      }
      append(s, "},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[");
      for (int k = 0; k <= 3; ++k) {
        const Point2& p = lonlat[e[k % 3]];
        s += k ? ",[" : "[";
        append_number(s, p[0]), s += ',', append_number(s, p[1]);
        if (!view.heights.empty()) s += ',', append_number(s, view.heights[e[k % 3]]);  // RFC 7946: altitude third
        s += ']';
      }
      s += "]]}}";
    }
    s += "\n]}\n";
    out << s;
  });
}

}  // namespace shoremesh::io
