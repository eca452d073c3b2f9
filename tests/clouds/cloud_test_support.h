#pragma once
// Small cloud scenes for the GPU tests: 64x36 images, 32^3 shape noise (the bake of 128^3 takes ~2 s
// on lavapipe), one SkyRenderer per test binary.
#include <memory>
#include <string>
#include <vector>

#include "core/scene.h"
#include "sky/sky_renderer.h"
#include "tests/support/gpu_test.h"

namespace firmament::test {

inline SkyRenderer& cloudRenderer() {
  static std::unique_ptr<SkyRenderer> renderer = std::make_unique<SkyRenderer>(GpuTest::context());
  return *renderer;
}

inline SkyRenderOptions smallCloudOptions() {
  SkyRenderOptions o;
  o.cloudNoise.shapeSize = 32;
  o.cloudNoise.detailSize = 16;
  o.cloudNoise.curlSize = 32;
  o.cloudNoise.blueNoiseSize = 16;
  return o;
}

// A cumulus layer 1500-4000 m over a camera 2 m above the ground, sun 40 degrees from the zenith.
inline std::string cloudSceneText(
    const std::string& layer = R"({"kind": "cumulus", "bottom_m": 1500, "top_m": 4000, "coverage": 0.7})",
    const std::string& extra = "") {
  return std::string(R"({"location": {"height_m": 500}, "sun": {"zenith_deg": 40, "azimuth_deg": 180},
    "camera": {"height_above_ground_m": 2, "yaw_deg": 0, "pitch_deg": 50, "fov_deg": 80, "width": 64, "height": 36},
    "clouds": {"layers": [)") +
         layer + "]" + extra + "}}";
}

inline Scene cloudScene(const std::vector<std::string>& overrides = {}, const std::string& text = cloudSceneText()) {
  return Scene::parse(text, "<cloud test>", overrides);
}

}  // namespace firmament::test
