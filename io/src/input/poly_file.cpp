#include "shoremesh/io/poly_file.hpp"

#include <cmath>
#include <filesystem>
#include <optional>

#include "duplicates.hpp"
#include "input_builder.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/pslg.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

namespace {

using detail::NumberStatus;

// Records of a Triangle file: non-blank lines with comments removed, split on blanks.
struct Records {
  std::vector<std::vector<std::string_view>> fields;
  std::vector<std::size_t> lines;
  std::size_t next = 0;
  std::size_t last_line = 0;  // the file's last line (for "ends early" errors)
  std::string name;

  Records(std::string_view text, std::string file) : name(std::move(file)) {
    detail::for_each_line(text, [&](std::string_view raw, std::size_t line) {
      last_line = line;
      const auto body = detail::strip_comment(raw);
      if (body.empty()) return;
      fields.push_back(detail::split_fields(body));
      lines.push_back(line);
    });
  }
  bool done() const { return next >= fields.size(); }
  std::size_t line() const { return next < lines.size() ? lines[next] : last_line; }

  const std::vector<std::string_view>& take(const std::string& what) {
    if (done()) throw InputError("file ends before " + what, name, last_line ? std::optional(last_line) : std::nullopt);
    return fields[next++];
  }
  std::size_t taken_line() const { return lines[next - 1]; }

  long long integer(std::string_view f, const std::string& what) const {
    const auto v = detail::parse_integer(f);
    if (!v) throw InputError(what + ": " + detail::quoted(f) + " is not an integer", name, taken_line());
    return *v;
  }
  double number(std::string_view f, const std::string& what) const {
    double v = 0;
    const auto st = detail::parse_double(f, v);
    if (st == NumberStatus::NotANumber) throw InputError(what + ": " + detail::quoted(f) + " is not a number", name, taken_line());
    if (st == NumberStatus::NotFinite) throw InputError(what + ": " + detail::quoted(f) + " is not a finite number", name, taken_line());
    return v;
  }
};

constexpr long long kMaxCount = 100'000'000;  // refuse absurd declared counts before reserving memory

// Reads "<#vertices> 2 <#attributes> <#markers>" and the vertices; returns the first vertex number (0 or 1).
long long read_vertices(Records& r, PslgFile& out) {
  const auto& h = r.take("the header");
  if (h.size() < 1 || h.size() > 4) throw InputError("header: expected <#vertices> <dimension> <#attributes> <#markers>", r.name, r.taken_line());
  const long long n = r.integer(h[0], "number of vertices");
  const long long dim = h.size() > 1 ? r.integer(h[1], "dimension") : 2;
  const long long attrs = h.size() > 2 ? r.integer(h[2], "number of attributes") : 0;
  const long long markers = h.size() > 3 ? r.integer(h[3], "number of boundary markers") : 0;
  if (n < 0 || n > kMaxCount) throw InputError("number of vertices " + std::to_string(n) + " out of range", r.name, r.taken_line());
  if (dim != 2) throw InputError("dimension " + std::to_string(dim) + ": only 2D files are read", r.name, r.taken_line());
  if (attrs < 0 || attrs > 1000 || markers < 0 || markers > 1)
    throw InputError("attribute/marker counts out of range", r.name, r.taken_line());
  const std::size_t expect = static_cast<std::size_t>(3 + attrs + markers);
  long long first = 0;
  for (long long i = 0; i < n; ++i) {
    const auto& f = r.take("vertex " + std::to_string(i + 1) + " of " + std::to_string(n));
    if (f.size() != expect)
      throw InputError("vertex line: expected " + std::to_string(expect) + " values, found " + std::to_string(f.size()), r.name,
                       r.taken_line());
    const long long number = r.integer(f[0], "vertex number");
    if (i == 0) {
      if (number != 0 && number != 1) throw InputError("vertices must be numbered from 0 or 1", r.name, r.taken_line());
      first = number;
    } else if (number != first + i) {
      throw InputError("vertex number " + std::to_string(number) + " where " + std::to_string(first + i) + " was expected",
                       r.name, r.taken_line());
    }
    out.points.push_back({r.number(f[1], "x"), r.number(f[2], "y")});
    out.point_lines.push_back(r.taken_line());
    for (std::size_t k = 3; k < f.size(); ++k) (void)r.number(f[k], "attribute");
  }
  return first;
}

void check_points(const PslgFile& p, const std::string& name) {
  if (p.points.empty()) throw InputError("no points", name);
  if (const auto dup = detail::find_duplicate(p.points))
    throw InputError("duplicate point: line " + std::to_string(p.point_lines[dup->first]) + " repeats line " +
                         std::to_string(p.point_lines[dup->second]),
                     name, p.point_lines[dup->first]);
}

}  // namespace

PslgFile parse_node_text(std::string_view text, const std::string& name) {
  Records r(text, name);
  PslgFile out;
  out.vertex_file = name;
  read_vertices(r, out);
  check_points(out, name);
  return out;
}

PslgFile parse_poly_text(std::string_view text, const std::string& name, std::string_view node_text, const std::string& node_name) {
  Records r(text, name);
  PslgFile out;
  out.vertex_file = name;
  long long first = read_vertices(r, out);
  if (out.points.empty()) {
    if (node_name.empty()) throw InputError("the .poly declares no vertices and there is no .node file beside it", name, r.lines.empty() ? std::nullopt : std::optional(r.lines[0]));
    Records node_records(node_text, node_name);
    out = PslgFile{};
    out.vertex_file = node_name;
    first = read_vertices(node_records, out);
  }
  check_points(out, out.vertex_file);
  const auto& sh = r.take("the segment count");
  const long long ns = r.integer(sh[0], "number of segments");
  const long long smark = sh.size() > 1 ? r.integer(sh[1], "number of boundary markers") : 0;
  if (ns < 0 || ns > kMaxCount || smark < 0 || smark > 1 || sh.size() > 2)
    throw InputError("segment header: expected <#segments> <#markers 0|1>", name, r.taken_line());
  const long long n = static_cast<long long>(out.points.size());
  for (long long i = 0; i < ns; ++i) {
    const auto& f = r.take("segment " + std::to_string(i + 1) + " of " + std::to_string(ns));
    if (f.size() != static_cast<std::size_t>(3 + smark))
      throw InputError("segment line: expected " + std::to_string(3 + smark) + " values, found " + std::to_string(f.size()), name,
                       r.taken_line());
    (void)r.integer(f[0], "segment number");
    std::array<std::size_t, 2> seg{};
    for (int k = 0; k < 2; ++k) {
      const long long v = r.integer(f[1 + k], "endpoint");
      if (v < first || v >= first + n)
        throw InputError("segment endpoint " + std::to_string(v) + " is not a vertex (vertices are " + std::to_string(first) +
                             ".." + std::to_string(first + n - 1) + ")",
                         name, r.taken_line());
      seg[k] = static_cast<std::size_t>(v - first);
    }
    if (seg[0] == seg[1]) throw InputError("segment joins vertex " + std::string(f[1]) + " to itself", name, r.taken_line());
    out.segments.push_back(seg);
    out.segment_lines.push_back(r.taken_line());
  }
  if (!r.done()) {
    const auto& hh = r.take("the hole count");
    const long long nh = r.integer(hh[0], "number of holes");
    if (nh < 0 || nh > kMaxCount || hh.size() != 1) throw InputError("hole header: expected <#holes>", name, r.taken_line());
    for (long long i = 0; i < nh; ++i) {
      const auto& f = r.take("hole " + std::to_string(i + 1) + " of " + std::to_string(nh));
      if (f.size() != 3) throw InputError("hole line: expected 3 values, found " + std::to_string(f.size()), name, r.taken_line());
      (void)r.integer(f[0], "hole number");
      out.holes.push_back({r.number(f[1], "x"), r.number(f[2], "y")});
      out.hole_lines.push_back(r.taken_line());
    }
  }
  return out;  // optional regional attributes are ignored
}

PslgFile read_node_file(const std::string& path) { return parse_node_text(detail::read_text_file(path), path); }

PslgFile read_poly_file(const std::string& path) {
  const std::string text = detail::read_text_file(path);
  std::filesystem::path node = path;
  node.replace_extension(".node");
  std::error_code ec;
  if (std::filesystem::is_regular_file(node, ec)) {
    // Only needed when the .poly has no vertices of its own; read lazily by checking the header.
    Records r(text, path);
    if (!r.done() && !r.fields[0].empty() && detail::parse_integer(r.fields[0][0]) == 0)
      return parse_poly_text(text, path, detail::read_text_file(node.string()), node.string());
  }
  return parse_poly_text(text, path);
}

InputSet pslg_to_input(const PslgFile& p, const PslgOptions& options) {
  InputSet set;
  set.units = Units::MapUnits;
  if (p.points.size() < 3) throw InputError("fewer than three points", p.vertex_file);
  const std::size_t n = p.points.size();
  auto segment_name = [&](std::size_t s) {
    return "segment " + std::to_string(s + 1) + " (line " + std::to_string(p.segment_lines[s]) + ")";
  };
  if (const auto crossing = first_segment_crossing(p.points, p.segments))
    throw InputError(segment_name((*crossing)[0]) + " meets " + segment_name((*crossing)[1]) +
                         " other than at a common end point; the segments of a .poly may only meet at their ends",
                     p.vertex_file, p.segment_lines[(*crossing)[0]]);
  const PslgDomain pslg = pslg_domain(p.points, p.segments, p.holes);

  std::vector<bool> vertex_kept(n, false);
  for (const auto& vs : pslg.vertices)
    for (std::size_t v : vs) vertex_kept[v] = true;
  double count = 0;  // the points the spacing gives, checked before sampling any
  for (const Ring& ring : pslg.domain.rings) count += detail::subdivided_count(ring.points, ring.closed(), options.spacing);
  for (std::size_t v = 0; v < n; ++v) count += !vertex_kept[v];
  detail::check_sampled_count(count, options.spacing, options.max_points, p.vertex_file);

  detail::InputBuilder vertices(set, p.vertex_file, Source::Location::Line);
  for (std::size_t r = 0; r < pslg.domain.rings.size(); ++r) {
    std::vector<std::size_t> lines;
    for (std::size_t v : pslg.vertices[r]) lines.push_back(p.point_lines[v]);
    const Ring& ring = pslg.domain.rings[r];
    vertices.add_ring(ring.points, ring.role, lines, options.spacing, options.max_points, true);
  }
  check_rings(set);
  for (std::size_t v = 0; v < n; ++v)
    if (!vertex_kept[v]) vertices.add_point(p.points[v], p.point_lines[v]);

  std::size_t rings = 0, lines = 0;
  for (const Ring& ring : pslg.domain.rings) ++(ring.closed() ? rings : lines);
  auto plural = [](std::size_t k, const std::string& what) { return std::to_string(k) + " " + what + (k == 1 ? "" : "s"); };
  if (pslg.bounded_faces) {
    set.notes.push_back(plural(pslg.boundary_segments, "segment") + " bound the water (" + plural(rings, "ring") + ")" +
                        (pslg.line_segments ? ", " + plural(pslg.line_segments, "segment") + " with water on both sides are " +
                                                  plural(lines, "constraint line")
                                            : std::string()));
    if (pslg.dropped_segments)
      set.notes.push_back(plural(pslg.dropped_segments, "segment") +
                          " with land (a hole or the outside) on both sides bound nothing and are left out");
  } else if (!p.segments.empty()) {
    set.notes.push_back("the segments form no closed cycle: no water is bounded; they are " + plural(lines, "constraint line") +
                        " in the box's mesh");
  }
  if (pslg.duplicate_segments) set.notes.push_back(plural(pslg.duplicate_segments, "segment") + " given twice counted once");
  if (!pslg.pinch_vertices.empty()) {
    std::string at;
    for (std::size_t k = 0; k < std::min<std::size_t>(pslg.pinch_vertices.size(), 5); ++k)
      at += (k ? ", line " : "line ") + std::to_string(p.point_lines[pslg.pinch_vertices[k]]);
    const std::size_t k = pslg.pinch_vertices.size();
    set.notes.push_back("the input has " + std::to_string(k) + (k == 1 ? " pinch vertex" : " pinch vertices") +
                        " (water sectors that meet at a point; rings share the vertex): " + at +
                        (pslg.pinch_vertices.size() > 5 ? ", ..." : ""));
  }
  for (std::size_t h : pslg.holes_outside)
    set.notes.push_back("hole " + std::to_string(h + 1) + " (line " + std::to_string(p.hole_lines[h]) +
                        ") lies in no segment cycle; it removes nothing");
  if (const auto dup = detail::find_duplicate(set.points))
    throw InputError("duplicate point: " + describe_origin(set, dup->first) + " repeats " + describe_origin(set, dup->second),
                     p.vertex_file, set.origins[dup->first].location);
  return set;
}

}  // namespace shoremesh::io
