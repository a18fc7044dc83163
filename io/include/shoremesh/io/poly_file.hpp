#pragma once
// Triangle's .node and .poly files (https://www.cs.cmu.edu/~quake/triangle.node.html, .poly.html).
//
//   .node:  <#vertices> <dimension = 2> <#attributes> <#boundary markers 0|1>
//           <vertex #> <x> <y> [attributes...] [marker]           (numbered from 0 or 1, consecutively)
//   .poly:  the .node header and vertices (or "0 2 0 0" and the vertices in the sibling .node file), then
//           <#segments> <#markers>, <segment #> <endpoint> <endpoint> [marker], then <#holes>, <hole #> <x> <y>
//           (regional attributes after the holes are ignored). '#' starts a comment.
//
// The segments and holes become the water domain as Triangle's -p reads them (shoremesh/pslg.hpp): the
// water's boundary as rings, segments with water on both sides (open chains, dangling segments, segments
// between two water faces) as constraint lines, segments with land on both sides left out; rings and lines
// share the vertices where they meet. Segments that meet other than at their ends are refused. Segments are sampled
// like rings: with a spacing, points are inserted so that no piece is longer than the spacing. Errors
// (shoremesh::InputError with file and line): bad header, dimension other than 2, wrong value count,
// text in a number column, NaN/inf, vertex numbering that skips, a file that ends before the declared count,
// a segment naming a missing vertex or joining a vertex to itself, duplicate vertices, fewer than three points.
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "shoremesh/io/input_set.hpp"

namespace shoremesh::io {

struct PslgFile {
  std::vector<Point2> points;
  std::vector<std::size_t> point_lines;
  std::vector<std::array<std::size_t, 2>> segments;  // 0-based indices into points
  std::vector<std::size_t> segment_lines;
  std::vector<Point2> holes;
  std::vector<std::size_t> hole_lines;
  std::string vertex_file;  // the file the vertices came from (the .poly itself or its .node)
};

PslgFile parse_node_text(std::string_view text, const std::string& name);
// `node_text`/`node_name`: the sibling .node file, used when the .poly declares zero vertices.
PslgFile parse_poly_text(std::string_view text, const std::string& name, std::string_view node_text = {},
                         const std::string& node_name = {});
PslgFile read_node_file(const std::string& path);
PslgFile read_poly_file(const std::string& path);  // reads the sibling .node when needed

struct PslgOptions {
  double spacing = 0;  // > 0: subdivide segments so that no piece is longer (map units); 0: vertices only
  std::size_t max_points = kMaxSampledPoints;  // a spacing that would give more points is refused
};

InputSet pslg_to_input(const PslgFile& pslg, const PslgOptions& options = {});

}  // namespace shoremesh::io
