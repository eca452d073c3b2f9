#include "weather/compensating_subsidence.h"

#include <algorithm>
#include <cmath>

#include "weather/physical_constants.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace firmament::weather {
namespace {

int blockFactor(int nx, int ny, int target) {
  for (int f = std::max(1, target); f > 1; --f)
    if (nx % f == 0 && ny % f == 0) return f;
  return 1;
}

void neighbours(int n, int factor, std::vector<int32_t>& lo, std::vector<int32_t>& hi, std::vector<float>& w) {
  const int coarse = n / factor;
  lo.resize(n);
  hi.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = (i + 0.5) / factor - 0.5, fl = std::floor(x);
    int a = int(fl);
    w[i] = float(x - fl);
    lo[i] = (a % coarse + coarse) % coarse;
    hi[i] = ((a + 1) % coarse + coarse) % coarse;
  }
}

}  // namespace

CompensatingSubsidence::CompensatingSubsidence(int nx, int ny, double cellSize_m) : nx_(nx), ny_(ny) {
  block_ = blockFactor(nx, ny, int(std::lround(kBlock_m / cellSize_m)));
  cnx_ = nx / block_;
  cny_ = ny / block_;
  // A [1 2 1] pass adds ½ cell² of variance per direction: passes for σ = kRadius_m.
  const double sigmaCells = kRadius_m / (block_ * cellSize_m);
  passes_ = std::clamp(int(std::lround(2.0 * sigmaCells * sigmaCells)), 1, 64);
  flux_.assign(size_t(cnx_) * cny_, 0.0f);
  delta_.assign(size_t(cnx_) * cny_, 0.0f);
  neighbours(nx, block_, x0_, x1_, wx_);
  neighbours(ny, block_, y0_, y1_, wy_);
  // Runs of four columns that share their coarse neighbours (every aligned four when the block is a
  // multiple of eight cells).
  uniform_.resize(size_t(nx / 4));
  for (int q = 0; q + 4 <= nx; q += 4) uniform_[size_t(q / 4)] = x0_[q] == x0_[q + 3] && x1_[q] == x1_[q + 3];
}

double CompensatingSubsidence::domainMean_K() const {
  double sum = 0.0;
  for (float d : delta_) sum += d;
  return sum / double(delta_.size());
}

void CompensatingSubsidence::apply(const WeatherState& s, double coreFraction, double freeLapseRate, double dt_s,
                                   Field& warming) {
  const int cnx = cnx_, cny = cny_, b = block_;
  std::fill(flux_.begin(), flux_.end(), 0.0f);
  for (int j = 0; j < ny_; ++j) {
    const float* w = &s.updraft[size_t(j) * nx_];
    float* out = &flux_[size_t(j / b) * cnx];
    int block = 0;
#if defined(__SSE2__)
    // Four blocks of eight at a time, a block per lane (4×4 transposes): each block's sum from zero in
    // the cells' order, as below.
    if (b == 8)
      for (; block + 4 <= cnx; block += 4, w += 32) {
        __m128 lo[4], hi[4];
        for (int k = 0; k < 4; ++k) {
          lo[k] = _mm_loadu_ps(w + 8 * k);
          hi[k] = _mm_loadu_ps(w + 8 * k + 4);
        }
        _MM_TRANSPOSE4_PS(lo[0], lo[1], lo[2], lo[3]);
        _MM_TRANSPOSE4_PS(hi[0], hi[1], hi[2], hi[3]);
        __m128 sum = _mm_setzero_ps();
        for (int k = 0; k < 4; ++k) sum = _mm_add_ps(sum, lo[k]);
        for (int k = 0; k < 4; ++k) sum = _mm_add_ps(sum, hi[k]);
        _mm_storeu_ps(out + block, _mm_add_ps(_mm_loadu_ps(out + block), sum));
      }
#endif
    for (; block < cnx; ++block, w += b) {
      float sum = 0.0f;
      for (int k = 0; k < b; ++k) sum += w[k];
      out[block] += sum;
    }
  }
  const float perBlock = float(coreFraction / double(b * b));
  for (float& f : flux_) f *= perBlock;
  scratch_.resize(flux_.size());
  for (int pass = 0; pass < passes_; ++pass) {
    for (int j = 0; j < cny; ++j) {
      const float* row = &flux_[size_t(j) * cnx];
      float* out = &scratch_[size_t(j) * cnx];
      auto at = [&](int i) {
        out[i] = 0.5f * row[i] + 0.25f * (row[i == 0 ? cnx - 1 : i - 1] + row[i + 1 == cnx ? 0 : i + 1]);
      };
      at(0);
      int i = 1;
#if defined(__SSE2__)
      // The interior four cells at a time, the same operations per lane.
      for (; i + 4 <= cnx - 1; i += 4) {
        const __m128 west = _mm_loadu_ps(row + i - 1), east = _mm_loadu_ps(row + i + 1);
        _mm_storeu_ps(out + i, _mm_add_ps(_mm_mul_ps(_mm_set1_ps(0.5f), _mm_loadu_ps(row + i)),
                                          _mm_mul_ps(_mm_set1_ps(0.25f), _mm_add_ps(west, east))));
      }
#endif
      for (; i < cnx; ++i) at(i);
    }
    for (int j = 0; j < cny; ++j) {
      const float* south = &scratch_[size_t(j == 0 ? cny - 1 : j - 1) * cnx];
      const float* row = &scratch_[size_t(j) * cnx];
      const float* north = &scratch_[size_t(j + 1 == cny ? 0 : j + 1) * cnx];
      for (int i = 0; i < cnx; ++i) flux_[size_t(j) * cnx + i] = 0.5f * row[i] + 0.25f * (south[i] + north[i]);
    }
  }
  // δ ← δ_eq + (δ − δ_eq) e^{−Δt/τ}, δ_eq = γ M̃ τ.
  const float gamma = float(std::max(kDryAdiabaticLapseRate - freeLapseRate, 0.0));
  const float decay = float(std::exp(-dt_s / kRelaxation_s)), scale = gamma * float(kRelaxation_s);
  for (size_t c = 0; c < delta_.size(); ++c) {
    const float equilibrium = scale * flux_[c];
    delta_[c] = equilibrium + (delta_[c] - equilibrium) * decay;
  }
  // Bilinear back to the cells.
  warming.resize(s.cells());
  for (int j = 0; j < ny_; ++j) {
    const float wy = wy_[j];
    const float* r0 = &delta_[size_t(y0_[j]) * cnx];
    const float* r1 = &delta_[size_t(y1_[j]) * cnx];
    float* out = &warming[size_t(j) * nx_];
    int i = 0;
#if defined(__SSE2__)
    // Four columns with the same coarse neighbours at a time, the same operations per lane.
    const __m128 wyV = _mm_set1_ps(wy);
    for (; i + 4 <= nx_; i += 4) {
      if (!uniform_[size_t(i / 4)]) {
        for (int k = i; k < i + 4; ++k) {
          const int a = x0_[k], c = x1_[k];
          const float lo = r0[a] + wx_[k] * (r0[c] - r0[a]), hi = r1[a] + wx_[k] * (r1[c] - r1[a]);
          out[k] = lo + wy * (hi - lo);
        }
        continue;
      }
      const int a = x0_[i], c = x1_[i];
      const __m128 w = _mm_loadu_ps(&wx_[i]);
      const __m128 r0a = _mm_set1_ps(r0[a]), r0c = _mm_set1_ps(r0[c]), r1a = _mm_set1_ps(r1[a]),
                   r1c = _mm_set1_ps(r1[c]);
      const __m128 lo = _mm_add_ps(r0a, _mm_mul_ps(w, _mm_sub_ps(r0c, r0a)));
      const __m128 hi = _mm_add_ps(r1a, _mm_mul_ps(w, _mm_sub_ps(r1c, r1a)));
      _mm_storeu_ps(out + i, _mm_add_ps(lo, _mm_mul_ps(wyV, _mm_sub_ps(hi, lo))));
    }
#endif
    for (; i < nx_; ++i) {
      const int a = x0_[i], c = x1_[i];
      const float lo = r0[a] + wx_[i] * (r0[c] - r0[a]), hi = r1[a] + wx_[i] * (r1[c] - r1[a]);
      out[i] = lo + wy * (hi - lo);
    }
  }
}

}  // namespace firmament::weather
