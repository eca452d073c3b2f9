#pragma once
// The weather map as the clouds read it (common/cloud_weather.glsl): an RGBA float image over a square
// region centred on the scene's location, with the skew of the map's wind shear. The same texels go to
// the GPU (a linear, repeating 2D texture) and to the CPU path tracer (sample(), the same bilinear,
// repeating lookup), so both see the same coverage, type and top.
//
// Sources (sky/scene_weather.h decides): the weather simulation's map (weather/weather_map.h) when the
// scene has a `weather` section, else the procedural map below.
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "core/image.h"

namespace firmament {

struct CloudWeatherMap {
  Image map;                  // RGBA: coverage [0, 1], type [0, 1], precipitation mm/h, top m above ground
  double width_m = 51200.0;   // region size east-west (m)
  double height_m = 51200.0;  // region size north-south (m)
  glm::dvec2 skew{0.0};       // downwind shift per metre of height (east, north; m/m)
  std::string source;         // "procedural" or "weather simulation" (reports)
  // Coverage that jumps from 0 to 1 within a texel or two (the weather simulation's, 200 m cells).
  // The march's one-point empty-space test with a margin cannot bound such a map; it skips a span
  // only where coverageReach() says no coverage lies within the span's length (docs/clouds.md
  // "Empty-space skipping").
  bool sharpCoverage = false;

  // Bilinear, repeating lookup at texture coordinates uv (texel centres at (i + 1/2) / N), as the
  // GPU's linear, repeating sampler.
  glm::dvec4 sample(glm::dvec2 uv) const;
};

// The map without a weather section: coverage from a tileable Perlin fbm of the cloud seed, features
// a quarter of the region (12.8 km): WM_c = SAT((n - 0.38) / 0.2), so broad clear gaps (n < 0.38) and
// fully covered areas (n > 0.58) alternate; the layer's coverage g_c scales it (threshold
// 1 - g_c WM_c). Type kCloudWeatherLayerType (no type: each layer keeps its own kind and anvil), no
// precipitation, top kCloudWeatherNoTop (the layers keep their tops). size x size texels.
CloudWeatherMap proceduralCloudWeatherMap(uint32_t seed, int size = 128);

// The largest coverage within radius_m of each texel centre: the maximum over the texels whose
// centres lie within radius_m + one texel diagonal in x and y (a square window, wrapping), so that a
// bilinear read anywhere between four texel centres bounds the coverage within radius_m of that
// point. One channel, the map's size.
Image coverageReach(const CloudWeatherMap& map, double radius_m);

// A map of one value everywhere (tests: coverage 0 gives no cloud).
CloudWeatherMap uniformCloudWeatherMap(glm::vec4 value, int size = 4);

}  // namespace firmament
