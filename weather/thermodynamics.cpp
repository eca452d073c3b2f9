#include "weather/thermodynamics.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "weather/physical_constants.h"

namespace firmament::weather {

double saturationVapourPressure(double temperature_K) {
  // Keep T away from the formula's pole at 35.85 K; the model never goes there, extreme inputs might.
  double t = std::clamp(temperature_K, 150.0, 373.15);
  return 610.78 * std::exp(17.27 * (t - 273.15) / (t - 35.85));
}

double mixingRatioFromVapourPressure(double vapourPressure_Pa, double pressure_Pa) {
  double e = std::clamp(vapourPressure_Pa, 0.0, 0.5 * pressure_Pa);
  return kEpsilon * e / (pressure_Pa - e);
}

double saturationMixingRatio(double temperature_K, double pressure_Pa) {
  return mixingRatioFromVapourPressure(saturationVapourPressure(temperature_K), pressure_Pa);
}

double vapourPressureFromMixingRatio(double mixingRatio, double pressure_Pa) {
  double r = std::max(mixingRatio, 0.0);
  return pressure_Pa * r / (kEpsilon + r);
}

double dewPoint(double vapourPressure_Pa) {
  double x = std::log(std::max(vapourPressure_Pa, 1e-3) / 610.78);
  x = std::min(x, 17.0);  // e far above any real saturation: keep the denominator positive
  return (17.27 * 273.15 - 35.85 * x) / (17.27 - x);
}

double liftingCondensationLevel(double temperature_K, double dewPoint_K) {
  return kLclMetresPerKelvin * std::max(0.0, temperature_K - dewPoint_K);
}

double moistAdiabaticLapseRate(double temperature_K, double pressure_Pa) {
  double t = std::max(temperature_K, 150.0);
  double rs = saturationMixingRatio(t, pressure_Pa);
  double numerator = kGravity * (1.0 + kLatentHeatVaporization * rs / (kDryAirGasConstant * t));
  double denominator = kDryAirHeatCapacity +
                       kLatentHeatVaporization * kLatentHeatVaporization * rs * kEpsilon / (kDryAirGasConstant * t * t);
  return numerator / denominator;
}

double pressureAtHeight(double surfacePressure_Pa, double height_m) {
  return surfacePressure_Pa * std::exp(-height_m / kPressureScaleHeight);
}

double airDensity(double pressure_Pa, double temperature_K) {
  return pressure_Pa / (kDryAirGasConstant * std::max(temperature_K, 150.0));
}

}  // namespace firmament::weather

namespace firmament::weather {

SaturationTables::SaturationTables() {
  int nt = int((kMaxT - kMinT) / kStepT) + 2;
  es.resize(nt);
  for (int i = 0; i < nt; ++i) es[i] = float(saturationVapourPressure(kMinT + i * kStepT));
  int ne = int(kMaxE / kStepE) + 2;
  td.resize(ne);
  for (int i = 0; i < ne; ++i) td[i] = float(dewPoint(std::max(1e-3, double(i) * kStepE)));
}

const SaturationTables gSaturationTables;

}  // namespace firmament::weather
