// Coordinate systems through GDAL/OGR (PROJ underneath) for georeference.hpp and projection.hpp: parsing,
// transformations to lon/lat and GeoTIFF keys (raster_module.hpp).
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "../input/text_util.hpp"
#include "gdal_setup.hpp"
#include "raster_module.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/io/georeference.hpp"

namespace shoremesh::io {

namespace {

using detail::upper;

// WGS 84, NAD83 and ETRS89 agree within a metre: their lon/lat is taken as WGS 84's.
bool wgs84_like(const OGRSpatialReference& srs) {
  const char* datum = srs.GetAttrValue("DATUM");
  const std::string d = upper(datum ? datum : "");
  const char* code = srs.GetAuthorityCode("GEOGCS");
  const std::string c = code ? code : "";
  return c == "4326" || c == "4269" || c == "4258" || d.find("WGS_1984") != std::string::npos ||
         d.find("WGS 1984") != std::string::npos || d.find("WORLD GEODETIC SYSTEM 1984") != std::string::npos ||
         d.find("NORTH_AMERICAN_DATUM_1983") != std::string::npos || d.find("NORTH AMERICAN DATUM 1983") != std::string::npos ||
         d.find("EUROPEAN_TERRESTRIAL_REFERENCE_SYSTEM_1989") != std::string::npos ||
         d.find("EUROPEAN TERRESTRIAL REFERENCE SYSTEM 1989") != std::string::npos;
}

// The short forms PROJ does not read itself, as EPSG codes: "lonlat", "UTM 16N", "utm5s", "UTM zone 16 S".
std::optional<std::string> short_form(const std::string& text, const std::string& file) {
  const std::string up = upper(text);
  if (up == "LONLAT" || up == "LON/LAT" || up == "WGS 84" || up == "CRS84") return std::string("EPSG:4326");
  if (up.rfind("UTM", 0) != 0) return std::nullopt;
  std::size_t i = 3;
  auto blanks = [&] {
    while (i < up.size() && (up[i] == ' ' || up[i] == '_')) ++i;
  };
  blanks();
  if (up.compare(i, 4, "ZONE") == 0) i += 4, blanks();
  const std::size_t z0 = i;
  while (i < up.size() && i - z0 < 3 && std::isdigit(static_cast<unsigned char>(up[i]))) ++i;
  const std::string zone = up.substr(z0, i - z0);
  blanks();
  if (zone.empty() || i + 1 != up.size() || (up[i] != 'N' && up[i] != 'S')) return std::nullopt;
  const int z = std::stoi(zone);
  if (z < 1 || z > 60) throw InputError("UTM zone " + zone + " is not 1..60", file);
  return "EPSG:" + std::to_string((up[i] == 'N' ? 32600 : 32700) + z);
}

CoordinateSystem from_srs(OGRSpatialReference& srs) {
  CoordinateSystem cs;
  cs.name = srs.GetName() ? srs.GetName() : "unnamed";
  if (srs.IsLocal()) return cs;  // Kind::Unknown: map units, with its name
  int north = 1;
  const int zone = srs.IsProjected() ? srs.GetUTMZone(&north) : 0;
  if (srs.IsGeographic() && wgs84_like(srs)) {
    cs.kind = CoordinateSystem::Kind::Geographic;
  } else if (zone >= 1 && zone <= 60 && wgs84_like(srs)) {
    cs.kind = CoordinateSystem::Kind::Utm;
    cs.zone = zone;
    cs.north = north != 0;
  } else {
    cs.kind = CoordinateSystem::Kind::Other;
    cs.projected = srs.IsProjected() != 0;
    char* wkt = nullptr;
    const char* options[] = {"FORMAT=WKT2_2019", nullptr};
    srs.exportToWkt(&wkt, options);
    cs.wkt = wkt ? wkt : "";
    CPLFree(wkt);
  }
  return cs;
}

}  // namespace

CoordinateSystem parse_coordinate_system(std::string_view text_in, const std::string& file) {
  detail::register_gdal();
  const std::string text(detail::trim(detail::strip_bom(text_in)));
  const std::optional<std::string> code = short_form(text, file);
  OGRSpatialReference srs;
  CPLErrorReset();
  // Without file names and URLs: the text is the system itself, never a path PROJ would open.
  if (text.empty() ||
      srs.SetFromUserInput(code ? code->c_str() : text.c_str(), OGRSpatialReference::SET_FROM_USER_INPUT_LIMITATIONS) !=
          OGRERR_NONE)
    throw InputError("PROJ does not know the coordinate system " + detail::quoted(text.substr(0, 200)) +
                         " (expected EPSG:n, WKT, a PROJ string, lonlat or \"UTM 16N\")",
                     file);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return from_srs(srs);
}

std::function<Point2(const Point2&)> lonlat_transform(const CoordinateSystem& crs, const std::string& file) {
  detail::register_gdal();
  OGRSpatialReference src, ll;
  if (crs.wkt.empty() || src.importFromWkt(crs.wkt.c_str()) != OGRERR_NONE)
    throw InputError("cannot read the coordinate system " + detail::quoted(crs.name), file);
  ll.SetWellKnownGeogCS("WGS84");
  for (auto* s : {&src, &ll}) s->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::shared_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&src, &ll));
  if (!t) throw InputError("PROJ cannot transform " + detail::quoted(crs.name) + " to WGS 84 lon/lat", file);
  return [t](const Point2& m) {
    double x = m[0], y = m[1];
    if (!t->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y))
      throw std::domain_error("PROJ cannot take a point to lon/lat");
    return Point2{x, y};
  };
}

std::optional<Georeference> read_geotiff_tags(const std::string& path) {
  detail::register_gdal();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) return std::nullopt;
  double t[6];
  if (ds->GetGeoTransform(t) != CE_None) return std::nullopt;
  Georeference g;
  g.source = Georeference::Source::GeoTiff;
  // GDAL's transform is from the upper-left corner; ours from the upper-left pixel's centre.
  g.pixel_to_map = {t[1], t[2], t[0] + 0.5 * (t[1] + t[2]), t[4], t[5], t[3] + 0.5 * (t[4] + t[5])};
  if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
    OGRSpatialReference copy(*srs);
    copy.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    g.crs = from_srs(copy);
  } else {
    g.crs.name = "unknown";
  }
  g.description = "GeoTIFF keys of " + std::filesystem::path(path).filename().string() + " (" + g.crs.name + ")";
  return g;
}

detail::CrsTransforms detail::crs_transforms(const std::string& wkt, const std::string& name, const std::string& file) {
  register_gdal();
  OGRSpatialReference srs, ll;
  if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE || !srs.IsProjected())
    throw InputError("not a projected coordinate system: " + name, file);
  ll.SetWellKnownGeogCS("WGS84");
  for (auto* s : {&srs, &ll}) s->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  CrsTransforms out;
  out.forward = ogr_transform(OGRCreateCoordinateTransformation(&ll, &srs));
  out.reverse = ogr_transform(OGRCreateCoordinateTransformation(&srs, &ll));
  if (!out.forward || !out.reverse) throw InputError("PROJ cannot transform " + name + " to WGS 84 lon/lat", file);
  char* p4 = nullptr;
  if (srs.exportToProj4(&p4) == OGRERR_NONE && p4) out.proj4 = p4;
  CPLFree(p4);
  return out;
}

std::string detail::crs_wkt1(const std::string& wkt) {
  register_gdal();
  OGRSpatialReference srs;
  std::string out;
  if (srs.importFromWkt(wkt.c_str()) == OGRERR_NONE) {
    char* w = nullptr;
    if (srs.exportToWkt(&w) == OGRERR_NONE && w) out = w;
    CPLFree(w);
  }
  return out;
}

}  // namespace shoremesh::io
