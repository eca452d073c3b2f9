#include "weather/surface_heating.h"

#include <algorithm>
#include <cmath>

#include "weather/domain_sum.h"
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

// Sums of the fields as the runs produce them, in sumField's order (SSE2 only; without it nothing is
// summed here and the caller sums the fields): the vapour before and after (the exchange) and the heat
// flux.
class HeatingSums {
 public:
#if defined(__SSE2__)
  explicit HeatingSums(size_t n) : vapourBefore_(n), vapourAfter_(n), heatFlux_(n) {}
  void before(const float* vapour, size_t begin, size_t end) { vapourBefore_.addRange(vapour, begin, end); }
  void after(const float* vapour, size_t begin, size_t end) { vapourAfter_.addRange(vapour, begin, end); }
  void flux(const float* heatFlux, size_t begin, size_t end) { heatFlux_.addRange(heatFlux, begin, end); }
  double vapourBefore() const { return vapourBefore_.total(); }
  double vapourAfter() const { return vapourAfter_.total(); }
  double heatFlux() const { return heatFlux_.total(); }

 private:
  sse::DomainSum vapourBefore_, vapourAfter_, heatFlux_;
#else
  explicit HeatingSums(size_t) {}
  void before(const float*, size_t, size_t) {}
  void after(const float*, size_t, size_t) {}
  void flux(const float*, size_t, size_t) {}
  double vapourBefore() const { return 0.0; }
  double vapourAfter() const { return 0.0; }
  double heatFlux() const { return 0.0; }
#endif
};

// Runs of 64 cells (clouds come in patches, so most runs are all clear or all cloudy at once); the sums
// of each run while it is in cache.
template <bool kExchange>
void heatColumns(size_t n, const HeatingConstants k, const float* heatingMap, const float* cloud, float* heatFlux,
                 float* temperature, float* vapour, HeatingSums* sums) {
  constexpr size_t kRun = 64;
  for (size_t start = 0; start < n; start += kRun) {
    const size_t m = std::min(kRun, n - start);
    int cloudy = 0;
    for (size_t c = start; c < start + m; ++c) cloudy |= cloud[c] > 0.0f;
    if (sums && kExchange) sums->before(vapour, start, start + m);
    if (cloudy)
      heatRun<true, kExchange>(m, k, heatingMap + start, cloud + start, heatFlux + start, temperature + start,
                               vapour + start);
    else
      heatRun<false, kExchange>(m, k, heatingMap + start, cloud + start, heatFlux + start, temperature + start,
                                vapour + start);
    if (sums) {
      if (kExchange) sums->after(vapour, start, start + m);
      sums->flux(heatFlux, start, start + m);
    }
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
  // The exchange is booked as the change of the field's total (the totals the budget is checked with),
  // summed as the runs go where that can be done in sumField's order.
  double exchanged = 0.0;
  HeatingSums sums(n);
#if defined(__SSE2__)
  HeatingSums* fused = n % 4 == 0 ? &sums : nullptr;
#else
  HeatingSums* fused = nullptr;
#endif
  if (p.exchangeWithSurroundings) {
    if (!fused) exchanged = -sumField(s.vapour);
    heatColumns<true>(n, k, heatingMap.data(), s.cloudWater.data(), s.surfaceHeatFlux.data(), s.temperature.data(),
                      s.vapour.data(), fused);
    if (fused) exchanged = -sums.vapourBefore();
    exchanged += fused ? sums.vapourAfter() : sumField(s.vapour);
  } else {
    heatColumns<false>(n, k, heatingMap.data(), s.cloudWater.data(), s.surfaceHeatFlux.data(), s.temperature.data(),
                       s.vapour.data(), fused);
  }
  s.meanSensibleHeat_W_m2 = (fused ? sums.heatFlux() : sumField(s.surfaceHeatFlux)) / double(n);
  return exchanged * s.cellArea();
}

}  // namespace firmament::weather
