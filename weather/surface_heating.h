#pragma once
// Surface heating of the boundary layer, shaded by cloud, with night cooling and exchange with the
// surroundings. Per cell:
//   R = S₀ max(0, sin e) · m(x,y) · T_c − L↑ (1 − c)            net radiation at the ground (W/m²)
//   H = R β/(1+β), E = R/((1+β) L_v) for R > 0;  H = R, E = 0 at night (no dew)
//   dT′/dt = H/(ρ c_p h) − T′/τ_T,     dW_v/dt = E − (W_v − W_bg)/τ_q
// S₀: absorbed solar flux for a zenith sun (preset × heating_scale); m: the heating map (land/water,
// heterogeneity; mean 1); β: Bowen ratio; L↑ = 70 W/m², net clear-sky longwave loss (Stull 1988 §7.3
// gives 50–100 W/m²); c: cloud cover. Cloud transmission is the two-stream result for a conservative
// scatterer, T_c = 1/(1 + ¾(1−g)τ) (Bohren 1987, Am. J. Phys. 55:524), with g = 0.85 and the optical
// depth of liquid water τ = 3 LWP/(2 ρ_w r_e), r_e = 10 µm (Stephens 1978, JAS 35:2123). The relaxations
// stand for entrainment and large-scale advection (τ = 6 h); the vapour exchange is booked as water
// entering or leaving the domain.
#include <algorithm>

#include "weather/fast_math.h"
#include "weather/physical_constants.h"
#include "weather/sounding.h"
#include "weather/weather_state.h"

namespace firmament::weather {

struct SurfaceHeatingParameters {
  double sunElevation_rad = 0.0;
  double absorbedSolar_W_m2 = 650.0;
  double bowenRatio = 0.6;
  double longwaveCooling_W_m2 = 70.0;
  double temperatureRelaxation_s = 6.0 * 3600.0;
  double vapourRelaxation_s = 6.0 * 3600.0;
  double backgroundVapour_kg_m2 = 10.0;
  bool exchangeWithSurroundings = true;
};

// Cloud cover from liquid water path: c = 1 − exp(−LWP / 0.05 kg m⁻²) (τ ≈ 7.5 at the e-folding path).
inline constexpr float kCoverPerWater = 20.0f;  // 1 / (0.05 kg m⁻²)
inline float cloudCover(float w) { return oneMinusExpFast(std::max(w, 0.0f) * kCoverPerWater); }
// Two-stream transmission of a cloud of this liquid water path.
inline float cloudTransmission(float w) {
  constexpr float kAsymmetry = 0.85f, kEffectiveRadius = 10e-6f;
  constexpr float kOpticalDepthPerWater = float(1.5 / (kWaterDensity * double(kEffectiveRadius)));  // 3/(2 ρ_w r_e)
  float tau = kOpticalDepthPerWater * std::max(w, 0.0f);
  return 1.0f / (1.0f + 0.75f * (1.0f - kAsymmetry) * tau);
}

// Returns the water that entered the domain in this step (kg; negative when it left); sets the state's
// domain-mean sensible heat flux (the mixed layer's growth integrates it).
double applySurfaceHeating(WeatherState& state, const Field& heatingMap, const BoundaryLayer& layer,
                           const SurfaceHeatingParameters& p, double dt_s);

}  // namespace firmament::weather
