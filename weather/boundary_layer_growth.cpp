#include "weather/boundary_layer_growth.h"

#include <algorithm>
#include <cmath>

#include "weather/domain_sum.h"
#include "weather/physical_constants.h"

namespace firmament::weather {

double mixedLayerCeiling(double lcl, const LayerGrowthParameters& p) {
  return std::max(p.morningDepth_m, std::min({kMaxLayerDepth_m, p.stableLayerBase_m - 300.0, lcl / kThermalOvershoot}));
}

double applyLayerGrowth(WeatherState& s, const LayerGrowthParameters& p, double dt_s) {
  const double h0 = p.morningDepth_m, before = s.layerDepth_m;
  if (!p.exchangeWithSurroundings) {
    s.layerDepth_m = h0;
    return 0.0;
  }
  const size_t n = s.cells();
  const double flux = s.meanSensibleHeat_W_m2;
  double grown = 0.0, vented = 0.0, after = before;
  if (flux > 0.0) {
    const double gamma = std::max(kDryAdiabaticLapseRate - p.freeLapseRate_K_m, 1e-4);  // never neutral
    const double entrained =
        (1.0 + 2.0 * kEntrainmentRatio) * flux * dt_s / (p.density_kg_m3 * kDryAirHeatCapacity * gamma * before);
    const double lcl = sumField(s.cloudBase) / double(n);
    const double ceiling = mixedLayerCeiling(lcl > 0.0 ? lcl : 1e9, p);
    grown = std::clamp(ceiling - before, 0.0, entrained);
    vented = std::min(entrained - grown, 0.5 * before);
    after = before + grown;
  } else {
    after = h0 + (before - h0) * std::exp(-dt_s / kLayerCollapseTime_s);
  }
  s.layerDepth_m = after;
  // The exchange is booked as the change of the field's total (the totals the budget is checked with;
  // a running sum of per-cell changes would be one long chain of dependent double additions).
  double exchanged = 0.0;
  float* vapour = s.vapour.data();
  const bool grows = after > before || vented > 0.0;
  if (!grows && !(after < before)) return 0.0;
  const float added = grows ? float(p.density_kg_m3 * (grown + vented) * p.entrainedMixingRatio) : 0.0f;
  const float kept = grows ? float((before - vented) / before) : float(after / before);
  auto update = [&](size_t begin, size_t end) {
    if (grows)
      for (size_t c = begin; c < end; ++c) vapour[c] = vapour[c] * kept + added;
    else
      for (size_t c = begin; c < end; ++c) vapour[c] = vapour[c] * kept;
  };
#if defined(__SSE2__)
  // In runs of 256 cells, each summed before and after while in cache (sumField's order).
  if (n % 4 == 0) {
    sse::DomainSum total(n), totalAfter(n);
    constexpr size_t kRun = 256;
    for (size_t begin = 0; begin < n; begin += kRun) {
      const size_t end = std::min(n, begin + kRun);
      total.addRange(vapour, begin, end);
      update(begin, end);
      totalAfter.addRange(vapour, begin, end);
    }
    exchanged = -total.total();
    exchanged += totalAfter.total();
    return exchanged * s.cellArea();
  }
#endif
  exchanged = -sumField(s.vapour);
  update(0, n);
  exchanged += sumField(s.vapour);
  return exchanged * s.cellArea();
}

}  // namespace firmament::weather
