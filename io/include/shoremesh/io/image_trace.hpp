#pragma once
// Coastline images: water/land separation, cleaning, contour tracing with hierarchy, ring sampling.
//
// Reading. PNG, JPEG, TIFF (and PNM), 8 or 16 bits, grey or colour (an alpha channel is ignored). The size is
// read from the header first (OpenImageIO) and images over ImageTraceOptions::max_pixels are refused before
// any decoding.
//
// Water and land. Grey images: a threshold on the grey level, given (in the image's own range, 0..255 or
// 0..65535) or found by Otsu's method; the user says whether water is the light or the dark side. Map images
// where water has a colour: pixels within `colour_tolerance` (Euclidean RGB distance) of `water_colour`.
// A result that is all water or all land is an error (nothing to trace).
//
// Cleaning. Morphological opening then closing (elliptical kernels of the given radii; 0 = none), then every
// island (land inside water) and every water region smaller than `min_area` pixels is dropped and counted in
// TracedImage::dropped_small_islands / dropped_small_water — never silently. Islands at or above the minimum
// are all kept.
//
// Tracing. OpenCV's findContours with the full hierarchy on the land mask framed by one pixel of land:
// water regions are 4-connected and land 8-connected, so diagonal pixel contacts never pinch a water ring.
// Each ring is moved from the land pixel centres a quarter pixel toward the water, along the normal of the
// traced chain: a one-pixel channel or spit keeps half a pixel of width instead of collapsing, and the
// samples stay within a pixel of the true shoreline (Lake Superior mask: mean 0.24, max 0.76 pixel from the
// polygon it was rendered from). Roles: the outer boundary of a water region is a
// Shore ring, land inside it an Island ring, a pond on an island a Shore ring again (even-odd rule).
//
// Sampling rule. Points are placed along each ring at a spacing h(p) that is
//     h(p) = clamp(width_fraction * w(p), 1 pixel, spacing)
// where w(p) is the local width at p: twice the smaller of the water-side and the land-side half-widths,
// each the maximum of the distance transform (distance to the other side) found walking from p along the
// ring's normal into that side — the radius of the largest disc that fits in the channel or the island
// there. With the default fraction 1/2, a channel or an island of width w gets points at most w/2 apart,
// so both its sides are resolved and a small island keeps at least 2*pi ~ 6 points. h is then graded along
// the ring (|dh/ds| <= 1/2) and the samples are placed at equal steps of the integral of 1/h, so every ring
// stays closed with a smooth spacing. `spacing` is in pixels or, with SpacingUnit::Map, in the output units
// (metres for projected or metric images).
//
// Open water. Ring points beyond the outermost pixel centres, where the water reaches the image's edge,
// are InputSet::open_points: an open boundary in fort.14.
//
// Georeferencing (georeference.hpp): world file + .prj, GeoTIFF tags, or a user box; geographic images are
// projected to metres (Projection, kept in the result); otherwise pixel units, said plainly in the notes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shoremesh/io/georeference.hpp"
#include "shoremesh/io/input_set.hpp"
#include "shoremesh/io/projection.hpp"

namespace shoremesh::io {

enum class WaterSide { Light, Dark, Colour };

struct ImageTraceOptions {
  WaterSide water = WaterSide::Light;
  std::optional<double> threshold;          // grey level; none: Otsu. Water is > threshold (Light) or <= (Dark)
  std::array<int, 3> water_colour{0, 0, 255};  // RGB, for WaterSide::Colour
  double colour_tolerance = 40;             // Euclidean distance in RGB (0..441)
  int open_radius = 0;                      // morphological opening (removes specks of water), pixels
  int close_radius = 0;                     // morphological closing (removes specks of land), pixels
  double min_area = 16;                     // pixels; islands and water regions below are dropped (>= 3)
  bool largest_water_only = false;          // keep only the largest water region and its islands (no ponds)
  enum class SpacingUnit { Pixels, Map };
  double spacing = 4;                       // largest sample spacing along rings
  SpacingUnit spacing_unit = SpacingUnit::Pixels;
  double width_fraction = 0.5;              // spacing <= width_fraction * local width
  // Refuse larger images (width*height) before decoding. Working memory is about 12 bytes per pixel plus the
  // decoded image (1-8 bytes per pixel): about 1 GB at the default of 50 million pixels (7000 x 7000).
  std::size_t max_pixels = 50'000'000;
  GeoreferenceOptions georeference;         // user box / coordinate system
  std::optional<Projection> projection;     // for geographic images; none: chosen from the image's extent
  ProjectionChoice projection_choice = ProjectionChoice::LocalTransverseMercator;
};

// A water mask in memory: water[row * width + col] != 0 is water (for tests and callers with their own raster).
struct WaterMask {
  int width = 0, height = 0;
  std::vector<std::uint8_t> water;
};

struct TracedRing {
  RingRole role = RingRole::Shore;
  int parent = -1;                  // index of the enclosing ring in TracedImage::rings, -1 for outer shores
  int depth = 0;                    // 0 outer shore, 1 island, 2 pond, ...
  double area_pixels = 0;           // pixels enclosed by the ring's pixel edges (holes not subtracted)
  std::vector<Point2> dense_pixels; // the traced ring on pixel edges, (col, row) with (0, 0) the centre of the
                                    // upper-left pixel, before sampling
  std::vector<Point2> pixels;       // the samples, same pixel coordinates
  std::vector<Point2> points;       // the samples in output units (metres, map units or pixel units)
};

struct TracedImage {
  std::string file;
  int width = 0, height = 0, channels = 0, bits = 0;
  double threshold = 0;              // the grey threshold used (WaterSide::Light/Dark)
  Georeference georeference;
  std::size_t dropped_small_islands = 0;  // islands smaller than min_area
  std::size_t dropped_small_water = 0;    // water regions (lakes, ponds) smaller than min_area
  std::size_t dropped_other_water = 0;    // water regions dropped by largest_water_only (with their islands)
  std::vector<TracedRing> rings;          // shores before their islands, parents before children
  InputSet input;                         // the rings as an InputSet (units, projection, notes)
};

// Reads, separates, cleans, traces and samples an image. Errors (shoremesh::InputError naming the file): not
// an image / cannot decode, too large, unsupported sample type, all water or all land, nothing left above the
// minimum area.
TracedImage trace_image(const std::string& path, const ImageTraceOptions& options = {});

// The same from a water mask in memory, with an explicit georeference (pixel units when none).
TracedImage trace_water_mask(const WaterMask& mask, const ImageTraceOptions& options = {},
                             const std::optional<Georeference>& georeference = std::nullopt,
                             const std::string& name = "<mask>");

}  // namespace shoremesh::io
