// ADCIRC fort.14: nodes, triangles, no open boundaries, and one no-normal-flow land boundary per boundary
// loop: IBTYPE 0 (external, mainland) for shores, listed first and counter-clockwise, IBTYPE 1 (internal)
// for islands, clockwise. ADCIRC's manual asks that a closed boundary (a lake shore, an island) repeat its
// first node as its last. With to_lonlat the coordinates are longitude/latitude degrees (ADCIRC's ICS = 2,
// what coastal models usually read); otherwise the metric coordinates (ICS = 1).
#include <string>

#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/export_text.hpp"

namespace shoremesh::io {

void write_adcirc(const std::filesystem::path& path, const MeshView<2>& view) {
  write_atomically(path, [&](std::ostream& out) {
    std::string s = std::string("shoremesh mesh (") + (view.to_lonlat ? "lon/lat degrees" : "metric") + ")\n";
    append(s, view.elements.size(), ' ', view.points.size(), " ! NE NP\n");
    for (std::size_t i = 0; i < view.points.size(); ++i) {
      const Point2 p = view.to_lonlat ? view.to_lonlat(view.points[i]) : view.points[i];
      append(s, i + 1, ' ');
      append_number(s, p[0]), s += ' ', append_number(s, p[1]), s += ' ';
      append_number(s, view.depth ? view.depth(view.points[i]) : 0.0);
      s += "\n";
    }
    for (std::size_t i = 0; i < view.elements.size(); ++i) {
      const auto& e = view.elements[i];
      append(s, i + 1, " 3 ", e[0] + 1, ' ', e[1] + 1, ' ', e[2] + 1, '\n');
    }
    s += "0 ! NOPE\n0 ! NETA\n";
    std::size_t total = 0;
    for (const BoundaryLoop& loop : view.boundary) total += loop.nodes.size() + 1;
    append(s, view.boundary.size(), " ! NBOU\n", total, " ! NVEL\n");
    for (const BoundaryLoop& loop : view.boundary) {
      append(s, loop.nodes.size() + 1, loop.role == RingRole::Shore ? " 0" : " 1", " ! NVELL IBTYPE\n");
      for (auto n : loop.nodes) append(s, n + 1, '\n');
      append(s, loop.nodes.front() + 1, '\n');
    }
    out << s;
  });
}

}  // namespace shoremesh::io
