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

// The text in pieces that end at a line's end, each read on its own thread into a list of what its lines
// are (a point, a break between groups, or the first malformed line), then joined in the file's order:
// on_group(points, lines) for each group of points separated by blank lines (and comments, GMT segment
// headers), in the file's order, then InputError at the first malformed line, in turn: as a reading line
// by line calls and throws.
template <class F>
void for_each_group(std::string_view text, const std::string& name, F&& on_group) {
  text = detail::strip_bom(text);
  struct Item {
    Point2 p{};
    std::size_t line = 0;  // within the piece, 1-based
    bool point = false;    // otherwise a break between groups
  };
  struct Piece {
    std::string_view text;
    std::vector<Item> items;
    std::size_t line_count = 0;
    std::string error;  // the first malformed line's message (items stop there), at items.back().line
  };
  constexpr std::size_t kPieceSize = 1 << 18;
  std::vector<Piece> pieces;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = std::min(text.size(), at + kPieceSize);
    if (end < text.size()) {
      const std::size_t nl = text.find('\n', end - 1);
      end = nl == std::string_view::npos ? text.size() : nl + 1;
    }
    pieces.push_back({text.substr(at, end - at), {}, 0, {}});
    at = end;
  }
  tbb::parallel_for(std::size_t(0), pieces.size(), [&](std::size_t k) {
    Piece& piece = pieces[k];
    piece.items.reserve(piece.text.size() / 16);
    std::string_view rest = piece.text;
    std::size_t line = 0;
    while (!rest.empty() && piece.error.empty()) {
      ++line;
      const auto nl = rest.find('\n');
      std::string_view raw = rest.substr(0, nl);
      rest.remove_prefix(nl == std::string_view::npos ? rest.size() : nl + 1);
      if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
      const auto trimmed = detail::trim(raw);
      // Comments and GMT segment headers end a group as a blank line does.
      if (trimmed.empty() || trimmed.front() == '#' || trimmed.front() == '>') {
        piece.items.push_back({{}, line, false});
        continue;
      }
      const auto fields = detail::split_fields(detail::strip_comment(trimmed));
      Item item{{}, line, true};
      if (fields.size() != 2) {
        piece.error = "expected 2 numbers, found " + std::to_string(fields.size()) + " columns";
      } else {
        for (std::size_t c = 0; c < 2 && piece.error.empty(); ++c) {
          const auto st = detail::parse_double(fields[c], item.p[c]);
          if (st != detail::NumberStatus::Ok)
            piece.error = "column " + std::to_string(c + 1) + ": " + detail::quoted(fields[c]) +
                          (st == detail::NumberStatus::NotFinite ? " is not a finite number" : " is not a number");
        }
      }
      piece.items.push_back(item);
    }
    piece.line_count = line;
  });
  std::vector<Point2> pts;
  std::vector<std::size_t> lines;
  auto flush = [&] {
    if (pts.empty()) return;
    on_group(std::move(pts), std::move(lines));
    pts.clear();
    lines.clear();
  };
  std::size_t offset = 0;  // lines in the pieces before
  for (Piece& piece : pieces) {
    for (std::size_t i = 0; i < piece.items.size(); ++i) {
      const Item& item = piece.items[i];
      if (!piece.error.empty() && i + 1 == piece.items.size()) throw InputError(piece.error, name, offset + item.line);
      if (!item.point) {
        flush();
        continue;
      }
      pts.push_back(item.p);
      lines.push_back(offset + item.line);
    }
    offset += piece.line_count;
    piece.items = {};
  }
  flush();
}

bool closed_group(const std::vector<Point2>& pts) { return pts.size() >= 4 && pts.front() == pts.back(); }

// Adds a group to `out` as a ring (without its closing point); throws for fewer than three points.
void add_ring(RingFile& out, std::vector<Point2> pts, std::vector<std::size_t> lines, const std::string& name) {
  if (pts.size() >= 2 && pts.front() == pts.back()) {
    pts.pop_back();
    lines.pop_back();
  }
  if (pts.size() < 3)
    throw InputError("a ring needs at least three points, this one has " + std::to_string(pts.size()), name, lines.front());
  out.rings.push_back(std::move(pts));
  out.lines.push_back(std::move(lines));
}

}  // namespace

RingFile parse_ring_file_text(std::string_view text, const std::string& name) {
  RingFile out;
  for_each_group(text, name, [&](std::vector<Point2> pts, std::vector<std::size_t> lines) {
    add_ring(out, std::move(pts), std::move(lines), name);
  });
  if (out.rings.empty()) throw InputError("no points", name);
  return out;
}

std::optional<RingFile> parse_ring_file_if_rings(std::string_view text, const std::string& name) {
  // Well formed with a closed group, the text is a ring file, whose errors are then only the rings'.
  std::vector<std::pair<std::vector<Point2>, std::vector<std::size_t>>> groups;
  bool closed = false;
  try {
    for_each_group(text, name, [&](std::vector<Point2> pts, std::vector<std::size_t> lines) {
      closed = closed || closed_group(pts);
      groups.emplace_back(std::move(pts), std::move(lines));
    });
  } catch (const InputError&) {
    return std::nullopt;
  }
  if (!closed) return std::nullopt;
  RingFile out;
  for (auto& [pts, lines] : groups) add_ring(out, std::move(pts), std::move(lines), name);
  if (out.rings.empty()) throw InputError("no points", name);
  return out;
}

RingFile read_ring_file(const std::string& path) { return parse_ring_file_text(detail::read_text_file(path), path); }

bool looks_like_ring_file(std::string_view text) {
  bool closed = false;
  try {
    for_each_group(text, "", [&](const std::vector<Point2>& pts, const std::vector<std::size_t>&) {
      closed = closed || closed_group(pts);
    });
  } catch (const InputError&) {
    return false;
  }
  return closed;
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
