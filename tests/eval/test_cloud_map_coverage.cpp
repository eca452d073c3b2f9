// The coverage the weather map asks of the cloud field (CloudMedium::mapCoverage, averaged over the
// columns by sampleCloudColumns): the cloud fraction `firmament analyze clouds` reports beside the
// field's own (docs/clouds/shapes.md). Textures are the shared noise functions evaluated on the CPU,
// so no GPU is needed.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "clouds/cloud_weather_map.h"
#include "clouds/noise_volume.h"
#include "clouds/reference_clouds.h"
#include "common/cloud_density.glsl"
#include "common/cloud_noise.glsl"
#include "common/cloud_weather.glsl"
#include "eval/cloud_field_statistics.h"

namespace firmament {
namespace {

constexpr double kGround = 6360000.0;

// A small texture of the shared function f at texel centres.
template <class F>
NoiseVolume cpuTexture(int size, int depth, F f) {
  NoiseVolume v;
  v.size = size;
  v.depth = depth;
  v.texels.resize(size_t(size) * size * depth * 4);
  size_t k = 0;
  for (int z = 0; z < depth; ++z)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::dvec4 c = f(glm::dvec3((x + 0.5) / size, (y + 0.5) / size, (z + 0.5) / depth));
        for (int i = 0; i < 4; ++i) v.texels[k++] = float(c[i]);
      }
  return v;
}

// One cumulus layer 1500-2500 m of coverage g_c over `map`.
CloudMedium cumulusOver(CloudWeatherMap map, double coverage) {
  shared::CloudLayer l{};
  l.bottom_radius = kGround + 1500.0;
  l.top_radius = kGround + 2500.0;
  l.coverage = coverage;
  l.extinction = 0.1;
  l.density_scale = 1.0;
  l.shape_period = 12000.0;
  l.detail_period = 1500.0;
  l.detail_strength = 0.35;
  l.curl_period = 6000.0;
  l.curl_strength = 150.0;
  l.wind_offset = glm::dvec3(0.0);
  l.skew = glm::dvec2(0.0);
  l.kind = shared::kCloudCumulus;
  l.stratiform_kind = shared::kCloudStratus;
  return CloudMedium({l}, cpuTexture(8, 8, [](glm::dvec3 p) { return shared::cloudShapeNoise(p, 1u); }),
                     cpuTexture(4, 4, [](glm::dvec3 p) { return shared::cloudDetailNoise(p, 1u); }),
                     cpuTexture(8, 1, [](glm::dvec3 p) { return shared::cloudCurlNoise(glm::dvec2(p), 1u, 1e-3); }),
                     std::move(map), kGround);
}

CloudVolumeRegion box(double halfWidth_m) {
  CloudVolumeRegion r;
  r.west_m = r.south_m = -halfWidth_m;
  r.east_m = r.north_m = halfWidth_m;
  r.bottom_m = 1500.0;
  r.top_m = 2500.0;
  r.voxelSize_m = 400.0;  // 128 columns over the 51.2 km map
  return r;
}

// A uniform map: the asked coverage is g_c WM_c everywhere.
TEST(CloudMapCoverage, AUniformMapAsksTheLayersCoverageTimesTheMaps) {
  const CloudMedium medium = cumulusOver(uniformCloudWeatherMap(glm::vec4(0.5f, float(shared::kCloudWeatherLayerType),
                                                                          0.0f, float(shared::kCloudWeatherNoTop))),
                                         0.6);
  EXPECT_NEAR(sampleCloudColumns(medium, box(5000.0), 100.0).mapCoverage, 0.3, 1e-6);
}

// Half the map covered (its west half, whole texels): over the whole region the asked coverage is half
// the layer's; a column whose top is below the layer asks none.
TEST(CloudMapCoverage, HalfACoveredMapAsksHalfAndALowTopAsksNone) {
  CloudWeatherMap half = uniformCloudWeatherMap(
      glm::vec4(0.0f, float(shared::kCloudWeatherLayerType), 0.0f, float(shared::kCloudWeatherNoTop)), 16);
  for (int row = 0; row < 16; ++row)
    for (int column = 0; column < 8; ++column) half.map.at(column, row)[0] = 1.0f;
  // The region's columns sample the map bilinearly; over a whole period the halves' ramps cancel.
  const double w = 0.5 * half.width_m;
  EXPECT_NEAR(sampleCloudColumns(cumulusOver(half, 0.8), box(w), 100.0).mapCoverage, 0.4, 0.01);
  CloudWeatherMap low = uniformCloudWeatherMap(glm::vec4(1.0f, float(shared::kCloudWeatherLayerType), 0.0f, 1000.0f));
  EXPECT_EQ(sampleCloudColumns(cumulusOver(low, 0.8), box(5000.0), 100.0).mapCoverage, 0.0);
}

}  // namespace
}  // namespace firmament
