#pragma once
// The daytime growth of the mixed layer, its exchange with the free troposphere and its collapse at
// night.
//
// Growth. A mixed layer heated from below at H (W/m²) entrains the stable air above it at the rate of
// encroachment with entrainment (Tennekes 1973, JAS 30:558; Stull 1988 §11.2):
//     w_e = (1 + 2A) H̄ / (ρ c_p γ h),
// A = 0.2 the entrainment ratio (the entrainment heat flux at the top is −A times the surface flux),
// γ = Γ_d − Γ the potential-temperature lapse rate of the free troposphere above the layer, H̄ the
// domain-mean sensible heat flux. Without a limit, dh/dt = w_e, i.e. h² = h₀² + 2(1 + 2A) ∫H̄ dt/(ρ c_p γ)
// from the preset's depth h₀ (now the depth before sunrise). The layer stays below the preset's stable
// layer (less 300 m) and 3 km, and its overshooting thermals stay below the domain-mean lifting
// condensation level: h ≤ LCL̄/1.2, thermals reaching the top of the entrainment zone at ≈ 1.2 h (Stull
// 1988 §11.1: the entrainment zone spans ≈ 0.8–1.2 h). Where the layer reaches its condensation level it
// becomes the sub-cloud layer of a cumulus layer (Betts 1973, QJRMS 99:178; Stull 1985, JCAM 24:49).
// There, and under a ceiling, the layer keeps entraining at w_e but sends as much air up into the
// clouds and the free troposphere, so its depth holds while its air is exchanged.
//
// The layer's contents. Over a step the layer entrains a depth Δh_e = w_e Δt of free-tropospheric air
// with r_ft = RH_ft · r_s just above the inversion. Of it, Δh = min(Δh_e, ceiling − h) deepens the layer:
// the vapour ρ Δh r_ft joins every column. The rest, Δh_v = Δh_e − Δh, replaces layer air:
// W_v ← W_v (1 − Δh_v/h) + ρ Δh_v r_ft, the entrainment drying that balances surface evaporation on a
// fair day. T′ is left alone: it is the anomaly against the layer's reference, and the sounding is
// anchored to the layer (sounding.h), so the warming that entrainment brings moves the reference with
// the layer top rather than the anomaly.
// Collapse. Once H̄ ≤ 0 (evening), turbulence decays within about an hour and the layer's upper part is
// left behind as the residual layer (Stull 1988 §1.1; Nieuwstadt & Brost 1986, JAS 43:532): h relaxes to
// h₀ with τ = 1 h, W_v ← W_v h_new/h_old (the mixing ratio is kept), T′ unchanged.
// All of these exchange water with the surroundings and are booked as such; with exchange off (a closed
// box) the depth stays h₀ and nothing is exchanged.
#include "weather/weather_state.h"

namespace firmament::weather {

struct LayerGrowthParameters {
  double morningDepth_m = 800.0;      // h₀
  double freeLapseRate_K_m = 6.5e-3;  // Γ of the free troposphere
  double stableLayerBase_m = 11000.0;
  double density_kg_m3 = 1.15;          // ρ of the layer
  double entrainedMixingRatio = 0.004;  // r_ft (kg/kg)
  bool exchangeWithSurroundings = true;
};

inline constexpr double kEntrainmentRatio = 0.2;        // A (Stull 1988 §11.2)
inline constexpr double kLayerCollapseTime_s = 3600.0;  // τ of the evening collapse
inline constexpr double kMaxLayerDepth_m = 3000.0;
inline constexpr double kThermalOvershoot = 1.2;  // thermal tops / h

// The highest the layer may grow for a domain-mean condensation level `lcl_m` (m).
double mixedLayerCeiling(double lcl_m, const LayerGrowthParameters& p);

// Moves the layer over dt with the state's last domain-mean sensible flux (entraining, venting or
// leaving behind water; diluting T′) and returns the water that entered the domain (kg; negative when
// it left).
double applyLayerGrowth(WeatherState& state, const LayerGrowthParameters& p, double dt_s);

}  // namespace firmament::weather
