#pragma once
// A planar straight-line graph (Triangle's .poly: vertices, segments, hole seeds) as a water domain.
//
// The segments cut the plane into faces. As Triangle does with -p, the water is every bounded face
// except those holding a hole seed (Triangle's holes eat outward from the seed until segments stop them,
// and eat the region outside the segments from the convex hull inward: exactly these faces). Then:
//  - a segment with water on one side only is part of the water's boundary: the boundary is walked with
//    the water on its left, one closed walk per water sector at a vertex, and split where a walk comes
//    back to a vertex, so every ring is a simple cycle; counter-clockwise ones bound water (Shore), the
//    others land (Island), which is the even-odd rule's water;
//  - a segment with water on both sides (a dangling one, or one between two water faces) is a
//    constraint line inside the water: maximal chains through vertices where exactly two such segments
//    meet and no ring passes (a closed chain is cut in two);
//  - a segment with land on both sides (inside a hole, or outside) bounds nothing and is left out.
// Rings and lines share the vertices where they meet (docs/conforming.md, "Shared vertices"). Every
// decision (angular order around a vertex, the outer face of each connected part, which face holds a
// seed or a part) is exact, through the engine's orient2d.
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "shoremesh/domain.hpp"

namespace shoremesh {

struct PslgDomain {
  Domain2 domain;                                    // rings (Shore/Island), then lines
  std::vector<std::vector<std::size_t>> vertices;    // per ring or line: its vertices as indices of the points
  std::size_t boundary_segments = 0, line_segments = 0, dropped_segments = 0, duplicate_segments = 0;
  // Vertices where the water's boundary touches itself: four or more boundary segments meet (the input's
  // own pinch vertices: water sectors that meet only at a point).
  std::vector<std::size_t> pinch_vertices;
  std::vector<std::size_t> holes_outside;  // hole seeds (indices) in no bounded face: they remove nothing
  bool bounded_faces = false;              // false: no segment cycle at all (then every segment is a line)
};

// Two segments of a PSLG that meet other than at a common end point (the first in segment order), or
// nothing. Segment indices.
std::optional<std::array<std::size_t, 2>> first_segment_crossing(std::span<const Point2> points,
                                                                std::span<const std::array<std::size_t, 2>> segments);

// The water domain of a PSLG whose segments meet only at common end points (first_segment_crossing finds
// nothing) and join distinct vertices. Without any bounded face (no segment cycle) the segments are all
// lines and there are no rings.
PslgDomain pslg_domain(std::span<const Point2> points, std::span<const std::array<std::size_t, 2>> segments,
                       std::span<const Point2> holes);

}  // namespace shoremesh
