// 2D previews (mesh, optional underlay and colouring, input and Steiner points) and the delta preview.
#include "shoremesh/io/preview.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "shoremesh/error.hpp"
#include "shoremesh/io/preview_canvas.hpp"
#include "shoremesh/mesh_quality.hpp"

namespace shoremesh::io {

namespace {

using P = std::array<double, 2>;

template <class Range>
std::pair<P, P> bounds_of(const Range& points) {
  P lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  P hi{-lo[0], -lo[1]};
  for (const auto& p : points)
    for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
  if (lo[0] > hi[0]) lo = {0, 0}, hi = {1, 1};  // nothing to draw
  return {lo, hi};
}

P xy(const Point2& p) { return {p[0], p[1]}; }

// Each undirected edge once, so that shared edges are not blended twice (they would look darker).
std::set<std::pair<std::uint32_t, std::uint32_t>> unique_edges(std::span<const Element<2>> elements) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& e : elements)
    for (int i = 0; i < 3; ++i) edges.insert(std::minmax(e[i], e[(i + 1) % 3]));
  return edges;
}

// An element's size: the side of the square of the same area.
double element_size(const ElementCorners<2>& c) {
  return std::sqrt(std::abs((c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) - (c[1][1] - c[0][1]) * (c[2][0] - c[0][0])) / 2);
}

// Hypsometric tint of the mean height (water below 0 in blues, land from green through brown to white),
// darkened by a hillshade: the cosine between the triangle's normal and light from azimuth 315, altitude 45.
Rgb height_colour(const ElementCorners<2>& c, const std::array<double, 3>& h, double low, double high) {
  const double mean = (h[0] + h[1] + h[2]) / 3;
  Rgb tint;
  if (mean < 0) {
    const float t = static_cast<float>(low < 0 ? std::clamp(mean / low, 0.0, 1.0) : 0.0);
    tint = {0.65f - 0.55f * t, 0.82f - 0.5f * t, 0.95f - 0.35f * t};
  } else {
    const double t = high > 0 ? std::clamp(mean / high, 0.0, 1.0) : 0.0;
    const Rgb stops[4] = {{0.35f, 0.6f, 0.3f}, {0.75f, 0.7f, 0.4f}, {0.55f, 0.4f, 0.3f}, {0.97f, 0.97f, 0.97f}};
    const double x = t * 3;
    const int k = std::min(static_cast<int>(x), 2);
    const float f = static_cast<float>(x - k);
    tint = {stops[k].r + f * (stops[k + 1].r - stops[k].r), stops[k].g + f * (stops[k + 1].g - stops[k].g),
            stops[k].b + f * (stops[k + 1].b - stops[k].b)};
  }
  const double ux = c[1][0] - c[0][0], uy = c[1][1] - c[0][1], uz = h[1] - h[0];
  const double vx = c[2][0] - c[0][0], vy = c[2][1] - c[0][1], vz = h[2] - h[0];
  double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  if (nz < 0) nx = -nx, ny = -ny, nz = -nz;
  const double norm = std::sqrt(nx * nx + ny * ny + nz * nz);
  const double s = std::sqrt(0.5);  // the light: (-cos 45 sin 45, cos 45 cos 45, sin 45) for azimuth 315
  const double shade = norm > 0 ? std::max(0.0, (-0.5 * nx + 0.5 * ny + s * nz) / norm) : 1.0;
  const float k = static_cast<float>(0.3 + 0.7 * shade / s);  // flat ground at full tint
  return {std::min(1.0f, tint.r * k), std::min(1.0f, tint.g * k), std::min(1.0f, tint.b * k)};
}

// Longest edge over h at the centroid: log scale from 1/4 (blue) to 1 (green), red above 1.01.
Rgb size_ratio_colour(const ElementCorners<2>& c, const std::function<double(const Point2&)>& size_at) {
  const double longest = std::max({std::hypot(c[0][0] - c[1][0], c[0][1] - c[1][1]), std::hypot(c[1][0] - c[2][0], c[1][1] - c[2][1]),
                                   std::hypot(c[2][0] - c[0][0], c[2][1] - c[0][1])});
  const double h = size_at({(c[0][0] + c[1][0] + c[2][0]) / 3, (c[0][1] + c[1][1] + c[2][1]) / 3});
  const double ratio = longest / h;
  if (!(ratio <= 1.01)) return {0.9f, 0.1f, 0.1f};
  const float t = static_cast<float>(std::clamp(std::log(ratio / 0.25) / std::log(4.0), 0.0, 1.0));
  return {0.1f, 0.25f + 0.55f * t, 0.85f - 0.65f * t};
}

PreviewImage draw_2d(const MeshView<2>& view, const PreviewOptions& o) {
  const auto [lo, hi] = bounds_of(view.points);
  Canvas canvas(lo, hi, o.width, o.height, o.margin, o.background_colour);
  if (o.background) canvas.underlay(read_image(*o.background), o.background_extent);

  if (o.colouring != PreviewColouring::None && !view.elements.empty()) {
    std::vector<ElementCorners<2>> corners;
    for (const auto& e : view.elements) corners.push_back({view.points[e[0]], view.points[e[1]], view.points[e[2]]});
    double small = std::numeric_limits<double>::infinity(), large = 0;
    for (const auto& c : corners) small = std::min(small, element_size(c)), large = std::max(large, element_size(c));
    const double bound = std::asin(std::min(1.0, 1 / (2 * o.rho))) * 180 / std::numbers::pi;
    if (o.colouring == PreviewColouring::Depth && view.depths.size() != view.points.size())
      throw InputError("colouring by depth needs depths at the nodes (--dem, --depth-from or x,y,depth soundings)");
    if (o.colouring == PreviewColouring::Height && view.heights.size() != view.points.size())
      throw InputError("colouring by height needs heights at the nodes (a terrain: shoremesh terrain)");
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (double h : view.heights) low = std::min(low, h), high = std::max(high, h);
    double shallow = std::numeric_limits<double>::infinity(), deep = -shallow;
    for (double d : view.depths) shallow = std::min(shallow, d), deep = std::max(deep, d);
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const auto& c = corners[k];
      const auto& e = view.elements[k];
      const Rgb colour =
          o.colouring == PreviewColouring::Height ? height_colour(c, {view.heights[e[0]], view.heights[e[1]], view.heights[e[2]]}, low, high)
          : o.colouring == PreviewColouring::Quality ? quality_colour(element_shape<2>(c).min_angle, bound, 60)
          : o.colouring == PreviewColouring::Depth
              ? depth_colour(deep > shallow ? ((view.depths[e[0]] + view.depths[e[1]] + view.depths[e[2]]) / 3 - shallow) /
                                                  (deep - shallow)
                                            : 0.5)
          : o.size_at ? size_ratio_colour(c, o.size_at)
              : size_colour(large > small ? std::log(element_size(c) / small) / std::log(large / small) : 0.5);
      canvas.triangle(xy(c[0]), xy(c[1]), xy(c[2]), colour, 0.75);
    }
  }
  for (const auto& [a, b] : unique_edges(view.elements)) canvas.line(xy(view.points[a]), xy(view.points[b]), o.line_width, o.edge_colour);
  if (o.point_radius > 0) {
    // Steiner points first, input points on top: the input is what the user must find again.
    for (const PointKind kind : {PointKind::Steiner, PointKind::Input})
      for (std::size_t i = 0; i < view.points.size(); ++i) {
        const PointKind k = view.kinds.empty() ? PointKind::Input : view.kinds[i];
        if (k == kind) canvas.disc(xy(view.points[i]), o.point_radius, k == PointKind::Input ? o.input_colour : o.steiner_colour);
      }
  }
  return canvas.take();
}

}  // namespace

template <int D>
PreviewImage draw_preview(const MeshView<D>& view, const PreviewOptions& options) {
  if constexpr (D == 2) return draw_2d(view, options);
  else return draw_3d(view, options);
}

PreviewImage draw_delta_preview(const MeshView<2>& after, const MeshDelta<2>& delta, const PreviewOptions& o) {
  std::vector<Point2> all(after.points.begin(), after.points.end());
  for (const auto* list : {&delta.removed, &delta.added})
    for (const auto& c : *list) all.insert(all.end(), c.begin(), c.end());
  const auto [lo, hi] = bounds_of(all);
  Canvas canvas(lo, hi, o.width, o.height, o.margin, o.background_colour);
  if (o.background) canvas.underlay(read_image(*o.background), o.background_extent);
  const Rgb grey{0.72f, 0.72f, 0.72f}, red{0.85f, 0.1f, 0.1f}, green{0.1f, 0.6f, 0.2f};
  for (const auto& [a, b] : unique_edges(after.elements)) canvas.line(xy(after.points[a]), xy(after.points[b]), o.line_width, grey);
  // The region that changed is tinted green; removed edges in red, new ones in green on top.
  for (const auto& c : delta.added) canvas.triangle(xy(c[0]), xy(c[1]), xy(c[2]), green, 0.15);
  for (const auto& [list, colour] : {std::pair{&delta.removed, red}, std::pair{&delta.added, green}})
    for (const auto& c : *list)
      for (int i = 0; i < 3; ++i) canvas.line(xy(c[i]), xy(c[(i + 1) % 3]), o.line_width, colour);
  // Points only in removed elements were removed; points only in added elements are new.
  if (o.point_radius > 0) {
    std::set<Point2> old_corners, new_corners;
    for (const auto& c : delta.removed) old_corners.insert(c.begin(), c.end());
    for (const auto& c : delta.added) new_corners.insert(c.begin(), c.end());
    for (const Point2& p : old_corners)
      if (!new_corners.count(p)) canvas.disc(xy(p), 1.5 * o.point_radius, red);
    for (const Point2& p : new_corners)
      if (!old_corners.count(p)) canvas.disc(xy(p), 1.5 * o.point_radius, green);
  }
  return canvas.take();
}

template <int D>
void render_preview(const std::filesystem::path& path, const MeshView<D>& view, const PreviewOptions& options) {
  write_image(path, draw_preview<D>(view, options));
}

void render_delta_preview(const std::filesystem::path& path, const MeshView<2>& after, const MeshDelta<2>& delta,
                          const PreviewOptions& options) {
  write_image(path, draw_delta_preview(after, delta, options));
}

template PreviewImage draw_preview<2>(const MeshView<2>&, const PreviewOptions&);
template PreviewImage draw_preview<3>(const MeshView<3>&, const PreviewOptions&);
template void render_preview<2>(const std::filesystem::path&, const MeshView<2>&, const PreviewOptions&);
template void render_preview<3>(const std::filesystem::path&, const MeshView<3>&, const PreviewOptions&);

}  // namespace shoremesh::io
