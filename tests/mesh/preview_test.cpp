// Previews are checked pixel by pixel on small known meshes, after a round trip through a PNG file read
// back by OpenImageIO: an edge pixel is dark, an empty pixel is background, points have their colours.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "mesh_test_util.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/preview.hpp"
#include "shoremesh/mesh.hpp"

namespace shoremesh {
namespace {

using io::MeshSnapshot;
using io::PreviewImage;
using io::PreviewOptions;
using io::Rgb;
using mesh_test::ScratchDir;

// A quadrilateral (no four points co-circular) with its two triangles; corners are input points except
// (1.1, 1), a Steiner point.
MeshSnapshot<2> quad() {
  const std::vector<Point2> points{{0, 0}, {1, 0}, {0, 0.9}, {1.1, 1}};
  const Mesh2 mesh(points, 3);
  return MeshSnapshot<2>(mesh);
}

Rgb pixel_at(const PreviewImage& image, double x, double y) {
  const auto p = image.to_pixel(x, y);
  return image.at(static_cast<int>(p[0]), static_cast<int>(p[1]));
}

bool dark(Rgb c) { return c.r < 0.35f && c.g < 0.35f && c.b < 0.35f; }

// A one-pixel line may fall between two pixel rows and give each half its ink: look at the darkest pixel
// within one pixel of the point.
float darkest_near(const PreviewImage& image, double x, double y) {
  const auto p = image.to_pixel(x, y);
  float v = 1;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const Rgb c = image.at(static_cast<int>(p[0]) + dx, static_cast<int>(p[1]) + dy);
      v = std::min({v, std::max({c.r, c.g, c.b})});
    }
  return v;
}
bool white(Rgb c) { return c.r > 0.99f && c.g > 0.99f && c.b > 0.99f; }

PreviewOptions small(int width, int margin, double point_radius) {
  PreviewOptions o;
  o.width = width;
  o.margin = margin;
  o.point_radius = point_radius;
  return o;
}

PreviewImage through_png(const ScratchDir& dir, const PreviewImage& image) {
  io::write_image(dir.path("preview.png"), image);
  PreviewImage read = io::read_image(dir.path("preview.png"));
  read.scale = image.scale, read.offset_x = image.offset_x, read.offset_y = image.offset_y;
  return read;
}

TEST(Preview, EdgePixelIsDarkEmptyPixelIsBackground) {
  ScratchDir dir;
  const auto snap = quad();
  PreviewOptions o = small(220, 10, 0);
  const PreviewImage image = through_png(dir, io::draw_preview<2>(snap.view(), o));
  EXPECT_EQ(image.width, 220);
  EXPECT_GT(image.height, 150);
  // Midpoints of the four sides: at least half ink with a one-pixel line, full ink with a two-pixel line.
  const std::vector<std::pair<double, double>> sides{{0.5, 0}, {0, 0.45}, {1.05, 0.5}, {0.55, 0.95}};
  for (const auto& [x, y] : sides) EXPECT_LT(darkest_near(image, x, y), 0.56f) << x << ", " << y;
  o.line_width = 2;
  const PreviewImage thick = through_png(dir, io::draw_preview<2>(snap.view(), o));
  for (const auto& [x, y] : sides) EXPECT_TRUE(dark(pixel_at(thick, x, y))) << x << ", " << y;
  ASSERT_EQ(snap.view().elements.size(), 2u);
  // Inside the triangles, away from the edges, and in the margin: white.
  EXPECT_TRUE(white(pixel_at(image, 0.25, 0.2)));
  EXPECT_TRUE(white(pixel_at(image, 0.8, 0.75)));
  EXPECT_TRUE(white(image.at(2, 2)));
  EXPECT_TRUE(white(image.at(image.width - 3, image.height - 3)));
  // Anti-aliased: along a slanted edge some pixels are neither background nor full ink.
  std::size_t grey = 0;
  for (float v : image.rgb) grey += v > 0.2f && v < 0.8f;
  EXPECT_GT(grey, 0u);
}

TEST(Preview, InputAndSteinerPointsHaveTheirColours) {
  ScratchDir dir;
  const auto snap = quad();
  const PreviewOptions o = small(220, 12, 5);
  const PreviewImage image = through_png(dir, io::draw_preview<2>(snap.view(), o));
  const Rgb input = pixel_at(image, 0, 0), steiner = pixel_at(image, 1.1, 1);
  EXPECT_GT(input.r, 0.7f);
  EXPECT_LT(input.b, 0.3f);
  EXPECT_GT(steiner.b, 0.7f);
  EXPECT_LT(steiner.r, 0.3f);
}

TEST(Preview, QualityColouringFillsTrianglesAndBackgroundShowsUnderneath) {
  ScratchDir dir;
  const auto snap = quad();
  PreviewOptions o = small(200, 16, 0);
  o.colouring = io::PreviewColouring::Quality;
  const PreviewImage coloured = io::draw_preview<2>(snap.view(), o);
  const Rgb inside = pixel_at(coloured, 0.25, 0.2);
  EXPECT_FALSE(white(inside));
  EXPECT_GT(inside.g, inside.b);  // the ramp runs red - yellow - green, never blue

  // Size colouring: the ramp runs blue (smallest triangle) to orange (largest); the quad's two triangles differ.
  o.colouring = io::PreviewColouring::Size;
  const PreviewImage sized = io::draw_preview<2>(snap.view(), o);
  EXPECT_NE(pixel_at(sized, 0.25, 0.2), pixel_at(sized, 0.8, 0.75));

  // A solid magenta picture under the mesh: empty pixels inside its extent take its colour.
  PreviewImage magenta{4, 4, std::vector<float>(48, 0.0f)};
  for (std::size_t i = 0; i < 48; i += 3) magenta.rgb[i] = magenta.rgb[i + 2] = 1.0f;
  io::write_image(dir.path("under.png"), magenta);
  PreviewOptions u = small(200, 16, 0);
  u.background = dir.path("under.png");
  u.background_extent = {-0.5, -0.5, 2, 2};
  const PreviewImage under = io::draw_preview<2>(snap.view(), u);
  EXPECT_EQ(pixel_at(under, 0.25, 0.2), (Rgb{1, 0, 1}));
  EXPECT_LT(darkest_near(under, 0.5, 0), 0.56f);
  EXPECT_THROW(io::draw_preview<2>(snap.view(), PreviewOptions{.background = dir.path("missing.png")}), InputError);
}

// One insertion: the removed triangles' edges that are gone are drawn red, the new edges green.
TEST(Preview, DeltaShowsRemovedRedAndAddedGreen) {
  ScratchDir dir;
  std::vector<Point2> points = mesh_test::random_points<2>(12, 21);
  Mesh2 mesh(points, points.size());
  auto edges_of = [](const std::vector<ElementCorners<2>>& elements) {
    std::set<std::pair<Point2, Point2>> edges;
    for (const auto& c : elements)
      for (int i = 0; i < 3; ++i) edges.insert(std::minmax(c[i], c[(i + 1) % 3]));
    return edges;
  };
  const auto before = edges_of(mesh_test::corner_list(mesh));
  const MeshDelta<2> delta = mesh.apply({{}, {{0.5, 0.5}}});
  const auto after = edges_of(mesh_test::corner_list(mesh));
  const MeshSnapshot<2> snap(mesh);
  PreviewOptions o;
  o.width = 400;
  o.line_width = 1.5;
  io::render_delta_preview(dir.path("delta.png"), snap.view(), delta, o);
  PreviewImage image = io::read_image(dir.path("delta.png"));
  const PreviewImage drawn = io::draw_delta_preview(snap.view(), delta, o);
  image.scale = drawn.scale, image.offset_x = drawn.offset_x, image.offset_y = drawn.offset_y;
  std::size_t checked_removed = 0, checked_added = 0;
  for (const auto& e : before)
    if (!after.count(e)) {
      const Rgb c = pixel_at(image, (e.first[0] + e.second[0]) / 2, (e.first[1] + e.second[1]) / 2);
      EXPECT_GT(c.r, c.g + 0.3f);
      ++checked_removed;
    }
  for (const auto& e : after)
    if (!before.count(e)) {
      // Three quarters along, away from the new point where the new edges meet.
      const Rgb c = pixel_at(image, 0.25 * e.first[0] + 0.75 * e.second[0], 0.25 * e.first[1] + 0.75 * e.second[1]);
      EXPECT_GT(c.g, c.r + 0.2f);
      ++checked_added;
    }
  EXPECT_GT(checked_removed, 0u);
  EXPECT_GE(checked_added, 3u);
  const Rgb new_point = pixel_at(image, 0.5, 0.5);  // drawn as a green dot
  EXPECT_GT(new_point.g, 0.45f);
  EXPECT_LT(new_point.r, 0.3f);
}

TEST(Preview, Surface3DAndSliceCoverTheCubeOnly) {
  ScratchDir dir;
  std::vector<Point3> points = mesh_test::random_points<3>(200, 13);
  for (double x : {0.0, 1.0})
    for (double y : {0.0, 1.0})
      for (double z : {0.0, 1.0}) points.push_back({x, y, z});
  const Mesh3 mesh(points, 8);
  const MeshSnapshot<3> snap(mesh);
  PreviewOptions o;
  o.width = 300;
  io::render_preview<3>(dir.path("cube.png"), snap.view(), o);
  const PreviewImage surface = io::read_image(dir.path("cube.png"));
  EXPECT_FALSE(white(surface.at(surface.width / 2, surface.height / 2)));
  EXPECT_TRUE(white(surface.at(2, 2)));

  o.view3d = io::PreviewView3D::SliceZ;
  o.slice_z = 0.5;
  const PreviewImage slice = io::draw_preview<3>(snap.view(), o);
  EXPECT_FALSE(white(pixel_at(slice, 0.5, 0.5)));
  EXPECT_TRUE(white(slice.at(2, 2)));
}

// The height follows the mesh's aspect ratio only up to kMaxPreviewSide: a triangle 10^5 times taller
// than wide asked for 10^8 rows of 1024 pixels (1.2 TB of floats) before.
TEST(Preview, HeightFromAThinMeshsAspectIsCapped) {
  const std::vector<Point2> points{{0, 0}, {1, 0}, {0.5, 1e5}};
  const MeshSnapshot<2> thin{Mesh2(points, 3)};
  const PreviewImage image = io::draw_preview<2>(thin.view(), small(1024, 8, 2));
  EXPECT_EQ(image.height, io::kMaxPreviewSide);
  EXPECT_EQ(image.width, 1024);
  EXPECT_EQ(image.rgb.size(), std::size_t{1024} * io::kMaxPreviewSide * 3);
  // The whole mesh is in the picture: its top and bottom corners land inside.
  for (const Point2& p : points) {
    const auto px = image.to_pixel(p[0], p[1]);
    EXPECT_GE(px[1], 0) << p[1];
    EXPECT_LE(px[1], image.height) << p[1];
  }
}

TEST(Preview, UnknownImageFormatIsAnInputErrorAndWritesNothing) {
  ScratchDir dir;
  const auto snap = quad();
  EXPECT_THROW(io::render_preview<2>(dir.path("mesh.notanimage"), snap.view()), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path("")));
}

}  // namespace
}  // namespace shoremesh
