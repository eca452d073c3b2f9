#pragma once
// Moist convection: the trigger, the updraft, the cloud top and convective condensation.
//
// Trigger. A thermal rises with the Deardorff (1970) convective velocity w* = (g h H/(ρ c_p T))^{1/3}
// plus the ascent from convergence and large-scale lifting, w_l. It reaches free convection when its
// kinetic energy pays the inhibition and the parcel has buoyancy to spend:
//     ½ (w* + max(0, w_l) + w)² ≥ CIN  and  CAPE > 0          (CIN, CAPE from the ParcelTable)
// (the existing updraft w keeps a running cell going). Without heating there is no w*, so a capped layer
// stays clear; a warm anomaly lowers CIN and raises CAPE.
//
// Cold pools. Rain-cooled outflow (T′ < 0) raises CIN and lowers CAPE through the parcel table, and it
// also cuts a running cell off from its warm inflow: the updraft's own contribution to the thermal is
// scaled by s = clamp(1 + (T′ − T̄′)/ΔT_c, 0, 1), ΔT_c = 1 K, T̄′ the domain mean, so a cell whose inflow
// air is a kelvin colder than its surroundings must pay the cold air's CIN with w* and lift alone. That is how a single
// cell dies once its outflow undercuts it (Byers & Braham 1949; Weisman & Klemp 1982: the gust front outruns the
// updraft when shear is weak), while the convergence at the pool's edge (lift, wind_field.h) triggers
// new cells there.
//
// Compensating subsidence. The parcel table is looked up at T′ − δ(x), δ the warming of the environment
// above the mixed layer by the subsidence around nearby updrafts (compensating_subsidence.h): for the
// parcel's buoyancy a warmer free troposphere is a colder parcel. This is the negative feedback that
// keeps convection from starting everywhere at once and spaces cells apart.
//
// Updraft. Relaxes with τ_w = 600 s toward the parcel-theory value reduced by entrainment and loading,
// w_target = ½ √(2 CAPE) (observed cores reach about half the parcel value; Markowski & Richardson 2010
// §7.1), and back to zero when not triggered.
//
// Cloud base and top. Base: the LCL (Espy). The top rises at the updraft speed toward the level of
// neutral buoyancy plus overshoot w/N (N = 0.02 s⁻¹, the stratosphere's buoyancy frequency), capped at
// the tropopause + 2 km: cumulus → congestus → cumulonimbus as the cell matures.
//
// Inflow. The updraft draws its boundary-layer air from a catchment of kilometres, far larger than a
// cell: a fraction φ = 0.9 of the vapour it condenses is taken from the domain's vapour (returned as
// `drawnVapour` and removed by the model's next mass fix, spread over all cells in proportion), the rest
// from the cell itself. Without it a cell could rain out only its own column (≈ 10 mm) and storms
// would starve before their outflow forms; with it they are fed by the surrounding layer, as the
// convergence under real storms feeds them (Markowski & Richardson 2010 §7.2, moisture convergence).
//
// Condensation. A core covering σ = 0.1 of the cell carries boundary-layer air at ρ σ w; above the top
// it keeps only the saturation mixing ratio there (r_s at T_top = T_LCL − 6 K/km · (top − LCL), a mean
// moist lapse rate), so the condensation rate is  C = (σ w / h) (W_v − ρ h r_s(T_top)), integrated
// exactly over the step. The same exchange ventilates the layer's warm anomaly toward its surroundings,
// dT′/dt = −(σ w/h)(T′ − T̄′) where T′ > T̄′.
#include "weather/active_cells.h"
#include "weather/parcel_table.h"
#include "weather/sounding.h"
#include "weather/weather_state.h"

namespace firmament::weather {

struct ConvectionParameters {
  double tropopause_m = 11000.0;
  const Field* subsidenceWarming_K = nullptr;  // δ per cell (none: 0)
  double coldPoolCutoff_K = 1.0;               // ΔT_c
  double inflowFraction = 0.9;                 // φ
};

struct ConvectionResult {
  double massFlux_m_s = 0.0;  // domain-mean σ w̄
  double drawnVapour = 0.0;   // Σ over cells (kg/m²) of vapour condensed from the catchment
};

// `work` is scratch (the cells with an updraft or a chance to trigger).
ConvectionResult applyConvection(WeatherState& state, const ParcelTable& table, const BoundaryLayer& layer,
                                 const ConvectionParameters& p, double dt_s, ColumnScratch& work);

}  // namespace firmament::weather
