#include "weather/advection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <cstring>

namespace firmament::weather {

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
#if defined(__SSE2__)
  // Two cells at a time in double lanes, the same operations as the scalar loop below; the wrap covers
  // departures within one domain width, and the few farther ones get the full modulo afterwards.
  if (nx % 2 == 0) {
    const __m128d scaleV = _mm_set1_pd(scale), limit = _mm_set1_pd(1e9), one = _mm_set1_pd(1.0);
    const __m128i nxV = _mm_set1_epi32(nx), nyV = _mm_set1_epi32(ny), zero = _mm_setzero_si128();
    // Departure in cell units and its floor (truncation stepped down where it rounded up).
    auto departure = [&](__m128d position, const float* wind, __m128i& cell, __m128& fraction) {
      __m128d x = _mm_sub_pd(position, _mm_mul_pd(_mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(
                                                    reinterpret_cast<const __m128i*>(wind)))), scaleV));
      x = _mm_max_pd(_mm_sub_pd(_mm_setzero_pd(), limit), _mm_min_pd(limit, x));  // std::clamp(x, −1e9, 1e9)
      __m128d floorX = _mm_cvtepi32_pd(_mm_cvttpd_epi32(x));
      floorX = _mm_sub_pd(floorX, _mm_and_pd(_mm_cmpgt_pd(floorX, x), one));
      fraction = _mm_cvtpd_ps(_mm_sub_pd(x, floorX));
      cell = _mm_cvttpd_epi32(floorX);
    };
    __m128i outside = zero;  // any lane still outside [0, size) after one wrap
    auto wrap = [&](__m128i cell, __m128i size) {
      cell = _mm_add_epi32(cell, _mm_and_si128(_mm_cmplt_epi32(cell, zero), size));
      cell = _mm_sub_epi32(cell, _mm_andnot_si128(_mm_cmplt_epi32(cell, size), size));
      outside = _mm_or_si128(outside, _mm_or_si128(_mm_cmplt_epi32(cell, zero), _mm_cmpgt_epi32(cell, _mm_sub_epi32(size, _mm_set1_epi32(1)))));
      return cell;
    };
    for (int j = 0; j < ny; ++j) {
      const __m128d y0 = _mm_set1_pd(double(j));
      for (int i = 0; i < nx; i += 2) {
        const size_t c = size_t(j) * nx + i;
        __m128i ix, iy;
        __m128 fx, fy;
        departure(_mm_set_pd(double(i + 1), double(i)), &windU[c], ix, fx);
        departure(y0, &windV[c], iy, fy);
        _mm_storel_pi(reinterpret_cast<__m64*>(&fx_[c]), fx);
        _mm_storel_pi(reinterpret_cast<__m64*>(&fy_[c]), fy);
        _mm_storel_epi64(reinterpret_cast<__m128i*>(&i0_[c]), wrap(ix, nxV));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(&j0_[c]), wrap(iy, nyV));
      }
    }
    if (_mm_movemask_epi8(outside) != 0)
      for (size_t c = 0; c < n; ++c) {
        if (uint32_t(i0_[c]) >= uint32_t(nx)) i0_[c] = ((i0_[c] % nx) + nx) % nx;
        if (uint32_t(j0_[c]) >= uint32_t(ny)) j0_[c] = ((j0_[c] % ny) + ny) % ny;
      }
    return;
  }
#endif
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      size_t c = size_t(j) * nx + i;
      // Departure point in cell units, in double so that long steps keep their sub-cell fraction. The
      // floor is a truncation corrected for negative values (std::floor is a library call without
      // SSE4.1); only departures beyond the domain need the modulo.
      double x = i - windU[c] * scale, y = j - windV[c] * scale;
      double limit = 1e9;
      x = std::clamp(x, -limit, limit);
      y = std::clamp(y, -limit, limit);
      long long ix = (long long)x, iy = (long long)y;
      ix -= double(ix) > x;
      iy -= double(iy) > y;
      fx_[c] = float(x - double(ix));
      fy_[c] = float(y - double(iy));
      if (ix < 0 || ix >= nx) ix = ((ix % nx) + nx) % nx;  // far departures only
      if (iy < 0 || iy >= ny) iy = ((iy % ny) + ny) % ny;
      i0_[c] = int32_t(ix);
      j0_[c] = int32_t(iy);
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
    __m128 a = _mm_loadu_ps(src[0] + c), b = _mm_loadu_ps(src[1] + c), d = _mm_loadu_ps(src[2] + c), e = _mm_loadu_ps(src[3] + c);
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

double SemiLagrangianAdvection::restoreTotal(Field& f, double before) {
  double after = sumField(f);
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
