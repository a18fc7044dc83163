#pragma once
// The map between the user's coordinates and the engine's unit box [0,1]^D: one uniform scale and a
// shift (aspect kept), so that distances and angles are the user's up to one factor.
#include <optional>
#include <span>

#include "shoremesh/point.hpp"

namespace shoremesh {

template <int D>
struct BoxTransform {
  Point<D> origin{};  // the box's lowest corner, user coordinates
  double side = 1;    // the box's side, user units

  // The box that shoremesh derives from a point set: the bounding box made square around its centre,
  // grown by a margin of 5% of its side on every face, so that the input does not sit on the box.
  // A single point gets a box of side 1 centred on it.
  static BoxTransform fit(std::span<const Point<D>> points);

  bool contains(const Point<D>& p) const;        // in the closed box (user coordinates)
  Point<D> to_unit(const Point<D>& p) const;     // clamped into [0,1]^D
  Point<D> to_user(const Point<D>& u) const;
};

}  // namespace shoremesh
