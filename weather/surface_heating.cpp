#include "weather/surface_heating.h"

#include <algorithm>
#include <cmath>

#include "weather/fast_math.h"
#include "weather/physical_constants.h"

namespace firmament::weather {

float cloudCover(float w) { return oneMinusExpFast(std::max(w, 0.0f) * 20.0f); }

float cloudTransmission(float w) {
  constexpr float kAsymmetry = 0.85f, kEffectiveRadius = 10e-6f;
  float tau = 1.5f * std::max(w, 0.0f) / (float(kWaterDensity) * kEffectiveRadius);
  return 1.0f / (1.0f + 0.75f * (1.0f - kAsymmetry) * tau);
}

double applySurfaceHeating(WeatherState& s, const Field& heatingMap, const BoundaryLayer& layer,
                           const SurfaceHeatingParameters& p, double dt_s) {
  const float solar = float(p.absorbedSolar_W_m2 * std::max(0.0, std::sin(p.sunElevation_rad)));
  const float sensibleShare = float(p.bowenRatio / (1.0 + p.bowenRatio));
  const float latentPerWatt = float(1.0 / ((1.0 + p.bowenRatio) * kLatentHeatVaporization));
  const float kelvinPerJoule = float(1.0 / layer.heatCapacity_J_m2_K);
  const float dt = float(dt_s);
  const float tDecay = float(std::exp(-dt_s / p.temperatureRelaxation_s));
  const float qDecay = float(std::exp(-dt_s / p.vapourRelaxation_s));
  const float background = float(p.backgroundVapour_kg_m2);
  const float longwave = float(p.longwaveCooling_W_m2);
  double exchanged = 0.0, sensibleSum = 0.0;
  const size_t n = s.cells();
  for (size_t c = 0; c < n; ++c) {
    float w = s.cloudWater[c];
    float net = w > 0.0f ? solar * heatingMap[c] * cloudTransmission(w) - longwave * (1.0f - cloudCover(w))
                         : solar * heatingMap[c] - longwave;
    float sensible = net > 0.0f ? net * sensibleShare : net;
    s.surfaceHeatFlux[c] = sensible;
    sensibleSum += sensible;
    s.temperature[c] = (s.temperature[c] + sensible * kelvinPerJoule * dt) * tDecay;
    if (p.exchangeWithSurroundings) {
      float before = s.vapour[c];
      float evaporation = net > 0.0f ? net * latentPerWatt * dt : 0.0f;
      float after = std::max(0.0f, background + (before + evaporation - background) * qDecay);
      s.vapour[c] = after;
      exchanged += double(after) - double(before);
    }
  }
  s.meanSensibleHeat_W_m2 = sensibleSum / double(n);
  return exchanged * s.cellArea();
}

}  // namespace firmament::weather
