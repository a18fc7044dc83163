// Gmsh MSH 4.1 (ASCII). 2D: one surface entity "water" with the triangles, one curve entity per boundary
// loop carrying its edges, in the physical group "shore" or "island". 3D: one volume entity "domain" with
// the tetrahedra and one surface entity "boundary" with the boundary triangles. All nodes are listed in
// the block of the top entity; Gmsh and meshio find nodes by tag, wherever they are listed. Depths, when
// the view has them, follow as the node field "depth" ($NodeData).
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/export_text.hpp"

namespace shoremesh::io {

namespace {

enum : int { kLine = 1, kTriangle = 2, kTetrahedron = 4 };

// One entity's elements: its own flat list (`arity` node indices each, 0-based; a vector per element cost
// 40 bytes and an allocation for each of a 600k-triangle mesh), or the view's elements read in place
// (the top entity's: a copy of them held another 8 MB at Lake Superior while the summary ran beside).
template <int D>
struct Block {
  int dim = 0, entity = 0, physical = 0, type = 0;
  std::size_t arity = 0;
  std::vector<std::uint32_t> own;
  std::span<const Element<D>> elements;  // when not empty, the block's elements (arity D + 1)
  std::size_t size() const { return elements.empty() ? own.size() / arity : elements.size(); }
  std::uint32_t node(std::size_t k, std::size_t j) const { return elements.empty() ? own[k * arity + j] : elements[k][j]; }
  template <class Nodes>
  void push(const Nodes& e) {
    own.insert(own.end(), std::begin(e), std::end(e));
  }
};

// The text goes to the stream in pieces of about this many bytes, not as one string of the whole file.
constexpr std::size_t kFlushBytes = std::size_t(1) << 20;

template <int D>
std::string bounding_box(const MeshView<D>& view, const Block<D>& b) {
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  if (b.size() != 0) {
    // The coordinates the nodes have: a 2D mesh without heights lies at z = 0, whose box is 0 .. 0.
    for (int i = 0; i < 3; ++i) lo[i] = std::numeric_limits<double>::infinity(), hi[i] = -lo[i];
    for (std::size_t k = 0; k < b.size(); ++k)
      for (std::size_t j = 0; j < b.arity; ++j) {
        const std::uint32_t n = b.node(k, j);
        for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], node_coordinate(view, n, i)), hi[i] = std::max(hi[i], node_coordinate(view, n, i));
      }
  }
  std::string s;
  for (double x : lo) append_number(s, x), s += ' ';
  for (double x : hi) append_number(s, x), s += ' ';
  return s;
}

}  // namespace

template <int D>
void write_gmsh(const std::filesystem::path& path, const MeshView<D>& view) {
  // Physical tags are per dimension; names make them readable in Gmsh and meshio's cell_sets.
  std::vector<Block<D>> blocks;
  std::vector<std::string> physical_names;
  if constexpr (D == 2) {
    const bool shore = std::any_of(view.boundary.begin(), view.boundary.end(), [](auto& l) { return l.role == RingRole::Shore; });
    const bool island = std::any_of(view.boundary.begin(), view.boundary.end(), [](auto& l) { return l.role == RingRole::Island; });
    if (shore) physical_names.push_back("1 1 \"shore\"");
    if (island) physical_names.push_back("1 2 \"island\"");
    physical_names.push_back("2 3 \"water\"");
    int curve = 0;
    for (const BoundaryLoop& loop : view.boundary) {
      Block<D> b{1, ++curve, loop.role == RingRole::Shore ? 1 : 2, kLine, 2, {}, {}};
      for (std::size_t i = 0; i < loop.nodes.size(); ++i)
        b.push(std::array<std::uint32_t, 2>{loop.nodes[i], loop.nodes[(i + 1) % loop.nodes.size()]});
      blocks.push_back(std::move(b));
    }
    blocks.push_back(Block<D>{2, 1, 3, kTriangle, 3, {}, view.elements});
  } else {
    physical_names.push_back("2 1 \"boundary\"");
    physical_names.push_back("3 2 \"domain\"");
    Block<D> boundary{2, 1, 1, kTriangle, 3, {}, {}};
    for (const auto& f : boundary_faces(view.elements)) boundary.push(f);
    blocks.push_back(std::move(boundary));
    blocks.push_back(Block<D>{3, 1, 2, kTetrahedron, 4, {}, view.elements});
  }

  write_atomically(path, [&](std::ostream& out) {
    std::string s;
    append(s, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n", physical_names.size(), '\n');
    for (const auto& n : physical_names) append(s, n, '\n');
    s += "$EndPhysicalNames\n$Entities\n";
    // Entity counts: points, curves, surfaces, volumes.
    std::array<int, 4> count{0, 0, 0, 0};
    for (const Block<D>& b : blocks) ++count[b.dim];
    append(s, "0 ", count[1], ' ', count[2], ' ', count[3], '\n');
    for (int dim = 1; dim <= 3; ++dim)
      for (const Block<D>& b : blocks) {
        if (b.dim != dim) continue;
        append(s, b.entity, ' ', bounding_box<D>(view, b), "1 ", b.physical);
        if (dim == 1) {
          s += " 0\n";  // closed loops: no bounding points
        } else {
          // The bounding entities of the top entity: every entity one dimension lower.
          std::string bounds;
          int n = 0;
          for (const Block<D>& c : blocks)
            if (c.dim == dim - 1) ++n, append(bounds, ' ', c.entity);
          append(s, ' ', n, bounds, '\n');
        }
      }
    s += "$EndEntities\n$Nodes\n";
    const std::size_t np = view.points.size();
    append(s, "1 ", np, " 1 ", np, '\n');
    append(s, D, " 1 0 ", np, '\n');
    auto flush = [&](std::size_t at_least) {
      if (s.size() < at_least) return;
      out << s;
      s.clear();
    };
    for (std::size_t i = 1; i <= np; ++i) append(s, i, '\n'), flush(kFlushBytes);
    for (std::size_t n = 0; n < np; ++n) {
      for (int i = 0; i < 3; ++i) {
        append_number(s, node_coordinate(view, n, i));
        s += i < 2 ? ' ' : '\n';
      }
      flush(kFlushBytes);
    }
    s += "$EndNodes\n$Elements\n";
    std::size_t total = 0;
    for (const Block<D>& b : blocks) total += b.size();
    append(s, blocks.size(), ' ', total, " 1 ", total, '\n');
    std::size_t tag = 0;
    for (const Block<D>& b : blocks) {
      append(s, b.dim, ' ', b.entity, ' ', b.type, ' ', b.size(), '\n');
      for (std::size_t k = 0; k < b.size(); ++k) {
        append(s, ++tag);
        for (std::size_t j = 0; j < b.arity; ++j) append(s, ' ', b.node(k, j) + 1);
        s += '\n';
        flush(kFlushBytes);
      }
    }
    s += "$EndElements\n";
    if (!view.depths.empty()) {
      // The depths as a node field (string tag "depth", one real tag: time 0, three integer tags: step 0,
      // one component, the node count).
      append(s, "$NodeData\n1\n\"depth\"\n1\n0\n3\n0\n1\n", np, '\n');
      for (std::size_t i = 0; i < np; ++i) {
        append(s, i + 1, ' '), append_number(s, view.depths[i]), s += '\n';
        flush(kFlushBytes);
      }
      s += "$EndNodeData\n";
    }
    out << s;
  });
}

template void write_gmsh<2>(const std::filesystem::path&, const MeshView<2>&);
template void write_gmsh<3>(const std::filesystem::path&, const MeshView<3>&);

}  // namespace shoremesh::io
