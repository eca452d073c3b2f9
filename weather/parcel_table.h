#pragma once
// Convective parcel properties as a table over the boundary layer's temperature anomaly T′ and dew-point
// depression D. A parcel leaves the surface at T_ref + T′, rises dry-adiabatically to its lifting
// condensation level (Espy, 125 m/K · D), then moist-adiabatically (Γ_m, AMS Glossary), and is compared
// with the sounding; its buoyancy is b = g (T_p − T_e)/T_e (virtual-temperature and loading effects are
// neglected). From b(z):
//   CIN  = ∫₀^LFC max(0, −b) dz    (J/kg; the energy a thermal must bring to reach free convection)
//   CAPE = ∫_LFC^LNB b dz          (J/kg; LFC = first buoyant level above the LCL, LNB = where b < 0 again)
// CIN is tabulated as the thermal speed that pays it, v_c = √(2 CIN), which varies about linearly near
// the edge of free convection where CIN itself is quadratic, so bilinear interpolation does not
// overstate the inhibition of a parcel a fraction of a kelvin from free convection.
// The table is rebuilt only when the sounding changes, so the per-cell cost is one bilinear lookup. The
// parcel profiles are kept between rebuilds that keep the surface temperature and pressure (a growing
// mixed layer changes only the environment), so such a rebuild costs ~1 ms, not ~20.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "weather/sounding.h"

namespace firmament::weather {

struct ParcelProperties {
  float cin_J_kg = 0.0f;
  float cape_J_kg = 0.0f;
  float freeConvectionLevel_m = 0.0f;   // LFC; 0 when there is none
  float neutralBuoyancyLevel_m = 0.0f;  // LNB; 0 when there is no free convection
};

class ParcelTable {
 public:
  static constexpr float kMinAnomaly = -20.0f, kMaxAnomaly = 20.0f, kMaxDepression = 40.0f;
  static constexpr float kAnomalyStep = 0.5f, kDepressionStep = 1.0f;
  void build(const Sounding& sounding);
  // Bilinear lookup; inputs beyond the table are clamped to its edge.
  // Where an input pair falls in the table: the cell (lower corner) and the fractions within it.
  struct Position {
    size_t index;
    float ta, td;
  };
  Position locate(float temperatureAnomaly_K, float dewPointDepression_K) const {
    float fa = (temperatureAnomaly_K - kMinAnomaly) * (1.0f / kAnomalyStep);
    float fd = dewPointDepression_K * (1.0f / kDepressionStep);
    fa = fa < 0.0f ? 0.0f : (fa > maxA_ ? maxA_ : fa);
    fd = fd < 0.0f ? 0.0f : (fd > maxD_ ? maxD_ : fd);
    int a = int(fa), d = int(fd);
    return {size_t(d) * size_t(nAnomaly_) + size_t(a), fa - float(a), fd - float(d)};
  }
  // The same cell index in 32-bit arithmetic, as a value a vectorised loop keeps in registers (a member
  // function would reload the table's sizes after every float store).
  struct Indexer {
    float maxA, maxD;
    int32_t nAnomaly;
    // The cell index; ta, td the fractions within it (as in Position).
    int32_t operator()(float temperatureAnomaly_K, float dewPointDepression_K, float& ta, float& td) const {
      float fa = (temperatureAnomaly_K - kMinAnomaly) * (1.0f / kAnomalyStep);
      float fd = dewPointDepression_K * (1.0f / kDepressionStep);
      fa = fa < 0.0f ? 0.0f : (fa > maxA ? maxA : fa);
      fd = fd < 0.0f ? 0.0f : (fd > maxD ? maxD : fd);
      const int32_t a = int32_t(fa), d = int32_t(fd);
      ta = fa - float(a);
      td = fd - float(d);
      return d * nAnomaly + a;
    }
  };
  Indexer indexer() const { return {maxA_, maxD_, nAnomaly_}; }
  // Bounds of the interpolated CIN (from below) and CAPE (from above) anywhere in a table cell.
  struct CellBounds {
    float minCin, maxCape;
  };
  const CellBounds& bounds(const Position& at) const { return bounds_[at.index]; }
  // The same bounds as two flat arrays by cell index (what a vectorised loop can gather).
  const float* minCinData() const { return minCin_.data(); }
  const float* maxCapeData() const { return maxCape_.data(); }
  // The tabulated values of one node side by side, so that a bilinear lookup is four 16-byte loads and
  // one 4-wide interpolation; and per table cell whether all four corners have free convection (where
  // that interpolation is what lookup() returns).
  struct alignas(16) Node {
    float cape, cinSpeed, neutralBuoyancyLevel, freeConvectionLevel;
  };
  const Node* nodes() const { return nodes_.data(); }
  // Per table cell (by its lower corner's index): the four corners' CAPE and v_c in the order of the
  // bilinear interpolation (lower, next anomaly, next depression, both), so that four cells' corners are
  // four 16-byte loads and a transpose; and, in the same 32 bytes as v_c's corners, the cell's bounds
  // (CellBounds) and whether all four corners have free convection (1 or 0).
  struct alignas(16) Corners {
    float c00, c10, c01, c11;
  };
  struct alignas(32) Summary {
    Corners cinSpeed;
    float maxCape, minCin, allFree, unused;
  };
  const Corners* capeCorners() const { return capeCorners_.data(); }
  const Summary* summaries() const { return summaries_.data(); }
  const uint8_t* allFreeData() const { return allFree_.data(); }
  int32_t rowStride() const { return nAnomaly_; }
  ParcelProperties lookup(float temperatureAnomaly_K, float dewPointDepression_K) const {
    return lookup(locate(temperatureAnomaly_K, dewPointDepression_K));
  }
  ParcelProperties lookup(const Position& at) const {
    const float ta = at.ta, td = at.td;
    size_t i00 = at.index, i01 = i00 + size_t(nAnomaly_);
    auto mix = [&](const std::vector<float>& v) {
      float lo = v[i00] + ta * (v[i00 + 1] - v[i00]);
      float hi = v[i01] + ta * (v[i01 + 1] - v[i01]);
      return lo + td * (hi - lo);
    };
    ParcelProperties out;
    auto cinOf = [](float speed) { return 0.5f * speed * speed; };
    out.cape_J_kg = mix(cape_);
    if (!(out.cape_J_kg > 0.0f)) {
      out.cin_J_kg = cinOf(mix(cin_));
      return out;
    }
    bool allFree = cape_[i00] > 0 && cape_[i00 + 1] > 0 && cape_[i01] > 0 && cape_[i01 + 1] > 0;
    if (allFree) {
      out.cin_J_kg = cinOf(mix(cin_));
      out.freeConvectionLevel_m = mix(lfc_);
      out.neutralBuoyancyLevel_m = mix(lnb_);
      return out;
    }
    // Next to the edge of free convection: a corner without free convection has a CIN integrated
    // through the whole troposphere, meaningless for a parcel that is free a fraction of a kelvin away;
    // CIN and LFC are weighted over the free corners only, and the LNB is the highest corner's (an
    // unstable corner must not pull the top toward zero).
    const float w[4] = {(1 - ta) * (1 - td), ta * (1 - td), (1 - ta) * td, ta * td};
    const size_t idx[4] = {i00, i00 + 1, i01, i01 + 1};
    float weight = 0.0f, cin = 0.0f, lfc = 0.0f, lnb = 0.0f;
    for (int k = 0; k < 4; ++k) {
      lnb = std::max(lnb, lnb_[idx[k]]);
      if (cape_[idx[k]] > 0.0f) {
        weight += w[k];
        cin += w[k] * cin_[idx[k]];
        lfc += w[k] * lfc_[idx[k]];
      }
    }
    out.cin_J_kg = cinOf(weight > 0.0f ? cin / weight : mix(cin_));
    out.freeConvectionLevel_m = weight > 0.0f ? lfc / weight : mix(lfc_);
    out.neutralBuoyancyLevel_m = lnb;
    return out;
  }
  // The parcel ascent for one surface state (also used to build the table).
  static ParcelProperties ascend(const Sounding& sounding, double surfaceTemperature_K, double dewPointDepression_K);

 private:
  int nAnomaly_ = 0, nDepression_ = 0;
  float maxA_ = 0.0f, maxD_ = 0.0f;
  std::vector<float> cin_, cape_, lfc_, lnb_;  // [depression][anomaly]; cin_ holds v_c = √(2 CIN)
  std::vector<CellBounds> bounds_;
  std::vector<float> minCin_, maxCape_;
  std::vector<Node> nodes_;
  std::vector<Corners> capeCorners_;
  std::vector<Summary> summaries_;
  std::vector<uint8_t> allFree_;
  std::vector<double> profiles_;  // parcel temperature per node and level
  double profileTemperature_ = -1.0, profilePressure_ = -1.0;
};

}  // namespace firmament::weather
