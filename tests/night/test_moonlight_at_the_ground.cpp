// The full Moon's illuminance at the ground through the project's clear-sky reference atmosphere
// (atmosphere/reference_optical_depth.h: the spectral transmittance along the Moon's direction), against
// the published range: K&S 1991's 0.31 lx outside the air for a mean full Moon, "about 0.3 lx near the
// zenith", 0.05-0.1 lx at lower altitudes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "astro/moon_photometry.h"
#include "atmosphere/atmosphere_settings.h"
#include "atmosphere/reference_optical_depth.h"
#include "core/spectrum.h"

namespace firmament {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Direct illuminance of the Moon at the ground, normal to its light: the Moon's spectral irradiance
// (moonToSolarIrradianceRatio x tabulated solar spectrum) times the reference transmittance from the
// ground along the Moon's zenith angle, through the CIE observer. Sea-level ground, Bruneton's Earth.
double groundIlluminance(const astro::MoonLight& moon) {
  const TabulatedSpectrum& sun = solarIrradianceTopOfAtmosphere();
  std::vector<double> wavelengths;
  for (size_t i = 0; i < sun.values.size(); ++i) wavelengths.push_back(sun.firstWavelength + sun.spacing * double(i));
  const reference::SpectralMedium medium = reference::SpectralMedium::fromSettings(AtmosphereSettings{}, wavelengths);
  const reference::ColumnIntegrator integrator(medium, 1e-7);
  bool ground = false;
  const reference::RaySegment up =
      reference::segmentToBoundary(medium, medium.groundRadius(), std::cos(moon.zenith), &ground);
  EXPECT_FALSE(ground);
  const reference::ConstituentDensities column = integrator.column(up);
  TabulatedSpectrum atGround = sun;
  for (size_t i = 0; i < atGround.values.size(); ++i) {
    const double transmittance = std::exp(-glm::dot(medium.extinctionPerDensity(int(i)), column));
    atGround.values[i] *= astro::moonToSolarIrradianceRatio(moon.illuminanceLux, wavelengths[i]) * transmittance;
  }
  return spectrumToXyz(atGround).y;
}

TEST(Moonlight, FullMoonNearTheZenithGivesAboutAThirdOfALux) {
  // Three full Moons, each from (about) its sub-lunar point, zenith angle < 0.3 degrees: near apogee
  // (2024-01-25, 394 600 km), near perigee (2024-12-15, 364 000 km; 2025-11-05, 350 600 km).
  struct Case {
    const char* utc;
    double latitude, longitude;
  };
  const Case cases[] = {{"2024-01-25T17:54:00Z", 23.5, 96.0},
                        {"2024-12-15T09:02:00Z", 28.0, -137.0},
                        {"2025-11-05T13:19:00Z", 20.0, 155.0}};
  for (const Case& c : cases) {
    const astro::MoonLight moon = astro::moonLight(astro::makeAstroTime(c.utc),
                                                   astro::GeodeticLocation::fromDegrees(c.latitude, c.longitude, 0.0));
    ASSERT_LT(moon.zenith, 0.5 * kDegree);
    const double ground = groundIlluminance(moon);
    std::printf(
        "%s: distance %.0f km, phase angle %.2f deg, %.3f lx above the air, %.3f lx at the ground "
        "(transmittance %.3f)\n",
        c.utc, moon.distance / 1e3, moon.phaseAngle / kDegree, moon.illuminanceLux, ground,
        ground / moon.illuminanceLux);
    // The published range for a full Moon near the zenith on a clear night: 0.25-0.36 lx (K&S 1991's 0.31 lx
    // above the air at the mean distance, 0.85-0.9 transmitted; up to 14 % more at perigee).
    EXPECT_GT(ground, 0.25) << c.utc;  // measured 0.263 (apogee side)
    EXPECT_LT(ground, 0.36) << c.utc;  // measured 0.345 (perigee 2025)
  }
}

TEST(Moonlight, FullMoonLowInTheSkyGivesAFewHundredthsOfALuxOnTheGround) {
  // The 2024-01-25 full Moon at 15 and 25 degrees elevation (the first place west of the sub-lunar point, on
  // its latitude, where it is that low): horizontal illuminance = normal illuminance x sin(elevation);
  // published 0.05-0.1 lx at such altitudes.
  const astro::AstroTime t = astro::makeAstroTime("2024-01-25T17:54:00Z");
  for (double target : {15.0, 25.0}) {
    astro::MoonLight moon;
    for (double longitude = 96.0; longitude > -84.0; longitude -= 0.1) {
      moon = astro::moonLight(t, astro::GeodeticLocation::fromDegrees(23.5, longitude, 0.0));
      if (90.0 - moon.zenith / kDegree <= target) break;
    }
    const double elevation = std::numbers::pi / 2 - moon.zenith;
    ASSERT_NEAR(elevation / kDegree, target, 0.2);
    const double horizontal = groundIlluminance(moon) * std::sin(elevation);
    std::printf("elevation %.1f deg: %.3f lx on the horizontal ground\n", elevation / kDegree, horizontal);
    EXPECT_GT(horizontal, 0.03);  // measured 0.045 at 15 degrees
    EXPECT_LT(horizontal, 0.12);  // measured 0.090 at 25 degrees
  }
}

}  // namespace
}  // namespace firmament
