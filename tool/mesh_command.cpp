// shoremesh mesh INPUT -o OUTPUT.csv: the well-spaced superset of a point file.
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/point_file.hpp"
#include "shoremesh/io/point_set_csv.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh::tool {

namespace {

struct MeshOptions {
  std::string input;
  std::string output;
  double rho = std::sqrt(2.0);
  std::vector<double> box;
};

template <int D>
int run_mesh(const MeshOptions& opt, const std::vector<Point<D>>& points, const std::vector<std::size_t>& lines) {
  Parameters<D> parameters;
  parameters.rho = opt.rho;
  if (parameters.beta <= opt.rho) parameters.beta = 1.5 * opt.rho;  // keep the picking region non-empty
  std::optional<BoxTransform<D>> box;
  if (!opt.box.empty()) {
    if (opt.box.size() != D + 1)
      throw InputError("--box takes " + std::to_string(D + 1) + " numbers for " + std::to_string(D) + "D input (X0 Y0" +
                       (D == 3 ? " Z0" : "") + " SIDE)");
    BoxTransform<D> b;
    for (int i = 0; i < D; ++i) b.origin[i] = opt.box[std::size_t(i)];
    b.side = opt.box[D];
    box = b;
  }
  StableResult<D> result;
  try {
    result = stable_well_spaced<D>(points, parameters, box);
  } catch (const PointInputError& e) {
    // Say where the offending point is in the user's file.
    if (!e.points().empty() && e.points().front() < lines.size())
      throw InputError(e.message(), opt.input, lines[e.points().front()]);
    throw;
  }
  io::write_point_set_csv<D>(opt.output, result.box, result.points);
  std::cerr << "shoremesh: " << result.input_count << " input points, " << result.points.size() - result.input_count
            << " Steiner points -> " << opt.output << '\n';
  return kExitOk;
}

}  // namespace

Command add_mesh_command(CLI::App& app) {
  auto opt = std::make_shared<MeshOptions>();
  CLI::App* cmd = app.add_subcommand("mesh", "Build the rho-well-spaced superset of the input points");
  cmd->add_option("input", opt->input, "Point file: CSV or whitespace separated, 2 or 3 numbers a line, # comments")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", opt->output, "Output .csv: '# box X0 Y0 [Z0] SIDE', input points, Steiner points")
      ->required();
  cmd->add_option("--rho", opt->rho, "Quality bound rho > 1 (default sqrt 2: angles >= 20.7 degrees in 2D)");
  cmd->add_option("--box", opt->box, "Fix the box: X0 Y0 [Z0] SIDE (default: the input's bounding box + 5%)")
      ->expected(3, 4);
  cmd->footer("Example:\n  shoremesh mesh samples/points/lake_shore.csv -o lake_ws.csv");
  return [opt]() {
    const io::PointFile file = io::read_point_file(opt->input);
    if (file.dimension == 3) return run_mesh<3>(*opt, file.points3, file.lines);
    return run_mesh<2>(*opt, file.points2, file.lines);
  };
}

}  // namespace shoremesh::tool
