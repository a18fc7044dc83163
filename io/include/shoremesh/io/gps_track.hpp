#pragma once
// GPS tracks: GPX 1.0/1.1 (tracks and their segments, routes, waypoints) through pugixml, and CSV files whose
// header names lat/lon columns (and optionally elevation), projected to metres with GeographicLib.
//
// GPX: the root must be <gpx> with version 1.0 or 1.1; <trk>/<trkseg>/<trkpt>, <rte>/<rtept> and <wpt> are
// read (namespace prefixes ignored), each point needs numeric lat in [-90, 90] and lon in [-180, 180], <ele> is
// optional. XML errors (truncated files, mismatched tags) and bad points throw shoremesh::InputError with the
// file and line.
//
// CSV: the first non-comment line is a header; columns are found by name, case-insensitively:
// lat|latitude, lon|lng|long|longitude, and optionally ele|elevation|alt|altitude|height. Fields are separated
// by commas (or blanks when a line has no comma; quoted fields with embedded commas are not supported); other
// columns (time, name, ...) are ignored; numbers are parsed strictly; an empty elevation is "no elevation".
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "shoremesh/io/input_set.hpp"
#include "shoremesh/io/projection.hpp"

namespace shoremesh::io {

struct GeoPoint {
  double lon = 0, lat = 0;    // degrees, WGS84
  std::optional<double> ele;  // metres, when given
  std::size_t line = 0;       // 1-based source line
};

struct GpsSequence {
  enum class Kind { TrackSegment, Route, Waypoints };
  Kind kind = Kind::TrackSegment;
  std::string name;  // <name> of the track or route (empty if none)
  std::size_t line = 0;
  std::vector<GeoPoint> points;
};

struct GpsData {
  std::string version;  // "1.0", "1.1" (GPX) or "csv"
  std::vector<GpsSequence> sequences;
  std::size_t point_count() const;
};

GpsData parse_gpx_text(std::string_view text, const std::string& name);
GpsData read_gpx(const std::string& path);
GpsData parse_track_csv_text(std::string_view text, const std::string& name);
GpsData read_track_csv(const std::string& path);
// True when the first non-comment line of a CSV names both a latitude and a longitude column.
bool csv_header_has_lat_lon(std::string_view text);

struct TrackOptions {
  // Projection: the given one, or one chosen from the data (UTM zone of the data's centre by default).
  std::optional<Projection> projection;
  ProjectionChoice choice = ProjectionChoice::LocalTransverseMercator;
  // Sampling (metres): along each track or route, no piece longer than `spacing`. The fixes are thinned
  // first (from each kept fix, the last of the fixes that follow within `spacing` of it: GPS jitter stays
  // out, and the kept fixes lie about `spacing` apart), then longer gaps are cut evenly. 0 keeps every
  // fix except exact repeats.
  double spacing = 0;
  std::size_t max_points = kMaxSampledPoints;  // a spacing that would give more points is refused
  // Smoothing before resampling: moving average of 2*smooth_window+1 projected points (0: none). The first and
  // last points of an open track are kept in place.
  int smooth_window = 0;
  // A track or route whose last point is within `close_tolerance` metres of its first is a closed shoreline
  // walk: it becomes a ring of the domain (roles from nesting: a walk around a lake encloses water). Negative:
  // max(2 * spacing, 25 m); 0: never close (every track stays loose points).
  double close_tolerance = -1;
  // A track or route that does not close becomes a constraint line (RingRole::Line: a chain of mesh edges
  // inside the water that bounds nothing) instead of loose points. It must lie in the water and cross no
  // ring or line (check_rings says which one does).
  bool open_lines = false;
  bool waypoints = true;  // include <wpt> points (as loose points)
};

// Projects, smooths, resamples and closes; rings are validated (self-intersecting walks are reported).
InputSet gps_to_input(const GpsData& data, const std::string& file, const TrackOptions& options = {});

}  // namespace shoremesh::io
