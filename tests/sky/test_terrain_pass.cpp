// The terrain in the frame (sky/terrain_pass.h) on the GPU: the float ray cast against the CPU walk
// (terrain/terrain_intersection.h), a flat terrain at the ground sphere's height against the sky's own
// ground, the cloud march stopping at the terrain, the sky the terrain hides against a closed form, and
// finite pixels for extreme cameras and suns.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "common/geometry.glsl"
#include "core/color.h"
#include "sky/scene_view.h"
#include "sky/sky_renderer.h"
#include "terrain/height_map_file.h"
#include "terrain/terrain_intersection.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

class TerrainPassTest : public test::GpuTest {
 protected:
  static SkyRenderer& renderer() {
    static SkyRenderer r(context());
    return r;
  }
  static Scene scene(const std::string& json, std::vector<std::string> overrides = {}) {
    return Scene::parse(json, "<test>", overrides);
  }
  // The ray from `origin` along `d` (unit) as the GPU cast takes it ((origin, r), (d, mu)) and as the
  // CPU walk takes it, from the same floats.
  static void addRay(const glm::vec3& origin, const glm::vec3& d, std::vector<glm::vec4>& gpu,
                     std::vector<terrain::TerrainRay>& cpu) {
    double r = 0.0, mu = 0.0;
    shared::rayRadiusAndCosine(glm::dvec3(origin), glm::dvec3(d), r, mu);
    gpu.push_back(glm::vec4(origin, float(r)));
    gpu.push_back(glm::vec4(d, float(mu)));
    terrain::TerrainRay ray;
    ray.origin = glm::dvec3(origin);
    ray.direction = glm::dvec3(d);
    cpu.push_back(ray);
  }
  static size_t nonFinite(const Image& image) {
    size_t bad = 0;
    for (float v : image.pixels) bad += !(std::isfinite(v) && v >= 0.0f);
    return bad;
  }
};

constexpr const char* kAlpine = R"({
  "location": { "latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 1200 },
  "time": { "utc": "2026-06-21T15:30:00Z" },
  "camera": { "height_above_ground_m": 2, "yaw_deg": 250, "pitch_deg": 4, "fov_deg": 75, "width": 48, "height": 27 },
  "terrain": { "style": "alpine", "seed": 3, "resolution": 129, "extent_m": 10000 }
})";

// The GPU's float walk finds the CPU's double hits: 3000 rays from 2 m, 300 m, 3 km, 30 km and 1e8 m
// above the location's ground, towards the field, the horizon and the sky. Origins and directions are
// the floats the GPU is given, so the two differ by float arithmetic alone. Measured (lavapipe): 1703
// hits, the largest difference 4.7 % of the tolerance, 0 rays that hit on one side only. Tolerance
// 1 m + 1e-4 t; up to 3 rays may disagree about hitting (a graze that float rounding decides).
TEST_F(TerrainPassTest, GpuCastMatchesTheCpuWalk) {
  TerrainPass pass(context());
  const Scene s = scene(kAlpine);
  const double R = AtmosphereSettings::fromScene(s).bottomRadius;
  pass.prepare(s, R);
  const terrain::HeightField& field = pass.resolved().field;
  terrain::TerrainIntersector cpu(field, R);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<glm::vec4> rays;
  std::vector<terrain::TerrainRay> cpuRays;
  const double ground = pass.groundUnderCamera();
  for (double height : {2.0, 300.0, 3000.0, 30000.0, 1.0e8}) {
    for (int k = 0; k < 600; ++k) {
      const double azimuth = 2.0 * 3.14159265358979 * unit(random);
      // Elevations from looking straight down to 30 degrees up, most near the horizon.
      const double elevation = -1.5707 * std::pow(unit(random), 3.0) + 0.52 * std::pow(unit(random), 3.0);
      const glm::vec3 origin(float(200.0 * (unit(random) - 0.5)), float(200.0 * (unit(random) - 0.5)),
                             float(R + ground + height));
      glm::dvec3 direction(std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth),
                           std::sin(elevation));
      if (height > 1e6) direction = glm::normalize(glm::dvec3(0.3 * direction.x, 0.3 * direction.y, -1.0));
      const glm::vec3 d = glm::vec3(glm::normalize(direction));
      addRay(origin, d, rays, cpuRays);
    }
  }
  const std::vector<glm::vec4> gpu = pass.castRays(rays);
  int hits = 0, disagree = 0;
  double worst = 0.0;
  for (size_t i = 0; i < cpuRays.size(); ++i) {
    const terrain::TerrainHit c = cpu.intersect(cpuRays[i]);
    const float t = gpu[2 * i].w;
    const bool gpuHit = t < 1e29f;
    ASSERT_TRUE(std::isfinite(t)) << "ray " << i;
    if (gpuHit != c.hit) {
      // Only a graze: the CPU's ray passes within 1 m of the surface (or the GPU's hit is at such a graze).
      ++disagree;
      continue;
    }
    if (!c.hit) continue;
    ++hits;
    const double error = std::abs(double(t) - c.t);
    worst = std::max(worst, error / (1.0 + 1e-4 * c.t));
    EXPECT_LE(error, 1.0 + 1e-4 * c.t) << "ray " << i << ": CPU t " << c.t << " GPU t " << t;
    const glm::dvec3 n = glm::dvec3(gpu[2 * i]);
    EXPECT_GT(glm::dot(n, c.normal), 0.99) << "ray " << i;
  }
  EXPECT_GT(hits, 1500);
  EXPECT_LE(disagree, 3) << "rays that hit on one side only";
  std::printf("GPU vs CPU: %d hits, %d disagree, worst %.4g of the tolerance\n", hits, disagree, worst);
}

// A flat terrain at the ground sphere's height (location at sea level, vertical_scale 0) with the
// sphere's albedo is the sky's own ground: the per-pixel sky march's albedo / pi (E_sun mu_s T_sun +
// E_sky) through the same air, L = T_air L_ground + L_air. Measured (lavapipe): largest relative
// difference of a pixel's luminance 3e-7 from 2 m, 6e-7 from 8 km (float rounding of the hit
// distance); tolerance 1e-4.
TEST_F(TerrainPassTest, FlatTerrainAtSeaLevelIsTheSkysGround) {
  const std::string base = R"({
    "location": { "latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 0 },
    "sun": { "zenith_deg": 50, "azimuth_deg": 200 },
    "camera": { "height_above_ground_m": 2, "yaw_deg": 250, "pitch_deg": -20, "fov_deg": 90, "width": 40, "height": 24 },
    "atmosphere": { "ground_albedo": 0.25 })";
  const std::string terrain = R"(,
    "terrain": { "style": "plains", "vertical_scale": 0, "resolution": 33, "extent_m": 4000,
                 "albedo": { "rock": [0.25, 0.25, 0.25], "vegetation": [0.25, 0.25, 0.25], "snow": [0.25, 0.25, 0.25] } })";
  SkyRenderOptions options;
  options.method = SkyMethod::PerPixel;
  for (const char* height : {"2", "8000"}) {
    const std::vector<std::string> set = {std::string("/camera/height_above_ground_m=") + height};
    const RenderResult sphere = renderer().render(scene(base + "}", set), options);
    const RenderResult flat = renderer().render(scene(base + terrain + "}", set), options);
    ASSERT_EQ(sphere.image.pixels.size(), flat.image.pixels.size());
    double worst = 0.0;
    size_t ground = 0;
    for (size_t i = 0; i < sphere.image.pixelCount(); ++i) {
      const double a = luminanceRec709(sphere.image.pixels.data() + 4 * i);
      const double b = luminanceRec709(flat.image.pixels.data() + 4 * i);
      worst = std::max(worst, std::abs(b - a) / std::max(a, 1e-6));
      for (int c = 0; c < 3; ++c) {
        const double x = sphere.image.pixels[4 * i + c], y = flat.image.pixels[4 * i + c];
        EXPECT_NEAR(y, x, 1e-4 * std::max(x, 1.0)) << "pixel " << i << " channel " << c << " camera " << height;
      }
    }
    const std::vector<float> depth = renderer().terrainPass()->depth().download<float>();
    for (float t : depth) ground += t < 1e29f;
    EXPECT_GT(ground, sphere.image.pixelCount() / 3) << "camera " << height;
    EXPECT_LT(worst, 1e-4) << "camera " << height;
    std::printf("flat terrain vs sphere, camera %s m: worst relative luminance difference %.3g\n", height, worst);
  }
}

// Mountains in front of clouds: a deck at 2000-3000 m over an alpine valley at 1200 m. Wherever the view
// ray meets the terrain before it reaches the deck's base, the cloud march has nothing to march: the
// clouds' transmittance there is exactly 1 and their light 0. Without the terrain's depth the march
// went on behind the mountain (this test then fails on hundreds of pixels). The deck shows in the sky
// above the mountains.
TEST_F(TerrainPassTest, CloudsStopAtTheTerrain) {
  const Scene s = scene(R"({
    "location": { "latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 1200 },
    "sun": { "zenith_deg": 40, "azimuth_deg": 200 },
    "camera": { "height_above_ground_m": 2, "yaw_deg": 250, "pitch_deg": 6, "fov_deg": 80, "width": 64, "height": 36 },
    "terrain": { "style": "alpine", "seed": 3, "resolution": 257, "extent_m": 20000 },
    "clouds": { "layers": [ { "kind": "stratocumulus", "bottom_m": 2000, "top_m": 3000, "coverage": 0.9 } ] }
  })");
  SkyRenderOptions options;
  options.cloudNoise.shapeSize = 32;
  options.cloudNoise.detailSize = 16;
  const RenderResult r = renderer().render(s, options);
  ASSERT_FALSE(r.clouds.pixels.empty());
  EXPECT_EQ(nonFinite(r.image), 0u);
  const std::vector<float> depth = renderer().terrainPass()->depth().download<float>();
  const double R = r.view.atmosphere.bottomRadius;
  const double base = R + 2000.0;
  int before = 0, cloudInFront = 0;  // cloudInFront: pixels with cloud
  for (int y = 0; y < r.view.camera.height; ++y)
    for (int x = 0; x < r.view.camera.width; ++x) {
      const size_t i = size_t(y) * size_t(r.view.camera.width) + size_t(x);
      if (!(depth[i] < 1e29f)) continue;
      bool valid = false;
      const glm::dvec3 d = shared::cameraRayDirection(r.view.camera, glm::dvec2(x + 0.5, y + 0.5), valid);
      double near = 0.0, far = 0.0;
      const double rc = r.view.cameraRadius;
      const double mu = d.z;
      // The camera is below the base: the ray reaches it at the far root (if at all).
      const bool reaches = shared::raySphereRoots(rc, mu, base, near, far) && far > 0.0;
      if (!reaches || depth[i] < far - 1.0) {
        ++before;
        EXPECT_EQ(r.clouds.pixels[4 * i + 3], 1.0f) << "pixel " << x << "," << y;
        EXPECT_EQ(r.clouds.pixels[4 * i + 0], 0.0f) << "pixel " << x << "," << y;
      }
    }
  for (size_t i = 0; i < r.clouds.pixelCount(); ++i) cloudInFront += r.clouds.pixels[4 * i + 3] < 0.99f;
  std::printf("clouds: %d terrain pixels before the base, %d pixels with cloud\n", before, cloudInFront);
  EXPECT_GT(before, 100);
  EXPECT_GT(cloudInFront, 0);
}

// The share of the sky the cast gives the ground (hits' fourth value of the second vec4) on a plain in
// front of a straight cliff 400 m high (a height map, 10 m samples), against the closed form of a
// horizontal point that sees the cliff's top at elevation alpha straight ahead: (1 + cos alpha) / 2
// (tests/terrain/test_horizon_map.cpp derives it), tan(alpha) = (400 - d^2 / 2R) / d at distance d from
// the top edge, over the plain's pixels 150-1400 m from it (alpha 16-69 deg). Measured (lavapipe, 448
// pixels on the plain): the horizon map within 0.0037 per pixel (its 16 sectors and the bilinear
// horizons between 20 m texels: the 401-sample field strided to 201; tolerance 0.01); 32 rays per pixel:
// mean over the pixels +0.0020 (tolerance 0.02: their binomial noise, 0.07 a pixel, over 448 pixels).
TEST_F(TerrainPassTest, SkyShareBeforeACliffIsOnePlusCosineOverTwo) {
  const std::filesystem::path dir = test::scratchDir("terrain_pass_cliff");
  terrain::HeightField map(401, 3, -2000.0, -2000.0, 10.0, 2000.0);
  for (int j = 0; j < map.ny; ++j)
    for (int i = 0; i < map.nx; ++i) map.at(i, j) = map.xAt(i) >= 1700.0 ? 400.0f : 0.0f;
  terrain::writeHeightFieldExr(dir / "cliff.exr", map);
  const Scene s = scene(R"({
    "location": { "latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 0 },
    "sun": { "zenith_deg": 40, "azimuth_deg": 200 },
    "camera": { "height_above_ground_m": 600, "yaw_deg": 90, "pitch_deg": -30, "fov_deg": 50, "width": 32, "height": 18 },
    "terrain": { "kind": "heightmap", "file": ")" +
                        (dir / "cliff.exr").string() + R"(", "extent_m": 4000, "resolution": 401,
                 "heightmap": { "width_m": 4000, "length_m": 4000 } }
  })");
  const double R = AtmosphereSettings::fromScene(s).bottomRadius;
  auto shares = [&](TerrainSkyOcclusion mode, std::vector<double>& got, std::vector<double>& expected) {
    SkyRenderOptions o;
    o.luts.spectralSamples = 3;
    o.terrain.skyOcclusion = mode;
    o.terrain.occlusionRays = 32;
    const RenderResult r = renderer().render(s, o);
    const terrain::HeightField& f = renderer().terrainPass()->resolved().field;
    int topIndex = 0;
    while (topIndex < f.nx && f.at(topIndex, f.ny / 2) < 399.99f) ++topIndex;
    const double top = f.xAt(topIndex);
    const std::vector<float> hits = renderer().terrainPass()->hits().download<float>();
    const std::vector<float> depth = renderer().terrainPass()->depth().download<float>();
    const glm::dvec3 camera(0.0, 0.0, double(float(r.view.cameraRadius)));
    got.clear(), expected.clear();
    for (int y = 0; y < r.view.camera.height; ++y)
      for (int x = 0; x < r.view.camera.width; ++x) {
        const size_t i = size_t(y) * size_t(r.view.camera.width) + size_t(x);
        bool valid = false;
        const glm::dvec3 d = shared::cameraRayDirection(r.view.camera, glm::dvec2(x + 0.5, y + 0.5), valid);
        if (!valid || !(depth[i] < 1e29f) || hits[12 * i + 6] > 0.01f) continue;
        const glm::dvec3 p = camera + d * double(depth[i]);
        const double distance = top - R * p.x / p.z;
        if (distance < 150.0 || distance > 1400.0 || std::abs(R * p.y / p.z) > 1000.0) continue;
        const double alpha = std::atan((400.0 - 0.5 * distance * distance / R) / distance);
        got.push_back(hits[12 * i + 7]);
        expected.push_back(0.5 * (1.0 + std::cos(alpha)));
      }
  };
  std::vector<double> got, expected;
  shares(TerrainSkyOcclusion::HorizonMap, got, expected);
  ASSERT_GT(got.size(), 200u);
  double worst = 0.0;
  for (size_t k = 0; k < got.size(); ++k) {
    worst = std::max(worst, std::abs(got[k] - expected[k]));
    EXPECT_NEAR(got[k], expected[k], 0.01) << "pixel " << k;
  }
  shares(TerrainSkyOcclusion::Rays, got, expected);
  double mean = 0.0;
  for (size_t k = 0; k < got.size(); ++k) mean += (got[k] - expected[k]) / double(got.size());
  EXPECT_NEAR(mean, 0.0, 0.02);
  std::printf("sky share before a cliff: %zu pixels, horizon map within %.4f, 32 rays mean %+.4f\n", got.size(), worst,
              mean);
}

// No NaN, no Inf, no negative radiance: cameras under, on and far above the terrain, a grazing and a
// set sun, vertical cliffs (canyon terraces), with clouds over them too.
TEST_F(TerrainPassTest, ExtremeCamerasAndSunsAreFinite) {
  for (const char* height : {"-200", "0", "1", "5000", "1000000", "100000000"})
    for (const char* zenith : {"30", "89.9", "91"}) {
      const RenderResult r = renderer().render(
          scene(kAlpine, {std::string("/camera/height_above_ground_m=") + height,
                          std::string("/sun/zenith_deg=") + zenith, "/sun/azimuth_deg=120", "/camera/pitch_deg=-30",
                          "/camera/projection=equirectangular", "/camera/width=32", "/camera/height=16"}));
      EXPECT_EQ(nonFinite(r.image), 0u) << "camera " << height << " sun zenith " << zenith;
    }
  for (const char* zenith : {"60", "89.5"}) {
    const RenderResult r = renderer().render(scene(
        kAlpine, {"/terrain/style=\"canyon\"", "/terrain/vertical_scale=4", std::string("/sun/zenith_deg=") + zenith,
                  "/sun/azimuth_deg=40", "/camera/pitch_deg=-10", "/camera/width=48", "/camera/height=27"}));
    EXPECT_EQ(nonFinite(r.image), 0u) << "canyon, sun zenith " << zenith;
  }
}

TEST_F(TerrainPassTest, PlanListsTheTerrainPassesOnlyWithATerrainSection) {
  const RenderPlan with = planRender(scene(kAlpine));
  EXPECT_TRUE(with.has("terrain/cast_terrain"));
  EXPECT_TRUE(with.has("terrain/shade_terrain"));
  const RenderPlan without = planRender(scene("{}"));
  EXPECT_FALSE(without.has("terrain/cast_terrain"));
  EXPECT_FALSE(without.has("terrain/shade_terrain"));
}

// The default scene's view rays where the image crosses due west (a rising ray with d.y ~ 0 never
// reaches the grid lines north of the camera: terrain_geometry.glsl, terrainCrossingX). The walk once
// took those lines' negative crossings as "now" and hit the terrain kilometres away at t = 0: dark
// green pixels in the clouds. From 700 m above the ground nothing lies nearer than 700 m; the GPU and
// the CPU walks agree on every ray.
TEST_F(TerrainPassTest, DefaultViewRaysAlongAGridLineHitNothingAtTheCamera) {
  TerrainPass pass(context());
  const Scene s = Scene::parse(defaultSceneText(), "<default>");
  const double R = AtmosphereSettings::fromScene(s).bottomRadius;
  pass.prepare(s, R);
  terrain::TerrainIntersector cpu(pass.resolved().field, R);
  const SceneView view = makeSceneView(s);
  const glm::vec3 o(0.0f, 0.0f, float(view.cameraRadius));
  std::vector<glm::vec4> rays;
  std::vector<terrain::TerrainRay> cpuRays;
  for (int y = 0; y < 120; ++y)
    for (int x = 690; x < 730; ++x) {
      bool valid = false;
      const glm::vec3 d = shared::cameraRayDirection(view.camera, glm::vec2(x + 0.5f, y + 0.5f), valid);
      ASSERT_TRUE(valid);
      addRay(o, d, rays, cpuRays);
    }
  const std::vector<glm::vec4> gpu = pass.castRays(rays);
  int nearCamera = 0, disagree = 0, hits = 0;
  for (size_t i = 0; i < cpuRays.size(); ++i) {
    const terrain::TerrainHit c = cpu.intersect(cpuRays[i]);
    const float t = gpu[2 * i].w;
    nearCamera += (t < 600.0f) + (c.hit && c.t < 600.0);
    disagree += (t < 1e29f) != c.hit;
    hits += c.hit;
  }
  EXPECT_EQ(nearCamera, 0);
  EXPECT_LE(disagree, 3);
  std::printf("%zu rays, %d hit, %d disagree\n", cpuRays.size(), hits, disagree);
}

// Penumbra: a flat ground 5 km under a hand-made Beer shadow map of a slab that ends along x = 0 (opaque,
// tau 20, for x < 0; clear beyond), the sun at the zenith, seen straight down from 200 m over 160 pixels
// (0.67 m each). The shadow's edge on the ground is the sun's disc (radius a = 0.265 deg) occulted by the
// edge: the visible share of a uniform disc F(u) = 1 - (acos u - u sqrt(1 - u^2)) / pi, u = x / (h tan a),
// 0 below x = -h tan a, 1 above h tan a: a penumbra 2 h tan a = 46.3 m wide, F = 1/4 and 3/4 at
// u = -+0.404 (40.4 % of the width apart). Measured (lavapipe): 25-75 % width 16.7 m against 18.7 m
// (-10 %: 8 lookups over the disc), its middle 2.4 m from the hard edge's; without the penumbra the
// 25-75 % width is 0.4 m (the opaque texel's bilinear blend). Tolerances: the width within 15 %, the
// middle within one texel (3.9 m) of the hard edge's, fully dark below -h tan a - 4 m and fully lit
// above h tan a + 4 m.
TEST_F(TerrainPassTest, CloudShadowEdgeIsTheSunsDiscPenumbra) {
  const Scene s = scene(R"({
    "location": { "latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 500 },
    "sun": { "zenith_deg": 0, "azimuth_deg": 180 },
    "camera": { "height_above_ground_m": 200, "yaw_deg": 0, "pitch_deg": -90, "fov_deg": 30, "width": 160, "height": 4 },
    "terrain": { "style": "plains", "vertical_scale": 0, "resolution": 33, "extent_m": 4000 }
  })");
  const double R = AtmosphereSettings::fromScene(s).bottomRadius;
  TerrainPass pass(context());
  pass.prepare(s, R);
  const SceneView sv = makeSceneView(s);
  const int size = 512;
  const double extent = 2000.0, h = 5000.0, tanA = std::tan(0.265 * 3.14159265358979 / 180.0);
  std::vector<float> texels(size_t(size) * size * 4, 0.0f);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size / 2; ++i) {
      float* t = &texels[(size_t(j) * size + size_t(i)) * 4];
      t[0] = 0.0f, t[1] = 1.0f, t[2] = 20.0f;  // front at the start plane, opaque beyond
    }
  gpu::Image map(context(), {uint32_t(size), uint32_t(size), 1, gpu::Format::RGBA32F, false, true, "test shadow map"});
  map.upload(texels.data(), texels.size() * sizeof(float));
  TerrainCloudShadow shadow;
  shadow.map = &map;
  shadow.centre = glm::dvec3(0.0, 0.0, R + 500.0 + h);
  shadow.u = glm::dvec3(1.0, 0.0, 0.0);
  shadow.v = glm::dvec3(0.0, 1.0, 0.0);
  shadow.extent_m = extent;
  shadow.start_m = 1000.0;
  TerrainPassView view;
  view.cameraPosition = glm::dvec3(0.0, 0.0, double(float(R + 500.0 + 200.0)));
  view.sunDirection = glm::dvec3(0.0, 0.0, 1.0);
  view.camera = sv.camera;
  const gpu::TileDispatch tiles =
      gpu::tileDispatch(context(), uint32_t(view.camera.width), uint32_t(view.camera.height));
  auto edge = [&](double sunRadius, std::vector<double>& xs, std::vector<double>& ts) {
    view.sunAngularRadius = sunRadius;
    gpu::CommandList commands(context());
    pass.recordCast(view, tiles, commands, &shadow);
    commands.submitAndWait();
    const std::vector<float> hits = pass.hits().download<float>();
    const std::vector<float> depth = pass.depth().download<float>();
    xs.clear(), ts.clear();
    const int row = 1;
    for (int x = 0; x < view.camera.width; ++x) {
      const size_t i = size_t(row) * size_t(view.camera.width) + size_t(x);
      bool valid = false;
      const glm::dvec3 d = shared::cameraRayDirection(view.camera, glm::dvec2(x + 0.5, row + 0.5), valid);
      ASSERT_TRUE(depth[i] < 1e29f);
      xs.push_back(view.cameraPosition.x + d.x * depth[i]);
      ts.push_back(std::exp(-double(hits[12 * i + 5])));
    }
  };
  // Where the transmittance first rises through `level` (x increasing), linearly between pixels.
  auto crossing = [](const std::vector<double>& xs, const std::vector<double>& ts, double level) {
    for (size_t k = 1; k < xs.size(); ++k)
      if (ts[k - 1] < level && ts[k] >= level)
        return xs[k - 1] + (level - ts[k - 1]) / (ts[k] - ts[k - 1]) * (xs[k] - xs[k - 1]);
    return std::nan("");
  };
  std::vector<double> xs, ts;
  edge(0.265 * 3.14159265358979 / 180.0, xs, ts);
  ASSERT_LT(xs.front(), -30.0);
  ASSERT_GT(xs.back(), 30.0);
  const double x25 = crossing(xs, ts, 0.25), x50 = crossing(xs, ts, 0.5), x75 = crossing(xs, ts, 0.75);
  const double expected = 2.0 * 0.404 * h * tanA;
  std::printf("penumbra: 25-75 %% width %.2f m (expected %.2f), middle %.2f m, full width 2 h tan a = %.1f m\n",
              x75 - x25, expected, x50, 2.0 * h * tanA);
  EXPECT_NEAR(x75 - x25, expected, 0.15 * expected);
  for (size_t k = 0; k < xs.size(); ++k) {
    if (xs[k] < -h * tanA - 4.0) {
      EXPECT_LT(ts[k], 1e-6) << "x " << xs[k];
    }
    if (xs[k] > h * tanA + 4.0) {
      EXPECT_GT(ts[k], 1.0 - 1e-6) << "x " << xs[k];
    }
  }
  // Without the penumbra: the map's own texel.
  edge(0.0, xs, ts);
  const double hard = crossing(xs, ts, 0.75) - crossing(xs, ts, 0.25), hardMiddle = crossing(xs, ts, 0.5);
  std::printf("without the penumbra: 25-75 %% width %.2f m, middle %.2f m\n", hard, hardMiddle);
  EXPECT_LT(hard, extent / size);
  EXPECT_NEAR(x50, hardMiddle, extent / size);
}

}  // namespace
}  // namespace firmament
