#pragma once
// Four-lane SSE2 versions of the fast functions (fast_math.h, thermodynamics.h) and of std::min/max/clamp,
// each the same operations in the same order as the scalar one, so a lane gives the scalar result bit
// for bit. For the per-cell loops GCC's own vectorisation of clamps and selects (x86-64 without SSE4.1
// has no blend) turns each select into and/andnot/or chains and spills; with minps/maxps and explicit
// masks the convection's first pass is about half the instructions.
#if defined(__SSE2__)
#include <emmintrin.h>

#include <cstdint>

namespace firmament::weather::sse {

using F4 = __m128;
using I4 = __m128i;

inline F4 set1(float x) { return _mm_set1_ps(x); }
// std::max(a, b) = a < b ? b : a, and maxps(x, y) = x > y ? x : y: so maxps(b, a), NaN cases included.
inline F4 maxStd(F4 a, F4 b) { return _mm_max_ps(b, a); }
// std::min(a, b) = b < a ? b : a = minps(b, a).
inline F4 minStd(F4 a, F4 b) { return _mm_min_ps(b, a); }
// std::clamp(v, lo, hi) = v < lo ? lo : (hi < v ? hi : v).
inline F4 clampStd(F4 v, F4 lo, F4 hi) { return _mm_max_ps(lo, _mm_min_ps(hi, v)); }
// mask ? a : b (mask lanes all ones or all zeros).
inline F4 select(F4 mask, F4 a, F4 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); }

// logFast, lane by lane.
inline F4 logFast(F4 x) {
  const I4 bits = _mm_castps_si128(x);
  const I4 k = _mm_srai_epi32(_mm_sub_epi32(bits, _mm_set1_epi32(0x3f3504f3)), 23);
  const F4 m = _mm_castsi128_ps(_mm_sub_epi32(bits, _mm_slli_epi32(k, 23)));
  const F4 one = set1(1.0f);
  const F4 s = _mm_div_ps(_mm_sub_ps(m, one), _mm_add_ps(m, one)), s2 = _mm_mul_ps(s, s);
  F4 p = _mm_add_ps(set1(2.0f / 7), _mm_mul_ps(s2, set1(2.0f / 9)));
  p = _mm_add_ps(set1(2.0f / 5), _mm_mul_ps(s2, p));
  p = _mm_add_ps(set1(2.0f / 3), _mm_mul_ps(s2, p));
  p = _mm_add_ps(set1(2.0f), _mm_mul_ps(s2, p));
  const F4 series = _mm_mul_ps(s, p);
  const F4 kf = _mm_cvtepi32_ps(k);
  return _mm_add_ps(_mm_mul_ps(kf, set1(0.693359375f)), _mm_add_ps(_mm_mul_ps(kf, set1(-2.12194440e-4f)), series));
}

// Unsigned 32-bit division by 3 (x < 2³¹ here: positive floats' bits): ⌊x · 0xAAAAAAAB / 2³³⌋.
inline I4 divideBy3(I4 x) {
  const I4 magic = _mm_set1_epi32(int32_t(0xAAAAAAABu));
  const I4 even = _mm_srli_epi64(_mm_mul_epu32(x, magic), 33);                     // lanes 0, 2
  const I4 odd = _mm_srli_epi64(_mm_mul_epu32(_mm_srli_epi64(x, 32), magic), 33);  // lanes 1, 3
  return _mm_or_si128(even, _mm_slli_epi64(odd, 32));
}

// cbrtFast, lane by lane (x ≤ 0 → 0).
inline F4 cbrtFast(F4 x) {
  const F4 positive = _mm_cmpgt_ps(x, _mm_setzero_ps());
  const F4 a = select(positive, x, set1(1.0f));
  const I4 bits = _mm_add_epi32(divideBy3(_mm_castps_si128(a)), _mm_set1_epi32(709921077));
  F4 y = _mm_castsi128_ps(bits);
  const F4 three = set1(3.0f);
  for (int step = 0; step < 2; ++step) {
    const F4 cube = _mm_mul_ps(_mm_mul_ps(y, y), y);
    y = _mm_sub_ps(y, _mm_div_ps(_mm_sub_ps(cube, a), _mm_mul_ps(_mm_mul_ps(three, y), y)));
  }
  return _mm_and_ps(positive, y);
}

inline F4 negate(F4 x) { return _mm_xor_ps(x, set1(-0.0f)); }

// expFast, lane by lane.
inline F4 expFast(F4 x) {
  x = _mm_max_ps(set1(-87.0f), x);
  x = _mm_min_ps(set1(88.0f), x);
  const F4 kRound = set1(12582912.0f);
  const F4 t = _mm_add_ps(_mm_mul_ps(x, set1(1.44269504f)), kRound);
  const F4 n = _mm_sub_ps(t, kRound);
  const F4 r = _mm_sub_ps(_mm_sub_ps(x, _mm_mul_ps(n, set1(0.693359375f))), _mm_mul_ps(n, set1(-2.12194440e-4f)));
  F4 p = _mm_add_ps(set1(1.0f / 120), _mm_mul_ps(r, set1(1.0f / 720)));
  p = _mm_add_ps(set1(1.0f / 24), _mm_mul_ps(r, p));
  p = _mm_add_ps(set1(1.0f / 6), _mm_mul_ps(r, p));
  p = _mm_add_ps(set1(0.5f), _mm_mul_ps(r, p));
  p = _mm_add_ps(set1(1.0f), _mm_mul_ps(r, p));
  p = _mm_add_ps(set1(1.0f), _mm_mul_ps(r, p));
  const I4 bits = _mm_slli_epi32(
      _mm_add_epi32(_mm_sub_epi32(_mm_castps_si128(t), _mm_set1_epi32(0x4B400000)), _mm_set1_epi32(127)), 23);
  return _mm_mul_ps(p, _mm_castsi128_ps(bits));
}

// oneMinusExpFast, lane by lane (both forms, selected).
inline F4 oneMinusExpFast(F4 x) {
  F4 p = _mm_sub_ps(set1(1.0f / 720), _mm_mul_ps(x, set1(1.0f / 5040)));
  p = _mm_sub_ps(set1(1.0f / 120), _mm_mul_ps(x, p));
  p = _mm_sub_ps(set1(1.0f / 24), _mm_mul_ps(x, p));
  p = _mm_sub_ps(set1(1.0f / 6), _mm_mul_ps(x, p));
  p = _mm_sub_ps(set1(0.5f), _mm_mul_ps(x, p));
  p = _mm_sub_ps(set1(1.0f), _mm_mul_ps(x, p));
  const F4 series = _mm_mul_ps(x, p);
  const F4 direct = _mm_sub_ps(set1(1.0f), expFast(negate(x)));
  return select(_mm_cmpge_ps(x, set1(0.25f)), direct, series);
}

// powFast, lane by lane (0 for x ≤ 0).
inline F4 powFast(F4 x, float y) {
  return _mm_and_ps(_mm_cmpgt_ps(x, _mm_setzero_ps()), expFast(_mm_mul_ps(set1(y), logFast(x))));
}

// transferWater (weather_state.h), lane by lane: both candidate moves computed, the exact one selected.
inline void transferWater(F4& from, F4& to, F4 amount) {
  const F4 f = from, t = to;
  const F4 move = _mm_cmpgt_ps(amount, _mm_setzero_ps());
  const F4 a = _mm_min_ps(amount, f);  // amount < f ? amount : f
  const F4 toA = _mm_add_ps(t, a), gained = _mm_sub_ps(toA, t), fromA = _mm_sub_ps(f, gained);
  const F4 exactA = _mm_and_ps(_mm_cmple_ps(gained, f), _mm_cmpeq_ps(_mm_sub_ps(f, fromA), gained));
  const F4 fromB = _mm_sub_ps(f, a), lost = _mm_sub_ps(f, fromB), toB = _mm_add_ps(t, lost);
  const F4 exactB = _mm_cmpeq_ps(_mm_sub_ps(toB, t), lost);
  from = select(move, select(exactA, fromA, select(exactB, fromB, f)), f);
  to = select(move, select(exactA, toA, select(exactB, toB, t)), t);
}

}  // namespace firmament::weather::sse
#endif
