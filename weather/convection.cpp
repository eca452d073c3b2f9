#include "weather/convection.h"

#include <algorithm>
#include <cmath>

#include "weather/fast_math.h"
#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {

ConvectionResult applyConvection(WeatherState& s, const ParcelTable& table, const BoundaryLayer& layer,
                                 const ConvectionParameters& p, double dt_s) {
  constexpr float kCoreFraction = 0.1f, kUpdraftTime_s = 600.0f, kBuoyancyFrequency = 0.02f;
  constexpr float kMeanMoistLapse = 6.0e-3f;
  const float dt = float(dt_s);
  const float relax = 1.0f - std::exp(-dt / kUpdraftTime_s);
  const float rhoH = float(layer.massPerArea_kg_m2), invRhoH = 1.0f / rhoH;
  const float depth = float(layer.depth_m);
  const float tRef = float(layer.referenceTemperature_K);
  const float p0 = float(layer.surfacePressure_Pa);
  const float maxTop = float(p.tropopause_m) + 2000.0f;
  // g h/(ρ c_p) (heatCapacity is ρ c_p h per m²).
  const float deardorff = float(kGravity * layer.depth_m * layer.depth_m / layer.heatCapacity_J_m2_K);
  const float inflowPerKelvin = float(1.0 / p.coldPoolCutoff_K);
  const float exchangePerUpdraft = kCoreFraction / depth * dt;
  const float invScaleHeight = float(-1.0 / kPressureScaleHeight);
  const size_t n = s.cells();
  // The cold pool is cold against its surroundings: T′ relative to the domain mean.
  const float environment = float(sumField(s.temperature) / double(n));
  // Cloud base (LCL) of every cell first, in a loop that vectorises: the dew point from Tetens inverted
  // with logFast (dewPoint in thermodynamics.h; |error| < 1e-4 K against the double formula).
  {
    const float eps = float(kEpsilon), espy = float(kLclMetresPerKelvin);
    const float invE0 = 1.0f / 610.78f;
    for (size_t c = 0; c < n; ++c) {
      const float mixing = s.vapour[c] * invRhoH;
      const float e = std::max(p0 * mixing / (eps + mixing), 1e-3f);
      const float x = std::min(logFast(e * invE0), 17.0f);
      const float dew = (17.27f * 273.15f - 35.85f * x) / (17.27f - x);
      s.cloudBase[c] = espy * std::max(0.0f, tRef + s.temperature[c] - dew);
    }
  }
  const float ownShare = float(1.0 - p.inflowFraction);
  double updraftSum = 0.0, drawn = 0.0;
  for (size_t c = 0; c < n; ++c) {
    const float anomaly = s.temperature[c];
    const float surfaceT = tRef + anomaly;
    const float vapour = s.vapour[c];
    const float lcl = s.cloudBase[c];
    const float depression = lcl * float(1.0 / kLclMetresPerKelvin);

    // Trigger; the table cell's bounds reject most clear cells with one load.
    const float shift = p.subsidenceWarming_K ? (*p.subsidenceWarming_K)[c] : 0.0f;
    const ParcelTable::Position at = table.locate(anomaly - shift, depression);
    const ParcelTable::CellBounds& bounds = table.bounds(at);
    float w = s.updraft[c];
    bool triggered = false;
    ParcelProperties parcel;
    if (bounds.maxCape > 0.0f) {
      const float heat = s.surfaceHeatFlux[c];
      const float wStar = heat > 0.0f ? cbrtFast(deardorff * heat / surfaceT) : 0.0f;
      const float inflow = std::clamp(1.0f + (anomaly - environment) * inflowPerKelvin, 0.0f, 1.0f);
      const float thermal = wStar + std::max(0.0f, s.lift[c]) + w * inflow;
      const float kinetic = 0.5f * thermal * thermal;
      if (kinetic >= bounds.minCin) {
        parcel = table.lookup(at);
        triggered = parcel.cape_J_kg > 0.0f && kinetic >= parcel.cin_J_kg;
      }
    }
    if (!triggered && w == 0.0f) continue;
    const float target = triggered ? std::min(0.5f * std::sqrt(2.0f * parcel.cape_J_kg), 60.0f) : 0.0f;
    w += (target - w) * relax;
    if (w < 0.01f) w = 0.0f;  // a dead updraft is zero, not an endless exponential tail
    s.updraft[c] = w;
    updraftSum += w;
    if (!triggered || w < 0.05f) continue;

    // Cloud top: grows at w toward the LNB plus overshoot; collapses toward it if above.
    const float topTarget = std::min(std::max(parcel.neutralBuoyancyLevel_m, lcl) + w / kBuoyancyFrequency, maxTop);
    float top = std::max(s.cloudTop[c], lcl);
    top = top < topTarget ? std::min(topTarget, top + w * dt) : topTarget + (top - topTarget) * (1.0f - relax);
    s.cloudTop[c] = top;

    // Condensation into the core.
    const float lclTemperature = surfaceT - float(kDryAdiabaticLapseRate) * lcl;
    const float topTemperature = lclTemperature - kMeanMoistLapse * (top - lcl);
    const float topPressure = p0 * expFast(top * invScaleHeight);
    const float remaining = rhoH * saturationMixingRatioFast(topTemperature, topPressure);
    const float exchange = oneMinusExpFast(exchangePerUpdraft * w);
    const float dq = std::max(0.0f, vapour - remaining) * exchange;
    const float cloud = s.cloudWater[c];
    // The cloud gains dq, the cell's vapour loses its own share; what the stored floats gained and lost
    // differs by the catchment's share (and round-off), booked exactly in double.
    const float newCloud = cloud + dq, newVapour = std::max(0.0f, vapour - ownShare * dq);
    drawn += (double(newCloud) - double(cloud)) - (double(vapour) - double(newVapour));
    s.cloudWater[c] = newCloud;
    s.vapour[c] = newVapour;
    const float conv = s.convectiveFraction[c];
    s.convectiveFraction[c] = cloud + dq > 0.0f ? (conv * cloud + dq) / (cloud + dq) : 1.0f;
    // The exchanged air is replaced by the surroundings': a warm anomaly relaxes toward them.
    if (anomaly > environment) s.temperature[c] = environment + (anomaly - environment) * (1.0f - exchange);
  }
  return {double(kCoreFraction) * updraftSum / double(n), drawn};
}

}  // namespace firmament::weather
