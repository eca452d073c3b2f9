#pragma once
// The weather map the clouds read, and how it lies on the planet.
//
// Textures (firmament::Image, RGBA float, row 0 = the northern edge, column 0 = the western edge):
//   map:  R coverage [0, 1]   G cloud type [0, 1]: 0 stratus, 1/3 cumulus, 2/3 congestus, 1 cumulonimbus
//         B precipitation rate at the ground (mm/h)   A cloud-top height above ground (m; 0 = no cloud)
//   wind: R east wind (m/s)   G north wind (m/s)   B convective updraft (m/s)   A cloud-base height (m)
// Placement: the region is a square of width × cellSize metres centred on (centreLatitude,
// centreLongitude), laid on the tangent plane there: a point on the (spherical) planet maps to
// east = R·atan2(d·Ê, d·Û), north = R·atan2(d·N̂, d·Û) (d the point's unit direction; Ê, N̂, Û the local
// axes at the centre), which is the local distance near the centre and finite everywhere. The map wraps:
// it repeats with the region's period in east and north, so every point on the sphere gets a value.
// Motion: the map is a snapshot at `time_s`; sampling at a later time shifts it with the mean wind
// (clouds move with the wind between snapshots), and a sample at height z is shifted downwind by the
// shear over the rise time of a thermal, (du/dz) z · 300 s, which skews towers with the shear.
#include <glm/glm.hpp>

#include "core/image.h"
#include "weather/weather_state.h"

namespace firmament::weather {

struct RegionPlacement {
  double centreLatitude_rad = 0.0;
  double centreLongitude_rad = 0.0;
  double planetRadius_m = 6360000.0;  // Bruneton 2017's Earth ground radius, the atmosphere's sphere
};

struct WeatherMap {
  Image map;   // coverage, type, precipitation mm/h, top m
  Image wind;  // east m/s, north m/s, updraft m/s, base m
  double cellSize_m = 200.0;
  double time_s = 0.0;              // model time of the snapshot (seconds since the scene's start time)
  glm::dvec2 meanWind_m_s{0.0};     // domain-mean wind at cloud base (east, north)
  glm::dvec2 windShear_per_s{0.0};  // d(east, north wind)/dz
  RegionPlacement placement;

  static constexpr double kSkewRiseTime_s = 300.0;

  double width_m() const { return map.width * cellSize_m; }
  double height_m() const { return map.height * cellSize_m; }
  // East/north metres from the region centre (not wrapped) of a planet-centred point (metres; z toward
  // the north pole, x toward longitude 0) or of a latitude/longitude.
  glm::dvec2 regionCoordinates(const glm::dvec3& planetCentred_m) const;
  glm::dvec2 regionCoordinates(double latitude_rad, double longitude_rad) const;
  // Bilinear, periodic samples at region coordinates, moved with the wind to `time_s` and skewed to
  // `height_m` above ground.
  glm::vec4 sampleMap(const glm::dvec2& region_m, double time_s, double height_m = 0.0) const;
  glm::vec4 sampleWind(const glm::dvec2& region_m, double time_s, double height_m = 0.0) const;
  // Direct texel-space sample without motion (tests, previews).
  static glm::vec4 sampleImage(const Image& image, double column, double row);
};

// Builds the two textures from the model state.
WeatherMap makeWeatherMap(const WeatherState& state, const RegionPlacement& placement, const glm::dvec2& shear_per_s);

// The cloud type code of the G channel from cloud depth and top (m): a continuous ramp from cumulus
// (depth < 1 km) through congestus (≈ 3 km deep) to cumulonimbus (top above ≈ 7.5 km, glaciated).
float convectiveCloudType(float depth_m, float top_m);

}  // namespace firmament::weather
