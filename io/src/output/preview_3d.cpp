// 3D previews: an orthographic view of the boundary surface (back faces culled, the rest painted far to
// near and shaded by the angle to the viewer), or the slice of the tetrahedra by a plane z = const.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "shoremesh/io/preview.hpp"
#include "shoremesh/io/preview_canvas.hpp"
#include "shoremesh/mesh_boundary.hpp"
#include "shoremesh/mesh_quality.hpp"

namespace shoremesh::io {

namespace {

using P = std::array<double, 2>;

// The view: azimuth turns about z, elevation tilts towards the viewer; the screen is (x, z) after the
// rotation and y is the depth (larger is farther).
Point3 rotate(const Point3& p, double azimuth, double elevation) {
  const double a = azimuth * std::numbers::pi / 180, e = elevation * std::numbers::pi / 180;
  const double x = std::cos(a) * p[0] + std::sin(a) * p[1];
  const double y = -std::sin(a) * p[0] + std::cos(a) * p[1];
  return {x, std::cos(e) * y + std::sin(e) * p[2], -std::sin(e) * y + std::cos(e) * p[2]};
}

std::pair<P, P> bounds(const std::vector<P>& points) {
  P lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}, hi{-lo[0], -lo[1]};
  for (const P& p : points)
    for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
  if (lo[0] > hi[0]) lo = {0, 0}, hi = {1, 1};
  return {lo, hi};
}

PreviewImage draw_surface(const MeshView<3>& view, const PreviewOptions& o) {
  std::vector<Point3> r;
  std::vector<P> screen;
  for (const auto& p : view.points) {
    r.push_back(rotate(p, o.azimuth, o.elevation));
    screen.push_back({r.back()[0], r.back()[2]});
  }
  const auto [lo, hi] = bounds(screen);
  Canvas canvas(lo, hi, o.width, o.height, o.margin, o.background_colour);
  struct Face {
    std::array<std::uint32_t, 3> f;
    double depth, facing;
  };
  std::vector<Face> faces;
  for (const auto& f : boundary_faces(view.elements)) {
    const Point3 &a = r[f[0]], &b = r[f[1]], &c = r[f[2]];
    const Point3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Point3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    // Outward normals pointing away from the viewer (towards +y) are back faces.
    if (len == 0 || n[1] >= 0) continue;
    faces.push_back({f, (a[1] + b[1] + c[1]) / 3, -n[1] / len});
  }
  std::sort(faces.begin(), faces.end(), [](const Face& x, const Face& y) { return x.depth > y.depth; });
  for (const Face& face : faces) {
    const float shade = static_cast<float>(0.45 + 0.5 * face.facing);
    canvas.triangle(screen[face.f[0]], screen[face.f[1]], screen[face.f[2]], {0.55f * shade, 0.7f * shade, 0.9f * shade}, 1.0);
    for (int i = 0; i < 3; ++i) canvas.line(screen[face.f[i]], screen[face.f[(i + 1) % 3]], o.line_width, o.edge_colour);
  }
  return canvas.take();
}

PreviewImage draw_slice(const MeshView<3>& view, const PreviewOptions& o) {
  std::vector<P> xy;
  for (const auto& p : view.points) xy.push_back({p[0], p[1]});
  const auto [lo, hi] = bounds(xy);
  Canvas canvas(lo, hi, o.width, o.height, o.margin, o.background_colour);
  const double z = o.slice_z;
  for (const auto& t : view.elements) {
    // The section of a tetrahedron by the plane: where its edges cross it (a triangle or a quadrilateral).
    std::vector<P> section;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const Point3 &a = view.points[t[i]], &b = view.points[t[j]];
        if ((a[2] - z) * (b[2] - z) >= 0) continue;
        const double s = (z - a[2]) / (b[2] - a[2]);
        section.push_back({a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])});
      }
    if (section.size() < 3) continue;
    P c{0, 0};
    for (const P& p : section) c[0] += p[0] / section.size(), c[1] += p[1] / section.size();
    std::sort(section.begin(), section.end(), [&](const P& a, const P& b) {
      return std::atan2(a[1] - c[1], a[0] - c[0]) < std::atan2(b[1] - c[1], b[0] - c[0]);
    });
    Rgb fill{0.8f, 0.88f, 0.97f};
    if (o.colouring == PreviewColouring::Quality) {
      const ElementShape<3> s = element_shape<3>({view.points[t[0]], view.points[t[1]], view.points[t[2]], view.points[t[3]]});
      fill = quality_colour(s.min_angle, 10, 70.5);  // dihedral angles: no guarantee, a fixed scale
    }
    canvas.polygon(section, fill, 1.0);
    for (std::size_t i = 0; i < section.size(); ++i) canvas.line(section[i], section[(i + 1) % section.size()], o.line_width, o.edge_colour);
  }
  return canvas.take();
}

}  // namespace

PreviewImage draw_3d(const MeshView<3>& view, const PreviewOptions& options) {
  return options.view3d == PreviewView3D::Surface ? draw_surface(view, options) : draw_slice(view, options);
}

}  // namespace shoremesh::io
