#pragma once
// The drawing primitives behind the previews: anti-aliased lines and discs by exact pixel coverage of a
// distance field (coverage = clamp(half width + 0.5 - distance)), filled triangles by pixel centres, and
// alpha blending, on a PreviewImage whose plane-to-pixel map is set once.
#include <vector>

#include "shoremesh/io/preview.hpp"

namespace shoremesh::io {

class Canvas {
 public:
  // Fits the plane rectangle [lo, hi] into the image with `margin` pixels around it, keeping the aspect;
  // height 0 takes the rectangle's aspect.
  Canvas(std::array<double, 2> lo, std::array<double, 2> hi, int width, int height, int margin, Rgb background);

  PreviewImage& image() { return image_; }
  PreviewImage take() { return std::move(image_); }
  std::array<double, 2> pixel(double x, double y) const { return image_.to_pixel(x, y); }

  void blend(int x, int y, Rgb c, double alpha);
  // Plane coordinates in, pixel-space drawing.
  void line(std::array<double, 2> a, std::array<double, 2> b, double width, Rgb c, double alpha = 1);
  void disc(std::array<double, 2> centre, double radius, Rgb c);
  void triangle(std::array<double, 2> a, std::array<double, 2> b, std::array<double, 2> c, Rgb colour, double alpha);
  void polygon(const std::vector<std::array<double, 2>>& corners, Rgb colour, double alpha);  // convex
  // Draws `picture` so that it covers the plane rectangle extent {min x, min y, max x, max y}.
  void underlay(const PreviewImage& picture, const std::array<double, 4>& extent);

 private:
  PreviewImage image_;
};

// The 3D drawing (preview_3d.cpp), which draw_preview<3> calls.
PreviewImage draw_3d(const MeshView<3>& view, const PreviewOptions& options);

// Colour ramps for the colouring modes: t in [0, 1].
Rgb quality_colour(double min_angle, double bound_angle, double best_angle);
Rgb size_colour(double t);
// Depth for t in [0, 1] (0: the shallowest, 1: the deepest): pale to dark blue.
Rgb depth_colour(double t);

}  // namespace shoremesh::io
