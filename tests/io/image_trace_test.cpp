#include "shoremesh/io/image_trace.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <filesystem>
#include <cmath>

#include "io_test_names.hpp"
#include "shoremesh/io/ring_file.hpp"

namespace {

const std::string kMask = samples("superior/superior_watermask_h.png");

double ring_length(const std::vector<Point2>& r) {
  double len = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const auto& a = r[i];
    const auto& b = r[(i + 1) % r.size()];
    len += std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  return len;
}

double ring_area(const std::vector<Point2>& r) {
  double a = 0;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) a += r[j][0] * r[i][1] - r[i][0] * r[j][1];
  return std::abs(a) / 2;
}

double segment_distance(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1], len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

// The GSHHG polygon the mask was rendered from, in the mask's pixel coordinates (through its world file).
struct Truth {
  std::vector<Point2> outer;
  std::vector<std::vector<Point2>> islands;
};

Truth superior_truth() {
  const auto rf = read_ring_file(samples("superior/lake_superior_lonlat.csv"));
  const auto wld = parse_world_file_text(shoremesh::io::test::read_file(samples("superior/superior_watermask_h.wld")), "wld");
  Truth t;
  for (std::size_t r = 0; r < rf.rings.size(); ++r) {
    std::vector<Point2> px;
    for (const auto& ll : rf.rings[r]) px.push_back(wld.inverse(ll));
    if (r == 0) t.outer = std::move(px);
    else t.islands.push_back(std::move(px));
  }
  return t;
}

// Length of the part of a closed ring west of column x_max (segments clipped).
double length_west_of(const std::vector<Point2>& r, double x_max) {
  double len = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    Point2 a = r[i], b = r[(i + 1) % r.size()];
    if (a[0] > b[0]) std::swap(a, b);
    if (a[0] >= x_max) continue;
    if (b[0] > x_max) {
      const double t = (x_max - a[0]) / (b[0] - a[0]);
      b = {x_max, a[1] + t * (b[1] - a[1])};
    }
    len += std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  return len;
}

// Index of the largest water region (Lake Superior in the bundled mask).
int largest_water(const TracedImage& img) {
  int best = -1;
  for (std::size_t i = 0; i < img.rings.size(); ++i)
    if (img.rings[i].depth == 0 && (best < 0 || img.rings[i].area_pixels > img.rings[best].area_pixels)) best = static_cast<int>(i);
  return best;
}

bool contains(const std::vector<Point2>& ring, const Point2& p) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    if ((ring[i][1] > p[1]) != (ring[j][1] > p[1]) &&
        p[0] < (ring[j][0] - ring[i][0]) * (p[1] - ring[i][1]) / (ring[j][1] - ring[i][1]) + ring[i][0])
      in = !in;
  return in;
}

Point2 centroid(const std::vector<Point2>& r) {
  double a = 0, cx = 0, cy = 0;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
    const double w = r[j][0] * r[i][1] - r[i][0] * r[j][1];
    a += w, cx += (r[j][0] + r[i][0]) * w, cy += (r[j][1] + r[i][1]) * w;
  }
  return {cx / (3 * a), cy / (3 * a)};
}

// Column of longitude -84.75 in the mask: east of it the mask's water continues into the St. Marys River
// while the polygon closes with a straight chord, so shape comparisons stop there.
constexpr double kRiverColumn = (-84.75 + 92.5) / 0.005 - 0.5;

// A binary PGM (P5), 8-bit or 16-bit (big-endian) samples.
std::string pgm(int w, int h, const std::vector<int>& v, int maxval = 255) {
  std::string s = "P5\n" + std::to_string(w) + " " + std::to_string(h) + "\n" + std::to_string(maxval) + "\n";
  for (int x : v) {
    if (maxval > 255) s += static_cast<char>(x >> 8);
    s += static_cast<char>(x & 0xFF);
  }
  return s;
}

// A binary PPM (P6) from RGB triples.
std::string ppm(int w, int h, const std::vector<std::array<int, 3>>& v) {
  std::string s = "P6\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
  for (const auto& c : v)
    for (int k = 0; k < 3; ++k) s += static_cast<char>(c[k]);
  return s;
}

// w x h mask: water everywhere except where land(col, row) is true.
template <class F>
WaterMask mask_of(int w, int h, F&& land) {
  WaterMask m{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h, 1)};
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      if (land(c, r)) m.water[static_cast<std::size_t>(r) * w + c] = 0;
  return m;
}

}  // namespace

TEST(ImageTrace, SuperiorIslandsAboveMinimumArea) {
  const double min_area = 20;
  ImageTraceOptions opt;
  opt.min_area = min_area;
  const auto img = trace_image(kMask, opt);
  const auto truth = superior_truth();
  const int sup = largest_water(img);
  ASSERT_GE(sup, 0);
  std::vector<const TracedRing*> islands;
  for (const auto& r : img.rings)
    if (r.parent == sup) islands.push_back(&r);
  for (const auto* r : islands) {
    EXPECT_EQ(r->role, RingRole::Island);
    EXPECT_GE(r->area_pixels, min_area);
  }
  // Rasterising moves an island's area by about half a pixel times its perimeter: count the polygon's islands
  // clearly above and clearly below the minimum, the traced count must lie between.
  std::size_t clearly_above = 0, maybe_above = 0;
  for (const auto& isl : truth.islands) {
    clearly_above += ring_area(isl) >= 1.5 * min_area;
    maybe_above += ring_area(isl) >= min_area / 1.5;
  }
  std::printf("islands: traced %zu above %.0f px (polygon: %zu clearly above, %zu possibly), dropped %zu smaller\n",
              islands.size(), min_area, clearly_above, maybe_above, img.dropped_small_islands);
  EXPECT_GE(islands.size(), clearly_above);
  EXPECT_LE(islands.size(), maybe_above);
  EXPECT_GT(img.dropped_small_islands, 0u);  // the small ones are counted, not silently lost
  EXPECT_THAT(img.input.notes.back(), HasSubstr("dropped " + std::to_string(img.dropped_small_islands) + " islands"));
  // Every polygon island of at least twice the minimum is found, at its place and with its size.
  for (const auto& isl : truth.islands) {
    if (ring_area(isl) < 2 * min_area) continue;
    const Point2 c = centroid(isl);
    const TracedRing* match = nullptr;
    for (const auto* r : islands)
      if (contains(r->pixels, c) || contains(r->dense_pixels, c)) match = r;
    ASSERT_NE(match, nullptr) << "island at pixel " << c[0] << "," << c[1];
    EXPECT_NEAR(match->area_pixels, ring_area(isl), 0.35 * ring_area(isl) + 4) << "island at pixel " << c[0] << "," << c[1];
  }
}

// The mask traced with islands of 10 pixels and more, samples at most 3 pixels apart (shared by two tests).
constexpr double kShapeMinArea = 10;
const TracedImage& superior_traced_for_shape() {
  static const TracedImage img = [] {
    ImageTraceOptions opt;
    opt.min_area = kShapeMinArea;
    opt.spacing = 3;
    return trace_image(kMask, opt);
  }();
  return img;
}

TEST(ImageTrace, SuperiorShorelineLengthWithinFewPercent) {
  const auto& img = superior_traced_for_shape();
  const auto truth = superior_truth();
  const int sup = largest_water(img);
  const double outer = length_west_of(img.rings[sup].pixels, kRiverColumn);
  const double outer_truth = length_west_of(truth.outer, kRiverColumn);
  double islands = 0, islands_truth = 0;
  for (const auto& r : img.rings)
    if (r.parent == sup) islands += ring_length(r.pixels);
  for (const auto& isl : truth.islands)
    if (ring_area(isl) >= kShapeMinArea) islands_truth += ring_length(isl);
  const double total_error = (outer + islands) / (outer_truth + islands_truth) - 1;
  std::printf("shore length (pixels): outer %.1f vs %.1f (%+.2f%%), islands %.1f vs %.1f (%+.2f%%), total %+.2f%%\n", outer,
              outer_truth, 100 * (outer / outer_truth - 1), islands, islands_truth, 100 * (islands / islands_truth - 1),
              100 * total_error);
  EXPECT_NEAR(outer / outer_truth, 1.0, 0.03);
  EXPECT_NEAR(islands / islands_truth, 1.0, 0.05);
  EXPECT_NEAR(total_error, 0.0, 0.03);
}

TEST(ImageTrace, SuperiorSamplesWithinOnePixelOfTrueBoundary) {
  const auto& img = superior_traced_for_shape();
  const auto truth = superior_truth();
  std::vector<std::pair<Point2, Point2>> segments;
  auto add = [&](const std::vector<Point2>& r) {
    for (std::size_t i = 0; i < r.size(); ++i) segments.push_back({r[i], r[(i + 1) % r.size()]});
  };
  add(truth.outer);
  for (const auto& isl : truth.islands) add(isl);
  const int sup = largest_water(img);
  double worst = 0, sum = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < img.rings.size(); ++k) {
    const auto& r = img.rings[k];
    if (!(static_cast<int>(k) == sup || r.parent == sup)) continue;
    for (const auto& p : r.pixels) {
      if (p[0] > kRiverColumn) continue;
      double d = 1e300;
      for (const auto& [a, b] : segments) d = std::min(d, segment_distance(p, a, b));
      EXPECT_LE(d, 1.0) << "sample at pixel " << p[0] << "," << p[1];
      worst = std::max(worst, d);
      sum += d;
      ++n;
    }
  }
  std::printf("%zu samples: distance to the polygon max %.3f px, mean %.3f px\n", n, worst, sum / n);
  EXPECT_GT(n, 3000u);
}

TEST(ImageTrace, SuperiorGeoreferencedProjectedAndBack) {
  ImageTraceOptions opt;
  opt.min_area = 10;
  opt.largest_water_only = true;
  const auto img = trace_image(kMask, opt);
  EXPECT_EQ(img.georeference.source, Georeference::Source::WorldFile);
  EXPECT_EQ(img.georeference.crs.kind, CoordinateSystem::Kind::Geographic);
  const InputSet& set = img.input;
  EXPECT_EQ(set.units, Units::Metres);
  // lon/lat: a transverse Mercator centred on the image (the projection rule; UTM 16N reaches 1.0018 here).
  EXPECT_EQ(set.projection.describe(), "local transverse Mercator at 47.732699N 88.250000W (WGS84)");
  EXPECT_GT(img.dropped_other_water, 0u);  // the other inland lakes
  ASSERT_EQ(set.domain.rings.size(), img.rings.size());
  EXPECT_EQ(set.domain.rings[0].role, RingRole::Shore);
  // One body of water: the lake and its islands, no pond on an island (Isle Royale's lakes are water of
  // their own).
  for (std::size_t r = 1; r < set.domain.rings.size(); ++r) EXPECT_EQ(set.domain.rings[r].role, RingRole::Island) << r;
  // Samples go back to the lon/lat of their pixel position.
  double worst = 0;
  for (const auto& r : img.rings)
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      const LonLat ll = set.projection.reverse(r.points[i]);
      const Point2 expect = img.georeference.pixel_to_map(r.pixels[i]);
      worst = std::max({worst, std::abs(ll.lon - expect[0]), std::abs(ll.lat - expect[1])});
    }
  EXPECT_LT(worst, 1e-9);
  // The water area in square metres: the GSHHG geodesic area is 82,078 km^2 (plus a little St. Marys River).
  double area = 0;
  for (const auto& ring : set.domain.rings) area += (ring.role == RingRole::Shore ? 1 : -1) * ring_area(ring.points);
  std::printf("Superior water area traced, local transverse Mercator: %.0f km^2 (GSHHG geodesic 82078 km^2)\n", area / 1e6);
  EXPECT_NEAR(area / 1e6, 82078, 0.02 * 82078);
}

TEST(ImageTrace, GeoTiffTagsGiveTheSameGeoreferenceAsTheWorldFile) {
  const auto g = read_geotiff_tags(samples("superior/superior_watermask_h.tif"));
  ASSERT_TRUE(g.has_value());
  const auto w = parse_world_file_text(shoremesh::io::test::read_file(samples("superior/superior_watermask_h.wld")), "w");
  EXPECT_EQ(g->crs.kind, CoordinateSystem::Kind::Geographic);
  for (auto [a, b] : {std::pair{g->pixel_to_map.a, w.a}, {g->pixel_to_map.b, w.b}, {g->pixel_to_map.c, w.c},
                      {g->pixel_to_map.d, w.d}, {g->pixel_to_map.e, w.e}, {g->pixel_to_map.f, w.f}})
    EXPECT_NEAR(a, b, 1e-9);
  ImageTraceOptions opt;
  opt.min_area = 10;
  // Alone in a directory (beside the sample's .wld, the world file would be found first).
  shoremesh::io::test::ScratchDir dir;
  const auto alone = dir.write("superior.tif", shoremesh::io::test::read_file(samples("superior/superior_watermask_h.tif")));
  const auto tif = trace_image(alone, opt);
  const auto png = trace_image(kMask, opt);
  EXPECT_EQ(tif.georeference.source, Georeference::Source::GeoTiff);
  ASSERT_EQ(tif.input.points.size(), png.input.points.size());
  for (std::size_t i = 0; i < tif.input.points.size(); ++i) {
    EXPECT_NEAR(tif.input.points[i][0], png.input.points[i][0], 1e-6);  // metres; the world file has 10 decimals
    EXPECT_NEAR(tif.input.points[i][1], png.input.points[i][1], 1e-6);
  }
}

TEST(ImageTrace, NarrowChannelAndSmallIslandKeepEnoughPoints) {
  // Two 60x60 basins joined by a 3-pixel channel 40 pixels long, and a 4x4 island in one basin.
  const auto m = mask_of(160, 80, [](int c, int r) {
    const bool basin = (c >= 10 && c < 70 && r >= 10 && r < 70) || (c >= 110 && c < 150 && r >= 10 && r < 70);
    const bool channel = c >= 70 && c < 110 && r >= 39 && r < 42;
    const bool island = c >= 40 && c < 44 && r >= 40 && r < 44;
    return !(basin || channel) || island;
  });
  ImageTraceOptions opt;
  opt.spacing = 20;
  opt.min_area = 5;
  const auto img = trace_water_mask(m, opt);
  ASSERT_EQ(img.rings.size(), 2u);
  EXPECT_EQ(img.input.units, Units::Pixels);
  const auto& shore = img.rings[0];
  const auto& island = img.rings[1];
  EXPECT_EQ(island.role, RingRole::Island);
  EXPECT_GE(island.pixels.size(), 6u);  // a 4-pixel island: spacing <= half its width
  // Along the channel, samples on each side are at most half the channel's width (+ a pixel) apart.
  std::vector<Point2> in_channel;
  for (const auto& p : shore.pixels)
    if (p[0] > 75 && p[0] < 105) in_channel.push_back(p);
  EXPECT_GE(in_channel.size(), 2u * 30 / 3);
  for (std::size_t i = 0; i + 1 < shore.pixels.size(); ++i) {
    const auto& a = shore.pixels[i];
    const auto& b = shore.pixels[i + 1];
    if (a[0] > 75 && a[0] < 105 && b[0] > 75 && b[0] < 105) {
      EXPECT_LE(std::hypot(a[0] - b[0], a[1] - b[1]), 2.5);
    }
  }
  // Far from narrow parts the spacing reaches the requested 20 pixels.
  double longest = 0;
  for (std::size_t i = 0; i < shore.pixels.size(); ++i) {
    const auto& a = shore.pixels[i];
    const auto& b = shore.pixels[(i + 1) % shore.pixels.size()];
    longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1]));
  }
  EXPECT_GT(longest, 12.0);
  EXPECT_LE(longest, 20.5);
}

TEST(ImageTrace, SmallIslandsDroppedAreCounted) {
  const auto m = mask_of(100, 100, [](int c, int r) {
    if (c < 5 || r < 5 || c >= 95 || r >= 95) return true;  // shore
    if (c >= 20 && c < 22 && r >= 20 && r < 22) return true;  // 4 px
    if (c == 50 && r == 50) return true;                      // 1 px
    if (c >= 70 && c < 73 && r >= 70 && r < 73) return true;  // 9 px
    return c >= 40 && c < 50 && r >= 70 && r < 80;             // 100 px, kept
  });
  ImageTraceOptions opt;
  opt.min_area = 12;
  const auto img = trace_water_mask(m, opt);
  EXPECT_EQ(img.dropped_small_islands, 3u);
  EXPECT_EQ(img.input.dropped_small_islands, 3u);
  ASSERT_EQ(img.rings.size(), 2u);
  EXPECT_NEAR(img.rings[1].area_pixels, 100, 1);
  opt.min_area = 3;
  EXPECT_EQ(trace_water_mask(m, opt).rings.size(), 4u);  // shore, 2x2, 3x3 and 10x10 islands; 1 px dropped
}

TEST(ImageTrace, PondOnIslandIsWaterAgain) {
  const auto m = mask_of(60, 60, [](int c, int r) {
    if (c < 3 || r < 3 || c >= 57 || r >= 57) return true;
    const bool island = c >= 15 && c < 45 && r >= 15 && r < 45;
    const bool pond = c >= 25 && c < 35 && r >= 25 && r < 35;
    return island && !pond;
  });
  const auto img = trace_water_mask(m);
  ASSERT_EQ(img.rings.size(), 3u);
  EXPECT_EQ(img.rings[0].role, RingRole::Shore);
  EXPECT_EQ(img.rings[1].role, RingRole::Island);
  EXPECT_EQ(img.rings[2].role, RingRole::Shore);
  EXPECT_EQ(img.rings[2].parent, 1);
  EXPECT_EQ(img.rings[2].depth, 2);
}

TEST(ImageTrace, GreyThresholdOtsuDarkWaterAnd16Bit) {
  shoremesh::io::test::ScratchDir dir;
  // Dark water (values 20..40) in the middle, light land (200..230) around, some noise.
  std::vector<int> v;
  for (int r = 0; r < 50; ++r)
    for (int c = 0; c < 80; ++c) {
      const bool water = c >= 10 && c < 70 && r >= 10 && r < 40;
      v.push_back((water ? 20 : 200) + (c * 7 + r * 3) % 30);
    }
  const auto p8 = dir.write("dark.pgm", pgm(80, 50, v));
  ImageTraceOptions opt;
  opt.water = WaterSide::Dark;
  const auto a = trace_image(p8, opt);
  EXPECT_GE(a.threshold, 49);  // any level between the classes separates them; Otsu takes the first
  EXPECT_LT(a.threshold, 200);
  ASSERT_EQ(a.rings.size(), 1u);
  EXPECT_NEAR(a.rings[0].area_pixels, 60 * 30, 60);
  EXPECT_EQ(a.input.units, Units::Pixels);
  EXPECT_THAT(a.input.notes.front(), HasSubstr("pixels"));
  // The same as 16-bit samples, and with a threshold given by the user.
  std::vector<int> v16;
  for (int x : v) v16.push_back(x * 257);
  const auto p16 = dir.write("dark16.pgm", pgm(80, 50, v16, 65535));
  const auto b = trace_image(p16, opt);
  EXPECT_EQ(b.bits, 16);
  EXPECT_EQ(b.input.points, a.input.points);
  opt.threshold = 120 * 257;
  EXPECT_EQ(trace_image(p16, opt).input.points, a.input.points);
  // Light water: the complement — the 'water' is the frame of land, inverted.
  opt.threshold.reset();
  opt.water = WaterSide::Light;
  EXPECT_EQ(trace_image(p8, opt).rings[0].role, RingRole::Shore);
}

TEST(ImageTrace, ColourWaterWithTolerance) {
  shoremesh::io::test::ScratchDir dir;
  std::vector<std::array<int, 3>> v;
  for (int r = 0; r < 40; ++r)
    for (int c = 0; c < 60; ++c) {
      const bool water = (c - 30) * (c - 30) + (r - 20) * (r - 20) < 15 * 15;
      v.push_back(water ? std::array<int, 3>{176 + (c % 5), 196, 222 - (r % 7)} : std::array<int, 3>{222, 184, 135});
    }
  const auto path = dir.write("map.ppm", ppm(60, 40, v));
  ImageTraceOptions opt;
  opt.water = WaterSide::Colour;
  opt.water_colour = {176, 196, 222};  // lightsteelblue
  opt.colour_tolerance = 20;
  // 10 map units per pixel, on zone 33's central meridian, where UTM is kept (the projection rule).
  opt.georeference.box = MapBox{500000, 2000, 500600, 2400};
  opt.georeference.crs = "UTM 33N";
  const auto img = trace_image(path, opt);
  ASSERT_EQ(img.rings.size(), 1u);
  EXPECT_NEAR(img.rings[0].area_pixels, 3.14159 * 15 * 15, 40);
  EXPECT_EQ(img.georeference.source, Georeference::Source::UserBox);
  EXPECT_EQ(img.input.units, Units::Metres);
  EXPECT_EQ(img.input.projection.describe(), "UTM zone 33N (WGS84)");
  // Pixel (30, 20) is the circle's centre: x = 500000 + 30.5 * 10, y = 2400 - 20.5 * 10.
  const Point2 c = centroid(img.rings[0].points);
  EXPECT_NEAR(c[0], 500305, 5);
  EXPECT_NEAR(c[1], 2195, 5);
}

TEST(ImageTrace, RealColourMapTracesItsWater) {
  ImageTraceOptions opt;
  opt.water = WaterSide::Colour;
  opt.water_colour = {176, 196, 222};  // GMT's lightsteelblue
  opt.colour_tolerance = 30;
  opt.min_area = 50;
  opt.largest_water_only = true;
  opt.close_radius = 1;  // the grey international border (about 1 pixel) crosses the lake: close it
  const auto img = trace_image(samples("superior/superior_map_gmt.png"), opt);
  EXPECT_EQ(img.input.units, Units::Pixels);
  ASSERT_FALSE(img.rings.empty());
  const double fraction = img.rings[0].area_pixels / (img.width * img.height);
  std::printf("map image: Superior covers %.1f%% of the map, %zu islands kept\n", 100 * fraction, img.rings.size() - 1);
  EXPECT_GT(fraction, 0.25);
  EXPECT_LT(fraction, 0.6);
}

TEST(ImageTrace, MalformedImagesGetClearErrors) {
  shoremesh::io::test::ScratchDir dir;
  const auto land = dir.write("land.pgm", pgm(20, 10, std::vector<int>(200, 0)));
  auto e = expect_input_error([&] { trace_image(land); });
  EXPECT_EQ(e.file(), land);
  EXPECT_THAT(e.message(), HasSubstr("single grey level"));
  ImageTraceOptions given;
  given.threshold = 128;
  e = expect_input_error([&] { trace_image(land, given); });
  EXPECT_THAT(e.message(), HasSubstr("all land"));
  const auto water = dir.write("water.pgm", pgm(20, 10, std::vector<int>(200, 255)));
  e = expect_input_error([&] { trace_image(water, given); });
  EXPECT_THAT(e.message(), HasSubstr("all water"));
  // Too large: refused from the header, before decoding (the file holds no pixel data at all).
  const auto big = dir.write("big.pgm", "P5\n100000 100000\n255\n");
  e = expect_input_error([&] { trace_image(big); });
  EXPECT_THAT(e.message(), HasSubstr("image too large: 100000 x 100000"));
  EXPECT_THAT(e.message(), HasSubstr("refused before decoding"));
  ImageTraceOptions small;
  small.max_pixels = 1000;
  e = expect_input_error([&] { trace_image(kMask, small); });
  EXPECT_THAT(e.message(), HasSubstr("image too large: 1700 x 600"));
  const auto text = dir.write("notimage.png", "this is not a PNG\n");
  e = expect_input_error([&] { trace_image(text); });
  EXPECT_EQ(e.file(), text);
  const auto empty = dir.write("empty.png", "");
  e = expect_input_error([&] { trace_image(empty); });
  EXPECT_EQ(e.file(), empty);
  const auto truncated = dir.write("cut.png", shoremesh::io::test::read_file(kMask).substr(0, 3000));
  e = expect_input_error([&] { trace_image(truncated); });
  EXPECT_EQ(e.file(), truncated);
  e = expect_input_error([&] { trace_image(dir.path("missing.png")); });
  EXPECT_THAT(e.message(), HasSubstr("cannot open"));
}

TEST(Georeference, CoordinateSystemsFromPrjAndShortForms) {
  const auto prj = parse_coordinate_system(shoremesh::io::test::read_file(samples("superior/superior_watermask_h.prj")));
  EXPECT_EQ(prj.kind, CoordinateSystem::Kind::Geographic);
  EXPECT_EQ(prj.name, "WGS 84");
  auto utm = parse_coordinate_system("EPSG:32716");
  EXPECT_EQ(utm.kind, CoordinateSystem::Kind::Utm);
  EXPECT_EQ(utm.zone, 16);
  EXPECT_FALSE(utm.north);
  utm = parse_coordinate_system(Projection::utm_ups(33, true).wkt());
  EXPECT_EQ(utm.kind, CoordinateSystem::Kind::Utm);
  EXPECT_EQ(utm.zone, 33);
  EXPECT_TRUE(utm.north);
  utm = parse_coordinate_system(
      "PROJCS[\"WGS_1984_UTM_Zone_10N\",GEOGCS[\"GCS_WGS_1984\",DATUM[\"D_WGS_1984\",SPHEROID[\"WGS_1984\",6378137,298.257223563]],"
      "PRIMEM[\"Greenwich\",0],UNIT[\"Degree\",0.017453292519943295]],PROJECTION[\"Transverse_Mercator\"],"
      "PARAMETER[\"central_meridian\",-123],UNIT[\"Meter\",1]]");
  // A transverse Mercator at -123 without UTM's scale factor and false easting is not UTM zone 10 (PROJ
  // reads its parameters, not its name): another system, taken through lon/lat.
  EXPECT_EQ(utm.kind, CoordinateSystem::Kind::Other);
  EXPECT_EQ(parse_coordinate_system("utm 5s").zone, 5);
  EXPECT_FALSE(parse_coordinate_system("UTM zone 16 S").north);
  EXPECT_EQ(parse_coordinate_system("EPSG: 4326").kind, CoordinateSystem::Kind::Geographic);
  // An incomplete WKT is refused even with an ID: PROJ reads the definition, not the label.
  EXPECT_THROW(parse_coordinate_system("PROJCRS[\"WGS 84 / UTM zone 16N\",BASEGEOGCRS[\"WGS 84\"],ID[\"EPSG\",32616]]"),
               InputError);
  EXPECT_THROW(parse_coordinate_system("UTM 61N"), InputError);
  EXPECT_THROW(parse_coordinate_system("EPSG:99999999999"), InputError);
  EXPECT_EQ(parse_coordinate_system("WGS84").kind, CoordinateSystem::Kind::Geographic);
  EXPECT_EQ(parse_coordinate_system("EPSG:32116").kind, CoordinateSystem::Kind::Other);  // NAD83 / New York East
  EXPECT_THROW(parse_coordinate_system("PROJCS[\"NAD83 / Wisconsin Central\",GEOGCS[\"NAD83\"]]"), InputError);
  const auto e = expect_input_error([] { parse_coordinate_system("hello", "x.prj"); });
  EXPECT_EQ(e.file(), "x.prj");
}

TEST(Georeference, WorldFileErrorsNameTheLine) {
  auto e = expect_input_error([] { parse_world_file_text("1\n0\n0\n-1\nabc\n5\n", "a.wld"); });
  EXPECT_EQ(e.line(), 5u);
  e = expect_input_error([] { parse_world_file_text("1\n0\n0\n-1\n5\n", "a.wld"); });
  EXPECT_THAT(e.message(), HasSubstr("found 5"));
  e = expect_input_error([] { parse_world_file_text("0\n0\n0\n0\n5\n6\n", "a.wld"); });
  EXPECT_THAT(e.message(), HasSubstr("zero pixel size"));
  const auto w = parse_world_file_text("2\n0\n0\n-2\n100\n200\n", "b.wld");
  const Point2 p = w(3, 4);
  EXPECT_EQ(p, (Point2{106, 192}));
  EXPECT_EQ(w.inverse(p), (Point2{3, 4}));
}

namespace {

// Writes the Superior mask in another format/bit depth through OpenImageIO (8-bit source values scaled to the
// target depth), with a copy of the world file and .prj under the names that format uses.
std::string convert_mask(const shoremesh::io::test::ScratchDir& dir, const std::string& name, OIIO::TypeDesc type,
                         int channels, const std::string& world_ext) {
  auto in = OIIO::ImageInput::open(kMask);
  const auto spec = in->spec();
  std::vector<std::uint8_t> grey(static_cast<std::size_t>(spec.width) * spec.height);
  in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, grey.data());
  in->close();
  std::vector<float> pixels;
  for (auto g : grey)
    for (int c = 0; c < channels; ++c) pixels.push_back(c == 2 ? g / 255.0f : g / 255.0f * 0.8f);  // bluish water
  const std::string path = dir.path(name);
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec ospec(spec.width, spec.height, channels, type);
  out->open(path, ospec);
  out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
  out->close();
  dir.write(std::filesystem::path(name).stem().string() + world_ext,
            shoremesh::io::test::read_file(samples("superior/superior_watermask_h.wld")));
  dir.write(std::filesystem::path(name).stem().string() + ".prj",
            shoremesh::io::test::read_file(samples("superior/superior_watermask_h.prj")));
  return path;
}

}  // namespace

TEST(ImageTrace, JpegAndTiffGreyAndColourEightAndSixteenBit) {
  shoremesh::io::test::ScratchDir dir;
  ImageTraceOptions opt;
  opt.min_area = 20;
  opt.largest_water_only = true;
  const auto reference = trace_image(kMask, opt);
  struct Case {
    std::string name;
    OIIO::TypeDesc type;
    int channels;
    std::string world;
    int bits;
  };
  const std::vector<Case> cases{{"grey.jpg", OIIO::TypeDesc::UINT8, 1, ".jgw", 8},
                                {"colour.jpg", OIIO::TypeDesc::UINT8, 3, ".jpgw", 8},
                                {"grey16.tif", OIIO::TypeDesc::UINT16, 1, ".tfw", 16},
                                {"colour16.tif", OIIO::TypeDesc::UINT16, 3, ".tfw", 16},
                                {"colour.png", OIIO::TypeDesc::UINT8, 3, ".pgw", 8}};
  for (const auto& c : cases) {
    const auto path = convert_mask(dir, c.name, c.type, c.channels, c.world);
    const auto img = trace_image(path, opt);
    EXPECT_EQ(img.bits, c.bits) << c.name;
    EXPECT_EQ(img.channels, c.channels) << c.name;
    EXPECT_EQ(img.georeference.source, Georeference::Source::WorldFile) << c.name;
    EXPECT_EQ(img.input.projection, reference.input.projection) << c.name;
    // Same lake: area within 0.5 %, island count within 2 (JPEG blurs edges of the smallest islands).
    EXPECT_NEAR(img.rings[0].area_pixels, reference.rings[0].area_pixels, 0.005 * reference.rings[0].area_pixels) << c.name;
    EXPECT_NEAR(static_cast<double>(img.rings.size()), static_cast<double>(reference.rings.size()), 2.0) << c.name;
  }
  // Colour selection on the colour TIFF: water is the bluish colour (0.8*255, 0.8*255, 255) scaled to 16 bits.
  ImageTraceOptions colour = opt;
  colour.water = WaterSide::Colour;
  colour.water_colour = {204, 204, 255};
  colour.colour_tolerance = 10;
  const auto img = trace_image(dir.path("colour16.tif"), colour);
  EXPECT_EQ(img.rings.size(), reference.rings.size());
  EXPECT_NEAR(img.rings[0].area_pixels, reference.rings[0].area_pixels, 1.0);
}
