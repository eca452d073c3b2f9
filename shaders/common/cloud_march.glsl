// cloud_march.glsl: the view-march step schedule, shared by the GPU march and the C++ side (sample
// budgets, tests); compat.glsl rules.
//
// A step that grows with distance (level of detail). The base step is
//     h0 = H / N      (H: the thickest layer's thickness, m; N: the view steps),
// so a vertical ray through a layer takes about N steps. At distance t from the camera the step is
//     h(t) = h0 * clamp(t / D, 1, G)     (D = H: the growth starts one layer thickness away; G: cap),
// constant up to D, then proportional to t (a constant angle h/t = 1/N seen from the camera, like a
// pixel footprint), capped at G h0. Steps needed over a stretch [t0, t1] with D <= t0 < t1 <= G D:
//     n = ∫ dt / h(t) = (D / h0) ∫ dt / t = N ln(t1 / t0),
// so a horizon stretch from 20 to 80 km takes N ln 4 = 1.4 N steps where the uniform split of the old
// march (total length / N) took N steps of ~1.2 km each, and the nearest clouds get steps of H / N
// instead. Every step length is proportional to 1 / N, so the quadrature still converges as N grows.
// G = 1 gives the fixed base step everywhere.
#ifndef FIRMAMENT_CLOUD_MARCH_GLSL
#define FIRMAMENT_CLOUD_MARCH_GLSL

#include "common/compat.glsl"

SHARED_BEGIN

// h(t) in m for base step h0 (m), growth start D (m, > 0), cap G >= 1.
SHARED_INLINE Real cloudViewStep(Real t, Real h0, Real growthStart, Real maxFactor) {
  return h0 * clamp(t / growthStart, 1.0, max(maxFactor, 1.0));
}

// Longer steps where little of the light gets through (CloudMarchSettings::lowTransmittanceStepStart
// T1, lowTransmittanceStepMax K): a sample's light reaches the pixel weighted by the view ray's
// transmittance T in front of it, so once T < T1 the step is multiplied by
//     f(T) = clamp(T1 / T, 1, K),
// continuous in T (no seam). In a cloud of extinction sigma a step then moves T by
// dT = -T sigma h0 f = -sigma h0 T1 (until the cap): linear in T instead of geometric, so the stretch
// from T1 down to T1 / K takes (T1 - T1 / K) / (T1 sigma h0) steps and the rest to the early exit's T_e
// ln(T1 / (K T_e)) / (K sigma h0), instead of ln(T1 / T_e) / (sigma h0) in all: 0.98 against 2.3 for
// T1 = 0.1, K = 4, T_e = 0.01, while that stretch carries at most T1 - T_e of the pixel's light
// (docs/clouds.md "Longer steps behind dense cloud"). T1 <= 0: 1 (off).
SHARED_INLINE Real cloudLowTransmittanceStepFactor(Real transmittance, Real start, Real maxFactor) {
  if (!(start > 0.0)) return 1.0;
  return clamp(start / max(transmittance, Real(1e-6)), 1.0, max(maxFactor, 1.0));
}

SHARED_END

#endif  // FIRMAMENT_CLOUD_MARCH_GLSL
