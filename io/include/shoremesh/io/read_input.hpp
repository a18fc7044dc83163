#pragma once
// One entry point for the command line: read any supported input file into an InputSet.
//
// Dispatch on the extension (case-insensitive):
//   .png .jpg .jpeg .tif .tiff .pgm .ppm .pnm  coastline image            (image_trace.hpp)
//   .gpx                                       GPS track                  (gps_track.hpp)
//   .csv .txt .xyz .dat                        a header naming lat/lon -> GPS track (CSV);
//                                              blank-line separated closed rings -> ring file (ring_file.hpp);
//                                              otherwise plain 2D/3D points (point_file.hpp)
//   .node .poly                                Triangle files             (poly_file.hpp)
//   .geojson .json                             GeoJSON                    (geojson_input.hpp)
// Anything else is a shoremesh::InputError naming the file.
#include <optional>
#include <string>
#include <vector>

#include "shoremesh/io/geojson_input.hpp"
#include "shoremesh/io/gps_track.hpp"
#include "shoremesh/io/image_trace.hpp"
#include "shoremesh/io/input_set.hpp"
#include "shoremesh/io/poly_file.hpp"
#include "shoremesh/io/projection.hpp"

namespace shoremesh::io {

enum class InputFormat { Image, Gpx, TrackCsv, RingFile, PointFile, Node, Poly, GeoJson };
const char* to_string(InputFormat f);

struct InputOptions {
  // For every lon/lat input (GPS, GeoJSON, geographic images, point and ring files with `lonlat`): this
  // projection, or one chosen from the data. Overrides the projection fields of the per-format options.
  std::optional<Projection> projection;
  ProjectionChoice projection_choice = ProjectionChoice::LocalTransverseMercator;
  bool lonlat = false;  // plain point files and ring files hold lon, lat (degrees) in their first two columns
  double ring_spacing = 0;  // ring files: largest segment length, in the input's units (0: the vertices as given)
  TrackOptions track;
  ImageTraceOptions image;
  PslgOptions poly;
  GeoJsonOptions geojson;
};

// The format read_input would use for `path` (reads the start of CSV/text files to decide).
InputFormat detect_input_format(const std::string& path);
// Whether read_input traces `path` as an image: by its extension alone (reads nothing; text is never one).
bool is_image_input(const std::string& path);

InputSet read_input(const std::string& path, const InputOptions& options = {});

// Reads several files with one projection (the given one, or the first one chosen from the data) and merges
// them (merge(): same units, dimension and projection; duplicate points across files are an error).
InputSet read_inputs(const std::vector<std::string>& paths, const InputOptions& options = {});

}  // namespace shoremesh::io
