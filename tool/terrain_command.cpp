// shoremesh terrain DEM --max-error E -o OUT: a quality TIN of a DEM within a vertical error bound
// (core/include/shoremesh/terrain.hpp, docs/terrain.md), with heights in every export, a hillshaded
// preview, and windows of new heights (--patch) applied through the dynamic engine.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "dem_patch.hpp"
#include "edit_session.hpp"
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

std::optional<nlohmann::json> run_dem_edit_line(std::size_t line, const std::string& text, const std::string& kind,
                                                const DemEditOps& ops) {
  const std::vector<std::string> words = split_words(text);
  if (words.empty() || words[0][0] == '#') return std::nullopt;
  const std::string& op = words[0];
  nlohmann::json reply = {{"line", line}, {"ok", true}, {"op", op}};
  try {
    if (op == "dem-patch") ops.patch(rest_after_op(text), reply);
    else if (op == "export") ops.export_to(rest_after_op(text), reply);
    else if (op == "stats" && words.size() == 1) ops.stats(reply);
    else if (op == "stats") throw InputError("stats takes no arguments");
    else throw InputError("unknown " + kind + " edit '" + op + "' (dem-patch FILE, export PATH, stats)");
  } catch (const InputError& e) {
    return nlohmann::json{{"line", line}, {"ok", false}, {"op", op}, {"error", e.what()}};
  } catch (const ParameterError& e) {
    return nlohmann::json{{"line", line}, {"ok", false}, {"op", op}, {"error", e.what()}};
  }
  return reply;
}

namespace {

struct TerrainOptionsArgs {
  std::string dem;
  double max_error = std::nan("");
  double seed_fraction = 0;
  std::string output, format, preview;
  std::vector<std::string> patches;
  std::string edits;  // edit lines (dem-patch FILE, export PATH, stats), '-' for standard input
  bool json = false;
  PreviewArgs preview_args;
  double rho = std::numbers::sqrt2;
  bool quiet = false;
};

std::string ms(double x) { return approx(x, 3) + " ms"; }

std::string update_text(const TerrainUpdate& u) {
  std::ostringstream s;
  s << "seeds +" << u.seeds_added << " -" << u.seeds_removed << ", greedy picks +" << u.picks_added << " -"
    << u.picks_removed << " and " << u.boundary_splits << " boundary splits in " << u.rounds << " rounds, Steiner +" << u.steiner_added << " -" << u.steiner_removed
    << ", " << u.operations << " engine operations, " << u.triangles_measured << " triangles measured";
  return s.str();
}

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

// The TIN with its heights, in lon/lat when the DEM has a coordinate system.
struct TinView {
  io::MeshSnapshot<2> snapshot;
  io::MeshView<2> view;
  TinView(const TerrainSession& s, const io::DemGrid& plane)
      : snapshot(s.points(), s.triangles(), s.kinds()),
        view(plane.to_lonlat ? snapshot.view(plane.to_lonlat) : snapshot.view()) {
    view.heights = s.heights();
  }
};

io::ExportFormat tin_format(const std::filesystem::path& path, const std::string& format, const io::DemGrid& plane,
                            const std::string& option) {
  const io::ExportFormat f = format.empty() ? io::export_format_from_path(path) : parse_export_format(format);
  if (f == io::ExportFormat::Triangle || f == io::ExportFormat::Adcirc)
    throw ParameterError(option + ": a terrain is written with its heights: .msh, .vtu, .obj, .ply, .off or .geojson");
  if (f == io::ExportFormat::GeoJson && !plane.to_lonlat)
    throw InputError(option + ": GeoJSON needs longitude/latitude, and the DEM has no coordinate system");
  return f;
}

// The triangles by their corners (sorted), to count what an edit changed.
std::vector<ElementCorners<2>> tin_corners(const TerrainSession& s) {
  return sorted_corners<2>(s.points(), s.triangles());
}

// The terrain's edit language (--edits): one reply per line, a bad line an error reply that changes nothing.
//   dem-patch FILE   new heights for a window of the DEM (a raster with the DEM's cells, aligned)
//   export PATH      the current TIN with its heights (.msh .vtu .obj .ply .off .geojson)
//   stats            counts and the error measured against the current DEM
class TerrainEdits {
 public:
  TerrainEdits(TerrainSession& session, const io::Dem& dem, const io::DemGrid& plane, std::vector<std::filesystem::path> inputs)
      : session_(session), dem_(dem), plane_(plane), inputs_(std::move(inputs)) {}

  std::optional<nlohmann::json> run(std::size_t line, const std::string& text) {
    return run_dem_edit_line(line, text, "terrain",
                             {[this](const std::string& f, nlohmann::json& r) { patch(f, r); },
                              [this](const std::string& p, nlohmann::json& r) { export_to(p, r); },
                              [this](nlohmann::json& r) { stats(r); }});
  }

  static std::string text(const nlohmann::json& r) {
    const std::string head = "line " + r["line"].dump() + ": ";
    if (!r.value("ok", false)) return head + "error: " + r.value("error", "");
    const std::string op = r.value("op", "");
    if (op == "dem-patch")
      return head + "dem-patch " + r.value("file", "") + ": " + r["cells"].dump() + " cells at column " + r["column"].dump() +
             ", row " + r["row"].dump() + ": triangles -" + r["triangles_removed"].dump() + " +" +
             r["triangles_added"].dump() + " (now " + r["triangles"].dump() + "); " + r.value("update", "") + "; " +
             ms(r.value("ms", 0.0));
    if (op == "export") return head + "wrote " + r.value("path", "") + " (" + r["triangles"].dump() + " triangles)";
    return head + r["triangles"].dump() + " triangles, " + r["vertices"].dump() + " vertices; error max " +
           approx(r.value("max_error", 0.0), 6) + ", RMS " + approx(r.value("rms_error", 0.0), 6);
  }

 private:
  void patch(const std::string& file, nlohmann::json& reply) {
    if (file.empty()) throw InputError("dem-patch takes a FILE (a raster with the DEM's cells)");
    const io::Dem p = io::read_dem(file);
    const PatchWindow at = locate_patch(dem_, p);
    const auto before = tin_corners(session_);
    const auto t0 = std::chrono::steady_clock::now();
    TerrainUpdate u;
    try {
      u = session_.patch(at.col, at.row, p.width, p.height, p.heights, p.valid);
    } catch (const InputError& e) {
      throw InputError(e.message(), file);
    }
    const double t = ms_since(t0);
    const auto after = tin_corners(session_);
    std::vector<ElementCorners<2>> gone, came;
    std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(gone));
    std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(came));
    reply.update({{"file", file}, {"column", at.col}, {"row", at.row}, {"cells", std::size_t(p.width) * std::size_t(p.height)},
                  {"triangles_removed", gone.size()}, {"triangles_added", came.size()},
                  {"triangles", session_.triangles().size()}, {"update", update_text(u)}, {"ms", t}});
  }

  void export_to(const std::string& path, nlohmann::json& reply) {
    if (path.empty()) throw InputError("export takes a PATH (.msh .vtu .obj .ply .off .geojson)");
    const io::ExportFormat format = tin_format(path, "", plane_, "export");
    io::OutputBatch batch(inputs_);  // never over an input
    const TinView tin(session_, plane_);
    io::export_mesh<2>(batch.add(path, "export"), tin.view, format);
    batch.commit();
    reply.update({{"path", path}, {"triangles", session_.triangles().size()}});
  }

  void stats(nlohmann::json& reply) const {
    const TerrainError e = session_.error();
    reply.update({{"triangles", session_.triangles().size()}, {"vertices", session_.points().size()},
                  {"max_error", e.max}, {"rms_error", e.rms}, {"samples_over", e.over}});
  }

  TerrainSession& session_;
  const io::Dem& dem_;
  const io::DemGrid& plane_;
  std::vector<std::filesystem::path> inputs_;
};

int run_terrain(const TerrainOptionsArgs& opt, Progress& progress) {
  if (!(opt.max_error > 0) || !std::isfinite(opt.max_error))
    throw ParameterError("--max-error must be a finite height above 0 (got " + readable(opt.max_error) + ")");
  const std::filesystem::path output = opt.output;
  std::vector<std::filesystem::path> inputs{opt.dem};
  inputs.insert(inputs.end(), opt.patches.begin(), opt.patches.end());
  std::ifstream edit_file;
  if (!opt.edits.empty() && opt.edits != "-") {
    edit_file.open(opt.edits);
    if (!edit_file) throw InputError("cannot read the edits", opt.edits);
    inputs.emplace_back(opt.edits);
  }
  io::OutputBatch batch(inputs);
  const std::filesystem::path staged = batch.add(output, "-o");
  const std::filesystem::path staged_preview = opt.preview.empty() ? std::filesystem::path() : batch.add(opt.preview, "--preview");

  progress.stage("reading " + std::filesystem::path(opt.dem).filename().string());
  const io::Dem dem = io::read_dem(opt.dem);
  io::DemGrid plane = io::dem_grid(dem);
  io::ExportFormat format;
  try {
    format = tin_format(output, opt.format, plane, "-o");
  } catch (const InputError& e) {
    throw InputError(e.message(), opt.dem);
  }
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
  // Patches update each greedy round in a level of its own; building the levels here keeps that one-off
  // cost out of the first patch's reply (docs/terrain.md, "One setting for both targets").
  if (!patches.empty() || !opt.edits.empty()) {
    progress.stage("levels for patches");
    session->prepare_patches();
  }
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

  std::size_t failed = 0;
  if (!opt.edits.empty()) {
    progress.stage("edits");
    TerrainEdits edits(*session, dem, plane, inputs);
    std::istream& in = opt.edits == "-" ? std::cin : edit_file;
    std::size_t line_no = 0;
    for (std::string line; std::getline(in, line);) {
      const auto reply = edits.run(++line_no, line);
      if (!reply) continue;
      failed += !reply->value("ok", false);
      std::cout << (opt.json ? reply->dump() : TerrainEdits::text(*reply)) << std::endl;  // a program may wait
    }
  }

  const TerrainUpdate& b = session->build_stats();
  progress.stage("measuring");
  const TerrainError error = session->error();
  const auto& points = session->points();
  const auto& triangles = session->triangles();
  const TinView tin(*session, plane);
  const io::MeshView<2>& view = tin.view;
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
  if (failed) std::cerr << "shoremesh: " << failed << " edit line(s) failed (exit code 1)\n";
  return error.over != 0 ? kExitInternal : failed ? kExitBadInput : kExitOk;
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
                  "(default 0: block picks and greedy rounds, fewest triangles; a patch updates either locally)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--patch", opt->patches,
                  "After the build, replace a window of the DEM by this raster (same cells, aligned) and update the TIN; "
                  "repeatable, applied in order")
      ->take_all();
  cmd->add_option("--edits", opt->edits,
                  "After the build (and --patch), edit lines from FILE or '-' (standard input): dem-patch FILE (a "
                  "window of new heights; the TIN updates and equals a fresh run on the patched DEM) | export PATH | "
                  "stats ('#' comments); -o is written after the last line");
  cmd->add_flag("--json", opt->json, "Reply to each edit line with one JSON object");
  add_quiet_option(cmd, opt->quiet);
  cmd->footer(
      "Examples:\n"
      "  shoremesh terrain samples/salish/salish_sea_topobathy.tif --max-error 20 -o salish.obj \\\n"
      "      --preview salish.png --preview-colour height\n"
      "  shoremesh terrain dem.tif --max-error 1 -o tin.vtu --patch dredged_channel.tif\n"
      "  printf 'dem-patch channel.tif\\nexport dredged.vtu\\ndem-patch levee.tif\\nstats\\n' | \\\n"
      "      shoremesh terrain dem.tif --max-error 1 -o final.vtu --edits -\n"
      "Exit code 3 if the error bound is not met at some sample (never expected: the TIN is refined until it is).");
  return [opt]() {
    Progress progress(!opt->quiet && Progress::stderr_is_terminal(),
                      5 + opt->patches.size() + !opt->edits.empty() + (!opt->patches.empty() || !opt->edits.empty()));
    return run_terrain(*opt, progress);
  };
}

}  // namespace shoremesh::tool
