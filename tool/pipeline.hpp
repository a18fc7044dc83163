#pragma once
// The steps `mesh` and `edit` share, each a call into the library: engine parameters and box from the
// options, the mesh of a point set (clipped to the water when the input has rings), exports, previews and
// the quality summary in the user's units.
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "shoremesh/box_transform.hpp"
#include "shoremesh/domain.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/atomic_file.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/input_set.hpp"
#include "shoremesh/io/preview.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/parameters.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/shore_session.hpp"
#include "shoremesh/size_function.hpp"
#include "shoremesh/well_spaced.hpp"
#include "user_frame.hpp"

namespace shoremesh::tool {

// --box X0 Y0 [Z0] SIDE (empty: none). InputError for the wrong count or a non-positive side.
template <int D>
std::optional<BoxTransform<D>> parse_box(const std::vector<double>& numbers);

// "msh", "vtu", "node", "fort14", "geojson", "obj", "ply", "off" (ParameterError otherwise).
io::ExportFormat parse_export_format(const std::string& name);
// True when `path` names the point-set CSV (`.csv`), not a mesh.
bool is_point_set_path(const std::filesystem::path& path);
// Adds a mesh output (`format`) or, with nullopt, a point set to `batch`, the Triangle format's .node and
// .ele both, and returns the temporary path to write it to. `option` names where it came from ("-o").
std::filesystem::path stage_output(io::OutputBatch& batch, const std::filesystem::path& output,
                                   std::optional<io::ExportFormat> format, const std::string& option);

// The input points of the chosen dimension (3D points dropped to x, y for dim 2). InputError when dim 3
// is asked of 2D input.
template <int D>
std::vector<Point<D>> input_points(const io::InputSet& set);

// What the library's session (and a fresh run) takes: the input points of the chosen dimension, and in 2D
// the rings with their offsets.
template <int D>
SessionInput<D> session_input(const io::InputSet& set);

// What the engine and the mesh take: the input points, then (2D with rings) the canonical split points of
// the shore (refine_input), which make every shore segment a mesh edge; the mesh's domain is the rings
// with those splits in them.
// With size control (2D) the size seeds follow the splits, the box is fixed to the input's before they
// join, and the field is kept for the summary.
template <int D>
struct EngineInput {
  std::vector<Point<D>> points;
  std::size_t input_count = 0;  // the user's input points, first in `points`
  std::size_t split_count = 0, seed_count = 0;  // then the splits, then the size seeds
  Domain2 domain;               // refined rings (2D), empty otherwise
  std::optional<BoxTransform<D>> box;  // the box to give the engine (nullopt: fitted to `points`)
  std::shared_ptr<const SizeField> size;
};
template <int D>
EngineInput<D> engine_input(const io::InputSet& set, const std::optional<BoxTransform<D>>& box,
                            const std::optional<SizeTerms>& size = std::nullopt);

// "size: h 4,000 .. 5,000 m (grid 512 x 512), graded 0.15 (--grade 0.15); longest edge / h(centroid) <= 0.98
// (mean 0.71), worst near ...; 7,234 size seeds\n"
std::string size_text(const SizeField& field, const Mesh<2>& mesh, std::size_t seeds, const UserFrame& frame);

// An engine error about particular input points, said with the file and line they came from (about the
// points as a whole: with the input files).
[[noreturn]] void rethrow_with_origin(const PointInputError& e, const io::InputSet& set);

// Exports `mesh` to `path` (format from the extension unless given); GeoJSON and fort.14 in lon/lat when
// the input was projected. Points numbered in `order` when given (io::MeshSnapshot).
template <int D>
void export_mesh_file(const Mesh<D>& mesh, const std::filesystem::path& path, std::optional<io::ExportFormat> format,
                      const UserFrame& frame, std::span<const Point<D>> order = {});

// Depths at the view's nodes from the frame's depth source (empty without one).
std::vector<double> mesh_depths(const io::MeshView<2>& view, const UserFrame& frame);

// "depths: 1234 nodes, 0.5 .. 1437 m, mean 210.3 m (positive down)\n"; empty for no depths.
std::string depth_text(std::span<const double> depths);

struct PreviewArgs {
  std::string colouring = "none";  // none | quality | size | depth | height (terrain)
  int width = 1024;
  double rho = 1.4142135623730951;
  std::shared_ptr<const SizeField> size;  // with size control: the size colouring shows longest edge / h
};
io::PreviewOptions preview_options(const PreviewArgs& args);

// `frame` gives the depths for the depth colouring.
template <int D>
void write_preview(const Mesh<D>& mesh, const std::filesystem::path& path, const PreviewArgs& args,
                   const UserFrame* frame = nullptr);

// The numbers of the quality summary, for text and JSON.
struct QualityNumbers {
  std::size_t elements = 0, points = 0, input_points = 0, steiner_points = 0;
  double min_angle = 0, max_angle = 0, min_angle_bound = 0, rho = 0;
  double max_radius_edge = 0, covered_max_radius_edge = 0;
  std::size_t covered = 0, covered_meeting_bound = 0, meeting_bound = 0;
  std::optional<std::size_t> left_out_at_box_edge;  // when the mesh is clipped to the box (not --keep-hull)
  std::string worst_at;                 // the worst element's centroid in the user's frame
  std::optional<std::size_t> shore_segments, shore_covered;
  std::size_t shore_splits = 0;  // input points the shore's splits added (counted in input_points)
  // Elements below the bound that the shore's constraints made (not Delaunay: a point hidden behind the
  // shore lies in their circumcircle), and the others (none, unless the box cuts the water).
  std::size_t shore_below_bound = 0, interior_below_bound = 0;
  // Where the elements below the bound are (2D with rings): those whose centroid is nearer to an input
  // corner sharper than 60 degrees than the shorter of its two segments (SharpCorner), the exception of
  // every quality mesher; how many such corners there are and how many have their water outside (spikes
  // of land); the others, and where the worst of them is.
  std::size_t below_bound_at_sharp_corners = 0, sharp_corners = 0, sharp_corners_of_land = 0;
  std::string worst_elsewhere_at;
  double shore_worst_depth = 0;
  std::string shore_worst_depth_text;  // in the user's units
};

// `input_rings`: the rings as given (before the shore's splits), for the sharp corners' reach; the mesh's
// refined rings otherwise.
template <int D>
QualityNumbers quality_numbers(const Mesh<D>& mesh, double rho, const BoxTransform<D>& box, const UserFrame& frame,
                               const Domain2* input_rings = nullptr);

// A few lines for a person, the first "quality: ..." one stable for scripts.
std::string quality_text(const QualityNumbers& q, int dimension);

// What the input holds, a few lines (files, points, rings, units, projection, notes).
std::string describe_input(const io::InputSet& set);

}  // namespace shoremesh::tool
