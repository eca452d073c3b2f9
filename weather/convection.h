#pragma once
// Moist convection: the trigger, the updraft, the cloud top and convective condensation.
//
// Trigger. A thermal rises with the Deardorff (1970) convective velocity w* = (g h H/(ρ c_p T))^{1/3}
// plus the ascent from convergence and large-scale lifting, w_l. It reaches free convection when its
// kinetic energy pays the inhibition and the parcel has buoyancy to spend:
//     ½ (w* + max(0, w_l) + w)² ≥ CIN  and  CAPE > 0          (CIN, CAPE from the ParcelTable)
// (the existing updraft w keeps a running cell going). Without heating there is no w*, so a capped layer
// stays clear; a warm anomaly lowers CIN and raises CAPE. Cold outflow (T′ < 0) raises CIN: no new
// cells under a storm, while its edge's convergence lifts air and triggers new ones.
//
// Updraft. Relaxes with τ_w = 600 s toward the parcel-theory value reduced by entrainment and loading,
// w_target = ½ √(2 CAPE) (observed cores reach about half the parcel value; Markowski & Richardson 2010
// §7.1), and back to zero when not triggered.
//
// Cloud base and top. Base: the LCL (Espy). The top rises at the updraft speed toward the level of
// neutral buoyancy plus overshoot w/N (N = 0.02 s⁻¹, the stratosphere's buoyancy frequency), capped at
// the tropopause + 2 km: cumulus → congestus → cumulonimbus as the cell matures.
//
// Condensation. A core covering σ = 0.1 of the cell carries boundary-layer air at ρ σ w; above the top
// it keeps only the saturation mixing ratio there (r_s at T_top = T_LCL − 6 K/km · (top − LCL), a mean
// moist lapse rate), so the condensation rate is  C = (σ w / h) (W_v − ρ h r_s(T_top)), integrated
// exactly over the step. The same exchange ventilates the layer's warm anomaly, dT′/dt = −(σ w/h) T′.
#include "weather/parcel_table.h"
#include "weather/sounding.h"
#include "weather/weather_state.h"

namespace firmament::weather {

struct ConvectionParameters {
  double tropopause_m = 11000.0;
};

void applyConvection(WeatherState& state, const ParcelTable& table, const BoundaryLayer& layer,
                     const ConvectionParameters& p, double dt_s);

}  // namespace firmament::weather
