#pragma once
// The common result of every reader: points in metric or map coordinates, the rings of the water domain when
// the input has rings, where each point came from, the units, and the projection that produced them.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "shoremesh/domain.hpp"
#include "shoremesh/io/projection.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::io {

struct DepthSource;   // dem.hpp
struct OpenBoundary;  // open_boundary.hpp

enum class Units {
  Metres,    // projected lon/lat (see InputSet::projection) or a metric coordinate system (UTM world file)
  Pixels,    // an image without georeference: x = column + 0.5, y = height - row - 0.5 (y up), said plainly
  MapUnits,  // plain coordinates of unknown meaning (point files, .poly/.node, georeferenced images of unknown CRS)
};
const char* to_string(Units u);  // "metres", "pixels", "map units"

// The most points one input may have once a spacing has cut its rings and segments (its other points
// included). A spacing far below the input's scale would otherwise fill the memory, and the engine's
// time, instead of failing; the readers refuse it before sampling, naming the file, the spacing and the
// count it would create. Their options may lower it (the fuzz targets do, to keep each run short).
constexpr std::size_t kMaxSampledPoints = 10'000'000;

// Where a point came from. `location` is a 1-based line for text formats (point files, CSV tracks, .node/.poly,
// GPX via the XML parser's offsets), a 1-based element index for GeoJSON (the n-th coordinate position read),
// and 0 for traced image points (whose ring tells where they are).
struct Source {
  enum class Location { Line, Element, None };
  std::string file;
  Location location = Location::Line;  // what PointOrigin::location counts for this source
};

struct PointOrigin {
  std::uint32_t source = 0;              // index into InputSet::sources
  std::uint32_t ring = kNoRing;          // index into InputSet::domain.rings, or kNoRing
  std::size_t location = 0;
  static constexpr std::uint32_t kNoRing = 0xFFFFFFFFu;
};

struct InputSet {
  int dimension = 2;                  // 3 only for 3-column point files (points3 filled, points empty)
  std::vector<Point2> points;         // every input point (ring samples included), metres/pixels/map units
  std::vector<Point3> points3;        // dimension == 3
  std::vector<PointOrigin> origins;   // parallel to points (or points3)
  std::vector<Source> sources;        // the files that origins refer to
  Domain2 domain;                     // rings (even-odd rule); empty when the input has none
  // Ring r's vertex k is points[ring_ids[r][k]]; a vertex that rings share (a .poly's) is one point.
  std::vector<std::vector<std::size_t>> ring_ids;
  Units units = Units::MapUnits;
  Projection projection;              // Kind::None unless lon/lat input was projected
  std::vector<std::string> notes;     // plain statements for the user ("pixel units: no georeference", ...)
  std::size_t dropped_small_islands = 0;  // islands (and water specks) under the minimum area, images only
  // Ring points where the water reaches the edge of the data (a traced image's or DEM's outer edge): a mesh
  // boundary edge between two of them is an open (ocean) boundary, not land. Sorted.
  std::vector<Point2> open_points;
  // Lines the user gives as open boundaries (--open-boundary), beside open_points; null: none.
  std::shared_ptr<const OpenBoundary> open_boundary;
  // Where depths at mesh nodes come from (--dem, --depth-from, soundings), in the frame of these points;
  // null: none.
  std::shared_ptr<const DepthSource> depth;

  std::size_t size() const { return dimension == 3 ? points3.size() : points.size(); }
};

// Concatenates several input sets: the same dimension, units and projection are required (shoremesh::InputError
// naming the first file that differs, otherwise); sources, ring indices and notes are renumbered and kept.
// Exact duplicate points across the sets are an error that names both origins.
InputSet merge(const std::vector<InputSet>& sets);

// Checks the rings (shoremesh::find_ring_defect) and throws shoremesh::InputError naming the file and the
// line or element of the first offending vertex, e.g. "lake.poly:12: ring 1 edge 3-4 crosses ring 2 edge 1-2".
void check_rings(const InputSet& set);

// "file:line" (or "file, element n", "file, ring r") for messages about a point.
std::string describe_origin(const InputSet& set, std::size_t point_index);

}  // namespace shoremesh::io
