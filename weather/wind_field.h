#pragma once
// The wind at cloud base: prevailing wind + a divergence-free perturbation + buoyancy-driven flow
// (storm outflow from rain-cooled air, inflow toward warm patches).
//
//   u = U₀ + (∂ψ/∂y, −∂ψ/∂x) + u_b,   u_b = κ ∇T′ limited to |u_b| ≤ c_max,
//
// ψ is a sum of seeded Fourier modes that tile the domain (so ∇·(∂ψ/∂y, −∂ψ/∂x) = 0 exactly) whose phases
// drift with periods of one to three hours. u_b is the surface flow of a density current, directed from
// cold to warm air: under a storm's cold pool it spreads out, and its convergence at the pool's edge
// (w = −h ∇·u_b, mass continuity through the boundary layer) lifts air there and triggers new cells.
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
  WindField(int nx, int ny, double cellSize_m, uint32_t seed);
  // Writes state.windU/V and the convergence part of state.lift; returns max |∂u_i/∂x_j| (s⁻¹), the
  // deformation the advection's sub-stepping needs.
  double update(WeatherState& state, const WindParameters& p, double t_s);

 private:
  struct Mode {
    int kx, ky;
    double amplitude;  // of the velocity, m/s per unit turbulence
    double phase, angularFrequency;
  };
  int nx_, ny_;
  double cellSize_;
  std::vector<Mode> modes_;
  std::vector<float> cosX_, sinX_, cosY_, sinY_;  // per mode, per column / row
};

}  // namespace firmament::weather
