#include "weather/parcel_table.h"

#include <algorithm>
#include <cmath>

#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {

ParcelProperties ParcelTable::ascend(const Sounding& s, double surfaceTemperature, double depression) {
  constexpr double kDz = 150.0, kTop = 16050.0;
  double lcl = kLclMetresPerKelvin * std::max(0.0, depression);
  ParcelProperties out;
  double cin = 0.0, cape = 0.0;
  double parcel = surfaceTemperature;
  double previousB = kGravity * (parcel - s.temperatureAt(0.0)) / s.temperatureAt(0.0);
  bool free = false;
  for (double z = kDz; z <= kTop; z += kDz) {
    // Dry below the LCL, moist (lapse at the layer's start) above; a step straddling the LCL splits.
    double z0 = z - kDz;
    if (z <= lcl) {
      parcel -= kDryAdiabaticLapseRate * kDz;
    } else {
      double dry = std::max(0.0, lcl - z0);
      parcel -= kDryAdiabaticLapseRate * dry;
      parcel -= moistAdiabaticLapseRate(parcel, pressureAtHeight(s.surfacePressure_Pa, z0 + dry)) * (kDz - dry);
    }
    double env = s.temperatureAt(z);
    double b = kGravity * (parcel - env) / env;
    if (!free) {
      cin += 0.5 * kDz * (std::max(0.0, -previousB) + std::max(0.0, -b));
      if (z > lcl && b > 0.0) {
        free = true;
        out.freeConvectionLevel_m = float(z);
        cape += 0.5 * kDz * b;
      }
    } else {
      if (b < 0.0) {
        // Linear zero crossing between z0 and z.
        double f = previousB / (previousB - b);
        cape += 0.5 * kDz * f * previousB;
        out.neutralBuoyancyLevel_m = float(z0 + f * kDz);
        break;
      }
      cape += 0.5 * kDz * (previousB + b);
      out.neutralBuoyancyLevel_m = float(z);
    }
    previousB = b;
  }
  out.cin_J_kg = float(cin);
  out.cape_J_kg = free ? float(cape) : 0.0f;
  if (!free) out.neutralBuoyancyLevel_m = 0.0f;
  return out;
}

void ParcelTable::build(const Sounding& s) {
  nAnomaly_ = int(std::lround((kMaxAnomaly - kMinAnomaly) / kStep)) + 1;
  nDepression_ = int(std::lround(kMaxDepression / kStep)) + 1;
  maxA_ = float(nAnomaly_ - 1) - 1e-3f;
  maxD_ = float(nDepression_ - 1) - 1e-3f;
  size_t n = size_t(nAnomaly_) * nDepression_;
  for (auto* v : {&cin_, &cape_, &lfc_, &lnb_}) v->resize(n);
  for (int d = 0; d < nDepression_; ++d)
    for (int a = 0; a < nAnomaly_; ++a) {
      ParcelProperties p = ascend(s, s.surfaceTemperature_K + kMinAnomaly + a * kStep, d * kStep);
      size_t i = size_t(d) * nAnomaly_ + a;
      cin_[i] = p.cin_J_kg;
      cape_[i] = p.cape_J_kg;
      lfc_[i] = p.freeConvectionLevel_m;
      lnb_[i] = p.neutralBuoyancyLevel_m;
    }
}

}  // namespace firmament::weather
