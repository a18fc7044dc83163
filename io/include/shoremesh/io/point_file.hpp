#pragma once
// Plain point files: CSV or whitespace separated, 2 or 3 numbers a line.
//
//   # comment lines and trailing comments start with '#'; blank lines are ignored
//   x,y            <- optional header (non-numeric names only), first non-comment line
//   0.5, 1.25
//   2 3            <- blanks work too (a line with a comma is split on commas, otherwise on blanks)
//
// Numbers are parsed strictly (std::from_chars over the whole field: "1.5abc" is an error). Every error is a
// shoremesh::InputError naming the file and the 1-based line: text in a number column, a wrong or mixed
// column count, NaN/inf ("not a finite number"), duplicate points ("duplicate point: line 7 repeats line 3",
// found by sorting, O(n log n)), and a file without points ("no points").
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh::io {

struct PointFile {
  int dimension = 0;               // 2 or 3, from the data
  std::vector<Point2> points2;     // filled when dimension == 2
  std::vector<Point3> points3;     // filled when dimension == 3
  std::vector<std::size_t> lines;  // 1-based source line of each point
};

// Reads a point file from disk. Throws shoremesh::InputError(message, path, line).
PointFile read_point_file(const std::string& path);

// The same parser on text in memory; `name` is used as the file name in errors (tests, fuzzing).
PointFile parse_point_file_text(std::string_view text, const std::string& name);

}  // namespace shoremesh::io
