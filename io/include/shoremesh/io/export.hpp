#pragma once
// Mesh exports: Gmsh .msh 4.1, VTK .vtu, Triangle/TetGen .node+.ele, ADCIRC fort.14, GeoJSON, and OBJ, PLY
// and OFF surfaces. Every file is written atomically (io/atomic_file.hpp). Coordinates are written as
// given, in the metric coordinates the engine meshed in (metres for geographic inputs), where the angle
// guarantee holds; only GeoJSON (and fort.14, which ADCIRC reads in degrees) go through to_lonlat.
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "shoremesh/mesh.hpp"
#include "shoremesh/mesh_boundary.hpp"

namespace shoremesh::io {

// What a writer reads: spans into storage the caller keeps alive (MeshSnapshot keeps it for a Mesh).
template <int D>
struct MeshView {
  std::span<const Point<D>> points;
  std::span<const Element<D>> elements;
  std::span<const PointKind> kinds;          // per point; empty means every point is an input point
  std::span<const BoundaryLoop> boundary;    // 2D: closed loops of nodes with their role (shore, island)
  // 2D geographic inputs: the inverse of the projection the engine meshed in, metric -> {lon, lat} degrees.
  std::function<Point2(const Point2&)> to_lonlat;
  // ADCIRC: depth below the datum at a node (positive down); without it (and without `depths`) the depth
  // column is 0.
  std::function<double(const Point<D>&)> depth;
  // Depths at the nodes, positive down, parallel to `points` (empty: none): fort.14's depth column (before
  // `depth`), a "depth" node field in .msh and .vtu, the corners' depths in GeoJSON.
  std::span<const double> depths;
  // 2D terrains: heights at the nodes, positive up, parallel to `points` (empty: none). They become the
  // nodes' z in .msh, .vtu, OBJ, PLY and OFF, and each GeoJSON position's third coordinate (RFC 7946).
  std::span<const double> heights;
  // 2D: per node, 1 where the water leaves the data (a DEM's or image's edge; every node of a mesh without
  // rings, which ends at the box); a boundary edge between two such nodes
  // is an open boundary in fort.14 (empty: none).
  std::span<const std::uint8_t> open_nodes;
};

// Coordinate i (0, 1, 2) of node n as the writers write it: the point's, then (2D) the node's height or 0.
template <int D>
double node_coordinate(const MeshView<D>& view, std::size_t n, int i) {
  if (i < D) return view.points[n][i];
  return view.heights.empty() ? 0.0 : view.heights[n];
}

// A copy of a Mesh's points, elements, kinds and boundary, and a view of it. Points that no element uses
// (the fill outside the water) are left out and the rest renumbered in their order.
template <int D>
class MeshSnapshot {
 public:
  // The points in `order` when given (the mesh's points, each once, in the order to number them; else
  // the mesh's own order), and the elements each turned to start at its smallest index (orientation
  // kept) and sorted. A dynamic update renumbers the mesh's points, and CGAL visits its elements in
  // storage order: with the edit session's canonical point list as `order`, an export after edits is
  // byte-identical to one from a fresh run on the edited input. std::logic_error when `order` is not a
  // permutation of the mesh's points.
  // With `in_place`, when every point is kept in the mesh's own order (no `order`, none unused), the
  // points and kinds are read from the mesh, not copied: the mesh must then outlive the snapshot, unchanged
  // (an export of a large mesh beside other work on it: 7 MB less at Lake Superior).
  explicit MeshSnapshot(const Mesh<D>& mesh, std::span<const Point<D>> order = {}, bool in_place = false);
  MeshSnapshot(std::vector<Point<D>> points, std::vector<Element<D>> elements, std::vector<PointKind> kinds = {});
  MeshView<D> view() const;
  MeshView<D> view(std::function<Point2(const Point2&)> to_lonlat) const;

 private:
  std::vector<Point<D>> points_;
  std::vector<Element<D>> elements_;
  std::vector<PointKind> kinds_;
  std::vector<BoundaryLoop> boundary_;
  // The mesh's own points and kinds when read in place (see the constructor); null otherwise.
  const std::vector<Point<D>>* mesh_points_ = nullptr;
  const std::vector<PointKind>* mesh_kinds_ = nullptr;
  std::span<const Point<D>> points() const { return mesh_points_ ? std::span<const Point<D>>(*mesh_points_) : points_; }
  std::span<const PointKind> kinds() const { return mesh_kinds_ ? std::span<const PointKind>(*mesh_kinds_) : kinds_; }
};

enum class ExportFormat { Gmsh, Vtu, Triangle, Adcirc, GeoJson, Obj, Ply, Off };

// From the file name: .msh, .vtu, .node or .ele, fort.14 / .14 / .fort14, .geojson or .json, .obj, .ply,
// .off (case-insensitive). Throws InputError naming the path for anything else.
ExportFormat export_format_from_path(const std::filesystem::path& path);

// Writes `view` to `path` in `format` (by default from the file name). The Triangle format writes two
// files, path with .node and with .ele. Throws InputError for a format the dimension or the view cannot
// give (GeoJSON without to_lonlat, fort.14 in 3D) and std::runtime_error naming the path when writing
// fails; an existing file is left untouched in both cases.
template <int D>
void export_mesh(const std::filesystem::path& path, const MeshView<D>& view, std::optional<ExportFormat> format = {});

// The individual writers, for callers that know what they want.
template <int D>
void write_gmsh(const std::filesystem::path& path, const MeshView<D>& view);
template <int D>
void write_vtu(const std::filesystem::path& path, const MeshView<D>& view);
template <int D>
void write_triangle(const std::filesystem::path& node_path, const MeshView<D>& view);  // also writes .ele
void write_adcirc(const std::filesystem::path& path, const MeshView<2>& view);
void write_geojson(const std::filesystem::path& path, const MeshView<2>& view);
// OBJ, PLY and OFF: the triangles in 2D (z = 0), the boundary surface in 3D.
template <int D>
void write_surface(const std::filesystem::path& path, const MeshView<D>& view, ExportFormat format);

}  // namespace shoremesh::io
