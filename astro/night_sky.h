#pragma once
// The moonless night sky above the air at a place and instant: the frames that the shared model
// (shaders/common/night_sky.glsl: airglow, zodiacal light, stellar background) needs per direction, and a
// CPU evaluation of it by wavelength and in luminance (docs/night.md, "Night-sky brightness").
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "astro/geodetic.h"
#include "astro/time.h"

namespace firmament::astro {

// Rotations from the local ENU frame (x east, y north, z up) to
//  - the Sun's ecliptic frame of date: z the ecliptic north pole, x toward the Sun's apparent ecliptic
//    longitude (so atan2(y, x) of a direction is its lambda - lambda_sun, asin(z) its ecliptic latitude);
//  - galactic coordinates (IAU 1958 via ERFA's eraIcrs2g): z the north galactic pole, x the centre.
// Built from ERFA's observed -> ICRS chain (eraAtoiq, eraAticq) applied to the ENU axes, aberration and
// refraction left out (under 0.01°, nothing at the scale of these diffuse lights).
struct NightSkyFrame {
  glm::dmat3 enuToSunEcliptic{1.0};
  glm::dmat3 enuToGalactic{1.0};
  double sunEclipticLongitude = 0.0;  // radians, of date
};
NightSkyFrame nightSkyFrame(const AstroTime& time, const GeodeticLocation& location);

// The three lights above the air along one direction, either as spectral radiance (W m^-2 sr^-1 nm^-1) at
// one wavelength or as luminance (cd/m^2) when integrated.
struct NightSkyTerms {
  double airglow = 0.0;
  double zodiacal = 0.0;
  double stellar = 0.0;
  double total() const { return airglow + zodiacal + stellar; }
};

// Spectral radiance toward `directionEnu` (unit) at wavelengthNm, averaged over a band of binWidthNm
// (the caller's sampling step: the airglow lines are spread over it), for an observer at observerRadius
// (m from the planet's centre) on a planet of planetRadius (m). The zodiacal light and stellar background
// follow the tabulated solar spectrum (core/spectrum.h).
NightSkyTerms nightSkySpectralRadiance(const NightSkyFrame& frame, const glm::dvec3& directionEnu, double wavelengthNm,
                                       double binWidthNm, double observerRadius, double planetRadius,
                                       double airglowScale = 1.0);

// Luminance (photopic, cd/m^2) of each term: 683 lm/W · ∫ L(lambda) ybar(lambda) d lambda over 360-830 nm
// in 1-nm bands. V-band surface brightness in mag/arcsec^2 from a luminance: see surfaceBrightnessMagnitude.
NightSkyTerms nightSkyLuminance(const NightSkyFrame& frame, const glm::dvec3& directionEnu, double observerRadius,
                                double planetRadius, double airglowScale = 1.0);

// m = -2.5 log10(L / 1.0807e5 cd/m^2): the surface brightness (V mag/arcsec^2) of a luminance, from the
// star zero point 2.54e-6 lx at V = 0 (star_catalogue.h) over one square arcsecond, and its inverse.
// Treats the photopic luminance as V, as the zero point does (exact for a solar-type spectrum to ~0.05
// mag; the airglow's green line sits in both bands' peak).
double surfaceBrightnessMagnitude(double luminance);
double surfaceBrightnessLuminance(double magnitudePerSquareArcsecond);

}  // namespace firmament::astro
