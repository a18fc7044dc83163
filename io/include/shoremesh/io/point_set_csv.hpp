#pragma once
// The well-spaced point set as text: the contract of `shoremesh mesh INPUT -o OUT.csv`.
//
//   # box X0 Y0 [Z0] SIDE         <- the box in the user's coordinates
//   x,y[,z]                       <- input points first, in input order (by increasing id),
//   ...                              then the Steiner points
//
// Numbers are written in the shortest form that reads back to the same double (round-trip exact).
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::io {

template <int D>
struct PointSetFile {
  BoxTransform<D> box;
  std::vector<Point<D>> points;
};

// Writes atomically (temporary file, then rename). Throws std::runtime_error naming the path.
template <int D>
void write_point_set_csv(const std::filesystem::path& path, const BoxTransform<D>& box, std::span<const Point<D>> points);

// Reads a file written by write_point_set_csv. Throws InputError naming the file and line.
template <int D>
PointSetFile<D> read_point_set_csv(const std::filesystem::path& path);

// The shortest decimal text that reads back to exactly x.
std::string format_double(double x);

}  // namespace shoremesh::io
