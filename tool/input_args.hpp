#pragma once
// The options every command that reads inputs shares (mesh, edit, info): the files and how to read them.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "shoremesh/io/input_set.hpp"
#include "pipeline.hpp"
#include "shoremesh/io/read_input.hpp"

namespace shoremesh::tool {

class Progress;

struct InputArgs {
  std::vector<std::string> files;
  std::optional<double> spacing;   // along shorelines, tracks and segments, in the input's units
  std::string water = "light";     // dark | light | a colour
  std::optional<double> threshold;
  double colour_tolerance = 40;
  double min_area = 16;
  bool largest_water = false;
  int open_radius = 0, close_radius = 0;
  std::vector<double> map_box;     // images: XMIN YMIN XMAX YMAX of the image's outer edges
  std::string crs;                 // images: coordinate system of --map-box (or of a world file without .prj)
  std::optional<double> track_close_distance;  // GPS walks ending this near their start become rings
  bool gps_open_lines = false;                 // open GPS walks become constraint lines
  bool lonlat = false;
  std::string projection = "local";  // local | utm
  std::string dem;                 // a DEM traced at shoreline_level, and the depth source
  double shoreline_level = 0;
  std::optional<double> land_up_to;  // --dem: mesh the land below this height too (land_water.cpp)
  std::optional<double> max_error;   // --land-up-to: vertical error bound on land
  std::string depth_from;          // a DEM giving depths beside other inputs
  std::optional<double> min_depth;
  std::string open_boundary;       // lines along which fort.14's boundary is open (beside the data's edges)
  std::optional<double> open_boundary_distance;  // how near a boundary node must be to such a line
  bool three_d = false;            // --dim 3: a third column is z; otherwise x,y,depth soundings
  bool quiet = false;
};

// Registers INPUT... and the reading options on `cmd`. `several`: more than one input file allowed.
void add_input_options(CLI::App* cmd, InputArgs& args, bool several = true);
// The engine's options: --rho, --box, --dim, and --keep-hull for the mesh of its output.
struct EngineArgs {
  double rho = 1.4142135623730951;
  std::vector<double> box;
  int dim = 0;             // 0: the input's
  bool keep_hull = false;  // the mesh keeps the slivers along the box's edge (well_spaced_mesh)
  bool whole_shore_cells = false;  // mesh only: Parameters::shore_cells off (docs/water_only.md)
};
void add_engine_options(CLI::App* cmd, EngineArgs& args);  // --threads too
// Registers --threads (the engine's thread count, process-wide).
void add_threads_option(CLI::App* cmd);

// Element size control (docs/sizing.md), in the input's units (metres for georeferenced input).
struct SizeArgs {
  std::optional<double> max_size, min_size, grade;
  std::vector<double> from_shore;  // H0 RATE
  std::string polygons;            // GeoJSON polygons with a `size` property
  std::string raster;              // a raster of sizes (GDAL)
  std::optional<double> from_depth;  // WL: h = T sqrt(g depth) / WL
  double period = 44712;             // T in seconds (M2: 12.42 h)
  std::optional<double> from_slope;  // S: h = 2 pi depth / (S |grad depth|)
  bool any() const {
    return max_size || min_size || grade || !from_shore.empty() || !polygons.empty() || !raster.empty() || from_depth ||
           from_slope;
  }
};
void add_size_options(CLI::App* cmd, SizeArgs& args);
// The size terms the options ask for (nullopt: none), reading the polygons and the raster, and sampling the
// depth source of `set` for --size-from-depth and --size-from-slope. ParameterError/InputError naming the
// option for what cannot be honoured.
std::optional<SizeTerms> size_terms(const SizeArgs& args, const io::InputSet& set);
// The files the size options read (outputs may replace none).
std::vector<std::filesystem::path> size_paths(const SizeArgs& args);

// Registers --preview-colour and --preview-width.
void add_preview_options(CLI::App* cmd, PreviewArgs& args);
// Registers --quiet.
void add_quiet_option(CLI::App* cmd, bool& quiet);

// The io options the arguments ask for (InputError for a bad --water colour).
io::InputOptions input_options(const InputArgs& args);

// Reads and merges the inputs (one progress stage per file).
io::InputSet read_user_inputs(const InputArgs& args, Progress& progress);

// Every file a run read: the inputs, the files they named (a .poly's .node), --dem and --depth-from. An
// output may replace none of them (io::OutputBatch).
std::vector<std::filesystem::path> input_paths(const InputArgs& args, const io::InputSet& set);

// "#rrggbb", "R,G,B" or a few names (blue, lightsteelblue, lightblue, cyan, navy, white, black).
std::array<int, 3> parse_colour(const std::string& text);

}  // namespace shoremesh::tool
