// The image tracer (image_trace.hpp) on OpenCV, with OpenImageIO reading the size first: everything but the
// final ring check, which image_trace.cpp in io/src/input adds (raster_module.hpp).
#include "shoremesh/io/image_trace.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "../input/input_builder.hpp"
#include "raster_module.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/domain.hpp"

namespace shoremesh::io {

namespace {

// Ring vertices sit this far (pixels) from the land pixel centres toward the water: a quarter pixel keeps a
// one-pixel channel (or spit) half a pixel wide instead of collapsing it, and stays within a pixel of the
// true shoreline.
constexpr double kEdgeOffset = 0.25;

// Otsu's threshold on a histogram: the level t maximising the between-class variance of {<= t} and {> t}.
double otsu(const std::vector<double>& hist) {
  double total = 0, sum = 0;
  for (std::size_t i = 0; i < hist.size(); ++i) total += hist[i], sum += static_cast<double>(i) * hist[i];
  double w0 = 0, sum0 = 0, best = -1, best_t = 0;
  for (std::size_t t = 0; t + 1 < hist.size(); ++t) {
    w0 += hist[t];
    sum0 += static_cast<double>(t) * hist[t];
    const double w1 = total - w0;
    if (w0 == 0 || w1 == 0) continue;
    const double m0 = sum0 / w0, m1 = (sum - sum0) / w1;
    const double between = w0 * w1 * (m0 - m1) * (m0 - m1);
    if (between > best) best = between, best_t = static_cast<double>(t);
  }
  return best_t;
}

struct Output {
  PixelToMap affine;
  CoordinateSystem::Kind crs = CoordinateSystem::Kind::Unknown;
  Projection source;      // the image's own projected system (UTM or another), if it has one
  Projection projection;  // output projection (None for pixel/map units)
  std::function<Point2(const Point2&)> map_to_lonlat;  // Georeference::map_to_lonlat
  // Map coordinates -> lon/lat (degrees), for a georeferenced image in any system.
  LonLat lonlat(const Point2& m) const {
    if (!source.is_none()) return source.reverse(m);
    if (map_to_lonlat) {
      const Point2 ll = map_to_lonlat(m);
      return {ll[0], ll[1]};
    }
    return {m[0], m[1]};
  }
  Point2 operator()(const Point2& px) const {
    const Point2 m = affine(px);
    if (projection.is_none() || (!source.is_none() && source == projection)) return m;
    return projection.forward(lonlat(m));
  }
  // Output length of one pixel near px: square root of the Jacobian's determinant.
  double scale(const Point2& px) const {
    const Point2 o = (*this)(px), ox = (*this)(Point2{px[0] + 1, px[1]}), oy = (*this)(Point2{px[0], px[1] + 1});
    return std::sqrt(std::abs((ox[0] - o[0]) * (oy[1] - o[1]) - (ox[1] - o[1]) * (oy[0] - o[0])));
  }
};

double signed_area(const std::vector<Point2>& r) {
  double a = 0;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) a += r[j][0] * r[i][1] - r[i][0] * r[j][1];
  return a / 2;
}

// Ring on the water side of a chain of land pixel centres; `water_inside`: the chain encloses water (a hole of
// the land), otherwise water is outside (an island).
std::vector<Point2> offset_chain(const std::vector<cv::Point>& chain, bool water_inside, std::vector<Point2>& normals) {
  std::vector<Point2> out;
  normals.clear();
  const std::size_t n = chain.size();
  if (n < 3) {
    // One- or two-pixel features: the convex outline of their pixel squares.
    std::vector<cv::Point2f> corners, hull;
    for (const auto& p : chain)
      for (int dx : {-1, 1})
        for (int dy : {-1, 1}) corners.emplace_back(p.x + 0.5f * dx, p.y + 0.5f * dy);
    cv::convexHull(corners, hull);
    const double cx = chain.size() == 1 ? chain[0].x : 0.5 * (chain[0].x + chain[1].x);
    const double cy = chain.size() == 1 ? chain[0].y : 0.5 * (chain[0].y + chain[1].y);
    for (const auto& h : hull) {
      out.push_back({h.x, h.y});
      const double dx = h.x - cx, dy = h.y - cy, len = std::hypot(dx, dy);
      const double s = water_inside ? -1 : 1;
      normals.push_back({s * dx / len, s * dy / len});
    }
    return out;
  }
  std::vector<Point2> pts(n);
  for (std::size_t i = 0; i < n; ++i) pts[i] = {static_cast<double>(chain[i].x), static_cast<double>(chain[i].y)};
  const bool ccw = signed_area(pts) > 0;  // interior to the left of the direction of travel
  const double side = (ccw == water_inside) ? 1.0 : -1.0;  // +1: water on the left
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& prev = pts[(i + n - 1) % n];
    const Point2& next = pts[(i + 1) % n];
    double tx = next[0] - prev[0], ty = next[1] - prev[1];
    Point2 normal;
    if (tx == 0 && ty == 0) {
      // The tip of a one-pixel spit (the chain turns back): water lies straight ahead.
      const double dx = pts[i][0] - prev[0], dy = pts[i][1] - prev[1], len = std::hypot(dx, dy);
      normal = {dx / len, dy / len};
    } else {
      const double len = std::hypot(tx, ty);
      tx /= len, ty /= len;
      normal = {-ty * side, tx * side};  // left normal times side
    }
    normals.push_back(normal);
    out.push_back({pts[i][0] + kEdgeOffset * normal[0], pts[i][1] + kEdgeOffset * normal[1]});
  }
  return out;
}

// Area in pixels enclosed by the pixel edges around a ring: rings from chains of three or more pixel centres
// lie kEdgeOffset inside the edges (islands) or outside them (water), so half a perimeter strip of that
// width is added or removed (exact for axis-aligned rectangles up to 1/4 pixel); small features' rings are
// their pixel edges already.
double pixel_area(const std::vector<Point2>& ring, std::size_t chain_size, bool water_inside) {
  const double a = std::abs(signed_area(ring));
  if (chain_size < 3) return a;
  double perimeter = 0;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    perimeter += std::hypot(ring[i][0] - ring[j][0], ring[i][1] - ring[j][1]);
  const double offset = 0.5 - kEdgeOffset;
  return std::max(0.0, water_inside ? a - offset * perimeter : a + offset * perimeter);
}

// Half-width (pixels) of the region `dist` belongs to, walking from p along dir until past the ridge of the
// distance transform (or `limit` pixels). dist is framed by one pixel (index = pixel + 1). Land beyond the image
// edge is unknown, not narrow: a walk that leaves the image returns `limit`.
double half_width(const cv::Mat& dist, const Point2& p, const Point2& dir, double limit) {
  double best = 0;
  for (double t = 0.5; t <= limit; t += 0.5) {
    const int col = static_cast<int>(std::lround(p[0] + t * dir[0])) + 1;
    const int row = static_cast<int>(std::lround(p[1] + t * dir[1])) + 1;
    if (col < 0 || row < 0 || col >= dist.cols || row >= dist.rows) return std::max(best, limit);  // beyond the image
    const float d = dist.at<float>(row, col);
    if (d == 0) {
      if (t > 1.0) break;  // left the region
      continue;
    }
    if (d > best) best = d;
    else if (d < best - 1.0) break;  // past the ridge
  }
  return best;
}

struct Contour {
  int cv_index = -1;
  int parent = -1;  // in `kept` order
  int depth = 0;
  double area = 0;
  std::vector<Point2> dense;
  std::vector<Point2> normals;  // toward the water
};

// Samples a closed ring at the spacing h(p) of the header's rule. Returns samples in pixel and output units.
void sample_ring(const Contour& c, const Output& out, const cv::Mat& dist_water, const cv::Mat& dist_land,
                 const ImageTraceOptions& opt, std::vector<Point2>& pixels, std::vector<Point2>& points) {
  const std::size_t n = c.dense.size();
  std::vector<Point2> o(n);
  std::vector<double> h(n);
  const double px_limit = opt.spacing_unit == ImageTraceOptions::SpacingUnit::Pixels
                              ? opt.spacing / opt.width_fraction
                              : 1e9;  // refined below per point
  for (std::size_t i = 0; i < n; ++i) {
    o[i] = out(c.dense[i]);
    const double s = out.scale(c.dense[i]);
    const double spacing = opt.spacing_unit == ImageTraceOptions::SpacingUnit::Pixels ? opt.spacing * s : opt.spacing;
    const double limit = std::min(px_limit, spacing / s / opt.width_fraction) / 2 + 2;
    const Point2 back{-c.normals[i][0], -c.normals[i][1]};
    const double rw = half_width(dist_water, c.dense[i], c.normals[i], limit);
    const double rl = half_width(dist_land, c.dense[i], back, limit);
    const double width_px = std::max(1.0, 2 * std::min(rw, rl) - 1);
    h[i] = std::max(s, std::min(spacing, opt.width_fraction * width_px * s));
  }
  std::vector<double> seg(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& a = o[i];
    const Point2& b = o[(i + 1) % n];
    seg[i] = std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  // Grading: |dh/ds| <= 1/2 around the ring (two cyclic passes each way).
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 1; k <= n; ++k) h[k % n] = std::min(h[k % n], h[k - 1] + 0.5 * seg[k - 1]);
    for (std::size_t k = n; k >= 1; --k) h[k - 1] = std::min(h[k - 1], h[k % n] + 0.5 * seg[k - 1]);
  }
  std::vector<double> integral(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) integral[i + 1] = integral[i] + seg[i] * 0.5 * (1 / h[i] + 1 / h[(i + 1) % n]);
  const double total = integral[n];
  const std::size_t count = std::max<std::size_t>(4, static_cast<std::size_t>(std::lround(total)));
  pixels.clear();
  points.clear();
  std::size_t i = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const double target = total * static_cast<double>(k) / static_cast<double>(count);
    while (i + 1 < n && integral[i + 1] <= target) ++i;
    const double span = integral[i + 1] - integral[i];
    const double t = span > 0 ? (target - integral[i]) / span : 0;
    const Point2& a = c.dense[i];
    const Point2& b = c.dense[(i + 1) % n];
    const Point2 pp{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
    const Point2 op = out(pp);
    if (!points.empty() && (op == points.back() || op == points.front())) continue;
    pixels.push_back(pp);
    points.push_back(op);
  }
}

Output make_output(const Georeference& g, const cv::Size& size, const ImageTraceOptions& opt, const std::string& name,
                   InputSet& set) {
  Output out;
  out.affine = g.pixel_to_map;
  out.crs = g.crs.kind;
  set.notes.push_back("georeference: " + g.description);
  if (g.source == Georeference::Source::None) {
    set.units = Units::Pixels;
    out.crs = CoordinateSystem::Kind::Unknown;
    return out;
  }
  out.map_to_lonlat = g.map_to_lonlat;
  if (g.crs.kind == CoordinateSystem::Kind::Unknown && !g.map_to_lonlat) {
    set.units = Units::MapUnits;
    return out;
  }
  set.units = Units::Metres;
  if (g.crs.kind == CoordinateSystem::Kind::Utm) out.source = Projection::utm_ups(g.crs.zone, g.crs.north);
  if (g.crs.kind == CoordinateSystem::Kind::Other && g.crs.projected) out.source = Projection::crs(g.crs.wkt, g.crs.name, name);
  if (opt.projection && !opt.projection->is_none()) {
    out.projection = *opt.projection;
    set.notes.push_back("projected to metres with " + out.projection.describe());
  } else {
    // The image's outer edges and inside, in lon/lat: the extent the projection rule measures.
    std::vector<LonLat> extent;
    constexpr int kSteps = 8;
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; j <= kSteps; ++j) {
        const double c = -0.5 + size.width * double(i) / kSteps, r = -0.5 + size.height * double(j) / kSteps;
        try {
          extent.push_back(out.lonlat(g.pixel_to_map(c, r)));
        } catch (const std::domain_error&) {
          throw InputError("PROJ cannot take the image's point (" + std::to_string(c) + ", " + std::to_string(r) +
                               ") to lon/lat",
                           name);
        }
      }
    ChosenProjection chosen = choose_projection(out.source.is_none() ? std::nullopt : std::optional(out.source), extent,
                                                opt.projection_choice, name);
    out.projection = chosen.projection;
    set.notes.push_back(chosen.note);
  }
  set.projection = out.projection;
  return out;
}

TracedImage trace_mask(cv::Mat water, const ImageTraceOptions& opt, const Georeference& georef, TracedImage result) {
  const std::string& name = result.file;
  if (!(opt.spacing > 0) || !(opt.width_fraction > 0) || !(opt.min_area >= 0))
    throw InputError("image tracing needs spacing > 0, width_fraction > 0 and min_area >= 0", name);
  const double min_area = std::max(opt.min_area, 3.0);
  auto check_mixed = [&](const char* when) {
    const int n_water = cv::countNonZero(water);
    if (n_water == 0) throw InputError(std::string("all land: no water in the image") + when, name);
    if (n_water == water.rows * water.cols) throw InputError(std::string("all water: no shoreline in the image") + when, name);
  };
  check_mixed("");
  if (opt.open_radius > 0)
    cv::morphologyEx(water, water, cv::MORPH_OPEN,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * opt.open_radius + 1, 2 * opt.open_radius + 1)));
  if (opt.close_radius > 0)
    cv::morphologyEx(water, water, cv::MORPH_CLOSE,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * opt.close_radius + 1, 2 * opt.close_radius + 1)));
  check_mixed(" after cleaning");

  // Land framed by one pixel of land: water regions are its holes (4-connected), islands its nested parts.
  cv::Mat land = 255 - water, framed_land, framed_water;
  cv::copyMakeBorder(land, framed_land, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(255));
  cv::copyMakeBorder(water, framed_water, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::Mat dist_water, dist_land;
  cv::distanceTransform(framed_water, dist_water, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::distanceTransform(framed_land, dist_land, cv::DIST_L2, cv::DIST_MASK_PRECISE);

  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(framed_land, contours, hierarchy, cv::RETR_TREE, cv::CHAIN_APPROX_NONE);
  // Depth in the tree; the frame's outer contour is the root (depth -1 here), water regions are depth 0.
  std::vector<int> depth(contours.size(), -2);
  for (std::size_t i = 0; i < contours.size(); ++i) {
    int d = -1;
    for (int p = hierarchy[i][3]; p >= 0; p = hierarchy[p][3]) ++d;
    depth[i] = d;
  }
  // Visit parents before children (breadth-first by depth), dropping small features with their subtrees.
  std::vector<int> order;
  for (std::size_t i = 0; i < contours.size(); ++i)
    if (depth[i] >= 0) order.push_back(static_cast<int>(i));
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return depth[a] < depth[b]; });
  std::vector<int> kept_index(contours.size(), -1);
  std::vector<Contour> kept;
  for (int i : order) {
    const int parent_cv = hierarchy[i][3];
    int parent = -1;
    if (depth[i] > 0) {
      parent = kept_index[parent_cv];
      if (parent < 0) continue;  // inside a dropped feature
    }
    Contour c;
    c.cv_index = i;
    c.parent = parent;
    c.depth = depth[i];
    std::vector<cv::Point> chain = contours[i];
    for (auto& p : chain) p -= cv::Point(1, 1);  // frame -> image pixel indices
    const bool water_inside = depth[i] % 2 == 0;
    c.dense = offset_chain(chain, water_inside, c.normals);
    c.area = pixel_area(c.dense, chain.size(), water_inside);
    if (c.area < min_area) {
      (water_inside ? result.dropped_small_water : result.dropped_small_islands)++;
      continue;
    }
    kept_index[i] = static_cast<int>(kept.size());
    kept.push_back(std::move(c));
  }
  if (opt.largest_water_only) {
    int best = -1;
    for (std::size_t k = 0; k < kept.size(); ++k)
      if (kept[k].depth == 0 && (best < 0 || kept[k].area > kept[best].area)) best = static_cast<int>(k);
    std::vector<int> remap(kept.size(), -1);
    std::vector<Contour> filtered;
    for (std::size_t k = 0; k < kept.size(); ++k) {
      // One connected body of water: the largest lake and its islands. A pond on an island (depth 2) is
      // water of its own, so it goes with whatever lies in it.
      const bool keep = kept[k].depth == 0 ? static_cast<int>(k) == best
                                           : kept[k].depth == 1 && remap[kept[k].parent] >= 0;
      if (!keep) {
        if (kept[k].depth % 2 == 0 && (kept[k].depth == 0 || remap[kept[k].parent] >= 0)) ++result.dropped_other_water;
        continue;
      }
      remap[k] = static_cast<int>(filtered.size());
      filtered.push_back(std::move(kept[k]));
      if (filtered.back().parent >= 0) filtered.back().parent = remap[filtered.back().parent];
    }
    kept = std::move(filtered);
  }
  if (kept.empty())
    throw InputError("no water region of at least " + readable(min_area) + " pixels (min_area) in the image", name);

  InputSet& set = result.input;
  const Output out = make_output(georef, water.size(), opt, name, set);
  detail::InputBuilder builder(set, name, Source::Location::None);
  for (const Contour& c : kept) {
    TracedRing ring;
    ring.role = c.depth % 2 == 0 ? RingRole::Shore : RingRole::Island;
    ring.parent = c.parent;
    ring.depth = c.depth;
    ring.area_pixels = c.area;
    ring.dense_pixels = c.dense;
    try {
      sample_ring(c, out, dist_water, dist_land, opt, ring.pixels, ring.points);
    } catch (const std::domain_error& e) {
      throw InputError(std::string("cannot project the image: ") + e.what(), name);
    }
    builder.add_ring(ring.points, ring.role);
    result.rings.push_back(std::move(ring));
  }
  result.georeference = georef;
  set.dropped_small_islands = result.dropped_small_islands;
  // Ring points beyond the outermost pixel centres: the ring runs along the land frame there (0.75 pixel
  // outside them), cuts a corner of the image between two frame stretches, or is where the shore meets the
  // edge. The water leaves the data there: an open boundary.
  const double last_col = water.cols - 1, last_row = water.rows - 1;
  for (const TracedRing& ring : result.rings)
    for (std::size_t k = 0; k < ring.pixels.size(); ++k) {
      const Point2& px = ring.pixels[k];
      if (px[0] < 0 || px[1] < 0 || px[0] > last_col || px[1] > last_row) set.open_points.push_back(ring.points[k]);
    }
  std::sort(set.open_points.begin(), set.open_points.end());
  if (!set.open_points.empty())
    set.notes.push_back(std::to_string(set.open_points.size()) +
                        " shore points where the water reaches the edge of the image: an open boundary");
  std::size_t islands = 0;
  for (const auto& r : result.rings) islands += r.role == RingRole::Island;
  set.notes.push_back("traced " + std::to_string(result.rings.size()) + " rings (" + std::to_string(islands) +
                      " islands); dropped " + std::to_string(result.dropped_small_islands) + " islands and " +
                      std::to_string(result.dropped_small_water) + " water regions smaller than " +
                      std::to_string(static_cast<long>(min_area)) + " pixels" +
                      (opt.largest_water_only ? ", and " + std::to_string(result.dropped_other_water) +
                                                    " water regions other than the largest"
                                              : std::string()));
  return result;
}

}  // namespace

TracedImage detail::trace_water_mask_unchecked(const WaterMask& mask, const ImageTraceOptions& options,
                                               const std::optional<Georeference>& georeference,
                                               const std::string& name) {
  if (mask.width <= 0 || mask.height <= 0 ||
      mask.water.size() != static_cast<std::size_t>(mask.width) * static_cast<std::size_t>(mask.height))
    throw InputError("water mask size does not match width x height", name);
  cv::Mat water(mask.height, mask.width, CV_8U);
  for (int r = 0; r < mask.height; ++r)
    for (int c = 0; c < mask.width; ++c)
      water.at<std::uint8_t>(r, c) = mask.water[static_cast<std::size_t>(r) * mask.width + c] ? 255 : 0;
  TracedImage result;
  result.file = name;
  result.width = mask.width;
  result.height = mask.height;
  result.channels = 1;
  result.bits = 1;
  Georeference g;
  if (georeference) {
    g = *georeference;
  } else {
    g.pixel_to_map = {1, 0, 0.5, 0, -1, mask.height - 0.5};
    g.description = "no georeference: coordinates are pixels";
  }
  return trace_mask(water, options, g, std::move(result));
}

namespace {
// libjpeg decodes a JPEG cut short with only a warning ("Premature end of JPEG file") and fills the missing
// rows with grey, which would become a rectangular lake. A whole JPEG ends with the end-of-image marker
// FF D9 (ITU T.81, B.2.1), perhaps followed by padding.
void refuse_cut_jpeg(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[3] = {0, 0, 0};
  if (!in.read(reinterpret_cast<char*>(magic), 3) || magic[0] != 0xFF || magic[1] != 0xD8 || magic[2] != 0xFF) return;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 4096);
  std::string end(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(end.data(), tail);
  while (!end.empty() && (end.back() == '\0' || std::isspace(static_cast<unsigned char>(end.back())))) end.pop_back();
  if (end.size() < 2 || static_cast<unsigned char>(end[end.size() - 2]) != 0xFF ||
      static_cast<unsigned char>(end.back()) != 0xD9)
    throw InputError("the JPEG is cut short (it does not end with the end-of-image marker): the missing part would be "
                     "traced as water or land",
                     path);
}
}  // namespace

TracedImage detail::trace_image_unchecked(const std::string& path, const ImageTraceOptions& opt) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError("cannot open file", path);
  TracedImage result;
  result.file = path;
  {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError("not a readable image: " + OIIO::geterror(), path);
    const auto& spec = in->spec();
    const std::uint64_t pixels = static_cast<std::uint64_t>(std::max(spec.width, 0)) * static_cast<std::uint64_t>(std::max(spec.height, 0));
    if (pixels > opt.max_pixels)
      throw InputError("image too large: " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " = " +
                           std::to_string(pixels) + " pixels, more than the limit of " + std::to_string(opt.max_pixels) +
                           "; refused before decoding",
                       path);
    if (pixels == 0) throw InputError("image has no pixels", path);
    in->close();
  }
  refuse_cut_jpeg(path);
  cv::Mat img;
  try {
    img = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw InputError(std::string("cannot decode image: ") + e.what(), path);
  }
  if (img.empty()) throw InputError("cannot decode image (corrupt or unsupported)", path);
  if (img.depth() != CV_8U && img.depth() != CV_16U)
    throw InputError("unsupported sample type: only 8- and 16-bit images are read", path);
  result.width = img.cols;
  result.height = img.rows;
  result.channels = img.channels();
  result.bits = img.depth() == CV_8U ? 8 : 16;
  const double full = img.depth() == CV_8U ? 255.0 : 65535.0;
  // Colour channels in OpenCV order (B, G, R), alpha dropped.
  cv::Mat colour;
  if (img.channels() == 4) cv::cvtColor(img, colour, cv::COLOR_BGRA2BGR);
  else if (img.channels() == 3) colour = img;
  else if (img.channels() == 2) cv::extractChannel(img, colour, 0);
  else colour = img;
  cv::Mat water;
  // Per-pixel loops over the native samples: no floating-point copies of the image (memory stays near
  // the decoded image plus the one-byte mask).
  auto sample = [&](const cv::Mat& m, int r, int c, int ch) -> double {
    return m.depth() == CV_8U ? m.ptr<std::uint8_t>(r)[c * m.channels() + ch] : m.ptr<std::uint16_t>(r)[c * m.channels() + ch];
  };
  water = cv::Mat(colour.rows, colour.cols, CV_8U);
  if (opt.water == WaterSide::Colour) {
    const double scale = 255.0 / full, tol2 = opt.colour_tolerance * opt.colour_tolerance;
    const int cn = colour.channels();
    for (int r = 0; r < colour.rows; ++r)
      for (int c = 0; c < colour.cols; ++c) {
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {  // OpenCV order B, G, R; grey images count as equal channels
          const double v = sample(colour, r, c, cn == 3 ? k : 0) * scale - opt.water_colour[2 - k];
          d2 += v * v;
        }
        water.at<std::uint8_t>(r, c) = d2 <= tol2 ? 255 : 0;
      }
  } else {
    cv::Mat grey;
    if (colour.channels() == 3) cv::cvtColor(colour, grey, cv::COLOR_BGR2GRAY);
    else grey = colour;
    double t = 0;
    if (opt.threshold) {
      t = *opt.threshold;
    } else {
      std::vector<double> hist(static_cast<std::size_t>(full) + 1, 0.0);
      for (int r = 0; r < grey.rows; ++r)
        for (int c = 0; c < grey.cols; ++c) hist[static_cast<std::size_t>(sample(grey, r, c, 0))] += 1;
      std::size_t levels = 0;
      for (double v : hist) levels += v > 0;
      if (levels < 2)
        throw InputError("the image has a single grey level (" + std::to_string(static_cast<int>(sample(grey, 0, 0, 0))) +
                             "): all water or all land, no shoreline to trace",
                         path);
      t = otsu(hist);
    }
    result.threshold = t;
    const bool light = opt.water == WaterSide::Light;
    for (int r = 0; r < grey.rows; ++r)
      for (int c = 0; c < grey.cols; ++c) {
        const double v = sample(grey, r, c, 0);
        water.at<std::uint8_t>(r, c) = (light ? v > t : v <= t) ? 255 : 0;
      }
  }
  const Georeference g = find_georeference(path, img.cols, img.rows, opt.georeference);
  return trace_mask(water, opt, g, std::move(result));
}

}  // namespace shoremesh::io
