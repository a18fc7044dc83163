#pragma once
// The edges of a water domain's rings in an R-tree (Boost.Geometry): the whole check of a domain
// (find_ring_defect), and an edit session's check of one vertex moved, removed or added, or of a ring
// added, against the edges near the new ones only. Checking them against every edge (O(n) an edit) took
// about a tenth of a shore edit at 171k shore points (0.8 to 0.9 ms of 8, bench/RESULTS.md); with the
// tree it is O(log n) plus the edges the new ones come near.
//
// The rings must be valid (find_ring_defect finds nothing) when the index is built, and each edit checked
// here before it is committed. Rings may share a vertex where the caller lets them (a .poly's, read with
// find_ring_defect(domain, true); a line's end on a ring in an edit session, which refuses any other
// vertex put on a vertex before asking here): the edit checks let edges with a common end meet there
// unless they fold onto one another. An edge is known by its ring and its two end points. Rings without points (removed ones) hold no edge; a
// line (RingRole::Line) holds its segments, not a closing one. One-vertex edits (defect_at, commit) are
// for closed rings: a line changes as a whole (erase_ring, defect_of_new_ring, insert_ring).
#include <cstddef>
#include <memory>
#include <optional>

#include "shoremesh/domain.hpp"

namespace shoremesh {

// One vertex's edit of ring `ring`, with `vertex` an index in the ring after it:
//  - Move: vertex `vertex` moved from `gone`;
//  - Remove: the vertex at `gone` went, and `vertex` is the one before it;
//  - Insert: `vertex` is new, between the two ends of an edge that was there (`gone` is not used).
struct RingVertexEdit {
  enum class Kind { Move, Remove, Insert };
  Kind kind = Kind::Move;
  std::size_t ring = 0;
  std::size_t vertex = 0;
  Point2 gone{};
};

class RingEdgeIndex {
 public:
  explicit RingEdgeIndex(const Domain2& domain);
  ~RingEdgeIndex();
  RingEdgeIndex(RingEdgeIndex&&) noexcept;
  RingEdgeIndex& operator=(RingEdgeIndex&&) noexcept;

  // The first crossing of the indexed rings (`domain`, as indexed) in (ring, edge) order, or nothing:
  // each edge against the edges its box meets. Local defects (folds, repeats) are find_ring_defect's.
  // `shared_vertices`: edges with a common end meet only where they fold onto one another.
  std::optional<RingDefect> first_crossing(const Domain2& domain, bool shared_vertices = false) const;

  // The first defect of `after` (the indexed rings with `edit` made), as find_ring_defect would report
  // it for a defect the edit makes, or nothing: the edges at the changed vertex against the edges their
  // boxes meet, and the folds at it and its neighbours.
  std::optional<RingDefect> defect_at(const Domain2& after, const RingVertexEdit& edit) const;

  // Takes a checked edit in: the edges it took away leave (those at `edit.gone`, or the edge an inserted
  // vertex splits), those at the changed vertex of `after` come.
  void commit(const Domain2& after, const RingVertexEdit& edit);

  // Ring `ring` of `after` is new (it holds no indexed edge): its first defect, on its own or against the
  // indexed edges, as find_ring_defect would report it for `after`, or nothing.
  std::optional<RingDefect> defect_of_new_ring(const Domain2& after, std::size_t ring) const;
  // Ring (or line) number r comes (checked) or goes.
  void insert_ring(std::size_t r, const Ring& ring);
  void erase_ring(std::size_t r, const Ring& ring);

  // Whether p lies inside an odd number of the indexed rings (the even-odd rule; lines bound nothing): the
  // edges whose boxes meet the rightward ray from p, each decided exactly. p on an edge counts as inside.
  bool inside(const Point2& p) const;

  // Whether p is an end of an indexed edge (of a closed ring's edge when `closed_only`).
  bool has_vertex(const Point2& p, bool closed_only = false) const;
  // A point of line `line` that tells on which side of the indexed rings it lies (where it meets none): its
  // first vertex that is no closed ring's vertex, or, when every vertex is one (a chord between shore
  // vertices), its first segment's midpoint, rounded once.
  Point2 line_probe(const Ring& line) const;

  std::size_t size() const;  // edges indexed

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace shoremesh
