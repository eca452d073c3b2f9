#include "weather/microphysics.h"

#include <algorithm>
#include <cmath>

#include "weather/fast_math.h"
#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {

double applyMicrophysics(WeatherState& s, const BoundaryLayer& layer, double dt_s, ColumnScratch& work) {
  constexpr float kAutoconversionRate = 1e-3f, kThresholdMixingRatio = 0.5e-3f, kFallSpeed = 6.0f;
  const float dt = float(dt_s);
  const float rho = float(layer.density_kg_m3);
  const float kelvinPerKg = float(kLatentHeatVaporization / layer.heatCapacity_J_m2_K);
  const float rhoH = float(layer.massPerArea_kg_m2);
  const float tRef = float(layer.referenceTemperature_K);
  const float p0 = float(layer.surfacePressure_Pa);
  double out = 0.0;
  const size_t n = s.cells();
  // Which cells have work, in a loop that vectorises: a column without rain whose cloud is below the
  // autoconversion threshold converts nothing (accretion needs rain) and drops nothing, so the full
  // update would leave it as it is. Everywhere else the rate is zero until the sparse pass sets it.
  {
    work.active.resize(n);
    const float* __restrict cloudW = s.cloudWater.data();
    const float* __restrict rainW = s.rain.data();
    const float* __restrict baseZ = s.cloudBase.data();
    const float* __restrict topZ = s.cloudTop.data();
    float* __restrict rate = s.precipitationRate.data();
    uint8_t* __restrict active = work.active.data();
    const float thresholdPerMetre = rho * kThresholdMixingRatio;
    for (size_t c = 0; c < n; ++c) {
      const float cloud = cloudW[c], rain = rainW[c], base = baseZ[c];
      const float top = std::max(topZ[c], base + 100.0f);
      const float threshold = thresholdPerMetre * std::min(top - base, 2000.0f);
      const bool empty = cloud <= 0.0f && rain <= 0.0f;
      const bool idle = rain == 0.0f && cloud <= threshold;
      active[c] = uint8_t(!(empty || idle));
      rate[c] = 0.0f;
    }
  }
  forEachActiveCell(work.active, [&](size_t c) {
    float cloud = s.cloudWater[c], rain = s.rain[c];
    float base = s.cloudBase[c], top = std::max(s.cloudTop[c], base + 100.0f);
    float depth = top - base;
    // Cloud → rain.
    if (cloud > 0.0f) {
      float threshold = rho * kThresholdMixingRatio * std::min(depth, 2000.0f);
      float rainMixing = rain / (rho * depth);
      float rate = kAutoconversionRate * std::max(0.0f, cloud - threshold) +
                   2.2f * cloud * powFast(rainMixing, 0.875f);
      if (rate > 0.0f) {
        float converted = cloud * oneMinusExpFast(rate * dt / cloud);
        transferWater(s.cloudWater[c], rain, converted);
      }
    }
    // Rain-out, part evaporating below the base.
    float midHeight = std::max(0.5f * (base + top), 500.0f);
    float fallen = rain * oneMinusExpFast(dt * kFallSpeed / midHeight);
    float vapour = s.vapour[c];
    float saturated = rhoH * saturationMixingRatioFast(tRef + s.temperature[c], p0);
    float humidity = saturated > 0.0f ? std::clamp(vapour / saturated, 0.0f, 1.0f) : 1.0f;
    float evaporatedShare = std::min(0.9f, 0.5f * (1.0f - humidity) * base * 1e-3f);
    float evaporated = fallen * evaporatedShare;
    float newRain = rain - fallen;
    float newVapour = vapour + evaporated;
    // What left the fields is exactly what the stored values lost (round-off included).
    double left = (double(rain) - double(newRain)) - (double(newVapour) - double(vapour));
    s.rain[c] = newRain;
    s.vapour[c] = newVapour;
    s.temperature[c] -= kelvinPerKg * evaporated;
    s.precipitationRate[c] = float(left / dt_s);
    out += left;
  });
  return out * s.cellArea();
}

}  // namespace firmament::weather
