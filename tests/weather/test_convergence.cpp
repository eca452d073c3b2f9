// Convergence in the time step: halving Δt changes the day's domain statistics by a small, stated amount.
// The model's fastest process (updraft spin-up, τ = 600 s) and the 120 s sub-step cap bound the splitting
// error; the statistics are integrals over the day, so Δt = 60 s against 30 s must agree to within 10 %
// of their magnitude, and the change from 60 → 30 s must not exceed the change from 120 → 60 s by more
// than a factor 1.5 (the sequence is not diverging).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/weather/weather_test_support.h"

using namespace firmament::weather;

namespace {

struct DayIntegrals {
  double meanCloud = 0.0, meanTop = 0.0, precipitation = 0.0;
};

DayIntegrals integrate(const char* preset, double dt) {
  WeatherConfig c = test::smallConfig(preset, 64);
  c.timeStep_s = dt;
  WeatherModel model(c, test::summerDay());
  DayIntegrals d;
  const int samples = 15 * 6;  // every 10 min over 15 h
  for (int k = 0; k < samples; ++k) {
    model.advance(600.0);
    WeatherStats s = model.stats();
    d.meanCloud += s.cloudFraction / samples;
    d.meanTop += s.meanTop_m / samples;
  }
  d.precipitation = model.waterBudget().precipitatedOut_kg;
  return d;
}

double relative(double a, double b) { return std::fabs(a - b) / std::max(std::fabs(b), 1e-12); }

void checkConvergence(const char* preset, bool rains) {
  DayIntegrals d120 = integrate(preset, 120.0), d60 = integrate(preset, 60.0), d30 = integrate(preset, 30.0);
  std::printf("  %s: mean cloud %.4f / %.4f / %.4f, mean top %.0f / %.0f / %.0f m, rain %.4e / %.4e / %.4e kg "
              "(Δt 120 / 60 / 30 s)\n",
              preset, d120.meanCloud, d60.meanCloud, d30.meanCloud, d120.meanTop, d60.meanTop, d30.meanTop,
              d120.precipitation, d60.precipitation, d30.precipitation);
  std::printf("    relative change 60→30 s: cloud %.3f, top %.3f, rain %.3f\n", relative(d60.meanCloud, d30.meanCloud),
              relative(d60.meanTop, d30.meanTop), rains ? relative(d60.precipitation, d30.precipitation) : 0.0);
  EXPECT_LT(relative(d60.meanCloud, d30.meanCloud), 0.10);
  EXPECT_LT(relative(d60.meanTop, d30.meanTop), 0.10);
  EXPECT_LE(std::fabs(d60.meanCloud - d30.meanCloud), 1.5 * std::fabs(d120.meanCloud - d60.meanCloud) + 0.002);
  if (rains) {
    EXPECT_LT(relative(d60.precipitation, d30.precipitation), 0.10);
  }
}

}  // namespace

TEST(Convergence, FairWeatherHalvingTheStep) { checkConvergence("fair-weather", false); }
TEST(Convergence, ThunderstormHalvingTheStep) { checkConvergence("thunderstorm", true); }
