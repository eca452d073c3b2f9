#include "weather/sounding.h"

#include <algorithm>

#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {

Sounding::Sounding(const PresetParameters& p, double surfacePressure)
    : surfaceTemperature_K(p.referenceTemperature_K),
      boundaryLayerDepth_m(p.boundaryLayerDepth_m),
      inversion_K(p.inversion_K),
      lapseRate_K_m(p.lapseRate_K_per_km * 1e-3),
      stableLayerBase_m(std::max(p.stableLayerBase_m, p.boundaryLayerDepth_m)),
      upperLapseRate_K_m(p.upperLapseRate_K_per_km * 1e-3),
      tropopause_m(std::max(p.tropopause_m, std::max(p.stableLayerBase_m, p.boundaryLayerDepth_m))),
      surfacePressure_Pa(surfacePressure) {}

double Sounding::temperatureAt(double z) const {
  double h = boundaryLayerDepth_m;
  if (z <= h) return surfaceTemperature_K - kDryAdiabaticLapseRate * z;
  double t = surfaceTemperature_K - kDryAdiabaticLapseRate * h + inversion_K;
  double lower = std::min(z, stableLayerBase_m) - h;
  t -= lapseRate_K_m * lower;
  if (z > stableLayerBase_m) t -= upperLapseRate_K_m * (std::min(z, tropopause_m) - stableLayerBase_m);
  return t;
}

BoundaryLayer::BoundaryLayer(const PresetParameters& p, double surfacePressure)
    : depth_m(std::max(p.boundaryLayerDepth_m, 50.0)),
      referenceTemperature_K(p.referenceTemperature_K),
      surfacePressure_Pa(surfacePressure),
      topPressure_Pa(pressureAtHeight(surfacePressure, depth_m)) {
  double meanTemperature = referenceTemperature_K - 0.5 * kDryAdiabaticLapseRate * depth_m;
  density_kg_m3 = airDensity(pressureAtHeight(surfacePressure, 0.5 * depth_m), meanTemperature);
  massPerArea_kg_m2 = density_kg_m3 * depth_m;
  heatCapacity_J_m2_K = massPerArea_kg_m2 * kDryAirHeatCapacity;
}

}  // namespace firmament::weather
