#pragma once
// Warm-rain microphysics in column form after Kessler (1969), with the column's cloud depth D = top − base
// turning paths into mixing ratios (r = W/(ρ D)):
//   autoconversion  A = k₁ max(0, W_c − ρ r_c0 min(D, 2 km)),  k₁ = 10⁻³ s⁻¹, r_c0 = 0.5 g/kg
//   accretion       K = 2.2 W_c r_r^0.875                      (Kessler's collection law)
// integrated as W_c ← W_c e^{−(A+K)Δt/W_c} so no step takes more than there is.
// Rain falls out with terminal speed V_t = 6 m/s from the cloud's mid height z_m (Kessler's mean fall
// speed): F = W_r (1 − e^{−Δt V_t / z_m}). On the way down a fraction f = min(0.9, ½ (1 − RH) z_base/km)
// evaporates into the boundary layer and cools it by L_v/(ρ c_p h) per kg/m², which makes the cold pool;
// the rest reaches the ground and leaves the domain. A trace too small to change the vapour path exactly
// (below half its ulp) does not evaporate but falls out, so the rate at the ground is never negative.
#include "weather/active_cells.h"
#include "weather/sounding.h"
#include "weather/weather_state.h"

namespace firmament::weather {

// Returns the water that reached the ground in this step (kg). `work` is scratch (the active cells).
double applyMicrophysics(WeatherState& state, const BoundaryLayer& layer, double dt_s, ColumnScratch& work);

}  // namespace firmament::weather
