// The albedo of shaders/common/terrain_albedo.glsl at the cases its definition decides.
#include <gtest/gtest.h>

#include "common/terrain_albedo.glsl"
#include "core/scene.h"
#include "terrain/terrain_settings.h"

namespace firmament::terrain {
namespace {

TEST(TerrainAlbedo, CoversFollowHeightAndSlope) {
  const TerrainSettings s = terrainSettingsFromScene(Scene::parse(R"({"terrain": {}})", "<test>"));
  const shared::TerrainAlbedoParameters& p = s.albedo;
  const double flat = 1.0, cliff = std::cos(80.0 * 3.14159265358979 / 180.0);
  auto near = [](shared::vec3 a, shared::vec3 b) { return glm::length(a - b) < 1e-12; };
  EXPECT_TRUE(near(shared::terrainAlbedo(500.0, flat, p), p.vegetation));  // low meadow
  EXPECT_TRUE(near(shared::terrainAlbedo(500.0, cliff, p), p.rock));       // low cliff
  EXPECT_TRUE(near(shared::terrainAlbedo(2500.0, flat, p), p.rock));       // above trees, below snow
  EXPECT_TRUE(near(shared::terrainAlbedo(4000.0, flat, p), p.snow));       // high and flat
  EXPECT_TRUE(near(shared::terrainAlbedo(4000.0, cliff, p), p.rock));      // high and too steep for snow
  // On the snow line, half snow.
  const shared::vec2 w = shared::terrainCoverWeights(p.snowLine, flat, p);
  EXPECT_NEAR(w.y, 0.5, 1e-12);
  EXPECT_EQ(w.x, 0.0);
  // Robust at the ends of its inputs: slope cosines beyond [−1, 1] and zero-width transitions.
  shared::TerrainAlbedoParameters sharp = p;
  sharp.snowLineTransition = 0.0;
  sharp.slopeTransition = 0.0;
  for (double c : {-1.5, -1.0, 0.0, 1.0, 1.5})
    for (double h : {-11000.0, 2800.0, 9000.0}) {
      const shared::vec3 a = shared::terrainAlbedo(h, c, sharp);
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(a[k] >= 0.0 && a[k] <= 1.0);
    }
}

}  // namespace
}  // namespace firmament::terrain
