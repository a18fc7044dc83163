#include "shoremesh/io/gps_track.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "input_builder.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/domain.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

std::size_t GpsData::point_count() const {
  std::size_t n = 0;
  for (const auto& s : sequences) n += s.points.size();
  return n;
}

namespace {

using detail::NumberStatus;

// Maps byte offsets of a text to 1-based line numbers.
class LineIndex {
 public:
  explicit LineIndex(std::string_view text) {
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') newlines_.push_back(i);
  }
  std::size_t line(std::ptrdiff_t offset) const {
    if (offset < 0) return 0;
    return static_cast<std::size_t>(std::upper_bound(newlines_.begin(), newlines_.end(), static_cast<std::size_t>(offset)) -
                                    newlines_.begin()) + 1;
  }

 private:
  std::vector<std::size_t> newlines_;
};

std::string_view local_name(const char* qualified) {
  std::string_view n(qualified);
  const auto colon = n.find(':');
  return colon == std::string_view::npos ? n : n.substr(colon + 1);
}

pugi::xml_node child_local(pugi::xml_node node, std::string_view name) {
  for (auto c : node.children())
    if (c.type() == pugi::node_element && local_name(c.name()) == name) return c;
  return {};
}

pugi::xml_attribute attribute_local(pugi::xml_node node, std::string_view name) {
  for (auto a : node.attributes())
    if (local_name(a.name()) == name) return a;
  return {};
}

struct GpxReader {
  const std::string& file;
  LineIndex lines;

  std::size_t line_of(pugi::xml_node n) const { return lines.line(n.offset_debug()); }

  double coordinate(pugi::xml_node pt, const char* attr, double limit) const {
    const auto a = attribute_local(pt, attr);
    if (!a) throw InputError("<" + std::string(local_name(pt.name())) + "> without a " + attr + " attribute", file, line_of(pt));
    double v = 0;
    const auto st = detail::parse_double(detail::trim(a.value()), v);
    if (st == NumberStatus::NotANumber)
      throw InputError(std::string(attr) + "=" + detail::quoted(a.value()) + " is not a number", file, line_of(pt));
    if (st == NumberStatus::NotFinite)
      throw InputError(std::string(attr) + "=" + detail::quoted(a.value()) + " is not a finite number", file, line_of(pt));
    if (std::abs(v) > limit)
      throw InputError(std::string(attr) + " " + a.value() + " is out of range [-" + std::to_string(int(limit)) + ", " +
                           std::to_string(int(limit)) + "]",
                       file, line_of(pt));
    return v;
  }

  GeoPoint point(pugi::xml_node pt) const {
    GeoPoint g;
    g.lat = coordinate(pt, "lat", 90);
    g.lon = coordinate(pt, "lon", 180);
    g.line = line_of(pt);
    if (auto ele = child_local(pt, "ele")) {
      double v = 0;
      const auto text = detail::trim(ele.child_value());
      const auto st = detail::parse_double(text, v);
      if (st != NumberStatus::Ok)
        throw InputError("<ele> " + detail::quoted(text) + " is not a " + (st == NumberStatus::NotFinite ? "finite " : "") +
                             "number",
                         file, line_of(ele));
      g.ele = v;
    }
    return g;
  }

  GpsSequence sequence(pugi::xml_node parent, std::string_view point_name, GpsSequence::Kind kind) const {
    GpsSequence s;
    s.kind = kind;
    s.line = line_of(parent);
    for (auto c : parent.children())
      if (c.type() == pugi::node_element && local_name(c.name()) == point_name) s.points.push_back(point(c));
    return s;
  }
};

}  // namespace

GpsData parse_gpx_text(std::string_view text, const std::string& name) {
  pugi::xml_document doc;
  const auto result = doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_auto);
  GpxReader reader{name, LineIndex(text)};
  if (!result) {
    std::string what = std::string("malformed XML: ") + result.description();
    if (result.status == pugi::status_end_element_mismatch || result.status == pugi::status_bad_end_element ||
        static_cast<std::size_t>(result.offset) >= text.size())
      what += " (truncated or mismatched tags?)";
    throw InputError(what, name, reader.lines.line(result.offset));
  }
  const auto root = doc.document_element();
  if (!root) throw InputError("empty file: no GPX document", name);
  if (local_name(root.name()) != "gpx")
    throw InputError(std::string("not a GPX file: the root element is <") + root.name() + ">", name, reader.line_of(root));
  GpsData data;
  data.version = attribute_local(root, "version").value();
  if (data.version != "1.0" && data.version != "1.1")
    throw InputError("unsupported GPX version " + detail::quoted(data.version) + " (1.0 and 1.1 are read)", name,
                     reader.line_of(root));
  GpsSequence waypoints;
  waypoints.kind = GpsSequence::Kind::Waypoints;
  for (auto c : root.children()) {
    if (c.type() != pugi::node_element) continue;
    const auto tag = local_name(c.name());
    if (tag == "wpt") {
      if (waypoints.points.empty()) waypoints.line = reader.line_of(c);
      waypoints.points.push_back(reader.point(c));
    } else if (tag == "rte") {
      auto s = reader.sequence(c, "rtept", GpsSequence::Kind::Route);
      s.name = child_local(c, "name").child_value();
      if (!s.points.empty()) data.sequences.push_back(std::move(s));
    } else if (tag == "trk") {
      const std::string trk_name = child_local(c, "name").child_value();
      for (auto seg : c.children()) {
        if (seg.type() != pugi::node_element || local_name(seg.name()) != "trkseg") continue;
        auto s = reader.sequence(seg, "trkpt", GpsSequence::Kind::TrackSegment);
        s.name = trk_name;
        if (!s.points.empty()) data.sequences.push_back(std::move(s));
      }
    }
  }
  if (!waypoints.points.empty()) data.sequences.push_back(std::move(waypoints));
  if (data.sequences.empty()) throw InputError("no points: the GPX file has no track, route or waypoint points", name);
  return data;
}

GpsData read_gpx(const std::string& path) { return parse_gpx_text(detail::read_text_file(path), path); }

namespace {

std::string lower_unquoted(std::string_view s) {
  s = detail::trim(s);
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) s = s.substr(1, s.size() - 2);
  std::string out(s);
  for (auto& ch : out) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

struct CsvColumns {
  int lat = -1, lon = -1, ele = -1;
  std::size_t count = 0;
};

CsvColumns find_columns(const std::vector<std::string_view>& header) {
  CsvColumns c;
  c.count = header.size();
  for (std::size_t i = 0; i < header.size(); ++i) {
    const auto h = lower_unquoted(header[i]);
    const int idx = static_cast<int>(i);
    if ((h == "lat" || h == "latitude") && c.lat < 0) c.lat = idx;
    if ((h == "lon" || h == "lng" || h == "long" || h == "longitude") && c.lon < 0) c.lon = idx;
    if ((h == "ele" || h == "elevation" || h == "alt" || h == "altitude" || h == "height") && c.ele < 0) c.ele = idx;
  }
  return c;
}

// The first non-comment, non-blank line and its number.
std::pair<std::string_view, std::size_t> first_record(std::string_view text) {
  std::pair<std::string_view, std::size_t> out{{}, 0};
  detail::for_each_line(text, [&](std::string_view raw, std::size_t line) {
    if (out.second) return;
    const auto body = detail::strip_comment(raw);
    if (!body.empty()) out = {body, line};
  });
  return out;
}

}  // namespace

bool csv_header_has_lat_lon(std::string_view text) {
  const auto [header, line] = first_record(text);
  if (!line) return false;
  const auto c = find_columns(detail::split_fields(header));
  return c.lat >= 0 && c.lon >= 0;
}

GpsData parse_track_csv_text(std::string_view text, const std::string& name) {
  const auto first = first_record(text);  // not a structured binding: lambdas below capture it (clang 14)
  const std::string_view header = first.first;
  const std::size_t header_line = first.second;
  if (!header_line) throw InputError("no points: empty file", name);
  const auto cols = find_columns(detail::split_fields(header));
  if (cols.lat < 0 || cols.lon < 0)
    throw InputError("no lat/lon columns in the header (expected names like lat, latitude, lon, lng, longitude)", name,
                     header_line);
  GpsData data;
  data.version = "csv";
  GpsSequence seq;
  seq.kind = GpsSequence::Kind::TrackSegment;
  seq.line = header_line;
  detail::for_each_line(text, [&](std::string_view raw, std::size_t line) {
    if (line <= header_line) return;
    const auto body = detail::strip_comment(raw);
    if (body.empty()) return;
    const auto fields = detail::split_fields(body);
    if (fields.size() != cols.count)
      throw InputError("expected " + std::to_string(cols.count) + " columns as in the header, found " +
                           std::to_string(fields.size()),
                       name, line);
    auto number = [&](int col, const char* what, double limit) {
      double v = 0;
      const auto f = fields[static_cast<std::size_t>(col)];
      const auto st = detail::parse_double(f, v);
      if (st == NumberStatus::NotANumber)
        throw InputError(std::string(what) + " column: " + detail::quoted(f) + " is not a number", name, line);
      if (st == NumberStatus::NotFinite)
        throw InputError(std::string(what) + " column: " + detail::quoted(f) + " is not a finite number", name, line);
      if (std::abs(v) > limit)
        throw InputError(std::string(what) + " " + std::string(f) + " is out of range", name, line);
      return v;
    };
    GeoPoint g;
    g.lat = number(cols.lat, "lat", 90);
    g.lon = number(cols.lon, "lon", 180);
    if (cols.ele >= 0 && !fields[static_cast<std::size_t>(cols.ele)].empty()) g.ele = number(cols.ele, "elevation", 1e7);
    g.line = line;
    seq.points.push_back(g);
  });
  if (seq.points.empty()) throw InputError("no points", name);
  data.sequences.push_back(std::move(seq));
  return data;
}

GpsData read_track_csv(const std::string& path) { return parse_track_csv_text(detail::read_text_file(path), path); }

namespace {

double dist(const Point2& a, const Point2& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }

struct Projected {
  std::vector<Point2> xy;
  std::vector<std::size_t> lines;
};

// Moving average of 2w+1 points; cyclic for closed walks, endpoints kept for open tracks.
void smooth(Projected& p, int w, bool closed) {
  const std::size_t n = p.xy.size();
  if (w <= 0 || n < 3) return;
  std::vector<Point2> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    double sx = 0, sy = 0;
    int count = 0;
    for (int d = -w; d <= w; ++d) {
      long long j = static_cast<long long>(i) + d;
      if (closed) {
        j = ((j % static_cast<long long>(n)) + static_cast<long long>(n)) % static_cast<long long>(n);
      } else if (j < 0 || j >= static_cast<long long>(n)) {
        continue;
      }
      sx += p.xy[static_cast<std::size_t>(j)][0];
      sy += p.xy[static_cast<std::size_t>(j)][1];
      ++count;
    }
    out[i] = {sx / count, sy / count};
  }
  if (!closed) {
    out.front() = p.xy.front();
    out.back() = p.xy.back();
  }
  p.xy = std::move(out);
}

// Thins a walk to the spacing. From each kept fix it keeps the last fix of the run that follows within
// `spacing` of it: a log holds a fix every metre or second, and their jitter would be features the mesh
// must resolve, while keeping the farthest fix within reach leaves the kept ones about `spacing` apart,
// not less (the caller then cuts the gaps that are longer, so that no piece exceeds the spacing). A
// spacing of 0 keeps every fix but exact repeats. Closed: fixes at the end nearer the first than half
// the spacing go, so that the closing edge is not a sliver.
Projected resample(const Projected& p, double spacing, bool closed) {
  Projected out;
  auto keep = [&](std::size_t i) {
    out.xy.push_back(p.xy[i]);
    out.lines.push_back(p.lines[i]);
  };
  if (p.xy.empty()) return out;
  keep(0);
  for (std::size_t i = 1; i < p.xy.size(); ++i) {
    const Point2 last = out.xy.back();
    if (spacing > 0)
      while (i + 1 < p.xy.size() && dist(p.xy[i + 1], last) <= spacing) ++i;
    if (p.xy[i] != last) keep(i);
  }
  while (closed && out.xy.size() > 1 &&
         (out.xy.back() == out.xy.front() || dist(out.xy.back(), out.xy.front()) < spacing / 2)) {
    out.xy.pop_back();
    out.lines.pop_back();
  }
  return out;
}

}  // namespace

InputSet gps_to_input(const GpsData& data, const std::string& file, const TrackOptions& options) {
  std::vector<LonLat> all;
  for (const auto& s : data.sequences) {
    if (s.kind == GpsSequence::Kind::Waypoints && !options.waypoints) continue;
    for (const auto& g : s.points) all.push_back({g.lon, g.lat});
  }
  if (all.empty()) throw InputError("no points", file);
  InputSet set;
  set.units = Units::Metres;
  ChosenProjection chosen = lonlat_projection(options.projection, all, options.choice, file);
  set.projection = chosen.projection;
  set.notes.push_back(chosen.note);
  detail::InputBuilder builder(set, file, Source::Location::Line);
  if (std::isnan(options.close_tolerance)) throw InputError("track close distance nan is not a number", file);
  const double tolerance = options.close_tolerance >= 0 ? options.close_tolerance : std::max(2 * options.spacing, 25.0);

  // Each sequence projected (a walk also smoothed and thinned, and whether it closes), in reading order.
  struct Walk {
    Projected r;
    bool waypoints = false, closed = false;
  };
  struct Loose {
    Point2 p;
    std::size_t line;
  };
  std::vector<Walk> walks;
  std::vector<Loose> loose;
  for (const auto& s : data.sequences) {
    if (s.kind == GpsSequence::Kind::Waypoints && !options.waypoints) continue;
    Projected p;
    for (const auto& g : s.points) {
      try {
        p.xy.push_back(set.projection.forward({g.lon, g.lat}));
      } catch (const std::domain_error& e) {
        throw InputError(e.what(), file, g.line);
      }
      p.lines.push_back(g.line);
    }
    if (s.kind == GpsSequence::Kind::Waypoints) {
      walks.push_back({std::move(p), true, false});
      continue;
    }
    // A closed walk: end within tolerance of the start (and not a back-and-forth of two points).
    bool closed = tolerance > 0 && p.xy.size() >= 4 && dist(p.xy.front(), p.xy.back()) <= tolerance;
    if (closed) {
      // A repeated start point closes the ring explicitly: drop it, rings close implicitly.
      while (p.xy.size() > 3 && p.xy.back() == p.xy.front()) {
        p.xy.pop_back();
        p.lines.pop_back();
      }
    }
    smooth(p, options.smooth_window, closed);
    Projected r = resample(p, options.spacing, closed);
    closed = closed && r.xy.size() >= 3;
    walks.push_back({std::move(r), false, closed});
  }
  double count = 0;  // the points the spacing gives, checked before sampling any
  for (const Walk& w : walks)
    count += w.waypoints ? static_cast<double>(w.r.xy.size()) : detail::subdivided_count(w.r.xy, w.closed, options.spacing);
  detail::check_sampled_count(count, options.spacing, options.max_points, file);
  std::size_t closed_count = 0, line_count = 0;
  for (const Walk& w : walks) {
    if (w.waypoints) {
      for (std::size_t i = 0; i < w.r.xy.size(); ++i) loose.push_back({w.r.xy[i], w.r.lines[i]});
    } else if (w.closed) {
      builder.add_ring(w.r.xy, RingRole::Shore, w.r.lines, options.spacing, options.max_points);
      ++closed_count;
    } else if (options.open_lines && w.r.xy.size() >= 2) {
      builder.add_ring(w.r.xy, RingRole::Line, w.r.lines, options.spacing, options.max_points);
      ++line_count;
    } else {
      const auto sub = detail::subdivide(w.r.xy, false, options.spacing, options.max_points);
      const auto from = detail::subdivided_from(w.r.xy, sub);
      for (std::size_t i = 0; i < sub.size(); ++i) loose.push_back({sub[i], w.r.lines[from[i]]});
    }
  }
  assign_roles_by_nesting(set.domain);
  try {
    check_rings(set);
  } catch (const InputError& e) {
    // Closing was this reader's guess: say how to take it back.
    std::ostringstream message;
    message << e.message() << " (a walk that ends within " << tolerance
            << " m of its start is closed into a shore ring; --track-close-distance 0 keeps every walk as loose points)";
    if (line_count) message << " (open walks are constraint lines with --gps-open-lines; without it, loose points)";
    throw InputError(message.str(), e.file(), e.line());
  }
  // Loose points: drop exact repeats (of ring vertices or of each other); GPS logs repeat fixes.
  std::set<Point2> seen(set.points.begin(), set.points.end());
  std::size_t repeats = 0;
  for (const auto& l : loose) {
    if (!seen.insert(l.p).second) {
      ++repeats;
      continue;
    }
    builder.add_point(l.p, l.line);
  }
  if (closed_count) set.notes.push_back(std::to_string(closed_count) + " closed walk(s) became rings");
  if (line_count) set.notes.push_back(std::to_string(line_count) + " open walk(s) became constraint lines");
  if (repeats) set.notes.push_back("dropped " + std::to_string(repeats) + " repeated point(s)");
  if (set.points.empty()) throw InputError("no points", file);
  return set;
}

}  // namespace shoremesh::io
