#pragma once
// --size-polygons FILE.geojson: polygons with a size each (docs/sizing.md). Every Polygon or MultiPolygon
// feature needs a positive `size` property in the mesh's units (metres for lon/lat input). Coordinates are
// lon/lat (RFC 7946) projected like the input when it was projected, the mesh's own units otherwise.
// Polygons are numbered from 0 in the file's order (a MultiPolygon's parts one after another): the
// `size N H` edit line names them so.
#include <string>
#include <vector>

#include "shoremesh/io/projection.hpp"
#include "shoremesh/size_function.hpp"

namespace shoremesh::io {

// InputError naming the file and the feature: not JSON, no features, a feature without a positive finite
// `size`, a polygon with fewer than three distinct points.
std::vector<SizePolygon> read_size_polygons(const std::string& path, const Projection& projection);

}  // namespace shoremesh::io
