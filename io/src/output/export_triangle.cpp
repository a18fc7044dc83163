// Shewchuk's Triangle .node/.ele (2D) and TetGen's (3D, the same layout with 3 coordinates and 4 corners).
// Numbering starts at 1. Each node carries one boundary marker: 0 inside, 1 on a shore loop, 2 on an
// island loop (2D). Both files are written to temporaries first and renamed only when both are complete.
#include <string>
#include <vector>

#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/export_text.hpp"

namespace shoremesh::io {

template <int D>
void write_triangle(const std::filesystem::path& node_path, const MeshView<D>& view) {
  std::filesystem::path ele_path = node_path;
  ele_path.replace_extension(".ele");
  std::vector<int> marker(view.points.size(), 0);
  for (const BoundaryLoop& loop : view.boundary)
    for (auto n : loop.nodes) marker[n] = loop.role == RingRole::Shore ? 1 : 2;

  AtomicFile node(node_path), ele(ele_path);
  std::string s;
  append(s, view.points.size(), ' ', D, " 0 1\n");
  for (std::size_t i = 0; i < view.points.size(); ++i) {
    append(s, i + 1);
    for (int k = 0; k < D; ++k) append(s, ' ', view.points[i][k]);
    append(s, ' ', marker[i], '\n');
  }
  node.stream() << s;
  s.clear();
  append(s, view.elements.size(), ' ', D + 1, " 0\n");
  for (std::size_t i = 0; i < view.elements.size(); ++i) {
    append(s, i + 1);
    for (auto n : view.elements[i]) append(s, ' ', n + 1);
    s += '\n';
  }
  ele.stream() << s;
  node.commit();
  ele.commit();
}

template void write_triangle<2>(const std::filesystem::path&, const MeshView<2>&);
template void write_triangle<3>(const std::filesystem::path&, const MeshView<3>&);

}  // namespace shoremesh::io
