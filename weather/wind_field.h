#pragma once
// The wind at cloud base: prevailing wind + a divergence-free perturbation + buoyancy-driven flow
// (storm outflow from rain-cooled air, inflow toward warm patches).
//
//   u = U₀ + (∂ψ/∂y, −∂ψ/∂x) + u_b,   u_b = κ ∇T̃′ limited to |u_b| ≤ c_max,
//
// ψ is a sum of seeded Fourier modes that tile the domain (so ∇·(∂ψ/∂y, −∂ψ/∂x) = 0 exactly) whose phases
// drift with periods of one to three hours. u_b is the surface flow of a density current, directed from
// cold to warm air: under a storm's cold pool it spreads out, and its convergence at the pool's edge
// (w = −h ∇·u_b, mass continuity through the boundary layer) lifts air there and triggers new cells.
//
// Smoothing. u_b follows the pressure of the cold pool, which the hydrostatic and non-hydrostatic
// response spreads over about the layer depth, not the grid spacing. T̃′ is T′ averaged over blocks of
// ≈ 400 m and smoothed by a [1 2 1]² binomial filter twice (σ ≈ 450 m in all), u_b and the lift are
// computed on that coarse grid and interpolated back bilinearly. Besides being the physical scale of a
// gust front, this keeps grid-scale noise in T′ from driving grid-scale deformation, which would force
// short sub-steps (docs/weather.md, "Stability").
//
// Cache. The perturbation changes on its 1–3 h periods, so it is evaluated exactly at multiples of
// kPerturbationInterval_s (300 s) and interpolated linearly in time between two such snapshots. A
// rotating mode's linear interpolation shrinks it by at most 1 − cos(π Δt/P) = 3.4 % of its amplitude
// (P = 1 h, the fastest mode, mid-interval), i.e. ≤ 0.034 m/s at the default 1 m/s rms.
#include <cstdint>
#include <vector>

#include "weather/weather_state.h"

namespace firmament::weather {

struct WindParameters {
  double prevailingU_m_s = 0.0, prevailingV_m_s = 0.0;  // east, north
  double turbulence_m_s = 1.0;
  // κ: outflow speed per temperature gradient (m² s⁻¹ K⁻¹). With 1500, a 3 K cold pool with a 1 km edge
  // drives ≈ 4.5 m/s, the speed of a shallow density current c = √(g h ΔT/T) (Benjamin 1968).
  double buoyancyWind_m2_s_K = 1500.0;
  double maxBuoyancyWind_m_s = 15.0;
  double boundaryLayerDepth_m = 1000.0;
  uint32_t seed = 1;
};

class WindField {
 public:
  static constexpr double kPerturbationInterval_s = 300.0;
  static constexpr double kSmoothingBlock_m = 400.0;

  WindField(int nx, int ny, double cellSize_m, uint32_t seed);
  // Writes state.windU/V and the convergence part of state.lift; returns max |∂u_i/∂x_j| (s⁻¹), the
  // deformation the advection's sub-stepping needs.
  double update(WeatherState& state, const WindParameters& p, double t_s);
  // The block size (cells) of the coarse grid the buoyancy-driven flow is computed on.
  int smoothingFactor() const { return factor_; }

 private:
  struct Mode {
    int kx, ky;
    double amplitude;  // of the velocity, m/s per unit turbulence
    double phase, angularFrequency;
  };
  void perturbationSnapshot(double t_s, double turbulence_m_s, Field& u, Field& v) const;
  double buoyancyFlow(const WeatherState& s, const WindParameters& p);

  int nx_, ny_;
  double cellSize_;
  std::vector<Mode> modes_;
  std::vector<float> cosX_, sinX_, cosY_, sinY_;  // per mode, per column / row
  // Two exact snapshots of the perturbation, at snapshotIndex_ and snapshotIndex_ + 1 intervals.
  long long snapshotIndex_ = -1;
  double snapshotTurbulence_ = -1.0;
  Field snapU_[2], snapV_[2];
  // Coarse grid of the buoyancy-driven flow.
  int factor_ = 1, cnx_ = 0, cny_ = 0;
  Field coarseT_, scratch_, coarseU_, coarseV_, coarseLift_;
  std::vector<int32_t> x0_, x1_, y0_, y1_;    // per fine column / row: coarse neighbours
  std::vector<float> wx_, wy_;                // and the weight of the second
  std::vector<float> padded_;                 // a coarse row with its periodic neighbours (update)
  std::vector<float> rowU_, rowV_, rowLift_;  // a fine row's coarse values (update)
};

}  // namespace firmament::weather
