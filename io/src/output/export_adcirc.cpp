// ADCIRC fort.14 (the ADCIRC manual, "Grid and Boundary Information File"): AGRID; NE NP; the nodes with
// their depths (positive down); the triangles; the elevation-specified (open) boundary segments; the
// normal-flow (land) boundary segments.
//
// Open boundaries (NOPE, NETA): the runs of boundary edges whose two nodes both lie where the water leaves
// the data (MeshView::open_nodes, a DEM's edge), IBTYPEE 0, each a node string along the boundary with the
// water on its left. Land boundaries (NBOU, NVEL): the rest of each boundary loop with the water on its left,
// i.e. counter-clockwise around the mainland and clockwise around islands, as the manual orders them.
// A mainland loop with open parts is split into land segments between them, IBTYPE 20 (external, no normal
// flow, free tangential slip), each starting and ending on the nodes it shares with the adjacent open
// segments. A loop with no open part is closed, its first node repeated as its last: IBTYPE 20 for a
// mainland shore (a lake), 21 for an island (internal). Mainland segments are listed before islands.
// With to_lonlat the coordinates are longitude/latitude degrees (ICS = 2); otherwise metric (ICS = 1).
#include <string>
#include <vector>

#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/export_text.hpp"

namespace shoremesh::io {

namespace {

struct Segment {
  std::vector<std::uint32_t> nodes;
  int type = 20;
};

// Splits one loop into open and land node strings (see the header).
void split_loop(const BoundaryLoop& loop, std::span<const std::uint8_t> open, std::vector<Segment>& opens,
                std::vector<Segment>& lands) {
  const std::size_t n = loop.nodes.size();
  auto edge_open = [&](std::size_t j) {
    return !open.empty() && open[loop.nodes[j % n]] && open[loop.nodes[(j + 1) % n]];
  };
  std::size_t start = n;  // an edge that begins a run: its kind differs from the edge before it
  for (std::size_t j = 0; j < n && start == n; ++j)
    if (edge_open(j) && !edge_open(j + n - 1)) start = j;
  if (start == n) {
    if (edge_open(0)) {  // the whole loop is open (water everywhere to the data's edge)
      Segment s{loop.nodes, 0};
      s.nodes.push_back(loop.nodes.front());
      opens.push_back(std::move(s));
      return;
    }
    Segment s{loop.nodes, loop.role == RingRole::Shore ? 20 : 21};
    s.nodes.push_back(loop.nodes.front());
    lands.push_back(std::move(s));
    return;
  }
  Segment current{{loop.nodes[start]}, 0};
  bool current_open = true;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t j = start + k;
    const bool o = edge_open(j);
    if (o != current_open) {
      (current_open ? opens : lands).push_back(current);
      current = Segment{{loop.nodes[j % n]}, o ? 0 : 20};
      current_open = o;
    }
    current.nodes.push_back(loop.nodes[(j + 1) % n]);
  }
  (current_open ? opens : lands).push_back(std::move(current));
}

}  // namespace

void write_adcirc(const std::filesystem::path& path, const MeshView<2>& view) {
  std::vector<Segment> opens, mainland, islands;
  for (const BoundaryLoop& loop : view.boundary)
    split_loop(loop, view.open_nodes, opens, loop.role == RingRole::Shore ? mainland : islands);
  std::vector<Segment> lands = std::move(mainland);
  lands.insert(lands.end(), islands.begin(), islands.end());

  write_atomically(path, [&](std::ostream& out) {
    std::string s = std::string("shoremesh mesh (") + (view.to_lonlat ? "lon/lat degrees" : "metric") + ")\n";
    append(s, view.elements.size(), ' ', view.points.size(), " ! NE NP\n");
    for (std::size_t i = 0; i < view.points.size(); ++i) {
      const Point2 p = view.to_lonlat ? view.to_lonlat(view.points[i]) : view.points[i];
      append(s, i + 1, ' ');
      append_number(s, p[0]), s += ' ', append_number(s, p[1]), s += ' ';
      append_number(s, !view.depths.empty() ? view.depths[i] : view.depth ? view.depth(view.points[i]) : 0.0);
      s += "\n";
    }
    for (std::size_t i = 0; i < view.elements.size(); ++i) {
      const auto& e = view.elements[i];
      append(s, i + 1, " 3 ", e[0] + 1, ' ', e[1] + 1, ' ', e[2] + 1, '\n');
    }
    std::size_t neta = 0, nvel = 0;
    for (const Segment& o : opens) neta += o.nodes.size();
    for (const Segment& l : lands) nvel += l.nodes.size();
    append(s, opens.size(), " ! NOPE\n", neta, " ! NETA\n");
    for (const Segment& o : opens) {
      append(s, o.nodes.size(), " 0 ! NVDLL IBTYPEE\n");
      for (auto n : o.nodes) append(s, n + 1, '\n');
    }
    append(s, lands.size(), " ! NBOU\n", nvel, " ! NVEL\n");
    for (const Segment& l : lands) {
      append(s, l.nodes.size(), ' ', l.type, " ! NVELL IBTYPE\n");
      for (auto n : l.nodes) append(s, n + 1, '\n');
    }
    out << s;
  });
}

}  // namespace shoremesh::io
