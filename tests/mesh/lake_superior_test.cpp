// Real data end to end: the GSHHG Lake Superior shore and its 45 islands (lon/lat), projected to metres,
// sampled (ring vertices as input points, a jittered grid as Steiner-like points), meshed inside the water,
// checked against the shoreline, exported to GeoJSON in lon/lat and previewed over the sample water mask.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "mesh_test_util.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/preview.hpp"
#include "shoremesh/mesh.hpp"

namespace shoremesh {
namespace {

using mesh_test::Equirectangular;
using mesh_test::read_rings;

TEST(LakeSuperior, MeshesTheWaterExportsLonLatAndPreviews) {
  const auto lonlat_rings = read_rings(mesh_test::samples("superior/lake_superior_lonlat.csv"));
  ASSERT_EQ(lonlat_rings.size(), 46u);
  const Equirectangular projection;
  Domain2 domain;
  std::size_t ring_points = 0;
  for (std::size_t r = 0; r < lonlat_rings.size(); ++r) {
    Ring ring{{}, r == 0 ? RingRole::Shore : RingRole::Island};
    for (const Point2& ll : lonlat_rings[r]) ring.points.push_back(projection.forward(ll));
    ring_points += ring.points.size();
    domain.rings.push_back(std::move(ring));
  }
  EXPECT_EQ(ring_points + 46, 1679u);

  std::size_t input_count = 0;
  const double h = 4000;  // metres
  const auto points = mesh_test::sample_domain(domain, h, 0.5 * h, 17, input_count);
  const Mesh2 mesh(points, input_count, domain);
  mesh.check_valid();

  // The shore is far coarser in places than 4 km (long straight GSHHG segments next to grid points):
  // the check must find those crossings and give a depth no larger than the sampling explains.
  const ShorelineReport shore = mesh.shoreline_crossings();
  EXPECT_EQ(shore.segments, ring_points);
  EXPECT_GT(shore.covered, shore.segments * 8 / 10) << shore.summary();
  for (const auto& issue : shore.issues) {
    EXPECT_FALSE(issue.endpoint_missing);
    EXPECT_GT(issue.depth, 0.0);
  }
  RecordProperty("shore_segments", std::to_string(shore.segments));
  RecordProperty("shore_covered", std::to_string(shore.covered));
  RecordProperty("shore_worst_depth_m", std::to_string(shore.worst_depth));

  // Water area: 82,078 km² geodesic; the projection and the uncovered bits of shore stay within 2%.
  double area = 0;
  for (const auto& e : mesh.elements()) {
    const auto &a = mesh.points()[e[0]], &b = mesh.points()[e[1]], &c = mesh.points()[e[2]];
    area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  }
  EXPECT_NEAR(area / 1e6, 82078, 0.02 * 82078);

  const QualityReport<2> quality = mesh.quality(std::sqrt(2.0));
  EXPECT_EQ(quality.elements, mesh.element_count());

  mesh_test::ScratchDir dir;
  const io::MeshSnapshot<2> snap(mesh);
  const auto view = snap.view([&](const Point2& p) { return projection.inverse(p); });
  io::export_mesh<2>(dir.path("superior.geojson"), view);
  std::ifstream geo(dir.path("superior.geojson"));
  const nlohmann::json g = nlohmann::json::parse(geo);
  ASSERT_EQ(g["features"].size(), mesh.element_count());
  for (const auto& f : g["features"])
    for (const auto& c : f["geometry"]["coordinates"][0]) {
      ASSERT_GT(c[0].get<double>(), -92.5);
      ASSERT_LT(c[0].get<double>(), -84.0);
      ASSERT_GT(c[1].get<double>(), 46.2);
      ASSERT_LT(c[1].get<double>(), 49.2);
    }

  // Over the 0.005-degree water mask (plate carrée, so a rectangle in this projection): land is black
  // and the mesh covers none of it; inside the lake the edges are drawn.
  io::PreviewOptions o;
  o.width = 1200;
  o.point_radius = 1.2;
  o.background = mesh_test::samples("superior/superior_watermask_h.png");
  const Point2 lo = projection.forward({-92.5, 46.2}), hi = projection.forward({-84.0, 49.2});
  o.background_extent = {lo[0], lo[1], hi[0], hi[1]};
  io::render_preview<2>(dir.path("superior.png"), view, o);
  const io::PreviewImage drawn = io::draw_preview<2>(view, o);
  // Inland points within the picture (the water's extent; uniformly land in the mask for 5 pixels around)
  // show the mask's black.
  for (const Point2 ll : {Point2{-91.0, 47.6}, Point2{-89.0, 48.8}, Point2{-85.5, 46.5}, Point2{-89.5, 48.9}}) {
    const Point2 xy = projection.forward(ll);
    const auto px = drawn.to_pixel(xy[0], xy[1]);
    ASSERT_TRUE(px[0] >= 0 && px[0] < drawn.width && px[1] >= 0 && px[1] < drawn.height)
        << ll[0] << ", " << ll[1] << " is off the picture at " << px[0] << ", " << px[1];
    const io::Rgb c = drawn.at(static_cast<int>(px[0]), static_cast<int>(px[1]));
    EXPECT_EQ(c, (io::Rgb{0, 0, 0})) << ll[0] << ", " << ll[1];
  }
  std::size_t ink = 0;
  for (std::size_t i = 0; i < drawn.rgb.size(); i += 3) ink += drawn.rgb[i] < 0.3f && drawn.rgb[i + 2] < 0.3f && drawn.rgb[i] > 0.0f;
  EXPECT_GT(ink, 1000u);
  if (const char* keep = std::getenv("SHOREMESH_KEEP_PREVIEW")) std::filesystem::copy_file(dir.path("superior.png"), keep, std::filesystem::copy_options::overwrite_existing);
}

}  // namespace
}  // namespace shoremesh
