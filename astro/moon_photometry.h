#pragma once
// The Moon as a light: its illuminance at the top of the atmosphere from a published magnitude law with
// the opposition surge, its spectrum (sunlight reddened by the lunar reflectance), its apparent size and
// the geometry the disc shader (shaders/common/moon_disc.glsl) needs (docs/night.md, "Moonlight").
#include <glm/vec3.hpp>

#include <vector>

#include "astro/geodetic.h"
#include "astro/refraction.h"
#include "astro/time.h"

namespace firmament::astro {

// The Moon's mean radius, m (IAU WG on Cartographic Coordinates, Archinal et al. 2018: 1737.4 km).
inline constexpr double kMoonRadius = 1737.4e3;
// The mean Earth-Moon distance that the magnitude law refers to, m (384 400 km; Allen 1973).
inline constexpr double kMoonMeanDistance = 384400e3;

// Krisciunas & Schaefer (1991), "A model of the brightness of moonlight", PASP 103, 1033, eq. 9 (after
// Allen 1973): the Moon's V magnitude at its mean distance, as a function of the phase angle alpha
// (degrees, the Sun-Moon-Earth angle; 0 at full):
//   m(alpha) = -12.73 + 0.026 |alpha| + 4e-9 alpha^4.
double moonMagnitudeAtMeanDistance(double phaseAngleRadians);

// The opposition surge K&S describe next to eq. 9: within 7° of full the Moon is up to 35 % brighter than
// the magnitude law (Whitaker 1969). Here a factor 1 + 0.35 (1 - |alpha| / 7°) inside 7°, 1 outside:
// continuous in alpha (the linear ramp is this project's choice of shape; K&S give the size and extent).
double moonOppositionSurge(double phaseAngleRadians);

// Illuminance of the Moon outside the atmosphere, normal to its light, in lux: K&S eq. 8,
//   I = 10^(-0.4 (m + 16.57)) foot-candles (1 fc = 10.7639 lx),
// times the opposition surge, times (mean distance / distance)^2 for the Moon (observer to Moon) and
// (1 au / Sun-Moon distance)^2 for the Sun. Full Moon at the mean distances: 0.313 lx (0.423 lx with the
// full surge at alpha = 0, which only an eclipse reaches).
double moonIlluminanceLux(double phaseAngleRadians, double observerMoonDistanceM, double sunMoonDistanceAu = 1.0);

// The lunar reflectance relative to its value at 550 nm: linear in wavelength, 1 + s (lambda - 550 nm),
// s = 2.0e-3 per nm, the slope that makes moonlight redder than sunlight by the published colour
// difference: B-V of the Moon 0.92 against 0.65 for the Sun (Allen 1973), at the B and V bands' effective
// wavelengths 440 and 550 nm: 10^(-0.4 · 0.27) = 0.78 = 1 - 110 s.
double lunarRelativeReflectance(double wavelengthNm);

// The Moon's spectral irradiance outside the atmosphere divided by the tabulated solar spectral
// irradiance at 1 au (core/spectrum.h, solarIrradianceTopOfAtmosphere), at a wavelength: the factor by
// which the atmosphere's tables (linear in the light, made for the Sun's spectrum at 1 au) turn into
// moonlight. It is k · lunarRelativeReflectance(lambda), k such that the photopic illuminance of
// k · reflectance · solar spectrum is `illuminanceLux`.
double moonToSolarIrradianceRatio(double illuminanceLux, double wavelengthNm);

// Everything a frame needs about the Moon at a place and instant.
struct MoonLight {
  glm::dvec3 directionEnu{0.0, 0.0, 1.0};    // apparent (refraction as asked), unit, x east, y north, z up
  double zenith = 0.0;                       // apparent zenith angle, radians
  double azimuth = 0.0;                      // clockwise from north
  glm::dvec3 sunFromMoonEnu{0.0, 0.0, 1.0};  // unit vector from the Moon towards the Sun, ENU axes
  double distance = 0.0;                     // observer to Moon, m
  double angularRadius = 0.0;                // apparent radius, asin(kMoonRadius / distance), radians
  double phaseAngle = 0.0;                   // at the Moon between Sun and observer, radians (0 full)
  double illuminatedFraction = 0.0;          // (1 + cos phaseAngle) / 2
  bool waxing = false;
  double illuminanceLux = 0.0;       // moonIlluminanceLux for this geometry
  double litRadianceScale = 0.0;     // C of moon_disc.glsl for illuminanceLux: cd/m^2
  double earthshineLuminance = 0.0;  // moon_disc.glsl's earthshine, cd/m^2
};
// Topocentric: the phase angle and distance are the observer's (parallax up to ~1°), not the Earth
// centre's; moonPhase (moon.h) gives the geocentric ones.
MoonLight moonLight(const AstroTime& time, const GeodeticLocation& location,
                    const ObservingConditions& conditions = {});

}  // namespace firmament::astro
