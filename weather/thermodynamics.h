#pragma once
// Moist thermodynamics of the boundary layer: saturation, dew point, lifting condensation level and the
// moist-adiabatic lapse rate. Temperatures in K, pressures in Pa, mixing ratios in kg/kg.
#include <cstdint>
#include <cstring>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace firmament::weather {

// Saturation vapour pressure over liquid water, Tetens (1930) in the form of Murray (1967):
//   e_s(T) = 610.78 Pa · exp(17.27 (T − 273.15) / (T − 35.85)).
// Within 0.1 % of Goff–Gratch from 0 to 35 °C; used below 0 °C too (supercooled water).
double saturationVapourPressure(double temperature_K);

// Mixing ratio r = ε e / (p − e), with e limited to p/2 so that near-boiling input stays finite.
double mixingRatioFromVapourPressure(double vapourPressure_Pa, double pressure_Pa);
double saturationMixingRatio(double temperature_K, double pressure_Pa);
double vapourPressureFromMixingRatio(double mixingRatio, double pressure_Pa);

// Dew point: Tetens inverted, Td = (4717.3 − 35.85 x) / (17.27 − x), x = ln(e / 610.78 Pa).
// Vapour pressures below 1e-3 Pa (bone-dry air) are clamped there (Td ≈ 170 K).
double dewPoint(double vapourPressure_Pa);

// Lifting condensation level above the surface from Espy's rule: z = 125 m/K · (T − Td).
double liftingCondensationLevel(double temperature_K, double dewPoint_K);

// Saturated (pseudo-)adiabatic lapse rate (AMS Glossary of Meteorology, "moist-adiabatic lapse rate"):
//   Γ_m = g (1 + L r_s / (R_d T)) / (c_p + L² r_s ε / (R_d T²))   [K/m].
double moistAdiabaticLapseRate(double temperature_K, double pressure_Pa);

// Hydrostatic pressure at height z above a surface at p0, isothermal scale height (US Std. Atm.).
double pressureAtHeight(double surfacePressure_Pa, double height_m);

// Air density from the ideal gas law, ρ = p / (R_d T).
double airDensity(double pressure_Pa, double temperature_K);

}  // namespace firmament::weather

namespace firmament::weather {

// Table-driven float versions of the hot per-cell functions (linear interpolation; within 1e-5 relative
// of the formulas above over 150–373 K, and within 0.01 K for dew points above 50 Pa; below that and
// above 16 kPa they fall back to the formulas).
struct SaturationTables {
  static constexpr float kMinT = 150.0f, kMaxT = 373.15f, kStepT = 0.05f;
  static constexpr float kMaxE = 16000.0f, kStepE = 2.0f, kMinTableE = 50.0f;
  std::vector<float> es, td;
  SaturationTables();
};
extern const SaturationTables gSaturationTables;

inline float saturationVapourPressureFast(float t) {
  const SaturationTables& s = gSaturationTables;
  t = t < SaturationTables::kMinT ? SaturationTables::kMinT
                                  : (t > SaturationTables::kMaxT ? SaturationTables::kMaxT : t);
  float x = (t - SaturationTables::kMinT) * (1.0f / SaturationTables::kStepT);
  int i = int(x);
  i = i > int(s.es.size()) - 2 ? int(s.es.size()) - 2 : i;
  float f = x - float(i);
  return s.es[i] + f * (s.es[i + 1] - s.es[i]);
}

inline float saturationMixingRatioFast(float t, float p) {
  float e = saturationVapourPressureFast(t);
  e = e < 0.5f * p ? e : 0.5f * p;
  return 0.62199f * e / (p - e);  // ε = R_d/R_v
}

#if defined(__SSE2__)
// saturationMixingRatioFast for four lanes (the table's loads are scalar: SSE2 has no gather).
inline __m128 saturationMixingRatioFast4(__m128 t, __m128 p) {
  const SaturationTables& s = gSaturationTables;
  t = _mm_max_ps(_mm_set1_ps(SaturationTables::kMinT), _mm_min_ps(_mm_set1_ps(SaturationTables::kMaxT), t));
  const __m128 x =
      _mm_mul_ps(_mm_sub_ps(t, _mm_set1_ps(SaturationTables::kMinT)), _mm_set1_ps(1.0f / SaturationTables::kStepT));
  // i = min(⌊x⌋, size − 2), in float (exact integers).
  const __m128 fi = _mm_min_ps(_mm_cvtepi32_ps(_mm_cvttps_epi32(x)), _mm_set1_ps(float(int(s.es.size()) - 2)));
  const __m128 f = _mm_sub_ps(x, fi);
  alignas(16) int32_t index[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(index), _mm_cvttps_epi32(fi));
  const float* es = s.es.data();
  const __m128 lo = _mm_setr_ps(es[index[0]], es[index[1]], es[index[2]], es[index[3]]);
  const __m128 hi = _mm_setr_ps(es[index[0] + 1], es[index[1] + 1], es[index[2] + 1], es[index[3] + 1]);
  __m128 e = _mm_add_ps(lo, _mm_mul_ps(f, _mm_sub_ps(hi, lo)));
  e = _mm_min_ps(e, _mm_mul_ps(_mm_set1_ps(0.5f), p));  // e < 0.5 p ? e : 0.5 p
  return _mm_div_ps(_mm_mul_ps(_mm_set1_ps(0.62199f), e), _mm_sub_ps(p, e));
}
#endif

inline float dewPointFast(float e) {
  const SaturationTables& s = gSaturationTables;
  if (!(e >= SaturationTables::kMinTableE && e < SaturationTables::kMaxE)) return float(dewPoint(e));
  float x = e * (1.0f / SaturationTables::kStepE);
  int i = int(x);
  float f = x - float(i);
  return s.td[i] + f * (s.td[i + 1] - s.td[i]);
}

// Cube root by bit estimate and two Newton steps (relative error < 1e-6 for x > 0; 0 for x ≤ 0).
// Branch-free (x ≤ 0 computes the root of 1 and discards it), so loops that call it vectorise.
inline float cbrtFast(float x) {
  const bool positive = x > 0.0f;
  const float a = positive ? x : 1.0f;
  uint32_t bits;
  std::memcpy(&bits, &a, 4);
  bits = bits / 3u + 709921077u;
  float y;
  std::memcpy(&y, &bits, 4);
  y = y - (y * y * y - a) / (3.0f * y * y);
  y = y - (y * y * y - a) / (3.0f * y * y);
  return positive ? y : 0.0f;
}

}  // namespace firmament::weather
