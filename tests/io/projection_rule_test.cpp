// The projection rule (issue 34): a projected system is meshed in its own metres only where its scale
// factor stays within 0.1 % of 1 over the data; otherwise, and for lon/lat, the data goes to a transverse
// Mercator centred on it. Scale factors are PROJ's (proj_factors), checked here against GeographicLib's.
#include <cmath>

#include "io_test_names.hpp"
#include "shoremesh/io/georeference.hpp"
#include "shoremesh/io/projection.hpp"
#include "shoremesh/io/ring_file.hpp"

namespace {

std::vector<LonLat> superior_lonlat() {
  const RingFile rf = parse_ring_file_text(test::read_file(samples("superior/lake_superior_lonlat.csv")), "superior");
  std::vector<LonLat> out;
  for (const auto& r : rf.rings)
    for (const auto& p : r) out.push_back({p[0], p[1]});
  return out;
}

TEST(ProjectionRule, ProjScaleFactorsAgreeWithGeographicLibsForUtmAndLocalTransverseMercator) {
  for (const Projection& p : {Projection::utm_ups(16, true), Projection::local_transverse_mercator(-88.2, 47.6)})
    for (const LonLat ll : {LonLat{-92.2, 46.5}, LonLat{-87, 47}, LonLat{-84.3, 48.9}, LonLat{-88.2, 47.6}}) {
      const ScaleRange s = measure_scale(p, {ll});
      EXPECT_NEAR(s.max, p.scale(ll), 1e-7) << p.describe();  // PROJ differentiates numerically
      EXPECT_NEAR(s.min, s.max, 1e-7) << "a conformal projection has one scale in all directions";
    }
}

TEST(ProjectionRule, SuperiorInUtm16ReachesBeyondTheToleranceAndGoesToALocalTransverseMercator) {
  const auto data = superior_lonlat();
  const auto samples = extent_samples(data);
  ASSERT_EQ(samples.size(), 17u * 17u);
  const ScaleRange utm = measure_scale(Projection::utm_ups(16, true), samples);
  EXPECT_NEAR(utm.min, 0.9996, 1e-5);  // near the central meridian -87
  EXPECT_GT(utm.max, 1.0014);          // 5.1 degrees west of it at 46.4 N
  EXPECT_FALSE(utm.within());
  // Kept UTM data across the lake is reprojected; the local transverse Mercator is centred on the data and
  // so keeps its scale nearest 1 (1 on its central meridian, 1.0011 at the lake's ends).
  const ChosenProjection kept_not = choose_projection(Projection::utm_ups(16, true), data, ProjectionChoice::LocalTransverseMercator);
  EXPECT_EQ(kept_not.projection.kind(), Projection::Kind::LocalTransverseMercator);
  EXPECT_THAT(kept_not.note, HasSubstr("reprojected from UTM zone 16N (WGS84)"));
  const ScaleRange local = measure_scale(kept_not.projection, samples);
  EXPECT_NEAR(local.min, 1.0, 1e-5);  // the samples' nearest to its central meridian
  EXPECT_LT(local.max - 1, utm.max - 1);
  // lon/lat data: the local transverse Mercator unless UTM is asked for, and the note says the scale.
  const ChosenProjection ll = choose_projection(std::nullopt, data, ProjectionChoice::LocalTransverseMercator);
  EXPECT_EQ(ll.projection, kept_not.projection);
  EXPECT_THAT(ll.note, HasSubstr("scale 1.00000 .. 1.001"));
  const ChosenProjection asked = choose_projection(std::nullopt, data, ProjectionChoice::Utm);
  EXPECT_EQ(asked.projection, Projection::utm_ups(16, true));
  EXPECT_THAT(asked.note, HasSubstr("scale 0.99960 .. 1.00"));
}

TEST(ProjectionRule, UtmInsideItsZoneIsKeptWebMercatorIsReprojected) {
  // Around Cerknica (14.3 E, zone 33's central meridian at 15 E): UTM stays within 0.1 % and is kept.
  const std::vector<LonLat> cerknica = {{14.30, 45.74}, {14.37, 45.74}, {14.37, 45.79}, {14.30, 45.79}};
  const ChosenProjection utm = choose_projection(Projection::utm_ups(33, true), cerknica, ProjectionChoice::LocalTransverseMercator);
  EXPECT_EQ(utm.projection, Projection::utm_ups(33, true));
  EXPECT_THAT(utm.note, HasSubstr("meshed in UTM zone 33N (WGS84)"));
  // Web Mercator over the Salish Sea: scale 1.49 .. 1.56 (1 / cos(latitude)), reprojected.
  const Projection merc = Projection::crs(parse_coordinate_system("EPSG:3857").wkt, "WGS 84 / Pseudo-Mercator");
  const std::vector<LonLat> salish = {{-126, 48}, {-122, 48}, {-122, 50}, {-126, 50}};
  const ScaleRange s = measure_scale(merc, extent_samples(salish));
  EXPECT_NEAR(s.min, 1 / std::cos(48 * std::acos(-1.0) / 180), 0.01);
  EXPECT_NEAR(s.max, 1 / std::cos(50 * std::acos(-1.0) / 180), 0.01);
  const ChosenProjection c = choose_projection(merc, salish, ProjectionChoice::LocalTransverseMercator);
  EXPECT_EQ(c.projection.kind(), Projection::Kind::LocalTransverseMercator);
  EXPECT_NEAR(c.projection.lon0(), -124, 0.01);
  EXPECT_THAT(c.note, HasSubstr("reprojected from WGS 84 / Pseudo-Mercator"));
}

}  // namespace
