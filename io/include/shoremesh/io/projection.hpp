#pragma once
// Map projections of lon/lat (WGS84) input, wrapping GeographicLib.
//
// Geographic input (GPS tracks, GeoJSON, lon/lat images and point files) is projected to metres before
// meshing, and the Projection travels with the points (InputSet::projection) so that outputs can go back to
// lon/lat with reverse(). Three kinds:
//   None                      coordinates are already metric/map/pixel units; forward/reverse refuse.
//   UtmUps                    UTM zone 1..60 (north or south) or UPS (zone 0, north or south pole), with the
//                             standard false eastings/northings. The hemisphere is a property of the
//                             projection, not of each point: a track crossing the equator gets continuous
//                             northings (negative or above 10,000 km on the other side).
//   LocalTransverseMercator   transverse Mercator with scale 1 centred on (lon0, lat0): x = 0, y = 0 there.
//                             Works across the antimeridian and over the poles.
// Both transverse Mercator kinds use GeographicLib's Krüger series (TransverseMercator), accurate to 5 nm
// within 3,900 km of the central meridian; points farther than that are refused with a clear error.
#include <string>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh::io {

struct LonLat {
  double lon = 0;  // degrees east
  double lat = 0;  // degrees north
};

// How to choose a projection from the data when the user gives none.
enum class ProjectionChoice {
  Utm,                      // the UTM zone of the data's centre (UPS beyond 84N / 80S)
  LocalTransverseMercator,  // transverse Mercator centred on the data
};

class Projection {
 public:
  enum class Kind { None, UtmUps, LocalTransverseMercator };

  Projection() = default;  // Kind::None
  // zone 1..60 for UTM, 0 for UPS; throws std::invalid_argument on a bad zone.
  static Projection utm_ups(int zone, bool north);
  // lon0 in [-180, 180], lat0 in [-90, 90]; throws std::invalid_argument otherwise.
  static Projection local_transverse_mercator(double lon0, double lat0);

  // Chooses a projection for lon/lat data (which must not be empty): the zone or centre comes from the data's
  // centre (longitudes averaged on the circle, so data across the antimeridian is centred correctly), and
  // every point is checked to be within the projection's range. `file` names the data in errors
  // (shoremesh::InputError).
  static Projection choose(const std::vector<LonLat>& data, ProjectionChoice choice, const std::string& file = {});

  Kind kind() const { return kind_; }
  bool is_none() const { return kind_ == Kind::None; }
  int zone() const { return zone_; }  // UtmUps only (0 = UPS)
  bool north() const { return north_; }
  double lon0() const { return lon0_; }  // central meridian (UTM and local TM)
  double lat0() const { return lat0_; }  // origin latitude (local TM)

  // lon/lat (degrees) -> x/y (metres). Throws std::domain_error when the point is outside the projection's
  // range (more than 3,900 km from the central meridian, the wrong pole for UPS, or a non-finite value).
  Point2 forward(const LonLat& ll) const;
  // x/y (metres) -> lon/lat (degrees; lon in [-180, 180]).
  LonLat reverse(const Point2& xy) const;
  // Point scale factor k at a point (ratio of projected to true distance, 1 on the central meridian of the
  // local transverse Mercator, 0.9996 there for UTM).
  double scale(const LonLat& ll) const;

  // "none", "UTM zone 16N (WGS84)", "UPS north (WGS84)", "local transverse Mercator at 45.76N 14.33E (WGS84)".
  std::string describe() const;
  // OGC WKT 1 of the projected coordinate system (for .prj files next to exports); empty for None.
  std::string wkt() const;
  // PROJ string, e.g. "+proj=utm +zone=16 +datum=WGS84 +units=m +no_defs"; empty for None.
  std::string proj4() const;

  friend bool operator==(const Projection& a, const Projection& b) {
    return a.kind_ == b.kind_ && a.zone_ == b.zone_ && a.north_ == b.north_ && a.lon0_ == b.lon0_ && a.lat0_ == b.lat0_;
  }

 private:
  Kind kind_ = Kind::None;
  int zone_ = 0;
  bool north_ = true;
  double lon0_ = 0;
  double lat0_ = 0;
  double y0_ = 0;  // local TM: northing of (lon0, lat0) on the central meridian, subtracted
};

}  // namespace shoremesh::io
