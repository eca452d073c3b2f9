#include "weather/advection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <cstring>

namespace firmament::weather {

namespace {

// A departure farther than this many cells (a long step) is computed in double: in float its fraction
// would lose bits (an ulp of 64 is 8e-6 of a cell). With 0 every departure takes the double path, which
// is main's arithmetic before the float departures (weather2): the model is then bit-identical to main
// (checked over 14 h of every preset; docs/weather.md), at 0.14 ms more per 256² step.
constexpr float kNearDeparture = 64.0f;

// Departure x − d in double from the cell index (the far case): floor by truncation stepped down where
// it rounded up (std::floor is a library call without SSE4.1), any distance wrapped by the modulo.
void farDeparture(int i, float wind, double scale, int n, int32_t& cell, float& fraction) {
  double x = i - wind * scale;
  x = std::clamp(x, -1e9, 1e9);
  long long k = (long long)x;
  k -= double(k) > x;
  fraction = float(x - double(k));
  if (k < 0 || k >= n) k = ((k % n) + n) % n;
  cell = int32_t(k);
}

// Near case: the displacement d = u Δt/Δx in float; −d = k + fraction with k = ⌊−d⌋ (exact: the
// difference of −d and an integer within one of it); the cell i + k wrapped once (|k| < n).
inline void nearDeparture(int i, float x, int n, int32_t& cell, float& fraction) {
  float k = float(int32_t(x));
  k -= k > x ? 1.0f : 0.0f;
  fraction = x - k;
  int32_t c = i + int32_t(k);
  c += c < 0 ? n : 0;
  c -= c >= n ? n : 0;
  cell = c;
}

}  // namespace

void SemiLagrangianAdvection::departureRow(int j, const float* windU, const float* windV, int nx, int ny, double scale,
                                           int32_t* cellI, int32_t* cellJ, float* fx, float* fy) {
  const float s = float(scale);
  const float nearX = std::min(kNearDeparture, float(nx - 1)), nearY = std::min(kNearDeparture, float(ny - 1));
  int i = 0;
#if defined(__SSE2__)
  // Four cells at a time, the scalar near case's operations per lane; lanes with a far departure are
  // redone by the scalar code.
  {
    const __m128 sV = _mm_set1_ps(s), sign = _mm_set1_ps(-0.0f), one = _mm_set1_ps(1.0f);
    const __m128 nearXV = _mm_set1_ps(nearX), nearYV = _mm_set1_ps(nearY);
    const __m128i nxV = _mm_set1_epi32(nx), nyV = _mm_set1_epi32(ny), zero = _mm_setzero_si128();
    const __m128i lanes = _mm_setr_epi32(0, 1, 2, 3), jV = _mm_set1_epi32(j);
    auto split = [&](__m128 x, __m128i base, __m128i size, float* fraction, int32_t* cell) {
      __m128 k = _mm_cvtepi32_ps(_mm_cvttps_epi32(x));
      k = _mm_sub_ps(k, _mm_and_ps(_mm_cmpgt_ps(k, x), one));
      _mm_storeu_ps(fraction, _mm_sub_ps(x, k));
      __m128i c = _mm_add_epi32(base, _mm_cvttps_epi32(k));
      c = _mm_add_epi32(c, _mm_and_si128(_mm_cmplt_epi32(c, zero), size));
      c = _mm_sub_epi32(c, _mm_andnot_si128(_mm_cmplt_epi32(c, size), size));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(cell), c);
    };
    for (; i + 4 <= nx; i += 4) {
      const __m128 x = _mm_xor_ps(_mm_mul_ps(_mm_loadu_ps(windU + i), sV), sign);  // −(u s)
      const __m128 y = _mm_xor_ps(_mm_mul_ps(_mm_loadu_ps(windV + i), sV), sign);
      split(x, _mm_add_epi32(_mm_set1_epi32(i), lanes), nxV, fx + i, cellI + i);
      split(y, jV, nyV, fy + i, cellJ + i);
      const __m128 near =
          _mm_and_ps(_mm_cmplt_ps(_mm_andnot_ps(sign, x), nearXV), _mm_cmplt_ps(_mm_andnot_ps(sign, y), nearYV));
      if (_mm_movemask_ps(near) != 0xF)
        for (int l = i; l < i + 4; ++l) {
          farDeparture(l, windU[l], scale, nx, cellI[l], fx[l]);
          farDeparture(j, windV[l], scale, ny, cellJ[l], fy[l]);
        }
    }
  }
#endif
  for (; i < nx; ++i) {
    const float x = -(windU[i] * s), y = -(windV[i] * s);
    if (std::fabs(x) < nearX && std::fabs(y) < nearY) {
      nearDeparture(i, x, nx, cellI[i], fx[i]);
      nearDeparture(j, y, ny, cellJ[i], fy[i]);
    } else {
      farDeparture(i, windU[i], scale, nx, cellI[i], fx[i]);
      farDeparture(j, windV[i], scale, ny, cellJ[i], fy[i]);
    }
  }
}

void SemiLagrangianAdvection::prepare(const Field& windU, const Field& windV, int nx, int ny, double cellSize_m,
                                      double dt_s) {
  nx_ = nx;
  ny_ = ny;
  size_t n = size_t(nx) * ny;
  i0_.resize(n);
  j0_.resize(n);
  fx_.resize(n);
  fy_.resize(n);
  const double scale = dt_s / cellSize_m;
  for (int j = 0; j < ny; ++j) {
    const size_t row = size_t(j) * size_t(nx);
    departureRow(j, windU.data() + row, windV.data() + row, nx, ny, scale, i0_.data() + row, j0_.data() + row,
                 fx_.data() + row, fy_.data() + row);
  }
}

void SemiLagrangianAdvection::advect(Field& f) { advectFields({&f}); }

#if defined(__SSE2__)
namespace {

// Interleaves four fields into 4 floats per cell (stride floats apart, 16-byte aligned) and back: 4×4
// transposes, four cells at a time.
void interleave4(const float* const* src, size_t n, float* out, size_t stride) {
  size_t c = 0;
  for (; c + 4 <= n; c += 4) {
    __m128 a = _mm_loadu_ps(src[0] + c), b = _mm_loadu_ps(src[1] + c), d = _mm_loadu_ps(src[2] + c),
           e = _mm_loadu_ps(src[3] + c);
    _MM_TRANSPOSE4_PS(a, b, d, e);
    _mm_store_ps(out + (c + 0) * stride, a);
    _mm_store_ps(out + (c + 1) * stride, b);
    _mm_store_ps(out + (c + 2) * stride, d);
    _mm_store_ps(out + (c + 3) * stride, e);
  }
  for (; c < n; ++c)
    for (int k = 0; k < 4; ++k) out[c * stride + k] = src[k][c];
}

void deinterleave4(const float* in, size_t stride, size_t n, float* const* dst) {
  size_t c = 0;
  for (; c + 4 <= n; c += 4) {
    __m128 a = _mm_load_ps(in + (c + 0) * stride), b = _mm_load_ps(in + (c + 1) * stride);
    __m128 d = _mm_load_ps(in + (c + 2) * stride), e = _mm_load_ps(in + (c + 3) * stride);
    _MM_TRANSPOSE4_PS(a, b, d, e);
    _mm_storeu_ps(dst[0] + c, a);
    _mm_storeu_ps(dst[1] + c, b);
    _mm_storeu_ps(dst[2] + c, d);
    _mm_storeu_ps(dst[3] + c, e);
  }
  for (; c < n; ++c)
    for (int k = 0; k < 4; ++k) dst[k][c] = in[c * stride + k];
}

// The bilinear sweep over interleaved fields, V vectors of 4 per cell: a departure point's corners are
// 4·V aligned loads and the interpolation runs four fields at a time, the same arithmetic per lane as
// one field alone (w₀₀ f₀₀ + w₁₀ f₁₀ + w₀₁ f₀₁ + w₁₁ f₁₁, left to right).
template <int V>
void interpolateInterleaved(int nx, int ny, const int32_t* i0, const int32_t* j0, const float* fx, const float* fy,
                            const float* in, float* out) {
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const size_t c = size_t(j) * nx + i;
      const int x0 = i0[c], y0 = j0[c];
      const int x1 = x0 + 1 == nx ? 0 : x0 + 1, y1 = y0 + 1 == ny ? 0 : y0 + 1;
      const size_t r0 = size_t(y0) * nx, r1 = size_t(y1) * nx;
      const float tx = fx[c], ty = fy[c];
      const __m128 w00 = _mm_set1_ps((1.0f - tx) * (1.0f - ty)), w10 = _mm_set1_ps(tx * (1.0f - ty));
      const __m128 w01 = _mm_set1_ps((1.0f - tx) * ty), w11 = _mm_set1_ps(tx * ty);
      const float *p00 = in + (r0 + x0) * 4 * V, *p10 = in + (r0 + x1) * 4 * V;
      const float *p01 = in + (r1 + x0) * 4 * V, *p11 = in + (r1 + x1) * 4 * V;
      for (int v = 0; v < V; ++v) {
        __m128 sum = _mm_mul_ps(w00, _mm_load_ps(p00 + 4 * v));
        sum = _mm_add_ps(sum, _mm_mul_ps(w10, _mm_load_ps(p10 + 4 * v)));
        sum = _mm_add_ps(sum, _mm_mul_ps(w01, _mm_load_ps(p01 + 4 * v)));
        sum = _mm_add_ps(sum, _mm_mul_ps(w11, _mm_load_ps(p11 + 4 * v)));
        _mm_store_ps(out + c * 4 * V + 4 * v, sum);
      }
    }
}

}  // namespace
#endif

void SemiLagrangianAdvection::advectFields(std::initializer_list<Field*> fields) {
  // One pass over the cells for all fields: the departure indices and weights are read once.
  constexpr size_t kMax = 8;
  Field* in[kMax];
  size_t count = 0;
  for (Field* f : fields)
    if (count < kMax) in[count++] = f;
  const int nx = nx_, ny = ny_;
#if defined(__SSE2__)
  // Three or more fields: interleaved into 4 or 8 floats per cell, interpolated four fields at a time,
  // and split again (the transposes cost less than the scalar loads they save) — while the interleaved
  // copies (twice the fields' size) stay in cache: on 1024² they would double the memory traffic, and
  // the sweep below is faster there.
  constexpr size_t kInterleavedBytes = size_t(8) << 20;
  const size_t cellsHere = size_t(nx) * ny;
  const int vectorsHere = count > 4 ? 2 : 1;
  if (count >= 3 && 2 * cellsHere * size_t(4 * vectorsHere) * sizeof(float) <= kInterleavedBytes) {
    const size_t n = cellsHere;
    const int vectors = vectorsHere;
    const size_t stride = size_t(4 * vectors);
    zeros_.assign(n, 0.0f);  // the lanes no field fills
    packed_.resize(2 * n * stride + 4);
    float* packedIn = packed_.data();
    while (reinterpret_cast<uintptr_t>(packedIn) % 16 != 0) ++packedIn;
    float* result = packedIn + n * stride;
    const float* sources[8];
    float* targets[8];
    for (size_t k = 0; k < 8; ++k) {
      sources[k] = k < count ? in[k]->data() : zeros_.data();
      targets[k] = k < count ? in[k]->data() : zeros_.data();
    }
    for (int v = 0; v < vectors; ++v) interleave4(sources + 4 * v, n, packedIn + 4 * v, stride);
    if (vectors == 2)
      interpolateInterleaved<2>(nx, ny, i0_.data(), j0_.data(), fx_.data(), fy_.data(), packedIn, result);
    else
      interpolateInterleaved<1>(nx, ny, i0_.data(), j0_.data(), fx_.data(), fy_.data(), packedIn, result);
    for (int v = 0; v < vectors; ++v) deinterleave4(result + 4 * v, stride, n, targets + 4 * v);
    return;
  }
#endif
  scratchMany_.resize(count);
  float* out[kMax];
  const float* src[kMax];
  for (size_t k = 0; k < count; ++k) {
    scratchMany_[k].resize(in[k]->size());
    out[k] = scratchMany_[k].data();
    src[k] = in[k]->data();
  }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      size_t c = size_t(j) * nx + i;
      int x0 = i0_[c], y0 = j0_[c];
      int x1 = x0 + 1 == nx ? 0 : x0 + 1, y1 = y0 + 1 == ny ? 0 : y0 + 1;
      size_t r0 = size_t(y0) * nx, r1 = size_t(y1) * nx;
      float tx = fx_[c], ty = fy_[c];
      float w00 = (1.0f - tx) * (1.0f - ty), w10 = tx * (1.0f - ty), w01 = (1.0f - tx) * ty, w11 = tx * ty;
      for (size_t k = 0; k < count; ++k) {
        const float* f = src[k];
        out[k][c] = w00 * f[r0 + x0] + w10 * f[r0 + x1] + w01 * f[r1 + x0] + w11 * f[r1 + x1];
      }
    }
  for (size_t k = 0; k < count; ++k) in[k]->swap(scratchMany_[k]);
}

void SemiLagrangianAdvection::advectConservingFields(std::initializer_list<Field*> fields) {
  double before[8] = {};
  size_t k = 0;
  for (Field* f : fields) {
    before[k] = sumField(*f);
    if (++k == 8) break;
  }
  advectFields(fields);
  k = 0;
  for (Field* f : fields) {
    restoreTotal(*f, before[k]);
    if (++k == 8) break;
  }
}

double SemiLagrangianAdvection::restoreTotal(Field& f, double before) { return restoreTotal(f, before, sumField(f)); }

double SemiLagrangianAdvection::restoreTotal(Field& f, double before, double after) {
  if (after <= 0.0 || before <= 0.0) return 0.0;
  // Scale in double and carry each cell's rounding into the next: a correction far below a float's
  // resolution (1e-9 relative) would otherwise round away in every cell and never be applied, and the
  // small, biased round-off of interpolation would accumulate over a day.
  double ratio = before / after;
  if (ratio == 1.0) return 0.0;
  // Sixteen interleaved carry chains: each is a chain of dependent add → round → subtract (≈ 14 cycles
  // per cell), so the loop runs at the chains' latency unless there are enough of them; sixteen keep it
  // at the arithmetic's throughput (vectorised two doubles at a time). Their leftovers, a few ulps, go
  // into the last cell.
  using Float2 = float __attribute__((vector_size(8)));
  using Double2 = double __attribute__((vector_size(16)));
  constexpr size_t kPairs = 8;
  Double2 carry[kPairs] = {};
  const size_t n = f.size();
  float* values = f.data();
  size_t i = 0;
  for (; i + 2 * kPairs <= n; i += 2 * kPairs)
    for (size_t k = 0; k < kPairs; ++k) {
      Float2 value;
      std::memcpy(&value, values + i + 2 * k, sizeof value);
      const Double2 target = __builtin_convertvector(value, Double2) * ratio + carry[k];
      Float2 stored = __builtin_convertvector(target, Float2);
      stored = stored < 0.0f ? 0.0f : stored;  // std::max(stored, 0.0f) per lane
      carry[k] = target - __builtin_convertvector(stored, Double2);
      std::memcpy(values + i + 2 * k, &stored, sizeof stored);
    }
  double rest = 0.0;
  for (const Double2& c : carry) rest += c[0] + c[1];
  for (; i < n; ++i) {
    double target = double(f[i]) * ratio + rest;
    float stored = std::max(float(target), 0.0f);
    rest = target - double(stored);
    f[i] = stored;
  }
  if (n > 0) f[n - 1] = std::max(float(double(f[n - 1]) + rest), 0.0f);
  return ratio - 1.0;
}

double SemiLagrangianAdvection::advectConserving(Field& f) {
  double before = sumField(f);
  advect(f);
  return restoreTotal(f, before);
}

}  // namespace firmament::weather
