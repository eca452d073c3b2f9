#pragma once
// A colour-coded 8-bit preview of a weather map (north up): ground dark green; cloud cover blends in
// white for cumulus, warm yellow for congestus, orange-red for cumulonimbus, blue-grey for stratus,
// brighter for higher tops; rain at the ground tints blue (log scale, 0.1–50 mm/h).
#include <cstdint>
#include <vector>

#include "weather/weather_map.h"

namespace firmament::weather {

// RGB, row-major, width × height × 3.
std::vector<uint8_t> previewRgb(const WeatherMap& map);

}  // namespace firmament::weather
