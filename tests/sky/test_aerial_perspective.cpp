// The aerial-perspective volume (sky/aerial_perspective_volume.h; layout in
// shaders/common/aerial_perspective.glsl):
//  - its layout functions (corner-aligned columns, slice depths, depth lookup, fisheye rim);
//  - at froxel centres it agrees with a fine march of the same integrand along the same ray
//    (shaders/sky/air_march_test.comp, 4096 equal steps), the ray and the depth computed here on the
//    CPU from the shared layout functions, so a wrong direction mapping, slice depth, tile order or
//    colour conversion in the pass fails; the difference left is the volume's quadrature (one step
//    per slice, quadratic slices) and float round-off;
//  - every texel is finite and non-negative, transmittance in [0, 1], for a camera at 0 m, 10 km and
//    in space, the sun high and below the horizon, level and grazing views;
//  - the plan runs the pass only for clouds that read it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "atmosphere/atmosphere_luts.h"
#include "common/aerial_perspective.glsl"
#include "core/error.h"
#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/pipeline.h"
#include "sky/aerial_perspective_volume.h"
#include "sky/render_plan.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

shared::CameraParameters makeCamera(double yawDeg, double pitchDeg, double fovDeg, int projection, int width,
                                    int height) {
  shared::CameraParameters c{};
  shared::cameraBasis(yawDeg * kDegree, pitchDeg * kDegree, 0.0, c.forward, c.right, c.up);
  c.fov = fovDeg * kDegree;
  c.yaw = yawDeg * kDegree;
  c.projection = projection;
  c.width = width;
  c.height = height;
  return c;
}

glm::dvec3 sunAt(double zenithDeg, double azimuthDeg) {
  const double z = zenithDeg * kDegree, a = azimuthDeg * kDegree;
  return {std::sin(z) * std::sin(a), std::sin(z) * std::cos(a), std::cos(z)};
}

TEST(AerialPerspectiveLayout, SlicesColumnsAndDepthLookup) {
  const int n = 32;
  const double d = 80000.0;
  // Quadratic slices: d_k = D ((k + 1) / N)^2, the last at D.
  EXPECT_DOUBLE_EQ(shared::aerialSliceDepth(n - 1, n, d), d);
  EXPECT_NEAR(shared::aerialSliceDepth(0, n, d), d / (n * n), 1e-9);
  // At a slice's depth the lookup lands on that slice's texel centre, with the near factor 1.
  for (int k = 0; k < n; ++k) {
    const glm::dvec2 z = shared::aerialDepthCoordinate(shared::aerialSliceDepth(k, n, d), n, d);
    EXPECT_NEAR(z.x, (k + 0.5) / n, 1e-9) << k;
    EXPECT_DOUBLE_EQ(z.y, 1.0);
  }
  // Between two slices the coordinate is linear in distance; before d_0 it stays on slice 0 and the
  // near factor falls linearly to 0 at the camera; beyond D it clamps to the last slice.
  const double d5 = shared::aerialSliceDepth(5, n, d), d6 = shared::aerialSliceDepth(6, n, d);
  EXPECT_NEAR(shared::aerialDepthCoordinate(0.25 * d5 + 0.75 * d6, n, d).x, (5.75 + 0.5) / n, 1e-9);
  const double d0 = shared::aerialSliceDepth(0, n, d);
  EXPECT_NEAR(shared::aerialDepthCoordinate(0.5 * d0, n, d).x, 0.5 / n, 1e-12);
  EXPECT_NEAR(shared::aerialDepthCoordinate(0.5 * d0, n, d).y, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(shared::aerialDepthCoordinate(0.0, n, d).y, 0.0);
  EXPECT_NEAR(shared::aerialDepthCoordinate(2.0 * d, n, d).x, (n - 0.5) / n, 1e-12);
  // Columns are corner-aligned: the image's edges land on a tile's first and last texel centres, and
  // the tiles never share a filtering footprint.
  const int c = 32, width = 640;
  for (int tile = 0; tile < shared::kAerialTiles; ++tile) {
    EXPECT_NEAR(shared::aerialTileX(0.0, width, c, tile) * shared::kAerialTiles * c, tile * c + 0.5, 1e-9);
    EXPECT_NEAR(shared::aerialTileX(width, width, c, tile) * shared::kAerialTiles * c, tile * c + c - 0.5, 1e-9);
  }
  EXPECT_NEAR(shared::aerialTileY(360.0, 360, 18), (17.5) / 18.0, 1e-12);
  // Column (i, j) is the pixel point i / (C - 1) of the width: the lookup of that point is column i.
  const glm::dvec2 p = shared::aerialColumnPixel(7, 3, c, 18, width, 360);
  EXPECT_NEAR(shared::aerialTileX(p.x, width, c, 0) * shared::kAerialTiles * c, 7.5, 1e-9);
  EXPECT_NEAR(shared::aerialTileY(p.y, 360, 18) * 18.0, 3.5, 1e-9);
}

TEST(AerialPerspectiveLayout, ColumnDirectionsForEveryProjection) {
  // Perspective: the camera's own mapping.
  const shared::CameraParameters persp = makeCamera(30.0, 10.0, 75.0, shared::kProjectionPerspective, 640, 360);
  bool valid = false;
  const glm::dvec2 pixel = shared::aerialColumnPixel(5, 9, 32, 32, 640, 360);
  EXPECT_LT(glm::length(shared::aerialColumnDirection(persp, pixel) - shared::cameraRayDirection(persp, pixel, valid)),
            1e-12);
  // Equirectangular: the left and right edges are the same direction (the seam interpolates).
  const shared::CameraParameters equi = makeCamera(0.0, 0.0, 360.0, shared::kProjectionEquirectangular, 512, 256);
  for (int j = 1; j < 31; ++j) {
    const glm::dvec3 left = shared::aerialColumnDirection(equi, shared::aerialColumnPixel(0, j, 32, 32, 512, 256));
    const glm::dvec3 right = shared::aerialColumnDirection(equi, shared::aerialColumnPixel(31, j, 32, 32, 512, 256));
    EXPECT_LT(glm::length(left - right), 1e-9) << j;
  }
  // Fisheye of 360 degrees in a 16:9 image: the corners lie outside the image circle; their columns
  // take the rim's direction (just short of straight back), not the camera's fallback (forward).
  const shared::CameraParameters fish = makeCamera(0.0, 30.0, 360.0, shared::kProjectionFisheye, 640, 360);
  const glm::dvec2 corner = shared::aerialColumnPixel(0, 0, 32, 32, 640, 360);
  shared::cameraRayDirection(fish, corner, valid);
  EXPECT_FALSE(valid);
  const glm::dvec3 rim = shared::aerialColumnDirection(fish, corner);
  EXPECT_NEAR(glm::length(rim), 1.0, 1e-9);
  EXPECT_LT(glm::dot(rim, fish.forward), -0.999);
  // ... on the corner's side of the image: up and to the left.
  EXPECT_GT(glm::dot(rim, fish.up), 0.0);
  EXPECT_LT(glm::dot(rim, fish.right), 0.0);
}

class AerialPerspectiveVolumeTest : public test::GpuTest {
 protected:
  struct Case {
    std::string name;
    double altitude_m;  // camera above the ground sphere
    double pitchDeg, fovDeg;
    int projection;
    double sunZenithDeg;
    double maxDistance_m;
  };

  struct Outcome {
    double maxLightError = 0.0;          // |volume - march| / max(|march|, floor), sky-like and aerosol tiles
    double maxTransmittanceError = 0.0;  // |volume - march|
    double maxLight = 0.0;
    size_t compared = 0;
  };

  // Earth's tables, once per binary; destroyed before the shared context (constructed after it).
  static AtmosphereLuts& luts() {
    static std::unique_ptr<AtmosphereLuts> tables = [] {
      auto t = std::make_unique<AtmosphereLuts>(context());
      t->update(AtmosphereSettings{}, {});
      return t;
    }();
    return *tables;
  }

  // Renders the volume for `c`, checks every texel (finite, >= 0, T <= 1), and compares a subset of
  // froxel centres with the fine march.
  Outcome run(const Case& c, AerialPerspectiveVolumeSettings settings) {
    const int width = 640, height = 360;
    settings.maxDistance_m = c.maxDistance_m;
    const shared::CameraParameters camera = makeCamera(200.0, c.pitchDeg, c.fovDeg, c.projection, width, height);
    const double ground = luts().parameters().bottom_radius;
    const glm::dvec3 origin(0.0, 0.0, ground + c.altitude_m);
    const glm::dvec3 sun = sunAt(c.sunZenithDeg, 180.0);
    AerialPerspectiveVolume volume(context());
    gpu::CommandList commands(context());
    volume.record(settings, origin, sun, camera, luts(), commands);
    commands.submitAndWait();
    const int C = settings.columns, R = settings.rows, N = settings.slices;
    const int tiles = shared::kAerialTiles;
    const std::vector<float> texels = volume.volume(0).downloadFloats();
    EXPECT_EQ(texels.size(), size_t(tiles * C) * R * N * 4);
    auto texel = [&](int tile, int i, int j, int k, int channel) {
      return double(texels[((size_t(k) * R + j) * (tiles * C) + size_t(tile * C + i)) * 4 + channel]);
    };
    for (int k = 0; k < N; ++k)
      for (int j = 0; j < R; ++j)
        for (int i = 0; i < C; ++i)
          for (int tile = 0; tile < tiles; ++tile)
            for (int ch = 0; ch < 3; ++ch) {
              const double v = texel(tile, i, j, k, ch);
              EXPECT_TRUE(std::isfinite(v) && v >= 0.0)
                  << c.name << " tile " << tile << " froxel " << i << "," << j << "," << k;
              if (tile == 2) {
                EXPECT_LE(v, 1.0) << c.name;
              }
              if (!(std::isfinite(v) && v >= 0.0)) return {};
            }

    // The fine march at a subset of froxel centres: columns and rows at the edges and inside, and
    // slices near, mid and far.
    const std::vector<int> columns = {0, 5, 11, 16, 22, 27, 31}, slices = {0, 3, 10, 20, 31};
    std::vector<float> rays;
    struct Froxel {
      int i, j, k;
    };
    std::vector<Froxel> froxels;
    for (int j : columns)
      for (int i : columns)
        for (int k : slices) {
          const glm::dvec3 dir =
              shared::aerialColumnDirection(camera, shared::aerialColumnPixel(i, j, C, R, width, height));
          const double depth = shared::aerialSliceDepth(k, N, settings.maxDistance_m);
          rays.insert(rays.end(), {float(origin.x), float(origin.y), float(origin.z), float(depth), float(dir.x),
                                   float(dir.y), float(dir.z), 4096.0f});
          froxels.push_back({i, j, k});
        }
    const uint32_t count = uint32_t(froxels.size());
    gpu::Buffer rayBuffer(context(), rays.size() * sizeof(float), gpu::BufferUsage::Storage, gpu::MemoryLocation::Host,
                          "rays");
    rayBuffer.upload(rays);
    gpu::Buffer results(context(), size_t(count) * 3 * 4 * sizeof(float), gpu::BufferUsage::Storage,
                        gpu::MemoryLocation::Host, "results");
    gpu::ComputePipeline probe(
        context(), {"sky/air_march_test",
                    {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
                     gpu::BindingType::SampledImage, gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer},
                    20});
    struct {
      float sun[4];
      uint32_t count;
    } push{{float(sun.x), float(sun.y), float(sun.z), 0.0f}, count};
    const AtmosphereLuts::Batch& batch = luts().batch(0);
    gpu::CommandList list(context());
    list.bind(probe, {batch.block,
                      {batch.transmittance, luts().linearClamp()},
                      {batch.multipleScattering, luts().linearClamp()},
                      {batch.multipleScatteringAnisotropy, luts().linearClamp()},
                      rayBuffer,
                      results});
    list.pushConstants(&push, 20);
    list.dispatch((count + 63) / 64);
    list.submitAndWait();
    const std::vector<float> march = results.download<float>();

    Outcome out;
    // Light errors are relative to the larger of the value and 1e-3 of this case's largest value (a
    // floor for the dark froxels near the camera and in the night).
    for (size_t n = 0; n < froxels.size(); ++n)
      for (int tile = 0; tile < 2; ++tile)
        for (int ch = 0; ch < 3; ++ch) out.maxLight = std::max(out.maxLight, double(march[(3 * n + tile) * 4 + ch]));
    const double floor = std::max(1e-3 * out.maxLight, 1e-30);
    for (size_t n = 0; n < froxels.size(); ++n) {
      const Froxel& f = froxels[n];
      for (int tile = 0; tile < 3; ++tile)
        for (int ch = 0; ch < 3; ++ch) {
          const double v = texel(tile, f.i, f.j, f.k, ch), m = march[(3 * n + tile) * 4 + ch];
          if (tile < 2) {
            const double e = std::abs(v - m) / std::max(std::abs(m), floor);
            out.maxLightError = std::max(out.maxLightError, e);
          } else
            out.maxTransmittanceError = std::max(out.maxTransmittanceError, std::abs(v - m));
        }
      ++out.compared;
    }
    std::printf(
        "%d steps/slice, rise %4.0f m, %-40s max light error %.2e (of max %.3g), max |dT| %.2e over %zu froxels\n",
        settings.stepsPerSlice, settings.maxStepRise_m, c.name.c_str(), out.maxLightError, out.maxLight,
        out.maxTransmittanceError, out.compared);
    return out;
  }
};

// Two settings of the volume against the same fine march:
//  - converged (32 steps per slice, at most 50 m of altitude per step): what is left is float
//    round-off (the march's 4096 products in float: ~2e-4 in T) and the lookup tables' filtering at
//    different sample points; measured at most 4.3e-4 (light), 4.2e-4 (T). Any error of the layout
//    (direction of a column, depth of a slice, tile order, colour conversion) is far above 1e-3;
//  - the defaults (one step per slice, more where the ray climbs: at most 500 m of scaled altitude
//    per step; the slice that holds the ground hit split there): the volume's own quadrature,
//    measured at most 1.31 % (the sun 6 degrees below the horizon, where the light is 3000x dimmer)
//    and 0.94 % (camera in space), 0.58 % (10 km up), <= 0.4 % from the ground; T within 7.5e-4.
TEST_F(AerialPerspectiveVolumeTest, AgreesWithAFineMarchAtFroxelCentres) {
  const std::vector<Case> cases = {
      {"ground, level, sun 40 deg", 2.0, 5.0, 75.0, shared::kProjectionPerspective, 40.0, 80000.0},
      {"ground, grazing (horizon mid-image), sun 85", 0.0, 0.0, 60.0, shared::kProjectionPerspective, 85.0, 80000.0},
      {"ground, sun 96 deg (below the horizon)", 2.0, 10.0, 75.0, shared::kProjectionPerspective, 96.0, 80000.0},
      {"10 km, looking down 20 deg", 10000.0, -20.0, 75.0, shared::kProjectionPerspective, 40.0, 80000.0},
      {"space (100 km), looking down 30 deg", 100000.0, -30.0, 60.0, shared::kProjectionPerspective, 40.0, 300000.0},
      {"fisheye 180 deg up", 2.0, 90.0, 180.0, shared::kProjectionFisheye, 60.0, 80000.0},
      {"equirectangular", 500.0, 0.0, 360.0, shared::kProjectionEquirectangular, 70.0, 80000.0},
  };
  AerialPerspectiveVolumeSettings converged;
  converged.stepsPerSlice = 32;
  converged.maxStepRise_m = 50.0;
  for (const Case& c : cases) {
    const Outcome o = run(c, converged);
    ASSERT_GT(o.compared, 0u) << c.name;
    EXPECT_GT(o.maxLight, 0.0) << c.name << ": the march sees light";
    EXPECT_LT(o.maxLightError, 1e-3) << c.name << " (converged)";
    EXPECT_LT(o.maxTransmittanceError, 1e-3) << c.name << " (converged)";
  }
  for (const Case& c : cases) {
    const Outcome o = run(c, AerialPerspectiveVolumeSettings{});
    EXPECT_LT(o.maxLightError, 0.02) << c.name << " (defaults)";
    EXPECT_LT(o.maxTransmittanceError, 2e-3) << c.name << " (defaults)";
  }
}

// A camera above the atmosphere looking past it: no air anywhere, T = 1, no light.
TEST_F(AerialPerspectiveVolumeTest, RayMissingTheAtmosphereHoldsNoAir) {
  AerialPerspectiveVolumeSettings settings;
  settings.maxDistance_m = 80000.0;
  const shared::CameraParameters camera = makeCamera(0.0, 60.0, 30.0, shared::kProjectionPerspective, 64, 36);
  const glm::dvec3 origin(0.0, 0.0, luts().parameters().top_radius + 1000.0);
  AerialPerspectiveVolume volume(context());
  gpu::CommandList commands(context());
  volume.record(settings, origin, sunAt(30.0, 0.0), camera, luts(), commands);
  commands.submitAndWait();
  const std::vector<float> texels = volume.volume(0).downloadFloats();
  const size_t C = size_t(settings.columns);
  for (size_t t = 0; t < texels.size() / 4; ++t) {
    const bool transmittance = (t % (shared::kAerialTiles * C)) >= 2 * C;
    for (int ch = 0; ch < 3; ++ch) ASSERT_EQ(texels[4 * t + ch], transmittance ? 1.0f : 0.0f) << t;
  }
}

TEST(AerialPerspectivePlan, OnlyCloudsThatReadItRunThePass) {
  EXPECT_FALSE(planRender(Scene::parse("{}", "<t>")).has("sky/aerial_perspective_volume"));
  EXPECT_FALSE(planRender(Scene::parse(R"({"clouds": {"layers": []}})", "<t>")).has("sky/aerial_perspective_volume"));
  const std::string cloudy = R"({"clouds": {"layers": [{"kind": "cumulus", "bottom_m": 1500, "top_m": 3000}]}})";
  EXPECT_TRUE(planRender(Scene::parse(cloudy, "<t>")).has("sky/aerial_perspective_volume"));  // the default: volume
  EXPECT_FALSE(planRender(Scene::parse(cloudy, "<t>", {"/clouds/aerial_perspective=march"}))
                   .has("sky/aerial_perspective_volume"));
  EXPECT_FALSE(
      planRender(Scene::parse(cloudy, "<t>", {"/clouds/aerial_perspective=off"})).has("sky/aerial_perspective_volume"));
  PlanOptions off;
  off.aerialPerspective = AerialPerspective::Off;
  EXPECT_FALSE(planRender(Scene::parse(cloudy, "<t>"), off).has("sky/aerial_perspective_volume"));
  EXPECT_THROW(Scene::parse(cloudy, "<t>", {"/clouds/aerial_perspective=fog"}), InputError);
}

}  // namespace
}  // namespace firmament
