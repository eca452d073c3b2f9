#include "weather/boundary_layer_growth.h"

#include <algorithm>
#include <cmath>

#include "weather/physical_constants.h"

namespace firmament::weather {

double mixedLayerCeiling(double lcl, const LayerGrowthParameters& p) {
  return std::max(p.morningDepth_m,
                  std::min({kMaxLayerDepth_m, p.stableLayerBase_m - 300.0, lcl / kThermalOvershoot}));
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
    const double entrained = (1.0 + 2.0 * kEntrainmentRatio) * flux * dt_s /
                             (p.density_kg_m3 * kDryAirHeatCapacity * gamma * before);
    const double lcl = sumField(s.cloudBase) / double(n);
    const double ceiling = mixedLayerCeiling(lcl > 0.0 ? lcl : 1e9, p);
    grown = std::clamp(ceiling - before, 0.0, entrained);
    vented = std::min(entrained - grown, 0.5 * before);
    after = before + grown;
  } else {
    after = h0 + (before - h0) * std::exp(-dt_s / kLayerCollapseTime_s);
  }
  s.layerDepth_m = after;
  double exchanged = 0.0;
  if (after > before || vented > 0.0) {
    const float added = float(p.density_kg_m3 * (grown + vented) * p.entrainedMixingRatio);
    const float kept = float((before - vented) / before);
    for (size_t c = 0; c < n; ++c) {
      float v = s.vapour[c], mixed = v * kept + added;
      exchanged += double(mixed) - double(v);
      s.vapour[c] = mixed;
    }
  } else if (after < before) {
    const float kept = float(after / before);
    for (size_t c = 0; c < n; ++c) {
      float v = s.vapour[c], shrunk = v * kept;
      exchanged += double(shrunk) - double(v);
      s.vapour[c] = shrunk;
    }
  }
  return exchanged * s.cellArea();
}

}  // namespace firmament::weather
