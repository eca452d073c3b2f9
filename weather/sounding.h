#pragma once
// The environment the boundary layer sits under, from a preset: a well-mixed (dry-adiabatic) layer to
// h, a capping inversion of ΔT at h, a free troposphere with lapse rate Γ to a stable layer, a weaker
// (or negative) lapse rate above it to the tropopause, isothermal above.
#include "weather/weather_presets.h"

namespace firmament::weather {

struct Sounding {
  double surfaceTemperature_K, boundaryLayerDepth_m, inversion_K;
  double lapseRate_K_m, stableLayerBase_m, upperLapseRate_K_m, tropopause_m;
  double surfacePressure_Pa;

  Sounding(const PresetParameters& p, double surfacePressure_Pa);
  double temperatureAt(double height_m) const;  // K
};

// Quantities of the boundary layer the operators share each step.
struct BoundaryLayer {
  double depth_m;
  double referenceTemperature_K;
  double surfacePressure_Pa, topPressure_Pa;
  double density_kg_m3;        // at the layer's mean height and reference temperature
  double heatCapacity_J_m2_K;  // ρ c_p h: J per m² per kelvin of layer warming
  double massPerArea_kg_m2;    // ρ h: converts mixing ratio to vapour path

  BoundaryLayer(const PresetParameters& p, double surfacePressure_Pa);
};

}  // namespace firmament::weather
