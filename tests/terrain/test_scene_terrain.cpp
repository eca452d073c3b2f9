// A scene's terrain: the fields read from /terrain, height maps (16-bit PNG, EXR) that round-trip,
// the fallback where data ends, procedural scenes, and the bad inputs (each an InputError naming the
// file or field and what is allowed).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/error.h"
#include "core/exr_io.h"
#include "core/png_io.h"
#include "core/scene.h"
#include "terrain/gdal_raster.h"
#include "terrain/height_map_file.h"
#include "terrain/scene_terrain.h"
#include "terrain/terrain_fill.h"
#include "tests/support/test_paths.h"
#include "tests/terrain/terrain_test_support.h"

namespace firmament::terrain {
namespace {
namespace fs = std::filesystem;
using test::kR;

std::string messageOf(const std::function<void()>& body) {
  try {
    body();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

Scene sceneWith(const std::string& terrain, const std::string& source = "<test>") {
  return Scene::parse(
      R"({"location": {"latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 1200}, "terrain": )" + terrain + "}",
      source);
}

TEST(SceneTerrain, ASceneWithoutTerrainHasNone) {
  const Scene scene = Scene::parse("{}", "<test>");
  EXPECT_FALSE(scene.hasSection("terrain"));
}

TEST(SceneTerrain, DefaultsAreTheDocumentedOnes) {
  const TerrainSettings s = terrainSettingsFromScene(sceneWith("{}"));
  EXPECT_EQ(s.kind, TerrainKind::Procedural);
  EXPECT_EQ(s.procedural.style, TerrainStyle::Alpine);
  EXPECT_EQ(s.procedural.seed, 3u);
  EXPECT_EQ(s.extent_m, 20000.0);
  EXPECT_EQ(s.resolution, 1024);
  EXPECT_EQ(s.fallback, TerrainFallback::Sphere);
  EXPECT_EQ(s.procedural.baseHeight, 1200.0);
  EXPECT_NEAR(s.albedo.snowMaxSlope, 50.0 * 3.14159265358979 / 180.0, 1e-12);
}

TEST(SceneTerrain, ProceduralSceneIsTheGeneratorsTileThroughTheLocationHeight) {
  const ResolvedTerrain t =
      resolveSceneTerrain(sceneWith(R"({"style": "hills", "seed": 8, "extent_m": 4000, "resolution": 65})"), kR);
  EXPECT_EQ(t.field.nx, 65);
  EXPECT_DOUBLE_EQ(t.field.dx, 4000.0 / 64.0);
  EXPECT_EQ(t.field.outsideHeight, 1200.0);
  EXPECT_EQ(t.dataFraction, 1.0);
  ProceduralTerrain p;
  p.style = TerrainStyle::Hills;
  p.seed = 8;
  p.baseHeight = 1200.0;
  const HeightField direct = ProceduralTerrainField(p).tile(TileRegion::centred(0, 0, 4000.0, 65));
  EXPECT_EQ(t.field.heights, direct.heights);
  EXPECT_NEAR(t.field.at(32, 32), 1200.0, 2.0);  // the tile's detail stops at 2 spacings (125 m)
}

TEST(SceneTerrain, AbsurdProceduralScalesAreInputErrors) {
  const std::string m = messageOf([] {
    resolveSceneTerrain(
        Scene::parse(R"({"location": {"height_m": 6000}, "terrain": {"style": "alpine", "vertical_scale": 4,
                                         "resolution": 64, "extent_m": 60000}})",
                     "<test>"),
        kR);
  });
  EXPECT_NE(m.find("outside the allowed [-11000, 9000]"), std::string::npos) << m;
  EXPECT_NE(m.find("vertical_scale 4"), std::string::npos) << m;
}

TEST(HeightMapFile, SixteenBitPngRoundTripsAndIsPlacedByItsExtent) {
  const fs::path dir = firmament::test::scratchDir("heightmap_png");
  const int w = 6, h = 4;
  std::vector<uint16_t> v(size_t(w * h));
  for (size_t k = 0; k < v.size(); ++k) v[k] = uint16_t(k * 2731 + 5);
  v[3] = 65535;
  writePngGrey16(dir / "map.png", w, h, v.data());
  const Grey16 back = readPngGrey16(dir / "map.png");
  EXPECT_EQ(back.bitDepth, 16);
  EXPECT_EQ(back.samples, v);
  HeightMapPlacement p;
  p.width_m = 600.0;
  p.length_m = 400.0;
  p.centreEast_m = 50.0;
  p.minHeight_m = -100.0;
  p.maxHeight_m = 3000.0;
  const HeightField f = readHeightMap(dir / "map.png", p);
  // Pixel (col, row) is sample (col, h − 1 − row), its centre at x = 50 − 300 + 100 (col + 0.5).
  EXPECT_DOUBLE_EQ(f.x0, -200.0);
  EXPECT_DOUBLE_EQ(f.y0, -150.0);
  EXPECT_DOUBLE_EQ(f.dx, 100.0);
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col)
      EXPECT_EQ(f.at(col, h - 1 - row), float(-100.0 + 3100.0 * v[size_t(row * w + col)] / 65535.0));
  EXPECT_EQ(f.at(3, h - 1), 3000.0f);
}

TEST(HeightMapFile, ExrHeightsRoundTripBitForBit) {
  const fs::path dir = firmament::test::scratchDir("heightmap_exr");
  HeightField f(7, 5, -30.0, -20.0, 10.0, 10.0);
  for (size_t k = 0; k < f.heights.size(); ++k) f.heights[k] = float(1000.0 + 37.123 * k - 0.001 * k * k);
  writeHeightFieldExr(dir / "h.exr", f);
  HeightMapPlacement p;
  p.width_m = 70.0;
  p.length_m = 50.0;
  const HeightField back = readHeightMap(dir / "h.exr", p);
  EXPECT_EQ(back.heights, f.heights);
  EXPECT_DOUBLE_EQ(back.x0, f.x0);
  EXPECT_DOUBLE_EQ(back.y0, f.y0);
  const ExrChannel raw = readExrChannel(dir / "h.exr", {"Y"});
  EXPECT_EQ(raw.metadata.at("terrain:dx_m"), "10");
}

TEST(SceneTerrain, HeightMapSceneKeepsItsDataAndBlendsIntoTheFallback) {
  const fs::path dir = firmament::test::scratchDir("heightmap_scene");
  std::vector<uint16_t> v(size_t(21 * 21), 65535);  // a 2000 m plateau over 2.1 km
  writePngGrey16(dir / "plateau.png", 21, 21, v.data());
  std::ofstream(dir / "scene.json") << R"({"location": {"height_m": 500},
    "terrain": {"kind": "heightmap", "file": "plateau.png", "extent_m": 8000, "resolution": 81, "edge_blend_m": 1000,
                "heightmap": {"width_m": 2100, "length_m": 2100, "min_height_m": 0, "max_height_m": 2000}}})";
  const ResolvedTerrain t = resolveSceneTerrain(Scene::load(dir / "scene.json"), kR);  // file relative to the scene
  EXPECT_NEAR(t.dataFraction, 21.0 * 21.0 / (81.0 * 81.0), 0.01);
  EXPECT_EQ(t.field.sample(0.0, 0.0), 2000.0);     // data untouched
  EXPECT_EQ(t.field.sample(1000.0, 0.0), 2000.0);  // to the image's edge (1050 m)
  EXPECT_EQ(t.field.sample(3900.0, 0.0), 500.0);   // the sphere at /location/height_m beyond the blend
  // Continuous across the edge: each 100 m step outwards changes the height by less than the plateau.
  for (double x = 1000.0; x < 2500.0; x += 100.0)
    EXPECT_LT(std::fabs(t.field.sample(x + 100.0, 0.0) - t.field.sample(x, 0.0)), 1000.0) << x;
  EXPECT_GT(t.field.sample(1600.0, 0.0), 500.0);
  EXPECT_LT(t.field.sample(1600.0, 0.0), 2000.0);
}

TEST(TerrainFill, BlendIsSmoothstepOfTheDistanceToTheData) {
  HeightField f(11, 1, 0.0, 0.0, 100.0, 100.0);
  f.ny = 2;
  f.heights.assign(22, std::nanf(""));
  f.at(0, 0) = f.at(0, 1) = 1000.0f;
  fillFromFallback(
      f, [](double, double) { return 0.0; }, 500.0);
  for (int i = 1; i <= 10; ++i) {
    const double s = std::min(i * 100.0 / 500.0, 1.0);
    EXPECT_NEAR(f.at(i, 0), 1000.0 * (1.0 - s * s * (3.0 - 2.0 * s)), 1e-3) << i;
  }
}

TEST(SceneTerrain, BadInputsNameTheFileOrFieldAndWhatIsAllowed) {
  const fs::path dir = firmament::test::scratchDir("terrain_bad");
  EXPECT_NE(messageOf([] { terrainSettingsFromScene(sceneWith(R"({"kind": "gdal"})")); }).find("/terrain/file"),
            std::string::npos);
  EXPECT_NE(messageOf([] { sceneWith(R"({"style": "moon"})"); }).find("one of \"alpine\""), std::string::npos);
  EXPECT_NE(messageOf([] { sceneWith(R"({"resolution": 1})"); }).find("/terrain/resolution"), std::string::npos);
  const std::string missing = (dir / "nothing.tif").string();
  EXPECT_NE(messageOf([&] {
              resolveSceneTerrain(sceneWith(R"({"kind": "gdal", "file": ")" + missing + "\"}"), kR);
            }).find("no such raster file"),
            std::string::npos);
  // A colour PNG is not a height map.
  const std::vector<uint8_t> rgb(4 * 4 * 3, 100);
  writePng(dir / "colour.png", 4, 4, 3, rgb.data());
  const std::string colour = messageOf([&] {
    resolveSceneTerrain(sceneWith(R"({"kind": "heightmap", "file": ")" + (dir / "colour.png").string() + "\"}"), kR);
  });
  EXPECT_NE(colour.find("expected a grey PNG"), std::string::npos) << colour;
  // An EXR with absurd heights.
  HeightField absurd(2, 2, 0, 0, 1, 1);
  absurd.heights = {0.0f, 20000.0f, 0.0f, 0.0f};
  writeHeightFieldExr(dir / "absurd.exr", absurd);
  const std::string high = messageOf([&] {
    resolveSceneTerrain(sceneWith(R"({"kind": "heightmap", "file": ")" + (dir / "absurd.exr").string() + "\"}"), kR);
  });
  EXPECT_NE(high.find("is absurd"), std::string::npos) << high;
  // A height map placed away from the location.
  std::vector<uint16_t> v(16, 100);
  writePngGrey16(dir / "away.png", 4, 4, v.data());
  const std::string away = messageOf([&] {
    resolveSceneTerrain(sceneWith(R"({"kind": "heightmap", "file": ")" + (dir / "away.png").string() +
                                  R"(", "heightmap": {"centre_east_m": 50000}})"),
                        kR);
  });
  EXPECT_NE(away.find("does not cover the scene"), std::string::npos) << away;
  // A text file given as a raster; an inverted PNG range.
  std::ofstream(dir / "notes.txt") << "heights\n";
  EXPECT_NE(messageOf([&] {
              resolveSceneTerrain(sceneWith(R"({"kind": "gdal", "file": ")" + (dir / "notes.txt").string() + "\"}"),
                                  kR);
            }).find("not a raster GDAL reads"),
            std::string::npos);
  EXPECT_NE(messageOf([&] {
              terrainSettingsFromScene(sceneWith(R"({"kind": "heightmap", "file": "x.png",
                                                     "heightmap": {"min_height_m": 10, "max_height_m": 5}})"));
            }).find("above min_height_m"),
            std::string::npos);
}

TEST(SceneTerrain, GdalSceneOnTheTerraDemUsesItsHeightsAndTheFallbackBeyond) {
  const fs::path file = test::demFile("terra/elev.tif");
  const GdalRaster raster = readGdalRaster(file);
  // The raster's centre pixel (47, 45).
  const double lon = raster.geoTransform[0] + 47.5 * raster.geoTransform[1];
  const double lat = raster.geoTransform[3] + 45.5 * raster.geoTransform[5];
  const Scene scene = Scene::parse(R"({"location": {"latitude_deg": )" + std::to_string(lat) +
                                       R"(, "longitude_deg": )" + std::to_string(lon) + R"(, "height_m": 300},
      "terrain": {"kind": "gdal", "file": ")" +
                                       file.string() + R"(", "extent_m": 200000, "resolution": 201,
                  "fallback": "procedural", "style": "hills"}})",
                                   "<test>");
  const ResolvedTerrain t = resolveSceneTerrain(scene, kR);
  EXPECT_GT(t.dataFraction, 0.05);
  EXPECT_LT(t.dataFraction, 0.5);
  const TerrainFrame frame(astro::GeodeticLocation::fromDegrees(lat, lon, 300.0), kR);
  const GdalPlacement placement(raster, frame);
  EXPECT_NEAR(t.field.sample(0.0, 0.0), placement.heightAt({0.0, 0.0}), 1e-3);
  // Far outside the raster (90 km east), the hills around 300 m.
  EXPECT_NEAR(t.field.sample(95000.0, 0.0), 300.0, 400.0);
  // And a raster that does not cover the location is refused.
  const Scene away = Scene::parse(R"({"location": {"latitude_deg": 10, "longitude_deg": 10},
      "terrain": {"kind": "gdal", "file": ")" +
                                      file.string() + "\"}}",
                                  "away.json");
  EXPECT_NE(messageOf([&] { resolveSceneTerrain(away, kR); }).find("does not cover the scene"), std::string::npos);
}

}  // namespace
}  // namespace firmament::terrain
