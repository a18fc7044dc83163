#pragma once
// Digital elevation models (topography and bathymetry rasters) through GDAL: any single-band raster GDAL
// reads (GeoTIFF, NetCDF, ESRI ASCII grid, ...), heights positive up, with its geotransform, nodata and
// coordinate system.
//
// Nodata. Cells equal to the band's nodata value (or NaN) are filled from their neighbours, wave by wave:
// each wave gives every empty cell with filled 8-neighbours their mean. The count of filled cells is kept
// and said in the notes. A raster with no data at all is an error.
//
// Coastline. trace_dem() traces the contour at `level` (water strictly below it) with the image tracer
// (image_trace.hpp): islands, --min-area, sampling, projection and the open boundary where the water
// reaches the raster's edge (InputSet::open_points) as for images.
//
// Coordinates (georeference.hpp, the projection rule of projection.hpp): a geographic DEM is projected like
// lon/lat images; a projected one (UTM, a national grid) keeps its system where its scale stays within
// 0.1 % of 1 over the DEM, otherwise (Web Mercator, UTM across zones) it is reprojected through lon/lat
// (GDAL/PROJ) to a transverse Mercator centred on the data, so that lengths and --spacing are true metres.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "shoremesh/io/image_trace.hpp"
#include "shoremesh/io/input_set.hpp"
#include "shoremesh/io/projection.hpp"
#include "shoremesh/point.hpp"
#include "shoremesh/terrain.hpp"

namespace shoremesh::io {

struct Dem {
  std::string file;
  int width = 0, height = 0;
  // GDAL's geotransform: X = g[0] + col * g[1] + row * g[2], Y = g[3] + col * g[4] + row * g[5], where
  // (col, row) = (0, 0) is the upper-left corner of the upper-left cell.
  std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};
  std::vector<float> heights;     // row-major, nodata filled
  std::size_t nodata_cells = 0;   // cells that held nodata (filled)
  std::vector<std::uint8_t> valid;  // per cell, 0 where it held nodata; empty when none did
  double min = 0, max = 0;        // over the cells that held data
  std::string crs_wkt;            // empty: the raster has no coordinate system
  std::string crs_name;           // "WGS 84 / Pseudo-Mercator", ...
  bool geographic = false;        // lon/lat degrees on WGS 84 (or a datum within a metre of it)

  float at(int col, int row) const { return heights[static_cast<std::size_t>(row) * width + col]; }
  // Map coordinates of a point given in cell units with (0, 0) the centre of the upper-left cell.
  Point2 cell_to_map(double col, double row) const;
  // The inverse: map coordinates to cell units (centre convention).
  Point2 map_to_cell(const Point2& xy) const;
  // Bilinear interpolation between cell centres (clamped to the outermost centres).
  double bilinear(double col, double row) const;
};

// Reads band 1 of a raster. InputError naming the file: not a raster GDAL reads (unknown format, truncated),
// more than `max_cells` cells, no geotransform (pixel units are meaningless for a DEM), rotated grids, or
// no data at all.
Dem read_dem(const std::string& path, std::size_t max_cells = 200'000'000);

// A DEM as the terrain mesher's grid (terrain.hpp): its samples in the plane where the angles are measured,
// and the way from that plane to lon/lat. A projected DEM keeps its map coordinates (metres; a conformal
// projection such as UTM or Web Mercator keeps angles); a geographic one is taken to metres by an
// equirectangular map about its centre (conformal there; its scale errs by under 0.1 % within 2.5 degrees
// of latitude of it). to_lonlat is empty when the DEM has no coordinate system.
struct DemGrid {
  HeightGrid grid;
  std::function<Point2(const Point2&)> to_lonlat;
  bool metres = false;  // false: the DEM's map units (no coordinate system, or one PROJ calls local)
};
DemGrid dem_grid(const Dem& dem);

// From the mesh's coordinates to a DEM's cells: mesh metres -> (projection's lon/lat) -> DEM CRS -> cells.
// Without a mesh projection the mesh is taken to be in the DEM's own coordinates.
class DemFrame {
 public:
  DemFrame(std::shared_ptr<const Dem> dem, const Projection& mesh_projection);
  ~DemFrame();
  DemFrame(DemFrame&&) noexcept;
  DemFrame& operator=(DemFrame&&) noexcept;
  const Dem& dem() const { return *dem_; }
  // Cell coordinates (centre convention) of a mesh point; InputError when PROJ cannot transform it.
  Point2 to_cell(const Point2& mesh_xy) const;

 private:
  struct Transform;
  std::shared_ptr<const Dem> dem_;
  Projection projection_;
  std::unique_ptr<Transform> transform_;
};

// Depths at mesh nodes, positive down (depth = -height), from a DEM: the mean of the DEM cells whose centre
// lies in the node's cell of the mesh (the part of each incident triangle nearer to the node than to the
// triangle's other corners, the node's Voronoi cell restricted to the mesh for well-shaped Delaunay
// triangles), or the bilinear value at the node where that cell holds no DEM cell centre. Heights above
// `max_height` are lowered to it: with --dem the mesh is the water below the shoreline level, so a shore node,
// whose bilinear value mixes in the land cells beside it (a fjord's walls), lies at the shoreline, and a
// dropped islet (under --min-area) is water at that level. Then every depth is at least `min_depth` when
// given. Nodes are indices into `points`; `triangles` are the mesh's elements.
struct DepthOptions {
  std::optional<double> max_height;
  std::optional<double> min_depth;
};
std::vector<double> node_depths(const DemFrame& frame, std::span<const Point2> points,
                                std::span<const std::array<std::uint32_t, 3>> triangles,
                                const DepthOptions& options = {});

class Soundings;  // soundings.hpp

// The depth source of a run: a DEM in the frame of the mesh or soundings, and the clamp.
struct DepthSource {
  std::shared_ptr<const DemFrame> frame;
  std::shared_ptr<const Soundings> soundings;  // when there is no frame
  DepthOptions options;
};

struct DemTraceOptions {
  double level = 0;         // the shoreline: water strictly below this height
  ImageTraceOptions image;  // min_area, largest_water_only, spacing, projection as for images
};

struct TracedDem {
  std::shared_ptr<const Dem> dem;
  TracedImage traced;  // traced.input: the rings, with open_points set
};

TracedDem trace_dem(const std::string& path, const DemTraceOptions& options = {});
TracedDem trace_dem(std::shared_ptr<const Dem> dem, const DemTraceOptions& options = {});

}  // namespace shoremesh::io
