#include "weather/transport.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "weather/domain_sum.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace firmament::weather {
namespace {

// Σ of the interleaved copies (4 or 8 floats per cell, both buffers) that still fit in cache on one core.
constexpr size_t kFusedBytes = size_t(8) << 20;

float* aligned16(std::vector<float>& buffer, size_t floats) {
  buffer.resize(floats + 4);
  float* p = buffer.data();
  while (reinterpret_cast<uintptr_t>(p) % 16 != 0) ++p;
  return p;
}

#if defined(__SSE2__)
template <int L>
inline __m128 lane(__m128 v) {
  return _mm_shuffle_ps(v, v, _MM_SHUFFLE(L, L, L, L));
}

// One cell's bilinear interpolation of the interleaved fields (V vectors of 4 per cell): the weights are
// lane L of the four weight vectors; vector 0 goes to `first`, vector 1 (if any) to `second`.
template <int V, int L>
inline void interpolateCell(const float* packed, size_t corner00, size_t corner10, size_t corner01, size_t corner11,
                            __m128 w00, __m128 w10, __m128 w01, __m128 w11, __m128& first, __m128& second) {
  constexpr size_t stride = 4 * V;
  const __m128 a = lane<L>(w00), b = lane<L>(w10), c = lane<L>(w01), d = lane<L>(w11);
  const float *p00 = packed + corner00 * stride, *p10 = packed + corner10 * stride;
  const float *p01 = packed + corner01 * stride, *p11 = packed + corner11 * stride;
  for (int v = 0; v < V; ++v) {
    __m128 sum = _mm_mul_ps(a, _mm_load_ps(p00 + 4 * v));
    sum = _mm_add_ps(sum, _mm_mul_ps(b, _mm_load_ps(p10 + 4 * v)));
    sum = _mm_add_ps(sum, _mm_mul_ps(c, _mm_load_ps(p01 + 4 * v)));
    sum = _mm_add_ps(sum, _mm_mul_ps(d, _mm_load_ps(p11 + 4 * v)));
    (v == 0 ? first : second) = sum;
  }
}
#endif

}  // namespace

bool Transport::fusedGrid(const WeatherState& s) const {
#if defined(__SSE2__)
  return s.nx % 4 == 0 && s.nx >= 4 && s.ny >= 2 && s.cells() * 12 * sizeof(float) <= kFusedBytes;
#else
  (void)s;
  return false;
#endif
}

void Transport::advect(WeatherState& s, double dt_s) {
  fused_ = fusedGrid(s);
  if (fused_) {
    advectInterleaved(s, dt_s);
    return;
  }
  // Fields that are zero everywhere (no cloud yet) are skipped; they are non-negative, so a zero sum says
  // so.
  vapourBefore_ = sumField(s.vapour);
  cloudBefore_ = sumField(s.cloudWater);
  rainBefore_ = sumField(s.rain);
  const bool convective = anyNonZero(s.cloudTop) || anyNonZero(s.updraft);  // both are ≥ 0
  advection_.prepare(s.windU, s.windV, s.nx, s.ny, s.cellSize_m, dt_s);
  if (convective)
    advection_.advectFields(
        {&s.temperature, &s.vapour, &s.updraft, &s.cloudTop, &s.convectiveFraction, &s.cloudWater, &s.rain});
  else if (cloudBefore_ > 0.0 || rainBefore_ > 0.0)
    advection_.advectFields({&s.temperature, &s.vapour, &s.cloudWater, &s.rain});
  else
    advection_.advectFields({&s.temperature, &s.vapour});
}

void Transport::mixAndConserve(WeatherState& s, double diffusivity_m2_s, double dt_s, double vapourOwed) {
  if (fused_) {
    mixInterleaved(s, diffusivity_m2_s, dt_s, vapourOwed);
    return;
  }
  mixing_.apply(s.temperature, s.nx, s.ny, s.cellSize_m, diffusivity_m2_s, dt_s);
  mixing_.apply(s.vapour, s.nx, s.ny, s.cellSize_m, diffusivity_m2_s, dt_s);
  if (cloudBefore_ > 0.0) mixing_.apply(s.cloudWater, s.nx, s.ny, s.cellSize_m, diffusivity_m2_s, dt_s);
  SemiLagrangianAdvection::restoreTotal(s.vapour, vapourBefore_ + vapourOwed);
  if (cloudBefore_ > 0.0) SemiLagrangianAdvection::restoreTotal(s.cloudWater, cloudBefore_);
  if (rainBefore_ > 0.0) SemiLagrangianAdvection::restoreTotal(s.rain, rainBefore_);
}

#if defined(__SSE2__)

void Transport::advectInterleaved(WeatherState& s, double dt_s) {
  const size_t n = s.cells();
  // Which fields move: all while there is convection (updraft or tops), else T′ and vapour and, where
  // there is any, cloud and rain (non-negative fields: any non-zero value is a positive total).
  const bool convective = anyNonZero(s.cloudTop) || anyNonZero(s.updraft);
  wet_ = convective || anyNonZero(s.cloudWater) || anyNonZero(s.rain);
  const int vectors = convective ? 2 : 1;
  const size_t stride = size_t(4 * vectors);
  packed_ = aligned16(packedBuffer_, n * stride);

  // Interleave (4×4 transposes), summing the water fields as sumField does.
  sse::DomainSum vapourSum(n), cloudSum(n), rainSum(n);
  {
    const float *t = s.temperature.data(), *q = s.vapour.data(), *cw = s.cloudWater.data(), *r = s.rain.data();
    const float *w = s.updraft.data(), *top = s.cloudTop.data(), *conv = s.convectiveFraction.data();
    for (size_t c = 0; c < n; c += 4) {
      __m128 a = _mm_loadu_ps(t + c), b = _mm_loadu_ps(q + c), d = _mm_loadu_ps(cw + c), e = _mm_loadu_ps(r + c);
      vapourSum.add(c, b);
      cloudSum.add(c, d);
      rainSum.add(c, e);
      _MM_TRANSPOSE4_PS(a, b, d, e);
      float* out = packed_ + c * stride;
      _mm_store_ps(out, a);
      _mm_store_ps(out + stride, b);
      _mm_store_ps(out + 2 * stride, d);
      _mm_store_ps(out + 3 * stride, e);
      if (vectors == 2) {
        __m128 f = _mm_loadu_ps(w + c), g = _mm_loadu_ps(top + c), h = _mm_loadu_ps(conv + c), z = _mm_setzero_ps();
        _MM_TRANSPOSE4_PS(f, g, h, z);
        _mm_store_ps(out + 4, f);
        _mm_store_ps(out + stride + 4, g);
        _mm_store_ps(out + 2 * stride + 4, h);
        _mm_store_ps(out + 3 * stride + 4, z);
      }
    }
  }
  vapourBefore_ = vapourSum.total();
  cloudBefore_ = cloudSum.total();
  rainBefore_ = rainSum.total();
  sse::DomainSum rainAfter(n);

  // The bilinear sweep (SemiLagrangianAdvection::advectFields: w₀₀ f₀₀ + w₁₀ f₁₀ + w₀₁ f₀₁ + w₁₁ f₁₁, left
  // to right, per lane; the weights as there, four cells at a time): T′, vapour and cloud into the
  // mixing's input, rain (not mixed) and the convective fields straight back into their fields (the
  // input is the interleaved copy).
  if (vectors == 2)
    sweep<2>(s, dt_s, rainAfter);
  else
    sweep<1>(s, dt_s, rainAfter);
  rainAfter_ = rainAfter.total();
}

template <int V>
void Transport::sweep(WeatherState& s, double dt_s, sse::DomainSum& rainSum) {
  const int nx = s.nx, ny = s.ny;
  const size_t n = s.cells();
  for (Field* f : {&mixT_, &mixQ_, &mixC_}) f->resize(n);
  rowI_.resize(size_t(nx));
  rowJ_.resize(size_t(nx));
  rowFx_.resize(size_t(nx));
  rowFy_.resize(size_t(nx));
  const double scale = dt_s / s.cellSize_m;
  const __m128 one = _mm_set1_ps(1.0f);
  float *t = mixT_.data(), *q = mixQ_.data(), *cw = mixC_.data(), *r = s.rain.data();
  float *updraft = s.updraft.data(), *top = s.cloudTop.data(), *conv = s.convectiveFraction.data();
  for (int j = 0; j < ny; ++j) {
    const size_t row = size_t(j) * size_t(nx);
    SemiLagrangianAdvection::departureRow(j, s.windU.data() + row, s.windV.data() + row, nx, ny, scale, rowI_.data(),
                                          rowJ_.data(), rowFx_.data(), rowFy_.data());
    for (int i = 0; i < nx; i += 4) {
      const __m128 tx = _mm_loadu_ps(&rowFx_[size_t(i)]), ty = _mm_loadu_ps(&rowFy_[size_t(i)]);
      const __m128 sx = _mm_sub_ps(one, tx), sy = _mm_sub_ps(one, ty);
      const __m128 w00 = _mm_mul_ps(sx, sy), w10 = _mm_mul_ps(tx, sy), w01 = _mm_mul_ps(sx, ty),
                   w11 = _mm_mul_ps(tx, ty);
      size_t corner[4][4];
      for (int l = 0; l < 4; ++l) {
        const int x0 = rowI_[size_t(i + l)], y0 = rowJ_[size_t(i + l)];
        const int x1 = x0 + 1 == nx ? 0 : x0 + 1, y1 = y0 + 1 == ny ? 0 : y0 + 1;
        const size_t r0 = size_t(y0) * size_t(nx), r1 = size_t(y1) * size_t(nx);
        corner[l][0] = r0 + size_t(x0);
        corner[l][1] = r0 + size_t(x1);
        corner[l][2] = r1 + size_t(x0);
        corner[l][3] = r1 + size_t(x1);
      }
      __m128 first[4], second[4];
      interpolateCell<V, 0>(packed_, corner[0][0], corner[0][1], corner[0][2], corner[0][3], w00, w10, w01, w11,
                            first[0], second[0]);
      interpolateCell<V, 1>(packed_, corner[1][0], corner[1][1], corner[1][2], corner[1][3], w00, w10, w01, w11,
                            first[1], second[1]);
      interpolateCell<V, 2>(packed_, corner[2][0], corner[2][1], corner[2][2], corner[2][3], w00, w10, w01, w11,
                            first[2], second[2]);
      interpolateCell<V, 3>(packed_, corner[3][0], corner[3][1], corner[3][2], corner[3][3], w00, w10, w01, w11,
                            first[3], second[3]);
      const size_t c = row + size_t(i);
      _MM_TRANSPOSE4_PS(first[0], first[1], first[2], first[3]);
      _mm_storeu_ps(t + c, first[0]);
      _mm_storeu_ps(q + c, first[1]);
      _mm_storeu_ps(cw + c, first[2]);
      if (wet_) {
        _mm_storeu_ps(r + c, first[3]);
        rainSum.add(c, first[3]);
      }
      if (V == 2) {
        _MM_TRANSPOSE4_PS(second[0], second[1], second[2], second[3]);
        _mm_storeu_ps(updraft + c, second[0]);
        _mm_storeu_ps(top + c, second[1]);
        _mm_storeu_ps(conv + c, second[2]);
      }
    }
  }
}

namespace {

// One explicit iteration of Mixing::apply on row j of a periodic nx × ny field, four cells at a time with
// the same operations per lane: c + k (e + w + n + s − 4c), east first. The result's Σ is accumulated.
void mixRow(const float* in, float* out, int j, int nx, int ny, __m128 k, sse::DomainSum* sum) {
  const float* row = in + size_t(j) * size_t(nx);
  const float* north = in + size_t(j + 1 == ny ? 0 : j + 1) * size_t(nx);
  const float* south = in + size_t(j == 0 ? ny - 1 : j - 1) * size_t(nx);
  float* to = out + size_t(j) * size_t(nx);
  const __m128 four = _mm_set1_ps(4.0f);
  for (int i = 0; i < nx; i += 4) {
    const __m128 centre = _mm_loadu_ps(row + i);
    const __m128 west = i == 0 ? _mm_setr_ps(row[nx - 1], row[0], row[1], row[2]) : _mm_loadu_ps(row + i - 1);
    const __m128 east =
        i + 4 == nx ? _mm_setr_ps(row[i + 1], row[i + 2], row[i + 3], row[0]) : _mm_loadu_ps(row + i + 1);
    __m128 flux = _mm_add_ps(_mm_add_ps(_mm_add_ps(east, west), _mm_loadu_ps(north + i)), _mm_loadu_ps(south + i));
    flux = _mm_sub_ps(flux, _mm_mul_ps(four, centre));
    const __m128 mixed = _mm_add_ps(centre, _mm_mul_ps(k, flux));
    _mm_storeu_ps(to + i, mixed);
    if (sum) sum->add(size_t(j) * size_t(nx) + size_t(i), mixed);
  }
}

// A copy of row j with its Σ accumulated.
void copyRow(const float* in, float* out, int j, int nx, sse::DomainSum* sum) {
  const size_t row = size_t(j) * size_t(nx);
  for (int i = 0; i < nx; i += 4) {
    const __m128 v = _mm_loadu_ps(in + row + size_t(i));
    _mm_storeu_ps(out + row + size_t(i), v);
    if (sum) sum->add(row + size_t(i), v);
  }
}

}  // namespace

void Transport::mixInterleaved(WeatherState& s, double diffusivity_m2_s, double dt_s, double vapourOwed) {
  const int nx = s.nx, ny = s.ny;
  const size_t n = s.cells();
  // Mixing::apply's iterations and coefficient, on T′, vapour and (where there was cloud) cloud water;
  // all but the last iteration between scratch fields, the last one into the model's fields with the
  // water totals summed as sumField does.
  const double number = diffusivity_m2_s * dt_s / (s.cellSize_m * s.cellSize_m);
  const int iterations = number <= 0.0 ? 0 : int(std::ceil(number / 0.2));
  const __m128 k = _mm_set1_ps(iterations > 0 ? float(number / iterations) : 0.0f);
  sse::DomainSum vapourSum(n), cloudSum(n);
  const bool mixCloud = cloudBefore_ > 0.0;
  struct Mixed {
    Field* scratch;
    Field* target;
    bool mixes;
    sse::DomainSum* sum;
  };
  const Mixed fields[3] = {{&mixT_, &s.temperature, true, nullptr},
                           {&mixQ_, &s.vapour, true, &vapourSum},
                           {&mixC_, &s.cloudWater, mixCloud, &cloudSum}};
  for (const Mixed& f : fields) {
    if (f.target == &s.cloudWater && !wet_) continue;  // not advected: zero, and left as it was
    if (!f.mixes || iterations == 0) {
      for (int j = 0; j < ny; ++j) copyRow(f.scratch->data(), f.target->data(), j, nx, f.sum);
      continue;
    }
    spare_.resize(n);
    Field* from = f.scratch;
    Field* other = &spare_;
    for (int it = 0; it + 1 < iterations; ++it) {
      for (int j = 0; j < ny; ++j) mixRow(from->data(), other->data(), j, nx, ny, k, nullptr);
      std::swap(from, other);
    }
    for (int j = 0; j < ny; ++j) mixRow(from->data(), f.target->data(), j, nx, ny, k, f.sum);
  }
  // The mass fix, with the fields' totals known.
  SemiLagrangianAdvection::restoreTotal(s.vapour, vapourBefore_ + vapourOwed, vapourSum.total());
  if (cloudBefore_ > 0.0) SemiLagrangianAdvection::restoreTotal(s.cloudWater, cloudBefore_, cloudSum.total());
  if (rainBefore_ > 0.0) SemiLagrangianAdvection::restoreTotal(s.rain, rainBefore_, rainAfter_);
}

#else

void Transport::advectInterleaved(WeatherState&, double) {}
void Transport::mixInterleaved(WeatherState&, double, double, double) {}

#endif

}  // namespace firmament::weather
