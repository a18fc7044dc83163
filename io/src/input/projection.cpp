#include "shoremesh/io/projection.hpp"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Math.hpp>
#include <GeographicLib/PolarStereographic.hpp>
#include <GeographicLib/TransverseMercator.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "shoremesh/error.hpp"

namespace shoremesh::io {

namespace {

constexpr double kMaxDistanceFromCentralMeridian = 3.9e6;  // metres: Krüger series accuracy limit (5 nm)
constexpr double kUtmFalseEasting = 500000, kUtmFalseNorthingSouth = 10000000, kUpsFalse = 2000000;

const GeographicLib::TransverseMercator& local_tm() {
  static const GeographicLib::TransverseMercator tm(GeographicLib::Constants::WGS84_a(),
                                                    GeographicLib::Constants::WGS84_f(), 1.0);
  return tm;
}

std::string fmt(const char* f, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, a);
  return buf;
}

const char* kGeogcs =
    "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563,AUTHORITY[\"EPSG\",\"7030\"]],"
    "AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],"
    "UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],AUTHORITY[\"EPSG\",\"4326\"]]";

}  // namespace

Projection Projection::utm_ups(int zone, bool north) {
  if (zone < 0 || zone > 60) throw std::invalid_argument("UTM zone must be 1..60 (0 for UPS), got " + std::to_string(zone));
  Projection p;
  p.kind_ = Kind::UtmUps;
  p.zone_ = zone;
  p.north_ = north;
  p.lon0_ = zone == 0 ? 0.0 : 6.0 * zone - 183.0;
  return p;
}

Projection Projection::local_transverse_mercator(double lon0, double lat0) {
  if (!(lon0 >= -180 && lon0 <= 180) || !(lat0 >= -90 && lat0 <= 90))
    throw std::invalid_argument("local transverse Mercator centre out of range");
  Projection p;
  p.kind_ = Kind::LocalTransverseMercator;
  p.lon0_ = lon0;
  p.lat0_ = lat0;
  p.north_ = lat0 >= 0;
  double x = 0, y = 0;
  local_tm().Forward(lon0, lat0, lon0, x, y);
  p.y0_ = y;
  return p;
}

Point2 Projection::forward(const LonLat& ll) const {
  if (kind_ == Kind::None) throw std::domain_error("no projection: coordinates are not lon/lat");
  if (!std::isfinite(ll.lon) || !std::isfinite(ll.lat) || std::abs(ll.lat) > 90)
    throw std::domain_error("not a valid lon/lat: " + fmt("%.9g", ll.lon) + ", " + fmt("%.9g", ll.lat));
  double x = 0, y = 0;
  if (kind_ == Kind::UtmUps && zone_ == 0) {
    if ((north_ && ll.lat < 0) || (!north_ && ll.lat > 0))
      throw std::domain_error(std::string("latitude ") + fmt("%.6f", ll.lat) + " is on the wrong side of the equator for UPS " +
                              (north_ ? "north" : "south"));
    double gamma, k;
    GeographicLib::PolarStereographic::UPS().Forward(north_, ll.lat, ll.lon, x, y, gamma, k);
    return {x + kUpsFalse, y + kUpsFalse};
  }
  const auto& tm = kind_ == Kind::UtmUps ? GeographicLib::TransverseMercator::UTM() : local_tm();
  tm.Forward(lon0_, ll.lat, ll.lon, x, y);
  if (!(std::abs(x) <= kMaxDistanceFromCentralMeridian))
    throw std::domain_error("lon/lat " + fmt("%.6f", ll.lon) + ", " + fmt("%.6f", ll.lat) + " is " +
                            fmt("%.0f", std::abs(x) / 1000) + " km from the central meridian " + fmt("%.6g", lon0_) +
                            " of " + describe() + " (the limit is 3900 km)");
  if (kind_ == Kind::UtmUps) return {x + kUtmFalseEasting, y + (north_ ? 0.0 : kUtmFalseNorthingSouth)};
  return {x, y - y0_};
}

LonLat Projection::reverse(const Point2& xy) const {
  if (kind_ == Kind::None) throw std::domain_error("no projection: coordinates are not lon/lat");
  LonLat out;
  if (kind_ == Kind::UtmUps && zone_ == 0) {
    double gamma, k;
    GeographicLib::PolarStereographic::UPS().Reverse(north_, xy[0] - kUpsFalse, xy[1] - kUpsFalse, out.lat, out.lon,
                                                     gamma, k);
    return out;
  }
  if (kind_ == Kind::UtmUps) {
    GeographicLib::TransverseMercator::UTM().Reverse(lon0_, xy[0] - kUtmFalseEasting,
                                                     xy[1] - (north_ ? 0.0 : kUtmFalseNorthingSouth), out.lat, out.lon);
  } else {
    local_tm().Reverse(lon0_, xy[0], xy[1] + y0_, out.lat, out.lon);
  }
  return out;
}

double Projection::scale(const LonLat& ll) const {
  if (kind_ == Kind::None) return 1.0;
  double x, y, gamma, k;
  if (kind_ == Kind::UtmUps && zone_ == 0)
    GeographicLib::PolarStereographic::UPS().Forward(north_, ll.lat, ll.lon, x, y, gamma, k);
  else
    (kind_ == Kind::UtmUps ? GeographicLib::TransverseMercator::UTM() : local_tm()).Forward(lon0_, ll.lat, ll.lon, x, y, gamma, k);
  return k;
}

std::string Projection::describe() const {
  switch (kind_) {
    case Kind::None: return "none";
    case Kind::UtmUps:
      if (zone_ == 0) return std::string("UPS ") + (north_ ? "north" : "south") + " (WGS84)";
      return "UTM zone " + std::to_string(zone_) + (north_ ? "N" : "S") + " (WGS84)";
    case Kind::LocalTransverseMercator:
      return "local transverse Mercator at " + fmt("%.6f", std::abs(lat0_)) + (lat0_ >= 0 ? "N " : "S ") +
             fmt("%.6f", std::abs(lon0_)) + (lon0_ >= 0 ? "E" : "W") + " (WGS84)";
  }
  return "none";
}

std::string Projection::proj4() const {
  switch (kind_) {
    case Kind::None: return {};
    case Kind::UtmUps:
      if (zone_ == 0) return std::string("+proj=ups ") + (north_ ? "" : "+south ") + "+datum=WGS84 +units=m +no_defs";
      return "+proj=utm +zone=" + std::to_string(zone_) + (north_ ? "" : " +south") + " +datum=WGS84 +units=m +no_defs";
    case Kind::LocalTransverseMercator:
      return "+proj=tmerc +lat_0=" + fmt("%.12g", lat0_) + " +lon_0=" + fmt("%.12g", lon0_) +
             " +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs";
  }
  return {};
}

std::string Projection::wkt() const {
  auto param = [](const char* name, double v) { return std::string(",PARAMETER[\"") + name + "\"," + fmt("%.12g", v) + "]"; };
  std::string name, proj, params, authority;
  switch (kind_) {
    case Kind::None: return {};
    case Kind::UtmUps:
      if (zone_ == 0) {
        name = std::string("WGS 84 / UPS ") + (north_ ? "North (E,N)" : "South (E,N)");
        proj = "Polar_Stereographic";
        params = param("latitude_of_origin", north_ ? 90 : -90) + param("central_meridian", 0) +
                 param("scale_factor", 0.994) + param("false_easting", kUpsFalse) + param("false_northing", kUpsFalse);
        authority = north_ ? "32661" : "32761";
      } else {
        name = "WGS 84 / UTM zone " + std::to_string(zone_) + (north_ ? "N" : "S");
        proj = "Transverse_Mercator";
        params = param("latitude_of_origin", 0) + param("central_meridian", lon0_) + param("scale_factor", 0.9996) +
                 param("false_easting", kUtmFalseEasting) + param("false_northing", north_ ? 0 : kUtmFalseNorthingSouth);
        authority = std::to_string((north_ ? 32600 : 32700) + zone_);
      }
      break;
    case Kind::LocalTransverseMercator:
      name = "WGS 84 / local transverse Mercator";
      proj = "Transverse_Mercator";
      params = param("latitude_of_origin", lat0_) + param("central_meridian", lon0_) + param("scale_factor", 1) +
               param("false_easting", 0) + param("false_northing", 0);
      break;
  }
  std::string w = "PROJCS[\"" + name + "\"," + kGeogcs + ",PROJECTION[\"" + proj + "\"]" + params +
                  ",UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AXIS[\"Easting\",EAST],AXIS[\"Northing\",NORTH]";
  if (!authority.empty()) w += ",AUTHORITY[\"EPSG\",\"" + authority + "\"]";
  return w + "]";
}

Projection Projection::choose(const std::vector<LonLat>& data, ProjectionChoice choice, const std::string& file) {
  if (data.empty()) throw InputError("no points to choose a projection from", file);
  // Centre: mean of the unit vectors (robust across the antimeridian and over a pole).
  double sx = 0, sy = 0, sz = 0;
  for (const auto& p : data) {
    if (!std::isfinite(p.lon) || !std::isfinite(p.lat) || std::abs(p.lat) > 90 || std::abs(p.lon) > 540)
      throw InputError("not a valid lon/lat: " + fmt("%.9g", p.lon) + ", " + fmt("%.9g", p.lat), file);
    const double phi = p.lat * GeographicLib::Math::degree(), lam = p.lon * GeographicLib::Math::degree();
    sx += std::cos(phi) * std::cos(lam);
    sy += std::cos(phi) * std::sin(lam);
    sz += std::sin(phi);
  }
  const double norm = std::sqrt(sx * sx + sy * sy + sz * sz) / static_cast<double>(data.size());
  if (norm < 0.5)
    throw InputError("the lon/lat data is spread over too much of the globe for one map projection", file);
  const double lat_c = std::atan2(sz, std::hypot(sx, sy)) / GeographicLib::Math::degree();
  // Exactly at a pole the longitude of the centre is arbitrary: use 0.
  const double lon_c = std::hypot(sx, sy) < 1e-12 * std::abs(sz) ? 0.0 : std::atan2(sy, sx) / GeographicLib::Math::degree();
  Projection proj;
  if (choice == ProjectionChoice::Utm) {
    const int zone = GeographicLib::UTMUPS::StandardZone(lat_c, lon_c);
    proj = utm_ups(zone, lat_c >= 0);
  } else {
    proj = local_transverse_mercator(lon_c, lat_c);
  }
  for (std::size_t i = 0; i < data.size(); ++i) {
    try {
      (void)proj.forward(data[i]);
    } catch (const std::domain_error& e) {
      throw InputError(std::string(e.what()) + " (point " + std::to_string(i + 1) +
                           "); the data does not fit one projection" +
                           (choice == ProjectionChoice::Utm ? ": try a local transverse Mercator projection" : ""),
                       file);
    }
  }
  return proj;
}

}  // namespace shoremesh::io
