// The Delaunay neighbour source of 2D one-shot builds (delaunay_neighbours.hpp, docs/delaunay_neighbours.md).
#include "shoremesh/engine/delaunay_neighbours.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <utility>

namespace shoremesh::engine {

namespace {
// Off by default: the walk costs more than the tree search it saves (bench/RESULTS.md, "Delaunay
// neighbour source").
std::atomic<bool> g_delaunay_neighbours{false};

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexId, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Triangulation = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using Handle = Triangulation::Vertex_handle;
using Face = Triangulation::Face_handle;

// The walk's order, as a heap's "less": by squared distance, ties by position (the cells' order).
bool after(const DelaunayNeighbours::Near& a, const DelaunayNeighbours::Near& b) {
  if (a.d2 != b.d2) return a.d2 > b.d2;
  return b.position < a.position;
}
}  // namespace

void set_delaunay_neighbours(bool on) { g_delaunay_neighbours = on; }
bool delaunay_neighbours() { return g_delaunay_neighbours; }

struct DelaunayNeighbours::Impl {
  struct Deferred {
    std::uint64_t birth;
    VertexId id, near;
    Point2 p;
  };
  Triangulation dt;
  std::vector<Handle> handle;      // by vertex id; null for a vertex not in the triangulation
  std::vector<Deferred> deferred;  // in commit order, so by birth
  std::size_t deferred_done = 0;

  // Puts the neighbours of h not met yet on the walk.
  void push_neighbours(const Handle& h, Walk& walk) const;
};

DelaunayNeighbours::DelaunayNeighbours() : impl_(std::make_unique<Impl>()) {}
DelaunayNeighbours::~DelaunayNeighbours() = default;

void DelaunayNeighbours::build(std::span<const Point2> points) {
  // CGAL's predicates' static filters expect rounding to nearest (the engine's operations round upward).
  const CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);
  Impl& m = *impl_;
  m.dt.clear();
  m.deferred.clear();
  m.deferred_done = 0;
  std::vector<std::pair<Kernel::Point_2, VertexId>> with_ids;
  with_ids.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) with_ids.emplace_back(Kernel::Point_2(points[k][0], points[k][1]), VertexId(k));
  m.dt.insert(with_ids.begin(), with_ids.end());  // spatially sorted inside
  m.handle.assign(points.size(), Handle());
  for (auto v = m.dt.finite_vertices_begin(); v != m.dt.finite_vertices_end(); ++v) m.handle[v->info()] = v;
}

void DelaunayNeighbours::defer(VertexId id, const Point2& p, VertexId near, std::uint64_t birth) {
  impl_->deferred.push_back({birth, id, near, p});
}

void DelaunayNeighbours::insert_born_before(std::uint64_t now) {
  Impl& m = *impl_;
  if (m.deferred_done == m.deferred.size()) return;
  const CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);
  std::size_t k = m.deferred_done;
  for (; k < m.deferred.size() && m.deferred[k].birth < now; ++k) {
    const Impl::Deferred& d = m.deferred[k];
    Face hint;
    if (d.near < m.handle.size() && m.handle[d.near] != Handle()) hint = m.handle[d.near]->face();
    const Handle h = m.dt.insert(Kernel::Point_2(d.p[0], d.p[1]), hint);
    h->info() = d.id;
    if (m.handle.size() <= d.id) m.handle.resize(std::size_t(d.id) + 1 + m.handle.size() / 2, Handle());
    m.handle[d.id] = h;
  }
  m.deferred_done = k;
  if (m.deferred_done == m.deferred.size()) {
    m.deferred.clear();
    m.deferred_done = 0;
  }
}

double DelaunayNeighbours::Walk::next_d2() const {
  return heap_.empty() ? std::numeric_limits<double>::infinity() : heap_.front().d2;
}

bool DelaunayNeighbours::Walk::mark(VertexId id) {
  if (2 * (used_.size() + 1) > table_.size()) {
    // At most half full: the met vertices again in a table twice the size.
    std::vector<VertexId> met;
    for (std::uint32_t slot : used_) met.push_back(table_[slot]);
    table_.assign(std::max<std::size_t>(256, 2 * table_.size()), kNoVertex);
    used_.clear();
    for (VertexId x : met) mark(x);
  }
  const std::size_t mask = table_.size() - 1;
  for (std::size_t slot = (std::uint64_t(id) * 0x9E3779B97F4A7C15ull >> 40) & mask;; slot = (slot + 1) & mask) {
    if (table_[slot] == id) return false;
    if (table_[slot] == kNoVertex) {
      table_[slot] = id;
      used_.push_back(std::uint32_t(slot));
      return true;
    }
  }
}

void DelaunayNeighbours::Impl::push_neighbours(const Handle& h, Walk& walk) const {
  const auto first = dt.incident_vertices(h);
  auto c = first;
  do {
    if (dt.is_infinite(c) || !walk.mark(c->info())) continue;
    const Point2 q{c->point().x(), c->point().y()};
    // Rounded as the cells' candidates are (engine_cells.cpp: consider), under the caller's rounding.
    double d2 = 0;
    for (int i = 0; i < 2; ++i) d2 += (q[i] - walk.from_[i]) * (q[i] - walk.from_[i]);
    const Near x{d2, q, c->info()};
    if (after(walk.last_, x)) walk.out_of_order_ = true;
    walk.heap_.push_back(x);
    std::push_heap(walk.heap_.begin(), walk.heap_.end(), after);
  } while (++c != first);
}

bool DelaunayNeighbours::start_walk(VertexId v, const Point2& p, Walk& walk) const {
  const Impl& m = *impl_;
  for (std::uint32_t slot : walk.used_) walk.table_[slot] = kNoVertex;
  walk.used_.clear();
  walk.heap_.clear();
  walk.returned_ = 0;
  walk.out_of_order_ = false;
  if (m.dt.dimension() < 2 || v >= m.handle.size() || m.handle[v] == Handle()) return false;
  walk.from_ = p;
  walk.last_ = {0, p, v};
  walk.mark(v);
  m.push_neighbours(m.handle[v], walk);
  return true;
}

bool DelaunayNeighbours::next(Walk& walk, Near& out) const {
  if (walk.heap_.empty()) return false;
  std::pop_heap(walk.heap_.begin(), walk.heap_.end(), after);
  out = walk.heap_.back();
  walk.heap_.pop_back();
  ++walk.returned_;
  walk.last_ = out;
  impl_->push_neighbours(impl_->handle[out.id], walk);
  return true;
}

std::size_t DelaunayNeighbours::vertex_count() const { return impl_->dt.number_of_vertices(); }

std::size_t DelaunayNeighbours::memory_bytes() const {
  const Impl& m = *impl_;
  return m.dt.tds().vertices().capacity() * sizeof(Tds::Vertex) + m.dt.tds().faces().capacity() * sizeof(Tds::Face) +
         m.handle.capacity() * sizeof(Handle) + m.deferred.capacity() * sizeof(Impl::Deferred);
}

}  // namespace shoremesh::engine
