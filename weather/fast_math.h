#pragma once
// Branch-free float exp and log for the per-cell physics (rates, decays, Kessler's power law). They are
// inline and use only arithmetic and bit moves, so loops that call them can vectorise; libm's expf and
// powf are calls the compiler cannot fold into a loop.
//
// expFast: exp(x) = 2ⁿ e^r with n = round(x / ln 2) and r = x − n ln 2 (ln 2 in two parts, Cody & Waite
// 1980), |r| ≤ ln 2 / 2; e^r by its Taylor polynomial to r⁶ (truncation r⁷/7! ≤ 1.2e-7). Relative error
// ≤ 3e-7 over [−87, 88] (tests/weather/test_thermodynamics.cpp); x is clamped there, so exp(−1e30) = 1.6e-38,
// not 0, which no caller can tell from zero.
// logFast: ln x = k ln 2 + 2 atanh(s), s = (m − 1)/(m + 1), m ∈ [√½, √2) the mantissa, k the exponent; the
// atanh series to s⁹ (|s| ≤ 0.172, truncation s¹¹/11 ≤ 4e-10). Absolute error ≤ 4e-7 over [1e-3, 1e3]
// (≤ 4e-6 over [1e-30, 1e30]: the float rounding of a result near ±69); powFast ≤ 2e-6 relative for
// |y ln x| ≤ 20; oneMinusExpFast ≤ 1e-6 relative.
#include <cstdint>
#include <cstring>

namespace firmament::weather {

inline float expFast(float x) {
  x = x < -87.0f ? -87.0f : x;
  x = x > 88.0f ? 88.0f : x;
  constexpr float kLog2e = 1.44269504f, kLn2Hi = 0.693359375f, kLn2Lo = -2.12194440e-4f;
  // Adding 1.5 · 2²³ rounds to an integer, which then sits in the low mantissa bits (no float → int
  // conversion, which would keep the loop from vectorising).
  constexpr float kRound = 12582912.0f;
  const float t = x * kLog2e + kRound;
  int32_t ti;
  std::memcpy(&ti, &t, 4);
  const float n = t - kRound;
  float r = (x - n * kLn2Hi) - n * kLn2Lo;
  float p = 1.0f + r * (1.0f + r * (0.5f + r * (1.0f / 6 + r * (1.0f / 24 + r * (1.0f / 120 + r * (1.0f / 720))))));
  int32_t bits = (ti - 0x4B400000 + 127) << 23;
  float scale;
  std::memcpy(&scale, &bits, 4);
  return p * scale;
}

// 1 − e^{−x} for x ≥ 0 without the cancellation of 1 − expFast(−x) at small x: its Taylor series to x⁷
// below ¼ (truncation ≤ 5e-8 relative). Relative error ≤ 1e-6.
inline float oneMinusExpFast(float x) {
  if (x >= 0.25f) return 1.0f - expFast(-x);
  return x * (1.0f -
              x * (0.5f - x * (1.0f / 6 - x * (1.0f / 24 - x * (1.0f / 120 - x * (1.0f / 720 - x * (1.0f / 5040)))))));
}

inline float logFast(float x) {
  uint32_t bits;
  std::memcpy(&bits, &x, 4);
  // Exponent relative to a mantissa in [√½, √2): subtracting the bits of √½ before the (arithmetic)
  // shift moves the split point there.
  int32_t k = int32_t(bits - 0x3f3504f3u) >> 23;
  uint32_t mBits = bits - (uint32_t(k) << 23);
  float m;
  std::memcpy(&m, &mBits, 4);
  float s = (m - 1.0f) / (m + 1.0f), s2 = s * s;
  float series = s * (2.0f + s2 * (2.0f / 3 + s2 * (2.0f / 5 + s2 * (2.0f / 7 + s2 * (2.0f / 9)))));
  return float(k) * 0.693359375f + (float(k) * -2.12194440e-4f + series);
}

// x^y for x > 0 (0 for x ≤ 0, the only case the callers need).
inline float powFast(float x, float y) { return x > 0.0f ? expFast(y * logFast(x)) : 0.0f; }

}  // namespace firmament::weather
