#pragma once
// User-given open (ocean) boundaries for fort.14 (--open-boundary FILE): lines along which the mesh's
// boundary is open water, beside the automatic ones (where the water reaches a DEM's or image's edge).
//
// The file is either GeoJSON (.geojson/.json: LineString and MultiLineString geometries, alone, as
// Features or in a FeatureCollection; positions WGS 84 lon/lat as RFC 7946 says, or in the system a legacy
// "crs" member names, read by PROJ as for inputs) or a text polyline file
// (any other extension): one point a line as "x,y" or "x y", '#' comments, a blank line between lines.
// Text and GeoJSON positions are lon/lat degrees, projected with the mesh's projection; when the mesh is not
// projected (map units, pixels), text positions are in the mesh's own units and GeoJSON is refused.
//
// A mesh boundary node lies on a line when it is within `distance` of one of the line's segments (in the
// mesh's units); a boundary edge whose two nodes lie on lines is open. Each line must reach at least one
// boundary edge, so that a line drawn in the wrong place (or the wrong units) is an error naming it, not a
// silent no-op. Errors are shoremesh::InputError naming the file and the line number or the feature.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "shoremesh/io/projection.hpp"
#include "shoremesh/mesh_boundary.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::io {

struct OpenBoundary {
  struct Line {
    std::vector<Point2> points;  // in the mesh's coordinates
    std::string where;           // "open.txt:3" (first point's line) or "open.geojson, features[1]"
  };
  std::string file;
  std::vector<Line> lines;
  double distance = 0;  // a boundary node this near a line is on it (mesh units)
};

// Reads `path` (see above). `projection` is the mesh's (Kind::None: positions are mesh units).
OpenBoundary read_open_boundary(const std::string& path, const Projection& projection);

// Sets open[i] = 1 for the nodes of `boundary` within `ob.distance` of a line (open.size() == points.size()).
// Throws shoremesh::InputError naming a line that reaches no boundary edge, with how far the boundary is.
void mark_open_boundary(const OpenBoundary& ob, std::span<const Point2> points, std::span<const BoundaryLoop> boundary,
                        std::span<std::uint8_t> open);

}  // namespace shoremesh::io
