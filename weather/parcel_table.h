#pragma once
// Convective parcel properties as a table over the boundary layer's temperature anomaly T′ and dew-point
// depression D. A parcel leaves the surface at T_ref + T′, rises dry-adiabatically to its lifting
// condensation level (Espy, 125 m/K · D), then moist-adiabatically (Γ_m, AMS Glossary), and is compared
// with the sounding; its buoyancy is b = g (T_p − T_e)/T_e (virtual-temperature and loading effects are
// neglected). From b(z):
//   CIN  = ∫₀^LFC max(0, −b) dz    (J/kg; the energy a thermal must bring to reach free convection)
//   CAPE = ∫_LFC^LNB b dz          (J/kg; LFC = first buoyant level above the LCL, LNB = where b < 0 again)
// The table is rebuilt only when the sounding changes, so the per-cell cost is one bilinear lookup.
#include <algorithm>
#include <vector>

#include "weather/sounding.h"

namespace firmament::weather {

struct ParcelProperties {
  float cin_J_kg = 0.0f;
  float cape_J_kg = 0.0f;
  float freeConvectionLevel_m = 0.0f;  // LFC; 0 when there is none
  float neutralBuoyancyLevel_m = 0.0f; // LNB; 0 when there is no free convection
};

class ParcelTable {
 public:
  static constexpr float kMinAnomaly = -20.0f, kMaxAnomaly = 20.0f, kMaxDepression = 40.0f;
  static constexpr float kStep = 1.0f;
  void build(const Sounding& sounding);
  // Bilinear lookup; inputs beyond the table are clamped to its edge.
  ParcelProperties lookup(float temperatureAnomaly_K, float dewPointDepression_K) const {
    float fa = (temperatureAnomaly_K - kMinAnomaly) * (1.0f / kStep);
    float fd = dewPointDepression_K * (1.0f / kStep);
    fa = fa < 0.0f ? 0.0f : (fa > maxA_ ? maxA_ : fa);
    fd = fd < 0.0f ? 0.0f : (fd > maxD_ ? maxD_ : fd);
    int a = int(fa), d = int(fd);
    float ta = fa - float(a), td = fd - float(d);
    size_t i00 = size_t(d) * size_t(nAnomaly_) + size_t(a), i01 = i00 + size_t(nAnomaly_);
    auto mix = [&](const std::vector<float>& v) {
      float lo = v[i00] + ta * (v[i00 + 1] - v[i00]);
      float hi = v[i01] + ta * (v[i01 + 1] - v[i01]);
      return lo + td * (hi - lo);
    };
    ParcelProperties out;
    out.cin_J_kg = mix(cin_);
    out.cape_J_kg = mix(cape_);
    if (out.cape_J_kg > 0.0f) {
      out.freeConvectionLevel_m = mix(lfc_);
      // The LNB is interpolated where all four corners convect, else the highest corner's (an
      // unstable corner must not pull the top toward zero).
      bool allFree = cape_[i00] > 0 && cape_[i00 + 1] > 0 && cape_[i01] > 0 && cape_[i01 + 1] > 0;
      out.neutralBuoyancyLevel_m =
          allFree ? mix(lnb_) : std::max(std::max(lnb_[i00], lnb_[i00 + 1]), std::max(lnb_[i01], lnb_[i01 + 1]));
    }
    return out;
  }
  // The parcel ascent for one surface state (also used to build the table).
  static ParcelProperties ascend(const Sounding& sounding, double surfaceTemperature_K, double dewPointDepression_K);

 private:
  int nAnomaly_ = 0, nDepression_ = 0;
  float maxA_ = 0.0f, maxD_ = 0.0f;
  std::vector<float> cin_, cape_, lfc_, lnb_;  // [depression][anomaly]
};

}  // namespace firmament::weather
