// The CGAL side of Mesh<D>: a Delaunay triangulation kept alive between updates, with a map from exact
// coordinates to vertex handles so that the points a dynamic update names are found in O(1).
// All of CGAL's heavy templates live in this translation unit.
#include "shoremesh/mesh.hpp"
#include "shoremesh/mesh_point_map.hpp"
#include "shoremesh/point_table.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "shoremesh/error.hpp"
#include "shoremesh/mesh_coverage.hpp"
#include "shoremesh/mesh_water.hpp"

namespace shoremesh {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// A face's (cell's) info: where it lies. The mesh keeps it when both hold.
enum FaceFlag : std::uint8_t {
  kInWater = 1,  // inside the water (always without a domain, and in 3D)
  kCovered = 2,  // its circumcentre in the box, or no box to clip to
  kPending = 4,  // 2D: created or changed during an update, classified at its end (never kept meanwhile)
};

// Per dimension: the triangulation type and the few calls whose names differ between 2D and 3D.
template <int D>
struct Cgal;

// A 2D face's info: its flags and the vertices it had when it was classified, so that a face that CGAL
// changed in place (a flip) or created is told apart from one it left alone.
struct FaceInfo2 {
  std::uint8_t flags = 0;
  std::uint32_t visit = 0;             // the last walk that reached the face (MeshTriangulation::next_walk)
  std::array<const void*, 3> stamp{};  // vertex addresses, sorted; all null for a face never classified
};
static_assert(sizeof(FaceInfo2) == 32, "the walk's mark lives in the padding after the flags");

// The constrained Delaunay triangulation of the mesh: the shore's segments are constraints, so that they
// are mesh edges whatever the points around them. Constraints never cross (the rings are valid), so no
// intersection point is ever constructed. It reports the faces a constraint's insertion deletes (the
// faces it crosses), so that the mesh can name them before they go.
template <class Tds>
class Cdt : public CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds,
                                                             CGAL::No_constraint_intersection_requiring_constructions_tag> {
  using Base =
      CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

 public:
  using typename Base::Face_handle;
  using typename Base::List_edges;
  using typename Base::List_faces;
  std::function<void(const List_faces&)> on_hole;  // called with the faces about to be deleted

  // The constraints at v stop being constraints, without flips (a triangulation of dimension below 2).
  void unmark_incident_constraints(typename Base::Vertex_handle v) {
    CGAL::Constrained_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>::
        remove_incident_constraints(v);
  }

 protected:
  void triangulate_hole(List_faces& intersected_faces, List_edges& conflict_boundary_ab,
                        List_edges& conflict_boundary_ba) override {
    if (on_hole) on_hole(intersected_faces);
    Base::triangulate_hole(intersected_faces, conflict_boundary_ab, conflict_boundary_ba);
  }
};

template <>
struct Cgal<2> {
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<
      Kernel, CGAL::Triangulation_face_base_with_info_2<FaceInfo2, Kernel>>;
  using Triangulation = Cdt<CGAL::Triangulation_data_structure_2<Vb, Fb>>;
  using Vertex = Triangulation::Vertex_handle;
  using Face = Triangulation::Face_handle;

  static std::uint8_t& flags(Face f) { return f->info().flags; }

  static Kernel::Point_2 to_cgal(const Point2& p) { return {p[0], p[1]}; }
  static Point2 from_cgal(const Kernel::Point_2& p) { return {p.x(), p.y()}; }

  template <class F>
  static void for_each_finite_face(const Triangulation& t, F&& f) {
    for (Face face : t.finite_face_handles()) f(face);
  }
  template <class F>
  static void for_each_incident_finite_face(const Triangulation& t, Vertex v, F&& f) {
    auto c = t.incident_faces(v), done = c;
    do {
      if (!t.is_infinite(c)) f(Face(c));
    } while (++c != done);
  }
  static std::vector<Vertex> adjacent_finite_vertices(const Triangulation& t, Vertex v) {
    std::vector<Vertex> out;
    auto c = t.incident_vertices(v), done = c;
    do {
      if (!t.is_infinite(c)) out.push_back(c);
    } while (++c != done);
    return out;
  }
  static Face locate(const Triangulation& t, const Kernel::Point_2& p, Vertex hint) {
    return hint == Vertex() ? t.locate(p) : t.locate(p, hint->face());
  }
  static std::vector<Face> conflicts(const Triangulation& t, const Kernel::Point_2& p, Face start) {
    std::vector<Face> out;
    t.get_conflicts(p, std::back_inserter(out), start);
    return out;
  }
};

template <>
struct Cgal<3> {
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel>;
  using Cb = CGAL::Triangulation_cell_base_with_info_3<std::uint8_t, Kernel,
                                                       CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;  // FaceFlags
  using Triangulation = CGAL::Delaunay_triangulation_3<Kernel, CGAL::Triangulation_data_structure_3<Vb, Cb>>;
  using Vertex = Triangulation::Vertex_handle;
  using Face = Triangulation::Cell_handle;

  static std::uint8_t& flags(Face f) { return f->info(); }

  static Kernel::Point_3 to_cgal(const Point3& p) { return {p[0], p[1], p[2]}; }
  static Point3 from_cgal(const Kernel::Point_3& p) { return {p.x(), p.y(), p.z()}; }

  template <class F>
  static void for_each_finite_face(const Triangulation& t, F&& f) {
    for (Face cell : t.finite_cell_handles()) f(cell);
  }
  template <class F>
  static void for_each_incident_finite_face(const Triangulation& t, Vertex v, F&& f) {
    std::vector<Face> cells;
    t.finite_incident_cells(v, std::back_inserter(cells));
    for (Face c : cells) f(c);
  }
  static std::vector<Vertex> adjacent_finite_vertices(const Triangulation& t, Vertex v) {
    std::vector<Vertex> out;
    t.finite_adjacent_vertices(v, std::back_inserter(out));
    return out;
  }
  static Face locate(const Triangulation& t, const Kernel::Point_3& p, Vertex hint) {
    return hint == Vertex() ? t.locate(p) : t.locate(p, hint->cell());
  }
  static std::vector<Face> conflicts(const Triangulation& t, const Kernel::Point_3& p, Face start) {
    std::vector<Face> out;
    t.find_conflicts(p, start, CGAL::Emptyset_iterator(), std::back_inserter(out));
    return out;
  }
};

template <int D>
std::string describe(const Point<D>& p) {
  std::string s = "(";
  for (int i = 0; i < D; ++i) s += (i ? ", " : "") + std::to_string(p[i]);
  return s + ")";
}

template <int D>
bool finite(const Point<D>& p) {
  return std::all_of(p.begin(), p.end(), [](double x) { return std::isfinite(x); });
}

// Where the water of `after` can differ from that of `before`: the bounding box of each ring's changed
// stretch with its two unchanged ends, old and new points (a whole ring when it came or went: a ring past
// the other's last, or one without points), and a point of it (an unchanged end) to start a walk from.
// Empty when the rings are the same.
struct ChangedWater {
  bool changed = false;
  Point2 lo{}, hi{}, seed{};
  struct Stretch {
    std::size_t ring, prefix, suffix;  // the ring's vertices other than its first prefix and last suffix
    bool whole = false;                // the ring came or went
  };
  std::vector<Stretch> stretches;
};

const std::vector<Point2>& ring_points(const Domain2& domain, std::size_t r) {
  static const std::vector<Point2> none;
  return r < domain.rings.size() ? domain.rings[r].points : none;
}

ChangedWater changed_water(const Domain2& before, const Domain2& after) {
  ChangedWater w;
  w.lo = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  w.hi = {-w.lo[0], -w.lo[1]};
  auto take = [&](const Point2& p) {
    for (int i = 0; i < 2; ++i) {
      w.lo[std::size_t(i)] = std::min(w.lo[std::size_t(i)], p[std::size_t(i)]);
      w.hi[std::size_t(i)] = std::max(w.hi[std::size_t(i)], p[std::size_t(i)]);
    }
  };
  for (std::size_t r = 0; r < std::max(before.rings.size(), after.rings.size()); ++r) {
    const auto& o = ring_points(before, r);
    const auto& n = ring_points(after, r);
    if (o == n) continue;
    w.changed = true;
    // A line's change is taken whole: its segments change, the water does not.
    const bool line = (r < before.rings.size() && !before.rings[r].closed()) || (r < after.rings.size() && !after.rings[r].closed());
    if (o.empty() || n.empty() || line) {  // a ring came or went: the water flips inside it only
      for (const Point2& p : o) take(p);
      for (const Point2& p : n) take(p);
      w.seed = o.empty() ? n.front() : o.front();
      w.stretches.push_back({r, 0, 0, true});
      continue;
    }
    // The common prefix and suffix; the stretch between them changed, with the edges to its ends.
    const std::size_t common = std::min(o.size(), n.size());
    std::size_t prefix = 0, suffix = 0;
    while (prefix < common && o[prefix] == n[prefix]) ++prefix;
    while (suffix < common - prefix && o[o.size() - 1 - suffix] == n[n.size() - 1 - suffix]) ++suffix;
    for (const auto* ring : {&o, &n}) {
      const std::size_t m = ring->size();
      // From the end before the stretch (cyclically) to the end after it.
      for (std::size_t k = prefix + m - 1; k <= 2 * m - suffix; ++k) take((*ring)[k % m]);
    }
    w.seed = o[(prefix + o.size() - 1) % o.size()];
    w.stretches.push_back({r, prefix, suffix});
  }
  return w;
}

// The shore segments of `before` that `after` no longer has and those it gained: from each changed stretch
// (the segments from the vertex before it to the vertex after it; all of a ring that came or went).
void changed_segments(const Domain2& before, const Domain2& after, const ChangedWater& water,
                      std::vector<std::pair<Point2, Point2>>& dropped, std::vector<std::pair<Point2, Point2>>& inserted) {
  using Segment = std::pair<Point2, Point2>;
  auto segments = [](const Domain2& d, std::size_t r, std::size_t prefix, std::size_t suffix, bool whole,
                     std::vector<Segment>& out) {
    if (r >= d.rings.size()) return;
    const Ring& ring = d.rings[r];
    const auto& pts = ring.points;
    const std::size_t m = pts.size();
    if (whole) {  // every segment of the ring or line
      for (std::size_t k = 0; k < ring.segment_count(); ++k)
        if (pts[k] != pts[(k + 1) % m]) out.push_back(std::minmax(pts[k], pts[(k + 1) % m]));
      return;
    }
    const std::size_t count = std::min(m, m - prefix - suffix + 1);
    for (std::size_t j = 0; j < count; ++j) {
      const std::size_t k = (prefix + m - 1 + j) % m;
      const Point2 &a = pts[k], &b = pts[(k + 1) % m];
      if (a != b) out.push_back(std::minmax(a, b));
    }
  };
  std::vector<Segment> old_segments, new_segments;
  for (const auto& st : water.stretches) {
    segments(before, st.ring, st.prefix, st.suffix, st.whole, old_segments);
    segments(after, st.ring, st.prefix, st.suffix, st.whole, new_segments);
  }
  std::sort(old_segments.begin(), old_segments.end());
  std::sort(new_segments.begin(), new_segments.end());
  std::set_difference(old_segments.begin(), old_segments.end(), new_segments.begin(), new_segments.end(),
                      std::back_inserter(dropped));
  std::set_difference(new_segments.begin(), new_segments.end(), old_segments.begin(), old_segments.end(),
                      std::back_inserter(inserted));
}


}  // namespace

template <int D>
class MeshTriangulation {
 public:
  using C = Cgal<D>;
  using Triangulation = typename C::Triangulation;
  using Vertex = typename C::Vertex;
  using Face = typename C::Face;
  using Key = ElementCorners<D>;

  // A vertex's info is its slot in the point list; the top bit marks the link of a vertex being removed
  // while the faces around it are compared (keys_within), so slots stay below it.
  static constexpr std::uint32_t kLinkMark = 1u << 31;
  static constexpr std::size_t kMaxPoints = kLinkMark;

  MeshTriangulation(const Domain2& domain, std::optional<BoxTransform<D>> covered_box)
      : water_(domain), covered_box_(covered_box) {}

  Triangulation triangulation;

  // Each vertex by its exact coordinates, for the updates, which name points. Made at the first call: a
  // mesh built once and exported never looks a point up (the map would take 25 MB at Superior's 480k
  // points, beside CGAL's 100 MB of faces).
  PointMap<D, Vertex>& vertex_of() const {
    if (!vertex_map_made_) {
      vertex_map_.reserve(triangulation.number_of_vertices());
      for (Vertex v : triangulation.finite_vertex_handles()) vertex_map_.emplace(C::from_cgal(v->point()), v);
      vertex_map_made_ = true;
    }
    return vertex_map_;
  }
  bool has_vertex_map() const { return vertex_map_made_; }

  // The mesh vertex at each point of `domain`'s rings (a null handle where none is), by one pass over the
  // vertices: what the build and a report on the shore need, without vertex_of's map of every vertex.
  PointTable<Vertex> vertices_at(const Domain2& domain) const
    requires(D == 2)
  {
    PointTable<Vertex> at = ring_point_table(domain);
    find_vertices(at);
    return at;
  }
  // vertices_at in two steps: the table of the rings' points (null handles), which needs no triangulation,
  // then the vertices at them.
  static PointTable<Vertex> ring_point_table(const Domain2& domain)
    requires(D == 2)
  {
    PointTable<Vertex> at;
    for (const Ring& ring : domain.rings)
      for (const Point2& p : ring.points) at.add(p);
    at.seal();
    return at;
  }
  void find_vertices(PointTable<Vertex>& at) const
    requires(D == 2)
  {
    if (!at.empty())
      for (Vertex v : triangulation.finite_vertex_handles())
        if (Vertex* slot = at.find(C::from_cgal(v->point()))) *slot = v;
  }

  // The elements a change destroyed and created, netted once at the end: an element removed then
  // recreated (or created then removed) cancels. Each element's births and deaths alternate, so the net is
  // the multiset difference of the two lists. (Vectors sorted once, not std::sets kept sorted on every
  // insertion: with keys of D + 1 points the sets took most of a 3D mesh update.)
  struct Accumulator {
    std::vector<Key> gone, born;
    void remove(const Key& k) { gone.push_back(k); }
    void add(const Key& k) { born.push_back(k); }
    void record(const std::set<Key>& before, const std::set<Key>& after) {
      for (const Key& k : before)
        if (!after.count(k)) remove(k);
      for (const Key& k : after)
        if (!before.count(k)) add(k);
    }
    MeshDelta<D> net() {
      std::sort(gone.begin(), gone.end());
      std::sort(born.begin(), born.end());
      MeshDelta<D> delta;
      std::set_difference(gone.begin(), gone.end(), born.begin(), born.end(), std::back_inserter(delta.removed));
      std::set_difference(born.begin(), born.end(), gone.begin(), gone.end(), std::back_inserter(delta.added));
      return delta;
    }
  };

  // The mesh of `points`; in 2D every segment of `domain`'s rings is a constraint.
  // False (and nothing more done) when two of the points are equal: CGAL merged them.
  bool build(std::span<const Point<D>> points, const Domain2& domain) {
    // The rings' points sorted (2D) on another thread meanwhile: the insertion is sequential.
    std::conditional_t<D == 2, PointTable<Vertex>, int> ring_vertex{};
    tbb::parallel_invoke(
        [&] {
          std::vector<std::pair<decltype(C::to_cgal(points[0])), std::uint32_t>> input;
          input.reserve(points.size());
          for (std::uint32_t i = 0; i < points.size(); ++i) input.emplace_back(C::to_cgal(points[i]), i);
          triangulation.insert(input.begin(), input.end());  // spatially sorted bulk insertion
        },
        [&] {
          if constexpr (D == 2) ring_vertex = ring_point_table(domain);
        });
    if (triangulation.number_of_vertices() != points.size()) return false;
    bool every_segment = true;  // every ring segment of positive length is a chain of constrained edges
    if constexpr (D == 2) {
      find_vertices(ring_vertex);
      for (const Ring& ring : domain.rings)
        for (std::size_t k = 0; k < ring.segment_count(); ++k) {
          const Point2& a = ring.points[k];
          const Point2& b = ring.points[(k + 1) % ring.points.size()];
          const Vertex va = ring_vertex.at(a), vb = ring_vertex.at(b);
          // A ring vertex that is not a mesh point leaves its segments out (shoreline_crossings says so).
          if (a == b) continue;
          if (va != Vertex() && vb != Vertex()) insert_constraint(va, vb);
          else every_segment = false;
        }
    }
    std::vector<Face> faces;
    if constexpr (D == 2) faces.reserve(triangulation.number_of_faces());
    else faces.reserve(triangulation.number_of_finite_cells());
    C::for_each_finite_face(triangulation, [&](Face f) { faces.push_back(f); });
    if constexpr (D == 2) {
      if (every_segment) {
        classify_by_regions(faces);
        return true;
      }
    }
    // Each face's class depends on that face alone (its corners, the rings, the box): classified on
    // every thread, each face writing its own info.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faces.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) classify(faces[i]);
    });
    return true;
  }

  // How many shore segments end at each point: a point with constraints that is no segment's end lies
  // inside one (Steiner points on a straight shore), whose constraint is joined again when it goes.
  // Made at the first update, from the rings the mesh was built with (a mesh built once and exported
  // never asks).
  std::unordered_map<Point2, std::uint32_t, PointHash<2>> segment_ends;
  bool segment_ends_made = false;
  void make_segment_ends(const Domain2& domain) {
    segment_ends_made = true;
    for (const Ring& ring : domain.rings)
      for (std::size_t k = 0; k < ring.segment_count(); ++k) {
        const Point2& a = ring.points[k];
        const Point2& b = ring.points[(k + 1) % ring.points.size()];
        if (a != b) count_segment(a, b, 1);
      }
  }
  void count_segment(const Point2& a, const Point2& b, int delta) {
    for (const Point2* p : {&a, &b}) {
      auto& n = segment_ends[*p];
      n = static_cast<std::uint32_t>(static_cast<int>(n) + delta);
      if (n == 0) segment_ends.erase(*p);
    }
  }
  bool segment_end(const Point2& p) const { return segment_ends.count(p) != 0; }

  // Constraints never cross when the rings are valid (find_ring_defect); CGAL's refusal to construct a
  // crossing is turned into an error that says so.
  void insert_constraint(Vertex a, Vertex b)
    requires(D == 2)
  {
    try {
      triangulation.insert_constraint(a, b);
    } catch (const typename Triangulation::Intersection_of_constraints_exception&) {
      throw InputError("shore segment " + describe<2>(C::from_cgal(a->point())) + "-" +
                       describe<2>(C::from_cgal(b->point())) + " crosses another shore segment");
    }
  }

  // A face's corners by address, sorted: what classify() stamps on a 2D face.
  static std::array<const void*, 3> stamp_of(Face f)
    requires(D == 2)
  {
    std::array<const void*, 3> s{&*f->vertex(0), &*f->vertex(1), &*f->vertex(2)};
    std::sort(s.begin(), s.end(), std::less<const void*>{});
    return s;
  }

  // After a CGAL operation on the 2D triangulation: every face it created or changed in place is new
  // (unclassified, or its corners are not those it was classified with). Such faces touch the seeds or
  // another such face (CGAL's flips spread through neighbours), so a walk from the faces around the
  // seeds through the changed faces finds them all. A changed face's old corners are alive (no vertex
  // was deleted by the operations that change faces in place), so its old key is read from them. A
  // finite face may become infinite in place (a point inserted on the hull): it leaves the mesh.
  void sweep(std::initializer_list<Vertex> seeds, Accumulator& acc)
    requires(D == 2)
  {
    sweep(std::span<const Vertex>(seeds.begin(), seeds.size()), acc);
  }
  void sweep(std::span<const Vertex> seeds, Accumulator& acc)
    requires(D == 2)
  {
    std::vector<Face>& todo = todo_;
    todo.clear();
    const std::uint32_t walk = next_walk();
    auto first_visit = [walk](Face f) {
      if (f->info().visit == walk) return false;
      f->info().visit = walk;
      return true;
    };
    for (Vertex v : seeds) {
      auto c = triangulation.incident_faces(v), done = c;
      if (c != nullptr) do {
          if (first_visit(c)) todo.push_back(c);
        } while (++c != done);
    }
    while (!todo.empty()) {
      const Face f = todo.back();
      todo.pop_back();
      const bool infinite = triangulation.is_infinite(f);
      const auto now = stamp_of(f);
      const auto& old = f->info().stamp;
      if (old == now || (infinite && !old[0])) continue;
      if (old[0] && kept(f)) {
        Key k;
        for (int i = 0; i < 3; ++i) k[i] = C::from_cgal(static_cast<const typename Triangulation::Vertex*>(old[i])->point());
        std::sort(k.begin(), k.end());
        acc.remove(k);
      }
      if (infinite) {
        f->info() = FaceInfo2{};
        f->info().visit = walk;
      } else if (deferring_) {
        if (!(C::flags(f) & kPending)) pending_.push_back(f);
        C::flags(f) = kPending;
        f->info().stamp = now;
      } else {
        classify(f);
        if (kept(f)) acc.add(key(f));
      }
      for (int i = 0; i < 3; ++i)
        if (first_visit(f->neighbor(i))) todo.push_back(f->neighbor(i));
    }
  }

  // During an update's point and constraint changes, the faces the sweeps find are classified once, at the
  // end (classify_pending), not after each change: a face that a later change of the same update deletes
  // or changes again is never classified. The net delta is the same: such a face's birth and death
  // cancelled, and a face alive at the end is classified against the same rings and box either way.
  // Faces are read as not kept while pending, so no death is recorded for one never born.
  void defer_classification(bool on)
    requires(D == 2)
  {
    deferring_ = on;
  }
  void classify_pending(Accumulator& acc)
    requires(D == 2)
  {
    deferring_ = false;
    const auto& faces = triangulation.tds().faces();
    for (const Face f : pending_) {
      // A face deleted since (its slot free, or taken by a face of its own) is skipped or taken once.
      if (!faces.is_used(f) || !(C::flags(f) & kPending)) continue;
      if (triangulation.is_infinite(f)) {
        C::flags(f) = 0;
        f->info().stamp = {};
        continue;
      }
      classify(f);
      if (kept(f)) acc.add(key(f));
    }
    pending_.clear();
  }

  // A fresh mark for a walk over 2D faces: a face is visited by the current walk iff its mark equals it
  // (an O(1) test, no set of faces). When the counter wraps, every face's mark is cleared first.
  std::uint32_t next_walk()
    requires(D == 2)
  {
    if (++walk_ == 0) {
      for (Face f : triangulation.all_face_handles()) f->info().visit = 0;
      walk_ = 1;
    }
    return walk_;
  }

  // Keys of the kept faces that `faces` lists (about to be deleted).
  template <class Faces>
  void record_deleted(const Faces& faces, Accumulator& acc) {
    for (Face f : faces)
      if (!triangulation.is_infinite(f) && kept(f)) acc.remove(key(f));
  }

  // A ring segment's constraint is a chain of constrained edges: CGAL splits it at every mesh point that
  // lies inside it (on a straight shore, a Steiner point on the line). The chain from a to b, or empty.
  std::vector<Vertex> constrained_chain(Vertex a, Vertex b) const
    requires(D == 2)
  {
    std::vector<Vertex> chain{a};
    const auto pa = a->point(), pb = b->point();
    for (Vertex v = a; v != b;) {
      std::vector<typename Triangulation::Edge> edges;
      triangulation.incident_constraints(v, std::back_inserter(edges));
      Vertex next;
      for (const auto& [f, i] : edges) {
        Vertex w = f->vertex(Triangulation::cw(i));
        if (w == v) w = f->vertex(Triangulation::ccw(i));
        if (w == b || (w != chain.back() && !triangulation.is_infinite(w) &&
                       CGAL::orientation(pa, pb, w->point()) == CGAL::COLLINEAR &&
                       CGAL::collinear_are_strictly_ordered_along_line(v->point(), w->point(), pb))) {
          next = w;
          if (w == b) break;
        }
      }
      if (next == Vertex()) return {};
      chain.push_back(v = next);
    }
    return chain;
  }

  // The shore segments that went stop being constraints, along their whole chain (after the point
  // removals, which took the segments of removed ring vertices with them); add_constraints inserts the
  // new ones after the point insertions.
  void drop_constraints(const std::vector<std::pair<Point2, Point2>>& segments, Accumulator& acc)
    requires(D == 2)
  {
    for (const auto& [a, b] : segments) {
      const Vertex* ia = vertex_of().find(a);
      const Vertex* ib = vertex_of().find(b);
      if (!ia || !ib) continue;  // a removed point takes it along
      const std::vector<Vertex> chain = constrained_chain(*ia, *ib);
      for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
        Face f;
        int i;
        if (!triangulation.is_edge(chain[k], chain[k + 1], f, i) || !f->is_constrained(i)) continue;
        triangulation.remove_constrained_edge(f, i);
        sweep({chain[k], chain[k + 1]}, acc);
      }
    }
  }

  void add_constraints(const std::vector<std::pair<Point2, Point2>>& segments, Accumulator& acc)
    requires(D == 2)
  {
    for (const auto& [a, b] : segments) {
      const Vertex* ia = vertex_of().find(a);
      const Vertex* ib = vertex_of().find(b);
      if (!ia || !ib) continue;  // as in build
      constrain(*ia, *ib, acc);
    }
  }

  void constrain(Vertex va, Vertex vb, Accumulator& acc)
    requires(D == 2)
  {
    std::vector<Vertex> seeds{va, vb};
    triangulation.on_hole = [&](const auto& faces) {
      record_deleted(faces, acc);
      for (Face f : faces)
        for (int i = 0; i < 3; ++i) seeds.push_back(f->vertex(i));
    };
    insert_constraint(va, vb);
    triangulation.on_hole = nullptr;
    std::erase_if(seeds, [&](Vertex v) { return triangulation.is_infinite(v); });
    sweep(seeds, acc);
  }

  bool canonical_ties = false;  // Mesh::canonicalize_ties

  // Lawson flips of the unconstrained edges between two kept faces whose four corners are exactly
  // co-circular, toward the triangulation of a symbolic perturbation: each point lifted by an
  // infinitesimal that grows with its lexicographic rank. Of four co-circular points the highest-ranked
  // then lies above the others' circle, so the diagonal avoids it. Edges with a definite in-circle sign are
  // Delaunay (or constraints) already; flipping toward the perturbed criterion reaches its unique
  // triangulation (Edelsbrunner & Muecke's simulation of simplicity), whatever CGAL's history left among
  // the co-circular choices. Starts from the edges of the faces named by `keys` (those still alive).
  void flip_ties(const std::vector<Key>& keys, Accumulator& acc)
    requires(D == 2)
  {
    std::vector<std::pair<Face, int>> stack;
    auto push_face = [&](Face f) {
      for (int i = 0; i < 3; ++i) stack.emplace_back(f, i);
    };
    for (const Key& k : keys) {
      const Vertex* at = vertex_of().find(k[0]);
      if (!at) continue;
      C::for_each_incident_finite_face(triangulation, *at, [&](Face f) {
        if (kept(f) && key(f) == k) push_face(f);
      });
    }
    while (!stack.empty()) {
      auto [f, i] = stack.back();
      stack.pop_back();
      if (triangulation.is_infinite(f) || f->is_constrained(i) || !kept(f)) continue;
      const Face n = f->neighbor(i);
      if (triangulation.is_infinite(n) || !kept(n)) continue;
      const Vertex a = f->vertex(i), b = f->vertex(Triangulation::ccw(i)), c = f->vertex(Triangulation::cw(i));
      const Vertex d = n->vertex(n->index(f));
      if (CGAL::side_of_oriented_circle(a->point(), b->point(), c->point(), d->point()) != CGAL::ON_ORIENTED_BOUNDARY)
        continue;
      Vertex top = a;
      for (Vertex v : {b, c, d})
        if (C::from_cgal(v->point()) > C::from_cgal(top->point())) top = v;
      if (top != b && top != c) continue;
      triangulation.flip(f, i);
      sweep({a, b, c, d}, acc);
      push_face(f);
      push_face(n);
    }
  }

  // Whether the mesh keeps f: in the water and covered.
  bool kept(Face f) const { return C::flags(f) == (kInWater | kCovered); }
  bool in_water(Face f) const { return C::flags(f) & kInWater; }

  Element<D> element(Face f) const {
    Element<D> e;
    for (int i = 0; i <= D; ++i) e[i] = f->vertex(i)->info();
    return e;
  }

  Key key(Face f) const {
    Key k;
    for (int i = 0; i <= D; ++i) k[i] = C::from_cgal(f->vertex(i)->point());
    std::sort(k.begin(), k.end());
    return k;
  }

  // A new face: its side of the water and whether the box covers it.
  void classify(Face f) {
    std::uint8_t flags = water_side(f);
    if (!covered_box_) {
      flags |= kCovered;
    } else {
      ElementCorners<D> corners;
      for (int i = 0; i <= D; ++i) corners[i] = C::from_cgal(f->vertex(i)->point());
      if (circumcentre_in_box<D>(corners, *covered_box_)) flags |= kCovered;
    }
    C::flags(f) = flags;
    if constexpr (D == 2) f->info().stamp = stamp_of(f);
  }

  // The water side of a triangle is the side of its centroid: with the ring segments as constraints no
  // element crosses a ring (shoreline_crossings reports a ring vertex that is not a mesh point). A triangle
  // thinner than the rounding of its corners has no double strictly inside it, and its rounded centroid
  // may fall on either side of the shore: such a sliver (a split and the two ends of its ring edge, the
  // split off the edge by one rounding; docs/water_only.md, "A sliver the empty land let in") is no element.
  std::uint8_t water_side(Face f) const {
    if constexpr (D == 2) {
      const auto c = inner_centroid(f);
      return c && water_.in_water(*c) ? kInWater : 0;
    } else {
      return kInWater;
    }
  }

  // A 2D face's rounded centroid when it lies strictly inside the face (exact orientations); none for a
  // sliver.
  std::optional<Point2> inner_centroid(Face f) const
    requires(D == 2)
  {
    const auto &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &d = f->vertex(2)->point();
    const auto c = CGAL::centroid(a, b, d);
    const CGAL::Orientation o = CGAL::orientation(a, b, d);
    if (o == CGAL::COLLINEAR || CGAL::orientation(a, b, c) != o || CGAL::orientation(b, d, c) != o ||
        CGAL::orientation(d, a, c) != o)
      return std::nullopt;
    return Point2{c.x(), c.y()};
  }

  // classify() for every finite face of a fresh build in which every ring segment is a chain of
  // constrained edges. Faces joined by an unconstrained edge then lie on one side of every ring: the
  // interior of their union meets no ring, so the side of each one's centroid (strictly inside it) is
  // the same. One point-in-rings test per region of faces so joined, not one per face, gives the flags
  // classify() gives (a sliver is still no element; a region of slivers alone has no water).
  void classify_by_regions(const std::vector<Face>& faces)
    requires(D == 2)
  {
    constexpr std::uint8_t kSolid = 8;  // during this call: the face is no sliver
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faces.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const Face f = faces[i];
        std::uint8_t flags = inner_centroid(f) ? kSolid : 0;
        if (!covered_box_) {
          flags |= kCovered;
        } else {
          ElementCorners<2> corners;
          for (int k = 0; k < 3; ++k) corners[k] = C::from_cgal(f->vertex(k)->point());
          if (circumcentre_in_box<2>(corners, *covered_box_)) flags |= kCovered;
        }
        C::flags(f) = flags;
        f->info().stamp = stamp_of(f);
      }
    });
    const std::uint32_t walk = next_walk();
    std::vector<Face> stack;
    for (const Face seed : faces) {
      if (seed->info().visit == walk || !(C::flags(seed) & kSolid)) continue;
      const std::uint8_t water = water_.in_water(*inner_centroid(seed)) ? kInWater : 0;
      seed->info().visit = walk;
      stack.push_back(seed);
      while (!stack.empty()) {
        const Face f = stack.back();
        stack.pop_back();
        std::uint8_t& flags = C::flags(f);
        if (flags & kSolid) flags = static_cast<std::uint8_t>((flags & ~kSolid) | water);
        for (int i = 0; i < 3; ++i) {
          if (f->is_constrained(i)) continue;
          const Face n = f->neighbor(i);
          if (n->info().visit == walk || triangulation.is_infinite(n)) continue;
          n->info().visit = walk;
          stack.push_back(n);
        }
      }
    }
  }

  std::set<Key> all_keys() const {
    std::set<Key> keys;
    if (triangulation.dimension() < D) return keys;
    C::for_each_finite_face(triangulation, [&](Face f) {
      if (kept(f)) keys.insert(key(f));
    });
    return keys;
  }

  // The keys of the kept elements whose corners are all in `link` (sorted). With `known` (the kept ones
  // before a removal, sorted), the others are new or were not kept: they are classified first. The
  // link's vertices carry kLinkMark meanwhile; each face is taken once, from its first corner in memory.
  std::vector<Key> keys_within(const std::vector<Vertex>& link, const std::vector<Key>* known) {
    std::vector<Key> keys;
    for (Vertex u : link)
      C::for_each_incident_finite_face(triangulation, u, [&](Face f) {
        for (int i = 0; i <= D; ++i)
          if (!(f->vertex(i)->info() & kLinkMark) || std::less<const void*>{}(&*f->vertex(i), &*u)) return;
        Key k = key(f);
        if (known && !std::binary_search(known->begin(), known->end(), k)) classify(f);
        if (kept(f)) keys.push_back(std::move(k));
      });
    std::sort(keys.begin(), keys.end());
    return keys;
  }

  // `ring_vertex`: whether a point is a vertex of the rings before the change (2D). A point with
  // constraints that is not one lies inside a ring segment, whose constraint is joined again around it.
  void remove(const Point<D>& p, std::vector<Point<D>>& points, std::vector<PointKind>& kinds, Accumulator& acc,
              const std::function<bool(const Point2&)>& ring_vertex = {}) {
    const Vertex v = vertex_of().at(p);
    const std::uint32_t slot = v->info();
    std::vector<Vertex> rejoin;  // the ends of the segment's constrained edges at v
    if constexpr (D == 2) {
      // Its segments go first, with CGAL's flips: points they hid become visible to faces outside the star.
      if (triangulation.dimension() < 2) {
        triangulation.unmark_incident_constraints(v);
      } else if (triangulation.are_there_incident_constraints(v)) {
        if (ring_vertex && !ring_vertex(p)) {
          std::vector<typename Triangulation::Edge> edges;
          triangulation.incident_constraints(v, std::back_inserter(edges));
          for (const auto& [f, i] : edges) {
            const Vertex w = f->vertex(Triangulation::cw(i));
            rejoin.push_back(w == v ? f->vertex(Triangulation::ccw(i)) : w);
          }
          if (rejoin.size() != 2) rejoin.clear();
        }
        triangulation.remove_incident_constraints(v);
        sweep({v}, acc);
      }
    }
    if (triangulation.dimension() < D) {
      const std::set<Key> before = all_keys();
      triangulation.remove(v);
      acc.record(before, all_keys());
      hint_ = Vertex();
    } else if constexpr (D == 2) {
      // The star goes; the faces that fill its hole have link vertices only.
      const std::vector<Vertex> link = C::adjacent_finite_vertices(triangulation, v);
      C::for_each_incident_finite_face(triangulation, v, [&](Face f) {
        if (kept(f)) acc.remove(key(f));
      });
      triangulation.remove(v);
      if (!link.empty()) hint_ = link.front();
      if (triangulation.dimension() == D) sweep(link, acc);
      if (rejoin.size() == 2 && triangulation.dimension() == D) constrain(rejoin[0], rejoin[1], acc);
    } else {
      // The faces destroyed are those around v (its star). The faces created fill the star's hole, so
      // they have only link vertices as corners; so may a few faces outside the star, which the
      // removal keeps. The faces with only link corners, before and after, tell the new ones apart.
      const std::vector<Vertex> link = C::adjacent_finite_vertices(triangulation, v);
      for (Vertex u : link) u->info() |= kLinkMark;
      C::for_each_incident_finite_face(triangulation, v, [&](Face f) {
        if (kept(f)) acc.remove(key(f));
      });
      const std::vector<Key> link_faces = keys_within(link, nullptr);  // none has v as a corner
      triangulation.remove(v);
      if (!link.empty()) hint_ = link.front();
      if (triangulation.dimension() == D) {
        const std::vector<Key> after = keys_within(link, &link_faces);
        std::vector<Key> created;
        std::set_difference(after.begin(), after.end(), link_faces.begin(), link_faces.end(), std::back_inserter(created));
        for (const Key& k : created) acc.add(k);
      }
      for (Vertex u : link) u->info() &= ~kLinkMark;
    }
    vertex_of().erase(p);
    if (hint_ == v) hint_ = Vertex();
    // Keep the point array compact: the last point moves into the freed slot.
    const std::size_t last = points.size() - 1;
    if (slot != last) {
      points[slot] = points[last];
      kinds[slot] = kinds[last];
      vertex_of().at(points[slot])->info() = slot;
    }
    points.pop_back();
    kinds.pop_back();
  }

  // A new vertex joins the point list (its slot is its info) and the map; the next walk starts at it.
  void adopt(Vertex v, const Point<D>& p, PointKind kind, std::vector<Point<D>>& points, std::vector<PointKind>& kinds) {
    hint_ = v;
    v->info() = static_cast<std::uint32_t>(points.size());
    points.push_back(p);
    kinds.push_back(kind);
    vertex_of().emplace(p, v);
  }

  void insert(const Point<D>& p, PointKind kind, std::vector<Point<D>>& points, std::vector<PointKind>& kinds,
              Accumulator& acc) {
    const auto cp = C::to_cgal(p);
    const bool full = triangulation.dimension() == D;
    if constexpr (D == 2) {
      if (full) {  // CGAL splits and flips faces in place here, and deletes none: the sweep sees it all
        const Vertex v = triangulation.insert(cp, C::locate(triangulation, cp, hint_));
        adopt(v, p, kind, points, kinds);
        sweep({v}, acc);
        return;
      }
    }
    std::set<Key> before;
    Face start;
    if (full) {
      // Updates are local: start the walk at the last point touched. The faces whose circumcircle
      // (circumsphere) contains p are exactly the ones the insertion destroys.
      start = C::locate(triangulation, cp, hint_);
      for (Face f : C::conflicts(triangulation, cp, start))
        if (!triangulation.is_infinite(f) && kept(f)) acc.remove(key(f));
    } else {
      before = all_keys();
    }
    const Vertex v = full ? triangulation.insert(cp, start) : triangulation.insert(cp);
    adopt(v, p, kind, points, kinds);
    if (full) {
      C::for_each_incident_finite_face(triangulation, v, [&](Face f) {
        classify(f);
        if (kept(f)) acc.add(key(f));
      });
    } else {
      C::for_each_finite_face(triangulation, [&](Face f) { classify(f); });
      acc.record(before, all_keys());
    }
  }

  // Classifies face f's water side again (the rings changed; its circumcentre did not move); if it
  // changed side, it left or joined the mesh.
  void reclassify(Face f, Accumulator& acc) {
    const bool was = kept(f);
    C::flags(f) = std::uint8_t((C::flags(f) & ~kInWater) | water_side(f));
    if (was == kept(f)) return;
    if (was) acc.remove(key(f));
    else acc.add(key(f));
  }

  // Classifies every face again.
  void reclassify_all(Accumulator& acc) {
    if (triangulation.dimension() < D) return;
    C::for_each_finite_face(triangulation, [&](Face f) { reclassify(f, acc); });
  }

  // The water becomes that of `after` (changed_water from `before`): new faces are classified against it
  // from now on, without a rebuild.
  void update_water(const Domain2& before, const Domain2& after, const ChangedWater& change) {
    for (const auto& s : change.stretches) {
      const bool line = (s.ring < after.rings.size() && !after.rings[s.ring].closed()) ||
                        (s.ring < before.rings.size() && !before.rings[s.ring].closed());
      if (line) continue;  // lines bound no water
      if (s.whole) water_.replace_ring(ring_points(before, s.ring), ring_points(after, s.ring));
      else water_.replace_stretch(s.ring, before.rings[s.ring].points, after.rings[s.ring].points, s.prefix, s.suffix);
    }
  }

  // The water test takes the segments that went and came (those of closed rings).
  void update_water(const ShoreChange& shore) {
    for (const ShoreSegment& s : shore.removed)
      if (s.water) water_.remove_edge(s.a, s.b);
    for (const ShoreSegment& s : shore.added)
      if (s.water) water_.add_edge(s.a, s.b);
  }

  // After the change: the faces whose side can differ are classified again. The water segments that went
  // and came meet every point an even number of times (old and new rings are closed), so each connected
  // chain of them is closed, and a point's side changes only where such a chain winds around it an odd
  // number of times: inside its bounding box.
  void reclassify_changed(const ShoreChange& shore, Accumulator& acc)
    requires(D == 2)
  {
    std::vector<const ShoreSegment*> segments;
    for (const auto* list : {&shore.removed, &shore.added})
      for (const ShoreSegment& s : *list)
        if (s.water) segments.push_back(&s);
    if (segments.empty()) return;
    // Chains: segments joined through their ends.
    const std::vector<std::size_t> chain = segment_chains(
        segments.size(), [&](std::size_t i) { return std::pair<const Point2&, const Point2&>(segments[i]->a, segments[i]->b); });
    struct Box {
      Point2 lo, hi, seed;
      bool seeded = false;
    };
    std::vector<Box> ordered;
    for (std::size_t i = 0; i < segments.size(); ++i) {
      const ShoreSegment* s = segments[i];
      if (chain[i] == ordered.size()) ordered.push_back(Box{s->a, s->a, s->a});
      Box& box = ordered[chain[i]];
      for (const Point2* p : {&s->a, &s->b}) {
        for (std::size_t k = 0; k < 2; ++k) {
          box.lo[k] = std::min(box.lo[k], (*p)[k]);
          box.hi[k] = std::max(box.hi[k], (*p)[k]);
        }
        // A mesh point to start the walk from, where there is one.
        if (!box.seeded && vertex_of().contains(*p)) box.seed = *p, box.seeded = true;
      }
    }
    // Walked in the order of the boxes' corners.
    std::sort(ordered.begin(), ordered.end(), [](const Box& x, const Box& y) {
      return std::tie(x.lo, x.hi) < std::tie(y.lo, y.hi);
    });
    for (const Box& box : ordered) reclassify_within(box.lo, box.hi, box.seed, acc);
  }

  // Visits the finite faces whose bounding box meets [lo, hi] (a walk from the face at `seed`, a point in
  // that box and in the mesh's hull); false (nothing visited) when the seed's face misses the box.
  template <class F>
  bool for_each_face_meeting(const Point2& lo, const Point2& hi, const Point2& seed, F&& visit)
    requires(D == 2)
  {
    auto meets = [&](Face f) {
      if (triangulation.is_infinite(f)) return false;
      for (int i = 0; i < 2; ++i) {
        double f_lo = f->vertex(0)->point()[i], f_hi = f_lo;
        for (int k = 1; k < 3; ++k) {
          f_lo = std::min(f_lo, f->vertex(k)->point()[i]);
          f_hi = std::max(f_hi, f->vertex(k)->point()[i]);
        }
        if (f_hi < lo[std::size_t(i)] || f_lo > hi[std::size_t(i)]) return false;
      }
      return true;
    };
    Face start = C::locate(triangulation, C::to_cgal(seed), hint_);
    if (triangulation.is_infinite(start)) start = start->neighbor(start->index(triangulation.infinite_vertex()));
    if (!meets(start)) return false;
    const std::uint32_t walk = next_walk();
    std::vector<Face> todo{start};
    start->info().visit = walk;
    while (!todo.empty()) {
      const Face f = todo.back();
      todo.pop_back();
      if (!meets(f)) continue;  // the walk stops at the first faces outside the box
      visit(f);
      for (int i = 0; i < 3; ++i)
        if (const Face g = f->neighbor(i); g->info().visit != walk) {
          g->info().visit = walk;
          todo.push_back(g);
        }
    }
    return true;
  }

  // Classifies again the faces whose bounding box meets [lo, hi], a box around `seed`. Outside that box
  // the change of the rings changed no face's side (Mesh::apply with a domain says why).
  void reclassify_within(const Point2& lo, const Point2& hi, const Point2& seed, Accumulator& acc)
    requires(D == 2)
  {
    if (triangulation.dimension() < 2) return;
    // The seed outside the mesh's hull: no walk to start from.
    if (!for_each_face_meeting(lo, hi, seed, [&](Face f) { reclassify(f, acc); })) reclassify_all(acc);
  }

 private:
  WaterTest water_;
  std::optional<BoxTransform<D>> covered_box_;
  Vertex hint_;  // a live vertex near the last change, where the next point location starts
  std::uint32_t walk_ = 0;  // the last walk's mark (next_walk)
  std::vector<Face> todo_;  // sweep's stack, kept between calls
  bool deferring_ = false;   // defer_classification
  std::vector<Face> pending_;  // faces marked kPending, to classify (classify_pending), kept between calls
  mutable PointMap<D, Vertex> vertex_map_;  // vertex_of()
  mutable bool vertex_map_made_ = false;
};

template <int D>
Mesh<D>::Mesh(std::span<const Point<D>> points, std::size_t input_count, std::optional<BoxTransform<D>> covered_box)
    : covered_box_(covered_box) {
  build(points, input_count);
}

template <int D>
Mesh<D>::Mesh(std::span<const Point2> points, std::size_t input_count, const Domain2& domain,
              std::optional<BoxTransform<2>> covered_box)
  requires(D == 2)
    : domain_(domain), covered_box_(covered_box) {
  build(points, input_count);
}

template <int D>
Mesh<D>::~Mesh() = default;
template <int D>
Mesh<D>::Mesh(Mesh&&) noexcept = default;
template <int D>
Mesh<D>& Mesh<D>::operator=(Mesh&&) noexcept = default;

template <int D>
void Mesh<D>::build(std::span<const Point<D>> points, std::size_t input_count) {
  if (covered_box_ && !(finite<D>(covered_box_->origin) && std::isfinite(covered_box_->side) && covered_box_->side > 0))
    throw InputError("the box to clip the mesh to needs a finite corner and a finite positive side");
  if (input_count > points.size()) throw InputError("input_count exceeds the number of points");
  if (points.size() >= MeshTriangulation<D>::kMaxPoints) throw InputError("too many points for a mesh");
  // The first point that is not finite or repeats an earlier one. Duplicates are rare, so they are
  // looked for only when the triangulation merged some (no hash of every point on the way).
  auto reject = [&] {
    std::unordered_map<Point<D>, std::size_t, PointHash<D>> seen;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!finite<D>(points[i])) throw InputError("point " + std::to_string(i) + " is not finite", {}, i + 1);
      if (const auto [it, fresh] = seen.emplace(points[i], i); !fresh)
        throw InputError("point " + std::to_string(i) + " " + describe<D>(points[i]) + " repeats point " +
                             std::to_string(it->second),
                         {}, i + 1);
    }
  };
  if (!std::all_of(points.begin(), points.end(), [](const Point<D>& p) { return finite<D>(p); })) reject();
  points_.assign(points.begin(), points.end());
  kinds_.assign(points.size(), PointKind::Steiner);
  std::fill_n(kinds_.begin(), input_count, PointKind::Input);
  triangulation_ = std::make_unique<MeshTriangulation<D>>(domain_, covered_box_);
  if (!triangulation_->build(points_, domain_)) {
    triangulation_.reset();
    reject();
    throw std::logic_error("mesh: the triangulation merged points that are all distinct");
  }
  element_count_ = count_elements();
}

template <int D>
std::vector<Element<D>> Mesh<D>::elements() const {
  std::vector<Element<D>> out;
  const auto& t = *triangulation_;
  if (t.triangulation.dimension() < D) return out;
  out.reserve(element_count_);  // no doubling's slack: a list of the whole mesh's elements is large
  Cgal<D>::for_each_finite_face(t.triangulation, [&](auto f) {
    if (t.kept(f)) out.push_back(t.element(f));
  });
  return out;
}

namespace {
// The finite faces (cells) of t for which counts(f) holds, visiting every one.
template <int D, class F>
std::size_t count_faces(const MeshTriangulation<D>& t, F&& counts) {
  if (t.triangulation.dimension() < D) return 0;
  std::size_t n = 0;
  Cgal<D>::for_each_finite_face(t.triangulation, [&](auto f) { n += counts(f); });
  return n;
}
}  // namespace

template <int D>
std::size_t Mesh<D>::count_elements() const {
  const auto& t = *triangulation_;
  return count_faces<D>(t, [&](auto f) { return t.kept(f); });
}

template <int D>
std::size_t Mesh<D>::uncovered_count() const {
  const auto& t = *triangulation_;
  return count_faces<D>(t, [&](auto f) { return t.in_water(f) && !t.kept(f); });
}

template <int D>
const Domain2& Mesh<D>::domain() const {
  if (domain_source_) {
    domain_ = domain_source_();
    domain_source_ = nullptr;
  }
  return domain_;
}

template <int D>
MeshDelta<D> Mesh<D>::apply(const PointChange<D>& change) {
  return apply_with_water(change, nullptr, nullptr);
}

// The rings' change is local too: a point's side of the water (even-odd over the rings) changes only
// where the closed path made of a ring's old stretch and its new stretch winds around it an odd number
// of times, which is inside that path's bounding box (changed_water). Faces elsewhere keep their side,
// so only the faces meeting the box are classified again, and the mesh is not rebuilt.
template <int D>
MeshDelta<D> Mesh<D>::apply(const PointChange<D>& change, const Domain2& domain)
  requires(D == 2)
{
  return apply_with_water(change, &domain, nullptr);
}

template <int D>
MeshDelta<D> Mesh<D>::apply(const PointChange<D>& change, const ShoreChange& shore, std::function<Domain2()> domain)
  requires(D == 2)
{
  MeshDelta<D> delta = apply_with_water(change, nullptr, &shore);
  domain_source_ = std::move(domain);
  return delta;
}

template <int D>
std::vector<std::pair<Point2, Point2>> Mesh<D>::constrained_edges() const
  requires(D == 2)
{
  const auto& t = *triangulation_;
  std::vector<std::pair<Point2, Point2>> out;
  for (const auto& e : t.triangulation.constrained_edges()) {
    const auto& [f, i] = e;
    const Point2 a = Cgal<2>::from_cgal(f->vertex(t.triangulation.cw(i))->point());
    const Point2 b = Cgal<2>::from_cgal(f->vertex(t.triangulation.ccw(i))->point());
    out.push_back(std::minmax(a, b));
  }
  std::sort(out.begin(), out.end());
  return out;
}

template <int D>
MeshDelta<D> Mesh<D>::apply_with_water(const PointChange<D>& change, const Domain2* domain, const ShoreChange* shore) {
  auto& t = *triangulation_;
  t.vertex_of();  // made before the triangulation changes
  // From the rings before the change (asked only the first time: domain() may have a refinement to make).
  if constexpr (D == 2)
    if (!t.segment_ends_made) t.make_segment_ends(this->domain());
  // Validate everything first, so that a bad change leaves the mesh as it was.
  if (change.added_input_count > change.added.size())
    throw InputError("added_input_count exceeds the number of added points");
  PointMap<D, bool> removed, added;  // the points named so far (true)
  removed.reserve(change.removed.size());
  added.reserve(change.added.size());
  for (std::size_t i = 0; i < change.removed.size(); ++i) {
    const Point<D>& p = change.removed[i];
    if (!t.vertex_of().contains(p)) throw InputError("removed point " + describe<D>(p) + " is not in the mesh", {}, i + 1);
    if (!removed.emplace(p, true)) throw InputError("removed point " + describe<D>(p) + " is given twice", {}, i + 1);
  }
  for (std::size_t i = 0; i < change.added.size(); ++i) {
    const Point<D>& p = change.added[i];
    if (!finite<D>(p)) throw InputError("added point " + std::to_string(i) + " is not finite", {}, i + 1);
    if (t.vertex_of().contains(p) && !removed.contains(p))
      throw InputError("added point " + describe<D>(p) + " is already in the mesh", {}, i + 1);
    if (!added.emplace(p, true)) throw InputError("added point " + describe<D>(p) + " is given twice", {}, i + 1);
  }

  if (points_.size() + change.added.size() - change.removed.size() >= MeshTriangulation<D>::kMaxPoints)
    throw InputError("too many points for a mesh");
  std::optional<ChangedWater> water;
  std::vector<std::pair<Point2, Point2>> dropped, inserted;  // shore segments that went and came
  if constexpr (D == 2) {
    if (domain) {
      const Domain2& before = this->domain();
      water = changed_water(before, *domain);
      changed_segments(before, *domain, *water, dropped, inserted);
      // The faces the change creates are classified against the new rings.
      t.update_water(before, *domain, *water);
      domain_ = *domain;
    } else if (shore) {
      for (const ShoreSegment& s : shore->removed) dropped.emplace_back(s.a, s.b);
      for (const ShoreSegment& s : shore->added) inserted.emplace_back(s.a, s.b);
      t.update_water(*shore);
    }
  }
  typename MeshTriangulation<D>::Accumulator acc;
  // Whether a point was a segment's end before the change (the segments' ends are counted after the
  // removals).
  std::function<bool(const Point2&)> ring_vertex;
  if constexpr (D == 2) ring_vertex = [&](const Point2& p) { return t.segment_end(p); };
  if constexpr (D == 2) t.defer_classification(true);
  struct StopDeferring {  // also when a change throws half-way
    MeshTriangulation<D>& t;
    ~StopDeferring() {
      if constexpr (D == 2) t.defer_classification(false);
    }
  } stop_deferring{t};
  for (const Point<D>& p : change.removed) t.remove(p, points_, kinds_, acc, ring_vertex);
  if constexpr (D == 2) {
    for (const auto& [a, b] : dropped) t.count_segment(a, b, -1);
    for (const auto& [a, b] : inserted) t.count_segment(a, b, 1);
    t.drop_constraints(dropped, acc);
  }
  for (std::size_t i = 0; i < change.added.size(); ++i)
    t.insert(change.added[i], i < change.added_input_count ? PointKind::Input : PointKind::Steiner, points_, kinds_, acc);
  if constexpr (D == 2) t.add_constraints(inserted, acc);
  if constexpr (D == 2) t.classify_pending(acc);
  if constexpr (D == 2) {
    if (water && water->changed) t.reclassify_within(water->lo, water->hi, water->seed, acc);
    if (shore) t.reclassify_changed(*shore, acc);
  }
  if constexpr (D == 2) {
    if (t.canonical_ties) t.flip_ties(std::vector<ElementCorners<2>>(acc.born), acc);
  }
  MeshDelta<D> delta = acc.net();
  element_count_ = element_count_ + delta.added.size() - delta.removed.size();
  return delta;
}

template <int D>
std::vector<ElementCorners<2>> Mesh<D>::elements_meeting(const Point2& lo, const Point2& hi) const
  requires(D == 2)
{
  auto& t = *triangulation_;
  std::vector<ElementCorners<2>> out;
  if (t.triangulation.dimension() < 2) return out;
  auto take = [&](auto f) {
    if (t.kept(f)) out.push_back(t.key(f));
  };
  if (!t.for_each_face_meeting(lo, hi, {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])}, take)) {
    Cgal<2>::for_each_finite_face(t.triangulation, [&](auto f) {  // the box's centre outside the hull
      const auto k = t.key(f);
      for (int i = 0; i < 2; ++i) {
        const double f_lo = std::min({k[0][i], k[1][i], k[2][i]}), f_hi = std::max({k[0][i], k[1][i], k[2][i]});
        if (f_hi < lo[i] || f_lo > hi[i]) return;
      }
      take(f);
    });
  }
  return out;
}

template <int D>
void Mesh<D>::canonicalize_ties()
  requires(D == 2)
{
  auto& t = *triangulation_;
  t.canonical_ties = true;
  typename MeshTriangulation<D>::Accumulator acc;  // flips keep the count: a tie's quadrilateral is in the water
  const std::set<ElementCorners<2>> kept = t.all_keys();
  t.flip_ties(std::vector<ElementCorners<2>>(kept.begin(), kept.end()), acc);
}

template <int D>
QualityReport<D> Mesh<D>::quality(double rho, std::optional<BoxTransform<D>> box) const {
  const std::vector<Element<D>> e = elements();
  return quality_report<D>(points_, e, rho, box);
}

template <int D>
void Mesh<D>::check_valid() const {
  const auto& t = *triangulation_;
  if (!t.triangulation.is_valid()) throw std::logic_error("mesh: CGAL triangulation is not valid");
  if (t.triangulation.number_of_vertices() != points_.size() || t.vertex_of().size() != points_.size() ||
      kinds_.size() != points_.size())
    throw std::logic_error("mesh: vertex count, vertex map and point list disagree");
  for (auto v : t.triangulation.finite_vertex_handles()) {
    const std::uint32_t i = v->info();
    if (i >= points_.size() || points_[i] != Cgal<D>::from_cgal(v->point()))
      throw std::logic_error("mesh: vertex " + describe<D>(Cgal<D>::from_cgal(v->point())) + " has a stale index");
  }
  if (element_count_ != count_elements())
    throw std::logic_error("mesh: element count " + std::to_string(element_count_) + ", but " +
                           std::to_string(count_elements()) + " elements in the water");
}

// Walks each ring segment a->b through the triangulation: along mesh edges lying on it while there are
// some, otherwise across the triangles it passes through, counting the edges it crosses. Every decision is
// an exact orientation test.
template <int D>
ShorelineReport Mesh<D>::shoreline_crossings() const
  requires(D == 2)
{
  using C = Cgal<2>;
  const auto& t = *triangulation_;
  const auto& dt = t.triangulation;
  ShorelineReport report;
  auto segment_distance = [](const Kernel::Point_2& a, const Kernel::Point_2& b, const Kernel::Point_2& p) {
    return std::sqrt(CGAL::to_double(CGAL::squared_distance(Kernel::Segment_2(a, b), p)));
  };

  const Domain2& domain = this->domain();
  // The rings' vertices: from the map of every vertex when updates have made it, else by one pass.
  PointTable<C::Vertex> ring_vertex;
  if (!t.has_vertex_map()) ring_vertex = t.vertices_at(domain);
  auto vertex_at = [&](const Point2& p) {
    if (!t.has_vertex_map()) return ring_vertex.at(p);
    const C::Vertex* v = t.vertex_of().find(p);
    return v ? *v : C::Vertex();
  };
  // Each segment on its own (the walks only read the triangulation), on every thread; the issues in the
  // rings' order, the counts summed, whatever the split.
  std::vector<std::size_t> first_segment(domain.rings.size() + 1, 0);  // ring r's segments: a flat range
  for (std::size_t r = 0; r < domain.rings.size(); ++r)
    first_segment[r + 1] = first_segment[r] + domain.rings[r].segment_count();
  auto check = [&](std::size_t r, std::size_t s, ShorelineReport& out) {
    const auto& ring = domain.rings[r].points;
    {
      const Point2& a = ring[s];
      const Point2& b = ring[(s + 1) % ring.size()];
      if (a == b) return;
      ++out.segments;
      ShoreSegmentIssue issue;
      issue.ring = r, issue.segment = s, issue.a = a, issue.b = b;
      const auto pa = C::to_cgal(a), pb = C::to_cgal(b);
      const C::Vertex va = vertex_at(a), vb = vertex_at(b);
      if (va == C::Vertex() || vb == C::Vertex() || dt.dimension() < 2) {
        issue.endpoint_missing = true;
        for (const auto& p : {pa, pb})
          if (vertex_at(C::from_cgal(p)) == C::Vertex()) {
            double nearest = std::numeric_limits<double>::infinity();
            for (const Point2& q : points_) nearest = std::min(nearest, std::hypot(q[0] - p.x(), q[1] - p.y()));
            if (!points_.empty()) issue.depth = std::max(issue.depth, nearest);
          }
        out.issues.push_back(issue);
        return;
      }
      auto v = va;
      bool uncovered = false;
      std::vector<C::Face> passed;
      while (v != vb) {
        // The segment a mesh edge (no vertex of the triangulation lies inside an edge of it).
        if (dt.is_edge(v, vb)) {
          v = vb;
          continue;
        }
        // A mesh edge from v along the segment towards b?
        C::Vertex next;
        for (auto w : C::adjacent_finite_vertices(dt, v))
          if (w == vb || (CGAL::orientation(pa, pb, w->point()) == CGAL::COLLINEAR &&
                          CGAL::collinear_are_strictly_ordered_along_line(v->point(), w->point(), pb))) {
            next = w;
            break;
          }
        if (next != C::Vertex()) {
          v = next;
          continue;
        }
        uncovered = true;
        // The triangle (v, p, q) at v whose angle the segment enters: b left of v->p and right of v->q.
        C::Face f;
        C::Vertex p, q;
        C::for_each_incident_finite_face(dt, v, [&](C::Face g) {
          const int i = g->index(v);
          const auto gp = g->vertex(dt.ccw(i)), gq = g->vertex(dt.cw(i));
          if (CGAL::orientation(v->point(), gp->point(), pb) == CGAL::LEFT_TURN &&
              CGAL::orientation(v->point(), gq->point(), pb) == CGAL::RIGHT_TURN)
            f = g, p = gp, q = gq;
        });
        if (f == C::Face()) throw std::logic_error("shoreline walk: no triangle at a ring vertex contains the segment");
        // Cross edges (p, q), p right and q left of the line, until a vertex on the segment is reached.
        C::Vertex behind = v;
        while (true) {
          passed.push_back(f);
          ++issue.crossing_edges;
          issue.depth = std::max(issue.depth, std::min(segment_distance(pa, pb, p->point()),
                                                       segment_distance(pa, pb, q->point())));
          const C::Face g = f->neighbor(f->index(behind));
          if (dt.is_infinite(g)) throw std::logic_error("shoreline walk left the convex hull");
          passed.push_back(g);
          const auto w = g->vertex(3 - g->index(p) - g->index(q));
          const CGAL::Orientation o = CGAL::orientation(pa, pb, w->point());
          if (w == vb || o == CGAL::COLLINEAR) {
            v = w;
            break;
          }
          if (o == CGAL::LEFT_TURN) behind = q, q = w;
          else behind = p, p = w;
          f = g;
        }
      }
      if (!uncovered) {
        ++out.covered;
        return;
      }
      std::sort(passed.begin(), passed.end());
      passed.erase(std::unique(passed.begin(), passed.end()), passed.end());
      for (C::Face f : passed)
        if (t.kept(f)) issue.crossing_elements.push_back(t.element(f));
      out.issues.push_back(std::move(issue));
    }
  };
  report = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, first_segment.back(), 4096), ShorelineReport{},
      [&](const tbb::blocked_range<std::size_t>& range, ShorelineReport part) {
        std::size_t r = static_cast<std::size_t>(
            std::upper_bound(first_segment.begin(), first_segment.end(), range.begin()) - first_segment.begin() - 1);
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          while (k >= first_segment[r + 1]) ++r;
          check(r, k - first_segment[r], part);
        }
        return part;
      },
      [](ShorelineReport x, ShorelineReport y) {
        x.segments += y.segments;
        x.covered += y.covered;
        x.issues.insert(x.issues.end(), std::make_move_iterator(y.issues.begin()), std::make_move_iterator(y.issues.end()));
        return x;
      });
  for (const auto& issue : report.issues) report.worst_depth = std::max(report.worst_depth, issue.depth);
  return report;
}

std::string ShorelineReport::summary() const {
  std::string s = std::to_string(covered) + " of " + std::to_string(segments) + " shore segments are mesh edges";
  if (ok()) return s + "\n";
  s += "; the sampling is too coarse along " + std::to_string(issues.size()) +
       " segments: mesh edges reach up to " + std::to_string(worst_depth) + " across the shoreline\n";
  for (const auto& i : issues) {
    s += "  ring " + std::to_string(i.ring) + " segment " + std::to_string(i.segment) + " " + describe<2>(i.a) +
         "-" + describe<2>(i.b) + ": ";
    s += i.endpoint_missing ? "an end is not a mesh point (" + std::to_string(i.depth) + " from the nearest)"
                            : std::to_string(i.crossing_edges) + " crossing edges, depth " + std::to_string(i.depth);
    s += "\n";
  }
  return s;
}

template class Mesh<2>;
template class Mesh<3>;

}  // namespace shoremesh
