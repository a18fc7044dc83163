#include "user_frame.hpp"

#include <cmath>
#include <cstdio>

#include "shoremesh/io/point_set_csv.hpp"

namespace shoremesh::tool {

std::string exact(double x) { return io::format_double(x); }

std::string approx(double x, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

std::string UserFrame::unit_suffix() const {
  switch (units) {
    case io::Units::Metres: return "m";
    case io::Units::Pixels: return "px";
    case io::Units::MapUnits: return "";
  }
  return "";
}

std::string UserFrame::length(double d) const {
  const std::string s = unit_suffix();
  return approx(d) + (s.empty() ? " map units" : " " + s);
}

namespace {
std::string degrees(double v, char positive, char negative) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.5f%c", std::fabs(v), v < 0 ? negative : positive);
  return buffer;
}
}  // namespace

std::string UserFrame::point(const Point2& p) const {
  // Appended, not "(" + std::string: GCC 12 warns falsely on that (-Wrestrict).
  std::string out = "(";
  out.append(approx(p[0], 9)).append(", ").append(approx(p[1], 9)).append(")");
  const std::string s = unit_suffix();
  if (!s.empty()) out += " " + s;
  if (!projection.is_none()) {
    const io::LonLat ll = projection.reverse(p);
    // Far outside the projection's range the inverse has no answer (NaN): say nothing rather than "nanN".
    if (std::isfinite(ll.lat) && std::isfinite(ll.lon))
      out += " = " + degrees(ll.lat, 'N', 'S') + " " + degrees(ll.lon, 'E', 'W');
  }
  return out;
}

std::string UserFrame::point(const Point3& p) const {
  std::string out = "(";
  out.append(approx(p[0], 9)).append(", ").append(approx(p[1], 9)).append(", ").append(approx(p[2], 9)).append(")");
  const std::string s = unit_suffix();
  if (!s.empty()) out += " " + s;
  return out;
}

}  // namespace shoremesh::tool
