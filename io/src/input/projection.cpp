#include "shoremesh/io/projection.hpp"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Math.hpp>
#include <GeographicLib/PolarStereographic.hpp>
#include <GeographicLib/TransverseMercator.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <proj.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>

#include "../raster/raster_module.hpp"
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

namespace detail {

// PROJ's transformations between WGS 84 lon/lat and a projected system (through OGR, in the raster module).
// They are not safe to share between threads: one lock.
struct CrsProjection {
  std::string wkt, name;
  CrsTransforms transforms;
  mutable std::mutex mutex;
};

}  // namespace detail

const std::string& Projection::crs_wkt() const {
  static const std::string empty;
  return crs_ ? crs_->wkt : empty;
}

Projection Projection::crs(const std::string& wkt, const std::string& name, const std::string& file) {
  auto c = std::make_shared<detail::CrsProjection>();
  c->wkt = wkt;
  c->name = name;
  c->transforms = detail::crs_transforms(wkt, name, file);
  Projection p;
  p.kind_ = Kind::Crs;
  p.crs_ = std::move(c);
  return p;
}

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
  if (kind_ == Kind::Crs) {
    x = ll.lon, y = ll.lat;
    std::lock_guard lock(crs_->mutex);
    if (!crs_->transforms.forward->transform(x, y) || !std::isfinite(x) || !std::isfinite(y))
      throw std::domain_error("PROJ cannot take lon/lat " + fmt("%.6f", ll.lon) + ", " + fmt("%.6f", ll.lat) + " to " +
                              crs_->name);
    return {x, y};
  }
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
  if (kind_ == Kind::Crs) {
    double x = xy[0], y = xy[1];
    std::lock_guard lock(crs_->mutex);
    if (!crs_->transforms.reverse->transform(x, y)) x = y = std::nan("");  // as GeographicLib: no answer is NaN
    return {x, y};
  }
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
  if (kind_ == Kind::Crs) return measure_scale(*this, {ll}).max;
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
    case Kind::Crs: return crs_->name;
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
    case Kind::Crs: return crs_->transforms.proj4;
  }
  return {};
}

std::string Projection::wkt() const {
  auto param = [](const char* name, double v) { return std::string(",PARAMETER[\"") + name + "\"," + fmt("%.12g", v) + "]"; };
  std::string name, proj, params, authority;
  switch (kind_) {
    case Kind::None: return {};
    case Kind::Crs: return detail::crs_wkt1(crs_->wkt);  // WKT 1: ESRI's .prj readers know no WKT 2
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
  // Centre: mean of the unit vectors (robust across the antimeridian and over a pole). Each point's vector
  // on every thread, summed in the data's order; the error is the first invalid point's.
  std::vector<std::array<double, 3>> unit(data.size());
  std::atomic<std::size_t> first_invalid{data.size()};
  auto lower_to = [](std::atomic<std::size_t>& first, std::size_t i) {
    std::size_t seen = first.load();
    while (i < seen && !first.compare_exchange_weak(seen, i)) {
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, data.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const LonLat& p = data[i];
      if (!std::isfinite(p.lon) || !std::isfinite(p.lat) || std::abs(p.lat) > 90 || std::abs(p.lon) > 540) {
        lower_to(first_invalid, i);
        return;
      }
      const double phi = p.lat * GeographicLib::Math::degree(), lam = p.lon * GeographicLib::Math::degree();
      unit[i] = {std::cos(phi) * std::cos(lam), std::cos(phi) * std::sin(lam), std::sin(phi)};
    }
  });
  if (const std::size_t i = first_invalid.load(); i < data.size())
    throw InputError("not a valid lon/lat: " + fmt("%.9g", data[i].lon) + ", " + fmt("%.9g", data[i].lat), file);
  double sx = 0, sy = 0, sz = 0;
  for (const auto& u : unit) {
    sx += u[0];
    sy += u[1];
    sz += u[2];
  }
  unit = {};
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
  // Every point projects (on every thread; the error is the first failing point's, as in order).
  std::atomic<std::size_t> first_failing{data.size()};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, data.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      try {
        (void)proj.forward(data[i]);
      } catch (const std::domain_error&) {
        lower_to(first_failing, i);
        return;
      }
    }
  });
  if (const std::size_t i = first_failing.load(); i < data.size()) {
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

std::string ScaleRange::describe() const { return "scale " + fmt("%.5f", min) + " .. " + fmt("%.5f", max); }

ScaleRange measure_scale(const Projection& projection, const std::vector<LonLat>& samples) {
  ScaleRange r;
  if (projection.is_none() || samples.empty()) return r;
  // The projection as a PROJ string: an operation from lon/lat radians that proj_factors differentiates
  // directly (lon/lat of the system's own datum: within metres of WGS 84's, the same scale). A projected
  // CRS object would do too, but PROJ then builds its operation at every call (20 ms each).
  std::string text = projection.proj4();
  if (text.empty()) text = projection.wkt();
  PJ_CONTEXT* ctx = proj_context_create();
  PJ* pj = proj_create(ctx, text.c_str());
  if (!pj) {
    proj_context_destroy(ctx);
    throw std::runtime_error("PROJ cannot read the projection " + projection.describe());
  }
  bool any = false;
  r = {1e300, -1e300};
  for (const LonLat& ll : samples) {
    if (projection.kind() != Projection::Kind::Crs) {
      try {
        (void)projection.forward(ll);  // outside the projection's range: no scale to speak of
      } catch (const std::domain_error&) {
        continue;
      }
    }
    proj_errno_reset(pj);
    const PJ_FACTORS f = proj_factors(pj, proj_coord(proj_torad(ll.lon), proj_torad(ll.lat), 0, 0));
    if (proj_errno(pj) != 0 || !(f.tissot_semimajor > 0) || !std::isfinite(f.tissot_semimajor)) continue;
    r.min = std::min(r.min, f.tissot_semiminor);
    r.max = std::max(r.max, f.tissot_semimajor);
    any = true;
  }
  proj_destroy(pj);
  proj_context_destroy(ctx);
  if (!any) return ScaleRange{};
  return r;
}

std::vector<LonLat> extent_samples(const std::vector<LonLat>& data) {
  std::vector<LonLat> out;
  if (data.empty()) return out;
  double sx = 0, sy = 0;
  for (const auto& p : data) {
    sx += std::cos(p.lon * GeographicLib::Math::degree());
    sy += std::sin(p.lon * GeographicLib::Math::degree());
  }
  const double lon_c = std::atan2(sy, sx) / GeographicLib::Math::degree();
  double lo = 1e300, hi = -1e300, south = 90, north = -90;
  for (const auto& p : data) {
    const double d = std::remainder(p.lon - lon_c, 360.0);
    lo = std::min(lo, d), hi = std::max(hi, d);
    south = std::min(south, p.lat), north = std::max(north, p.lat);
  }
  constexpr int kSteps = 16;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; j <= kSteps; ++j) {
      const double lon = std::remainder(lon_c + lo + (hi - lo) * i / kSteps, 360.0);
      out.push_back({lon, south + (north - south) * j / kSteps});
    }
  return out;
}

ChosenProjection choose_projection(const std::optional<Projection>& source, const std::vector<LonLat>& data,
                                   ProjectionChoice choice, const std::string& file) {
  ChosenProjection out;
  const std::vector<LonLat> samples = extent_samples(data);
  if (source && !source->is_none()) {
    const ScaleRange s = measure_scale(*source, samples);
    if (s.within()) {
      out.projection = *source;
      out.note = "meshed in " + source->describe() + ": its " + s.describe() +
                 " over the data stays within 0.1 % of 1";
      return out;
    }
    out.projection = Projection::choose(data, choice, file);
    out.note = "reprojected from " + source->describe() + " (" + s.describe() +
               " over the data, beyond 0.1 % of 1) to " + out.projection.describe() + ", " +
               measure_scale(out.projection, samples).describe();
    return out;
  }
  out.projection = Projection::choose(data, choice, file);
  out.note = "projected lon/lat to metres with " + out.projection.describe() + ", " +
             measure_scale(out.projection, samples).describe() + " over the data";
  return out;
}

ChosenProjection lonlat_projection(const std::optional<Projection>& fixed, const std::vector<LonLat>& data,
                                   ProjectionChoice choice, const std::string& file) {
  if (!fixed || fixed->is_none()) return choose_projection(std::nullopt, data, choice, file);
  return {*fixed, "projected lon/lat to metres with " + fixed->describe()};
}

}  // namespace shoremesh::io
