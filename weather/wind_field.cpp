#include "weather/wind_field.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "weather/value_noise.h"

namespace firmament::weather {
namespace {

// [1 2 1]/4 along x then y on a periodic nx × ny field (in place, via scratch).
void binomialSmooth(Field& f, Field& scratch, int nx, int ny) {
  scratch.resize(f.size());
  for (int j = 0; j < ny; ++j) {
    const float* row = &f[size_t(j) * nx];
    float* out = &scratch[size_t(j) * nx];
    auto at = [&](int i) {
      int w = i == 0 ? nx - 1 : i - 1, e = i + 1 == nx ? 0 : i + 1;
      out[i] = 0.25f * (row[w] + row[e]) + 0.5f * row[i];
    };
    at(0);
    int i = 1;
#if defined(__SSE2__)
    // The interior four cells at a time, the same operations per lane.
    for (; i + 4 <= nx - 1; i += 4)
      _mm_storeu_ps(out + i, _mm_add_ps(_mm_mul_ps(_mm_set1_ps(0.25f),
                                                   _mm_add_ps(_mm_loadu_ps(row + i - 1), _mm_loadu_ps(row + i + 1))),
                                        _mm_mul_ps(_mm_set1_ps(0.5f), _mm_loadu_ps(row + i))));
#endif
    for (; i < nx; ++i) at(i);
  }
  for (int j = 0; j < ny; ++j) {
    const float* south = &scratch[size_t(j == 0 ? ny - 1 : j - 1) * nx];
    const float* row = &scratch[size_t(j) * nx];
    const float* north = &scratch[size_t(j + 1 == ny ? 0 : j + 1) * nx];
    float* out = &f[size_t(j) * nx];
    for (int i = 0; i < nx; ++i) out[i] = 0.25f * (south[i] + north[i]) + 0.5f * row[i];
  }
}

#if defined(__SSE2__)
// One coarse row to the fine row of a grid twice as fine (the 400 m grid on 200 m cells): fine cell 2k
// lies ¾ of the way from coarse k − 1 to k, cell 2k + 1 ¼ of the way from k to k + 1 (the weights
// coarseNeighbours gives), so four coarse values make eight cells, with the same arithmetic as the
// general loop in update(): (offset + a) + w (b − a), or a + w (b − a) without an offset; then, where
// given, the perturbation b₀ p₀ + b₁ p₁ added as update()'s general loop adds it. The row is padded with
// its periodic neighbours.
void interpolatePairs(const std::vector<float>& coarse, float offset, bool withOffset, float* out,
                      std::vector<float>& padded, const float* perturbation0 = nullptr,
                      const float* perturbation1 = nullptr, float b0 = 0.0f, float b1 = 0.0f) {
  const size_t cn = coarse.size();
  padded.resize(cn + 8);
  padded[0] = coarse[cn - 1];
  std::copy(coarse.begin(), coarse.end(), padded.begin() + 1);
  padded[cn + 1] = coarse[0];
  const __m128 offsetV = _mm_set1_ps(offset), threeQuarters = _mm_set1_ps(0.75f), quarter = _mm_set1_ps(0.25f);
  const __m128 b0V = _mm_set1_ps(b0), b1V = _mm_set1_ps(b1);
  size_t k = 0;
  for (; k + 4 <= cn; k += 4) {
    const __m128 left = _mm_loadu_ps(&padded[k]), centre = _mm_loadu_ps(&padded[k + 1]),
                 right = _mm_loadu_ps(&padded[k + 2]);
    const __m128 evenBase = withOffset ? _mm_add_ps(offsetV, left) : left;
    const __m128 oddBase = withOffset ? _mm_add_ps(offsetV, centre) : centre;
    const __m128 even = _mm_add_ps(evenBase, _mm_mul_ps(threeQuarters, _mm_sub_ps(centre, left)));
    const __m128 odd = _mm_add_ps(oddBase, _mm_mul_ps(quarter, _mm_sub_ps(right, centre)));
    __m128 lo = _mm_unpacklo_ps(even, odd), hi = _mm_unpackhi_ps(even, odd);
    if (perturbation0) {
      lo = _mm_add_ps(lo, _mm_add_ps(_mm_mul_ps(b0V, _mm_loadu_ps(perturbation0 + 2 * k)),
                                     _mm_mul_ps(b1V, _mm_loadu_ps(perturbation1 + 2 * k))));
      hi = _mm_add_ps(hi, _mm_add_ps(_mm_mul_ps(b0V, _mm_loadu_ps(perturbation0 + 2 * k + 4)),
                                     _mm_mul_ps(b1V, _mm_loadu_ps(perturbation1 + 2 * k + 4))));
    }
    _mm_storeu_ps(out + 2 * k, lo);
    _mm_storeu_ps(out + 2 * k + 4, hi);
  }
  for (; k < cn; ++k) {
    const float a = padded[k], b = padded[k + 1], c = padded[k + 2];
    out[2 * k] = (withOffset ? offset + a : a) + 0.75f * (b - a);
    out[2 * k + 1] = (withOffset ? offset + b : b) + 0.25f * (c - b);
    if (perturbation0)
      for (size_t i = 2 * k; i < 2 * k + 2; ++i) out[i] += b0 * perturbation0[i] + b1 * perturbation1[i];
  }
}
#endif

// Largest block size ≤ target that divides both grid sizes.
int blockFactor(int nx, int ny, int target) {
  for (int f = std::max(1, target); f > 1; --f)
    if (nx % f == 0 && ny % f == 0) return f;
  return 1;
}

// Bilinear neighbours of fine cell centres in a grid coarser by `factor` (periodic).
void coarseNeighbours(int n, int factor, std::vector<int32_t>& lo, std::vector<int32_t>& hi, std::vector<float>& w) {
  const int coarse = n / factor;
  lo.resize(n);
  hi.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = (i + 0.5) / factor - 0.5;  // in coarse cell-centre units
    double fl = std::floor(x);
    int a = int(fl);
    w[i] = float(x - fl);
    lo[i] = (a % coarse + coarse) % coarse;
    hi[i] = ((a + 1) % coarse + coarse) % coarse;
  }
}

}  // namespace

WindField::WindField(int nx, int ny, double cellSize_m, uint32_t seed) : nx_(nx), ny_(ny), cellSize_(cellSize_m) {
  // Six modes with wavelengths from the domain size down to about an eighth of it.
  const int kModes = 6;
  for (int m = 0; m < kModes; ++m) {
    uint32_t h = hashCombine(seed ^ 0x5EEDu, uint32_t(m));
    Mode mode;
    int k = 1 + m;
    double angle = 2.0 * std::numbers::pi * unitFloat(hashCombine(h, 1));
    mode.kx = int(std::lround(k * std::cos(angle)));
    mode.ky = int(std::lround(k * std::sin(angle)));
    if (mode.kx == 0 && mode.ky == 0) mode.kx = 1;
    mode.amplitude = std::sqrt(2.0 / kModes);  // each cos mode has mean square a²/2
    mode.phase = 2.0 * std::numbers::pi * unitFloat(hashCombine(h, 2));
    double period_s = 3600.0 * (1.0 + 2.0 * unitFloat(hashCombine(h, 3)));
    mode.angularFrequency = 2.0 * std::numbers::pi / period_s * (unitFloat(hashCombine(h, 4)) < 0.5 ? -1 : 1);
    modes_.push_back(mode);
  }
  cosX_.resize(modes_.size() * nx_);
  sinX_.resize(modes_.size() * nx_);
  cosY_.resize(modes_.size() * ny_);
  sinY_.resize(modes_.size() * ny_);
  for (size_t m = 0; m < modes_.size(); ++m) {
    for (int i = 0; i < nx_; ++i) {
      double a = 2.0 * std::numbers::pi * modes_[m].kx * (i + 0.5) / nx_;
      cosX_[m * nx_ + i] = float(std::cos(a));
      sinX_[m * nx_ + i] = float(std::sin(a));
    }
    for (int j = 0; j < ny_; ++j) {
      double a = 2.0 * std::numbers::pi * modes_[m].ky * (j + 0.5) / ny_;
      cosY_[m * ny_ + j] = float(std::cos(a));
      sinY_[m * ny_ + j] = float(std::sin(a));
    }
  }
  factor_ = blockFactor(nx, ny, int(std::lround(kSmoothingBlock_m / cellSize_m)));
  cnx_ = nx / factor_;
  cny_ = ny / factor_;
  for (Field* f : {&coarseT_, &coarseU_, &coarseV_, &coarseLift_}) f->assign(size_t(cnx_) * cny_, 0.0f);
  coarseNeighbours(nx, factor_, x0_, x1_, wx_);
  coarseNeighbours(ny, factor_, y0_, y1_, wy_);
}

void WindField::perturbationSnapshot(double t_s, double turbulence, Field& u, Field& v) const {
  // ψ = Σ A sin(θ), θ = kx·2πx/Lx + ky·2πy/Ly + φ(t); u = ∂ψ/∂y = Σ A (2π ky/Ly) cos θ,
  // v = −∂ψ/∂x = −Σ A (2π kx/Lx) cos θ; A is chosen so that each mode's speed amplitude is
  // amplitude · turbulence.
  const int nx = nx_, ny = ny_;
  const double lx = nx * cellSize_, ly = ny * cellSize_;
  // All modes in one pass over the cells, each cell's sum in the order of the modes (as a pass per mode
  // would add them).
  u.resize(size_t(nx) * ny);
  v.resize(size_t(nx) * ny);
  const size_t modes = modes_.size();
  std::vector<float> cu(modes), cv(modes), cp(modes), sp(modes), cb(modes), sb(modes);
  for (size_t m = 0; m < modes; ++m) {
    const Mode& mode = modes_[m];
    double kxw = mode.kx / lx, kyw = mode.ky / ly, kNorm = std::hypot(kxw, kyw);
    cu[m] = float(turbulence * mode.amplitude * kyw / kNorm);
    cv[m] = float(-turbulence * mode.amplitude * kxw / kNorm);
    double phase = mode.phase + mode.angularFrequency * t_s;
    cp[m] = float(std::cos(phase));
    sp[m] = float(std::sin(phase));
  }
  for (int j = 0; j < ny; ++j) {
    // cos(a + b + φ) with the y part and φ folded into (cb, sb).
    for (size_t m = 0; m < modes; ++m) {
      float cy = cosY_[m * ny + j], sy = sinY_[m * ny + j];
      cb[m] = cy * cp[m] - sy * sp[m];
      sb[m] = sy * cp[m] + cy * sp[m];
    }
    float* ur = &u[size_t(j) * nx];
    float* vr = &v[size_t(j) * nx];
    std::fill(ur, ur + nx, 0.0f);
    std::fill(vr, vr + nx, 0.0f);
    for (size_t m = 0; m < modes; ++m) {
      const float* cx = &cosX_[m * nx];
      const float* sx = &sinX_[m * nx];
      const float cbm = cb[m], sbm = sb[m], cum = cu[m], cvm = cv[m];
      for (int i = 0; i < nx; ++i) {
        float c = cx[i] * cbm - sx[i] * sbm;
        ur[i] += cum * c;
        vr[i] += cvm * c;
      }
    }
  }
}

double WindField::buoyancyFlow(const WeatherState& s, const WindParameters& p) {
  // Block means of T′, smoothed; then centred differences on the coarse grid (spacing D = f Δx).
  const int f = factor_, cnx = cnx_, cny = cny_;
  const float inv = 1.0f / float(f * f);
  std::fill(coarseT_.begin(), coarseT_.end(), 0.0f);
  int j0 = 0;
#if defined(__SSE2__)
  // Blocks of 2 × 2 (200 m cells), four coarse cells from two rows of eight: each row's pair sum added to
  // the block's running sum of zero as the general loop below adds them, then the mean.
  if (f == 2 && nx_ % 8 == 0) {
    const __m128 invV = _mm_set1_ps(inv);
    for (; j0 + 2 <= ny_; j0 += 2) {
      const float* a = &s.temperature[size_t(j0) * nx_];
      const float* b = a + nx_;
      float* out = &coarseT_[size_t(j0 / 2) * cnx];
      for (int i = 0; i < nx_; i += 8) {
        const __m128 a0 = _mm_loadu_ps(a + i), a1 = _mm_loadu_ps(a + i + 4), b0 = _mm_loadu_ps(b + i),
                     b1 = _mm_loadu_ps(b + i + 4);
        const __m128 first = _mm_add_ps(_mm_shuffle_ps(a0, a1, _MM_SHUFFLE(2, 0, 2, 0)),
                                        _mm_shuffle_ps(a0, a1, _MM_SHUFFLE(3, 1, 3, 1)));
        const __m128 second = _mm_add_ps(_mm_shuffle_ps(b0, b1, _MM_SHUFFLE(2, 0, 2, 0)),
                                         _mm_shuffle_ps(b0, b1, _MM_SHUFFLE(3, 1, 3, 1)));
        _mm_storeu_ps(out + i / 2, _mm_mul_ps(_mm_add_ps(_mm_add_ps(_mm_setzero_ps(), first), second), invV));
      }
    }
  }
#endif
  if (j0 < ny_) {
    for (int j = j0; j < ny_; ++j) {
      const float* row = &s.temperature[size_t(j) * nx_];
      float* out = &coarseT_[size_t(j / f) * cnx];
      for (int b = 0; b < cnx; ++b, row += f) {
        float sum = 0.0f;
        for (int k = 0; k < f; ++k) sum += row[k];
        out[b] += sum;
      }
    }
    for (float& t : coarseT_) t *= inv;
  }
  binomialSmooth(coarseT_, scratch_, cnx, cny);
  binomialSmooth(coarseT_, scratch_, cnx, cny);

  const double spacing = f * cellSize_;
  const float kappa = float(p.buoyancyWind_m2_s_K), maxSpeed = float(p.maxBuoyancyWind_m_s);
  const float inv2d = float(1.0 / (2.0 * spacing)), invD2 = float(1.0 / (spacing * spacing));
  const float depth = float(p.boundaryLayerDepth_m);
  const Field& T = coarseT_;
  float maxCurvature = 0.0f;  // max over cells of κ·limit·(|∂²T/∂x²| + |∂²T/∂y²|)·D²
  // One coarse cell's flow, limit and lift (the same operations in SSE2 lanes below).
  auto cell = [&](size_t c, float tc, float te, float tw, float tn, float ts) {
    float ub = kappa * (te - tw) * inv2d, vb = kappa * (tn - ts) * inv2d;
    float speed2 = ub * ub + vb * vb;
    float limit = speed2 > maxSpeed * maxSpeed ? maxSpeed / std::sqrt(speed2) : 1.0f;
    coarseU_[c] = ub * limit;
    coarseV_[c] = vb * limit;
    // ∇·u_b = κ ∇²T̃′ (limited alike); w at the boundary-layer top = −h ∇·u_b.
    float laplacian = (te + tw + tn + ts - 4.0f * tc) * invD2;
    coarseLift_[c] = -depth * kappa * limit * laplacian;
    maxCurvature =
        std::max(maxCurvature, kappa * limit * (std::fabs(te + tw - 2.0f * tc) + std::fabs(tn + ts - 2.0f * tc)));
  };
  for (int j = 0; j < cny; ++j) {
    int jn = j + 1 == cny ? 0 : j + 1, js = j == 0 ? cny - 1 : j - 1;
    const float* row = &T[size_t(j) * cnx];
    const float* north = &T[size_t(jn) * cnx];
    const float* south = &T[size_t(js) * cnx];
    const size_t base = size_t(j) * cnx;
    cell(base, row[0], row[cnx > 1 ? 1 : 0], row[cnx - 1], north[0], south[0]);
    int i = 1;
#if defined(__SSE2__)
    {
      const __m128 kappaV = _mm_set1_ps(kappa), inv2dV = _mm_set1_ps(inv2d), invD2V = _mm_set1_ps(invD2);
      const __m128 maxSpeedV = _mm_set1_ps(maxSpeed), maxSpeed2 = _mm_set1_ps(maxSpeed * maxSpeed),
                   one = _mm_set1_ps(1.0f);
      const __m128 four = _mm_set1_ps(4.0f), two = _mm_set1_ps(2.0f), minusDepthKappa = _mm_set1_ps(-depth * kappa);
      const __m128 sign = _mm_set1_ps(-0.0f);
      __m128 curvature = _mm_setzero_ps();
      for (; i + 4 <= cnx - 1; i += 4) {
        const __m128 tc = _mm_loadu_ps(row + i), te = _mm_loadu_ps(row + i + 1), tw = _mm_loadu_ps(row + i - 1);
        const __m128 tn = _mm_loadu_ps(north + i), ts = _mm_loadu_ps(south + i);
        const __m128 ub = _mm_mul_ps(_mm_mul_ps(kappaV, _mm_sub_ps(te, tw)), inv2dV);
        const __m128 vb = _mm_mul_ps(_mm_mul_ps(kappaV, _mm_sub_ps(tn, ts)), inv2dV);
        const __m128 speed2 = _mm_add_ps(_mm_mul_ps(ub, ub), _mm_mul_ps(vb, vb));
        const __m128 fast = _mm_cmpgt_ps(speed2, maxSpeed2);
        const __m128 limit =
            _mm_or_ps(_mm_and_ps(fast, _mm_div_ps(maxSpeedV, _mm_sqrt_ps(speed2))), _mm_andnot_ps(fast, one));
        _mm_storeu_ps(&coarseU_[base + i], _mm_mul_ps(ub, limit));
        _mm_storeu_ps(&coarseV_[base + i], _mm_mul_ps(vb, limit));
        const __m128 laplacian =
            _mm_mul_ps(_mm_sub_ps(_mm_add_ps(_mm_add_ps(_mm_add_ps(te, tw), tn), ts), _mm_mul_ps(four, tc)), invD2V);
        _mm_storeu_ps(&coarseLift_[base + i], _mm_mul_ps(_mm_mul_ps(minusDepthKappa, limit), laplacian));
        const __m128 bendX = _mm_andnot_ps(sign, _mm_sub_ps(_mm_add_ps(te, tw), _mm_mul_ps(two, tc)));
        const __m128 bendY = _mm_andnot_ps(sign, _mm_sub_ps(_mm_add_ps(tn, ts), _mm_mul_ps(two, tc)));
        curvature = _mm_max_ps(curvature, _mm_mul_ps(_mm_mul_ps(kappaV, limit), _mm_add_ps(bendX, bendY)));
      }
      alignas(16) float lanes[4];
      _mm_store_ps(lanes, curvature);
      for (float x : lanes) maxCurvature = std::max(maxCurvature, x);
    }
#endif
    for (; i < cnx; ++i) {
      const int ie = i + 1 == cnx ? 0 : i + 1, iw = i - 1;
      cell(base + i, row[i], row[ie], row[iw], north[i], south[i]);
    }
  }
  return double(maxCurvature) * double(invD2);
}

double WindField::update(WeatherState& s, const WindParameters& p, double t_s) {
  const int nx = nx_, ny = ny_;
  const double lx = nx * cellSize_, ly = ny * cellSize_;
  // Perturbation snapshots bracketing t.
  const bool turbulent = p.turbulence_m_s > 0.0;
  float a = 0.0f;
  if (turbulent) {
    long long k = (long long)std::floor(t_s / kPerturbationInterval_s);
    if (p.turbulence_m_s != snapshotTurbulence_ || k != snapshotIndex_) {
      if (k == snapshotIndex_ + 1 && p.turbulence_m_s == snapshotTurbulence_) {
        std::swap(snapU_[0], snapU_[1]);
        std::swap(snapV_[0], snapV_[1]);
      } else {
        perturbationSnapshot(double(k) * kPerturbationInterval_s, p.turbulence_m_s, snapU_[0], snapV_[0]);
      }
      perturbationSnapshot(double(k + 1) * kPerturbationInterval_s, p.turbulence_m_s, snapU_[1], snapV_[1]);
      snapshotIndex_ = k;
      snapshotTurbulence_ = p.turbulence_m_s;
    }
    a = float(t_s / kPerturbationInterval_s - double(k));
  }
  const double buoyancyDeformation = buoyancyFlow(s, p);

  // u = U₀ + perturbation (interpolated in time) + u_b (interpolated from the coarse grid), one pass.
  const float u0 = float(p.prevailingU_m_s), v0 = float(p.prevailingV_m_s);
  const float b0 = 1.0f - a, b1 = a;
  std::vector<float>& rowU = rowU_;
  std::vector<float>& rowV = rowV_;
  std::vector<float>& rowLift = rowLift_;
  rowU.resize(size_t(cnx_));
  rowV.resize(size_t(cnx_));
  rowLift.resize(size_t(cnx_));
  for (int j = 0; j < ny; ++j) {
    const float wy = wy_[j];
    const size_t r0 = size_t(y0_[j]) * cnx_, r1 = size_t(y1_[j]) * cnx_;
    for (int i = 0; i < cnx_; ++i) {
      rowU[i] = coarseU_[r0 + i] + wy * (coarseU_[r1 + i] - coarseU_[r0 + i]);
      rowV[i] = coarseV_[r0 + i] + wy * (coarseV_[r1 + i] - coarseV_[r0 + i]);
      rowLift[i] = coarseLift_[r0 + i] + wy * (coarseLift_[r1 + i] - coarseLift_[r0 + i]);
    }
    const size_t row = size_t(j) * nx;
    float* u = &s.windU[row];
    float* v = &s.windV[row];
    float* lift = &s.lift[row];
#if defined(__SSE2__)
    if (factor_ == 2 && cnx_ >= 4) {
      // The perturbation added in the same pass (the general loop's arithmetic).
      if (turbulent) {
        interpolatePairs(rowU, u0, true, u, padded_, &snapU_[0][row], &snapU_[1][row], b0, b1);
        interpolatePairs(rowV, v0, true, v, padded_, &snapV_[0][row], &snapV_[1][row], b0, b1);
      } else {
        interpolatePairs(rowU, u0, true, u, padded_);
        interpolatePairs(rowV, v0, true, v, padded_);
      }
      interpolatePairs(rowLift, 0.0f, false, lift, padded_);
      continue;
    }
#endif
    for (int i = 0; i < nx; ++i) {
      const int c0 = x0_[i], c1 = x1_[i];
      const float wx = wx_[i];
      u[i] = u0 + rowU[c0] + wx * (rowU[c1] - rowU[c0]);
      v[i] = v0 + rowV[c0] + wx * (rowV[c1] - rowV[c0]);
      lift[i] = rowLift[c0] + wx * (rowLift[c1] - rowLift[c0]);
    }
    if (turbulent) {
      const float *su0 = &snapU_[0][row], *su1 = &snapU_[1][row], *sv0 = &snapV_[0][row], *sv1 = &snapV_[1][row];
      for (int i = 0; i < nx; ++i) {
        u[i] += b0 * su0[i] + b1 * su1[i];
        v[i] += b0 * sv0[i] + b1 * sv1[i];
      }
    }
  }
  // The perturbation's deformation: Σ |amplitude| |k|.
  double turbulenceDeformation = 0.0;
  for (const Mode& m : modes_)
    turbulenceDeformation += p.turbulence_m_s * m.amplitude * 2.0 * std::numbers::pi * std::hypot(m.kx / lx, m.ky / ly);
  return buoyancyDeformation + turbulenceDeformation;
}

}  // namespace firmament::weather
