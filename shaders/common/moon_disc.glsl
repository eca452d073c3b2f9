// moon_disc.glsl: the Moon's disc as the camera sees it, per pixel: phase, limb and terminator from the
// Lommel-Seeliger reflectance law, earthshine on the dark part, normalised so that the disc's light
// summed over its solid angle is the Moon's illuminance from the published magnitude law (Krisciunas &
// Schaefer 1991, astro/moon_photometry.h). Shared by the GPU pass and the C++ tests (docs/night.md,
// "The Moon's disc"; docs/shared-physics.md for the rules).
//
// Lommel-Seeliger: the radiance of a point of the lit part is proportional to mu0 / (mu0 + mu), mu0 and
// mu the cosines of the incidence (Sun) and emission (observer) angles. It is the single-scattering law
// of a dark, rough regolith: it has the Moon's nearly flat full disc (no limb darkening at full, as
// observed) and a soft terminator. The disc-integrated law has the closed form
//   Phi(alpha) = 1 - sin(alpha/2) tan(alpha/2) ln(cot(alpha/4)),  Phi(0) = 1,
// with integral over the unit disc of mu0/(mu0+mu) = (pi/2) Phi(alpha). The phase dependence of the
// Moon's brightness itself (with the opposition surge) comes from the magnitude law; this header only
// distributes that light over the disc.
#ifndef FIRMAMENT_MOON_DISC_GLSL
#define FIRMAMENT_MOON_DISC_GLSL

#include "common/compat.glsl"

SHARED_BEGIN

// Earthshine radiance on the dark part relative to the lit part's mean radiance, at a full Earth
// (Danjon's ashen light: about ten magnitudes below the lit crescent). Scaled by the Earth's lit
// fraction seen from the Moon, (1 - cos alpha) / 2: none at full Moon, full at new Moon.
const Real kMoonEarthshineRatio = 1.0e-4;

// Phi(alpha) above, for a phase angle in [0, pi] (radians); clamped just inside the interval, where the
// closed form is 1 (alpha = 0) and 0 (alpha = pi) in the limit.
SHARED_INLINE Real lommelSeeligerDiscPhase(Real phaseAngle) {
  Real a = clamp(phaseAngle, 1.0e-6, kPi - 1.0e-6);
  Real halfAngle = 0.5 * a;
  return max(1.0 - sin(halfAngle) * tan(halfAngle) * log(1.0 / tan(0.25 * a)), 0.0);
}

// Solid angle of the disc of angular radius rho (radians): 2 pi (1 - cos rho), written without the
// cancellation of 1 - cos for the Moon's ~0.0045 rad: 4 pi sin^2(rho/2).
SHARED_INLINE Real moonDiscSolidAngle(Real angularRadius) {
  Real s = sin(0.5 * angularRadius);
  return 4.0 * kPi * s * s;
}

// The factor C of the lit part's radiance C mu0/(mu0+mu): the illuminance E (any unit: lux gives
// cd/m^2, W m^-2 nm^-1 gives W m^-2 sr^-1 nm^-1) divided by the integral of mu0/(mu0+mu) over the disc's
// solid angle, (Omega / pi) (pi / 2) Phi(alpha). Returns 0 where Phi underflows (alpha at pi).
SHARED_INLINE Real moonLitRadianceScale(Real illuminance, Real angularRadius, Real phaseAngle) {
  Real phi = lommelSeeligerDiscPhase(phaseAngle);
  Real omega = moonDiscSolidAngle(angularRadius);
  return phi > 1.0e-12 && omega > 0.0 ? 2.0 * illuminance / (omega * phi) : 0.0;
}

// Earthshine radiance on the whole disc, in the unit of C: kMoonEarthshineRatio times the lit part's
// mean radiance C Phi (pi/2) / (lit area fraction (1 + cos alpha)/2 · pi) ~ C/2 at any phase, times the
// Earth's lit fraction (1 - cos alpha)/2. Lommel-Seeliger lit from the Earth (mu0 = mu) is uniform.
SHARED_INLINE Real moonEarthshineRadiance(Real litRadianceScale, Real phaseAngle) {
  return kMoonEarthshineRatio * 0.5 * litRadianceScale * 0.5 * (1.0 - cos(phaseAngle));
}

// Where a view direction meets the disc. `viewDir`, `moonDir` (to the disc's centre) are unit vectors
// from the observer; `sunFromMoon` is the unit vector from the Moon to the Sun; `angularRadius` the
// apparent radius (radians). Returns false off the disc. On the disc, `normal` is the unit surface
// normal at the point seen (the component along -moonDir is toward the observer: mu), and mu, mu0 the
// cosines of emission and incidence (mu0 <= 0 on the dark part). Orthographic projection of the sphere:
// the error is of order rho^2 ~ 2e-5.
SHARED_INLINE bool moonDiscPoint(vec3 viewDir, vec3 moonDir, vec3 sunFromMoon, Real angularRadius, OUT(vec3) normal,
                                 OUT(Real) mu, OUT(Real) mu0) {
  Real cosTheta = dot(viewDir, moonDir);
  Real sinRho = sin(angularRadius);
  vec3 offset = (viewDir - moonDir * cosTheta) / max(sinRho, 1.0e-12);
  Real r2 = dot(offset, offset);
  normal = -moonDir;
  mu = 1.0;
  mu0 = 0.0;
  if (cosTheta <= 0.0 || r2 >= 1.0) return false;
  mu = sqrt(max(1.0 - r2, 0.0));
  normal = offset - moonDir * mu;
  mu0 = dot(normal, sunFromMoon);
  return true;
}

// Radiance of the disc along `viewDir`: C mu0/(mu0+mu) on the lit part plus the earthshine, both times
// `albedoFactor` (the albedo texture's value relative to the disc's mean, 1 for a uniform disc); 0 off
// the disc. Units of C (moonLitRadianceScale).
SHARED_INLINE Real moonDiscRadiance(vec3 viewDir, vec3 moonDir, vec3 sunFromMoon, Real angularRadius,
                                    Real litRadianceScale, Real earthshineRadiance, Real albedoFactor) {
  vec3 normal;
  Real mu;
  Real mu0;
  if (!moonDiscPoint(viewDir, moonDir, sunFromMoon, angularRadius, normal, mu, mu0)) return 0.0;
  Real lit = mu0 > 0.0 ? litRadianceScale * mu0 / (mu0 + mu) : 0.0;
  return albedoFactor * (lit + earthshineRadiance);
}

SHARED_END

#endif  // FIRMAMENT_MOON_DISC_GLSL
