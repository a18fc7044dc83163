#pragma once
// Reading meshes back (for `info`): ADCIRC fort.14 and Gmsh .msh 4.1 ASCII, with their depths and
// boundaries. Every count is checked against what follows; errors name the file and line.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh::io {

struct MeshFileBoundary {
  std::vector<std::uint32_t> nodes;  // 0-based indices into MeshFile::nodes
  int type = 0;                      // fort.14: IBTYPEE (open) or IBTYPE (land); .msh: the physical tag
  std::string name;                  // .msh: the physical group's name
};

struct MeshFile {
  std::string format;                 // "ADCIRC fort.14" or "Gmsh 4.1"
  std::string title;                  // fort.14: AGRID
  std::vector<Point3> nodes;          // z = 0 for 2D
  std::vector<double> depths;         // fort.14: DP; .msh: the node field "depth"; empty when none
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::size_t tetrahedra = 0;
  std::vector<MeshFileBoundary> open;  // fort.14 elevation-specified segments
  std::vector<MeshFileBoundary> land;  // fort.14 normal-flow segments; .msh line elements by physical group
};

// InputError naming the file and line for anything that does not follow the format.
MeshFile read_fort14(const std::string& path);
MeshFile read_gmsh(const std::string& path);
// By name: fort.14, *.14, *.fort14 -> read_fort14; *.msh -> read_gmsh. Others: InputError.
bool is_mesh_file(const std::string& path);
MeshFile read_mesh_file(const std::string& path);

}  // namespace shoremesh::io
