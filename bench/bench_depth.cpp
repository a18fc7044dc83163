// Depth sampling benchmark (issue 34): reading a DEM with GDAL and sampling depths onto mesh nodes.
//
//   bench_depth SALISH_TIF SCRATCH_DIR [--repeats K] [--superior MASK_PNG]
//
// 1. The Salish Sea sample (120 x 91 cells): GDAL read, then the depths of the mesh `mesh --dem` makes of
//    it (--min-area 1: traced, StableWS, clipped to the water), by cell means (node_depths) and, as the
//    peer in the same run, by bilinear interpolation at the nodes alone.
// 2. A DEM of 10^7 cells made here by resampling the sample bilinearly (3,636 x 2,751), written as a
//    GeoTIFF and read back with GDAL, sampled onto 10^6 nodes (a 1,000 x 1,000 jittered grid over its
//    extent, two triangles per grid cell), cell means and the bilinear peer.
// 3. With --superior samples/superior/superior_watermask_h.png: the Superior demo mesh (the README's:
//    --largest-water --spacing 4000) with depths from a DEM on the mask's own grid (1,700 x 600 cells of
//    0.005 degrees, EPSG:4326, written here as a GeoTIFF and read back). The shared data hold no Superior
//    bathymetry, so the heights are made up from the mask (water -100 m, land +100 m): what is timed
//    (the read, locating cell centres, PROJ for every node) does not depend on the values.
// Prints one line per measurement: medians over the repeats of wall seconds.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "shoremesh/io/dem.hpp"
#include "shoremesh/io/export.hpp"
#include "shoremesh/io/image_trace.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/well_spaced.hpp"

using namespace shoremesh;

namespace {

double median_seconds(int repeats, const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

std::vector<double> bilinear_only(const io::DemFrame& frame, std::span<const Point2> nodes) {
  std::vector<double> d;
  d.reserve(nodes.size());
  for (const Point2& p : nodes) {
    const Point2 c = frame.to_cell(p);
    d.push_back(-frame.dem().bilinear(c[0], c[1]));
  }
  return d;
}

// A one-band Float32 GeoTIFF in EPSG:`epsg` with GDAL's geotransform `g`; false when GDAL cannot write it.
bool write_geotiff(const std::string& path, int w, int h, std::vector<float>& z, std::array<double, 6> g, int epsg) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(
      GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), w, h, 1, GDT_Float32, nullptr));
  if (!ds) return false;
  ds->SetGeoTransform(g.data());
  OGRSpatialReference srs;
  srs.importFromEPSG(epsg);
  ds->SetSpatialRef(&srs);
  return ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, z.data(), w, h, GDT_Float32, 0, 0) == CE_None;
}

double checksum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_depth SALISH_TIF SCRATCH_DIR [--repeats K]\n");
    return 2;
  }
  const std::string salish = argv[1];
  const std::filesystem::path scratch = argv[2];
  int repeats = 5;
  std::string superior;
  for (int a = 3; a + 1 < argc; a += 2) {
    if (std::strcmp(argv[a], "--repeats") == 0) repeats = std::max(1, std::atoi(argv[a + 1]));
    else if (std::strcmp(argv[a], "--superior") == 0) superior = argv[a + 1];
    else return std::fprintf(stderr, "unknown option %s\n", argv[a]), 2;
  }
  std::filesystem::create_directories(scratch);

  // 1. Salish Sea.
  std::shared_ptr<const io::Dem> dem;
  const double read_s = median_seconds(repeats, [&] { dem = std::make_shared<const io::Dem>(io::read_dem(salish)); });
  io::DemTraceOptions trace;
  trace.image.min_area = 1;
  const io::TracedDem traced = io::trace_dem(dem, trace);
  const io::InputSet& set = traced.traced.input;
  const StableResult<2> ws = stable_well_spaced<2>(set.points);
  const Mesh<2> mesh(ws.points, ws.input_count, set.domain, ws.box);
  const io::MeshSnapshot<2> snapshot(mesh);
  const io::MeshView<2> view = snapshot.view();
  const io::DemFrame frame(dem, set.projection);
  io::DepthOptions options;
  options.max_height = 0;
  std::vector<double> means, bilinear;
  const double means_s = median_seconds(repeats, [&] { means = io::node_depths(frame, view.points, view.elements, options); });
  const double bil_s = median_seconds(repeats, [&] { bilinear = bilinear_only(frame, view.points); });
  std::printf("salish cells=%d nodes=%zu triangles=%zu read_s=%.6f cell_means_s=%.6f bilinear_s=%.6f ratio=%.2f sum=%.6g\n",
              dem->width * dem->height, view.points.size(), view.elements.size(), read_s, means_s, bil_s,
              means_s / bil_s, checksum(means));

  // 2. 10^7 cells onto 10^6 nodes, in the DEM's own coordinates (EPSG:3857 metres; no projection step).
  const int W = 3636, H = 2751;
  std::vector<float> big(static_cast<std::size_t>(W) * H);
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c)
      big[static_cast<std::size_t>(r) * W + c] = static_cast<float>(
          dem->bilinear((c + 0.5) * dem->width / W - 0.5, (r + 0.5) * dem->height / H - 0.5));
  const auto& g = dem->geotransform;
  std::array<double, 6> gbig{g[0], g[1] * dem->width / W, 0, g[3], 0, g[5] * dem->height / H};
  const std::string big_path = (scratch / "salish_1e7.tif").string();
  if (!write_geotiff(big_path, W, H, big, gbig, 3857)) return 1;
  std::shared_ptr<const io::Dem> big_dem;
  const double big_read_s = median_seconds(repeats, [&] { big_dem = std::make_shared<const io::Dem>(io::read_dem(big_path)); });
  const int N = 1000;
  std::vector<Point2> nodes;
  std::mt19937 rng(34);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  const double x0 = gbig[0], y0 = gbig[3] + gbig[5] * H, sx = gbig[1] * W / N, sy = -gbig[5] * H / N;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      const double ji = (i == 0 || i == N - 1) ? 0 : jitter(rng), jj = (j == 0 || j == N - 1) ? 0 : jitter(rng);
      nodes.push_back({x0 + (i + ji) * sx, y0 + (j + jj) * sy});
    }
  std::vector<Element<2>> triangles;
  for (int j = 0; j + 1 < N; ++j)
    for (int i = 0; i + 1 < N; ++i) {
      const auto v = static_cast<std::uint32_t>(j * N + i);
      triangles.push_back({v, v + 1, v + N + 1});
      triangles.push_back({v, v + N + 1, v + N});
    }
  const io::DemFrame big_frame(big_dem, io::Projection());
  const double big_means_s = median_seconds(repeats, [&] { means = io::node_depths(big_frame, nodes, triangles); });
  const double big_bil_s = median_seconds(repeats, [&] { bilinear = bilinear_only(big_frame, nodes); });
  std::printf("big cells=%d nodes=%zu triangles=%zu read_s=%.6f cell_means_s=%.6f bilinear_s=%.6f ratio=%.2f sum=%.6g\n",
              W * H, nodes.size(), triangles.size(), big_read_s, big_means_s, big_bil_s, big_means_s / big_bil_s,
              checksum(means));
  std::filesystem::remove(big_path);

  // 3. The Superior demo mesh, depths from a DEM on the mask's grid.
  if (!superior.empty()) {
    io::ImageTraceOptions o;
    o.largest_water_only = true;
    o.spacing = 4000;
    o.spacing_unit = io::ImageTraceOptions::SpacingUnit::Map;
    const io::InputSet sup = io::trace_image(superior, o).input;
    const StableResult<2> sws = stable_well_spaced<2>(sup.points);
    const Mesh<2> smesh(sws.points, sws.input_count, sup.domain, sws.box);
    const io::MeshSnapshot<2> ssnap(smesh);
    const io::MeshView<2> sview = ssnap.view();
    GDALAllRegister();
    std::unique_ptr<GDALDataset> mask(GDALDataset::Open(superior.c_str(), GDAL_OF_RASTER));
    if (!mask) return std::fprintf(stderr, "cannot read %s\n", superior.c_str()), 1;
    const int mw = mask->GetRasterXSize(), mh = mask->GetRasterYSize();
    std::vector<float> z(static_cast<std::size_t>(mw) * mh);
    if (mask->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, mw, mh, z.data(), mw, mh, GDT_Float32, 0, 0) != CE_None) return 1;
    for (float& v : z) v = v > 127 ? -100.0f : 100.0f;
    const std::string sup_path = (scratch / "superior_dem.tif").string();
    // The mask's world file, as a geotransform.
    if (!write_geotiff(sup_path, mw, mh, z, {-92.5, 0.005, 0, 49.2, 0, -0.005}, 4326)) return 1;
    std::shared_ptr<const io::Dem> sdem;
    const double sread_s = median_seconds(repeats, [&] { sdem = std::make_shared<const io::Dem>(io::read_dem(sup_path)); });
    const io::DemFrame sframe(sdem, sup.projection);
    const double smeans_s = median_seconds(repeats, [&] { means = io::node_depths(sframe, sview.points, sview.elements); });
    const double sbil_s = median_seconds(repeats, [&] { bilinear = bilinear_only(sframe, sview.points); });
    std::printf("superior cells=%d nodes=%zu triangles=%zu projection=\"%s\" read_s=%.6f cell_means_s=%.6f bilinear_s=%.6f "
                "ratio=%.2f sum=%.6g\n",
                mw * mh, sview.points.size(), sview.elements.size(), sup.projection.describe().c_str(), sread_s, smeans_s,
                sbil_s, smeans_s / sbil_s, checksum(means));
    std::filesystem::remove(sup_path);
  }
  return 0;
}
