// The moonless night sky above the air (shaders/common/night_sky.glsl, astro/night_sky.h) against Leinert
// et al. (1998): a dark-site zenith of 21.6-22.0 V mag/arcsec^2 with airglow ~65 %, zodiacal light ~27 %,
// starlight ~7 % (their summary: 145 + 60 + 15 of 220 S10, 21.9 mag/arcsec^2).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "astro/moon.h"
#include "astro/night_sky.h"
#include "astro/star_catalogue.h"
#include "astro/sun.h"
#include "common/night_sky.glsl"
#include "core/spectrum.h"

namespace firmament::astro {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kPlanetRadius = 6360e3;

TEST(NightSky, UnitConstantsFollowFromTheZeroPointAndTheSolarTable) {
  // 1 S10 = one V = 10 star per square degree; mag/arcsec^2 <-> cd/m^2 from 2.54e-6 lx at V = 0.
  const double s10 = starIlluminanceLux(10.0) / (kDegree * kDegree);
  EXPECT_NEAR(shared::kS10Luminance, s10, 1e-4 * s10);
  EXPECT_NEAR(surfaceBrightnessLuminance(0.0), 1.0807e5, 10.0);
  EXPECT_NEAR(surfaceBrightnessLuminance(21.6), 2.47e-4, 0.01e-4);
  EXPECT_NEAR(surfaceBrightnessLuminance(22.0), 1.71e-4, 0.01e-4);
  EXPECT_NEAR(surfaceBrightnessMagnitude(surfaceBrightnessLuminance(21.9)), 21.9, 1e-12);
  // 220 S10 is 21.92 mag/arcsec^2 (Leinert's summary: 21.9).
  EXPECT_NEAR(surfaceBrightnessMagnitude(220.0 * shared::kS10Luminance), 21.92, 0.01);
  const TabulatedSpectrum& sun = solarIrradianceTopOfAtmosphere();
  EXPECT_NEAR(shared::kSolarSpectrumIlluminance, spectrumToXyz(sun).y, 0.1);
  EXPECT_NEAR(shared::kSolarSpectrumAt500Nm, sun(500.0), 1e-5);
  // One rayleigh of 557.7 nm light: 2.835e-10 W m^-2 sr^-1.
  EXPECT_NEAR(shared::rayleighToRadiance(1.0, 557.7), 2.8346e-10, 0.0005e-10);
}

TEST(NightSky, DarkSiteZenithIsLeinertsSkyWithItsShares) {
  // The zenith at the ecliptic and galactic poles (Leinert's table-17 pole, 77 = 60 S10, and the stellar
  // background's minimum), sea level, airglow at its typical intensity.
  NightSkyFrame frame;  // identity rotations: up is both poles
  const NightSkyTerms l = nightSkyLuminance(frame, {0.0, 0.0, 1.0}, kPlanetRadius, kPlanetRadius);
  const double total = l.total();
  const double magnitude = surfaceBrightnessMagnitude(total);
  std::printf(
      "zenith: %.3e cd/m^2 = %.2f mag/arcsec^2; airglow %.1f %% (%.0f S10), zodiacal %.1f %% (%.0f S10), "
      "stars %.1f %% (%.0f S10)\n",
      total, magnitude, 100 * l.airglow / total, l.airglow / shared::kS10Luminance, 100 * l.zodiacal / total,
      l.zodiacal / shared::kS10Luminance, 100 * l.stellar / total, l.stellar / shared::kS10Luminance);
  EXPECT_GT(magnitude, 21.6);
  EXPECT_LT(magnitude, 22.0);
  EXPECT_GT(total, 1.7e-4);
  EXPECT_LT(total, 2.5e-4);
  EXPECT_NEAR(l.airglow / total, 0.65, 0.03);
  EXPECT_NEAR(l.zodiacal / total, 0.27, 0.03);
  EXPECT_NEAR(l.stellar / total, 0.07, 0.02);
}

TEST(NightSky, SpectralBandsOfTheCallersSamplingKeepTheLines) {
  // 10-nm bands (the solar table's grid) and 1-nm bands integrate to the same airglow luminance.
  NightSkyFrame frame;
  double coarse = 0.0;
  for (double wavelength = 365.0; wavelength <= 825.0; wavelength += 10.0)
    coarse += nightSkySpectralRadiance(frame, {0, 0, 1}, wavelength, 10.0, kPlanetRadius, kPlanetRadius).airglow *
              cie1931ColorMatching(wavelength).y * 10.0;
  coarse *= kMaxLuminousEfficacy;
  const double fine = nightSkyLuminance(frame, {0, 0, 1}, kPlanetRadius, kPlanetRadius).airglow;
  std::printf("airglow luminance, 10-nm bands / 1-nm bands: %.4f\n", coarse / fine);
  EXPECT_NEAR(coarse / fine, 1.0, 0.02);
}

TEST(NightSky, AirglowBrightensTowardTheHorizonByTheVanRhijnFactor) {
  const double r = kPlanetRadius;
  EXPECT_DOUBLE_EQ(shared::vanRhijnFactor(1.0, r, r + 97e3), 1.0);
  const double horizon = shared::vanRhijnFactor(0.0, r, r + 97e3);
  EXPECT_NEAR(horizon, 1.0 / std::sqrt(1.0 - std::pow(r / (r + 97e3), 2.0)), 1e-9);
  EXPECT_NEAR(horizon, 5.79, 0.01);
  double previous = 0.0;
  for (double z = 0.0; z <= 90.0; z += 1.0) {
    const double v = shared::vanRhijnFactor(std::cos(z * kDegree), r, r + 97e3);
    EXPECT_GT(v, previous);
    previous = v;
  }
  // Above the layer (a camera in space) the factor stays finite.
  EXPECT_TRUE(std::isfinite(shared::vanRhijnFactor(0.0, r + 400e3, r + 97e3)));
  // At 80 degrees from the zenith the airglow is ~4x the zenith's (the dark sky's horizon glow).
  NightSkyFrame frame;
  const glm::dvec3 low(std::sin(80 * kDegree), 0.0, std::cos(80 * kDegree));
  const double ratio = nightSkyLuminance(frame, low, r, r).airglow / nightSkyLuminance(frame, {0, 0, 1}, r, r).airglow;
  std::printf("airglow at 80 degrees / zenith: %.2f\n", ratio);
  EXPECT_GT(ratio, 3.0);
  EXPECT_LT(ratio, 5.0);
}

TEST(NightSky, ZodiacalLightReproducesLeinertsTable17) {
  // Grid nodes are the table's values; between them the log-bilinear interpolation stays between them.
  EXPECT_NEAR(shared::zodiacalTable17At(90.0, 0.0), 259.0, 1e-9);
  EXPECT_NEAR(shared::zodiacalTable17At(180.0, 0.0), 230.0, 1e-9);  // the gegenschein
  EXPECT_NEAR(shared::zodiacalTable17At(120.0, 90.0), 77.0, 1e-9);  // the ecliptic pole
  EXPECT_NEAR(shared::zodiacalTable17At(30.0, 45.0), 207.0, 1e-9);
  EXPECT_NEAR(shared::zodiacalTable17At(0.0, 15.0), 3140.0, 1e-9);
  EXPECT_NEAR(shared::zodiacalTable17At(0.0, 0.0), 3140.0, 1e-9);  // empty cell: the row's first value
  const double between = shared::zodiacalTable17At(97.5, 0.0);
  EXPECT_NEAR(between, std::sqrt(259.0 * 212.0), 1e-9);
  // The factor against the solar spectrum: 77e-8 W m^-2 sr^-1 um^-1 at 500 nm at the pole.
  EXPECT_NEAR(shared::zodiacalSolarSpectrumFactor(glm::dvec3(0, 0, 1)) * shared::kSolarSpectrumAt500Nm, 77e-11, 1e-20);
  // Symmetric in the sign of the longitude difference and of the latitude.
  const glm::dvec3 a = glm::normalize(glm::dvec3(-0.3, 0.5, 0.4)), b(a.x, -a.y, -a.z);
  EXPECT_DOUBLE_EQ(shared::zodiacalSolarSpectrumFactor(a), shared::zodiacalSolarSpectrumFactor(b));
}

TEST(NightSky, FramesPointAtTheSunAndTheGalacticCentre) {
  const AstroTime t = makeAstroTime("2024-06-01T23:30:00Z");
  const GeodeticLocation site = GeodeticLocation::fromDegrees(-24.6272, -70.4042, 2635.0);  // Paranal
  const NightSkyFrame frame = nightSkyFrame(t, site);
  ObservingConditions geometric;
  geometric.refraction = RefractionModel::None;
  const glm::dvec3 sun = sunPosition(t, site, geometric).directionEnu();
  const glm::dvec3 inSunFrame = frame.enuToSunEcliptic * sun;
  std::printf("Sun in its ecliptic frame: (%.5f, %.5f, %.5f)\n", inSunFrame.x, inSunFrame.y, inSunFrame.z);
  EXPECT_GT(inSunFrame.x, std::cos(0.05 * kDegree));  // aberration and parallax: < 0.01 degree
  // The galactic centre (Sgr A*, ICRS 17h45m40.04s -29d00'28.2") through the star pipeline.
  StarCatalogue one;
  CatalogueStar sgrA;
  sgrA.rightAscension = (17.0 + 45.0 / 60 + 40.04 / 3600) * 15.0 * kDegree;
  sgrA.declination = -(29.0 + 0.0 / 60 + 28.2 / 3600) * kDegree;
  one.stars.push_back(sgrA);
  const glm::dvec3 centre = apparentStars(one, t, site, geometric)[0].directionEnu;
  const glm::dvec3 galactic = frame.enuToGalactic * centre;
  std::printf("galactic centre in galactic coordinates: (%.5f, %.5f, %.5f)\n", galactic.x, galactic.y, galactic.z);
  EXPECT_GT(galactic.x, std::cos(0.1 * kDegree));
  // Both are rotations.
  for (const glm::dmat3& m : {frame.enuToSunEcliptic, frame.enuToGalactic}) {
    const glm::dmat3 identity = glm::transpose(m) * m;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(identity[i][j], i == j ? 1.0 : 0.0, 1e-12);
    EXPECT_NEAR(glm::determinant(m), 1.0, 1e-12);
  }
}

TEST(NightSky, MoonlessAstronomicalNightsAtADarkSiteOverAYear) {
  // Paranal, every night of 2024 at 04:00 UTC (local midnight) when the Sun is below -18 degrees and the Moon
  // below the horizon: the zenith above the air through the real frames.
  const GeodeticLocation site = GeodeticLocation::fromDegrees(-24.6272, -70.4042, 2635.0);
  UtcTime utc = parseUtc("2024-01-01T04:00:00Z");
  std::vector<double> magnitudes;
  for (int day = 0; day < 366; ++day, utc = addSeconds(utc, 86400.0)) {
    const AstroTime t = makeAstroTime(utc);
    if (sunPosition(t, site).elevation() > -18.0 * kDegree || moonPosition(t, site).elevation() > 0.0) continue;
    const NightSkyFrame frame = nightSkyFrame(t, site);
    const double m = surfaceBrightnessMagnitude(
        nightSkyLuminance(frame, {0, 0, 1}, kPlanetRadius + site.height, kPlanetRadius).total());
    magnitudes.push_back(m);
  }
  std::sort(magnitudes.begin(), magnitudes.end());
  const double median = magnitudes[magnitudes.size() / 2];
  std::printf("%zu moonless nights: zenith %.2f to %.2f mag/arcsec^2 above the air, median %.2f\n", magnitudes.size(),
              magnitudes.front(), magnitudes.back(), median);
  EXPECT_GT(magnitudes.size(), 100u);
  // Brightest when the Milky Way's centre and the gegenschein pass the zenith together (June): 21.13.
  EXPECT_GT(magnitudes.front(), 21.0);
  EXPECT_LT(magnitudes.back(), 22.0);
  // Patat (2008) measured 21.6 at Paranal's zenith in dark time (V, at the ground).
  EXPECT_NEAR(median, 21.6, 0.2);
}

TEST(NightSky, FiniteAndNonNegativeEverywhere) {
  const NightSkyFrame frame =
      nightSkyFrame(makeAstroTime("2024-06-01T23:30:00Z"), GeodeticLocation::fromDegrees(46.55, 7.98, 1200.0));
  for (double z = 0.0; z <= 180.0; z += 7.5)
    for (double a = 0.0; a < 360.0; a += 15.0)
      for (double r : {kPlanetRadius, kPlanetRadius + 5e5}) {
        const glm::dvec3 d = enuDirection(z * kDegree, a * kDegree);
        for (double wavelength : {360.0, 557.7, 589.3, 700.0, 830.0}) {
          const NightSkyTerms l = nightSkySpectralRadiance(frame, d, wavelength, 10.0, r, kPlanetRadius);
          for (double v : {l.airglow, l.zodiacal, l.stellar}) {
            EXPECT_TRUE(std::isfinite(v));
            EXPECT_GE(v, 0.0);
          }
        }
      }
}

}  // namespace
}  // namespace firmament::astro
