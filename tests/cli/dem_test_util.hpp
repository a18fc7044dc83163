#pragma once
// Writing small DEMs for tests with GDAL.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

namespace shoremesh::cli_test {

// A small GeoTIFF in EPSG:32610 (UTM 10N, metres) with the given heights, row-major, north up, and GDAL's
// geotransform `g` (upper-left corner, cell sizes).
inline void write_dem(const std::filesystem::path& path, int w, int h, const std::vector<float>& z,
                      std::optional<double> nodata = {}, std::array<double, 6> g = {400000, 1000, 0, 5400000, 0, -1000}) {
  GDALAllRegister();
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  std::unique_ptr<GDALDataset> ds(drv->Create(path.c_str(), w, h, 1, GDT_Float32, nullptr));
  ds->SetGeoTransform(g.data());
  OGRSpatialReference srs;
  srs.importFromEPSG(32610);
  ds->SetSpatialRef(&srs);
  if (nodata) ds->GetRasterBand(1)->SetNoDataValue(*nodata);
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, const_cast<float*>(z.data()), w, h, GDT_Float32, 0, 0),
            CE_None);
}

}  // namespace shoremesh::cli_test
