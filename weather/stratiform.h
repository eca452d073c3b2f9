#pragma once
// Large-scale lifting and grid-scale condensation: stratus, overcast and frontal cloud.
//   w_ls(x, t) = w₀ + w_f exp(−(d/σ_f)²)
// with d the distance across a frontal band that moves with the prevailing wind. Lifting cools the layer
// adiabatically, dT′/dt = −Γ_d w_ls. The layer's top (at h) is saturated when the vapour path exceeds
//   W_sat = ρ h r_s(T_ref + T′ − Γ_d h, p(h)),
// and then the excess condenses, relaxing with τ_c = 300 s (a saturation adjustment), releasing latent
// heat L_v/(ρ c_p h) per kg/m². The stratiform top is h plus the depth the ascent lifts moist air
// through, h + min(8 km, w_ls · 10⁵ s) (a parameterisation: 0.01 m/s → 1 km deck, 0.08 m/s → deep
// nimbostratus).
// Cloud water evaporates by mixing with unsaturated air, E = W_c (1 − e^{−Δt/τ_e}) (1 − RH), τ_e = 600 s:
// convective cloud mixes with the free troposphere (RH_ft), stratiform cloud with the layer itself
// (and only while the layer top is unsaturated); the evaporated water returns to the vapour path.
#include "weather/active_cells.h"
#include "weather/sounding.h"
#include "weather/weather_state.h"

namespace firmament::weather {

struct StratiformParameters {
  double largeScaleLift_m_s = 0.0;
  double frontLift_m_s = 0.0;
  double frontWidth_m = 15000.0;
  double frontPosition_m = 0.0;                         // along the wind direction, from the domain's west/south corner
  double frontDirectionX = 1.0, frontDirectionY = 0.0;  // unit vector the front moves toward
  double freeTroposphereRH = 0.5;
};

// `work` is scratch (the ascent per cell, the cells with work).
void applyStratiform(WeatherState& state, const BoundaryLayer& layer, const StratiformParameters& p, double dt_s,
                     ColumnScratch& work);

}  // namespace firmament::weather
