#include "weather/wind_field.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "weather/value_noise.h"

namespace firmament::weather {

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
}

double WindField::update(WeatherState& s, const WindParameters& p, double t_s) {
  const int nx = nx_, ny = ny_;
  const double lx = nx * cellSize_, ly = ny * cellSize_;
  // Divergence-free part: ψ = Σ A sin(θ), θ = kx·2πx/Lx + ky·2πy/Ly + φ(t);
  // u = ∂ψ/∂y = Σ A (2π ky/Ly) cos θ,  v = −∂ψ/∂x = −Σ A (2π kx/Lx) cos θ.
  // A is chosen so that each mode's speed amplitude is amplitude · turbulence.
  std::fill(s.windU.begin(), s.windU.end(), float(p.prevailingU_m_s));
  std::fill(s.windV.begin(), s.windV.end(), float(p.prevailingV_m_s));
  if (p.turbulence_m_s > 0.0) {
    for (size_t m = 0; m < modes_.size(); ++m) {
      const Mode& mode = modes_[m];
      double kxw = mode.kx / lx, kyw = mode.ky / ly, kNorm = std::hypot(kxw, kyw);
      float cu = float(p.turbulence_m_s * mode.amplitude * kyw / kNorm);
      float cv = float(-p.turbulence_m_s * mode.amplitude * kxw / kNorm);
      double phase = mode.phase + mode.angularFrequency * t_s;
      float cp = float(std::cos(phase)), sp = float(std::sin(phase));
      const float* cx = &cosX_[m * nx];
      const float* sx = &sinX_[m * nx];
      for (int j = 0; j < ny; ++j) {
        // cos(a + b + φ) with b = y part folded into (cb, sb).
        float cy = cosY_[m * ny + j], sy = sinY_[m * ny + j];
        float cb = cy * cp - sy * sp, sb = sy * cp + cy * sp;
        float* u = &s.windU[s.index(0, j)];
        float* v = &s.windV[s.index(0, j)];
        for (int i = 0; i < nx; ++i) {
          float c = cx[i] * cb - sx[i] * sb;
          u[i] += cu * c;
          v[i] += cv * c;
        }
      }
    }
  }
  // Buoyancy-driven part from centred differences of T′, and the lift from its convergence.
  const float kappa = float(p.buoyancyWind_m2_s_K), maxSpeed = float(p.maxBuoyancyWind_m_s);
  const float inv2dx = float(1.0 / (2.0 * cellSize_)), invDx2 = float(1.0 / (cellSize_ * cellSize_));
  const float depth = float(p.boundaryLayerDepth_m);
  const Field& T = s.temperature;
  double maxDeformation = 0.0;
  for (int j = 0; j < ny; ++j) {
    int jn = j + 1 == ny ? 0 : j + 1, js = j == 0 ? ny - 1 : j - 1;
    for (int i = 0; i < nx; ++i) {
      int ie = i + 1 == nx ? 0 : i + 1, iw = i == 0 ? nx - 1 : i - 1;
      float tc = T[s.index(i, j)], te = T[s.index(ie, j)], tw = T[s.index(iw, j)];
      float tn = T[s.index(i, jn)], ts = T[s.index(i, js)];
      float ub = kappa * (te - tw) * inv2dx, vb = kappa * (tn - ts) * inv2dx;
      float speed = std::sqrt(ub * ub + vb * vb);
      float limit = speed > maxSpeed ? maxSpeed / speed : 1.0f;
      size_t c = s.index(i, j);
      s.windU[c] += ub * limit;
      s.windV[c] += vb * limit;
      // ∇·u_b = κ ∇²T′ (limited alike); w at the boundary-layer top = −h ∇·u_b.
      float laplacian = (te + tw + tn + ts - 4.0f * tc) * invDx2;
      s.lift[c] = -depth * kappa * limit * laplacian;
      // The deformation of u_b: κ times the second derivatives of T′.
      maxDeformation = std::max(maxDeformation, double(kappa * limit * invDx2) *
                                                    (std::fabs(te + tw - 2.0f * tc) + std::fabs(tn + ts - 2.0f * tc)));
    }
  }
  // The perturbation's deformation: Σ |amplitude| |k|.
  double turbulenceDeformation = 0.0;
  for (const Mode& m : modes_)
    turbulenceDeformation += p.turbulence_m_s * m.amplitude * 2.0 * std::numbers::pi *
                             std::hypot(m.kx / lx, m.ky / ly);
  return maxDeformation + turbulenceDeformation;
}

}  // namespace firmament::weather
