#include "input_args.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "progress.hpp"
#include "shoremesh/engine/engine.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/dem.hpp"
#include "shoremesh/io/open_boundary.hpp"
#include "shoremesh/io/size_polygons.hpp"
#include "shoremesh/io/soundings.hpp"

namespace shoremesh::tool {

namespace {

// A number above zero (`positive`) or at least zero, refused in the user's terms: CLI11's PositiveNumber
// and NonNegativeNumber name a range up to the largest double, printed in full. Text that is not a number
// is CLI11's to refuse as before; NaN and infinity are refused here (a command-line mistake, exit 2).
CLI::Validator above_zero(bool positive) {
  return CLI::Validator(
      [positive](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v)) return {};
        if (!std::isfinite(v)) return text + " is not a finite number";
        if (positive ? v > 0 : v >= 0) return {};
        return text + (positive ? " is not above 0" : " is below 0");
      },
      positive ? "POSITIVE" : "NONNEGATIVE");
}

// Any finite number (CLI11's Range lets NaN through: every comparison with it is false).
CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || std::isfinite(v)) return {};
        return text + " is not a finite number";
      },
      "");
}

}  // namespace

void add_quiet_option(CLI::App* cmd, bool& quiet) {
  cmd->add_flag("-q,--quiet", quiet, "No progress bar (it is drawn only when stderr is a terminal anyway)");
}

void add_threads_option(CLI::App* cmd) {
  cmd->add_option_function<unsigned>(
         "--threads", [](const unsigned& n) { engine::set_thread_count(n); },
         "Threads the engine computes on (default: every core; the output is the same for any count)")
      ->check(CLI::Range(1u, 1024u));
}

void add_engine_options(CLI::App* cmd, EngineArgs& args) {
  cmd->add_option("--rho", args.rho, "Quality bound rho > 1 (default sqrt 2: angles >= 20.7 degrees in 2D)")
      ->check(finite_number());
  cmd->add_option("--box", args.box, "Fix the box: X0 Y0 [Z0] SIDE (default: the input's bounding box + 5%)")
      ->expected(3, 4)
      ->check(finite_number());
  cmd->add_option("--dim", args.dim, "Dimension: 2 or 3 (default: the input's; 2 drops z)")->check(CLI::IsMember({2, 3}));
  add_threads_option(cmd);
  cmd->add_flag("--keep-hull", args.keep_hull,
                "Keep the mesh elements whose circumcentre lies outside the box (slivers along its edge, which the "
                "quality bound does not cover; dropped by default)");
}

void add_size_options(CLI::App* cmd, SizeArgs& a) {
  auto* g = cmd->add_option_group("Element size (docs/sizing.md; the input's units, metres when georeferenced)");
  g->add_option("--max-size", a.max_size, "Longest element edge anywhere")->check(finite_number());
  g->add_option("--min-size", a.min_size, "The size function is never below this")->check(finite_number());
  g->add_option("--grade", a.grade, "Grading G: h(x) <= h(y) + G |x - y| (limgrad); e.g. 0.15")->check(finite_number());
  g->add_option("--size-from-shore", a.from_shore, "H0 RATE: size H0 at the shore, growing by RATE per unit away")
      ->expected(2)
      ->check(finite_number());
  g->add_option("--size-polygons", a.polygons, "GeoJSON polygons with a 'size' property each (lon/lat when the input is)")
      ->check(CLI::ExistingFile);
  g->add_option("--size-raster", a.raster, "A raster of sizes (any raster GDAL reads; nodata: no size there)")
      ->check(CLI::ExistingFile);
  g->add_option("--size-from-depth", a.from_depth,
                "WL: wavelength term h = T sqrt(g depth) / WL (needs --dem or --depth-from)")
      ->check(finite_number());
  g->add_option("--size-period", a.period, "T of --size-from-depth in seconds (default 44712, the M2 tide)")
      ->check(above_zero(true));
  g->add_option("--size-from-slope", a.from_slope,
                "S: slope term h = 2 pi depth / (S |grad depth|) (needs --dem or --depth-from)")
      ->check(finite_number());
}

std::vector<std::filesystem::path> size_paths(const SizeArgs& args) {
  std::vector<std::filesystem::path> out;
  for (const std::string* f : {&args.polygons, &args.raster})
    if (!f->empty()) out.emplace_back(*f);
  return out;
}

std::optional<SizeTerms> size_terms(const SizeArgs& a, const io::InputSet& set) {
  if (!a.any()) return std::nullopt;
  SizeTerms t;
  t.max_size = a.max_size;
  t.min_size = a.min_size;
  t.grade = a.grade;
  if (!a.from_shore.empty()) {
    if (set.domain.empty()) throw ParameterError("--size-from-shore needs a shoreline (rings) in the input");
    t.shore_size = a.from_shore.at(0);
    t.shore_rate = a.from_shore.at(1);
  }
  if (!a.polygons.empty()) t.polygons = io::read_size_polygons(a.polygons, set.projection);
  if (!a.raster.empty()) {
    auto dem = std::make_shared<const io::Dem>(io::read_dem(a.raster));
    auto frame = std::make_shared<const io::DemFrame>(dem, set.projection);
    t.sampled.push_back({"--size-raster " + a.raster, [dem, frame](const Point2& p) {
                           const Point2 c = frame->to_cell(p);
                           if (c[0] < -0.5 || c[1] < -0.5 || c[0] > dem->width - 0.5 || c[1] > dem->height - 0.5)
                             return std::nan("");  // beyond the raster: no size there
                           return dem->bilinear(c[0], c[1]);
                         }});
  }
  if (a.from_depth || a.from_slope) {
    if (!set.depth || !set.depth->frame)
      throw ParameterError(std::string(a.from_depth ? "--size-from-depth" : "--size-from-slope") +
                           " needs depths from a DEM: --dem or --depth-from");
    const auto frame = set.depth->frame;
    const io::DepthOptions options = set.depth->options;
    auto depth = [frame, options](const Point2& p) {
      const Point2 c = frame->to_cell(p);
      double height = frame->dem().bilinear(c[0], c[1]);
      if (options.max_height) height = std::min(height, *options.max_height);
      double d = -height;
      if (options.min_depth) d = std::max(d, *options.min_depth);
      return d;
    };
    if (a.from_depth) {
      const double wl = *a.from_depth, period = a.period;
      if (!(wl > 0)) throw ParameterError("--size-from-depth: WL must be above 0 (got " + readable(wl) + ")");
      t.sampled.push_back({"--size-from-depth " + readable(wl), [depth, wl, period](const Point2& p) {
                             const double d = depth(p);
                             return d > 0 ? period * std::sqrt(9.81 * d) / wl : std::nan("");
                           }});
    }
    if (a.from_slope) {
      const double slope = *a.from_slope;
      if (!(slope > 0)) throw ParameterError("--size-from-slope: S must be above 0 (got " + readable(slope) + ")");
      t.sampled.push_back({"--size-from-slope " + readable(slope), [depth, frame, slope](const Point2& p) {
                             // Central differences half a DEM cell each way, in the mesh's units.
                             const Point2 c = frame->to_cell(p), cx = frame->to_cell({p[0] + 1, p[1]});
                             const double cells_per_unit = std::max(std::hypot(cx[0] - c[0], cx[1] - c[1]), 1e-300);
                             const double step = 0.5 / cells_per_unit;
                             const double gx = (depth({p[0] + step, p[1]}) - depth({p[0] - step, p[1]})) / (2 * step);
                             const double gy = (depth({p[0], p[1] + step}) - depth({p[0], p[1] - step})) / (2 * step);
                             const double d = depth(p), g = std::hypot(gx, gy);
                             if (!(d > 0) || !(g > 0)) return std::nan("");
                             return 2 * std::numbers::pi * d / (slope * g);
                           }});
    }
  }
  return t;
}

void add_preview_options(CLI::App* cmd, PreviewArgs& args) {
  cmd->add_option("--preview-colour", args.colouring,
                  "Preview triangles coloured by none, quality, size, depth (with --dem, --depth-from or soundings) or "
                  "height (terrain: hillshaded)")
      ->check(CLI::IsMember({"none", "quality", "size", "depth", "height"}));
  cmd->add_option("--preview-width", args.width, "Preview width in pixels (default 1024)")->check(CLI::Range(16, io::kMaxPreviewSide));
}

void add_input_options(CLI::App* cmd, InputArgs& a, bool several) {
  auto* files = cmd->add_option("input", a.files,
                                several ? "Input files: image (png/jpg/tif), GPS track (gpx, lat/lon csv), point "
                                          "file (csv/txt/xyz), ring file, Triangle .node/.poly, GeoJSON"
                                        : "The file to describe")
                    ->check(CLI::ExistingFile);
  if (!several) files->expected(1);
  auto* group = cmd->add_option_group("Reading inputs");
  group->add_option("--spacing", a.spacing,
                    "Largest sample spacing along shorelines, tracks and segments, in the input's units "
                    "(metres for georeferenced or lon/lat input, pixels for plain images; default: 4 pixels "
                    "for images, the vertices as given otherwise)")
      ->check(above_zero(true));
  group->add_option("--water", a.water,
                    "Images: which side is water, 'light' (default), 'dark', or a colour ('#b0c4de', "
                    "'176,196,222', 'lightsteelblue') for map images");
  group->add_option("--threshold", a.threshold, "Images: grey level between water and land (default: Otsu)")
      ->check(above_zero(false));
  group->add_option("--colour-tolerance", a.colour_tolerance,
                    "Images with --water COLOUR: RGB distance still counted as water (default 40)")
      ->check(above_zero(false));
  group->add_option("--min-area", a.min_area,
                    "Images and DEMs: drop islands and lakes under this many pixels or DEM cells (default 16; "
                    "images: at least 3)")
      ->check(finite_number() & CLI::Range(1.0, 1e12));
  group->add_flag("--largest-water", a.largest_water, "Images: keep only the largest body of water");
  group->add_option("--open-radius", a.open_radius, "Images: morphological opening in pixels (removes specks of water)")
      ->check(CLI::Range(0, 100));
  group->add_option("--close-radius", a.close_radius,
                    "Images: morphological closing in pixels (removes specks of land, e.g. a border line drawn "
                    "across the water)")
      ->check(CLI::Range(0, 100));
  group->add_option("--map-box", a.map_box,
                    "Images without georeference: XMIN YMIN XMAX YMAX of the image's outer edges on the map")
      ->expected(4);
  group->add_option("--crs", a.crs, "Images: coordinate system of --map-box or of a world file without .prj "
                                    "('EPSG:4326', 'lonlat', 'UTM 16N', WKT)");
  group->add_option("--track-close-distance", a.track_close_distance,
                    "GPS tracks: a walk that ends within this many metres of its start is a shore ring (default: "
                    "twice the spacing, at least 25 m; 0: every walk stays loose points)")
      ->check(above_zero(false));
  group->add_flag("--gps-open-lines", a.gps_open_lines,
                  "GPS tracks: a walk that does not close is a constraint line (a chain of mesh edges in the water: a "
                  "breakwater, a channel's edge, a survey line), not loose points");
  group->add_flag("--lonlat", a.lonlat, "Point and ring files hold lon,lat degrees (projected to metres)");
  group->add_option("--projection", a.projection,
                    "Projection of lon/lat input, and of projected input whose scale leaves 0.1 % of 1 over the "
                    "data (Web Mercator, UTM across zones; others keep their own metres): 'local' (transverse "
                    "Mercator centred on the data, default) or 'utm' (the data's UTM zone)")
      ->check(CLI::IsMember({"utm", "local"}));
  if (several) {
    auto* dem = cmd->add_option_group("Terrain and depths");
    dem->add_option("--dem", a.dem,
                    "A DEM (any raster GDAL reads, heights positive up) as an input: the shoreline is its contour "
                    "at --shoreline-level, water below; mesh nodes get their depths from it")
        ->check(CLI::ExistingFile);
    dem->add_option("--shoreline-level", a.shoreline_level, "--dem: height of the shoreline in metres (default 0)");
    dem->add_option("--land-up-to", a.land_up_to,
                    "--dem: one mesh of the water and of the land below this height (metres, above "
                    "--shoreline-level), the shoreline a chain of mesh edges inside it, heights on every node");
    dem->add_option("--max-error", a.max_error,
                    "--land-up-to: refine the land until the mesh is within this height (metres) of every DEM "
                    "sample on land");
    dem->add_option("--depth-from", a.depth_from, "A DEM giving the depths at mesh nodes beside other inputs")
        ->check(CLI::ExistingFile);
    dem->add_option("--min-depth", a.min_depth, "Depths below this value (metres, positive down) are raised to it");
    dem->add_option("--open-boundary", a.open_boundary,
                    "fort.14: lines along which the boundary is open ocean, beside the DEM's or image's edge: GeoJSON "
                    "LineStrings, or a text file of lon,lat points (x,y for unprojected input), a blank line "
                    "between lines")
        ->check(CLI::ExistingFile);
    dem->add_option("--open-boundary-distance", a.open_boundary_distance,
                    "--open-boundary: a boundary node this near a line (metres, or the input's units) is on it "
                    "(default: a millionth of the input's extent, i.e. on the line)")
        ->check(above_zero(true));
  }
  add_quiet_option(cmd, a.quiet);
  cmd->callback([&a, several, cmd] {
    if (a.files.empty() && (!several || a.dem.empty()))
      throw CLI::RequiredError(several ? "an input file or --dem" : "input");
    if (!a.dem.empty() && !a.depth_from.empty())
      throw CLI::ValidationError("--depth-from", "--dem is the depth source already; give one of them");
    if ((a.land_up_to || a.max_error) && cmd->get_name() != "mesh")
      throw CLI::ValidationError(a.land_up_to ? "--land-up-to" : "--max-error",
                                 "is for `mesh` (one land-and-water mesh of a DEM), not for `" + cmd->get_name() + "`");
    if (a.land_up_to && a.dem.empty())
      throw CLI::ValidationError("--land-up-to", "meshes a DEM's land and water: give --dem FILE");
    if (a.max_error && !a.land_up_to)
      throw CLI::ValidationError("--max-error", "bounds the error on land: give --land-up-to Z (and --dem FILE)");
    if (a.open_boundary_distance && a.open_boundary.empty())
      throw CLI::ValidationError("--open-boundary-distance", "applies to the lines of --open-boundary FILE; give one");
  });
}

namespace {

bool parse_int(const std::string& s, int& v) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc{} && end == s.data() + s.size();
}

}  // namespace

std::array<int, 3> parse_colour(const std::string& text) {
  std::string t;
  for (char c : text)
    if (!std::isspace(static_cast<unsigned char>(c))) t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::pair<const char*, std::array<int, 3>> names[] = {
      {"blue", {0, 0, 255}},       {"lightsteelblue", {176, 196, 222}}, {"lightblue", {173, 216, 230}},
      {"cyan", {0, 255, 255}},     {"navy", {0, 0, 128}},               {"white", {255, 255, 255}},
      {"black", {0, 0, 0}},        {"steelblue", {70, 130, 180}},       {"skyblue", {135, 206, 235}}};
  for (const auto& [name, rgb] : names)
    if (t == name) return rgb;
  std::array<int, 3> rgb{};
  if (t.size() == 7 && t[0] == '#') {
    for (int i = 0; i < 3; ++i) {
      const std::string h = t.substr(1 + 2 * i, 2);
      const auto [end, ec] = std::from_chars(h.data(), h.data() + 2, rgb[i], 16);
      if (ec != std::errc{} || end != h.data() + 2) throw InputError("bad colour '" + text + "' (expected #rrggbb)");
    }
    return rgb;
  }
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = t.find(',', start);
    const std::string part = t.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!parse_int(part, rgb[i]) || rgb[i] < 0 || rgb[i] > 255 || (i < 2) == (comma == std::string::npos))
      throw InputError("bad --water '" + text + "': expected light, dark, #rrggbb, R,G,B (0..255) or a colour name");
    start = comma + 1;
  }
  return rgb;
}

io::InputOptions input_options(const InputArgs& a) {
  io::InputOptions o;
  o.lonlat = a.lonlat;
  o.projection_choice = a.projection == "utm" ? io::ProjectionChoice::Utm : io::ProjectionChoice::LocalTransverseMercator;
  if (a.water == "light") {
    o.image.water = io::WaterSide::Light;
  } else if (a.water == "dark") {
    o.image.water = io::WaterSide::Dark;
  } else {
    o.image.water = io::WaterSide::Colour;
    o.image.water_colour = parse_colour(a.water);
  }
  o.image.threshold = a.threshold;
  o.image.colour_tolerance = a.colour_tolerance;
  o.image.min_area = a.min_area;
  o.image.largest_water_only = a.largest_water;
  o.image.open_radius = a.open_radius;
  o.image.close_radius = a.close_radius;
  if (!a.map_box.empty()) o.image.georeference.box = io::MapBox{a.map_box[0], a.map_box[1], a.map_box[2], a.map_box[3]};
  o.image.georeference.crs = a.crs;
  if (a.track_close_distance) o.track.close_tolerance = *a.track_close_distance;
  o.track.open_lines = a.gps_open_lines;
  if (a.spacing) {
    o.image.spacing = *a.spacing;
    o.image.spacing_unit = io::ImageTraceOptions::SpacingUnit::Map;
    o.track.spacing = *a.spacing;
    o.poly.spacing = *a.spacing;
    o.geojson.spacing = *a.spacing;
    o.ring_spacing = *a.spacing;
  }
  return o;
}

io::InputSet read_user_inputs(const InputArgs& a, Progress& progress) {
  const io::InputOptions options = input_options(a);
  std::vector<io::InputSet> sets;
  std::shared_ptr<const io::Dem> depth_dem;
  std::vector<Point2> sounding_points;
  std::vector<double> sounding_depths;
  if (!a.dem.empty()) {
    // First, so that its projection is the one the other inputs use.
    progress.stage("tracing " + std::filesystem::path(a.dem).filename().string());
    io::DemTraceOptions d;
    d.level = a.shoreline_level;
    d.image = options.image;
    d.image.projection = options.projection;
    d.image.projection_choice = options.projection_choice;
    io::TracedDem traced = io::trace_dem(a.dem, d);
    depth_dem = traced.dem;
    sets.push_back(std::move(traced.traced.input));
  }
  for (const std::string& file : a.files) {
    const bool image = io::is_image_input(file);  // for the label: detecting a text file's format reads it whole
    progress.stage((image ? "tracing " : "reading ") + std::filesystem::path(file).filename().string());
    // One projection for all: the first lon/lat input fixes it for the ones after it (inputs before it
    // have none).
    io::InputOptions o = options;
    for (const auto& s : sets)
      if (!s.projection.is_none()) {
        o.projection = s.projection;
        break;
      }
    sets.push_back(io::read_input(file, o));
    if (sets.back().dimension == 3 && !a.three_d) {
      // x, y, depth soundings: 2D points whose third column is a depth (--dim 3 meshes them in 3D).
      io::InputSet& s = sets.back();
      for (const Point3& p : s.points3) {
        s.points.push_back({p[0], p[1]});
        sounding_points.push_back({p[0], p[1]});
        sounding_depths.push_back(p[2]);
      }
      s.points3.clear();
      s.dimension = 2;
    }
  }
  io::InputSet set = sets.size() == 1 ? std::move(sets.front()) : io::merge(sets);
  const bool dem_depths = depth_dem || !a.depth_from.empty();
  if (!sounding_points.empty() && dem_depths) {
    set.notes.push_back("third column ignored: the depths come from the DEM (--dim 3 meshes the points in 3D)");
  } else if (!sounding_points.empty()) {
    auto source = std::make_shared<io::DepthSource>();
    source->soundings = std::make_shared<const io::Soundings>(sounding_points, sounding_depths);
    source->options.min_depth = a.min_depth;
    set.depth = std::move(source);
    set.notes.push_back("third column: depths (positive down) at the " + std::to_string(sounding_points.size()) +
                        " soundings, interpolated linearly between them (--dim 3 meshes the points in 3D)");
  }
  if (!a.depth_from.empty()) depth_dem = std::make_shared<const io::Dem>(io::read_dem(a.depth_from));
  if (depth_dem) {
    auto source = std::make_shared<io::DepthSource>();
    source->frame = std::make_shared<const io::DemFrame>(depth_dem, set.projection);
    source->options.min_depth = a.min_depth;
    if (!a.dem.empty()) source->options.max_height = a.shoreline_level;
    set.depth = std::move(source);
    set.notes.push_back("depths at nodes from " + depth_dem->file + " (" + std::to_string(depth_dem->width) + " x " +
                        std::to_string(depth_dem->height) + " cells, heights " + approx(depth_dem->min, 5) + " .. " +
                        approx(depth_dem->max, 5) + " m), positive down" +
                        (a.min_depth ? ", at least " + approx(*a.min_depth, 5) + " m" : std::string()));
  } else if (a.min_depth && !set.depth) {
    throw ParameterError("--min-depth needs a depth source (--dem, --depth-from or x,y,depth soundings)");
  }
  if (!a.open_boundary.empty()) {
    if (set.dimension != 2) throw ParameterError("--open-boundary is for 2D meshes (fort.14)");
    auto ob = std::make_shared<io::OpenBoundary>(io::read_open_boundary(a.open_boundary, set.projection));
    if (a.open_boundary_distance) {
      ob->distance = *a.open_boundary_distance;
    } else {
      // On the line, up to the rounding of projecting and of splitting the shore.
      Point2 lo = set.points.front(), hi = lo;
      for (const Point2& p : set.points)
        for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
      ob->distance = 1e-6 * std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
    }
    set.notes.push_back("open boundaries also along " + std::to_string(ob->lines.size()) + " line(s) of " +
                        a.open_boundary + " (boundary nodes within " + approx(ob->distance, 3) + " " +
                        io::to_string(set.units) + ")");
    set.open_boundary = std::move(ob);
  }
  return set;
}

std::vector<std::filesystem::path> input_paths(const InputArgs& args, const io::InputSet& set) {
  std::vector<std::filesystem::path> paths(args.files.begin(), args.files.end());
  for (const io::Source& s : set.sources) paths.emplace_back(s.file);
  for (const std::string* dem : {&args.dem, &args.depth_from})
    if (!dem->empty()) paths.emplace_back(*dem);
  return paths;
}

}  // namespace shoremesh::tool
