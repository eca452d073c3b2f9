#include "weather/weather_preview.h"

#include <algorithm>
#include <cmath>

namespace firmament::weather {

std::vector<uint8_t> previewRgb(const WeatherMap& m) {
  const Image& image = m.map;
  std::vector<uint8_t> rgb(image.pixelCount() * 3);
  auto mix = [](const float a[3], const float b[3], float t, float out[3]) {
    for (int k = 0; k < 3; ++k) out[k] = a[k] + t * (b[k] - a[k]);
  };
  const float ground[3] = {0.16f, 0.24f, 0.14f}, stratus[3] = {0.62f, 0.66f, 0.74f}, cumulus[3] = {0.97f, 0.97f, 0.97f},
              congestus[3] = {0.98f, 0.90f, 0.62f}, cumulonimbus[3] = {0.95f, 0.45f, 0.25f},
              rain[3] = {0.15f, 0.35f, 0.95f};
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* px = image.pixels.data() + 4 * i;
    float cover = std::clamp(px[0], 0.0f, 1.0f), type = std::clamp(px[1], 0.0f, 1.0f);
    float precipitation = std::max(px[2], 0.0f), top = std::max(px[3], 0.0f);
    float cloud[3];
    if (type < 1.0f / 3.0f)
      mix(stratus, cumulus, type * 3.0f, cloud);
    else if (type < 2.0f / 3.0f)
      mix(cumulus, congestus, (type - 1.0f / 3.0f) * 3.0f, cloud);
    else
      mix(congestus, cumulonimbus, (type - 2.0f / 3.0f) * 3.0f, cloud);
    float brightness = 0.75f + 0.25f * std::min(top / 10000.0f, 1.0f);
    for (float& c : cloud) c *= brightness;
    float colour[3];
    mix(ground, cloud, cover, colour);
    if (precipitation > 0.1f) {
      float t = std::clamp(std::log10(precipitation / 0.1f) / std::log10(500.0f), 0.0f, 1.0f) * 0.8f;
      mix(colour, rain, t, colour);
    }
    for (int k = 0; k < 3; ++k) rgb[3 * i + k] = uint8_t(std::lround(std::clamp(colour[k], 0.0f, 1.0f) * 255.0f));
  }
  return rgb;
}

}  // namespace firmament::weather
