#pragma once
// Previews of a mesh with OpenImageIO, in the style of the paper's Lake Superior figure: thin anti-aliased
// edges on white, input and Steiner points in two colours, optionally a source image underneath and the
// triangles coloured by quality or size. 3D: an orthographic view of the boundary surface, or a z-slice.
// A second kind of preview shows what one dynamic update changed.
#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <vector>

#include "shoremesh/io/export.hpp"
#include "shoremesh/mesh.hpp"

namespace shoremesh::io {

struct Rgb {
  float r = 0, g = 0, b = 0;  // 0..1
  bool operator==(const Rgb&) const = default;
};

enum class PreviewColouring { None, Quality, Size, Depth, Height };
enum class PreviewView3D { Surface, SliceZ };

// The largest side of a preview whose height follows the mesh's aspect ratio: a river 10^5 times longer
// than wide would otherwise ask for 10^8 rows (gigabytes); past it the picture is narrower instead.
inline constexpr int kMaxPreviewSide = 16384;

struct PreviewOptions {
  int width = 1024;           // pixels
  int height = 0;             // pixels; 0 follows the mesh's aspect ratio, up to kMaxPreviewSide
  int margin = 16;            // pixels of background around the mesh
  double line_width = 1.0;    // pixels
  double point_radius = 1.6;  // pixels; 0 hides the points
  // Quality: the minimum angle (dihedral in 3D) from red (0) through yellow (the rho bound, 20.7 degrees
  // for rho = sqrt 2) to green (60). Size: the square root of the area, blue (smallest) to orange (largest), log scale.
  // Depth (2D, the view's depths): the mean of the corners' depths, pale (shallowest) to dark blue (deepest).
  // Height (2D, the view's heights): hypsometric tints (blues below 0, greens to browns to white above)
  // by the corners' mean height, hillshaded by the triangle's slope (light from the north-west, 45 degrees up).
  PreviewColouring colouring = PreviewColouring::None;
  double rho = 1.4142135623730951;
  // An image drawn underneath, covering the mesh-coordinate rectangle background_extent
  // {min x, min y, max x, max y} (its top row at max y).
  std::optional<std::filesystem::path> background;
  std::array<double, 4> background_extent{0, 0, 1, 1};
  Rgb background_colour{1, 1, 1};
  Rgb edge_colour{0.08f, 0.08f, 0.08f};
  Rgb input_colour{0.85f, 0.1f, 0.1f};
  Rgb steiner_colour{0.1f, 0.3f, 0.85f};
  // 3D only.
  PreviewView3D view3d = PreviewView3D::Surface;
  double azimuth = 30, elevation = 25;  // degrees: the direction the surface is seen from
  double slice_z = 0.5;                 // the plane of a z-slice, in mesh coordinates
  // 2D, Size colouring with a size function h: the longest edge over h at the centroid instead, blue (1/4)
  // through green (1) to red (above 1.01: the bound broken).
  std::function<double(const Point2&)> size_at = {};
};

// An RGB image with float channels in [0, 1], row 0 at the top.
struct PreviewImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // width * height * 3
  Rgb at(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
  // The map from the drawn plane (mesh x, y in 2D; the projected plane in 3D) to pixel coordinates.
  double scale = 1, offset_x = 0, offset_y = 0;
  std::array<double, 2> to_pixel(double x, double y) const { return {offset_x + scale * x, offset_y - scale * y}; }
};

// Draws in memory (testable pixel by pixel).
template <int D>
PreviewImage draw_preview(const MeshView<D>& view, const PreviewOptions& options = {});
// `after` is the mesh after the change, drawn in light grey; the edges of removed elements in red, those of
// added elements in green over a green tint, removed points as red dots and new points as green dots.
PreviewImage draw_delta_preview(const MeshView<2>& after, const MeshDelta<2>& delta, const PreviewOptions& options = {});

// Writes PNG or any format OpenImageIO writes (by extension), 8 bits per channel, atomically. Throws
// InputError for an unknown extension, std::runtime_error naming the path when writing fails.
void write_image(const std::filesystem::path& path, const PreviewImage& image);
// Reads any image OpenImageIO reads into RGB floats (grey replicated); throws InputError naming the path.
PreviewImage read_image(const std::filesystem::path& path);

// draw_preview / draw_delta_preview, then write_image.
template <int D>
void render_preview(const std::filesystem::path& path, const MeshView<D>& view, const PreviewOptions& options = {});
void render_delta_preview(const std::filesystem::path& path, const MeshView<2>& after, const MeshDelta<2>& delta,
                          const PreviewOptions& options = {});

}  // namespace shoremesh::io
