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
//   Crs                       another projected coordinate system (a national grid, ...), kept because its
//                             scale stays near 1 over the data (the projection rule below); through PROJ.
// Both transverse Mercator kinds use GeographicLib's Krüger series (TransverseMercator), accurate to 5 nm
// within 3,900 km of the central meridian; points farther than that are refused with a clear error.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh::io {

struct LonLat {
  double lon = 0;  // degrees east
  double lat = 0;  // degrees north
};

// How to choose a projection for lon/lat data (and for projected data the rule does not keep).
enum class ProjectionChoice {
  Utm,                      // the UTM zone of the data's centre (UPS beyond 84N / 80S)
  LocalTransverseMercator,  // transverse Mercator centred on the data (the default)
};

namespace detail {
struct CrsProjection;  // PROJ's transformations for Projection::Kind::Crs
}

class Projection {
 public:
  enum class Kind { None, UtmUps, LocalTransverseMercator, Crs };

  Projection() = default;  // Kind::None
  // zone 1..60 for UTM, 0 for UPS; throws std::invalid_argument on a bad zone.
  static Projection utm_ups(int zone, bool north);
  // lon0 in [-180, 180], lat0 in [-90, 90]; throws std::invalid_argument otherwise.
  static Projection local_transverse_mercator(double lon0, double lat0);
  // A projected coordinate system as WKT (any PROJ reads); `name` for messages. Throws shoremesh::InputError
  // naming `file` when PROJ cannot transform between it and WGS 84 lon/lat.
  static Projection crs(const std::string& wkt, const std::string& name, const std::string& file = {});

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
  // local transverse Mercator, 0.9996 there for UTM; for Crs the largest over all directions).
  double scale(const LonLat& ll) const;

  // "none", "UTM zone 16N (WGS84)", "UPS north (WGS84)", "local transverse Mercator at 45.76N 14.33E (WGS84)",
  // or PROJ's name of a Crs ("OSGB36 / British National Grid").
  std::string describe() const;
  // OGC WKT 1 of the projected coordinate system (for .prj files next to exports); empty for None.
  std::string wkt() const;
  // PROJ string, e.g. "+proj=utm +zone=16 +datum=WGS84 +units=m +no_defs"; empty for None.
  std::string proj4() const;

  friend bool operator==(const Projection& a, const Projection& b) {
    return a.kind_ == b.kind_ && a.zone_ == b.zone_ && a.north_ == b.north_ && a.lon0_ == b.lon0_ &&
           a.lat0_ == b.lat0_ && a.crs_wkt() == b.crs_wkt();
  }

 private:
  Kind kind_ = Kind::None;
  int zone_ = 0;
  bool north_ = true;
  double lon0_ = 0;
  double lat0_ = 0;
  double y0_ = 0;  // local TM: northing of (lon0, lat0) on the central meridian, subtracted
  std::shared_ptr<const detail::CrsProjection> crs_;  // Kind::Crs
  const std::string& crs_wkt() const;                 // empty unless Kind::Crs
};

// The projection rule. A projected coordinate system is a faithful frame for meshing only where its point
// scale factor stays within 0.1 % of 1 (UTM inside its zone, most national grids): sizes, areas and
// --spacing are then true metres to that tolerance. Elsewhere (Web Mercator, whose scale at 49 N is 1.52;
// UTM across zones) and for lon/lat, the data goes to the projection `choice` names (a transverse Mercator
// centred on the data unless the user asks for UTM).
constexpr double kScaleTolerance = 1e-3;

// The extremes of a projection's point scale factor over lon/lat samples, measured by PROJ (proj_factors:
// the Tissot indicatrix's semi-axes, so the extremes over all directions). Samples outside the projection's
// range are skipped.
struct ScaleRange {
  double min = 1, max = 1;
  bool within(double tolerance = kScaleTolerance) const { return min >= 1 - tolerance && max <= 1 + tolerance; }
  std::string describe() const;  // "scale 0.99960 .. 1.00181"
};
ScaleRange measure_scale(const Projection& projection, const std::vector<LonLat>& samples);

// Samples of the data's extent: a 17 x 17 grid over its lon/lat box (corners and edges included; longitudes
// taken around the data's centre, so a box across the antimeridian is the short one).
std::vector<LonLat> extent_samples(const std::vector<LonLat>& data);

struct ChosenProjection {
  Projection projection;
  std::string note;  // for the summary: which projection, kept or reprojected and why, its scale over the data
};
// The projection rule for data given in `source` (a projected system; nullopt for lon/lat) whose lon/lat
// extent is `data`: `source` itself when its scale stays within kScaleTolerance over the extent, otherwise
// Projection::choose(data, choice). InputError naming `file` as for choose().
ChosenProjection choose_projection(const std::optional<Projection>& source, const std::vector<LonLat>& data,
                                   ProjectionChoice choice, const std::string& file = {});
// For lon/lat data: `fixed` when given and not None (the projection an earlier input fixed for all),
// otherwise choose_projection(nullopt, data, choice, file).
ChosenProjection lonlat_projection(const std::optional<Projection>& fixed, const std::vector<LonLat>& data,
                                   ProjectionChoice choice, const std::string& file = {});

}  // namespace shoremesh::io
