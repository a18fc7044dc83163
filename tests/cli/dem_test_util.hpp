#pragma once
// Writing small DEMs for tests with GDAL, and reading fort.14 as the ADCIRC manual describes it.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace shoremesh::cli_test {

// A raster's first band read with GDAL itself (the tests' independent reading, not io::read_dem): its size,
// geotransform `g`, heights row-major and spatial reference.
struct RasterBand {
  int w = 0, h = 0;
  double g[6]{};
  std::vector<float> z;
  OGRSpatialReference srs;
  explicit RasterBand(const std::string& path) {
    GDALAllRegister();
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
    if (!ds) throw std::runtime_error("cannot open " + path);
    w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
    ds->GetGeoTransform(g);
    z.resize(static_cast<std::size_t>(w) * h);
    if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, z.data(), w, h, GDT_Float32, 0, 0) != CE_None)
      throw std::runtime_error("cannot read " + path);
    if (const OGRSpatialReference* s = ds->GetSpatialRef()) srs = *s;
  }
  float at(int c, int r) const { return z[static_cast<std::size_t>(r) * w + c]; }
};

// A small GeoTIFF in EPSG:`epsg` (by default 32610, UTM 10N, metres) with the given heights, row-major, north
// up, and GDAL's geotransform `g` (upper-left corner, cell sizes).
inline void write_dem(const std::filesystem::path& path, int w, int h, const std::vector<float>& z,
                      std::optional<double> nodata = {}, std::array<double, 6> g = {400000, 1000, 0, 5400000, 0, -1000},
                      int epsg = 32610) {
  GDALAllRegister();
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  std::unique_ptr<GDALDataset> ds(drv->Create(path.c_str(), w, h, 1, GDT_Float32, nullptr));
  ds->SetGeoTransform(g.data());
  OGRSpatialReference srs;
  srs.importFromEPSG(epsg);
  ds->SetSpatialRef(&srs);
  if (nodata) ds->GetRasterBand(1)->SetNoDataValue(*nodata);
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, const_cast<float*>(z.data()), w, h, GDT_Float32, 0, 0),
            CE_None);
}

// fort.14 as the ADCIRC manual lays it out: AGRID; NE NP; NP lines JN X Y DP; NE lines JE NHY NM1 NM2 NM3;
// NOPE; NETA; per open segment NVDLL IBTYPEE then NVDLL node lines; NBOU; NVEL; per land segment NVELL
// IBTYPE then NVELL node lines. Anything after '!' on a line is a comment here.
struct Fort14 {
  struct Node {
    double x, y, depth;
  };
  std::map<long, Node> nodes;
  std::vector<std::array<long, 3>> triangles;
  struct Segment {
    int type;
    std::vector<long> nodes;
  };
  std::vector<Segment> open, land;
  long neta = 0, nvel = 0;
};

inline Fort14 parse_fort14(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  auto next = [&]() {
    if (!std::getline(in, line)) throw std::runtime_error("fort.14 ends early");
    std::istringstream words(line.substr(0, line.find('!')));
    return words.str();
  };
  Fort14 f;
  next();  // AGRID
  long ne = 0, np = 0;
  std::istringstream(next()) >> ne >> np;
  for (long i = 0; i < np; ++i) {
    long jn;
    Fort14::Node n{};
    std::istringstream(next()) >> jn >> n.x >> n.y >> n.depth;
    f.nodes[jn] = n;
  }
  for (long i = 0; i < ne; ++i) {
    long je, nhy;
    std::array<long, 3> t{};
    std::istringstream(next()) >> je >> nhy >> t[0] >> t[1] >> t[2];
    EXPECT_EQ(nhy, 3);
    f.triangles.push_back(t);
  }
  auto segments = [&](std::vector<Fort14::Segment>& out, long& total) {
    long count = 0;
    std::istringstream(next()) >> count;
    std::istringstream(next()) >> total;
    for (long k = 0; k < count; ++k) {
      long n = 0;
      Fort14::Segment s{};
      std::istringstream(next()) >> n >> s.type;
      for (long j = 0; j < n; ++j) {
        long node = 0;
        std::istringstream(next()) >> node;
        s.nodes.push_back(node);
      }
      out.push_back(s);
    }
  };
  segments(f.open, f.neta);
  segments(f.land, f.nvel);
  return f;
}

// Every boundary edge (used by one triangle) is listed once, in an open or a land segment.
inline void expect_boundary_listed_once(const Fort14& f) {
  std::map<std::pair<long, long>, int> uses, listed;
  for (const auto& t : f.triangles)
    for (int k = 0; k < 3; ++k) ++uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  long neta = 0, nvel = 0;
  for (const auto* list : {&f.open, &f.land})
    for (const auto& seg : *list) {
      (list == &f.open ? neta : nvel) += static_cast<long>(seg.nodes.size());
      for (std::size_t j = 0; j + 1 < seg.nodes.size(); ++j)
        ++listed[{std::min(seg.nodes[j], seg.nodes[j + 1]), std::max(seg.nodes[j], seg.nodes[j + 1])}];
    }
  EXPECT_EQ(neta, f.neta);
  EXPECT_EQ(nvel, f.nvel);
  for (const auto& [edge, n] : uses) {
    if (n == 1) {
      EXPECT_EQ(listed[edge], 1) << "boundary edge " << edge.first << "-" << edge.second;
    }
  }
  for (const auto& [edge, n] : listed) EXPECT_EQ(uses[edge], 1) << "listed edge is not a boundary edge";
}

}  // namespace shoremesh::cli_test
