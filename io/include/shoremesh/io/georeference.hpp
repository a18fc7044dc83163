#pragma once
// Where an image lies on the map: an affine map from pixel centres to map coordinates plus the coordinate
// system of the map, found (in this order) from
//   1. a bounding box and coordinate system the user gives (GeoreferenceOptions::box / crs),
//   2. a world file beside the image: same name with .wld, or the image's three-letter code (.pgw/.pngw for
//      PNG, .jgw/.jpgw for JPEG, .tfw/.tifw for TIFF), with its coordinate system from a .prj sidecar (WKT),
//   3. GeoTIFF tags (ModelPixelScale + ModelTiepoint + GeoKeyDirectory); OpenImageIO's geotiff:* attributes
//      are used when the library exposes them, otherwise the tags are read from the TIFF directory directly
//      (Debian's OpenImageIO 2.4 does not expose them),
//   4. otherwise pixel units, said plainly in the result.
// Coordinate systems understood: geographic WGS84 lon/lat (EPSG:4326 and WKT GEOGCS of WGS 84 / NAD83 /
// ETRS89, which agree within a metre), UTM zones (EPSG:326zz/327zz, WKT PROJCS named "UTM zone zzN/S");
// anything else is kept as "map units" with its name.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "shoremesh/point.hpp"

namespace shoremesh::io {

struct CoordinateSystem {
  enum class Kind { Unknown, Geographic, Utm };
  Kind kind = Kind::Unknown;
  int zone = 0;        // Utm: 1..60
  bool north = true;   // Utm
  std::string name;    // as given ("WGS 84", "WGS 84 / UTM zone 16N", ...)
};

// Parses WKT 1/2 (GEOGCS/GEOGCRS/PROJCS/PROJCRS) or short forms: "EPSG:4326", "EPSG:32616", "WGS84", "lonlat",
// "UTM 16N", "UTM16S". Unrecognised projected systems give Kind::Unknown with the name; text that is not a
// coordinate system at all throws shoremesh::InputError naming `file`.
CoordinateSystem parse_coordinate_system(std::string_view text, const std::string& file = {});

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
  // Another projected system (a DEM in Web Mercator, a national grid; dem.hpp): map -> {lon, lat} degrees
  // through GDAL/PROJ. The tracer then projects like geographic input.
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

// GeoTIFF tags of a TIFF file (classic TIFF, either byte order) as a georeference, if it has them.
std::optional<Georeference> read_geotiff_tags(const std::string& tiff_path);

}  // namespace shoremesh::io
