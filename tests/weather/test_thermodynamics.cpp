// Saturation, dew point, LCL and moist lapse rate against published values.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "weather/fast_math.h"
#include "weather/fast_math_sse.h"
#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"
#include "weather/weather_state.h"

using namespace firmament::weather;

TEST(Thermodynamics, TetensMatchesTabulatedSaturationPressure) {
  // Goff–Gratch values (Smithsonian Meteorological Tables; List 1951): 611.2 Pa at 0 °C, 2339 Pa at
  // 20 °C, 4246 Pa at 30 °C. Tetens is within 0.5 % there.
  EXPECT_NEAR(saturationVapourPressure(273.15), 611.2, 611.2 * 0.005);
  EXPECT_NEAR(saturationVapourPressure(293.15), 2339.0, 2339.0 * 0.005);
  EXPECT_NEAR(saturationVapourPressure(303.15), 4246.0, 4246.0 * 0.005);
}

TEST(Thermodynamics, DewPointInvertsSaturation) {
  for (double t = 230.0; t <= 320.0; t += 5.0) EXPECT_NEAR(dewPoint(saturationVapourPressure(t)), t, 1e-6);
}

TEST(Thermodynamics, EspyLcl) {
  EXPECT_DOUBLE_EQ(liftingCondensationLevel(303.15, 293.15), 1250.0);
  EXPECT_DOUBLE_EQ(liftingCondensationLevel(290.0, 295.0), 0.0);  // supersaturated input: at the ground
}

TEST(Thermodynamics, MoistLapseRateMatchesGlossaryValues) {
  // AMS Glossary / Wallace & Hobbs: ≈ 4.3 K/km at 20 °C and 1000 hPa, ≈ 6.5 K/km at 0 °C and 1000 hPa,
  // approaching the dry rate in cold air.
  EXPECT_NEAR(moistAdiabaticLapseRate(293.15, 100000.0) * 1e3, 4.3, 0.3);
  EXPECT_NEAR(moistAdiabaticLapseRate(273.15, 100000.0) * 1e3, 6.5, 0.4);
  EXPECT_NEAR(moistAdiabaticLapseRate(213.15, 20000.0) * 1e3, kDryAdiabaticLapseRate * 1e3, 0.3);
}

TEST(Thermodynamics, FastTablesMatchFormulas) {
  for (float t = 160.0f; t < 370.0f; t += 0.37f) {
    double exact = saturationVapourPressure(t);
    EXPECT_NEAR(saturationVapourPressureFast(t), exact, exact * 2e-5 + 1e-9) << t;
  }
  for (float e = 1.0f; e < 15000.0f; e *= 1.13f) EXPECT_NEAR(dewPointFast(e), dewPoint(e), 0.01) << e;
  for (float x : {1e-6f, 0.3f, 1.0f, 27.0f, 1234.5f}) EXPECT_NEAR(cbrtFast(x), std::cbrt(x), 1e-5 * std::cbrt(x));
  EXPECT_EQ(cbrtFast(0.0f), 0.0f);
  EXPECT_EQ(cbrtFast(-3.0f), 0.0f);
}

// The float exp/log the per-cell physics uses, against double libm (weather/fast_math.h).
TEST(Thermodynamics, FastExpAndLogMatchLibm) {
  double expError = 0.0, logError = 0.0, powError = 0.0, oneMinusError = 0.0;
  for (float x = -87.0f; x < 88.0f; x += 0.0137f) {
    double exact = std::exp(double(x));
    expError = std::max(expError, std::fabs(expFast(x) - exact) / exact);
  }
  for (float x = 1e-3f; x < 1e3f; x *= 1.0013f)
    logError = std::max(logError, std::fabs(logFast(x) - std::log(double(x))));
  for (float x = 1e-8f; x < 1.0f; x *= 1.001f) {
    double exact = std::pow(double(x), 0.875);
    powError = std::max(powError, std::fabs(powFast(x, 0.875f) - exact) / exact);
  }
  for (float x = 1e-7f; x < 20.0f; x *= 1.001f) {
    double exact = -std::expm1(-double(x));
    oneMinusError = std::max(oneMinusError, std::fabs(oneMinusExpFast(x) - exact) / exact);
  }
  EXPECT_LT(expError, 3e-7);
  EXPECT_LT(logError, 4e-7);
  EXPECT_LT(powError, 2e-6);
  EXPECT_LT(oneMinusError, 1e-6);
  EXPECT_EQ(powFast(0.0f, 0.875f), 0.0f);
  EXPECT_EQ(oneMinusExpFast(0.0f), 0.0f);
}

#if defined(__SSE2__)
// The four-lane versions give the scalar results bit for bit (weather/fast_math_sse.h), which is what
// lets the SSE2 loops and their scalar tails agree.
TEST(Thermodynamics, SseLanesMatchScalarBitForBit) {
  auto lanes = [](__m128 v) {
    alignas(16) float out[4];
    _mm_store_ps(out, v);
    return std::array<float, 4>{out[0], out[1], out[2], out[3]};
  };
  auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  int checked = 0;
  for (float x = -100.0f; x < 100.0f; x += 0.731f) {
    const float in[4] = {x, x * 0.5f, -x, x + 0.25f};
    const __m128 v = _mm_loadu_ps(in);
    const auto e = lanes(sse::expFast(v)), m = lanes(sse::oneMinusExpFast(_mm_max_ps(v, _mm_setzero_ps())));
    const auto l = lanes(sse::logFast(_mm_add_ps(_mm_mul_ps(v, v), _mm_set1_ps(1e-3f))));
    const auto p = lanes(sse::powFast(v, 0.875f)), c = lanes(sse::cbrtFast(v));
    const auto r = lanes(saturationMixingRatioFast4(_mm_add_ps(_mm_set1_ps(273.15f), v), _mm_set1_ps(90000.0f)));
    for (int k = 0; k < 4; ++k) {
      const float a = in[k];
      EXPECT_TRUE(same(e[k], expFast(a))) << a;
      EXPECT_TRUE(same(m[k], oneMinusExpFast(std::max(a, 0.0f)))) << a;
      EXPECT_TRUE(same(l[k], logFast(a * a + 1e-3f))) << a;
      EXPECT_TRUE(same(p[k], powFast(a, 0.875f))) << a;
      EXPECT_TRUE(same(c[k], cbrtFast(a))) << a;
      EXPECT_TRUE(same(r[k], saturationMixingRatioFast(273.15f + a, 90000.0f))) << a;
      ++checked;
    }
  }
  // transferWater: traces into large paths, ordinary moves, nothing, more than there is.
  const float from[4] = {1e-6f, 0.3f, 5.0f, 2.0f}, to[4] = {13.0f, 0.7f, 1e-3f, 0.0f},
              amount[4] = {1e-6f, 0.1f, 0.0f, 3.0f};
  __m128 f = _mm_loadu_ps(from), t = _mm_loadu_ps(to);
  sse::transferWater(f, t, _mm_loadu_ps(amount));
  const auto fl = lanes(f), tl = lanes(t);
  for (int k = 0; k < 4; ++k) {
    float a = from[k], b = to[k];
    transferWater(a, b, amount[k]);
    EXPECT_TRUE(same(fl[k], a) && same(tl[k], b)) << k;
  }
  EXPECT_GT(checked, 1000);
}
#endif
