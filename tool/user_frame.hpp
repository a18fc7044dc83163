#pragma once
// The user's frame for messages: the units the input came in (metres, pixels, map units) and, for lon/lat
// input, the projection that took it to metres, so that every coordinate a message prints is one the user
// recognises (metres with lon/lat beside them, pixels, map units), never the engine's unit box.
#include <memory>
#include <string>
#include <vector>

#include "shoremesh/io/input_set.hpp"
#include "shoremesh/io/open_boundary.hpp"
#include "shoremesh/io/projection.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::tool {

struct UserFrame {
  io::Units units = io::Units::MapUnits;
  io::Projection projection;
  // What exports add to the mesh: depths at its nodes (--dem, --depth-from; null: none) and the points
  // where the water leaves the data (an open boundary in fort.14).
  std::shared_ptr<const io::DepthSource> depth;
  std::vector<Point2> open_points;
  std::shared_ptr<const io::OpenBoundary> open_boundary;  // --open-boundary (null: none)

  static UserFrame of(const io::InputSet& set) {
    return {set.units, set.projection, set.depth, set.open_points, set.open_boundary};
  }

  // "523401.2 m", "3.5 px", "0.25 map units".
  std::string length(double d) const;
  // "(523401.2, 5276001.3) m = 47.6123N 87.3012W", "(12.5, 40.5) px", "(0.25, 0.75)".
  std::string point(const Point2& p) const;
  std::string point(const Point3& p) const;
  // The unit suffix alone: "m", "px", "" (map units).
  std::string unit_suffix() const;
};

// Shortest round-trip decimal of x (the point-set CSV's format), for machine-readable replies.
std::string exact(double x);
// A number for people: up to `digits` significant digits.
std::string approx(double x, int digits = 6);

}  // namespace shoremesh::tool
