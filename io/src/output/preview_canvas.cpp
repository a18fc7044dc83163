#include "shoremesh/io/preview_canvas.hpp"

#include <algorithm>
#include <cmath>

namespace shoremesh::io {

namespace {
using P = std::array<double, 2>;

double segment_distance(P p, P a, P b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

Rgb mix(Rgb a, Rgb b, double t) {
  const float s = static_cast<float>(t);
  return {a.r + (b.r - a.r) * s, a.g + (b.g - a.g) * s, a.b + (b.b - a.b) * s};
}
}  // namespace

Canvas::Canvas(P lo, P hi, int width, int height, int margin, Rgb background) {
  const double dx = std::max(hi[0] - lo[0], 1e-300), dy = std::max(hi[1] - lo[1], 1e-300);
  const int inner_w = std::max(1, width - 2 * margin);
  if (height <= 0) height = static_cast<int>(std::lround(std::min<double>(inner_w * dy / dx + 2 * margin, kMaxPreviewSide)));
  height = std::max(height, 1);
  const int inner_h = std::max(1, height - 2 * margin);
  image_.width = width;
  image_.height = height;
  image_.scale = std::min(inner_w / dx, inner_h / dy);
  // Centre the rectangle; pixel centres sit at integer + 0.5.
  image_.offset_x = width / 2.0 - image_.scale * (lo[0] + hi[0]) / 2;
  image_.offset_y = height / 2.0 + image_.scale * (lo[1] + hi[1]) / 2;
  image_.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t i = 0; i < image_.rgb.size(); i += 3) {
    image_.rgb[i] = background.r;
    image_.rgb[i + 1] = background.g;
    image_.rgb[i + 2] = background.b;
  }
}

void Canvas::blend(int x, int y, Rgb c, double alpha) {
  if (x < 0 || y < 0 || x >= image_.width || y >= image_.height || alpha <= 0) return;
  float* px = &image_.rgb[(static_cast<std::size_t>(y) * image_.width + x) * 3];
  const float a = static_cast<float>(std::min(alpha, 1.0));
  px[0] += (c.r - px[0]) * a;
  px[1] += (c.g - px[1]) * a;
  px[2] += (c.b - px[2]) * a;
}

void Canvas::line(P a, P b, double width, Rgb c, double alpha) {
  const P pa = pixel(a[0], a[1]), pb = pixel(b[0], b[1]);
  const double reach = width / 2 + 1;
  // Walk along the major axis, visiting only the few pixels across the line in each column (row).
  const bool steep = std::abs(pb[1] - pa[1]) > std::abs(pb[0] - pa[0]);
  const int u = steep ? 1 : 0, v = 1 - u;
  P s = pa, e = pb;
  if (s[u] > e[u]) std::swap(s, e);
  const double du = e[u] - s[u], dv = e[v] - s[v];
  const double spread = reach * std::hypot(du, dv) / std::max(du, 1e-12);  // half-height of the band
  const int u0 = static_cast<int>(std::floor(s[u] - reach)), u1 = static_cast<int>(std::ceil(e[u] + reach));
  const int limit_u = steep ? image_.height : image_.width, limit_v = steep ? image_.width : image_.height;
  for (int iu = std::max(u0, 0); iu <= std::min(u1, limit_u - 1); ++iu) {
    const double cu = iu + 0.5;
    const double t = du > 0 ? std::clamp((cu - s[u]) / du, 0.0, 1.0) : 0.0;
    const double cv = s[v] + t * dv;
    const double band = std::min(spread, reach + std::abs(dv));
    for (int iv = std::max(static_cast<int>(std::floor(cv - band)), 0);
         iv <= std::min(static_cast<int>(std::ceil(cv + band)), limit_v - 1); ++iv) {
      P centre;
      centre[u] = cu;
      centre[v] = iv + 0.5;
      const double coverage = std::clamp(width / 2 + 0.5 - segment_distance(centre, pa, pb), 0.0, 1.0);
      if (coverage > 0) blend(steep ? iv : iu, steep ? iu : iv, c, coverage * alpha);
    }
  }
}

void Canvas::disc(P centre, double radius, Rgb c) {
  const P p = pixel(centre[0], centre[1]);
  for (int y = static_cast<int>(std::floor(p[1] - radius - 1)); y <= static_cast<int>(std::ceil(p[1] + radius + 1)); ++y)
    for (int x = static_cast<int>(std::floor(p[0] - radius - 1)); x <= static_cast<int>(std::ceil(p[0] + radius + 1)); ++x) {
      const double d = std::hypot(x + 0.5 - p[0], y + 0.5 - p[1]);
      blend(x, y, c, std::clamp(radius + 0.5 - d, 0.0, 1.0));
    }
}

void Canvas::polygon(const std::vector<P>& corners, Rgb colour, double alpha) {
  std::vector<P> px;
  for (const P& c : corners) px.push_back(pixel(c[0], c[1]));
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const P& p : px) x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
  // A pixel centre is inside a convex polygon when it is on the same side of every edge.
  for (int y = std::max(0, static_cast<int>(std::floor(y0))); y <= std::min(image_.height - 1, static_cast<int>(y1)); ++y)
    for (int x = std::max(0, static_cast<int>(std::floor(x0))); x <= std::min(image_.width - 1, static_cast<int>(x1)); ++x) {
      int positive = 0, negative = 0;
      for (std::size_t i = 0; i < px.size(); ++i) {
        const P& a = px[i];
        const P& b = px[(i + 1) % px.size()];
        const double side = (b[0] - a[0]) * (y + 0.5 - a[1]) - (b[1] - a[1]) * (x + 0.5 - a[0]);
        positive += side > 0;
        negative += side < 0;
      }
      if (positive == 0 || negative == 0) blend(x, y, colour, alpha);
    }
}

void Canvas::triangle(P a, P b, P c, Rgb colour, double alpha) { polygon({a, b, c}, colour, alpha); }

void Canvas::underlay(const PreviewImage& picture, const std::array<double, 4>& extent) {
  const double w = extent[2] - extent[0], h = extent[3] - extent[1];
  if (picture.width <= 0 || picture.height <= 0 || !(w > 0) || !(h > 0)) return;
  for (int y = 0; y < image_.height; ++y)
    for (int x = 0; x < image_.width; ++x) {
      // Back from pixel centre to the plane, then into the picture (nearest sample).
      const double px = (x + 0.5 - image_.offset_x) / image_.scale;
      const double py = (image_.offset_y - (y + 0.5)) / image_.scale;
      const double u = (px - extent[0]) / w * picture.width, v = (extent[3] - py) / h * picture.height;
      if (u < 0 || v < 0 || u >= picture.width || v >= picture.height) continue;
      blend(x, y, picture.at(static_cast<int>(u), static_cast<int>(v)), 1.0);
    }
}

Rgb quality_colour(double min_angle, double bound_angle, double best_angle) {
  const Rgb red{0.85f, 0.15f, 0.1f}, yellow{0.95f, 0.85f, 0.2f}, green{0.3f, 0.75f, 0.35f};
  if (min_angle <= bound_angle) return mix(red, yellow, std::clamp(min_angle / bound_angle, 0.0, 1.0));
  return mix(yellow, green, std::clamp((min_angle - bound_angle) / (best_angle - bound_angle), 0.0, 1.0));
}

Rgb depth_colour(double t) {
  const Rgb shallow{0.8f, 0.92f, 0.98f}, deep{0.03f, 0.15f, 0.45f};
  return mix(shallow, deep, std::clamp(t, 0.0, 1.0));
}

Rgb size_colour(double t) {
  const Rgb blue{0.2f, 0.35f, 0.8f}, light{0.9f, 0.9f, 0.85f}, orange{0.95f, 0.55f, 0.1f};
  t = std::clamp(t, 0.0, 1.0);
  return t < 0.5 ? mix(blue, light, 2 * t) : mix(light, orange, 2 * t - 1);
}

}  // namespace shoremesh::io
