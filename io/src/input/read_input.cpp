#include "shoremesh/io/read_input.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "shoremesh/error.hpp"
#include "shoremesh/io/point_file.hpp"
#include "shoremesh/io/ring_file.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

const char* to_string(InputFormat f) {
  switch (f) {
    case InputFormat::Image: return "image";
    case InputFormat::Gpx: return "GPX";
    case InputFormat::TrackCsv: return "lat/lon CSV track";
    case InputFormat::RingFile: return "ring file";
    case InputFormat::PointFile: return "point file";
    case InputFormat::Node: return "Triangle .node";
    case InputFormat::Poly: return "Triangle .poly";
    case InputFormat::GeoJson: return "GeoJSON";
  }
  return "?";
}

namespace {

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

InputFormat text_format(std::string_view text) {
  if (csv_header_has_lat_lon(text)) return InputFormat::TrackCsv;
  if (looks_like_ring_file(text)) return InputFormat::RingFile;
  return InputFormat::PointFile;
}

std::optional<InputFormat> format_from_extension(const std::string& path) {
  const std::string ext = extension(path);
  for (const char* e : {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".pgm", ".ppm", ".pnm"})
    if (ext == e) return InputFormat::Image;
  if (ext == ".gpx") return InputFormat::Gpx;
  if (ext == ".node") return InputFormat::Node;
  if (ext == ".poly") return InputFormat::Poly;
  if (ext == ".geojson" || ext == ".json") return InputFormat::GeoJson;
  if (ext == ".rings") return InputFormat::RingFile;  // what `edit` exports as its shoreline
  return std::nullopt;
}

bool is_text_extension(const std::string& path) {
  const std::string ext = extension(path);
  return ext == ".csv" || ext == ".txt" || ext == ".xyz" || ext == ".dat";
}

InputSet points_to_input(const PointFile& pf, const std::string& file, const InputOptions& opt) {
  InputSet set;
  set.dimension = pf.dimension;
  set.units = Units::MapUnits;
  if (opt.lonlat) {
    std::vector<LonLat> all;
    for (const auto& p : pf.points2) all.push_back({p[0], p[1]});
    for (const auto& p : pf.points3) all.push_back({p[0], p[1]});
    set.units = Units::Metres;
    ChosenProjection chosen = lonlat_projection(opt.projection, all, opt.projection_choice, file);
    set.projection = chosen.projection;
    set.notes.push_back(chosen.note);
  }
  auto project = [&](double x, double y, std::size_t k) -> Point2 {
    if (!opt.lonlat) return {x, y};
    try {
      return set.projection.forward({x, y});
    } catch (const std::domain_error& e) {
      throw InputError(e.what(), file, pf.lines[k]);
    }
  };
  set.sources.push_back({file, Source::Location::Line});
  for (std::size_t k = 0; k < pf.lines.size(); ++k) {
    if (pf.dimension == 2) {
      set.points.push_back(project(pf.points2[k][0], pf.points2[k][1], k));
    } else {
      const Point2 xy = project(pf.points3[k][0], pf.points3[k][1], k);
      set.points3.push_back({xy[0], xy[1], pf.points3[k][2]});
    }
    set.origins.push_back({0, PointOrigin::kNoRing, pf.lines[k]});
  }
  return set;
}

}  // namespace

InputFormat detect_input_format(const std::string& path) {
  if (const auto f = format_from_extension(path)) return *f;
  if (is_text_extension(path)) return text_format(detail::read_text_file(path));
  throw InputError("unknown input format (extension " + detail::quoted(extension(path)) +
                       "); expected png/jpg/tif, gpx, csv/txt/xyz, rings, node, poly or geojson",
                   path);
}

bool is_image_input(const std::string& path) { return format_from_extension(path) == InputFormat::Image; }

InputSet read_input(const std::string& path, const InputOptions& options) {
  const auto projection = options.projection;
  const auto choice = options.projection_choice;
  std::optional<InputFormat> format = format_from_extension(path);
  std::string text;
  if (!format) {
    if (!is_text_extension(path)) detect_input_format(path);  // throws the unknown-format error
    text = detail::read_text_file(path);
    // text_format's choice, the text parsed once when it is rings.
    if (csv_header_has_lat_lon(text)) {
      format = InputFormat::TrackCsv;
    } else if (auto rings = parse_ring_file_if_rings(text, path)) {
      return ring_file_to_input(*rings, path, options.lonlat, projection, choice, options.ring_spacing);
    } else {
      format = InputFormat::PointFile;
    }
  }
  switch (*format) {
    case InputFormat::Image: {
      ImageTraceOptions o = options.image;
      if (projection) o.projection = projection;
      o.projection_choice = choice;
      return trace_image(path, o).input;
    }
    case InputFormat::Gpx:
    case InputFormat::TrackCsv: {
      TrackOptions o = options.track;
      if (projection) o.projection = projection;
      o.choice = choice;
      const GpsData data = *format == InputFormat::Gpx ? read_gpx(path) : parse_track_csv_text(text, path);
      return gps_to_input(data, path, o);
    }
    case InputFormat::RingFile:
      if (text.empty()) text = detail::read_text_file(path);  // a .rings file, known by its extension
      return ring_file_to_input(parse_ring_file_text(text, path), path, options.lonlat, projection, choice,
                                options.ring_spacing);
    case InputFormat::PointFile:
      return points_to_input(parse_point_file_text(text, path), path, options);
    case InputFormat::Node:
      return pslg_to_input(read_node_file(path), options.poly);
    case InputFormat::Poly:
      return pslg_to_input(read_poly_file(path), options.poly);
    case InputFormat::GeoJson: {
      GeoJsonOptions o = options.geojson;
      if (projection) o.projection = projection;
      o.choice = choice;
      return read_geojson(path, o);
    }
  }
  throw InputError("unknown input format", path);
}

InputSet read_inputs(const std::vector<std::string>& paths, const InputOptions& options) {
  if (paths.empty()) throw InputError("no input files");
  InputOptions opt = options;
  std::vector<InputSet> sets;
  for (const auto& p : paths) {
    sets.push_back(read_input(p, opt));
    if (!opt.projection && !sets.back().projection.is_none()) opt.projection = sets.back().projection;
  }
  // A geographic input read before the first projection was fixed needs the same projection: reread it.
  if (opt.projection)
    for (std::size_t i = 0; i < sets.size(); ++i)
      if (!sets[i].projection.is_none() && !(sets[i].projection == *opt.projection)) sets[i] = read_input(paths[i], opt);
  return sets.size() == 1 ? std::move(sets.front()) : merge(sets);
}

}  // namespace shoremesh::io
