#include "astro/moon_photometry.h"

#include <erfa.h>
#include <erfam.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "astro/moon.h"
#include "astro/sun.h"
#include "common/moon_disc.glsl"
#include "core/spectrum.h"

namespace firmament::astro {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kLuxPerFootCandle = 10.7639104;  // 1 lm/ft^2 = 1 / 0.3048^2 lm/m^2
constexpr double kReflectanceSlopePerNm = 2.0e-3;

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// 683 ∫ E_sun(λ) ρ(λ) ȳ(λ) dλ for the tabulated solar spectrum at 1 au: the illuminance (lux) of
// sunlight reflected with the relative reflectance, per unit of k.
double reddenedSolarIlluminance() {
  static const double value = [] {
    const TabulatedSpectrum& sun = solarIrradianceTopOfAtmosphere();
    TabulatedSpectrum reddened = sun;
    for (size_t i = 0; i < reddened.values.size(); ++i)
      reddened.values[i] *= lunarRelativeReflectance(sun.firstWavelength + sun.spacing * double(i));
    return spectrumToXyz(reddened).y;
  }();
  return value;
}

}  // namespace

double moonMagnitudeAtMeanDistance(double phaseAngleRadians) {
  const double alpha = std::abs(phaseAngleRadians) / kDegree;
  return -12.73 + 0.026 * alpha + 4e-9 * alpha * alpha * alpha * alpha;
}

double moonOppositionSurge(double phaseAngleRadians) {
  const double alpha = std::abs(phaseAngleRadians) / kDegree;
  return 1.0 + 0.35 * std::max(0.0, 1.0 - alpha / 7.0);
}

double moonIlluminanceLux(double phaseAngleRadians, double observerMoonDistanceM, double sunMoonDistanceAu) {
  const double footCandles = std::pow(10.0, -0.4 * (moonMagnitudeAtMeanDistance(phaseAngleRadians) + 16.57));
  const double moonDistance = kMoonMeanDistance / observerMoonDistanceM;
  const double sunDistance = 1.0 / sunMoonDistanceAu;
  return footCandles * kLuxPerFootCandle * moonOppositionSurge(phaseAngleRadians) * moonDistance * moonDistance *
         sunDistance * sunDistance;
}

double lunarRelativeReflectance(double wavelengthNm) {
  return std::max(1.0 + kReflectanceSlopePerNm * (wavelengthNm - 550.0), 0.0);
}

double moonToSolarIrradianceRatio(double illuminanceLux, double wavelengthNm) {
  return illuminanceLux / reddenedSolarIlluminance() * lunarRelativeReflectance(wavelengthNm);
}

MoonLight moonLight(const AstroTime& time, const GeodeticLocation& location, const ObservingConditions& conditions) {
  MoonLight light;
  const TopocentricPosition moon = moonPosition(time, location, conditions);
  const TopocentricPosition sun = sunPosition(time, location, conditions);
  light.zenith = moon.zenith;
  light.azimuth = moon.azimuth;
  light.directionEnu = moon.directionEnu();
  light.distance = moon.distance;
  light.angularRadius = std::asin(std::min(kMoonRadius / moon.distance, 1.0));
  // Observer-centred vectors in ENU metres (geometric directions: refraction does not move the bodies).
  const glm::dvec3 toMoon = enuDirection(moon.geometricZenith, moon.azimuth) * moon.distance;
  const glm::dvec3 toSun = enuDirection(sun.geometricZenith, sun.azimuth) * sun.distance;
  const glm::dvec3 moonToSun = toSun - toMoon;
  light.sunFromMoonEnu = glm::normalize(moonToSun);
  light.phaseAngle = angleBetween(moonToSun, -toMoon);
  light.illuminatedFraction = std::clamp((1.0 + std::cos(light.phaseAngle)) / 2.0, 0.0, 1.0);
  light.waxing = moonPhase(time).waxing;
  light.illuminanceLux = moonIlluminanceLux(light.phaseAngle, light.distance, glm::length(moonToSun) / ERFA_DAU);
  light.litRadianceScale = shared::moonLitRadianceScale(light.illuminanceLux, light.angularRadius, light.phaseAngle);
  light.earthshineLuminance = shared::moonEarthshineRadiance(light.litRadianceScale, light.phaseAngle);
  return light;
}

}  // namespace firmament::astro
