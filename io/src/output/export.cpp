// The export entry point: the snapshot of a mesh, the format from a file name, and the dispatch.
#include "shoremesh/io/export.hpp"

#include <algorithm>
#include <cctype>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "shoremesh/error.hpp"

namespace shoremesh::io {

namespace {
// The points no kept element uses (the box fill on land, beyond the shore) are not part of the mesh:
// drop them and renumber, keeping the order of the rest.
template <int D>
void drop_unused_points(std::vector<Point<D>>& points, std::vector<Element<D>>& elements, std::vector<PointKind>& kinds) {
  if (elements.empty()) return;
  constexpr std::uint32_t unused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> renumber(points.size(), unused);
  for (const auto& e : elements)
    for (auto i : e) renumber[i] = 0;
  std::uint32_t next = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (renumber[i] != unused) {
      renumber[i] = next;
      points[next] = points[i];
      if (!kinds.empty()) kinds[next] = kinds[i];
      ++next;
    }
  points.resize(next);
  if (!kinds.empty()) kinds.resize(next);
  for (auto& e : elements)
    for (auto& i : e) i = renumber[i];
}

// Renumbers the points to the order of `order` (a permutation of them): matched by sorting both.
template <int D>
void renumber_to(std::vector<Point<D>>& points, std::vector<Element<D>>& elements, std::vector<PointKind>& kinds,
                 std::span<const Point<D>> order) {
  if (order.size() != points.size())
    throw std::logic_error("export order names " + std::to_string(order.size()) + " points, the mesh has " +
                           std::to_string(points.size()));
  auto sorted_indices = [](auto list) {
    std::vector<std::uint32_t> idx(list.size());
    std::iota(idx.begin(), idx.end(), 0u);
    std::sort(idx.begin(), idx.end(), [&](std::uint32_t a, std::uint32_t b) { return list[a] < list[b]; });
    return idx;
  };
  const auto by_place = sorted_indices(std::span<const Point<D>>(points));
  const auto order_by_place = sorted_indices(order);
  std::vector<std::uint32_t> new_index(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (points[by_place[k]] != order[order_by_place[k]])
      throw std::logic_error("export order is not a permutation of the mesh's points");
    new_index[by_place[k]] = order_by_place[k];
  }
  std::vector<PointKind> new_kinds(kinds.size());
  for (std::size_t i = 0; i < kinds.size(); ++i) new_kinds[new_index[i]] = kinds[i];
  points.assign(order.begin(), order.end());
  kinds = std::move(new_kinds);
  for (auto& e : elements)
    for (auto& i : e) i = new_index[i];
}

// Turns an element to start at its smallest index, keeping its orientation: a rotation of a triangle; for
// a tetrahedron, an even permutation (two swaps), then a rotation of the last three.
template <int D>
Element<D> canonical(Element<D> e) {
  const auto first = std::min_element(e.begin(), e.end()) - e.begin();
  if constexpr (D == 2) {
    std::rotate(e.begin(), e.begin() + first, e.end());
  } else {
    if (first != 0) {
      std::swap(e[0], e[std::size_t(first)]);
      // A second swap of two of the other three keeps the permutation even.
      if (first == 1) std::swap(e[2], e[3]);
      else if (first == 2) std::swap(e[1], e[3]);
      else std::swap(e[1], e[2]);
    }
    std::rotate(e.begin() + 1, std::min_element(e.begin() + 1, e.end()), e.end());
  }
  return e;
}

// Whether the elements use each of `count` points.
template <int D>
bool every_point_used(std::size_t count, const std::vector<Element<D>>& elements) {
  std::vector<bool> used(count, false);
  for (const auto& e : elements)
    for (auto i : e) used[i] = true;
  return std::find(used.begin(), used.end(), false) == used.end();
}
}  // namespace

template <int D>
MeshSnapshot<D>::MeshSnapshot(const Mesh<D>& mesh, std::span<const Point<D>> order, bool in_place)
    : elements_(mesh.elements()) {
  // Every point kept where it is (a mesh of the water alone, written without an edit session's order).
  in_place = in_place && order.empty() && !elements_.empty() && every_point_used<D>(mesh.points().size(), elements_);
  if (in_place) {
    mesh_points_ = &mesh.points();
    mesh_kinds_ = &mesh.kinds();
  } else {
    points_ = mesh.points();
    kinds_ = mesh.kinds();
    if (!order.empty()) renumber_to<D>(points_, elements_, kinds_, order);
  }
  for (auto& e : elements_) e = canonical<D>(e);
  std::sort(elements_.begin(), elements_.end());
  if (!in_place) drop_unused_points<D>(points_, elements_, kinds_);
  if constexpr (D == 2) boundary_ = boundary_loops(points(), elements_);
}

template <int D>
MeshSnapshot<D>::MeshSnapshot(std::vector<Point<D>> points, std::vector<Element<D>> elements,
                              std::vector<PointKind> kinds)
    : points_(std::move(points)), elements_(std::move(elements)), kinds_(std::move(kinds)) {
  if constexpr (D == 2) boundary_ = boundary_loops(points_, elements_);
}

template <int D>
MeshView<D> MeshSnapshot<D>::view() const {
  MeshView<D> v;
  v.points = points();
  v.elements = elements_;
  v.kinds = kinds();
  v.boundary = boundary_;
  return v;
}

template <int D>
MeshView<D> MeshSnapshot<D>::view(std::function<Point2(const Point2&)> to_lonlat) const {
  MeshView<D> v = view();
  v.to_lonlat = std::move(to_lonlat);
  return v;
}

ExportFormat export_format_from_path(const std::filesystem::path& path) {
  auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
  };
  const std::string name = lower(path.filename().string());
  const std::string ext = lower(path.extension().string());
  if (ext == ".msh") return ExportFormat::Gmsh;
  if (ext == ".vtu") return ExportFormat::Vtu;
  if (ext == ".node" || ext == ".ele") return ExportFormat::Triangle;
  if (name == "fort.14" || ext == ".14" || ext == ".fort14") return ExportFormat::Adcirc;
  if (ext == ".geojson" || ext == ".json") return ExportFormat::GeoJson;
  if (ext == ".obj") return ExportFormat::Obj;
  if (ext == ".ply") return ExportFormat::Ply;
  if (ext == ".off") return ExportFormat::Off;
  throw InputError("unknown mesh format (expected .msh, .vtu, .node, fort.14, .geojson, .obj, .ply or .off)",
                   path.string());
}

template <int D>
void export_mesh(const std::filesystem::path& path, const MeshView<D>& view, std::optional<ExportFormat> format) {
  for (const auto& e : view.elements)
    for (auto i : e)
      if (i >= view.points.size()) throw InputError("an element refers to a point that does not exist", path.string());
  const ExportFormat chosen = format ? *format : export_format_from_path(path);  // the path only when not given
  switch (chosen) {
    case ExportFormat::Gmsh: return write_gmsh<D>(path, view);
    case ExportFormat::Vtu: return write_vtu<D>(path, view);
    case ExportFormat::Triangle: {
      std::filesystem::path node = path;
      return write_triangle<D>(node.replace_extension(".node"), view);
    }
    case ExportFormat::Adcirc:
    case ExportFormat::GeoJson:
      if constexpr (D == 2) {
        if (chosen == ExportFormat::Adcirc) return write_adcirc(path, view);
        return write_geojson(path, view);
      } else {
        throw InputError("fort.14 and GeoJSON exports are 2D only", path.string());
      }
    case ExportFormat::Obj:
    case ExportFormat::Ply:
    case ExportFormat::Off: return write_surface<D>(path, view, chosen);
  }
}

template class MeshSnapshot<2>;
template class MeshSnapshot<3>;
template void export_mesh<2>(const std::filesystem::path&, const MeshView<2>&, std::optional<ExportFormat>);
template void export_mesh<3>(const std::filesystem::path&, const MeshView<3>&, std::optional<ExportFormat>);

}  // namespace shoremesh::io
