#pragma once
// Where an image lies on the map: an affine map from pixel centres to map coordinates plus the coordinate
// system of the map, found (in this order) from
//   1. a bounding box and coordinate system the user gives (GeoreferenceOptions::box / crs),
//   2. a world file beside the image: same name with .wld, or the image's three-letter code (.pgw/.pngw for
//      PNG, .jgw/.jpgw for JPEG, .tfw/.tifw for TIFF), with its coordinate system from a .prj sidecar (WKT),
//   3. GeoTIFF keys, read by GDAL,
//   4. otherwise pixel units, said plainly in the result.
// Coordinate systems are GDAL/OGR spatial references (PROJ underneath): any form PROJ accepts (EPSG:n,
// WKT 1 or 2, PROJ strings, OGC URNs) plus the short forms "lonlat"/"WGS84" and "UTM 16N". Geographic
// lon/lat on WGS 84, NAD83 or ETRS89 (within a metre of each other) is projected like GPS input; a projected
// system (a UTM zone on those datums, Web Mercator, national grids) is kept or reprojected by the projection
// rule (projection.hpp: kept where its scale stays within 0.1 % of 1 over the data); other systems (other
// datums' lon/lat) reach WGS 84 lon/lat through PROJ (Georeference::map_to_lonlat) and are projected from
// there, so that lengths are true metres. Text PROJ cannot read is an error naming it; a local (engineering)
// system is kept as map units with its name.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "shoremesh/point.hpp"

namespace shoremesh::io {

struct CoordinateSystem {
  enum class Kind { Unknown, Geographic, Utm, Other };
  Kind kind = Kind::Unknown;
  int zone = 0;        // Utm: 1..60
  bool north = true;   // Utm
  std::string name;    // as PROJ names it ("WGS 84", "WGS 84 / UTM zone 16N", ...)
  std::string wkt;     // Other: the system as WKT, for the transformation to lon/lat
  bool projected = false;  // Other: a projected system (kept by the projection rule where its scale allows)
};

// Parses any coordinate system PROJ accepts (see above) or the short forms "WGS84", "lonlat", "UTM 16N",
// "UTM16S". Text PROJ cannot read (a junk WKT, EPSG:99999) throws shoremesh::InputError naming the text and
// `file`.
CoordinateSystem parse_coordinate_system(std::string_view text, const std::string& file = {});

// For Kind::Other: map coordinates -> {lon, lat} WGS 84 degrees (std::domain_error where PROJ fails).
std::function<Point2(const Point2&)> lonlat_transform(const CoordinateSystem& crs, const std::string& file = {});

// X = a*col + b*row + c, Y = d*col + e*row + f, where (col, row) = (0, 0) is the centre of the upper-left pixel
// (the world-file convention).
struct PixelToMap {
  double a = 1, b = 0, c = 0, d = 0, e = 1, f = 0;
  Point2 operator()(double col, double row) const { return {a * col + b * row + c, d * col + e * row + f}; }
  Point2 operator()(const Point2& p) const { return (*this)(p[0], p[1]); }
  // Inverse map (map -> pixel); throws std::domain_error when singular.
  Point2 inverse(const Point2& xy) const;
};

// Six numbers, one a line (A D B E C F), blank lines and surrounding blanks ignored; errors name the line.
PixelToMap parse_world_file_text(std::string_view text, const std::string& name);

struct Georeference {
  enum class Source { None, UserBox, WorldFile, GeoTiff, Gdal };
  Source source = Source::None;
  PixelToMap pixel_to_map;  // pixel units (Source::None): x = col + 0.5, y = height - row - 0.5
  CoordinateSystem crs;     // Unknown when none was found
  std::string description;  // e.g. "world file superior.wld with superior.prj (WGS 84)"
  // A system other than WGS 84 lon/lat and UTM (Web Mercator, a national grid, another datum's lon/lat):
  // map -> {lon, lat} degrees through GDAL/PROJ, for the tracer to reproject from (or to measure the scale
  // of a projected one it keeps).
  std::function<Point2(const Point2&)> map_to_lonlat;
};

// A user's box: the outer edges of the image in map coordinates (xmin/xmax at the left/right edges of the
// first/last column, ymax at the top edge), and its coordinate system (parse_coordinate_system syntax).
struct MapBox {
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
};

struct GeoreferenceOptions {
  std::optional<MapBox> box;
  std::string crs;  // for the box, or to override a world file without .prj; empty: unknown
};

Georeference find_georeference(const std::string& image_path, int width, int height,
                               const GeoreferenceOptions& options = {});

// The georeference GDAL reads from a TIFF file's GeoTIFF keys, if it has them.
std::optional<Georeference> read_geotiff_tags(const std::string& tiff_path);

}  // namespace shoremesh::io
