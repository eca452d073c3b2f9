// scattering_lut.glsl: parametrizations of Bruneton 2017's precomputed tables ("Precomputed
// Atmospheric Scattering: a New Implementation", section "Single scattering: precomputation" and
// "Irradiance"), shared by the GPU passes and the CPU tests (rules in compat.glsl).
//
//   - the 4D scattering table S(r, mu, mu_s, nu), stored as a 3D texture with nu folded into x:
//     width = nu_size * mu_s_size, height = mu_size, depth = r_size;
//   - the 2D ground irradiance table E(r, mu_s).
//
// Notation as in atmosphere_lut.glsl: r = distance from the planet centre (m), mu = cos(view zenith),
// mu_s = cos(sun zenith), nu = cos(view-sun angle); R_b and R_t the bottom (ground) and top radii;
// H = sqrt(R_t^2 - R_b^2) the distance from the ground to the top along a horizontal ray from the
// ground; rho = sqrt(r^2 - R_b^2) the distance from r to the horizon (the tangent point on the ground).
#ifndef FIRMAMENT_SCATTERING_LUT_GLSL
#define FIRMAMENT_SCATTERING_LUT_GLSL

#include "common/atmosphere_lut.glsl"

SHARED_BEGIN

// Sizes of the 4D table, in samples per dimension (Bruneton's defaults 8, 32, 128, 32).
struct ScatteringTableSize {
  int nu;
  int mu_s;
  int mu;    // must be even: half for rays that hit the ground, half for rays that do not
  int r;
};

// A point in the 4D table: unit-range coordinates u_nu, u_mu_s, u_mu, u_r.
// (x = nu, y = mu_s, z = mu, w = r, the order in which they are folded into the 3D texture.)

SHARED_INLINE Real groundToTopHorizontalDistance(AtmosphereParameters atmosphere) {
  return sqrt(max((atmosphere.top_radius - atmosphere.bottom_radius) * (atmosphere.top_radius + atmosphere.bottom_radius), 0.0));
}

// Normalised distance to the top from the ground along a ray of sun zenith cosine mu_s:
//   a(mu_s) = (d(R_b, mu_s) - d_min) / (d_max - d_min),  d_min = R_t - R_b (straight up), d_max = H (horizontal).
// a is 0 for the zenith, 1 for the horizon and > 1 below it (the ray then leaves through the far side).
SHARED_INLINE Real normalisedSunDistance(AtmosphereParameters atmosphere, Real mu_s) {
  Real d = distanceToTopAtmosphereBoundary(atmosphere, atmosphere.bottom_radius, mu_s);
  Real d_min = atmosphere.top_radius - atmosphere.bottom_radius;
  Real d_max = groundToTopHorizontalDistance(atmosphere);
  return (d - d_min) / (d_max - d_min);
}

// (r, mu, mu_s, nu) -> unit coordinates. `hitsGround` must be rayIntersectsGround(r, mu) as the caller
// decided it, so that a lookup and the texel it reads agree on which half of the mu axis applies.
//
// r:    u_r = rho / H, through texel centres. rho grows like sqrt(altitude) near the ground, so texels
//       crowd there, where the density and the horizon angle change fastest.
// mu:   by the distance d to the boundary the ray ends on, not by mu itself, which concentrates texels
//       near the horizon. Rays that miss the ground end at the top: d in [d_min, d_max] with
//       d_min = R_t - r (straight up) and d_max = rho + H (grazing the ground: rho to the tangent point,
//       then H from there to the top). Rays that hit the ground end there: d in [d_min, d_max] with
//       d_min = r - R_b (straight down) and d_max = rho (grazing). Each family gets half of the axis:
//       ground rays [0, 0.5) with u = 0.5 - x/2, sky rays (0.5, 1] with u = 0.5 + x/2, x the normalised
//       distance. The two vertical directions meet in the middle and the horizon, where radiance jumps
//       between ground and sky, lies at the two ends; each half maps through its own texel centres, so
//       filtering never blends a ground ray with a sky ray.
// mu_s: x = max(1 - a/A, 0) / (1 + a), with a = normalisedSunDistance(mu_s) and A its value at mu_s_min:
//       x = 1 at the zenith, 0 at mu_s_min, and, with a in the denominator, more texels near the horizon
//       where the light changes fastest. Suns below mu_s_min clamp to x = 0.
// nu:   linear, (nu + 1) / 2, stored at nu_size exact samples (the x-fold, see scatteringTexelCoordinates).
SHARED_INLINE vec4 scatteringUvwzFromRMuMuSNu(AtmosphereParameters atmosphere, ScatteringTableSize size, Real r, Real mu,
                                             Real mu_s, Real nu, bool hitsGround) {
  Real H = groundToTopHorizontalDistance(atmosphere);
  Real rho = safeSqrt((r - atmosphere.bottom_radius) * (r + atmosphere.bottom_radius));
  Real u_r = textureCoordFromUnitRange(clamp(rho / H, 0.0, 1.0), size.r);

  Real u_mu;
  int half_mu = size.mu / 2;
  if (hitsGround) {
    Real d = distanceToBottomAtmosphereBoundary(r, mu, atmosphere.bottom_radius);
    Real d_min = r - atmosphere.bottom_radius;
    Real d_max = rho;
    Real x = d_max > d_min ? clamp((d - d_min) / (d_max - d_min), 0.0, 1.0) : 0.0;
    u_mu = 0.5 - 0.5 * textureCoordFromUnitRange(x, half_mu);
  } else {
    Real d = distanceToTopAtmosphereBoundary(atmosphere, r, mu);
    Real d_min = atmosphere.top_radius - r;
    Real d_max = rho + H;
    Real x = d_max > d_min ? clamp((d - d_min) / (d_max - d_min), 0.0, 1.0) : 0.0;
    u_mu = 0.5 + 0.5 * textureCoordFromUnitRange(x, half_mu);
  }

  Real a = normalisedSunDistance(atmosphere, mu_s);
  Real A = normalisedSunDistance(atmosphere, atmosphere.mu_s_min);
  Real x_mu_s = max(1.0 - a / A, 0.0) / (1.0 + a);
  Real u_mu_s = textureCoordFromUnitRange(x_mu_s, size.mu_s);

  Real u_nu = 0.5 * (clamp(nu, -1.0, 1.0) + 1.0);
  return vec4(u_nu, u_mu_s, u_mu, u_r);
}

// Inverse of scatteringUvwzFromRMuMuSNu: the (r, mu, mu_s, nu) of unit coordinates, and which half
// of the mu axis they lie on. nu is returned as stored; scatteringTexelParameters clamps it to what
// mu and mu_s allow.
SHARED_INLINE void rMuMuSNuFromScatteringUvwz(AtmosphereParameters atmosphere, ScatteringTableSize size, vec4 uvwz,
                                              OUT(Real) r, OUT(Real) mu, OUT(Real) mu_s, OUT(Real) nu,
                                              OUT(bool) hitsGround) {
  Real H = groundToTopHorizontalDistance(atmosphere);
  Real rho = H * unitRangeFromTextureCoord(uvwz.w, size.r);
  r = sqrt(rho * rho + atmosphere.bottom_radius * atmosphere.bottom_radius);

  int half_mu = size.mu / 2;
  if (uvwz.z < 0.5) {
    // Ground half: d = d_min + x (d_max - d_min); the ray from r meets the ground sphere after d,
    // so by the law of cosines R_b^2 = r^2 + d^2 + 2 r d mu, i.e. mu = -(rho^2 + d^2) / (2 r d).
    Real d_min = r - atmosphere.bottom_radius;
    Real d_max = rho;
    Real d = d_min + (d_max - d_min) * unitRangeFromTextureCoord(1.0 - 2.0 * uvwz.z, half_mu);
    mu = d == 0.0 ? -1.0 : clampCosine(-(rho * rho + d * d) / (2.0 * r * d));
    hitsGround = true;
  } else {
    // Sky half: R_t^2 = r^2 + d^2 + 2 r d mu with R_t^2 - r^2 = H^2 - rho^2.
    Real d_min = atmosphere.top_radius - r;
    Real d_max = rho + H;
    Real d = d_min + (d_max - d_min) * unitRangeFromTextureCoord(2.0 * uvwz.z - 1.0, half_mu);
    mu = d == 0.0 ? 1.0 : clampCosine((H * H - rho * rho - d * d) / (2.0 * r * d));
    hitsGround = false;
  }

  // x (1 + a) = 1 - a / A  =>  a = A (1 - x) / (1 + A x); then d from a, and mu_s by the law of
  // cosines at the ground: R_t^2 = R_b^2 + d^2 + 2 R_b d mu_s, i.e. mu_s = (H^2 - d^2) / (2 R_b d).
  Real x_mu_s = unitRangeFromTextureCoord(uvwz.y, size.mu_s);
  Real d_min = atmosphere.top_radius - atmosphere.bottom_radius;
  Real d_max = H;
  Real A = normalisedSunDistance(atmosphere, atmosphere.mu_s_min);
  Real a = A * (1.0 - x_mu_s) / (1.0 + A * x_mu_s);
  Real d = d_min + min(a, A) * (d_max - d_min);
  mu_s = d == 0.0 ? 1.0 : clampCosine((H * H - d * d) / (2.0 * atmosphere.bottom_radius * d));

  nu = clampCosine(2.0 * uvwz.x - 1.0);
}

// The x axis of the 3D texture holds nu_size slices of mu_s_size texels: x = i_nu * mu_s_size +
// i_mu_s. The mu_s, mu and r axes sample texel centres, (i + 0.5) / size; nu is sampled at exactly
// nu_size points from -1 to 1, u_nu = i_nu / (nu_size - 1), since a lookup blends two slices itself.
SHARED_INLINE vec4 scatteringUvwzFromTexel(ScatteringTableSize size, ivec3 texel) {
  int i_nu = texel.x / size.mu_s;
  int i_mu_s = texel.x - i_nu * size.mu_s;
  return vec4(Real(i_nu) / Real(max(size.nu - 1, 1)), (Real(i_mu_s) + 0.5) / Real(size.mu_s),
              (Real(texel.y) + 0.5) / Real(size.mu), (Real(texel.z) + 0.5) / Real(size.r));
}

// What a texel stores: its (r, mu, mu_s, nu), with nu clamped to the values that mu and mu_s allow
// (the view and the sun are both at their zenith angles, so nu = mu mu_s + sqrt((1 - mu^2)(1 - mu_s^2))
// cos(delta azimuth) lies within mu mu_s -+ sqrt((1 - mu^2)(1 - mu_s^2))).
SHARED_INLINE void scatteringTexelParameters(AtmosphereParameters atmosphere, ScatteringTableSize size, ivec3 texel,
                                             OUT(Real) r, OUT(Real) mu, OUT(Real) mu_s, OUT(Real) nu,
                                             OUT(bool) hitsGround) {
  rMuMuSNuFromScatteringUvwz(atmosphere, size, scatteringUvwzFromTexel(size, texel), r, mu, mu_s, nu, hitsGround);
  Real spread = safeSqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s));
  nu = clamp(nu, mu * mu_s - spread, mu * mu_s + spread);
}

// Ground irradiance table E(r, mu_s) (Bruneton 2017, "Irradiance"): linear in altitude and in mu_s
// over [-1, 1], through texel centres. It is smooth in both, so no remapping is needed.
SHARED_INLINE vec2 irradianceUvFromRMuS(AtmosphereParameters atmosphere, Real r, Real mu_s, ivec2 size) {
  Real x_r = (r - atmosphere.bottom_radius) / (atmosphere.top_radius - atmosphere.bottom_radius);
  Real x_mu_s = 0.5 * mu_s + 0.5;
  return vec2(textureCoordFromUnitRange(clamp(x_mu_s, 0.0, 1.0), size.x),
              textureCoordFromUnitRange(clamp(x_r, 0.0, 1.0), size.y));
}

SHARED_INLINE void rMuSFromIrradianceUv(AtmosphereParameters atmosphere, vec2 uv, ivec2 size, OUT(Real) r, OUT(Real) mu_s) {
  Real x_mu_s = unitRangeFromTextureCoord(uv.x, size.x);
  Real x_r = unitRangeFromTextureCoord(uv.y, size.y);
  r = atmosphere.bottom_radius + x_r * (atmosphere.top_radius - atmosphere.bottom_radius);
  mu_s = clampCosine(2.0 * x_mu_s - 1.0);
}

SHARED_END

#endif  // FIRMAMENT_SCATTERING_LUT_GLSL
