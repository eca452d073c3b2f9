// atmosphere_lut.glsl: ray geometry in the spherical atmosphere and the parametrizations of the
// lookup tables, shared by the GPU passes, the CPU reference and the tests (see compat.glsl).
// Formulas follow Bruneton 2017 ("Precomputed Atmospheric Scattering: a New Implementation"); the
// numerically stable sphere intersections are in common/geometry.glsl.
//
// Notation: r = distance from the planet centre (m); mu = cosine of the view zenith angle at r;
// mu_s = cosine of the sun zenith angle; nu = cosine of the view-sun angle.
#ifndef FIRMAMENT_ATMOSPHERE_LUT_GLSL
#define FIRMAMENT_ATMOSPHERE_LUT_GLSL

#include "common/atmosphere_medium.glsl"
#include "common/geometry.glsl"

SHARED_BEGIN

SHARED_INLINE Real safeSqrt(Real a) { return sqrt(max(a, 0.0)); }
SHARED_INLINE Real clampCosine(Real mu) { return clamp(mu, -1.0, 1.0); }

SHARED_INLINE Real distanceToTopAtmosphereBoundary(AtmosphereParameters atmosphere, Real r, Real mu) {
  return distanceToTopAtmosphereBoundary(r, mu, atmosphere.top_radius);
}

SHARED_INLINE Real distanceToBottomAtmosphereBoundary(AtmosphereParameters atmosphere, Real r, Real mu) {
  return distanceToBottomAtmosphereBoundary(r, mu, atmosphere.bottom_radius);
}

SHARED_INLINE bool rayIntersectsGround(AtmosphereParameters atmosphere, Real r, Real mu) {
  return rayIntersectsGround(r, mu, atmosphere.bottom_radius);
}

// Distance to the nearest atmosphere boundary along (r, mu): the ground if the ray hits it, else the
// top. Bruneton's DistanceToNearestAtmosphereBoundary.
SHARED_INLINE Real distanceToNearestAtmosphereBoundary(AtmosphereParameters atmosphere, Real r, Real mu) {
  return rayIntersectsGround(atmosphere, r, mu) ? distanceToBottomAtmosphereBoundary(atmosphere, r, mu)
                                                : distanceToTopAtmosphereBoundary(atmosphere, r, mu);
}

// Radius and cosine after travelling d along (r, mu): r_d = sqrt(d^2 + 2 r mu d + r^2),
// mu_d = (r mu + d) / r_d (law of cosines).
SHARED_INLINE Real radiusAfter(Real r, Real mu, Real d) {
  return sqrt(max(d * d + 2.0 * r * mu * d + r * r, 0.0));
}

// Optical depth (sigma_t integrated, dimensionless per wavelength) from (r, mu) to the top of the
// atmosphere, by the trapezoidal rule with `steps` intervals (the transmittance LUT's integrator;
// the reference uses its own adaptive quadrature).
SHARED_INLINE vec3 opticalDepthToTop(AtmosphereParameters atmosphere, Real r, Real mu, int steps) {
  Real d = distanceToTopAtmosphereBoundary(atmosphere, r, mu);
  Real dx = d / Real(steps);
  vec3 sum = vec3(0.0);
  for (int i = 0; i <= steps; ++i) {
    Real di = Real(i) * dx;
    Real ri = radiusAfter(r, mu, di);
    Real weight = (i == 0 || i == steps) ? 0.5 : 1.0;
    sum += extinctionAt(atmosphere, ri) * weight;
  }
  return sum * dx;
}

// Texture coordinate of the centre of the first/last texel for x in [0, 1] (Bruneton
// GetTextureCoordFromUnitRange): keeps lookups off the clamped border.
SHARED_INLINE Real textureCoordFromUnitRange(Real x, int size) {
  return 0.5 / Real(size) + x * (1.0 - 1.0 / Real(size));
}

SHARED_INLINE Real unitRangeFromTextureCoord(Real u, int size) {
  return (u - 0.5 / Real(size)) / (1.0 - 1.0 / Real(size));
}

// Transmittance LUT parametrization (Bruneton 2017, section "Transmittance: precomputation"):
//   x_r  = rho / H,  rho = sqrt(r^2 - r_bottom^2),  H = sqrt(r_top^2 - r_bottom^2)
//   x_mu = (d - d_min) / (d_max - d_min),  d = distance to the top,  d_min = r_top - r,  d_max = rho + H
// which spends texels near the horizon where transmittance changes fastest.
SHARED_INLINE vec2 transmittanceUvFromRMu(AtmosphereParameters atmosphere, Real r, Real mu, ivec2 size) {
  Real H = sqrt(max(atmosphere.top_radius * atmosphere.top_radius - atmosphere.bottom_radius * atmosphere.bottom_radius, 0.0));
  Real rho = safeSqrt((r - atmosphere.bottom_radius) * (r + atmosphere.bottom_radius));
  Real d = distanceToTopAtmosphereBoundary(atmosphere, r, mu);
  Real d_min = atmosphere.top_radius - r;
  Real d_max = rho + H;
  Real x_mu = d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0;
  Real x_r = H > 0.0 ? rho / H : 0.0;
  return vec2(textureCoordFromUnitRange(clamp(x_mu, 0.0, 1.0), size.x),
              textureCoordFromUnitRange(clamp(x_r, 0.0, 1.0), size.y));
}

// Inverse of transmittanceUvFromRMu: the (r, mu) a texel stores.
SHARED_INLINE void rMuFromTransmittanceUv(AtmosphereParameters atmosphere, vec2 uv, ivec2 size, OUT(Real) r, OUT(Real) mu) {
  Real x_mu = unitRangeFromTextureCoord(uv.x, size.x);
  Real x_r = unitRangeFromTextureCoord(uv.y, size.y);
  Real H = sqrt(max(atmosphere.top_radius * atmosphere.top_radius - atmosphere.bottom_radius * atmosphere.bottom_radius, 0.0));
  Real rho = H * x_r;
  r = sqrt(rho * rho + atmosphere.bottom_radius * atmosphere.bottom_radius);
  Real d_min = atmosphere.top_radius - r;
  Real d_max = rho + H;
  Real d = d_min + x_mu * (d_max - d_min);
  // law of cosines on the triangle (centre, point, exit point): r_top^2 = r^2 + d^2 + 2 r d mu
  mu = d == 0.0 ? 1.0 : (H * H - rho * rho - d * d) / (2.0 * r * d);
  mu = clampCosine(mu);
}

// Multiple-scattering LUT parametrization (Hillaire 2020, section 5.5): u = mu_s mapped from [-1, 1],
// v = altitude fraction in [0, 1], both through texel centres.
SHARED_INLINE vec2 multipleScatteringUv(AtmosphereParameters atmosphere, Real r, Real mu_s, ivec2 size) {
  Real x_mu_s = 0.5 + 0.5 * mu_s;
  Real x_h = (r - atmosphere.bottom_radius) / (atmosphere.top_radius - atmosphere.bottom_radius);
  return vec2(textureCoordFromUnitRange(clamp(x_mu_s, 0.0, 1.0), size.x),
              textureCoordFromUnitRange(clamp(x_h, 0.0, 1.0), size.y));
}

SHARED_INLINE void rMuSFromMultipleScatteringUv(AtmosphereParameters atmosphere, vec2 uv, ivec2 size, OUT(Real) r, OUT(Real) mu_s) {
  Real x_mu_s = clamp(unitRangeFromTextureCoord(uv.x, size.x), 0.0, 1.0);
  Real x_h = clamp(unitRangeFromTextureCoord(uv.y, size.y), 0.0, 1.0);
  mu_s = 2.0 * x_mu_s - 1.0;
  r = atmosphere.bottom_radius + x_h * (atmosphere.top_radius - atmosphere.bottom_radius);
}


// The anisotropy of the multiple-scattering field (atmosphere/multiple_scattering_lut.glsl): real
// spherical harmonics of l = 1, 2 that survive the field's mirror symmetry about the plane of the
// zenith and the sun, in the local frame (z up, y towards the sun's azimuth, x across), w a unit
// direction in it. Normalised: ∫ Y_h^2 dw = 1.
#define kAnisotropyTerms 5
#define kAnisotropyTiles 4  // RGBA tiles that hold the five RGB coefficients (atmosphere/atmosphere_sampling.glsl)
SHARED_INLINE Real anisotropyHarmonic(int h, vec3 w) {
  if (h == 0) return 0.4886025119 * w.y;                        // Y_1,-1
  if (h == 1) return 0.4886025119 * w.z;                        // Y_1,0
  if (h == 2) return 1.0925484306 * w.y * w.z;                  // Y_2,-1
  if (h == 3) return 0.3153915653 * (3.0 * w.z * w.z - 1.0);    // Y_2,0
  return 0.5462742153 * (w.x * w.x - w.y * w.y);                // Y_2,2
}

// Legendre moments a_1, a_2 (a_l = 2 pi ∫ p(mu) P_l(mu) dmu) of the Rayleigh phase: 0 and 1/10.
#define kRayleighPhaseMoment2 0.1

// Sky-view LUT parametrization (after Hillaire 2020, section 5.3): for a camera at radius r, a view
// direction is given by its zenith angle theta and its azimuth phi relative to the sun (0..pi, the
// sky is symmetric about the sun's vertical plane). v puts the horizon (theta_h, the tangent to the
// ground, pi - asin(r_ground / r)) at exactly 0.5 and packs texels towards it with a square root on
// each side, where the sky changes fastest; u = sin(phi / 2) = sqrt((1 - cos phi) / 2) spends more
// texels near the sun's azimuth (du/dphi = 1/2 there against 1/pi for u = phi/pi), where the aerosol
// glow is, fewer towards the anti-sun, and needs a square root per pixel instead of an acos.
SHARED_INLINE Real horizonZenithAngle(AtmosphereParameters atmosphere, Real r) {
  return kPi - asin(clamp(atmosphere.bottom_radius / max(r, atmosphere.bottom_radius), 0.0, 1.0));
}

SHARED_INLINE vec2 skyViewUvFromAngles(AtmosphereParameters atmosphere, Real r, Real theta, Real cos_phi) {
  Real theta_h = horizonZenithAngle(atmosphere, r);
  Real v;
  if (theta < theta_h) {
    Real x = clamp(1.0 - theta / theta_h, 0.0, 1.0);  // 0 at the horizon, 1 at the zenith
    v = 0.5 + 0.5 * sqrt(x);
  } else {
    Real x = clamp((theta - theta_h) / max(kPi - theta_h, 1e-6), 0.0, 1.0);  // 0 at the horizon, 1 at the nadir
    v = 0.5 - 0.5 * sqrt(x);
  }
  return vec2(sqrt(clamp(0.5 - 0.5 * cos_phi, 0.0, 1.0)), v);
}

SHARED_INLINE void anglesFromSkyViewUv(AtmosphereParameters atmosphere, Real r, vec2 uv, OUT(Real) theta,
                                       OUT(Real) cos_phi) {
  Real theta_h = horizonZenithAngle(atmosphere, r);
  if (uv.y >= 0.5) {
    Real s = 2.0 * uv.y - 1.0;
    theta = theta_h * (1.0 - s * s);
  } else {
    Real s = 1.0 - 2.0 * uv.y;
    theta = theta_h + s * s * (kPi - theta_h);
  }
  cos_phi = 1.0 - 2.0 * uv.x * uv.x;
}

SHARED_END

#endif  // FIRMAMENT_ATMOSPHERE_LUT_GLSL
