// Semi-Lagrangian advection: a blob goes where u·t says, keeps its mass, and any step is stable.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "tests/weather/weather_test_support.h"
#include "weather/advection.h"
#include "weather/mixing.h"
#include "weather/transport.h"

using namespace firmament::weather;

namespace {

// Circular (periodic) centroid of a field along x and y, in cells.
std::pair<double, double> periodicCentroid(const Field& f, int nx, int ny) {
  double cx = 0, sx = 0, cy = 0, sy = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      double v = f[size_t(j) * nx + i];
      double ax = 2 * std::numbers::pi * (i + 0.0) / nx, ay = 2 * std::numbers::pi * (j + 0.0) / ny;
      cx += v * std::cos(ax);
      sx += v * std::sin(ax);
      cy += v * std::cos(ay);
      sy += v * std::sin(ay);
    }
  auto wrap = [](double a, int n) { return std::fmod(a / (2 * std::numbers::pi) * n + n, double(n)); };
  return {wrap(std::atan2(sx, cx), nx), wrap(std::atan2(sy, cy), ny)};
}

double periodicDistance(double a, double b, int n) {
  double d = std::fmod(std::fabs(a - b), double(n));
  return std::min(d, n - d);
}

Field gaussianBlob(int nx, int ny, double x0, double y0, double radius) {
  Field f(size_t(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      double dx = periodicDistance(i, x0, nx), dy = periodicDistance(j, y0, ny);
      f[size_t(j) * nx + i] = float(5.0 * std::exp(-(dx * dx + dy * dy) / (radius * radius)));
    }
  return f;
}

}  // namespace

TEST(Advection, BlobArrivesWhereUTimesTSaysWithItsMass) {
  const int n = 128;
  const double dx = 200.0, dt = 60.0, u = 7.3, v = -3.1;
  const int steps = 500;  // 30 000 s: 1095 km east... wrapped many times around the 25.6 km domain
  Field f = gaussianBlob(n, n, 40.0, 70.0, 4.0);
  Field windU(f.size(), float(u)), windV(f.size(), float(v));
  double mass0 = sumField(f);
  SemiLagrangianAdvection advection;
  advection.prepare(windU, windV, n, n, dx, dt);
  for (int s = 0; s < steps; ++s) advection.advectConserving(f);
  auto [cx, cy] = periodicCentroid(f, n, n);
  double ex = std::fmod(40.0 + u * dt * steps / dx, double(n)),
         ey = std::fmod(70.0 + v * dt * steps / dx + 10 * n, double(n));
  EXPECT_LT(periodicDistance(cx, ex, n), 1.0) << "centroid x " << cx << " expected " << ex;
  EXPECT_LT(periodicDistance(cy, ey, n), 1.0) << "centroid y " << cy << " expected " << ey;
  // The peak as well (not only the first moment).
  size_t peak = size_t(std::max_element(f.begin(), f.end()) - f.begin());
  EXPECT_LE(periodicDistance(double(peak % n), ex, n), 1.0);
  EXPECT_LE(periodicDistance(double(peak / n), ey, n), 1.0);
  EXPECT_LT(std::fabs(sumField(f) - mass0) / mass0, 1e-6);
  for (float x : f) ASSERT_GE(x, 0.0f);
}

TEST(Advection, HugeStepIsStableAndBounded) {
  const int n = 32;
  Field f = gaussianBlob(n, n, 10.0, 10.0, 3.0);
  float maxBefore = *std::max_element(f.begin(), f.end());
  Field windU(f.size(), 60.0f), windV(f.size(), -45.0f);
  SemiLagrangianAdvection advection;
  advection.prepare(windU, windV, n, n, 200.0, 86400.0);  // 26 000 cells in one step
  double mass0 = sumField(f);
  for (int s = 0; s < 10; ++s) advection.advectConserving(f);
  for (float x : f) {
    ASSERT_TRUE(std::isfinite(x));
    ASSERT_GE(x, 0.0f);
    ASSERT_LE(x, maxBefore * 1.0001f);  // bilinear interpolation is bounded by its neighbours
  }
  EXPECT_LT(std::fabs(sumField(f) - mass0) / mass0, 1e-6);
}

TEST(Advection, ModelMovesAVapourBlobWithThePrevailingWind) {
  // The whole model with a uniform wind (no perturbation, no buoyancy gradients: no sun, uniform T′),
  // dry air so nothing condenses, a closed box.
  WeatherConfig c = test::smallConfig("clear", 96);
  c.turbulence_m_s = 0.0;
  c.windSpeed_m_s = 10.0;
  c.windFrom_deg = 240.0;  // toward 60°: east-north-east
  c.exchangeWithSurroundings = false;
  WeatherModel model(c, constantSunElevation(-0.3));
  WeatherState& s = model.mutableState();
  std::fill(s.temperature.begin(), s.temperature.end(), 0.0f);
  Field blob = gaussianBlob(96, 96, 30.0, 30.0, 5.0);
  for (size_t i = 0; i < blob.size(); ++i) s.vapour[i] = 2.0f + blob[i];
  model.resetBudget();
  Field anomaly0(blob);
  auto [x0, y0] = periodicCentroid(anomaly0, 96, 96);
  model.advance(3 * 3600.0);
  Field anomaly(s.vapour.size());
  for (size_t i = 0; i < anomaly.size(); ++i) anomaly[i] = s.vapour[i] - 2.0f;
  auto [x1, y1] = periodicCentroid(anomaly, 96, 96);
  glm::dvec2 u = model.prevailingWind_m_s();
  double ex = std::fmod(x0 + u.x * 3 * 3600.0 / 200.0 + 960, 96.0),
         ey = std::fmod(y0 + u.y * 3 * 3600.0 / 200.0 + 960, 96.0);
  EXPECT_LT(periodicDistance(x1, ex, 96), 1.0) << x1 << " vs " << ex;
  EXPECT_LT(periodicDistance(y1, ey, 96), 1.0) << y1 << " vs " << ey;
  WaterBudget b = model.waterBudget();
  EXPECT_LT(std::fabs(b.imbalance_kg()) / b.initial_kg, 1e-6);
}

TEST(Advection, FusedTransportMatchesTheSeparateOperatorsBitForBit) {
  // transport.h: advection, mixing and the mass fix fused on a small grid give what the three separate
  // operators give, value for value, for every combination of fields the model carries and for one and
  // for two mixing iterations.
  const int n = 64;
  for (int fields = 0; fields < 3; ++fields)
    for (double dt : {60.0, 240.0}) {
      WeatherState s(n, n, 200.0);
      uint32_t h = 12345u + uint32_t(fields);
      auto noise = [&h]() {
        h = h * 1664525u + 1013904223u;
        return float(h >> 8) / float(1u << 24);
      };
      for (size_t c = 0; c < s.cells(); ++c) {
        s.temperature[c] = 2.0f * noise() - 1.0f;
        s.vapour[c] = 10.0f + noise();
        s.windU[c] = 8.0f + 3.0f * noise();
        s.windV[c] = -2.0f + 3.0f * noise();
        if (fields >= 1 && noise() < 0.3f) {
          s.cloudWater[c] = 0.2f * noise();
          s.rain[c] = 0.05f * noise();
        }
        if (fields == 2 && noise() < 0.1f) {
          s.updraft[c] = 5.0f * noise();
          s.cloudTop[c] = 3000.0f * noise();
          s.convectiveFraction[c] = noise();
        }
      }
      WeatherState expected = s;
      const double owed = 3.0;
      Transport transport;
      transport.advect(s, dt);
      transport.mixAndConserve(s, 100.0, dt, owed);

      const double vapourBefore = sumField(expected.vapour), cloudBefore = sumField(expected.cloudWater),
                   rainBefore = sumField(expected.rain);
      SemiLagrangianAdvection advection;
      advection.prepare(expected.windU, expected.windV, n, n, 200.0, dt);
      if (fields == 2)
        advection.advectFields({&expected.temperature, &expected.vapour, &expected.updraft, &expected.cloudTop,
                                &expected.convectiveFraction, &expected.cloudWater, &expected.rain});
      else if (fields == 1)
        advection.advectFields({&expected.temperature, &expected.vapour, &expected.cloudWater, &expected.rain});
      else
        advection.advectFields({&expected.temperature, &expected.vapour});
      Mixing mixing;
      mixing.apply(expected.temperature, n, n, 200.0, 100.0, dt);
      mixing.apply(expected.vapour, n, n, 200.0, 100.0, dt);
      if (cloudBefore > 0.0) mixing.apply(expected.cloudWater, n, n, 200.0, 100.0, dt);
      SemiLagrangianAdvection::restoreTotal(expected.vapour, vapourBefore + owed);
      if (cloudBefore > 0.0) SemiLagrangianAdvection::restoreTotal(expected.cloudWater, cloudBefore);
      if (rainBefore > 0.0) SemiLagrangianAdvection::restoreTotal(expected.rain, rainBefore);

      for (auto [got, want] : {std::pair{&s.temperature, &expected.temperature},
                               {&s.vapour, &expected.vapour},
                               {&s.cloudWater, &expected.cloudWater},
                               {&s.rain, &expected.rain},
                               {&s.updraft, &expected.updraft},
                               {&s.cloudTop, &expected.cloudTop},
                               {&s.convectiveFraction, &expected.convectiveFraction}})
        for (size_t c = 0; c < s.cells(); ++c)
          ASSERT_EQ(std::memcmp(&(*got)[c], &(*want)[c], sizeof(float)), 0)
              << "fields " << fields << " dt " << dt << " cell " << c << ": " << (*got)[c] << " vs " << (*want)[c];
    }
}
