// Water is conserved: vapour + cloud + rain + precipitated out (− exchanged in) stays constant to
// < 1e-6 relative over a day, through storms, for any step length.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/weather/weather_test_support.h"

using namespace firmament::weather;

namespace {

double dayImbalance(WeatherConfig c) {
  WeatherModel model(c, test::summerDay());
  model.advance(24 * 3600.0);
  WaterBudget b = model.waterBudget();
  double relative = std::fabs(b.imbalance_kg()) / b.initial_kg;
  std::printf("  %-14s exchange %-3s dt %5.0f s: precipitated %.3e kg, exchanged %.3e kg, |imbalance| %.2e relative\n",
              c.preset.c_str(), c.exchangeWithSurroundings ? "on" : "off", c.timeStep_s, b.precipitatedOut_kg,
              b.exchangedIn_kg, relative);
  return relative;
}

}  // namespace

TEST(Conservation, ClosedBoxThunderstormDay) {
  WeatherConfig c = test::smallConfig("thunderstorm", 96);
  c.exchangeWithSurroundings = false;
  EXPECT_LT(dayImbalance(c), 1e-6);
}

TEST(Conservation, OpenBudgetThunderstormDay) {
  WeatherConfig c = test::smallConfig("thunderstorm", 96);
  WeatherModel model(c, test::summerDay());
  model.advance(24 * 3600.0);
  WaterBudget b = model.waterBudget();
  EXPECT_GT(b.precipitatedOut_kg, 0.0);  // the test exercises rain-out
  EXPECT_LT(std::fabs(b.imbalance_kg()) / b.initial_kg, 1e-6);
}

TEST(Conservation, FrontalDayWithLongSteps) {
  WeatherConfig c = test::smallConfig("frontal", 64);
  c.timeStep_s = 900.0;  // sub-stepped
  EXPECT_LT(dayImbalance(c), 1e-6);
}
