#pragma once
// Elevation rasters through GDAL (Warmerdam et al., GDAL/OGR Geospatial Data Abstraction software
// Library, gdal.org): GeoTIFF, SRTM .hgt, and any raster format GDAL reads, placed on the terrain's
// plane by the raster's geotransform and coordinate system. This header has no GDAL types: only
// gdal_raster.cpp compiles GDAL's headers, and only firmament_terrain_gdal links GDAL.
//
// Placement: each plane point goes to WGS84 latitude and longitude (terrain/terrain_frame.h), then to
// the raster's coordinate system (OGR's coordinate transformation, PROJ underneath, datum shifts
// included), then through the inverse geotransform to a fractional pixel position; the height there
// is bilinear between the four nearest pixel centres (GDAL's convention: the geotransform maps the
// top-left corner of pixel (0, 0), its centre is at (0.5, 0.5)). Nodata pixels are left out and the
// weights of the others renormalised; a point with none of its four valid, or outside the raster's
// pixel area, has no height (NaN), which the scene's fallback fills (terrain/terrain_fill.h). Inside
// the half-pixel rim beyond the outer pixel centres, the edge pixels' values hold.
// Heights are taken as metres above sea level, the vertical datum of SRTM (EGM96) and of most DEMs; a
// raster whose values lie outside [kLowestHeight_m, kHighestHeight_m] is refused.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "terrain/height_field.h"
#include "terrain/procedural_terrain.h"
#include "terrain/terrain_frame.h"

namespace firmament::terrain {

// A raster's first band as read: exactly the stored values (as float; integers up to 2^24 and float32
// are exact), its validity, geotransform and coordinate system.
struct GdalRaster {
  std::string file;
  std::string driver;    // GDAL's short name ("GTiff", "SRTMHGT", ...)
  std::string dataType;  // GDAL's name of the band's type ("UInt16", "Float32", ...)
  std::string srsName;   // the coordinate system's name ("WGS 84", "WGS 84 / UTM zone 25S", ...)
  std::string srsWkt;    // its WKT2
  int width = 0;
  int height = 0;
  std::array<double, 6> geoTransform{};  // GDAL's: x = g0 + col g1 + row g2, y = g3 + col g4 + row g5
  bool hasNodata = false;
  double nodata = 0.0;
  std::vector<float> values;   // width × height, row 0 at the top (as stored)
  std::vector<uint8_t> valid;  // 1 where the value is data (not nodata, not NaN)
  double minimum = 0.0;        // over valid values
  double maximum = 0.0;
  size_t validCount = 0;
};

// Reads band 1. InputError (the tool's exit 2) for: a missing file; a file GDAL cannot open as a raster
// ("not a raster GDAL reads", with GDAL's own reason); no geotransform or no coordinate system ("no
// georeference"); no valid value; a value outside [kLowestHeight_m, kHighestHeight_m] (names the
// pixel, the value and the limits).
GdalRaster readGdalRaster(const std::filesystem::path& file);

// The raster placed at a scene's location.
class GdalPlacement {
 public:
  GdalPlacement(const GdalRaster& raster, const TerrainFrame& frame);
  ~GdalPlacement();
  GdalPlacement(const GdalPlacement&) = delete;
  GdalPlacement& operator=(const GdalPlacement&) = delete;

  // The fractional pixel position (column, row; pixel centres at +0.5) of a plane point.
  glm::dvec2 pixelOfPlane(glm::dvec2 plane) const;
  // The plane point of a fractional pixel position (corners at integers).
  glm::dvec2 planeOfPixel(glm::dvec2 pixel) const;
  // The raster's height at a plane point (the bilinear rule above), NaN where it has none.
  double heightAt(glm::dvec2 plane) const;
  // Every sample of a region (NaN where the raster has no height).
  HeightField resample(const TileRegion& region) const;
  // InputError unless the location (plane (0, 0)) lies on the raster's pixel area; the message names
  // the raster's corners in latitude and longitude and the scene's location.
  void checkCoversLocation(const std::string& sceneSource) const;
  // The plane's bounding box of the raster's outline (its edges sampled at 64 points each).
  std::array<double, 4> planeBounds() const;  // x min, y min, x max, y max

 private:
  struct Impl;
  const GdalRaster* raster_;
  const TerrainFrame* frame_;
  std::unique_ptr<Impl> impl_;
};

// Writes a single-band Float32 GeoTIFF with a geotransform, a coordinate system (any "EPSG:n" or WKT
// that OGR reads) and an optional nodata value: what the tests use to make rasters, through GDAL itself.
void writeGdalGeoTiff(const std::filesystem::path& file, int width, int height, const std::vector<float>& values,
                      const std::array<double, 6>& geoTransform, const std::string& srs,
                      const double* nodata = nullptr);

}  // namespace firmament::terrain
