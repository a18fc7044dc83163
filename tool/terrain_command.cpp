// shoremesh terrain DEM --max-error E -o OUT: a quality TIN of a DEM within a vertical error bound
// (core/include/shoremesh/terrain.hpp, docs/terrain.md), with heights in every export, a hillshaded
// preview, and windows of new heights (--patch) applied through the dynamic engine.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "input_args.hpp"
#include "pipeline.hpp"
#include "progress.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/dem.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/preview.hpp"
#include "shoremesh/mesh_quality.hpp"
#include "shoremesh/terrain.hpp"

namespace shoremesh::tool {

namespace {

struct TerrainOptionsArgs {
  std::string dem;
  double max_error = std::nan("");
  double seed_fraction = 0;
  std::string output, format, preview;
  std::vector<std::string> patches;
  PreviewArgs preview_args;
  double rho = std::numbers::sqrt2;
  bool quiet = false;
};

// Where a patch raster lies in the DEM: its cells must be the DEM's (same size, whole-cell offset).
struct PatchWindow {
  int col = 0, row = 0;
};
PatchWindow locate_patch(const io::Dem& dem, const io::Dem& patch) {
  const auto &a = dem.geotransform, &b = patch.geotransform;
  auto same = [](double x, double y) { return std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y)); };
  if (!same(a[1], b[1]) || !same(a[5], b[5]))
    throw InputError("the patch's cells (" + readable(b[1]) + " x " + readable(b[5]) + ") are not the DEM's (" +
                         readable(a[1]) + " x " + readable(a[5]) + ")",
                     patch.file);
  const double c = (b[0] - a[0]) / a[1], r = (b[3] - a[3]) / a[5];
  const double cr = std::round(c), rr = std::round(r);
  if (std::abs(c - cr) > 1e-6 || std::abs(r - rr) > 1e-6)
    throw InputError("the patch's cells are not aligned with the DEM's (offset " + readable(c) + ", " + readable(r) +
                         " cells)",
                     patch.file);
  if (cr < 0 || rr < 0 || cr + patch.width > dem.width || rr + patch.height > dem.height)
    throw InputError("the patch (" + std::to_string(patch.width) + " x " + std::to_string(patch.height) + " cells at " +
                         readable(cr) + ", " + readable(rr) + ") does not lie inside the DEM (" +
                         std::to_string(dem.width) + " x " + std::to_string(dem.height) + ")",
                     patch.file);
  if (dem.crs_name != patch.crs_name)
    throw InputError("the patch's coordinate system (" + patch.crs_name + ") is not the DEM's (" + dem.crs_name + ")",
                     patch.file);
  return {static_cast<int>(cr), static_cast<int>(rr)};
}

std::string ms(double x) { return approx(x, 3) + " ms"; }

std::string update_text(const TerrainUpdate& u) {
  std::ostringstream s;
  s << "seeds +" << u.seeds_added << " -" << u.seeds_removed << ", greedy picks +" << u.picks_added << " -"
    << u.picks_removed << " and " << u.boundary_splits << " boundary splits in " << u.rounds << " rounds, Steiner +" << u.steiner_added << " -" << u.steiner_removed
    << ", " << u.operations << " engine operations, " << u.triangles_measured << " triangles measured";
  return s.str();
}

int run_terrain(const TerrainOptionsArgs& opt, Progress& progress) {
  if (!(opt.max_error > 0) || !std::isfinite(opt.max_error))
    throw ParameterError("--max-error must be a finite height above 0 (got " + readable(opt.max_error) + ")");
  const std::filesystem::path output = opt.output;
  const io::ExportFormat format = opt.format.empty() ? io::export_format_from_path(output) : parse_export_format(opt.format);
  if (format == io::ExportFormat::Triangle || format == io::ExportFormat::Adcirc)
    throw ParameterError("-o: a terrain is written with its heights: .msh, .vtu, .obj, .ply, .off or .geojson");
  std::vector<std::filesystem::path> inputs{opt.dem};
  inputs.insert(inputs.end(), opt.patches.begin(), opt.patches.end());
  io::OutputBatch batch(inputs);
  const std::filesystem::path staged = batch.add(output, "-o");
  const std::filesystem::path staged_preview = opt.preview.empty() ? std::filesystem::path() : batch.add(opt.preview, "--preview");

  progress.stage("reading " + std::filesystem::path(opt.dem).filename().string());
  const io::Dem dem = io::read_dem(opt.dem);
  io::DemGrid plane = io::dem_grid(dem);
  if (format == io::ExportFormat::GeoJson && !plane.to_lonlat)
    throw InputError("GeoJSON needs longitude/latitude, and the DEM has no coordinate system", opt.dem);
  std::vector<io::Dem> patches;
  std::vector<PatchWindow> windows;
  for (const std::string& p : opt.patches) {
    patches.push_back(io::read_dem(p));
    windows.push_back(locate_patch(dem, patches.back()));
  }

  progress.stage("TIN of " + std::to_string(dem.width) + " x " + std::to_string(dem.height) + " samples");
  TerrainOptions options;
  options.max_error = opt.max_error;
  options.seed_fraction = opt.seed_fraction;
  options.engine = session_parameters<2>(opt.rho);
  const auto t0 = std::chrono::steady_clock::now();
  std::optional<TerrainSession> session;
  try {
    session.emplace(std::move(plane.grid), options);
  } catch (const InputError& e) {
    throw InputError(e.message(), opt.dem);
  }
  const double build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<std::string> patch_lines;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    progress.stage("patch " + std::filesystem::path(opt.patches[k]).filename().string());
    const auto t1 = std::chrono::steady_clock::now();
    const TerrainUpdate u = session->patch(windows[k].col, windows[k].row, patches[k].width, patches[k].height,
                                           patches[k].heights, patches[k].valid);
    const double t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
    patch_lines.push_back("patch " + opt.patches[k] + ": " + std::to_string(patches[k].width) + " x " +
                          std::to_string(patches[k].height) + " cells at column " + std::to_string(windows[k].col) +
                          ", row " + std::to_string(windows[k].row) + ": " + update_text(u) + "; " + ms(t) + " (seeds " +
                          ms(u.seed_ms) + ", engine " + ms(u.engine_ms) + ", mesh " + ms(u.mesh_ms) + ", error " +
                          ms(u.error_ms) + ")");
  }

  const TerrainUpdate& b = session->build_stats();
  progress.stage("measuring");
  const TerrainError error = session->error();
  const auto& points = session->points();
  const auto& triangles = session->triangles();
  io::MeshSnapshot<2> snapshot(points, triangles, session->kinds());
  io::MeshView<2> view = plane.to_lonlat ? snapshot.view(plane.to_lonlat) : snapshot.view();
  view.heights = session->heights();
  std::size_t meeting = 0;
  double worst_ratio = 0;
  for (const auto& t : triangles) {
    const ElementShape<2> shape = element_shape<2>({points[t[0]], points[t[1]], points[t[2]]});
    meeting += shape.radius_edge <= opt.rho;
    worst_ratio = std::max(worst_ratio, shape.radius_edge);
  }
  const auto angles = angle_range(points, triangles);

  progress.stage("writing " + output.filename().string());
  io::export_mesh<2>(staged, view, format);
  if (!opt.preview.empty()) {
    PreviewArgs args = opt.preview_args;
    args.rho = opt.rho;
    io::PreviewOptions po = preview_options(args);
    po.point_radius = 0;
    po.line_width = 0.5;
    io::render_preview<2>(staged_preview, view, po);
  }
  batch.commit();
  progress.finish();

  std::size_t samples = 0;
  for (auto k : session->kinds()) samples += k == PointKind::Input;
  std::cout << opt.dem << ": DEM " << dem.width << " x " << dem.height << " cells (" << error.samples << " with data), heights "
            << approx(dem.min, 6) << " .. " << approx(dem.max, 6) << (dem.crs_name.empty() ? "" : ", " + dem.crs_name) << '\n';
  std::cout << "tin: " << triangles.size() << " triangles, " << points.size() << " vertices (" << samples << " DEM samples: "
            << session->seed_count() << " seeds, " << session->pick_count() << " greedy picks in " << session->rounds()
            << " rounds; " << points.size() - samples << " Steiner, bilinear heights, of them " << b.boundary_splits
            << " halving encroached boundary edges)\n";
  std::cout << "error: max " << approx(error.max, 6) << ", RMS " << approx(error.rms, 6) << " (vertical, over " << error.samples
            << " DEM samples at cell centres; bound " << approx(opt.max_error, 6) << ": "
            << (error.over == 0 ? std::string("met by all") : std::to_string(error.over) + " samples over it") << ")\n";
  std::cout << "quality: angles " << approx(angles[0], 4) << ".." << approx(angles[1], 4) << " deg (guaranteed >= "
            << approx(std::asin(1 / (2 * opt.rho)) * 180 / std::numbers::pi, 4) << " deg for rho = " << approx(opt.rho)
            << " in the plane, " << (plane.metres ? "m" : "map units") << "); radius-edge <= " << approx(worst_ratio, 4) << "; bound met by "
            << meeting << " of " << triangles.size() << " triangles\n";
  std::cout << "time: build " << ms(build_ms) << " (seeds " << ms(b.seed_ms) << ", engine " << ms(b.engine_ms) << ", mesh "
            << ms(b.mesh_ms) << ", error " << ms(b.error_ms) << ")\n";
  for (const std::string& line : patch_lines) std::cout << line << '\n';
  std::cout << "wrote " << opt.output;
  if (!opt.preview.empty()) std::cout << " and " << opt.preview;
  std::cout << '\n';
  return error.over == 0 ? kExitOk : kExitInternal;
}

}  // namespace

Command add_terrain_command(CLI::App& app) {
  auto opt = std::make_shared<TerrainOptionsArgs>();
  CLI::App* cmd = app.add_subcommand(
      "terrain", "A quality TIN of a DEM within a vertical error bound (heights on every node), optionally patched");
  cmd->add_option("dem", opt->dem, "The DEM: any single-band raster GDAL reads, heights positive up")->required();
  cmd->add_option("--max-error", opt->max_error, "Largest vertical error allowed at any DEM cell centre (height units)")
      ->required();
  cmd->add_option("-o,--output", opt->output, "Output: .msh .vtu .obj .ply .off .geojson (heights as z)")->required();
  cmd->add_option("--format", opt->format, "Output format (default: from the output's extension)")
      ->check(CLI::IsMember({"msh", "vtu", "geojson", "obj", "ply", "off"}));
  cmd->add_option("--preview", opt->preview, "Also draw the TIN to this PNG");
  add_preview_options(cmd, opt->preview_args);
  cmd->add_option("--rho", opt->rho, "Quality bound rho > 1 (default sqrt 2: angles >= 20.7 degrees)");
  cmd->add_option("--seed-fraction", opt->seed_fraction,
                  "Seeds: corners of quadtree leaves whose cells lie within this fraction of --max-error of a plane; "
                  "a --patch then re-decides only the seeds near it (default 0: the greedy rounds alone, fewest triangles)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--patch", opt->patches,
                  "After the build, replace a window of the DEM by this raster (same cells, aligned) and update the TIN; "
                  "repeatable, applied in order")
      ->take_all();
  add_quiet_option(cmd, opt->quiet);
  cmd->footer(
      "Examples:\n"
      "  shoremesh terrain samples/salish/salish_sea_topobathy.tif --max-error 20 -o salish.obj \\\n"
      "      --preview salish.png --preview-colour height\n"
      "  shoremesh terrain dem.tif --max-error 1 -o tin.vtu --patch dredged_channel.tif\n"
      "Exit code 3 if the error bound is not met at some sample (never expected: the TIN is refined until it is).");
  return [opt]() {
    Progress progress(!opt->quiet && Progress::stderr_is_terminal(), 5 + opt->patches.size());
    return run_terrain(*opt, progress);
  };
}

}  // namespace shoremesh::tool
