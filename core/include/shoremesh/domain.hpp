#pragma once
// The water domain of a 2D input: closed rings (a lake shore, its islands, ponds on islands), and their
// validation. One module for every layer: the readers check what they read with it, the edit session
// checks each edit with its edge index (ring_edge_index.hpp), the mesh takes its water from it. Every
// orientation is the engine's exact predicate (engine::orient2d), so a reported intersection is a real one
// and none is missed, whatever the coordinates.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh {

// What a ring bounds. Water is where a point lies inside an odd number of rings (even-odd rule): a shore
// ring encloses water, an island ring inside it encloses land, a pond ring inside an island water again.
// A Line is an open chain (a breakwater, a channel's edge, a survey line kept open): its segments are
// constraints of the mesh like a ring's, but it bounds nothing and is not closed.
enum class RingRole { Shore, Island, Line };

struct Ring {
  std::vector<Point2> points;  // closed implicitly: the last point connects to the first (not repeated)
  RingRole role = RingRole::Shore;
  bool closed() const { return role != RingRole::Line; }
  // Segment k joins point k to point k + 1 (cyclically when closed).
  std::size_t segment_count() const { return closed() ? points.size() : (points.empty() ? 0 : points.size() - 1); }
};

// An edit session keeps a removed ring's place as a ring without points (so that ring numbers stay); such
// a ring bounds nothing: the edge index, the shore's refinement and the mesh skip it (find_ring_defect,
// which checks what a reader read, calls it a ring of too few points).
struct Domain2 {
  std::vector<Ring> rings;
  bool empty() const { return rings.empty(); }
};

struct RingDefect {
  enum class Kind { TooFewPoints, RepeatedVertex, Intersection, LineOnLand };
  Kind kind = Kind::Intersection;
  std::size_t ring_a = 0, vertex_a = 0;  // edge vertex_a -> vertex_a + 1 of ring_a (or the offending vertex)
  std::size_t ring_b = 0, vertex_b = 0;  // the other edge (Intersection) or the repeated vertex
  std::string describe() const;          // "ring 2 edge 5-6 crosses ring 2 edge 17-18"
};

// The first defect in (ring, edge) order, or nothing when the rings are valid: every ring has at least three
// distinct points (a line two), no ring or line crosses or touches itself or another one, and every line
// lies in the water (when there are closed rings: a line on land would be in no element). O(n log n + k) for n edges and k
// pairs of edges whose boxes meet (a few per edge for shorelines), through RingEdgeIndex.
// `shared_vertices`: rings and lines may share a vertex (where a .poly's segments meet, or a ring touches
// itself): edges with a common end then meet only where they fold onto one another (the same edge twice
// included). The mesh takes such rings as they are (a shared vertex is one point; docs/conforming.md).
std::optional<RingDefect> find_ring_defect(const Domain2& domain, bool shared_vertices = false);

// Sets each ring's role from its nesting depth (the number of other rings containing it): even -> Shore,
// odd -> Island, as the even-odd rule implies; lines stay lines. For rings that neither cross nor touch
// (check first).
void assign_roles_by_nesting(Domain2& domain);

// Point-in-ring test with exact orientations (crossing number); points on the boundary count as inside.
bool ring_contains(const std::vector<Point2>& ring, const Point2& p);

}  // namespace shoremesh
