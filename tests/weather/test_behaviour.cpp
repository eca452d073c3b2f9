// Behaviour over a summer day: the diurnal cycle of fair-weather cumulus, no heating → no convection,
// stronger heating → higher tops, thunderstorms make cumulonimbus and rain.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "tests/weather/weather_test_support.h"

using namespace firmament::weather;

namespace {

struct Day {
  std::vector<WeatherStats> samples;  // every 30 min from 03:00 UTC
  double maxUpdraft = 0.0;
  double peakCloud() const {
    double m = 0;
    for (auto& s : samples) m = std::max(m, s.cloudFraction);
    return m;
  }
};

Day runDay(WeatherConfig c, double hours = 24.0) {
  WeatherModel model(c, test::summerDay());
  Day day;
  day.samples.push_back(model.stats());
  for (int k = 0; k < int(hours * 2); ++k) {
    model.advance(1800.0);
    day.samples.push_back(model.stats());
    for (float w : model.state().updraft) day.maxUpdraft = std::max(day.maxUpdraft, double(w));
  }
  return day;
}

}  // namespace

TEST(Behaviour, FairWeatherDiurnalCycle) {
  Day day = runDay(test::smallConfig("fair-weather", 96));
  double peak = day.peakCloud();
  size_t peakAt = 0;
  for (size_t k = 0; k < day.samples.size(); ++k)
    if (day.samples[k].cloudFraction == peak) peakAt = k;
  auto solar = [](size_t k) { return test::localSolarHours(k * 1800.0); };
  std::printf("  fair weather: peak cloud fraction %.3f at %.1f h local solar time\n", peak, solar(peakAt));
  for (size_t k = 0; k < day.samples.size(); k += 2)
    std::printf("    %5.1f h  cloud %.3f  mean top %6.0f m\n", solar(k), day.samples[k].cloudFraction, day.samples[k].meanTop_m);
  EXPECT_GT(peak, 0.05);
  EXPECT_GE(solar(peakAt), 11.0);  // afternoon-ish peak (after late morning)
  EXPECT_LE(solar(peakAt), 18.0);
  for (size_t k = 0; k < day.samples.size(); ++k) {
    double h = solar(k);
    if (h <= 7.0) {
      EXPECT_LT(day.samples[k].cloudFraction, 0.02) << "dawn/morning at " << h;  // near zero at dawn
    }
    if (h >= 22.0) {
      EXPECT_LT(day.samples[k].cloudFraction, 0.1 * peak) << "after sunset at " << h;  // decayed
    }
  }
}

TEST(Behaviour, NoHeatingNoConvection) {
  for (const char* preset : {"fair-weather", "thunderstorm"}) {
    WeatherConfig c = test::smallConfig(preset, 48);
    c.heatingScale = 0.0;
    Day day = runDay(c, 18.0);
    EXPECT_EQ(day.maxUpdraft, 0.0) << preset;
    for (auto& s : day.samples) EXPECT_EQ(s.cumulonimbusFraction, 0.0) << preset;
  }
}

TEST(Behaviour, StrongerHeatingHigherTops) {
  double previous = -1.0;
  for (double scale : {0.7, 1.0, 1.5}) {
    WeatherConfig c = test::smallConfig("scattered-showers", 64);
    c.heatingScale = scale;
    Day day = runDay(c, 15.0);
    double highest = 0.0;
    for (auto& s : day.samples) highest = std::max(highest, s.meanTop_m);
    std::printf("  scattered showers, heating ×%.1f: highest mean top %.0f m, peak cloud %.3f\n", scale, highest, day.peakCloud());
    EXPECT_GT(highest, previous + 100.0) << "heating ×" << scale;
    previous = highest;
  }
}

TEST(Behaviour, ThunderstormMakesCumulonimbusAndRain) {
  Day day = runDay(test::smallConfig("thunderstorm", 96), 15.0);
  double cb = 0.0, rainArea = 0.0, top = 0.0;
  for (auto& s : day.samples) {
    cb = std::max(cb, s.cumulonimbusFraction);
    rainArea = std::max(rainArea, s.precipAreaFraction);
    top = std::max(top, s.maxTop_m);
  }
  std::printf("  thunderstorm: max Cb fraction %.3f, max rain area %.3f, max top %.0f m, updraft %.1f m/s, rain %.3e kg\n",
              cb, rainArea, top, day.maxUpdraft, day.samples.back().precipOut_kg);
  EXPECT_GT(cb, 0.01);
  EXPECT_GT(top, 8000.0);
  EXPECT_GT(rainArea, 0.01);
  EXPECT_GT(day.samples.back().precipOut_kg, 0.0);
  EXPECT_GT(day.maxUpdraft, 10.0);
}

TEST(Behaviour, OvercastMakesStratus) {
  Day day = runDay(test::smallConfig("overcast", 48), 12.0);
  EXPECT_GT(day.samples.back().cloudFraction, 0.8);
  EXPECT_LT(day.samples.back().meanTop_m, 4000.0);
}

TEST(Behaviour, DeterministicForASeed) {
  WeatherConfig c = test::smallConfig("thunderstorm", 48);
  c.seed = 42;
  WeatherModel a(c, test::summerDay()), b(c, test::summerDay());
  a.advance(8 * 3600.0);
  b.advance(8 * 3600.0);
  EXPECT_EQ(a.state().cloudWater, b.state().cloudWater);
  EXPECT_EQ(a.state().temperature, b.state().temperature);
  c.seed = 43;
  WeatherModel other(c, test::summerDay());
  other.advance(8 * 3600.0);
  EXPECT_NE(a.state().temperature, other.state().temperature);
}
