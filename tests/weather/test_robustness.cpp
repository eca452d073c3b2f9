// Extreme inputs: every field stays finite and within its physical bounds, water never goes negative.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "tests/weather/weather_test_support.h"
#include "weather/thermodynamics.h"

using namespace firmament::weather;

namespace {

void expectBounded(const WeatherModel& model, const std::string& label) {
  const WeatherState& s = model.state();
  for (size_t c = 0; c < s.cells(); ++c) {
    ASSERT_TRUE(std::isfinite(s.temperature[c]) && std::fabs(s.temperature[c]) <= 30.0f) << label;
    ASSERT_TRUE(std::isfinite(s.vapour[c]) && s.vapour[c] >= 0.0f && s.vapour[c] < 500.0f) << label;
    ASSERT_TRUE(std::isfinite(s.cloudWater[c]) && s.cloudWater[c] >= 0.0f && s.cloudWater[c] < 500.0f) << label;
    ASSERT_TRUE(std::isfinite(s.rain[c]) && s.rain[c] >= 0.0f && s.rain[c] < 500.0f) << label;
    ASSERT_TRUE(s.updraft[c] >= 0.0f && s.updraft[c] <= 60.0f) << label;
    ASSERT_TRUE(s.cloudTop[c] >= 0.0f && s.cloudTop[c] <= 20000.0f) << label;
    ASSERT_TRUE(s.cloudBase[c] >= 0.0f && s.cloudBase[c] <= 20000.0f) << label;
    ASSERT_TRUE(s.precipitationRate[c] >= 0.0f && std::isfinite(s.precipitationRate[c])) << label;
    ASSERT_TRUE(std::isfinite(s.windU[c]) && std::isfinite(s.windV[c])) << label;
  }
  WeatherMap map = model.map();
  for (const firmament::Image* image : {&map.map, &map.wind})
    for (float v : image->pixels) ASSERT_TRUE(std::isfinite(v)) << label;
  for (size_t p = 0; p < map.map.pixelCount(); ++p) {
    const float* px = map.map.pixels.data() + 4 * p;
    ASSERT_TRUE(px[0] >= 0.0f && px[0] <= 1.0f && px[1] >= 0.0f && px[1] <= 1.0f && px[2] >= 0.0f) << label;
  }
  WaterBudget b = model.waterBudget();
  EXPECT_LE(std::fabs(b.imbalance_kg()), 1e-6 * b.initial_kg) << label;
}

struct Extreme {
  const char* name;
  const char* preset;
  double sunElevation;  // NaN: the summer day
  double wind, heating, dt, hours;
  int moisture;  // 0 as preset, 1 saturated (3× saturation), −1 bone dry
};

}  // namespace

TEST(Robustness, ExtremeInputsStayBoundedAndFinite) {
  const double nan = std::nan("");
  const double zenith = std::numbers::pi / 2;
  const Extreme cases[] = {
      {"no sun", "thunderstorm", -0.5, 8, 1, 60, 12, 0},
      {"zenith sun all day", "thunderstorm", zenith, 8, 1, 60, 24, 0},
      {"zenith sun, heating ×5", "thunderstorm", zenith, 8, 5, 60, 12, 0},
      {"60 m/s wind", "thunderstorm", nan, 60, 1, 60, 12, 0},
      {"saturated air", "thunderstorm", nan, 8, 1, 60, 12, 1},
      {"saturated air, front", "frontal", nan, 20, 1, 300, 12, 1},
      {"bone-dry air", "fair-weather", zenith, 8, 1, 60, 12, -1},
      {"one-day step", "thunderstorm", nan, 30, 1, 86400, 24, 0},
      {"6 h steps, saturated", "overcast", nan, 60, 5, 21600, 24, 1},
  };
  for (const Extreme& e : cases) {
    WeatherConfig c = test::smallConfig(e.preset, 48);
    c.windSpeed_m_s = e.wind;
    c.heatingScale = e.heating;
    c.timeStep_s = e.dt;
    SunElevationFunction sun = std::isnan(e.sunElevation) ? test::summerDay() : constantSunElevation(e.sunElevation);
    c.exchangeWithSurroundings = e.moisture >= 0;  // bone dry stays dry: no evaporation from the ground
    WeatherModel model(c, sun);
    if (e.moisture != 0) {
      WeatherState& s = model.mutableState();
      float saturated = float(3.0 * 1000.0 * 1.1 * saturationMixingRatio(300.0, 101325.0));
      for (float& v : s.vapour) v = e.moisture > 0 ? saturated : 0.0f;
      model.resetBudget();
    }
    model.advance(e.hours * 3600.0);
    expectBounded(model, e.name);
    if (e.moisture < 0) {
      EXPECT_EQ(model.stats().cloudFraction, 0.0) << "bone-dry air cannot make cloud";
    }
  }
}

TEST(Robustness, BadInputsAreInputErrors) {
  WeatherConfig c = test::smallConfig("clear", 16);
  WeatherModel model(c, constantSunElevation(0.5));
  EXPECT_THROW(model.step(0.0), firmament::InputError);
  EXPECT_THROW(model.step(std::nan("")), firmament::InputError);
  EXPECT_THROW(model.setHeatingMap(std::vector<float>(3, 1.0f)), firmament::InputError);
  EXPECT_THROW(model.setHeatingMap(std::vector<float>(16 * 16, -1.0f)), firmament::InputError);
}
