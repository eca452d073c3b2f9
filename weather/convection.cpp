#include "weather/convection.h"

#include <algorithm>
#include <cmath>

#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {

void applyConvection(WeatherState& s, const ParcelTable& table, const BoundaryLayer& layer,
                     const ConvectionParameters& p, double dt_s) {
  constexpr float kCoreFraction = 0.1f, kUpdraftTime_s = 600.0f, kBuoyancyFrequency = 0.02f;
  constexpr float kMeanMoistLapse = 6.0e-3f;
  const float dt = float(dt_s);
  const float relax = 1.0f - std::exp(-dt / kUpdraftTime_s);
  const float rhoH = float(layer.massPerArea_kg_m2);
  const float depth = float(layer.depth_m);
  const float tRef = float(layer.referenceTemperature_K);
  const float p0 = float(layer.surfacePressure_Pa);
  const float maxTop = float(p.tropopause_m) + 2000.0f;
  const float deardorff = float(kGravity * layer.depth_m / layer.heatCapacity_J_m2_K);  // g h /(ρ c_p)
  const size_t n = s.cells();
  for (size_t c = 0; c < n; ++c) {
    float anomaly = s.temperature[c];
    float surfaceT = tRef + anomaly;
    float vapour = s.vapour[c];
    float mixing = vapour / rhoH;
    float e = p0 * mixing / (float(kEpsilon) + mixing);
    float depression = std::max(0.0f, surfaceT - dewPointFast(e));
    float lcl = float(kLclMetresPerKelvin) * depression;
    s.cloudBase[c] = lcl;

    ParcelProperties parcel = table.lookup(anomaly, depression);
    float w = s.updraft[c];
    bool triggered = false;
    if (parcel.cape_J_kg > 0.0f) {
      float heat = s.surfaceHeatFlux[c];
      float wStar = cbrtFast(deardorff * heat / surfaceT);
      float thermal = wStar + std::max(0.0f, s.lift[c]) + w;
      triggered = 0.5f * thermal * thermal >= parcel.cin_J_kg;
    }
    if (!triggered && w == 0.0f) continue;
    float target = triggered ? std::min(0.5f * std::sqrt(2.0f * parcel.cape_J_kg), 60.0f) : 0.0f;
    w += (target - w) * relax;
    if (w < 0.01f) w = 0.0f;  // a dead updraft is zero, not an endless exponential tail
    s.updraft[c] = w;
    if (!triggered || w < 0.05f) continue;

    // Cloud top: grows at w toward the LNB plus overshoot; collapses toward it if above.
    float topTarget = std::min(std::max(parcel.neutralBuoyancyLevel_m, lcl) + w / kBuoyancyFrequency, maxTop);
    float top = std::max(s.cloudTop[c], lcl);
    top = top < topTarget ? std::min(topTarget, top + w * dt) : topTarget + (top - topTarget) * (1.0f - relax);
    s.cloudTop[c] = top;

    // Condensation into the core.
    float lclTemperature = surfaceT - float(kDryAdiabaticLapseRate) * lcl;
    float topTemperature = lclTemperature - kMeanMoistLapse * (top - lcl);
    float topPressure = p0 * std::exp(top * float(-1.0 / kPressureScaleHeight));
    float remaining = rhoH * saturationMixingRatioFast(topTemperature, topPressure);
    float exchange = 1.0f - std::exp(-kCoreFraction * w / depth * dt);
    float dq = std::max(0.0f, vapour - remaining) * exchange;
    float cloud = s.cloudWater[c];
    transferWater(s.vapour[c], s.cloudWater[c], dq);
    float conv = s.convectiveFraction[c];
    s.convectiveFraction[c] = cloud + dq > 0.0f ? (conv * cloud + dq) / (cloud + dq) : 1.0f;
    if (anomaly > 0.0f) s.temperature[c] = anomaly * (1.0f - exchange);
  }
}

}  // namespace firmament::weather
