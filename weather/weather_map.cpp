#include "weather/weather_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "weather/surface_heating.h"

namespace firmament::weather {
namespace {
float ramp(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}
}  // namespace

float convectiveCloudType(float depth, float top) {
  return 1.0f / 3.0f + ramp((depth - 1000.0f) / 2000.0f) / 3.0f + ramp((top - 6500.0f) / 2000.0f) / 3.0f;
}

WeatherMap makeWeatherMap(const WeatherState& s, const RegionPlacement& placement, const glm::dvec2& shear) {
  WeatherMap m;
  m.map = Image(s.nx, s.ny, 4);
  m.wind = Image(s.nx, s.ny, 4);
  m.cellSize_m = s.cellSize_m;
  m.time_s = s.time_s;
  m.placement = placement;
  m.windShear_per_s = shear;
  double su = 0.0, sv = 0.0;
  for (int j = 0; j < s.ny; ++j) {
    int row = s.ny - 1 - j;  // north up
    for (int i = 0; i < s.nx; ++i) {
      size_t c = s.index(i, j);
      float coverage = cloudCover(s.cloudWater[c]);
      bool cloudy = s.cloudWater[c] > 1e-4f;
      float top = cloudy ? s.cloudTop[c] : 0.0f;
      float base = s.cloudBase[c];
      float type = s.convectiveFraction[c] * convectiveCloudType(top - base, top);
      float* px = m.map.at(i, row);
      px[0] = coverage;
      px[1] = cloudy ? type : 0.0f;
      px[2] = s.precipitationRate[c] * 3600.0f;
      px[3] = top;
      float* w = m.wind.at(i, row);
      w[0] = s.windU[c];
      w[1] = s.windV[c];
      w[2] = s.updraft[c];
      w[3] = base;
      su += s.windU[c];
      sv += s.windV[c];
    }
  }
  m.meanWind_m_s = glm::dvec2(su, sv) / double(s.cells());
  for (Image* image : {&m.map, &m.wind}) {
    image->metadata["weather:time_s"] = std::to_string(s.time_s);
    image->metadata["weather:cell_size_m"] = std::to_string(s.cellSize_m);
    image->metadata["weather:centre_latitude_deg"] =
        std::to_string(placement.centreLatitude_rad * 180.0 / std::numbers::pi);
    image->metadata["weather:centre_longitude_deg"] =
        std::to_string(placement.centreLongitude_rad * 180.0 / std::numbers::pi);
  }
  m.map.metadata["weather:channels"] = "coverage, type (0 St, 1/3 Cu, 2/3 Cg, 1 Cb), precipitation mm/h, top m";
  m.wind.metadata["weather:channels"] = "east m/s, north m/s, updraft m/s, cloud base m";
  return m;
}

glm::dvec2 WeatherMap::regionCoordinates(const glm::dvec3& p) const {
  double lat0 = placement.centreLatitude_rad, lon0 = placement.centreLongitude_rad;
  glm::dvec3 up(std::cos(lat0) * std::cos(lon0), std::cos(lat0) * std::sin(lon0), std::sin(lat0));
  glm::dvec3 east(-std::sin(lon0), std::cos(lon0), 0.0);
  glm::dvec3 north = glm::cross(up, east);
  double len = glm::length(p);
  if (!(len > 0.0)) return glm::dvec2(0.0);
  glm::dvec3 d = p / len;
  double u = glm::dot(d, up);
  return placement.planetRadius_m * glm::dvec2(std::atan2(glm::dot(d, east), u), std::atan2(glm::dot(d, north), u));
}

glm::dvec2 WeatherMap::regionCoordinates(double lat, double lon) const {
  return regionCoordinates(glm::dvec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)));
}

glm::vec4 WeatherMap::sampleImage(const Image& image, double column, double row) {
  // Texel centres at integer + 0.5; periodic in both directions.
  double x = column - 0.5, y = row - 0.5;
  double fx = std::floor(x), fy = std::floor(y);
  float tx = float(x - fx), ty = float(y - fy);
  auto wrap = [](double v, int n) {
    long long i = (long long)std::fmod(v, double(n));
    return int(i < 0 ? i + n : i);
  };
  int x0 = wrap(fx, image.width), y0 = wrap(fy, image.height);
  int x1 = x0 + 1 == image.width ? 0 : x0 + 1, y1 = y0 + 1 == image.height ? 0 : y0 + 1;
  glm::vec4 out(0.0f);
  for (int k = 0; k < std::min(4, image.channels); ++k) {
    float a = image.at(x0, y0)[k] + tx * (image.at(x1, y0)[k] - image.at(x0, y0)[k]);
    float b = image.at(x0, y1)[k] + tx * (image.at(x1, y1)[k] - image.at(x0, y1)[k]);
    out[k] = a + ty * (b - a);
  }
  return out;
}

namespace {
glm::vec4 sampleMoved(const WeatherMap& m, const Image& image, const glm::dvec2& region, double t, double z) {
  glm::dvec2 shift = m.meanWind_m_s * (t - m.time_s) + m.windShear_per_s * z * WeatherMap::kSkewRiseTime_s;
  glm::dvec2 p = region - shift;
  double column = (p.x + 0.5 * m.width_m()) / m.cellSize_m;
  double row = (0.5 * m.height_m() - p.y) / m.cellSize_m;  // row 0 is north
  return WeatherMap::sampleImage(image, column, row);
}
}  // namespace

glm::vec4 WeatherMap::sampleMap(const glm::dvec2& region, double t, double z) const {
  return sampleMoved(*this, map, region, t, z);
}
glm::vec4 WeatherMap::sampleWind(const glm::dvec2& region, double t, double z) const {
  return sampleMoved(*this, wind, region, t, z);
}

}  // namespace firmament::weather
