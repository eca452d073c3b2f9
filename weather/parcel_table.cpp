#include "weather/parcel_table.h"

#include <algorithm>
#include <cmath>

#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {

namespace {

constexpr double kDz = 150.0;
constexpr int kLevels = 107;  // 150 m … 16 050 m

// The parcel's temperature after each 150 m step: dry below the LCL, moist (lapse at the layer's start)
// above; a step straddling the LCL splits. It depends on the surface state only, not on the sounding.
void parcelProfile(double surfaceTemperature, double lcl, double surfacePressure, double* parcel) {
  double t = surfaceTemperature;
  for (int k = 1; k <= kLevels; ++k) {
    double z = k * kDz, z0 = z - kDz;
    if (z <= lcl) {
      t -= kDryAdiabaticLapseRate * kDz;
    } else {
      double dry = std::max(0.0, lcl - z0);
      t -= kDryAdiabaticLapseRate * dry;
      t -= moistAdiabaticLapseRate(t, pressureAtHeight(surfacePressure, z0 + dry)) * (kDz - dry);
    }
    parcel[k - 1] = t;
  }
}

// CIN, CAPE, LFC and LNB of a parcel profile against environment temperatures at the same levels.
ParcelProperties integrate(const double* parcel, const double* env, double surfaceParcel, double surfaceEnv,
                           double lcl) {
  ParcelProperties out;
  double cin = 0.0, cape = 0.0;
  double previousB = kGravity * (surfaceParcel - surfaceEnv) / surfaceEnv;
  bool free = false;
  for (int k = 1; k <= kLevels; ++k) {
    double z = k * kDz, z0 = z - kDz;
    double b = kGravity * (parcel[k - 1] - env[k - 1]) / env[k - 1];
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

void environment(const Sounding& s, double* env) {
  for (int k = 1; k <= kLevels; ++k) env[k - 1] = s.temperatureAt(k * kDz);
}

}  // namespace

ParcelProperties ParcelTable::ascend(const Sounding& s, double surfaceTemperature, double depression) {
  double lcl = kLclMetresPerKelvin * std::max(0.0, depression);
  double parcel[kLevels], env[kLevels];
  parcelProfile(surfaceTemperature, lcl, s.surfacePressure_Pa, parcel);
  environment(s, env);
  return integrate(parcel, env, surfaceTemperature, s.temperatureAt(0.0), lcl);
}

void ParcelTable::build(const Sounding& s) {
  nAnomaly_ = int(std::lround((kMaxAnomaly - kMinAnomaly) / kAnomalyStep)) + 1;
  nDepression_ = int(std::lround(kMaxDepression / kDepressionStep)) + 1;
  maxA_ = float(nAnomaly_ - 1) - 1e-3f;
  maxD_ = float(nDepression_ - 1) - 1e-3f;
  size_t n = size_t(nAnomaly_) * nDepression_;
  for (auto* v : {&cin_, &cape_, &lfc_, &lnb_}) v->resize(n);
  bounds_.resize(n);
  minCin_.resize(n);
  maxCape_.resize(n);
  nodes_.resize(n);
  allFree_.resize(n);
  capeCorners_.resize(n);
  summaries_.resize(n);
  // The parcel profiles depend on the surface temperature and pressure only: a new layer depth or
  // inversion (the daytime growth of the mixed layer) reuses them and only re-integrates the buoyancy.
  if (profiles_.size() != n * kLevels || profileTemperature_ != s.surfaceTemperature_K ||
      profilePressure_ != s.surfacePressure_Pa) {
    profiles_.resize(n * kLevels);
    for (int d = 0; d < nDepression_; ++d)
      for (int a = 0; a < nAnomaly_; ++a)
        parcelProfile(s.surfaceTemperature_K + kMinAnomaly + a * kAnomalyStep,
                      kLclMetresPerKelvin * (d * kDepressionStep), s.surfacePressure_Pa,
                      &profiles_[(size_t(d) * nAnomaly_ + a) * kLevels]);
    profileTemperature_ = s.surfaceTemperature_K;
    profilePressure_ = s.surfacePressure_Pa;
  }
  double env[kLevels];
  environment(s, env);
  const double surfaceEnv = s.temperatureAt(0.0);
  for (int d = 0; d < nDepression_; ++d)
    for (int a = 0; a < nAnomaly_; ++a) {
      size_t i = size_t(d) * nAnomaly_ + a;
      ParcelProperties p =
          integrate(&profiles_[i * kLevels], env, s.surfaceTemperature_K + kMinAnomaly + a * kAnomalyStep, surfaceEnv,
                    kLclMetresPerKelvin * (d * kDepressionStep));
      cin_[i] = std::sqrt(2.0f * p.cin_J_kg);
      cape_[i] = p.cape_J_kg;
      lfc_[i] = p.freeConvectionLevel_m;
      lnb_[i] = p.neutralBuoyancyLevel_m;
    }
  // Per table cell: the least CIN and the most CAPE of its four corners, bounds of the bilinear values
  // inside it, so that a cell that cannot trigger is rejected with one load.
  for (int d = 0; d < nDepression_; ++d)
    for (int a = 0; a < nAnomaly_; ++a) {
      size_t i = size_t(d) * nAnomaly_ + a;
      size_t right = a + 1 < nAnomaly_ ? i + 1 : i, up = d + 1 < nDepression_ ? size_t(nAnomaly_) : 0;
      float minSpeed = std::min(std::min(cin_[i], cin_[right]), std::min(cin_[i + up], cin_[right + up]));
      bounds_[i].minCin = 0.5f * minSpeed * minSpeed;
      bounds_[i].maxCape = std::max(std::max(cape_[i], cape_[right]), std::max(cape_[i + up], cape_[right + up]));
      minCin_[i] = bounds_[i].minCin;
      maxCape_[i] = bounds_[i].maxCape;
      nodes_[i] = {cape_[i], cin_[i], lnb_[i], lfc_[i]};
      allFree_[i] = cape_[i] > 0 && cape_[right] > 0 && cape_[i + up] > 0 && cape_[right + up] > 0;
      capeCorners_[i] = {cape_[i], cape_[right], cape_[i + up], cape_[right + up]};
      summaries_[i] = {{cin_[i], cin_[right], cin_[i + up], cin_[right + up]},
                       maxCape_[i],
                       minCin_[i],
                       allFree_[i] ? 1.0f : 0.0f,
                       0.0f};
    }
}

}  // namespace firmament::weather
