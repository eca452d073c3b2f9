// cloud_shadow.glsl: the Beer shadow map (BSM; Hillaire 2016, "Physically based sky, atmosphere and
// cloud rendering in Frostbite"), shared by its bake, the cloud light march and (later) terrain
// shading; compat.glsl rules. docs/clouds.md, "Beer shadow map".
//
// An orthographic grid seen from the sun: a square of side `extent` (m) centred on C in the plane
// spanned by the unit axes u, v (both perpendicular to the sun direction s). The texel at (a, b) in
// [0, 1]^2 marches the sun ray that enters at S = C + (a - 1/2) extent u + (b - 1/2) extent v + L s
// (L: far enough above every layer) and runs along -s; a point p has the depth
//     d(p) = L - (p - C) . s      (m from the start plane, along -s)
// and the grid coordinates a = (p - C) . u / extent + 1/2, b = (p - C) . v / extent + 1/2.
// Per texel three numbers along the ray through all layers: the front depth d_f (the first cloud),
// the mean extinction sigma_bar = tau_max / (d_b - d_f) over [d_f, d_b] (d_b: the last cloud) and the
// total optical depth tau_max. The optical depth between p and the sun is then
//     tau(p) = min(sigma_bar max(d(p) - d_f, 0), tau_max),
// exact for one homogeneous slab; with gaps or varying density the optical depth is spread evenly
// between the first and the last cloud (the map's stated approximation). Terrain will read the same
// map for cloud shadows on the ground (there d(p) > d_b, so tau = tau_max).
#ifndef FIRMAMENT_CLOUD_SHADOW_GLSL
#define FIRMAMENT_CLOUD_SHADOW_GLSL

#include "common/compat.glsl"

SHARED_BEGIN

// (a, b, depth) of p; centre, axes, sun in the cloud frame; extent and start distance L in m.
SHARED_INLINE vec3 cloudShadowCoordinate(vec3 p, vec3 centre, vec3 u, vec3 v, vec3 sun, Real extent, Real start) {
  vec3 q = p - centre;
  return vec3(dot(q, u) / extent + 0.5, dot(q, v) / extent + 0.5, start - dot(q, sun));
}

// Whether the map knows p's way to the sun: p lies on the square (a, b in [0, 1]) and not sunward of
// its start plane (depth >= 0). The march from the start plane crosses every layer (it runs 2 L, past
// the lowest base for any sun above the horizon), so points past its end take tau_max; but a point
// sunward of the plane — kilometres towards a low sun, where the view reaches — has clouds on its way
// that no texel marched (taking tau = 0 there made a sunset's far clouds ~6x too bright).
SHARED_INLINE bool cloudShadowCovers(vec3 coordinate) {
  return coordinate.x >= 0.0 && coordinate.x <= 1.0 && coordinate.y >= 0.0 && coordinate.y <= 1.0 && coordinate.z >= 0.0;
}

// tau(p) from a texel (d_f, sigma_bar, tau_max, unused).
SHARED_INLINE Real cloudShadowOpticalDepth(vec4 bsm, Real depth) {
  return min(bsm.y * max(depth - bsm.x, 0.0), bsm.z);
}

SHARED_END

#endif  // FIRMAMENT_CLOUD_SHADOW_GLSL
