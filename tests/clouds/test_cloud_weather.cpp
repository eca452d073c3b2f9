// The weather map in the cloud medium (common/cloud_weather.glsl): a map with no coverage gives no
// cloud; a single covered disc gives cloud only over that disc, on the GPU and in the CPU path
// tracer's medium alike; the procedural map; the thunderstorm scene's simulated map grows cumulonimbus.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "clouds/reference_clouds.h"
#include "common/cloud_weather.glsl"
#include "sky/scene_weather.h"
#include "tests/clouds/cloud_test_support.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

class CloudWeather : public test::GpuTest {};

// Coverage 1 inside a disc of `radius_m` around (east, north) = centre_m, 0 outside; cumulus type, no
// top cap. 128^2 texels over the default 51.2 km region (400 m texels).
CloudWeatherMap discMap(glm::dvec2 centre_m, double radius_m) {
  CloudWeatherMap m =
      uniformCloudWeatherMap(glm::vec4(0.0f, 1.0f / 3.0f, 0.0f, float(shared::kCloudWeatherNoTop)), 128);
  for (int row = 0; row < m.map.height; ++row)
    for (int column = 0; column < m.map.width; ++column) {
      const double east = ((column + 0.5) / m.map.width - 0.5) * m.width_m;
      const double north = (0.5 - (row + 0.5) / m.map.height) * m.height_m;
      if (glm::length(glm::dvec2(east, north) - centre_m) < radius_m) m.map.at(column, row)[0] = 1.0f;
    }
  return m;
}

// Optical depth of a vertical ray through the layers at (east, north) (m), midpoint rule, 20 m steps.
double verticalOpticalDepth(const CloudMedium& medium, double ground, double east, double north) {
  double tau = 0.0;
  for (size_t i = 0; i < medium.layers().size(); ++i)
    for (double r = medium.layers()[i].bottom_radius + 10.0; r < medium.layers()[i].top_radius; r += 20.0) {
      // The point at height r - ground above the tangent-plane point (east, north): along the unit
      // direction (east, north, R) (region coordinates are R atan2(x, z), exact for this direction).
      const glm::dvec3 d = glm::normalize(glm::dvec3(std::tan(east / ground), std::tan(north / ground), 1.0));
      tau += medium.extinction(i, d * r) * 20.0;
    }
  return tau;
}

CloudMedium mediumFor(const Scene& scene, CloudWeatherMap map, double ground) {
  const CloudSettings settings = CloudSettings::fromScene(scene);
  CloudNoise noise(test::GpuTest::context());
  gpu::CommandList commands(test::GpuTest::context());
  noise.update(settings.seed, test::smallCloudOptions().cloudNoise, commands);
  commands.submitAndWait();
  return CloudMedium(sharedCloudLayers(settings, ground), noise.downloadShape(), noise.downloadDetail(),
                     noise.downloadCurl(), std::move(map), ground);
}

double meanTransmittance(const Image& clouds) {
  double sum = 0.0;
  for (size_t i = 0; i < clouds.pixelCount(); ++i) sum += clouds.pixels[4 * i + 3];
  return sum / double(clouds.pixelCount());
}

TEST_F(CloudWeather, NoCoverageMeansNoCloud) {
  SkyRenderOptions o = test::smallCloudOptions();
  const Scene s = test::cloudScene({"/clouds/layers/0/coverage=1", "/camera/width=32", "/camera/height=18"});
  o.cloudWeather = std::make_shared<CloudWeatherMap>(uniformCloudWeatherMap(glm::vec4(0.0f, 0.33f, 0.0f, 5000.0f)));
  const RenderResult r = test::cloudRenderer().render(s, o);
  for (size_t i = 0; i < r.clouds.pixelCount(); ++i) ASSERT_EQ(r.clouds.pixels[4 * i + 3], 1.0f);
  const double ground = r.view.cameraRadius - 2.0;
  const CloudMedium medium = mediumFor(s, *o.cloudWeather, ground);
  for (double e = -30000.0; e <= 30000.0; e += 2500.0) EXPECT_EQ(verticalOpticalDepth(medium, ground, e, 0.5 * e), 0.0);
}

// A disc of 3 km radius: overhead (inside) the layer of coverage 1 is cloudy; 8 km east (outside) it
// holds nothing: exactly zero optical depth on the CPU; the GPU looking straight up (30 degrees
// field: a footprint of +-0.4 km at the 1.5 km base, +-1.1 km at the 4 km top) sees cloud over the
// disc and none when the disc is moved 10 km away.
TEST_F(CloudWeather, CloudOnlyOverTheCoveredDisc) {
  SkyRenderOptions o = test::smallCloudOptions();
  const Scene s = test::cloudScene({"/clouds/layers/0/coverage=1", "/camera/pitch_deg=90", "/camera/fov_deg=30",
                                    "/camera/width=16", "/camera/height=16"});
  o.cloudWeather = std::make_shared<CloudWeatherMap>(discMap({0.0, 0.0}, 3000.0));
  const RenderResult over = test::cloudRenderer().render(s, o);
  o.cloudWeather = std::make_shared<CloudWeatherMap>(discMap({10000.0, 0.0}, 3000.0));
  const RenderResult away = test::cloudRenderer().render(s, o);
  const double tOver = meanTransmittance(over.clouds), tAway = meanTransmittance(away.clouds);
  std::printf("disc overhead: mean T %.4f; disc 10 km east: mean T %.4f\n", tOver, tAway);
  EXPECT_LT(tOver, 0.5);
  EXPECT_EQ(tAway, 1.0);

  const double ground = over.view.cameraRadius - 2.0;
  const CloudMedium medium = mediumFor(s, discMap({0.0, 0.0}, 3000.0), ground);
  double inside = 0.0;
  for (double e : {-1500.0, 0.0, 1500.0}) inside += verticalOpticalDepth(medium, ground, e, 0.0);
  std::printf("CPU medium: optical depth over the disc %.2f\n", inside / 3.0);
  EXPECT_GT(inside / 3.0, 1.0);
  // Outside the disc by more than a texel (400 m) plus the skew: nothing.
  for (double e : {4000.0, 8000.0, -6000.0}) EXPECT_EQ(verticalOpticalDepth(medium, ground, e, 0.0), 0.0) << e;
  EXPECT_EQ(verticalOpticalDepth(medium, ground, 0.0, 5000.0), 0.0);
}

// The wind moves the whole field, the map's coverage with the noise: 10 m/s from the west for 1000 s
// carries the disc 10 km east. The GPU looking straight up then sees no cloud, and on the CPU the
// column 10 km east holds what the column overhead held at time 0. The two columns differ only by the
// curvature: the noise moves in the cloud frame's x, the map in tangent-plane angles times R, and a
// point 10 km east at the same height lies 2-6 m further along x and ~8 m lower in z.
TEST_F(CloudWeather, TheWindCarriesTheMapWithTheNoise) {
  SkyRenderOptions o = test::smallCloudOptions();
  const std::vector<std::string> view = {
      "/clouds/layers/0/coverage=1", "/camera/pitch_deg=90", "/camera/fov_deg=30",       "/camera/width=16",
      "/camera/height=16",           "/clouds/wind_m_s=10",  "/clouds/wind_from_deg=270"};
  auto at = [&](double time_s) {
    std::vector<std::string> v = view;
    v.push_back("/clouds/time_s=" + std::to_string(time_s));
    return test::cloudScene(v);
  };
  o.cloudWeather = std::make_shared<CloudWeatherMap>(discMap({0.0, 0.0}, 3000.0));
  const RenderResult before = test::cloudRenderer().render(at(0.0), o);
  const RenderResult after = test::cloudRenderer().render(at(1000.0), o);
  const double tBefore = meanTransmittance(before.clouds), tAfter = meanTransmittance(after.clouds);
  std::printf("overhead: mean T %.4f at 0 s, %.4f after 1000 s of 10 m/s wind\n", tBefore, tAfter);
  EXPECT_LT(tBefore, 0.5);
  EXPECT_EQ(tAfter, 1.0);

  const double ground = before.view.cameraRadius - 2.0;
  const CloudMedium still = mediumFor(at(0.0), discMap({0.0, 0.0}, 3000.0), ground);
  const CloudMedium moved = mediumFor(at(1000.0), discMap({0.0, 0.0}, 3000.0), ground);
  double worst = 0.0;
  for (double north : {-1500.0, 0.0, 1500.0}) {
    const double then = verticalOpticalDepth(still, ground, 0.0, north);
    const double now = verticalOpticalDepth(moved, ground, 10000.0, north);
    std::printf("column at north %+.0f m: optical depth %.4f overhead at 0 s, %.4f 10 km east at 1000 s\n", north, then,
                now);
    ASSERT_GT(then, 1.0);
    worst = std::max(worst, std::abs(now / then - 1.0));
    EXPECT_EQ(verticalOpticalDepth(moved, ground, 0.0, north), 0.0) << north;
  }
  EXPECT_LT(worst, 0.01);
}

// A camera offset (/clouds/offset_east_m, the viewer's horizontal flight) reads the field from there:
// 10 km east of a 3 km disc the GPU looking straight up sees no cloud, and on the CPU the column 10 km
// west of the camera holds what the column overhead held without the offset (the curvature's few metres
// as in the wind test above).
TEST_F(CloudWeather, TheCameraOffsetSeesTheFieldFromThere) {
  SkyRenderOptions o = test::smallCloudOptions();
  auto at = [&](double east_m) {
    return test::cloudScene({"/clouds/layers/0/coverage=1", "/camera/pitch_deg=90", "/camera/fov_deg=30",
                             "/camera/width=16", "/camera/height=16",
                             "/clouds/offset_east_m=" + std::to_string(east_m)});
  };
  o.cloudWeather = std::make_shared<CloudWeatherMap>(discMap({0.0, 0.0}, 3000.0));
  const RenderResult above = test::cloudRenderer().render(at(0.0), o);
  const RenderResult away = test::cloudRenderer().render(at(10000.0), o);
  const double tAbove = meanTransmittance(above.clouds), tAway = meanTransmittance(away.clouds);
  std::printf("overhead: mean T %.4f above the disc, %.4f 10 km east of it\n", tAbove, tAway);
  EXPECT_LT(tAbove, 0.5);
  EXPECT_EQ(tAway, 1.0);

  const double ground = above.view.cameraRadius - 2.0;
  const CloudMedium here = mediumFor(at(0.0), discMap({0.0, 0.0}, 3000.0), ground);
  const CloudMedium there = mediumFor(at(10000.0), discMap({0.0, 0.0}, 3000.0), ground);
  double worst = 0.0;
  for (double north : {-1500.0, 0.0, 1500.0}) {
    const double overhead = verticalOpticalDepth(here, ground, 0.0, north);
    const double west = verticalOpticalDepth(there, ground, -10000.0, north);
    ASSERT_GT(overhead, 1.0);
    worst = std::max(worst, std::abs(west / overhead - 1.0));
    EXPECT_EQ(verticalOpticalDepth(there, ground, 0.0, north), 0.0) << north;
  }
  EXPECT_LT(worst, 0.01);
}

// The procedural map: deterministic per seed, with clear gaps and fully covered areas.
TEST(CloudWeatherMapTest, ProceduralMapHasGapsAndCover) {
  const CloudWeatherMap a = proceduralCloudWeatherMap(1), b = proceduralCloudWeatherMap(1),
                        c = proceduralCloudWeatherMap(2);
  EXPECT_EQ(a.map.pixels, b.map.pixels);
  EXPECT_NE(a.map.pixels, c.map.pixels);
  int clear = 0, full = 0;
  double mean = 0.0;
  for (size_t i = 0; i < a.map.pixelCount(); ++i) {
    const float v = a.map.pixels[4 * i];
    clear += v == 0.0f;
    full += v == 1.0f;
    mean += v;
  }
  const double n = double(a.map.pixelCount());
  std::printf("procedural map: clear %.3f, full %.3f, mean coverage %.3f\n", clear / n, full / n, mean / n);
  EXPECT_GT(clear / n, 0.05);
  EXPECT_GT(full / n, 0.05);
  // The CPU sampler repeats: u and u + 1 read the same.
  const glm::dvec4 p = a.sample({0.3, 0.7}), q = a.sample({1.3, -0.3});
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(p[k], q[k], 1e-9 * (1.0 + std::abs(p[k])));
}

// The thunderstorm scene (afternoon): its simulated map holds cumulonimbus (type > 0.9, top > 8 km),
// the CPU medium has cloud above 8 km there, and the render is finite and non-negative.
TEST_F(CloudWeather, ThunderstormSceneGrowsCumulonimbus) {
  const Scene s =
      Scene::load(test::sourceDir() / "scenes" / "thunderstorm.json", {"/camera/width=32", "/camera/height=18"});
  SceneWeatherInfo info;
  const CloudWeatherMap map = cloudWeatherMapForScene(s, &info);
  std::printf("thunderstorm: %.1f h simulated in %.0f ms\n", info.simulated_s / 3600.0, info.milliseconds);
  double highestTop = 0.0, anyTop = 0.0, maxType = 0.0, maxCover = 0.0;
  for (size_t i = 0; i < map.map.pixelCount(); ++i) {
    anyTop = std::max(anyTop, double(map.map.pixels[4 * i + 3]));
    maxType = std::max(maxType, double(map.map.pixels[4 * i + 1]));
    maxCover = std::max(maxCover, double(map.map.pixels[4 * i]));
  }
  std::printf("map: highest top %.0f m, largest type %.2f, largest coverage %.2f\n", anyTop, maxType, maxCover);
  glm::dvec2 tallest(0.0);
  for (int row = 0; row < map.map.height; ++row)
    for (int column = 0; column < map.map.width; ++column) {
      const float* px = map.map.at(column, row);
      if (px[1] > 0.9f && px[0] > 0.5f && px[3] > highestTop) {
        highestTop = px[3];
        tallest = {((column + 0.5) / map.map.width - 0.5) * map.width_m,
                   (0.5 - (row + 0.5) / map.map.height) * map.height_m};
      }
    }
  std::printf("tallest cumulonimbus column: top %.0f m at (%.0f, %.0f) m\n", highestTop, tallest.x, tallest.y);
  ASSERT_GT(highestTop, 8000.0);

  SkyRenderOptions o = test::smallCloudOptions();
  const RenderResult r = test::cloudRenderer().render(s, o);
  for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
  for (float v : r.clouds.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);

  // Cloud above 8 km somewhere within 2 km of the tallest column (the shape noise leaves holes).
  const double ground = r.view.cameraRadius - s.number("/camera/height_above_ground_m");
  const CloudMedium medium = mediumFor(s, map, ground);
  double high = 0.0;
  for (size_t layer = 0; layer < medium.layers().size(); ++layer)
    for (double de = -2000.0; de <= 2000.0; de += 250.0)
      for (double dn = -2000.0; dn <= 2000.0; dn += 250.0)
        for (double z = 8000.0; z < highestTop; z += 250.0) {
          const double e = tallest.x + de + map.skew.x * z, n = tallest.y + dn + map.skew.y * z;
          const glm::dvec3 d = glm::normalize(glm::dvec3(std::tan(e / ground), std::tan(n / ground), 1.0));
          high = std::max(high, medium.extinction(layer, d * (ground + z)));
        }
  std::printf("largest extinction above 8 km near it: %.4f 1/m\n", high);
  EXPECT_GT(high, 0.0);
}

// A time-lapse's next frame runs the simulation on from the last run's checkpoint (the model at its
// last whole step) instead of from midnight, and gets the same map bit for bit as a run from midnight.
// 13:30 UTC at 7.98 deg E is 50515 s after the solar midnight, not a whole number of 60 s steps: the
// map there interpolates the steps around it. The frames after it are 90 s and 1 h later; an earlier
// time than the checkpoint runs from midnight again. Between steps the map is continuous: 1/30 s later
// it differs by a 1800th of a step's change (measured 2e-5 in coverage; the shortened last step that
// the first version ran changed it by up to 0.035).
TEST(SceneWeather, ATimeLapseContinuesTheSimulationBitForBit) {
  auto at = [](const std::string& utc) {
    return Scene::load(test::sourceDir() / "scenes" / "thunderstorm.json",
                       {"/weather/grid/cells_x=64", "/weather/grid/cells_y=64", "/time/utc=" + utc});
  };
  auto largestChange = [](const CloudWeatherMap& a, const CloudWeatherMap& b) {
    double worst = 0.0;
    for (size_t i = 0; i < a.map.pixels.size(); i += 4)
      worst = std::max(worst, double(std::abs(a.map.pixels[i] - b.map.pixels[i])));
    return worst;
  };
  clearSceneWeatherCache();
  SceneWeatherInfo info;
  const CloudWeatherMap first = cloudWeatherMapForScene(at("2026-06-21T13:30:00Z"), &info);
  EXPECT_FALSE(info.continued);
  EXPECT_GE(info.simulated_s - info.stepped_s, 0.0);
  EXPECT_LT(info.simulated_s - info.stepped_s, 60.0);
  const CloudWeatherMap frameLater = cloudWeatherMapForScene(at("2026-06-21T13:30:00.033Z"), &info);
  EXPECT_TRUE(info.continued);
  std::printf("1/30 s later: largest coverage change %.2g\n", largestChange(first, frameLater));
  EXPECT_LT(largestChange(first, frameLater), 1e-3);
  EXPECT_GT(largestChange(first, frameLater), 0.0);
  for (const std::string utc : {"2026-06-21T13:31:30Z", "2026-06-21T14:31:30Z"}) {
    const CloudWeatherMap continued = cloudWeatherMapForScene(at(utc), &info);
    std::printf("%s: continued %d, %.0f s of %.0f s run in %.0f ms\n", utc.c_str(), int(info.continued), info.stepped_s,
                info.simulated_s, info.milliseconds);
    EXPECT_TRUE(info.continued);
    EXPECT_LT(info.stepped_s, 3600.0 + 120.0);
    clearSceneWeatherCache();
    const CloudWeatherMap fresh = cloudWeatherMapForScene(at(utc), &info);
    EXPECT_FALSE(info.continued);
    ASSERT_EQ(continued.map.pixels.size(), fresh.map.pixels.size());
    EXPECT_EQ(continued.map.pixels, fresh.map.pixels) << utc << ": the continued map differs from a run from midnight";
    EXPECT_NE(continued.map.pixels, first.map.pixels) << utc << ": the weather did not move";
  }
  cloudWeatherMapForScene(at("2026-06-21T12:00:00Z"), &info);
  EXPECT_FALSE(info.continued);
}

// The map's type picks each column's height profiles (common/cloud_weather.glsl): stratiform at 0
// (stratocumulus in a stratocumulus layer, else stratus), cumulus at 1/3 and 2/3, cumulonimbus with the
// layer's anvil at 1, linear blends between; cirrus layers and maps without types keep the layer's own.
TEST(CloudWeatherType, TheMapTypePicksTheHeightProfiles) {
  shared::CloudLayer layer{};
  layer.bottom_radius = 6360000.0 + 1000.0;
  layer.top_radius = 6360000.0 + 8000.0;
  layer.coverage = 0.6;
  layer.anvil = 0.8;
  auto column = [&](int kind, double type) {
    shared::CloudLayer l = layer;
    l.kind = kind;
    bool empty = true;
    const shared::CloudLayer c =
        shared::cloudColumnLayer(l, glm::dvec4(1.0, type, 0.0, shared::kCloudWeatherNoTop), 6360000.0, empty);
    EXPECT_FALSE(empty);
    return c;
  };
  auto profiles = [&](int kind, double anvil) {
    return [=](double ph) {
      return glm::dvec2(shared::cloudShapeProfile(kind, ph, layer.coverage, anvil),
                        shared::cloudDensityProfile(kind, ph, anvil));
    };
  };
  auto blended = [&](const shared::CloudLayer& c) {
    return [=](double ph) {
      return glm::dvec2(shared::cloudLayerShapeProfile(c, ph), shared::cloudLayerDensityProfile(c, ph));
    };
  };
  const auto stratus = profiles(shared::kCloudStratus, 0.0), stratocumulus = profiles(shared::kCloudStratocumulus, 0.0);
  const auto cumulus = profiles(shared::kCloudCumulus, 0.0), cirrus = profiles(shared::kCloudCirrus, 0.0);
  const auto cumulonimbus = profiles(shared::kCloudCumulonimbus, layer.anvil);
  const auto half = profiles(shared::kCloudCumulonimbus, 0.5 * layer.anvil);
  for (double ph = 0.0; ph <= 1.0; ph += 1.0 / 64.0) {
    for (int kind : {shared::kCloudStratus, shared::kCloudCumulus, shared::kCloudCumulonimbus}) {
      EXPECT_EQ(blended(column(kind, 0.0))(ph), stratus(ph)) << kind << " " << ph;
      EXPECT_EQ(blended(column(kind, 1.0 / 3.0))(ph), cumulus(ph)) << kind << " " << ph;
      EXPECT_EQ(blended(column(kind, 2.0 / 3.0))(ph), cumulus(ph)) << kind << " " << ph;
      EXPECT_EQ(blended(column(kind, 1.0))(ph), cumulonimbus(ph)) << kind << " " << ph;
      const glm::dvec2 mid = blended(column(kind, 1.0 / 6.0))(ph), mean = 0.5 * (stratus(ph) + cumulus(ph));
      EXPECT_NEAR(mid.x, mean.x, 1e-12) << kind << " " << ph;
      EXPECT_NEAR(mid.y, mean.y, 1e-12) << kind << " " << ph;
      const glm::dvec2 anvil = blended(column(kind, 5.0 / 6.0))(ph);
      EXPECT_NEAR(anvil.x, half(ph).x, 1e-12) << kind << " " << ph;
      EXPECT_NEAR(anvil.y, half(ph).y, 1e-12) << kind << " " << ph;
    }
    EXPECT_EQ(blended(column(shared::kCloudStratocumulus, 0.0))(ph), stratocumulus(ph)) << ph;
    EXPECT_EQ(blended(column(shared::kCloudCirrus, 0.0))(ph), cirrus(ph)) << ph;
    EXPECT_EQ(blended(column(shared::kCloudCirrus, 1.0))(ph), cirrus(ph)) << ph;
    EXPECT_EQ(blended(column(shared::kCloudStratocumulus, shared::kCloudWeatherLayerType))(ph), stratocumulus(ph))
        << ph;
    EXPECT_EQ(blended(column(shared::kCloudCumulonimbus, shared::kCloudWeatherLayerType))(ph), cumulonimbus(ph)) << ph;
  }
  // The procedural map has no types.
  const CloudWeatherMap procedural = proceduralCloudWeatherMap(1, 16);
  for (size_t i = 0; i < procedural.map.pixelCount(); ++i)
    ASSERT_EQ(procedural.map.pixels[4 * i + 1], float(shared::kCloudWeatherLayerType));
}

// On the GPU: a cumulonimbus layer under a map of stratus type looks, straight up, as a stratus layer
// of the same extinction (0.0024 1/m) under a map without types: the same transmittance; under cumulus
// type it is another cloud.
TEST_F(CloudWeather, TheMapTypeShapesTheGpuColumnsToo) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.jitter = false;
  const std::vector<std::string> view = {"/camera/pitch_deg=90", "/camera/fov_deg=30", "/camera/width=16",
                                         "/camera/height=16"};
  auto meanT = [&](const std::string& layer, float type) {
    o.cloudWeather = std::make_shared<CloudWeatherMap>(
        uniformCloudWeatherMap(glm::vec4(1.0f, type, 0.0f, float(shared::kCloudWeatherNoTop))));
    return meanTransmittance(
        test::cloudRenderer().render(test::cloudScene(view, test::cloudSceneText(layer)), o).clouds);
  };
  const std::string cb =
      R"({"kind": "cumulonimbus", "bottom_m": 1500, "top_m": 2300, "coverage": 0.7, "extinction_scale": 0.02})";
  const std::string st =
      R"({"kind": "stratus", "bottom_m": 1500, "top_m": 2300, "coverage": 0.7, "extinction_scale": 0.048})";
  const double cbAsStratus = meanT(cb, 0.0f), stratus = meanT(st, float(shared::kCloudWeatherLayerType));
  const double cbAsCumulus = meanT(cb, 1.0f / 3.0f);
  std::printf(
      "mean T looking up: cumulonimbus layer, stratus type %.5f; stratus layer %.5f; cumulonimbus layer, cumulus type "
      "%.5f\n",
      cbAsStratus, stratus, cbAsCumulus);
  EXPECT_NEAR(cbAsStratus, stratus, 1e-4);
  EXPECT_GT(std::abs(cbAsCumulus - stratus), 0.02);
}

// coverageReach (the empty-space test's map for sharp coverage): one covered texel of a 64^2 map of
// 200 m texels reaches every texel whose centre lies within the radius plus one texel in x and y (a
// square window, wrapping at the edges), and no other; a bilinear read between texel centres within
// the radius of the covered point is positive.
TEST(CloudWeatherReach, OneCoveredTexelReachesItsWindow) {
  CloudWeatherMap m = uniformCloudWeatherMap(glm::vec4(0.0f, 0.0f, 0.0f, 5000.0f), 64);
  m.width_m = m.height_m = 64 * 200.0;
  m.map.at(1, 30)[0] = 0.7f;
  const Image reach = coverageReach(m, 1000.0);  // 5 texels + 1
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const int dx = std::min(std::abs(x - 1), 64 - std::abs(x - 1)), dy = std::abs(y - 30);
      EXPECT_EQ(reach.at(x, y)[0], dx <= 6 && dy <= 6 ? 0.7f : 0.0f) << x << " " << y;
    }
  EXPECT_EQ(reach.at(60, 30)[0], 0.7f);  // wraps: 5 texels west of column 1
  // Any read point within 1000 m of the covered texel's centre: its four bilinear neighbours all hold it.
  CloudWeatherMap r = m;
  r.map = Image(64, 64, 4);
  for (size_t i = 0; i < reach.pixelCount(); ++i) r.map.pixels[4 * i] = reach.pixels[i];
  const glm::dvec2 centre((1 + 0.5) / 64.0, (30 + 0.5) / 64.0);
  for (double a = 0.0; a < 6.283; a += 0.1)
    for (double d : {0.0, 500.0, 999.0}) {
      const glm::dvec2 uv = centre + d / (64 * 200.0) * glm::dvec2(std::cos(a), std::sin(a));
      EXPECT_NEAR(r.sample(uv).x, 0.7, 1e-6) << a << " " << d;
    }
}

}  // namespace
}  // namespace firmament
