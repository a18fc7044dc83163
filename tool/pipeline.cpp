#include "pipeline.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <cctype>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <span>
#include <sstream>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include "shoremesh/error.hpp"
#include "shoremesh/point_table.hpp"
#include "shoremesh/io/dem.hpp"
#include "shoremesh/io/open_boundary.hpp"
#include "shoremesh/io/soundings.hpp"
#include "shoremesh/mesh_quality.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/shore_session.hpp"

namespace shoremesh::tool {

template <int D>
std::optional<BoxTransform<D>> parse_box(const std::vector<double>& numbers) {
  if (numbers.empty()) return std::nullopt;
  if (numbers.size() != D + 1)
    throw ParameterError("--box takes " + std::to_string(D + 1) + " numbers for " + std::to_string(D) + "D input (X0 Y0" +
                     (D == 3 ? " Z0" : "") + " SIDE)");
  BoxTransform<D> b;
  for (int i = 0; i < D; ++i) b.origin[i] = numbers[std::size_t(i)];
  b.side = numbers[D];
  if (!(b.side > 0)) throw ParameterError("--box: the side must be above 0 (got " + approx(b.side) + ")");
  if (b.side < kSmallestSide || b.side > 2 * kLargestCoordinate)
    throw ParameterError("--box: the side " + readable(b.side) + " is outside what the engine represents (" +
                         readable(kSmallestSide) + " to " + readable(2 * kLargestCoordinate) + ")");
  return b;
}

io::ExportFormat parse_export_format(const std::string& name) {
  using F = io::ExportFormat;
  if (name == "msh") return F::Gmsh;
  if (name == "vtu") return F::Vtu;
  if (name == "node") return F::Triangle;
  if (name == "fort14") return F::Adcirc;
  if (name == "geojson") return F::GeoJson;
  if (name == "obj") return F::Obj;
  if (name == "ply") return F::Ply;
  if (name == "off") return F::Off;
  throw ParameterError("unknown format '" + name + "' (msh, vtu, node, fort14, geojson, obj, ply, off)");
}

bool is_point_set_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".csv";
}

std::filesystem::path stage_output(io::OutputBatch& batch, const std::filesystem::path& output,
                                   std::optional<io::ExportFormat> format, const std::string& option) {
  if (format != io::ExportFormat::Triangle) return batch.add(output, option);
  // Two files: the writer puts the .ele beside the .node it is given.
  std::filesystem::path node = output, ele = output;
  const std::filesystem::path staged = batch.add(node.replace_extension(".node"), option);
  std::filesystem::path staged_ele = staged;
  batch.add_written_as(ele.replace_extension(".ele"), staged_ele.replace_extension(".ele"), option);
  return staged;
}

template <int D>
std::vector<Point<D>> input_points(const io::InputSet& set) {
  if constexpr (D == 2) {
    if (set.dimension == 2) return set.points;
    std::vector<Point2> out;
    out.reserve(set.points3.size());
    for (const auto& p : set.points3) out.push_back({p[0], p[1]});
    return out;
  } else {
    if (set.dimension != 3) throw InputError("--dim 3 needs 3D input (a point file with three columns)");
    return set.points3;
  }
}

template <int D>
SessionInput<D> session_input(const io::InputSet& set) {
  SessionInput<D> in;
  in.points = input_points<D>(set);
  if constexpr (D == 2) {
    in.rings = set.domain;
    in.ring_ids = set.ring_ids;
  }
  return in;
}

template <int D>
EngineInput<D> engine_input(const io::InputSet& set, const std::optional<BoxTransform<D>>& box,
                            const std::optional<SizeTerms>& size) {
  SessionInput<D> session = session_input<D>(set);
  EngineInput<D> in;
  in.box = box;
  std::vector<Point2> splits, seeds;
  if constexpr (D == 2) {
    if (size) {
      in.box = run_box(session, box);
      in.size = std::make_shared<const SizeField>(*size, *in.box, session.rings);
    }
    if (const auto refinement = refine_input(session, box, in.size)) {
      splits = refinement->split_points();
      in.domain = refinement->refined();
    }
    if (in.size) seeds = size_seeds(*in.size, in.domain);
  } else if (size) {
    throw ParameterError("size control (--max-size and the other size options) is for 2D meshes");
  }
  in.input_count = session.points.size();
  in.split_count = splits.size();
  in.seed_count = seeds.size();
  in.points = std::move(session.points);
  if constexpr (D == 2) {
    in.points.insert(in.points.end(), splits.begin(), splits.end());
    in.points.insert(in.points.end(), seeds.begin(), seeds.end());
  }
  return in;
}

std::string size_text(const SizeField& field, const Mesh<2>& mesh, std::size_t seeds, const UserFrame& frame) {
  const SizeSummary s = field.summary();
  const SizeRatio r = size_ratio(field, mesh.points(), mesh.elements());
  std::ostringstream out;
  out << "size: h " << frame.length(s.min) << " .. " << frame.length(s.max) << " over the water (grid " << s.grid_cells
      << " x " << s.grid_cells << "), grading " << approx(s.grading, 3);
  if (field.terms().grade) out << " (--grade " << approx(*field.terms().grade) << ")";
  out << "; longest edge / h(centroid) <= " << approx(r.worst, 4) << " (mean " << approx(r.mean, 3) << ")";
  if (r.worst > 0) out << ", worst near " << frame.point(r.worst_at);
  out << "; " << seeds << " size seeds among the input points\n";
  return out.str();
}

void rethrow_with_origin(const PointInputError& e, const io::InputSet& set) {
  if (e.points().empty() || e.points().front() >= set.origins.size()) {
    // About the input points as a whole (their extent, their resolution) or a shore split: the files.
    std::string files;
    for (const io::Source& s : set.sources) files.append(files.empty() ? "" : ", ").append(s.file);
    throw InputError(e.message(), files);
  }
  const io::PointOrigin& o = set.origins[e.points().front()];
  const io::Source& s = set.sources.at(o.source);
  if (s.location == io::Source::Location::Line && o.ring == io::PointOrigin::kNoRing)
    throw InputError(e.message(), s.file, o.location);
  throw InputError(io::describe_origin(set, e.points().front()) + ": " + e.message());
}

template <int D>
void export_mesh_file(const Mesh<D>& mesh, const std::filesystem::path& path, std::optional<io::ExportFormat> format,
                      const UserFrame& frame, std::span<const Point<D>> order) {
  const io::MeshSnapshot<D> snapshot(mesh, order, /*in_place=*/true);  // the mesh outlives this call
  io::MeshView<D> view = snapshot.view();
  if (D == 2 && !frame.projection.is_none()) {
    const io::Projection projection = frame.projection;
    view = snapshot.view([projection](const Point2& p) {
      const io::LonLat ll = projection.reverse(p);
      return Point2{ll.lon, ll.lat};
    });
  }
  std::vector<double> depths;
  std::vector<std::uint8_t> open;
  if constexpr (D == 2) {
    depths = mesh_depths(view, frame);
    view.depths = depths;
    // Without rings no land is known: the mesh ends where the water reaches the box, all open.
    if (!frame.open_points.empty() || frame.open_boundary || mesh.domain().empty()) {
      open.resize(view.points.size(), 1);
      if (!mesh.domain().empty()) {
        for (std::size_t i = 0; i < open.size(); ++i)
          open[i] = std::binary_search(frame.open_points.begin(), frame.open_points.end(), view.points[i]);
        if (frame.open_boundary) io::mark_open_boundary(*frame.open_boundary, view.points, view.boundary, open);
      }
      view.open_nodes = open;
    }
  }
  io::export_mesh<D>(path, view, format);
}

std::vector<double> mesh_depths(const io::MeshView<2>& view, const UserFrame& frame) {
  if (!frame.depth) return {};
  if (!frame.depth->frame) return io::sounding_depths(*frame.depth->soundings, view.points, frame.depth->options);
  return io::node_depths(*frame.depth->frame, view.points, view.elements, frame.depth->options);
}

std::string depth_text(std::span<const double> depths) {
  if (depths.empty()) return {};
  const auto [lo, hi] = std::minmax_element(depths.begin(), depths.end());
  double sum = 0;
  for (double d : depths) sum += d;
  return "depths: " + std::to_string(depths.size()) + " nodes, " + approx(*lo, 5) + " .. " + approx(*hi, 5) +
         " m, mean " + approx(sum / static_cast<double>(depths.size()), 5) + " m (positive down)\n";
}

io::PreviewOptions preview_options(const PreviewArgs& args) {
  io::PreviewOptions o;
  o.width = args.width;
  o.rho = args.rho;
  if (args.colouring == "quality") o.colouring = io::PreviewColouring::Quality;
  else if (args.colouring == "size") o.colouring = io::PreviewColouring::Size;
  else if (args.colouring == "depth") o.colouring = io::PreviewColouring::Depth;
  else if (args.colouring == "height") o.colouring = io::PreviewColouring::Height;
  else if (args.colouring != "none") throw ParameterError("--preview-colour must be none, quality, size, depth or height");
  return o;
}

template <int D>
void write_preview(const Mesh<D>& mesh, const std::filesystem::path& path, const PreviewArgs& args,
                   const UserFrame* frame) {
  const io::MeshSnapshot<D> snapshot(mesh);
  io::MeshView<D> view = snapshot.view();
  std::vector<double> depths;
  if constexpr (D == 2)
    if (frame && args.colouring == "depth") depths = mesh_depths(view, *frame), view.depths = depths;
  io::PreviewOptions options = preview_options(args);
  if (args.size && args.colouring == "size") {
    // The view may be in lon/lat for exports, never for previews: the mesh's frame, as h is.
    const auto field = args.size;
    options.size_at = [field](const Point2& p) { return field->at(p); };
  }
  io::render_preview<D>(path, view, options);
}

namespace {
namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox = bg::model::box<BPoint>;
}  // namespace

// The elements below the bound of a mesh with rings: those the shore's constraints made and the others,
// those at a sharp input corner and the worst elsewhere (quality_numbers; sets those fields of q only).
static void shore_quality(const Mesh<2>& mesh, std::span<const Element<2>> elements, double rho, const UserFrame& frame,
                          const Domain2* input_rings, QualityNumbers& q) {
  // Elements below the bound: those the shore's constraints made (their circumcircle holds a mesh point
  // hidden behind the shore, so they are not Delaunay) and the others. Below the bound are few elements
  // (tens at a detailed shore): their circles' boxes go in a tree, and each mesh point asks it which of
  // them hold it, on every thread.
  std::vector<std::pair<ElementCorners<2>, ElementShape<2>>> below;  // the elements below the bound
  std::vector<double> radius;                                         // their circumcircles' radii
  // Their indices in element order, whatever the split of the work.
  const std::vector<std::size_t> below_index = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, elements.size(), 16384), std::vector<std::size_t>(),
      [&](const tbb::blocked_range<std::size_t>& range, std::vector<std::size_t> found) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const auto& e = elements[i];
          const ElementCorners<2> c{mesh.points()[e[0]], mesh.points()[e[1]], mesh.points()[e[2]]};
          if (radius_edge<2>(c) > rho) found.push_back(i);  // the shape's ratio, without its angles
        }
        return found;
      },
      [](std::vector<std::size_t> a, const std::vector<std::size_t>& b) {
        a.insert(a.end(), b.begin(), b.end());
        return a;
      });
  for (const std::size_t i : below_index) {
    const auto& e = elements[i];
    const ElementCorners<2> c{mesh.points()[e[0]], mesh.points()[e[1]], mesh.points()[e[2]]};
    const ElementShape<2> shape = element_shape<2>(c);
    below.emplace_back(c, shape);
    radius.push_back(std::hypot(c[0][0] - shape.circumcentre[0], c[0][1] - shape.circumcentre[1]));
  }
  if (!below.empty()) {
    using Circle = std::pair<BBox, std::uint32_t>;
    std::vector<Circle> boxes;
    boxes.reserve(below.size());
    for (std::uint32_t k = 0; k < below.size(); ++k) {
      const Point2& o = below[k].second.circumcentre;
      const double r = radius[k];
      boxes.emplace_back(BBox(BPoint(o[0] - r, o[1] - r), BPoint(o[0] + r, o[1] + r)), k);
    }
    const bgi::rtree<Circle, bgi::quadratic<16>> circles(boxes.begin(), boxes.end());
    // Strictly inside the circle (by more than its rounding): such a point is in the box about it.
    const std::vector<bool> hidden = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, mesh.points().size(), 16384), std::vector<bool>(below.size(), false),
        [&](const tbb::blocked_range<std::size_t>& range, std::vector<bool> hides) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Point2& p = mesh.points()[i];
            for (auto it = circles.qbegin(bgi::intersects(BPoint(p[0], p[1]))); it != circles.qend(); ++it) {
              const Point2& o = below[it->second].second.circumcentre;
              if (std::hypot(p[0] - o[0], p[1] - o[1]) < radius[it->second] * (1 - 1e-9)) hides[it->second] = true;
            }
          }
          return hides;
        },
        [](std::vector<bool> a, const std::vector<bool>& b) {
          for (std::size_t k = 0; k < a.size(); ++k) a[k] = a[k] || b[k];
          return a;
        });
    for (const bool hides : hidden) ++(hides ? q.shore_below_bound : q.interior_below_bound);
  }
  // Those near an input corner sharper than 60 degrees (core: sharp_corners, docs/conforming.md "Where
  // the bound may fail"), from the input's segments: the refined rings' would give the splits' pieces.
  const std::vector<SharpCorner> corners = sharp_corners(input_rings ? *input_rings : mesh.domain());
  q.sharp_corners = corners.size();
  // A corner whose water lies outside it (a spike of land): its apex's water angle, the sum of the
  // mesh's angles there, is reflex. The apexes sorted, each with its sum: a few against every corner.
  PointTable<double> apex_angle;
  for (const SharpCorner& c : corners) apex_angle.add(c.apex, 0.0);
  apex_angle.seal();
  auto angles_of = [](const ElementCorners<2>& c) {
    std::array<double, 3> a{};
    for (std::size_t i = 0; i < 3; ++i) {
      const Point2 &p = c[i], &u = c[(i + 1) % 3], &w = c[(i + 2) % 3];
      a[i] = std::atan2(std::abs((u[0] - p[0]) * (w[1] - p[1]) - (u[1] - p[1]) * (w[0] - p[0])),
                        (u[0] - p[0]) * (w[0] - p[0]) + (u[1] - p[1]) * (w[1] - p[1]));
    }
    return a;
  };
  if (!apex_angle.empty()) {
    // The mesh points at an apex, found once each (not at every corner of every element); the sums then
    // in element order.
    std::vector<std::uint8_t> at_apex(mesh.points().size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, at_apex.size(), 16384), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) at_apex[i] = apex_angle.find(mesh.points()[i]) != nullptr;
    });
    for (const auto& e : elements) {
      if (!(at_apex[e[0]] | at_apex[e[1]] | at_apex[e[2]])) continue;
      const ElementCorners<2> c{mesh.points()[e[0]], mesh.points()[e[1]], mesh.points()[e[2]]};
      for (std::size_t i = 0; i < 3; ++i)
        if (at_apex[e[i]]) *apex_angle.find(c[i]) += angles_of(c)[i];
    }
  }
  for (const SharpCorner& c : corners) q.sharp_corners_of_land += apex_angle.at(c.apex) > std::numbers::pi;
  double worst_elsewhere = std::numeric_limits<double>::infinity();
  for (const auto& [c, shape] : below) {
    if (sharp_corner_at(c, corners)) {
      ++q.below_bound_at_sharp_corners;
    } else if (const auto a = angles_of(c); *std::min_element(a.begin(), a.end()) < worst_elsewhere) {
      worst_elsewhere = *std::min_element(a.begin(), a.end());
      q.worst_elsewhere_at = frame.point(shape.centroid);
    }
  }
}

template <int D>
QualityNumbers quality_numbers(const Mesh<D>& mesh, double rho, const BoxTransform<D>& box, const UserFrame& frame,
                               const Domain2* input_rings) {
  // One list of the elements for the report and the counts below (Mesh::quality would make its own).
  const auto elements = mesh.elements();
  // The parts below only read the mesh, each into its own variables: they run at the same time, and the
  // numbers are the same whatever the thread count.
  QualityReport<D> r;
  QualityNumbers q;
  auto report = [&] { r = quality_report<D>(mesh.points(), elements, rho, box); };
  auto count_points = [&] {
    // Points of the mesh: those an element uses (the fill on land is not part of it).
    std::vector<bool> used(mesh.points().size(), elements.empty());
    for (const auto& e : elements)
      for (auto i : e) used[i] = true;
    for (std::size_t i = 0; i < used.size(); ++i) {
      if (!used[i]) continue;
      ++q.points;
      ++(mesh.kinds()[i] == PointKind::Input ? q.input_points : q.steiner_points);
    }
  };
  if constexpr (D == 2) {
    if (!mesh.domain().empty()) {
      ShorelineReport s;
      tbb::parallel_invoke(report, count_points, [&] { s = mesh.shoreline_crossings(); },
                           [&] { shore_quality(mesh, elements, rho, frame, input_rings, q); });
      q.shore_segments = s.segments;
      q.shore_covered = s.covered;
      q.shore_worst_depth = s.worst_depth;
      q.shore_worst_depth_text = frame.length(s.worst_depth);
    } else {
      tbb::parallel_invoke(report, count_points);
    }
  } else {
    tbb::parallel_invoke(report, count_points);
  }
  q.elements = r.elements;
  q.min_angle = r.min_angle;
  q.max_angle = r.max_angle;
  q.min_angle_bound = r.min_angle_bound;
  q.rho = r.rho;
  q.max_radius_edge = r.max_radius_edge;
  q.covered_max_radius_edge = r.covered_max_radius_edge;
  q.covered = r.covered;
  q.covered_meeting_bound = r.covered_meeting_bound;
  q.meeting_bound = r.meeting_bound;
  if (mesh.covered_box()) q.left_out_at_box_edge = mesh.uncovered_count();
  if (!r.worst.empty()) q.worst_at = frame.point(r.worst.front().shape.centroid);
  return q;
}

std::string quality_text(const QualityNumbers& q, int dimension) {
  std::ostringstream out;
  const char* elements = dimension == 2 ? "triangles" : "tetrahedra";
  const double percent =
      q.covered == 0 ? 100.0 : 100.0 * static_cast<double>(q.covered_meeting_bound) / static_cast<double>(q.covered);
  out << "quality: " << q.elements << ' ' << elements << ", " << q.points << " points (" << q.input_points << " input, "
      << q.steiner_points << " Steiner); bound met by " << q.covered_meeting_bound << " of " << q.covered
      << " covered " << elements << " (" << approx(percent, 4) << "%)\n";
  out << "  " << (dimension == 2 ? "angles " : "dihedral angles ") << approx(q.min_angle, 4) << ".."
      << approx(q.max_angle, 4) << " deg";
  if (dimension == 2) out << " (guaranteed >= " << approx(q.min_angle_bound, 4) << " deg for rho = " << approx(q.rho) << ")";
  out << "; radius-edge <= " << approx(q.max_radius_edge, 4) << ", covered <= " << approx(q.covered_max_radius_edge, 4)
      << " (bound " << approx(q.rho, 4) << ")\n";
  if (q.left_out_at_box_edge.value_or(0) > 0)
    out << "  clipped to the box: " << *q.left_out_at_box_edge << ' ' << elements
        << " whose circumcentre lies outside it left out (slivers along its edge, which the bound does not cover; "
           "--keep-hull keeps them)\n";
  else
    out << "  covered: " << elements << " whose circumcentre lies in the box, where rho-well-spacing guarantees the "
        << "bound; " << q.meeting_bound << " of " << q.elements << " meet it overall\n";
  if (!q.worst_at.empty()) out << "  worst " << (dimension == 2 ? "triangle" : "tetrahedron") << " near " << q.worst_at << "\n";
  if (q.shore_segments) {
    if (*q.shore_covered == *q.shore_segments) {
      out << "  shoreline: all " << *q.shore_segments << " shore segments are mesh edges (the shore is the mesh's "
          << "boundary; " << q.shore_splits << " of the input points are canonical splits of the shore)";
    } else {
      out << "  shoreline: " << *q.shore_covered << " of " << *q.shore_segments << " shore segments are mesh edges"
          << "; the others are crossed by mesh edges at most " << q.shore_worst_depth_text << " from the shore";
    }
    if (q.shore_below_bound)
      out << "\n  at the shore: " << q.shore_below_bound << ' ' << (dimension == 2 ? "triangles" : "tetrahedra")
          << " below the bound are made by the shore's constraints (a point across the shore lies in their "
             "circumcircle); others below the bound: "
          << q.interior_below_bound;
    if (const std::size_t below = q.shore_below_bound + q.interior_below_bound) {
      out << "\n  below the bound: " << below << " triangles, " << q.below_bound_at_sharp_corners
          << " of them at an input corner sharper than 60 deg (within the shorter of its two segments, the water "
          << "on either side: " << q.sharp_corners << " such corners, " << q.sharp_corners_of_land
          << " of them spikes of land), " << below - q.below_bound_at_sharp_corners << " elsewhere";
      if (!q.worst_elsewhere_at.empty()) out << " (the worst near " << q.worst_elsewhere_at << ")";
    }
    out << "\n";
  }
  return out.str();
}

std::string describe_input(const io::InputSet& set) {
  std::ostringstream out;
  std::size_t shores = 0, islands = 0, lines = 0, ring_points = 0, line_points = 0;
  for (const Ring& r : set.domain.rings) {
    ++(r.role == RingRole::Shore ? shores : r.role == RingRole::Island ? islands : lines);
    (r.closed() ? ring_points : line_points) += r.points.size();
  }
  out << "input: " << set.size() << ' ' << set.dimension << "D points";
  if (shores + islands)
    out << ", " << shores + islands << " rings (" << shores << " shore, " << islands << " island; " << ring_points
        << " ring points)";
  if (lines) out << ", " << lines << " constraint lines (" << line_points << " points)";
  out << "; " << io::to_string(set.units);
  if (!set.projection.is_none()) out << ", projected with " << set.projection.describe();
  out << "\n";
  for (const std::string& note : set.notes) out << "  " << note << "\n";
  return out.str();
}

template std::optional<BoxTransform<2>> parse_box<2>(const std::vector<double>&);
template std::optional<BoxTransform<3>> parse_box<3>(const std::vector<double>&);
template SessionInput<2> session_input<2>(const io::InputSet&);
template SessionInput<3> session_input<3>(const io::InputSet&);
template EngineInput<2> engine_input<2>(const io::InputSet&, const std::optional<BoxTransform<2>>&,
                                        const std::optional<SizeTerms>&);
template EngineInput<3> engine_input<3>(const io::InputSet&, const std::optional<BoxTransform<3>>&,
                                        const std::optional<SizeTerms>&);
template std::vector<Point<2>> input_points<2>(const io::InputSet&);
template std::vector<Point<3>> input_points<3>(const io::InputSet&);
template void export_mesh_file<2>(const Mesh<2>&, const std::filesystem::path&, std::optional<io::ExportFormat>,
                                  const UserFrame&, std::span<const Point<2>>);
template void export_mesh_file<3>(const Mesh<3>&, const std::filesystem::path&, std::optional<io::ExportFormat>,
                                  const UserFrame&, std::span<const Point<3>>);
template void write_preview<2>(const Mesh<2>&, const std::filesystem::path&, const PreviewArgs&, const UserFrame*);
template void write_preview<3>(const Mesh<3>&, const std::filesystem::path&, const PreviewArgs&, const UserFrame*);
template QualityNumbers quality_numbers<2>(const Mesh<2>&, double, const BoxTransform<2>&, const UserFrame&,
                                           const Domain2*);
template QualityNumbers quality_numbers<3>(const Mesh<3>&, double, const BoxTransform<3>&, const UserFrame&,
                                           const Domain2*);

}  // namespace shoremesh::tool
