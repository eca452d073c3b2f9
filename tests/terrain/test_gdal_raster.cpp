// Rasters through GDAL: a GeoTIFF written with GDAL reads back exactly and lands where its
// coordinates say (checked with GeographicLib's own UTM and geodesics, not with the code under test);
// the two real DEMs shipped in Debian packages read as GDAL's own reader gives them and are placed at
// their coordinates; every bad input is an InputError that says what is wrong.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

#include "core/error.h"
#include "terrain/gdal_raster.h"
#include "tests/support/test_paths.h"
#include "tests/terrain/terrain_test_support.h"

namespace firmament::terrain {
namespace {
namespace fs = std::filesystem;
using test::kR;
constexpr double kDegree = 3.14159265358979323846 / 180.0;

// The plane point of a latitude/longitude (degrees) seen from a location, from the geodesic between
// them: distance s along azimuth α lands at R tan(s / R) (sin α, cos α).
glm::dvec2 expectedPlane(double lat0, double lon0, double lat, double lon) {
  double s = 0, a1 = 0, a2 = 0;
  GeographicLib::Geodesic::WGS84().Inverse(lat0, lon0, lat, lon, s, a1, a2);
  const double rho = kR * std::tan(s / kR);
  return {rho * std::sin(a1 * kDegree), rho * std::cos(a1 * kDegree)};
}

std::string messageOf(const std::function<void()>& body) {
  try {
    body();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST(GdalRaster, WrittenGeoTiffReadsBackExactlyAndIsPlacedByItsUtmCoordinates) {
  // 40 × 30 pixels of 30 m in UTM 32N, its top-left corner at (420000, 5160000) (near 46.6° N, 7.95° E).
  const int w = 40, h = 30;
  std::vector<float> values(size_t(w * h));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(400.0f, 4000.0f);
  for (float& v : values) v = u(rng);
  const double nodata = -9999.0;
  values[17] = float(nodata);
  const fs::path file = firmament::test::scratchDir("gdal_written") / "utm.tif";
  writeGdalGeoTiff(file, w, h, values, {420000.0, 30.0, 0.0, 5160000.0, 0.0, -30.0}, "EPSG:32632", &nodata);

  const GdalRaster r = readGdalRaster(file);
  EXPECT_EQ(r.driver, "GTiff");
  EXPECT_EQ(r.dataType, "Float32");
  EXPECT_EQ(r.width, w);
  EXPECT_EQ(r.height, h);
  EXPECT_NE(r.srsName.find("UTM zone 32N"), std::string::npos) << r.srsName;
  EXPECT_EQ(r.geoTransform[0], 420000.0);
  EXPECT_EQ(r.geoTransform[5], -30.0);
  EXPECT_TRUE(r.hasNodata);
  EXPECT_EQ(std::memcmp(r.values.data(), values.data(), values.size() * sizeof(float)), 0);
  EXPECT_EQ(r.valid[17], 0);
  EXPECT_EQ(r.validCount, values.size() - 1);

  // The scene at the centre of pixel (20, 15); GeographicLib's UTM gives every position.
  auto centreLatLon = [&](double col, double row, double& lat, double& lon) {
    GeographicLib::UTMUPS::Reverse(32, true, 420000.0 + 30.0 * col, 5160000.0 - 30.0 * row, lat, lon);
  };
  double lat0, lon0;
  centreLatLon(20.5, 15.5, lat0, lon0);
  const TerrainFrame frame(astro::GeodeticLocation::fromDegrees(lat0, lon0, 1000.0), kR);
  const GdalPlacement placement(r, frame);
  placement.checkCoversLocation("<test>");
  // A known corner (the raster's top-left) at its known plane position, to a millimetre.
  double latC, lonC;
  centreLatLon(0.0, 0.0, latC, lonC);
  const glm::dvec2 corner = placement.planeOfPixel({0.0, 0.0}), expected = expectedPlane(lat0, lon0, latC, lonC);
  EXPECT_NEAR(corner.x, expected.x, 1e-3);
  EXPECT_NEAR(corner.y, expected.y, 1e-3);
  const glm::dvec2 pixel = placement.pixelOfPlane(expected);
  EXPECT_NEAR(pixel.x, 0.0, 1e-4);
  EXPECT_NEAR(pixel.y, 0.0, 1e-4);
  // Heights at pixel centres are the pixels' values.
  for (int k : {0, 21, 333, 1199}) {
    const int col = k % w, row = k / w;
    double lat, lon;
    centreLatLon(col + 0.5, row + 0.5, lat, lon);
    EXPECT_NEAR(placement.heightAt(expectedPlane(lat0, lon0, lat, lon)), values[size_t(k)], 2e-3) << col << ", " << row;
  }
  // Next to the nodata pixel (17, 0) the others' weights carry the height; beyond the raster, nothing.
  double lat, lon;
  centreLatLon(17.5, 0.5, lat, lon);
  const double nearNodata = placement.heightAt(expectedPlane(lat0, lon0, lat, lon));
  EXPECT_TRUE(std::isfinite(nearNodata));
  centreLatLon(-3.0, 10.0, lat, lon);
  EXPECT_TRUE(std::isnan(placement.heightAt(expectedPlane(lat0, lon0, lat, lon))));
}

// GDAL's own reading of a file, for comparison: min/max over valid pixels and single pixels.
struct GdalTruth {
  double minimum = 0, maximum = 0;
  std::array<double, 6> gt{};
};
GdalTruth gdalTruth(const fs::path& file) {
  GDALAllRegister();
  GDALDataset* d = GDALDataset::FromHandle(GDALOpen(file.c_str(), GA_ReadOnly));
  EXPECT_NE(d, nullptr);
  GdalTruth t;
  if (!d) return t;
  double mm[2];
  d->GetRasterBand(1)->ComputeRasterMinMax(FALSE, mm);
  t.minimum = mm[0];
  t.maximum = mm[1];
  d->GetGeoTransform(t.gt.data());
  GDALClose(GDALDataset::ToHandle(d));
  return t;
}
float gdalPixel(const fs::path& file, int col, int row) {
  GDALDataset* d = GDALDataset::FromHandle(GDALOpen(file.c_str(), GA_ReadOnly));
  float v = 0;
  EXPECT_EQ(d->GetRasterBand(1)->RasterIO(GF_Read, col, row, 1, 1, &v, 1, 1, GDT_Float32, 0, 0, nullptr), CE_None);
  GDALClose(GDALDataset::ToHandle(d));
  return v;
}

TEST(GdalRaster, TerraElevationLoadsAsGdalReadsItAndLiesAtItsCoordinates) {
  const fs::path file = test::demFile("terra/elev.tif");  // 95 × 90 Int16, WGS 84 (Luxembourg)
  const GdalRaster r = readGdalRaster(file);
  const GdalTruth truth = gdalTruth(file);
  EXPECT_EQ(r.width, 95);
  EXPECT_EQ(r.height, 90);
  EXPECT_EQ(r.dataType, "Int16");
  EXPECT_EQ(r.minimum, truth.minimum);
  EXPECT_EQ(r.maximum, truth.maximum);
  std::printf("terra elev.tif: %s, %s, heights %.0f..%.0f m, %zu valid of %d\n", r.driver.c_str(), r.srsName.c_str(),
              r.minimum, r.maximum, r.validCount, r.width * r.height);
  // Geographic: pixel (c, r)'s centre is at lon = g0 + (c + 0.5) g1, lat = g3 + (r + 0.5) g5.
  auto centre = [&](int c, int row) {
    return glm::dvec2(truth.gt[3] + (row + 0.5) * truth.gt[5], truth.gt[0] + (c + 0.5) * truth.gt[1]);
  };
  const glm::dvec2 at = centre(47, 45);
  const TerrainFrame frame(astro::GeodeticLocation::fromDegrees(at.x, at.y, 300.0), kR);
  const GdalPlacement placement(r, frame);
  int checked = 0;
  for (auto [c, row] : std::vector<std::pair<int, int>>{{47, 45}, {10, 60}, {70, 20}, {30, 30}, {60, 75}}) {
    const float value = gdalPixel(file, c, row);
    const size_t k = size_t(row) * 95 + size_t(c);
    if (!r.valid[k]) continue;
    EXPECT_EQ(r.values[k], value);
    const glm::dvec2 ll = centre(c, row);
    EXPECT_NEAR(placement.heightAt(expectedPlane(at.x, at.y, ll.x, ll.y)), value, 1e-2) << c << ", " << row;
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

TEST(GdalRaster, StarsOlindaDemInUtm25SouthLoadsAndLiesAtItsCoordinates) {
  const fs::path file = test::demFile("stars/olinda_dem_utm25s.tif");  // 111 × 111 Float32
  const GdalRaster r = readGdalRaster(file);
  const GdalTruth truth = gdalTruth(file);
  EXPECT_EQ(r.width, 111);
  EXPECT_EQ(r.height, 111);
  EXPECT_EQ(r.dataType, "Float32");
  EXPECT_EQ(r.minimum, truth.minimum);
  EXPECT_EQ(r.maximum, truth.maximum);
  std::printf("stars olinda: %s, %s, heights %.2f..%.2f m, pixel %.1f m\n", r.driver.c_str(), r.srsName.c_str(),
              r.minimum, r.maximum, truth.gt[1]);
  auto latLon = [&](double c, double row) {
    double lat, lon;
    GeographicLib::UTMUPS::Reverse(25, false, truth.gt[0] + c * truth.gt[1], truth.gt[3] + row * truth.gt[5], lat, lon);
    return glm::dvec2(lat, lon);
  };
  const glm::dvec2 at = latLon(55.5, 55.5);
  const TerrainFrame frame(astro::GeodeticLocation::fromDegrees(at.x, at.y, 10.0), kR);
  const GdalPlacement placement(r, frame);
  placement.checkCoversLocation("<test>");
  for (auto [c, row] : std::vector<std::pair<int, int>>{{55, 55}, {5, 100}, {100, 7}, {80, 40}}) {
    const float value = gdalPixel(file, c, row);
    EXPECT_EQ(r.values[size_t(row) * 111 + size_t(c)], value);
    const glm::dvec2 ll = latLon(c + 0.5, row + 0.5);
    EXPECT_NEAR(placement.heightAt(expectedPlane(at.x, at.y, ll.x, ll.y)), value, 1e-3) << c << ", " << row;
  }
  const glm::dvec2 corner = placement.planeOfPixel({0.0, 0.0});
  const glm::dvec2 ll = latLon(0.0, 0.0), expected = expectedPlane(at.x, at.y, ll.x, ll.y);
  EXPECT_NEAR(corner.x, expected.x, 1e-3);
  EXPECT_NEAR(corner.y, expected.y, 1e-3);
}

TEST(GdalRaster, BadRastersAreInputErrorsThatSayWhy) {
  const fs::path dir = firmament::test::scratchDir("gdal_bad");
  EXPECT_NE(messageOf([&] { readGdalRaster(dir / "missing.tif"); }).find("no such raster file"), std::string::npos);
  std::ofstream(dir / "text.tif") << "this is not a raster\n";
  EXPECT_NE(messageOf([&] { readGdalRaster(dir / "text.tif"); }).find("not a raster GDAL reads"), std::string::npos);
  const std::vector<float> v(16, 100.0f);
  writeGdalGeoTiff(dir / "nogeo.tif", 4, 4, v, {0, 1, 0, 0, 0, 1}, "");
  {  // a GeoTIFF without geotransform: written by GDAL with none set
    GDALAllRegister();
    GDALDataset* d = GetGDALDriverManager()->GetDriverByName("GTiff")->Create((dir / "bare.tif").c_str(), 4, 4, 1,
                                                                              GDT_Float32, nullptr);
    float buffer[16];
    std::fill(buffer, buffer + 16, 100.0f);
    ASSERT_EQ(d->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 4, 4, buffer, 4, 4, GDT_Float32, 0, 0, nullptr), CE_None);
    GDALClose(GDALDataset::ToHandle(d));
  }
  const std::string bare = messageOf([&] { readGdalRaster(dir / "bare.tif"); });
  EXPECT_NE(bare.find("no georeference"), std::string::npos) << bare;
  EXPECT_NE(bare.find("geotransform"), std::string::npos) << bare;
  const std::string noSrs = messageOf([&] { readGdalRaster(dir / "nogeo.tif"); });
  EXPECT_NE(noSrs.find("no georeference"), std::string::npos) << noSrs;
  EXPECT_NE(noSrs.find("coordinate system"), std::string::npos) << noSrs;
  // Absurd heights: centimetres (1234500 "m"), and SRTM's −32768 void without a declared nodata.
  std::vector<float> cm(16, 123450.0f);
  writeGdalGeoTiff(dir / "cm.tif", 4, 4, cm, {7.0, 0.01, 0, 47.0, 0, -0.01}, "EPSG:4326");
  const std::string absurd = messageOf([&] { readGdalRaster(dir / "cm.tif"); });
  EXPECT_NE(absurd.find("is absurd"), std::string::npos) << absurd;
  EXPECT_NE(absurd.find("[-11000, 9000]"), std::string::npos) << absurd;
  std::vector<float> voids(16, 500.0f);
  voids[5] = -32768.0f;
  writeGdalGeoTiff(dir / "void.tif", 4, 4, voids, {7.0, 0.01, 0, 47.0, 0, -0.01}, "EPSG:4326");
  EXPECT_NE(messageOf([&] { readGdalRaster(dir / "void.tif"); }).find("undeclared"), std::string::npos);
  const double declared = -32768.0;
  writeGdalGeoTiff(dir / "declared.tif", 4, 4, voids, {7.0, 0.01, 0, 47.0, 0, -0.01}, "EPSG:4326", &declared);
  EXPECT_EQ(readGdalRaster(dir / "declared.tif").validCount, 15u);
  std::vector<float> all(16, -32768.0f);
  writeGdalGeoTiff(dir / "empty.tif", 4, 4, all, {7.0, 0.01, 0, 47.0, 0, -0.01}, "EPSG:4326", &declared);
  EXPECT_NE(messageOf([&] { readGdalRaster(dir / "empty.tif"); }).find("every pixel is nodata"), std::string::npos);
  // A raster that does not cover the scene's location.
  const GdalRaster r = readGdalRaster(dir / "declared.tif");  // 7.00–7.04° E, 46.96–47.00° N
  const TerrainFrame elsewhere(astro::GeodeticLocation::fromDegrees(46.55, 7.98, 0.0), kR);
  const GdalPlacement placement(r, elsewhere);
  const std::string cover = messageOf([&] { placement.checkCoversLocation("scene.json"); });
  EXPECT_NE(cover.find("does not cover the scene"), std::string::npos) << cover;
  EXPECT_NE(cover.find("latitude 46.96 to 47"), std::string::npos) << cover;
  EXPECT_NE(cover.find("scene.json: /terrain/file"), std::string::npos) << cover;
}

}  // namespace
}  // namespace firmament::terrain
