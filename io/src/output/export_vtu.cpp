// VTK XML unstructured grid (.vtu), ASCII: points in 3 components, triangles (VTK type 5) or tetrahedra
// (type 10), point arrays "input" (1 for input points, 0 for Steiner points), "depth" and "height" (when
// the view has them; a terrain's height is also the points' z) and per-element quality
// ("radius_edge", "min_angle") so that ParaView can colour by them.
#include <string>

#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/export_text.hpp"
#include "shoremesh/mesh_quality.hpp"

namespace shoremesh::io {

template <int D>
void write_vtu(const std::filesystem::path& path, const MeshView<D>& view) {
  write_atomically(path, [&](std::ostream& out) {
    std::string s;
    append(s,
           "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"",
           view.points.size(), "\" NumberOfCells=\"", view.elements.size(), "\">\n");
    s += "<PointData>\n<DataArray type=\"Int32\" Name=\"input\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < view.points.size(); ++i)
      s += view.kinds.empty() || view.kinds[i] == PointKind::Input ? "1\n" : "0\n";
    s += "</DataArray>\n";
    if (!view.depths.empty()) {
      s += "<DataArray type=\"Float64\" Name=\"depth\" format=\"ascii\">\n";
      for (double d : view.depths) append_number(s, d), s += '\n';
      s += "</DataArray>\n";
    }
    if (!view.heights.empty()) {
      s += "<DataArray type=\"Float64\" Name=\"height\" format=\"ascii\">\n";
      for (double h : view.heights) append_number(s, h), s += '\n';
      s += "</DataArray>\n";
    }
    s += "</PointData>\n<CellData>\n";
    std::string radius_edge, min_angle;
    for (const auto& e : view.elements) {
      ElementCorners<D> c;
      for (int i = 0; i <= D; ++i) c[i] = view.points[e[i]];
      const ElementShape<D> shape = element_shape<D>(c);
      append_number(radius_edge, shape.radius_edge), radius_edge += '\n';
      append_number(min_angle, shape.min_angle), min_angle += '\n';
    }
    append(s, "<DataArray type=\"Float64\" Name=\"radius_edge\" format=\"ascii\">\n", radius_edge, "</DataArray>\n");
    append(s, "<DataArray type=\"Float64\" Name=\"min_angle\" format=\"ascii\">\n", min_angle, "</DataArray>\n");
    s += "</CellData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    out << s;
    s.clear();
    for (std::size_t n = 0; n < view.points.size(); ++n) {
      for (int i = 0; i < 3; ++i) append_number(s, node_coordinate(view, n, i)), s += i < 2 ? ' ' : '\n';
    }
    s += "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& e : view.elements) {
      for (int i = 0; i <= D; ++i) append(s, e[i], i < D ? ' ' : '\n');
    }
    s += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t i = 1; i <= view.elements.size(); ++i) append(s, i * (D + 1), '\n');
    s += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    const std::string type = D == 2 ? "5\n" : "10\n";
    for (std::size_t i = 0; i < view.elements.size(); ++i) s += type;
    s += "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    out << s;
  });
}

template void write_vtu<2>(const std::filesystem::path&, const MeshView<2>&);
template void write_vtu<3>(const std::filesystem::path&, const MeshView<3>&);

}  // namespace shoremesh::io
