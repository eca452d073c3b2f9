// atmosphere_medium.glsl: the clear-sky medium, written once for the GPU (GLSL, float) and the CPU
// reference and tests (C++, double). See compat.glsl for the rules and docs/atmosphere.md for the
// physics.
//
// The medium follows Bruneton 2017 ("Precomputed Atmospheric Scattering: a New Implementation"):
// three constituents with altitude-dependent number density, each described by coefficients at a
// reference density (units m^-1) times a dimensionless density profile in [0, 1]:
//   Rayleigh (molecules):   scattering only,          beta_R(lambda) * d_R(h)
//   Mie (aerosols):         scattering + absorption,  beta_M^s(lambda), beta_M^e(lambda), d_M(h)
//   ozone:                  absorption only,          beta_O(lambda) * d_O(h)
// Coefficients are vec3: three wavelengths at a time. The GPU fast path uses one triple (e.g. 680,
// 550, 440 nm); the spectral reference evaluates the same functions for successive triples.
#ifndef FIRMAMENT_ATMOSPHERE_MEDIUM_GLSL
#define FIRMAMENT_ATMOSPHERE_MEDIUM_GLSL

#include "common/compat.glsl"

SHARED_BEGIN

// One layer of a density profile (Bruneton 2017, DensityProfileLayer):
//   d(h) = exp_term * exp(exp_scale * h) + linear_term * h + constant_term, clamped to [0, 1],
// with h the altitude above the ground sphere in metres. An exponential profile with scale height H
// is exp_term = 1, exp_scale = -1/H; ozone's tent is two linear layers.
struct DensityLayer {
  Real width;          // m; the layer applies below this altitude (the last layer: everywhere above)
  Real exp_term;       // 1
  Real exp_scale;      // 1/m
  Real linear_term;    // 1/m
  Real constant_term;  // 1
};

// Two layers: layer0 below layer0.width, layer1 above.
struct DensityProfile {
  DensityLayer layer0;
  DensityLayer layer1;
};

struct AtmosphereParameters {
  Real bottom_radius;        // m, the ground sphere
  Real top_radius;           // m, where the density is taken as zero
  Real sun_angular_radius;   // rad
  Real mie_phase_g;          // Cornette-Shanks asymmetry
  vec3 solar_irradiance;     // W m^-2 nm^-1 at the top of the atmosphere, per wavelength
  vec3 rayleigh_scattering;  // m^-1 at density 1
  vec3 mie_scattering;       // m^-1 at density 1
  vec3 mie_extinction;       // m^-1 at density 1
  vec3 absorption_extinction;  // m^-1 at density 1 (ozone)
  vec3 ground_albedo;        // Lambertian, per wavelength
  DensityProfile rayleigh_density;
  DensityProfile mie_density;
  DensityProfile absorption_density;
  Real mu_s_min;             // cosine of the largest sun zenith angle the LUTs cover
};

SHARED_INLINE Real layerDensity(DensityLayer layer, Real altitude) {
  Real d = layer.exp_term * exp(layer.exp_scale * altitude) + layer.linear_term * altitude + layer.constant_term;
  return clamp(d, 0.0, 1.0);
}

SHARED_INLINE Real profileDensity(DensityProfile profile, Real altitude) {
  return altitude < profile.layer0.width ? layerDensity(profile.layer0, altitude)
                                         : layerDensity(profile.layer1, altitude);
}

// Scattering and extinction coefficients (m^-1) at radius r (m from the planet centre). Above the
// top radius the medium is empty by definition, which keeps the LUT domain and the reference equal.
SHARED_INLINE vec3 rayleighScatteringAt(AtmosphereParameters atmosphere, Real r) {
  Real h = r - atmosphere.bottom_radius;
  return r > atmosphere.top_radius ? vec3(0.0) : atmosphere.rayleigh_scattering * profileDensity(atmosphere.rayleigh_density, h);
}

SHARED_INLINE vec3 mieScatteringAt(AtmosphereParameters atmosphere, Real r) {
  Real h = r - atmosphere.bottom_radius;
  return r > atmosphere.top_radius ? vec3(0.0) : atmosphere.mie_scattering * profileDensity(atmosphere.mie_density, h);
}

// sigma_t = beta_R d_R + beta_M^e d_M + beta_O d_O.
SHARED_INLINE vec3 extinctionAt(AtmosphereParameters atmosphere, Real r) {
  if (r > atmosphere.top_radius) return vec3(0.0);
  Real h = r - atmosphere.bottom_radius;
  return atmosphere.rayleigh_scattering * profileDensity(atmosphere.rayleigh_density, h) +
         atmosphere.mie_extinction * profileDensity(atmosphere.mie_density, h) +
         atmosphere.absorption_extinction * profileDensity(atmosphere.absorption_density, h);
}

// Rayleigh phase function, normalised over the sphere (1/sr): 3/(16 pi) (1 + nu^2), nu = cos(angle).
SHARED_INLINE Real rayleighPhase(Real nu) {
  return 3.0 / (16.0 * kPi) * (1.0 + nu * nu);
}

// Cornette-Shanks (1992) phase function, an improved Henyey-Greenstein that tends to Rayleigh as
// g -> 0: 3/(8 pi) (1 - g^2)(1 + nu^2) / ((2 + g^2)(1 + g^2 - 2 g nu)^(3/2)). Normalised (1/sr).
SHARED_INLINE Real cornetteShanksPhase(Real g, Real nu) {
  Real k = 3.0 / (8.0 * kPi) * (1.0 - g * g) / (2.0 + g * g);
  Real denominator = max(1.0 + g * g - 2.0 * g * nu, 1e-12);
  return k * (1.0 + nu * nu) / (denominator * sqrt(denominator));
}

// Henyey-Greenstein (1941): (1 - g^2) / (4 pi (1 + g^2 - 2 g nu)^(3/2)). Normalised (1/sr).
SHARED_INLINE Real henyeyGreensteinPhase(Real g, Real nu) {
  Real denominator = max(1.0 + g * g - 2.0 * g * nu, 1e-12);
  return (1.0 - g * g) / (4.0 * kPi * denominator * sqrt(denominator));
}

// The sun's disc. Limb darkening I(mu)/I(1) = mu^alpha with mu = cos of the angle at the sun's
// surface (a power law, Hestroffer & Magnan 1998; alpha ~ 0.5 in the visible). Normalised so the
// disc integrates to the solar irradiance E: for a small disc of angular radius a, with rho the
// fraction of the radius, dOmega = 2 pi a^2 rho drho and mu = sqrt(1 - rho^2), so
//   ∫ I dOmega = I(1) 2 pi a^2 ∫_0^1 mu^alpha mu dmu = I(1) pi a^2 * 2/(alpha + 2)
//   =>  I(1) = E (alpha + 2) / (2 pi a^2).
const Real kSunLimbDarkeningExponent = 0.5;

// I(1) / E: the centre's radiance per unit irradiance (1/sr).
SHARED_INLINE Real sunDiscCentreFactor(Real angular_radius) {
  return (kSunLimbDarkeningExponent + 2.0) / (2.0 * kPi * angular_radius * angular_radius);
}

// I / I(1) in a direction at cosine `cos_angle` from the sun's centre; 0 outside the disc.
SHARED_INLINE Real sunLimbDarkening(Real cos_angle, Real angular_radius) {
  if (cos_angle < cos(angular_radius)) return 0.0;
  Real rho = clamp(acos(clamp(cos_angle, -1.0, 1.0)) / angular_radius, 0.0, 1.0);
  return pow(sqrt(max(1.0 - rho * rho, 0.0)), kSunLimbDarkeningExponent);
}

SHARED_END

#endif  // FIRMAMENT_ATMOSPHERE_MEDIUM_GLSL
