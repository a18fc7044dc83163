#pragma once
// GeoJSON (RFC 7946) through nlohmann::json: FeatureCollection, Feature, GeometryCollection and the
// geometries Point, MultiPoint, LineString, MultiLineString, Polygon, MultiPolygon.
//
// Positions are [lon, lat] or [lon, lat, elevation] in WGS84 degrees (RFC 7946) and are projected to metres
// (the given Projection or one chosen from the data). Old GeoJSON (2008) may name its coordinate system in a
// "crs" member ("EPSG:32616", "urn:ogc:def:crs:EPSG::32616"): PROJ reads it; a projected system keeps its
// metres or is reprojected by the projection rule (projection.hpp), another datum's lon/lat goes through
// PROJ to WGS 84, `"crs": null` and a local system are map units, and a linked or unknown system is refused
// naming it. Polygon rings (closed, first position repeated) become rings of
// the domain — roles from nesting, so an exterior ring bounds water and its holes are islands; LineStrings and
// points become loose points. With a spacing, ring edges and line segments are subdivided so that no piece is
// longer (metres or map units).
//
// Errors are shoremesh::InputError naming the file and the element, e.g.
//   "lakes.geojson: features[2].geometry.coordinates[0]: polygon ring has fewer than three points"
// and, for JSON syntax errors, the line. Nesting deeper than 256 levels is refused before parsing.
// Origins: Source::Location::Element, location = the 1-based index of the position in reading order.
#include <optional>
#include <string>
#include <string_view>

#include "shoremesh/io/input_set.hpp"
#include "shoremesh/io/projection.hpp"

namespace shoremesh::io {

struct GeoJsonOptions {
  std::optional<Projection> projection;
  ProjectionChoice choice = ProjectionChoice::LocalTransverseMercator;
  double spacing = 0;
  std::size_t max_points = kMaxSampledPoints;  // a spacing that would give more points is refused
};

InputSet parse_geojson_text(std::string_view text, const std::string& name, const GeoJsonOptions& options = {});
InputSet read_geojson(const std::string& path, const GeoJsonOptions& options = {});

}  // namespace shoremesh::io
