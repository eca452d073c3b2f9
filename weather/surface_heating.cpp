#include "weather/surface_heating.h"

#include <algorithm>
#include <cmath>

#include "weather/fast_math.h"
#include "weather/physical_constants.h"

namespace firmament::weather {

namespace {

struct HeatingConstants {
  float solar, longwave, sensibleShare, latentPerWatt, kelvinPerJoule, dt, tDecay, qDecay, background;
};

// A run of cells, in a loop that vectorises (restrict parameters, which GCC trusts here and not on
// pointers taken from vectors inside the caller). With cloud, the longwave loss L↑ (1 − c) is written
// L↑ e^{−w/w₀} (one expFast, no select); a run without cloud takes the clear formula R = S₀ m − L↑,
// which the cloudy one also gives for w = 0, without the exponential and the division.
template <bool kCloudy, bool kExchange>
void heatRun(size_t n, const HeatingConstants k, const float* __restrict heatingMap, const float* __restrict cloud,
             float* __restrict heatFlux, float* __restrict temperature, float* __restrict vapour) {
  for (size_t c = 0; c < n; ++c) {
    float net = k.solar * heatingMap[c] - k.longwave;
    if (kCloudy) {
      const float w = std::max(cloud[c], 0.0f);
      net = k.solar * heatingMap[c] * cloudTransmission(w) - k.longwave * expFast(-kCoverPerWater * w);
    }
    const float sensible = net > 0.0f ? net * k.sensibleShare : net;
    heatFlux[c] = sensible;
    temperature[c] = (temperature[c] + sensible * k.kelvinPerJoule * k.dt) * k.tDecay;
    if (kExchange) {
      const float evaporation = net > 0.0f ? net * k.latentPerWatt * k.dt : 0.0f;
      vapour[c] = std::max(0.0f, k.background + (vapour[c] + evaporation - k.background) * k.qDecay);
    }
  }
}

// Runs of 64 cells (clouds come in patches, so most runs are all clear or all cloudy at once).
template <bool kExchange>
void heatColumns(size_t n, const HeatingConstants k, const float* heatingMap, const float* cloud, float* heatFlux,
                 float* temperature, float* vapour) {
  constexpr size_t kRun = 64;
  for (size_t start = 0; start < n; start += kRun) {
    const size_t m = std::min(kRun, n - start);
    int cloudy = 0;
    for (size_t c = start; c < start + m; ++c) cloudy |= cloud[c] > 0.0f;
    if (cloudy)
      heatRun<true, kExchange>(m, k, heatingMap + start, cloud + start, heatFlux + start, temperature + start, vapour + start);
    else
      heatRun<false, kExchange>(m, k, heatingMap + start, cloud + start, heatFlux + start, temperature + start, vapour + start);
  }
}

}  // namespace

double applySurfaceHeating(WeatherState& s, const Field& heatingMap, const BoundaryLayer& layer,
                           const SurfaceHeatingParameters& p, double dt_s) {
  HeatingConstants k;
  k.solar = float(p.absorbedSolar_W_m2 * std::max(0.0, std::sin(p.sunElevation_rad)));
  k.sensibleShare = float(p.bowenRatio / (1.0 + p.bowenRatio));
  k.latentPerWatt = float(1.0 / ((1.0 + p.bowenRatio) * kLatentHeatVaporization));
  k.kelvinPerJoule = float(1.0 / layer.heatCapacity_J_m2_K);
  k.dt = float(dt_s);
  k.tDecay = float(std::exp(-dt_s / p.temperatureRelaxation_s));
  k.qDecay = float(std::exp(-dt_s / p.vapourRelaxation_s));
  k.background = float(p.backgroundVapour_kg_m2);
  k.longwave = float(p.longwaveCooling_W_m2);
  const size_t n = s.cells();
  // The exchange is booked as the change of the field's total (the totals the budget is checked with).
  double exchanged = 0.0;
  if (p.exchangeWithSurroundings) {
    exchanged = -sumField(s.vapour);
    heatColumns<true>(n, k, heatingMap.data(), s.cloudWater.data(), s.surfaceHeatFlux.data(), s.temperature.data(),
                      s.vapour.data());
    exchanged += sumField(s.vapour);
  } else {
    heatColumns<false>(n, k, heatingMap.data(), s.cloudWater.data(), s.surfaceHeatFlux.data(), s.temperature.data(),
                       s.vapour.data());
  }
  s.meanSensibleHeat_W_m2 = sumField(s.surfaceHeatFlux) / double(n);
  return exchanged * s.cellArea();
}

}  // namespace firmament::weather
