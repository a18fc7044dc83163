#pragma once
// A Delaunay triangulation of M_t kept beside a 2D one-shot build (docs/delaunay_neighbours.md): an
// operation at time t finds its cell's candidates by walking outward from its vertex through the
// triangulation instead of searching the quadtree. Only vertices born before the current time are in
// it: a vertex committed at time t is deferred and inserted once the operations of time t are done. It
// cannot answer "as of time t" for an earlier t, nor lose vertices, so builds for updates keep the tree.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "shoremesh/engine/ids.hpp"
#include "shoremesh/engine/predicates.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh::engine {

// Whether 2D one-shot builds read neighbours from a Delaunay triangulation or search the quadtree for
// them (the default: faster here, bench/RESULTS.md). The output is the same bit for bit
// (DelaunayNeighbours tests). Process-wide.
void set_delaunay_neighbours(bool on);
bool delaunay_neighbours();

class DelaunayNeighbours {
 public:
  DelaunayNeighbours();
  ~DelaunayNeighbours();
  DelaunayNeighbours(const DelaunayNeighbours&) = delete;
  DelaunayNeighbours& operator=(const DelaunayNeighbours&) = delete;

 private:
  struct Impl;

 public:

  // The triangulation of points[0, n), vertex id k at points[k]. Distinct points.
  void build(std::span<const Point2> points);
  // Vertex `id` at p, born at `birth` (a time key), made by an operation acting on vertex `near`: inserted
  // by the first insert_born_before(t) with t > birth, located from near's star.
  void defer(VertexId id, const Point2& p, VertexId near, std::uint64_t birth);
  // Inserts the deferred vertices born before `now`. Serial; no operation may be reading meanwhile.
  void insert_born_before(std::uint64_t now);
  // A vertex with its squared distance from the walk's start (rounded as the cells round it).
  struct Near {
    double d2;
    Point2 position;
    VertexId id;
  };
  // A walk outward from a vertex v through the triangulation: its vertices one by one in the order of
  // (d2, position), the order cells clip in. A vertex other than v has a neighbour nearer v (greedy
  // routing reaches v in a Delaunay triangulation), so once the walk has returned every vertex up to a
  // distance, it has seen all vertices within that distance. The scratch of one thread, reused.
  class Walk {
   public:
    // The next vertex's squared distance (infinity when none is left), without taking it.
    double next_d2() const;
    // Whether a vertex met later sorted before one returned earlier (distances within rounding): the
    // order is not the cells' then.
    bool out_of_order() const { return out_of_order_; }
    std::size_t returned() const { return returned_; }
    // The vertices met but not returned yet, in no particular order.
    std::span<const Near> pending() const { return heap_; }

   private:
    friend class DelaunayNeighbours;
    friend struct DelaunayNeighbours::Impl;
    bool mark(VertexId id);  // false when already met
    std::vector<Near> heap_;
    std::vector<VertexId> table_;  // met vertices, open addressing
    std::vector<std::uint32_t> used_;
    Point2 from_{};
    Near last_{};
    std::size_t returned_ = 0;
    bool out_of_order_ = false;
  };
  // Starts a walk from v at p: false when the triangulation cannot tell (v not in it, all its points on
  // a line). Reads only: several threads may walk at once, each with its own Walk.
  bool start_walk(VertexId v, const Point2& p, Walk& walk) const;
  // The next vertex (false when none is left); its neighbours join the walk.
  bool next(Walk& walk, Near& out) const;
  std::size_t vertex_count() const;
  std::size_t memory_bytes() const;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace shoremesh::engine
