// OBJ, PLY (ASCII) and OFF: triangle surfaces for general 3D viewers. In 2D the mesh's triangles at z = 0
// (at the nodes' heights for a terrain);
// in 3D the boundary triangles of the tetrahedra, oriented outwards.
#include <string>
#include <vector>

#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/export_text.hpp"

namespace shoremesh::io {

template <int D>
void write_surface(const std::filesystem::path& path, const MeshView<D>& view, ExportFormat format) {
  std::vector<std::array<std::uint32_t, 3>> faces;
  if constexpr (D == 2) faces.assign(view.elements.begin(), view.elements.end());
  else faces = boundary_faces(view.elements);
  write_atomically(path, [&](std::ostream& out) {
    std::string s;
    const std::size_t np = view.points.size(), nf = faces.size();
    if (format == ExportFormat::Ply)
      append(s, "ply\nformat ascii 1.0\ncomment shoremesh mesh\nelement vertex ", np,
             "\nproperty double x\nproperty double y\nproperty double z\nelement face ", nf,
             "\nproperty list uchar int vertex_indices\nend_header\n");
    else if (format == ExportFormat::Off)
      append(s, "OFF\n", np, ' ', nf, " 0\n");
    else
      s += "# shoremesh mesh\n";
    for (std::size_t n = 0; n < np; ++n) {
      if (format == ExportFormat::Obj) s += "v ";
      for (int i = 0; i < 3; ++i) append_number(s, node_coordinate(view, n, i)), s += i < 2 ? ' ' : '\n';
    }
    for (const auto& f : faces) {
      // OBJ counts from 1, PLY and OFF from 0 with the corner count first.
      if (format == ExportFormat::Obj) append(s, "f ", f[0] + 1, ' ', f[1] + 1, ' ', f[2] + 1, '\n');
      else append(s, "3 ", f[0], ' ', f[1], ' ', f[2], '\n');
    }
    out << s;
  });
}

template void write_surface<2>(const std::filesystem::path&, const MeshView<2>&, ExportFormat);
template void write_surface<3>(const std::filesystem::path&, const MeshView<3>&, ExportFormat);

}  // namespace shoremesh::io
