// terrain_sky_visibility.glsl: the share of the sky a ground point sees past the terrain, from its
// horizon (terrain/horizon_map.h). Shared with C++ (double) by the rules of compat.glsl: the GPU
// shading (shaders/terrain/cast_terrain.comp) and the tests call the same function.
//
// The sky light on a Lambertian surface of normal n is E = ∫ L(ω) max(n·ω, 0) dω over the directions the
// terrain leaves open. With an isotropic sky L it is L π V, V the cosine-weighted visible share
//   V = (1/π) ∫∫ max(n·ω, 0) cos e de dφ   over e from the horizon α(φ) to π/2,
// ω = cos e h(φ) + sin e z (h the horizontal unit vector of azimuth φ, z up), cos e de dφ the solid
// angle. In azimuth φ, with c = n·h(φ) and n_z = n·z, n·ω = c cos e + n_z sin e, and
//   ∫_α^{π/2} (c cos²e + n_z sin e cos e) de = c ((π/2 − α)/2 − sin 2α / 4) + n_z cos²α / 2,
// valid where n·ω ≥ 0 on the whole range: α is raised to the surface's own elevation along φ,
// atan2(−c, n_z), below which n·ω < 0 (the slice integral of Jimenez et al. 2016, "Practical
// real-time strategies for accurate indirect occlusion", for a horizontal slice). A horizontal
// surface under horizons α_k in A equal sectors: V = ⟨cos²α_k⟩; an open plain: V = 1; a tilted plane
// with nothing above its own tangent plane: V = 1; with the horizon at 0 all round: (1 + n_z)/2 (the
// isotropic tilt factor), up to the sectors' midpoint rule.
// Closed forms the tests hold this to: a horizontal point at the foot of an infinite straight cliff
// whose top it sees at elevation α straight ahead (horizon atan(tan α cos φ) on the cliff's side, 0 on
// the other) sees V = (1 + cos α)/2; at the bottom of a V-shaped valley of flank angle α, V = cos α
// (both from (1/2π) ∫ dφ / (1 + a² cos²φ) = 1/√(1 + a²) over a full turn).
#ifndef FIRMAMENT_TERRAIN_SKY_VISIBILITY_GLSL
#define FIRMAMENT_TERRAIN_SKY_VISIBILITY_GLSL

#include "common/compat.glsl"

SHARED_BEGIN

// The slice's integral ∫ max(n·ω, 0) cos e de from the horizon elevation to the zenith, for the slice's
// c = n·h(φ) and n_z = n·z (n_z ≥ 0).
SHARED_INLINE Real terrainSkySlice(Real horizon, Real c, Real nz) {
  Real alpha = clamp(max(horizon, atan(-c, max(nz, 1.0e-6))), -0.5 * kPi, 0.5 * kPi);
  Real cosine = cos(alpha);
  return c * (0.5 * (0.5 * kPi - alpha) - 0.25 * sin(2.0 * alpha)) + nz * 0.5 * cosine * cosine;
}

SHARED_END

#endif  // FIRMAMENT_TERRAIN_SKY_VISIBILITY_GLSL
