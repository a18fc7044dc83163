// shoremesh info FILE: what a file holds. Inputs: points, rings, units, projection, extent, water area.
// A point set written by `mesh -o OUT.csv` or `edit`'s export: its box, points and the quality of its mesh.
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <string>

#include "commands.hpp"
#include "input_args.hpp"
#include "pipeline.hpp"
#include "progress.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/mesh_file.hpp"
#include "shoremesh/io/point_set_csv.hpp"

namespace shoremesh::tool {

namespace {

// The number of values on the '# box' line of a point-set CSV (D + 1), or 0 when the file is not one.
int point_set_box_values(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line.find_first_not_of(" \t\r") == std::string::npos) {
  }
  if (line.rfind("# box", 0) != 0) return 0;
  std::istringstream words(line.substr(5));
  int n = 0;
  for (std::string w; words >> w;) ++n;
  return n;
}

template <int D>
int info_point_set(const std::string& path, double rho) {
  const io::PointSetFile<D> file = io::read_point_set_csv<D>(path);
  const UserFrame frame;  // a point set carries no units: map units
  std::cout << path << ": well-spaced point set (" << D << "D), " << file.points.size() << " points\n";
  std::cout << "box: origin " << frame.point(file.box.origin) << ", side " << frame.length(file.box.side) << '\n';
  const Mesh<D> mesh(file.points, file.points.size());
  QualityNumbers q = quality_numbers<D>(mesh, rho, file.box, frame);
  std::cout << quality_text(q, D);
  std::cout << "  (the file does not say which points were input, so all count as input here)\n";
  return kExitOk;
}

double ring_area(const std::vector<Point2>& ring) {
  double a = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2& p = ring[i];
    const Point2& q = ring[(i + 1) % ring.size()];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return std::fabs(a) / 2;
}

int info_input(const InputArgs& args) {
  Progress progress(!args.quiet && Progress::stderr_is_terminal(), 1);
  const io::InputSet set = read_user_inputs(args, progress);
  progress.finish();
  const UserFrame frame = UserFrame::of(set);
  std::cout << args.files.front() << ": " << io::to_string(io::detect_input_format(args.files.front())) << '\n';
  std::cout << describe_input(set);
  if (set.dimension == 2 && !set.points.empty()) {
    Point2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    Point2 hi{-lo[0], -lo[1]};
    for (const auto& p : set.points)
      for (int i = 0; i < 2; ++i) {
        lo[i] = std::min(lo[i], p[i]);
        hi[i] = std::max(hi[i], p[i]);
      }
    std::cout << "extent: " << frame.point(lo) << " to " << frame.point(hi) << '\n';
  } else if (set.dimension == 3 && !set.points3.empty()) {
    Point3 lo = set.points3.front(), hi = lo;
    for (const auto& p : set.points3)
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], p[i]);
        hi[i] = std::max(hi[i], p[i]);
      }
    std::cout << "extent: " << frame.point(lo) << " to " << frame.point(hi) << '\n';
  }
  if (!set.domain.empty()) {
    double water = 0;
    for (const Ring& r : set.domain.rings) water += (r.role == RingRole::Shore ? 1 : -1) * ring_area(r.points);
    std::cout << "water area: " << approx(water, 6);
    if (set.units == io::Units::Metres) std::cout << " m^2 = " << approx(water / 1e6, 6) << " km^2 (projected)";
    else if (set.units == io::Units::Pixels) std::cout << " px^2";
    else std::cout << " square map units";
    std::cout << '\n';
  }
  return kExitOk;
}

// A mesh written by `mesh` (or any fort.14 / Gmsh 4.1 ASCII file): nodes, elements, boundaries, depths.
int info_mesh_file(const std::string& path) {
  const io::MeshFile m = io::read_mesh_file(path);
  std::cout << path << ": " << m.format << " mesh, " << m.nodes.size() << " nodes, " << m.triangles.size() << " triangles";
  if (m.tetrahedra > 0) std::cout << ", " << m.tetrahedra << " tetrahedra";
  std::cout << '\n';
  if (!m.title.empty()) std::cout << "title: " << m.title << '\n';
  auto nodes_of = [](const std::vector<io::MeshFileBoundary>& list) {
    std::size_t n = 0;
    for (const auto& b : list) n += b.nodes.size();
    return n;
  };
  if (m.format == "ADCIRC fort.14") {
    std::cout << "open boundaries: " << m.open.size() << " segments, " << nodes_of(m.open) << " nodes\n";
    std::map<int, std::size_t> by_type;
    for (const auto& b : m.land) ++by_type[b.type];
    std::cout << "land boundaries: " << m.land.size() << " segments, " << nodes_of(m.land) << " nodes";
    for (const auto& [type, n] : by_type) std::cout << "; IBTYPE " << type << ": " << n;
    std::cout << '\n';
  } else {
    for (const auto& b : m.land)
      std::cout << "boundary lines: " << b.nodes.size() / 2 << " in physical group " << b.type
                << (b.name.empty() ? "" : " \"" + b.name + "\"") << '\n';
  }
  if (!m.depths.empty()) std::cout << depth_text(m.depths);
  else std::cout << "depths: none\n";
  return kExitOk;
}

struct InfoOptions {
  InputArgs in;
  double rho = std::sqrt(2.0);
};

}  // namespace

Command add_info_command(CLI::App& app) {
  auto opt = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info", "What a file holds: points, rings, projection, or a point set's mesh quality");
  add_input_options(cmd, opt->in, false);
  cmd->add_option("--rho", opt->rho, "Quality bound to rate a point set's mesh against (default sqrt 2)");
  cmd->footer(
      "Inputs (images, tracks, point, ring, .node/.poly and GeoJSON files) are read as 'mesh' reads them, with\n"
      "the same options. A point set written by 'mesh -o OUT.csv' or by 'edit''s 'export PATH.csv' is meshed\n"
      "and its quality rated in its box.\n"
      "\n"
      "Example:\n"
      "  shoremesh info samples/superior/superior_watermask_h.png --largest-water");
  return [opt]() {
    const std::string& path = opt->in.files.front();
    if (io::is_mesh_file(path)) return info_mesh_file(path);
    switch (point_set_box_values(path)) {
      case 3: return info_point_set<2>(path, opt->rho);
      case 4: return info_point_set<3>(path, opt->rho);
      default: return info_input(opt->in);
    }
  };
}

}  // namespace shoremesh::tool
