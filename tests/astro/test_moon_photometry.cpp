// Moonlight: the Krisciunas & Schaefer (1991) magnitude law with the opposition surge, its distance
// scaling, the spectrum, the illuminated fraction against the ephemeris, and the disc shader's
// energy: its radiance summed over the disc is the law's illuminance at every phase.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "astro/moon.h"
#include "astro/moon_photometry.h"
#include "common/moon_disc.glsl"
#include "core/spectrum.h"

namespace firmament::astro {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(MoonPhotometry, IlluminanceFollowsKrisciunasSchaeferEquations8And9) {
  // K&S eq. 9, m = -12.73 + 0.026|a| + 4e-9 a^4, and eq. 8, I = 10^(-0.4 (m + 16.57)) fc, evaluated here
  // independently, at the mean distance, outside the surge's 7 degrees.
  for (double alpha = 10.0; alpha <= 170.0; alpha += 10.0) {
    const double m = -12.73 + 0.026 * alpha + 4e-9 * std::pow(alpha, 4.0);
    const double lux = std::pow(10.0, -0.4 * (m + 16.57)) * 10.7639104;
    EXPECT_NEAR(moonMagnitudeAtMeanDistance(alpha * kDegree), m, 1e-12);
    EXPECT_NEAR(moonIlluminanceLux(alpha * kDegree, kMoonMeanDistance), lux, 1e-12 * lux) << alpha;
  }
  // The full Moon: K&S's 0.31 lx outside the atmosphere (their text; 0.0291 fc) without the surge.
  const double full = moonIlluminanceLux(0.0, kMoonMeanDistance) / moonOppositionSurge(0.0);
  std::printf("full Moon at the mean distance: %.4f lx (%.4f with the full surge)\n", full,
              moonIlluminanceLux(0.0, kMoonMeanDistance));
  EXPECT_NEAR(full, 0.313, 0.001);
  // A quarter Moon (90 degrees) gives 1/11 of the full Moon's light without the surge (2.60 mag), 1/15 with
  // it: the "about a tenth" the Moon's phase curve is known for.
  const double quarter = moonIlluminanceLux(90.0 * kDegree, kMoonMeanDistance);
  std::printf("quarter / full: 1/%.1f (1/%.1f with the surge)\n", full / quarter,
              moonIlluminanceLux(0.0, kMoonMeanDistance) / quarter);
  EXPECT_NEAR(full / quarter, std::pow(10.0, 0.4 * (0.026 * 90.0 + 4e-9 * std::pow(90.0, 4.0))), 1e-9);
  EXPECT_NEAR(full / quarter, 11.0, 0.1);
  // Monotonic from full to new.
  for (double alpha = 0.0; alpha < 180.0; alpha += 0.5)
    EXPECT_GT(moonIlluminanceLux(alpha * kDegree, kMoonMeanDistance),
              moonIlluminanceLux((alpha + 0.5) * kDegree, kMoonMeanDistance));
}

TEST(MoonPhotometry, OppositionSurgeIsUpTo35PercentWithinSevenDegrees) {
  EXPECT_DOUBLE_EQ(moonOppositionSurge(0.0), 1.35);
  EXPECT_DOUBLE_EQ(moonOppositionSurge(7.0 * kDegree), 1.0);
  EXPECT_DOUBLE_EQ(moonOppositionSurge(30.0 * kDegree), 1.0);
  EXPECT_NEAR(moonOppositionSurge(3.5 * kDegree), 1.175, 1e-12);
  EXPECT_NEAR(moonOppositionSurge(6.999 * kDegree), 1.0, 1e-4);  // continuous at 7 degrees
}

TEST(MoonPhotometry, InverseSquareInTheMoonsAndTheSunsDistance) {
  // Perigee 356 500 km against apogee 406 700 km: (406.7 / 356.5)^2 = 1.301 brighter.
  EXPECT_NEAR(moonIlluminanceLux(0.5, 356500e3) / moonIlluminanceLux(0.5, 406700e3), std::pow(406.7 / 356.5, 2), 1e-12);
  EXPECT_NEAR(moonIlluminanceLux(0.5, kMoonMeanDistance, 1.0167) / moonIlluminanceLux(0.5, kMoonMeanDistance, 1.0),
              1.0 / (1.0167 * 1.0167), 1e-12);
}

TEST(MoonPhotometry, SpectrumIsReddenedSunlightWithTheLawsIlluminance) {
  // The photopic illuminance of (ratio x tabulated solar spectrum) is the illuminance asked for.
  const TabulatedSpectrum& sun = solarIrradianceTopOfAtmosphere();
  TabulatedSpectrum moon = sun;
  for (size_t i = 0; i < moon.values.size(); ++i)
    moon.values[i] *= moonToSolarIrradianceRatio(0.25, sun.firstWavelength + sun.spacing * double(i));
  EXPECT_NEAR(spectrumToXyz(moon).y, 0.25, 1e-9);
  // The reflectance ratio between the B and V effective wavelengths is the colour difference Moon - Sun,
  // 0.92 - 0.65 = 0.27 mag (Allen 1973).
  EXPECT_NEAR(-2.5 * std::log10(lunarRelativeReflectance(440.0) / lunarRelativeReflectance(550.0)), 0.27, 0.005);
  // Moonlight is redder than sunlight: its chromaticity x is larger.
  const glm::dvec3 xyzMoon = spectrumToXyz(moon), xyzSun = spectrumToXyz(sun);
  const double xMoon = xyzMoon.x / (xyzMoon.x + xyzMoon.y + xyzMoon.z);
  const double xSun = xyzSun.x / (xyzSun.x + xyzSun.y + xyzSun.z);
  std::printf("chromaticity x: Moon %.4f, Sun %.4f\n", xMoon, xSun);
  EXPECT_GT(xMoon, xSun + 0.01);
}

TEST(MoonPhotometry, IlluminatedFractionMatchesTheEphemeris) {
  // Topocentric (moonLight) against geocentric (moonPhase, tested on Meeus 48.a) through a lunation from
  // one place: they differ only by the parallax (< 1 degree of phase angle, < 0.009 in k).
  const GeodeticLocation site = GeodeticLocation::fromDegrees(46.55, 7.98, 1200.0);
  UtcTime utc = parseUtc("2024-03-01T00:00:00Z");
  double worst = 0.0;
  for (int day = 0; day < 30; ++day, utc = addSeconds(utc, 86400.0 + 3600.0 * 7)) {
    const AstroTime t = makeAstroTime(utc);
    const MoonLight light = moonLight(t, site);
    const MoonPhase phase = moonPhase(t);
    worst = std::max(worst, std::abs(light.illuminatedFraction - phase.illuminatedFraction));
    EXPECT_NEAR(light.illuminatedFraction, (1.0 + std::cos(light.phaseAngle)) / 2.0, 1e-12);
    EXPECT_EQ(light.waxing, phase.waxing);
  }
  std::printf("illuminated fraction, topocentric - geocentric: worst %.4f\n", worst);
  EXPECT_LT(worst, 0.01);
  // Full Moon 2024-01-25 17:54 UTC and the total solar eclipse of 2024-04-08 (new Moon 18:21 UTC) seen
  // from the central line (Mazatlan region, 23.2 N 106.4 W at 18:17 UTC; here the sub-lunar point).
  EXPECT_GT(moonLight(makeAstroTime("2024-01-25T17:54:00Z"), GeodeticLocation::fromDegrees(23.5, 96.0, 0.0))
                .illuminatedFraction,
            0.998);
  EXPECT_LT(moonLight(makeAstroTime("2024-04-08T18:21:00Z"), GeodeticLocation::fromDegrees(8.0, -95.0, 0.0))
                .illuminatedFraction,
            1e-4);
}

TEST(MoonPhotometry, DiscRadianceSumsToTheIlluminanceAtEveryPhase) {
  // Integrates the shared disc function over a fine grid of directions around the Moon (solid angle per
  // cell exact for the tangent-plane grid) and compares with the illuminance it was normalised to.
  const double rho = 0.2588 * kDegree;  // the Moon at 384 400 km
  const glm::dvec3 moonDir(0.0, 0.0, 1.0);
  for (double alphaDeg : {0.0, 3.0, 30.0, 60.0, 90.0, 120.0, 150.0, 170.0}) {
    const double alpha = alphaDeg * kDegree;
    // The Sun seen from the Moon: at angle alpha from the direction back to the observer (-moonDir).
    const glm::dvec3 sunFromMoon(std::sin(alpha), 0.0, -std::cos(alpha));
    const double illuminance = moonIlluminanceLux(alpha, kMoonMeanDistance);
    const double scale = shared::moonLitRadianceScale(illuminance, rho, alpha);
    const int n = alphaDeg > 160.0 ? 4000 : 800;  // the 170-degree crescent is 0.015 radii wide
    const double extent = 1.02 * std::tan(rho), h = 2.0 * extent / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x = -extent + (i + 0.5) * h, y = -extent + (j + 0.5) * h;
        const glm::dvec3 v(x, y, 1.0);
        const double r2 = glm::dot(v, v);
        const double solidAngle = h * h / (r2 * std::sqrt(r2));
        sum += shared::moonDiscRadiance(v / std::sqrt(r2), moonDir, sunFromMoon, rho, scale, 0.0, 1.0) * solidAngle;
      }
    std::printf("alpha %5.1f deg: disc sum / illuminance = %.5f\n", alphaDeg, sum / illuminance);
    EXPECT_NEAR(sum / illuminance, 1.0, 0.005) << alphaDeg;  // grid error: measured <= 0.3 %
  }
}

TEST(MoonPhotometry, DiscLimbTerminatorAndEarthshine) {
  const double rho = 0.26 * kDegree;
  const glm::dvec3 moonDir(0.0, 0.0, 1.0);
  // Full: Lommel-Seeliger is flat (mu0 = mu: radiance C/2 everywhere on the disc), nothing off the disc.
  const glm::dvec3 sunBehindObserver(0.0, 0.0, -1.0);
  const double c = 1.0;
  auto at = [&](double x, double y, const glm::dvec3& sun, double earthshine) {
    return shared::moonDiscRadiance(glm::normalize(glm::dvec3(x * std::tan(rho), y * std::tan(rho), 1.0)), moonDir, sun,
                                    rho, c, earthshine, 1.0);
  };
  EXPECT_NEAR(at(0.0, 0.0, sunBehindObserver, 0.0), 0.5, 1e-9);
  EXPECT_NEAR(at(0.95, 0.0, sunBehindObserver, 0.0), 0.5, 1e-9);
  EXPECT_EQ(at(1.01, 0.0, sunBehindObserver, 0.0), 0.0);
  // First quarter (alpha 90, Sun toward +x): the +x half is lit, the -x half dark but for the earthshine.
  const glm::dvec3 sunSide(1.0, 0.0, 0.0);
  const double earthshine = shared::moonEarthshineRadiance(c, 90.0 * kDegree);
  EXPECT_GT(at(0.5, 0.0, sunSide, earthshine), 0.1);
  EXPECT_NEAR(at(-0.5, 0.0, sunSide, earthshine), earthshine, 1e-15);
  EXPECT_NEAR(at(0.0, 0.5, sunSide, 0.0), 0.0, 1e-12);  // the terminator: mu0 = 0
  // Earthshine ~1e-4 of the lit part's mean radiance near new Moon, none at full.
  EXPECT_NEAR(shared::moonEarthshineRadiance(c, std::numbers::pi) / (0.5 * c), 1e-4, 1e-12);
  EXPECT_DOUBLE_EQ(shared::moonEarthshineRadiance(c, 0.0), 0.0);
  // The closed form of the Lommel-Seeliger disc integral at its ends.
  EXPECT_NEAR(shared::lommelSeeligerDiscPhase(0.0), 1.0, 1e-9);
  EXPECT_NEAR(shared::lommelSeeligerDiscPhase(std::numbers::pi), 0.0, 1e-9);
  EXPECT_NEAR(shared::lommelSeeligerDiscPhase(std::numbers::pi / 2),
              1.0 - std::sqrt(0.5) * std::log(1.0 + std::sqrt(2.0)), 1e-12);
}

}  // namespace
}  // namespace firmament::astro
