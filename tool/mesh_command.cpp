// shoremesh mesh INPUT... -o OUT: inputs to the well-spaced point set, its mesh, a preview and a quality
// summary. `-o OUT.csv` writes the point set itself ('# box' line, input points, Steiner points).
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <tbb/parallel_invoke.h>

#include "commands.hpp"
#include "free_memory.hpp"
#include "input_args.hpp"
#include "land_water.hpp"
#include "pipeline.hpp"
#include "progress.hpp"
#include "timings.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/point_set_csv.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh::tool {

namespace {

struct MeshOptions {
  InputArgs in;
  std::string output;
  std::string preview;
  PreviewArgs preview_args;
  EngineArgs engine;
  SizeArgs size;
  std::string format;
  std::string edits;  // --land-up-to only (land_water.cpp)
  bool json = false;
  bool timings = false;
};

// Every output of the run, checked before any work and written together at the end (io::OutputBatch):
// a run that fails leaves every existing file as it was. The Triangle format is two files.
struct OutputPaths {
  std::filesystem::path output, preview;  // the temporaries to write to
};

OutputPaths plan_outputs(io::OutputBatch& batch, const std::filesystem::path& output, std::optional<io::ExportFormat> format,
                         const std::string& preview) {
  OutputPaths paths;
  paths.output = stage_output(batch, output, format, "-o");
  if (!preview.empty()) paths.preview = batch.add(preview, "--preview");
  return paths;
}

template <int D>
int run_mesh(const MeshOptions& opt, const io::InputSet& set, Progress& progress, Timings& timings) {
  const EngineInput<D> in =
      timings.time("shore", [&] { return engine_input<D>(set, parse_box<D>(opt.engine.box), size_terms(opt.size, set)); });
  const std::vector<Point<D>>& points = in.points;
  const UserFrame frame = UserFrame::of(set);
  const std::filesystem::path output = opt.output;
  const bool point_set = opt.format.empty() && is_point_set_path(output);
  // Refuse an unknown extension before the work.
  const std::optional<io::ExportFormat> format =
      point_set ? std::nullopt
                : std::optional(opt.format.empty() ? io::export_format_from_path(output) : parse_export_format(opt.format));
  if (opt.preview_args.colouring == "height")
    throw ParameterError("--preview-colour height is for terrains (shoremesh terrain DEM --max-error E ...)");
  if (opt.preview_args.colouring == "depth" && !set.depth)
    throw ParameterError("--preview-colour depth needs depths: --dem, --depth-from or x,y,depth soundings");
  std::vector<std::filesystem::path> read = input_paths(opt.in, set);
  for (const auto& p : size_paths(opt.size)) read.push_back(p);
  io::OutputBatch batch(read);
  const OutputPaths staged = plan_outputs(batch, output, format, opt.preview);

  timings.time("purge", [] { release_free_memory(); });  // the reading's temporaries
  progress.stage("StableWS on " + std::to_string(points.size()) + " points");
  StableResult<D> result;
  try {
    Parameters<D> parameters = session_parameters<D>(opt.engine.rho);
    parameters.shore_cells = !opt.engine.whole_shore_cells;
    result = timings.time("engine", [&] { return stable_well_spaced<D>(points, parameters, in.box, &set.domain); });
  } catch (const PointInputError& e) {
    rethrow_with_origin(e, set);
  }
  timings.time("purge", [] { release_free_memory(); });  // the engine's
  progress.stage("meshing " + std::to_string(result.points.size()) + " points");
  const Mesh<D> mesh = timings.time("mesh", [&] {
    return well_spaced_mesh<D>(result.points, result.input_count, in.domain, result.box, opt.engine.keep_hull);
  });
  if (mesh.element_count() == 0 && (!point_set || !opt.preview.empty()))
    throw InputError(std::string("the mesh has no ") + (D == 2 ? "triangle" : "tetrahedron") + ": " +
                         std::to_string(result.points.size()) + " points" +
                         (set.domain.empty() ? "" : " in the water") + " span no " +
                         (D == 2 ? "triangle (give at least 3 points not on one line)"
                                 : "tetrahedron (give at least 4 points not on one plane)"),
                     opt.output);
  // The mesh holds its own copy of the points: only a point-set output reads the engine's again.
  const std::size_t point_count = result.points.size();
  if (!point_set) std::vector<Point<D>>().swap(result.points);
  timings.time("purge", [] { release_free_memory(); });  // the mesh build's, before the outputs' and summary's

  // The outputs and the summary only read the finished mesh: they are made at the same time (each output
  // to its staged file, committed together once all are written).
  progress.stage("writing " + output.filename().string() + " and measuring quality");
  auto write_outputs = [&] {
    timings.time("write", [&] {
      if (point_set) {
        io::write_point_set_csv<D>(staged.output, result.box, result.points);
      } else {
        export_mesh_file<D>(mesh, staged.output, format, frame);
      }
    });
    if (!opt.preview.empty()) {
      PreviewArgs args = opt.preview_args;
      args.rho = opt.engine.rho;
      args.size = in.size;
      timings.time("preview", [&] { write_preview<D>(mesh, staged.preview, args, &frame); });
    }
  };
  QualityNumbers quality;
  std::string size_and_depths;  // the summary's lines after the quality's
  auto measure = [&] {
    quality = timings.time("quality", [&] { return quality_numbers<D>(mesh, opt.engine.rho, result.box, frame, &set.domain); });
    if constexpr (D == 2) {
      if (in.size) size_and_depths += size_text(*in.size, mesh, in.seed_count, frame);
      if (frame.depth) size_and_depths += depth_text(mesh_depths(io::MeshSnapshot<2>(mesh).view(), frame));
    }
  };
  tbb::parallel_invoke(write_outputs, measure);
  quality.shore_splits = in.split_count;
  timings.time("commit", [&] { batch.commit(); });
  progress.finish();

  // The engine's Steiner points fill its whole box; the mesh keeps those its elements use (the water).
  std::cerr << "shoremesh: " << result.input_count << " input points, " << point_count - result.input_count
            << " Steiner points in the box (" << quality.steiner_points << " of them in the mesh) -> " << opt.output
            << '\n';
  std::cout << describe_input(set);
  std::cout << "box: origin " << frame.point(result.box.origin) << ", side " << frame.length(result.box.side) << '\n';
  std::cout << quality_text(quality, D) << size_and_depths;
  std::cout << "wrote " << opt.output;
  if (!opt.preview.empty()) std::cout << " and " << opt.preview;
  std::cout << '\n';
  std::cerr << timings.line();
  return kExitOk;
}

}  // namespace

Command add_mesh_command(CLI::App& app) {
  auto opt = std::make_shared<MeshOptions>();
  CLI::App* cmd = app.add_subcommand("mesh", "Inputs to a well-spaced point set, its quality mesh, a preview and a summary");
  add_input_options(cmd, opt->in);
  cmd->add_option("-o,--output", opt->output,
                  "Output: a mesh (.msh .vtu .node fort.14 .geojson .obj .ply .off) or the point set (.csv: "
                  "'# box X0 Y0 [Z0] SIDE', input points, Steiner points)")
      ->required();
  cmd->add_option("--preview", opt->preview, "Also draw the mesh to this PNG");
  add_preview_options(cmd, opt->preview_args);
  add_engine_options(cmd, opt->engine);
  // mesh only: the edit sessions (edit, serve) and --land-up-to build with cells that stop at the shore.
  cmd->add_flag("--whole-shore-cells", opt->engine.whole_shore_cells,
                "With rings: shore vertices' cells reach onto land as other cells do (by default they stop at the "
                "shore: docs/water_only.md; not with --land-up-to)");
  add_size_options(cmd, opt->size);
  cmd->add_option("--format", opt->format, "Output format (default: from the output's extension)")
      ->check(CLI::IsMember({"msh", "vtu", "node", "fort14", "geojson", "obj", "ply", "off"}));
  cmd->add_option("--edits", opt->edits,
                  "--land-up-to: after the build, edit lines from FILE or '-' (standard input): dem-patch FILE (a "
                  "window of new heights; the contours and the mesh follow, equal to a fresh run on the patched DEM) "
                  "| export PATH | stats; -o is written after the last line");
  cmd->add_flag("--json", opt->json, "--edits: reply to each edit line with one JSON object");
  cmd->add_flag("--timings", opt->timings, "Print the wall time of each phase of the run on stderr at its end");
  cmd->footer(
      "Examples:\n"
      "  shoremesh mesh samples/superior/superior_watermask_h.png --largest-water --spacing 5000 \\\n"
      "      -o superior.msh --preview superior.png\n"
      "  shoremesh mesh points.csv -o points_ws.csv          # the well-spaced point set itself\n"
      "  shoremesh mesh lake.png track.gpx -o lake.geojson   # an image plus a survey track");
  return [opt]() {
    Progress progress(!opt->in.quiet && Progress::stderr_is_terminal(), opt->in.files.size() + 4);
    opt->in.three_d = opt->engine.dim == 3;
    if (opt->in.land_up_to) {
      LandWaterRequest req{opt->in, opt->output, opt->format, opt->preview, opt->engine.rho, std::nullopt, opt->edits, opt->json};
      if (opt->size.any()) req.other_options = "size control (--max-size and the other size options)";
      else if (!opt->engine.box.empty()) req.other_options = "--box";
      else if (opt->engine.dim == 3) req.other_options = "--dim 3";
      else if (opt->engine.whole_shore_cells) req.other_options = "--whole-shore-cells";
      else if (opt->engine.keep_hull) req.other_options = "--keep-hull";
      return run_land_water(req, progress);
    }
    if (!opt->edits.empty() || opt->json)
      throw ParameterError("--edits and --json are for --land-up-to meshes (water meshes are edited with `edit`)");
    Timings timings(opt->timings);
    const io::InputSet set = timings.time("read", [&] { return read_user_inputs(opt->in, progress); });
    const int dim = opt->engine.dim != 0 ? opt->engine.dim : set.dimension;
    return dim == 3 ? run_mesh<3>(*opt, set, progress, timings) : run_mesh<2>(*opt, set, progress, timings);
  };
}

}  // namespace shoremesh::tool
