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

SHARED_END

#endif  // FIRMAMENT_CLOUD_MARCH_GLSL
