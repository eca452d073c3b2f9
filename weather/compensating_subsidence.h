#pragma once
// Compensating subsidence. Updrafts carry mass up at σ w per unit area; the same mass sinks around
// them, spread by gravity waves over the surroundings within minutes (Bretherton & Smolarkiewicz 1989,
// JAS 46:740). Sinking at M through a free troposphere with potential-temperature lapse rate γ = Γ_d − Γ
// warms it at M γ. The warming δ(x) (K) of the environment above the mixed layer:
//     ∂δ/∂t = γ (G_L ∗ M)(x) − δ/τ,   τ = 1 h,
// where G_L ∗ M is the mass flux σ w smoothed over L ≈ 5 km (block means on a ≈ 1.6 km grid, then
// binomial passes to a Gaussian of σ ≈ 5 km; the smoothing keeps the domain mean, so the domain-wide
// warming is M̄ γ) and τ stands for the gravity waves carrying the anomaly further and the air that
// the wind brings in. Integrated exactly over a step with the mass flux held.
// Convection reads δ as a colder parcel (convection.h): the more convection nearby, the harder it is for
// a new cell to start there, which spaces storms apart; the domain-wide part is the quasi-equilibrium of
// Arakawa & Schubert (1974, JAS 31:674).
#include <cstdint>
#include <vector>

#include "weather/weather_state.h"

namespace firmament::weather {

class CompensatingSubsidence {
 public:
  static constexpr double kRelaxation_s = 3600.0;
  static constexpr double kBlock_m = 1600.0, kRadius_m = 5000.0;

  CompensatingSubsidence(int nx, int ny, double cellSize_m);
  // Advances δ with the state's updrafts (core fraction σ) and writes it per cell into `warming`.
  void apply(const WeatherState& state, double coreFraction, double freeLapseRate_K_m, double dt_s, Field& warming);
  double domainMean_K() const;

 private:
  int nx_, ny_, block_, cnx_, cny_, passes_;
  std::vector<float> flux_, scratch_, delta_;
  std::vector<int32_t> x0_, x1_, y0_, y1_;
  std::vector<float> wx_, wy_;
  std::vector<uint8_t> uniform_;  // per four columns: the same coarse neighbours
};

}  // namespace firmament::weather
