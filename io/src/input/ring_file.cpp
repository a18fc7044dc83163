#include "shoremesh/io/ring_file.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <stdexcept>

#include "input_builder.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/point_set_csv.hpp"
#include "shoremesh/domain.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

namespace {

// Groups of (point, line) separated by blank lines; throws on malformed lines when `strict`.
template <class F>
void for_each_group(std::string_view text, const std::string& name, F&& on_group) {
  std::vector<Point2> pts;
  std::vector<std::size_t> lines;
  auto flush = [&] {
    if (!pts.empty()) on_group(pts, lines);
    pts.clear();
    lines.clear();
  };
  detail::for_each_line(text, [&](std::string_view raw, std::size_t line) {
    const auto trimmed = detail::trim(raw);
    if (trimmed.empty()) return flush();
    if (trimmed.front() == '#' || trimmed.front() == '>') return flush();  // comments and GMT segment headers
    const auto fields = detail::split_fields(detail::strip_comment(trimmed));
    if (fields.size() != 2) throw InputError("expected 2 numbers, found " + std::to_string(fields.size()) + " columns", name, line);
    Point2 p{};
    for (std::size_t c = 0; c < 2; ++c) {
      const auto st = detail::parse_double(fields[c], p[c]);
      if (st != detail::NumberStatus::Ok)
        throw InputError("column " + std::to_string(c + 1) + ": " + detail::quoted(fields[c]) +
                             (st == detail::NumberStatus::NotFinite ? " is not a finite number" : " is not a number"),
                         name, line);
    }
    pts.push_back(p);
    lines.push_back(line);
  });
  flush();
}

}  // namespace

RingFile parse_ring_file_text(std::string_view text, const std::string& name) {
  RingFile out;
  for_each_group(text, name, [&](std::vector<Point2> pts, std::vector<std::size_t> lines) {
    if (pts.size() >= 2 && pts.front() == pts.back()) {
      pts.pop_back();
      lines.pop_back();
    }
    if (pts.size() < 3)
      throw InputError("a ring needs at least three points, this one has " + std::to_string(pts.size()), name, lines.front());
    out.rings.push_back(std::move(pts));
    out.lines.push_back(std::move(lines));
  });
  if (out.rings.empty()) throw InputError("no points", name);
  return out;
}

RingFile read_ring_file(const std::string& path) { return parse_ring_file_text(detail::read_text_file(path), path); }

bool looks_like_ring_file(std::string_view text) {
  bool closed_group = false;
  try {
    for_each_group(text, "", [&](const std::vector<Point2>& pts, const std::vector<std::size_t>&) {
      if (pts.size() >= 4 && pts.front() == pts.back()) closed_group = true;
    });
  } catch (const InputError&) {
    return false;
  }
  return closed_group;
}

InputSet ring_file_to_input(const RingFile& rf, const std::string& file, bool lonlat,
                            const std::optional<Projection>& projection, ProjectionChoice choice, double spacing) {
  InputSet set;
  set.units = lonlat ? Units::Metres : Units::MapUnits;
  if (lonlat) {
    std::vector<LonLat> all;
    for (const auto& r : rf.rings)
      for (const auto& p : r) all.push_back({p[0], p[1]});
    ChosenProjection chosen = lonlat_projection(projection, all, choice, file);
    set.projection = chosen.projection;
    set.notes.push_back(chosen.note);
  }
  std::vector<std::vector<Point2>> rings = rf.rings;
  if (lonlat) {
    // Each point on its own, on every thread; the error is the first point's that has one, as in order.
    std::size_t total = 0;
    for (const auto& ring : rings) total += ring.size();
    std::atomic<std::size_t> first_bad{total};
    tbb::parallel_for(std::size_t(0), rings.size(), [&](std::size_t r) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rings[r].size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          try {
            rings[r][k] = set.projection.forward({rings[r][k][0], rings[r][k][1]});
          } catch (const std::domain_error&) {
            std::size_t flat = k;  // the point's place in the file's order
            for (std::size_t q = 0; q < r; ++q) flat += rings[q].size();
            std::size_t seen = first_bad.load();
            while (flat < seen && !first_bad.compare_exchange_weak(seen, flat)) {
            }
          }
        }
      });
    });
    if (std::size_t flat = first_bad.load(); flat < total) {
      std::size_t r = 0;
      while (flat >= rings[r].size()) flat -= rings[r++].size();
      try {
        (void)set.projection.forward({rf.rings[r][flat][0], rf.rings[r][flat][1]});
      } catch (const std::domain_error& e) {
        throw InputError(e.what(), file, rf.lines[r][flat]);
      }
    }
  }
  double count = 0;  // the points the spacing gives, checked before sampling any
  for (std::size_t r = 0; r < rings.size(); ++r) count += detail::subdivided_count(rings[r], true, spacing);
  detail::check_sampled_count(count, spacing, kMaxSampledPoints, file);
  detail::InputBuilder builder(set, file, Source::Location::Line);
  for (std::size_t r = 0; r < rings.size(); ++r) builder.add_ring(rings[r], RingRole::Shore, rf.lines[r], spacing);
  assign_roles_by_nesting(set.domain);
  check_rings(set);
  return set;
}

void write_ring_file(const std::filesystem::path& path, const Domain2& domain) {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "# " << domain.rings.size() << " rings (shoremesh), each closed by its first point\n";
  for (const Ring& ring : domain.rings) {
    out << '\n';
    for (std::size_t k = 0; k <= ring.points.size(); ++k) {
      const Point2& p = ring.points[k % ring.points.size()];
      out << format_double(p[0]) << ',' << format_double(p[1]) << '\n';
    }
  }
  file.commit();
}

}  // namespace shoremesh::io
