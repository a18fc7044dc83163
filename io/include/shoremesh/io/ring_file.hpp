#pragma once
// Ring files: closed rings as plain x,y (or lon,lat) lines, rings separated by blank lines, each ring closed
// by repeating its first point at the end (the layout of GMT's multi-segment output and of the bundled
// samples/superior/lake_superior_lonlat.csv). '#' comments are allowed; numbers are parsed strictly.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "shoremesh/domain.hpp"
#include <string_view>
#include <vector>

#include "shoremesh/io/input_set.hpp"
#include "shoremesh/io/projection.hpp"

namespace shoremesh::io {

struct RingFile {
  std::vector<std::vector<Point2>> rings;       // without the repeated closing point
  std::vector<std::vector<std::size_t>> lines;  // 1-based source line of each vertex
};

RingFile parse_ring_file_text(std::string_view text, const std::string& name);
RingFile read_ring_file(const std::string& path);
// Writes `domain`'s rings as a ring file (each closed by repeating its first point), atomically: what an
// edit session saves as its current shoreline, readable by every command.
void write_ring_file(const std::filesystem::path& path, const Domain2& domain);

// True when the text looks like a ring file: blank-line separated groups of 2-column lines, and at least
// one group of four or more lines ends with its first point (no header).
bool looks_like_ring_file(std::string_view text);
// parse_ring_file_text(text, name) when looks_like_ring_file(text), else nothing: the text read once.
std::optional<RingFile> parse_ring_file_if_rings(std::string_view text, const std::string& name);

// Rings to an InputSet. `lonlat`: the columns are lon, lat in degrees (projected with `projection`, or one
// chosen by `choice`); otherwise map units. `spacing` > 0: points are inserted along every ring segment
// longer than it (after projecting, so in metres for lon/lat), each with the line of the vertex before it.
// Roles come from nesting (even-odd); rings are validated (fewer than three points, self-intersections:
// shoremesh::InputError with file and line).
InputSet ring_file_to_input(const RingFile& rings, const std::string& file, bool lonlat,
                            const std::optional<Projection>& projection = std::nullopt,
                            ProjectionChoice choice = ProjectionChoice::LocalTransverseMercator, double spacing = 0);

}  // namespace shoremesh::io
