#include "clouds/cloud_weather_map.h"

#include <algorithm>
#include <cmath>

#include "common/cloud_noise.glsl"
#include "common/cloud_weather.glsl"

namespace firmament {
namespace {

int wrap(long long i, int n) { return int(((i % n) + n) % n); }

}  // namespace

glm::dvec4 CloudWeatherMap::sample(glm::dvec2 uv) const {
  // x = u N - 1/2: texel floor(x) and floor(x) + 1 blended by fract(x), per axis, wrapped.
  const glm::dvec2 x = uv * glm::dvec2(map.width, map.height) - 0.5;
  const glm::dvec2 base = glm::floor(x);
  const glm::dvec2 f = x - base;
  const long long bx = (long long)base.x, by = (long long)base.y;
  glm::dvec4 result(0.0);
  for (int corner = 0; corner < 4; ++corner) {
    const int cx = corner & 1, cy = corner >> 1;
    const double w = (cx ? f.x : 1.0 - f.x) * (cy ? f.y : 1.0 - f.y);
    const float* t = map.at(wrap(bx + cx, map.width), wrap(by + cy, map.height));
    result += w * glm::dvec4(t[0], t[1], t[2], t[3]);
  }
  return result;
}

CloudWeatherMap proceduralCloudWeatherMap(uint32_t seed, int size) {
  CloudWeatherMap m;
  m.map = Image(size, size, 4);
  m.source = "procedural";
  const double period = 4.0;  // noise cells per region side
  const uint32_t noiseSeed = seed * 0x9E3779B9u + 0x7F4A7C15u;
  for (int row = 0; row < size; ++row)
    for (int column = 0; column < size; ++column) {
      const glm::dvec3 p((column + 0.5) / size * period, (row + 0.5) / size * period, 0.5);
      const double n = shared::perlinFbm01(p, period, noiseSeed);
      float* px = m.map.at(column, row);
      px[0] = float(std::clamp((n - 0.38) / 0.2, 0.0, 1.0));
      px[1] = float(shared::kCloudWeatherLayerType);  // no type: each layer keeps its own kind
      px[2] = 0.0f;
      px[3] = float(shared::kCloudWeatherNoTop);
    }
  return m;
}

Image coverageReach(const CloudWeatherMap& map, double radius_m) {
  const int w = map.map.width, h = map.map.height;
  const double texelX = map.width_m / w, texelY = map.height_m / h;
  // A read between texel centres blends the four around it: each must bound the coverage within
  // radius_m of the read point, up to one texel away, so the window reaches radius_m + 1 texel.
  const int rx = std::min(w / 2, int(std::ceil(radius_m / texelX)) + 1);
  const int ry = std::min(h / 2, int(std::ceil(radius_m / texelY)) + 1);
  // Separable maximum: rows, then columns.
  Image rows(w, h, 1), reach(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float m = 0.0f;
      for (int d = -rx; d <= rx; ++d) m = std::max(m, map.map.at(wrap(x + d, w), y)[0]);
      rows.at(x, y)[0] = m;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float m = 0.0f;
      for (int d = -ry; d <= ry; ++d) m = std::max(m, rows.at(x, wrap(y + d, h))[0]);
      reach.at(x, y)[0] = m;
    }
  return reach;
}

CloudWeatherMap uniformCloudWeatherMap(glm::vec4 value, int size) {
  CloudWeatherMap m;
  m.map = Image(size, size, 4);
  m.source = "uniform";
  for (int row = 0; row < size; ++row)
    for (int column = 0; column < size; ++column)
      for (int k = 0; k < 4; ++k) m.map.at(column, row)[k] = value[k];
  return m;
}

}  // namespace firmament
