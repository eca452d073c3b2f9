// The reference's numerical building blocks against closed forms: the Gauss–Kronrod rule and its
// cumulative matrix, density columns (optical depths) in constant and exponential media, free-path
// inversion, the medium's per-wavelength coefficients against the shared extinctionAt, the sun
// disc's normalisation and the phase-function samplers.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "atmosphere/reference_medium.h"
#include "atmosphere/reference_optical_depth.h"
#include "atmosphere/reference_path_tracer.h"
#include "atmosphere/reference_random.h"
#include "atmosphere/reference_single_scattering.h"
#include "common/atmosphere_lut.glsl"

namespace firmament::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A medium of one constituent kind with constant density 1 below the top (tests only).
shared::AtmosphereParameters constantMedium(double rayleigh, double mieExtinction, double mieScattering) {
  shared::AtmosphereParameters a = atmosphereParametersAt(AtmosphereSettings{}, glm::dvec3(680.0, 550.0, 440.0));
  shared::DensityLayer constant{0.0, 0.0, 0.0, 0.0, 1.0};
  a.rayleigh_density = {constant, constant};
  a.mie_density = {constant, constant};
  a.absorption_density = {constant, constant};
  a.rayleigh_scattering = glm::dvec3(rayleigh);
  a.mie_extinction = glm::dvec3(mieExtinction);
  a.mie_scattering = glm::dvec3(mieScattering);
  a.absorption_extinction = glm::dvec3(0.0);
  return a;
}

TEST(ReferenceQuadrature, KronrodIntegratesPolynomialsAndCumulativeMatrixIsExact) {
  const GaussKronrod15& rule = gaussKronrod15();
  for (int degree = 0; degree <= 14; ++degree) {
    // ∫_{-1}^{1} x^k = (1 - (-1)^(k+1)) / (k + 1); ∫_{-1}^{x_i} x^k = (x_i^(k+1) - (-1)^(k+1)) / (k+1).
    double k15 = 0.0;
    for (int m = 0; m < kKronrodPoints; ++m) k15 += rule.kronrodWeights[m] * std::pow(rule.nodes[m], degree);
    EXPECT_NEAR(k15, (1.0 - std::pow(-1.0, degree + 1)) / (degree + 1), 1e-14) << degree;
    for (int i = 0; i < kKronrodPoints; ++i) {
      double cumulative = 0.0;
      for (int m = 0; m < kKronrodPoints; ++m) cumulative += rule.cumulative[i][m] * std::pow(rule.nodes[m], degree);
      const double exact = (std::pow(rule.nodes[i], degree + 1) - std::pow(-1.0, degree + 1)) / (degree + 1);
      EXPECT_NEAR(cumulative, exact, 1e-13) << "degree " << degree << " node " << i;
    }
  }
}

TEST(ReferenceMedium, CoefficientsMatchTheSharedExtinctionAtEveryWavelength) {
  AtmosphereSettings settings;
  settings.groundHeight = 1200.0;
  settings.mieAngstromAlpha = 1.3;
  const std::vector<double> wavelengths = evenlySpacedWavelengths(11);  // 4 triples, the last padded
  const SpectralMedium medium = SpectralMedium::fromSettings(settings, wavelengths);
  ASSERT_EQ(medium.wavelengthCount(), 11);
  for (double h : {-50.0, 0.0, 500.0, 5000.0, 9000.0, 23800.0, 30000.0, 45000.0, 58700.0, 60000.0, 70000.0}) {
    const double r = medium.groundRadius() + h;
    const ConstituentDensities d = medium.densitiesAt(r);
    for (int i = 0; i < 11; ++i) {
      const glm::dvec3 lambda(wavelengths[size_t(i)]);
      const shared::AtmosphereParameters p = atmosphereParametersAt(settings, lambda);
      const double shared = shared::extinctionAt(p, r).x;
      EXPECT_NEAR(glm::dot(medium.extinctionPerDensity(i), d), shared, 1e-15 + 1e-13 * shared) << h << " " << i;
      EXPECT_NEAR(medium.rayleighScattering(i) * d.x, shared::rayleighScatteringAt(p, r).x, 1e-18);
      EXPECT_NEAR(medium.mieScattering(i) * d.y, shared::mieScatteringAt(p, r).x, 1e-18);
      EXPECT_EQ(medium.solarIrradiance(i), p.solar_irradiance.x);
    }
  }
  // Earth's ozone tent has kinks at 10, 25 and 40 km above sea level (ground at 1.2 km).
  std::vector<double> breaks;
  for (double radius : medium.densityBreakRadii()) breaks.push_back(radius - medium.groundRadius());
  ASSERT_EQ(breaks.size(), 3u);
  EXPECT_NEAR(breaks[0], 8800.0, 1e-6);
  EXPECT_NEAR(breaks[1], 23800.0, 1e-6);
  EXPECT_NEAR(breaks[2], 38800.0, 1e-6);
}

TEST(ReferenceOpticalDepth, ConstantMediumColumnIsTheChordLength) {
  // Tolerance 1e-12 relative: the integrand is exactly 1, so only rounding remains.
  const SpectralMedium medium = SpectralMedium::fromParameters({constantMedium(1e-5, 0.0, 0.0)}, {680.0, 550.0, 440.0});
  const ColumnIntegrator integrator(medium, 1e-8);
  for (double mu : {1.0, 0.5, 0.01, 0.0, -0.02, -0.5, -1.0}) {
    bool ground = false;
    const RaySegment s = segmentToBoundary(medium, medium.groundRadius() + 1000.0, mu, &ground);
    const ConstituentDensities d = integrator.column(s);
    EXPECT_NEAR(d.x, s.length, 1e-12 * s.length) << mu;
    // Transmittance exp(-beta L), the closed form.
    EXPECT_NEAR(std::exp(-1e-5 * d.x), std::exp(-1e-5 * s.length), 1e-12) << mu;
  }
}

TEST(ReferenceOpticalDepth, ExponentialMediumMatchesClosedFormAndBruteForce) {
  // Vertical ray from the ground: ∫_0^{H_top} e^{-h/H} dh = H (1 - e^{-H_top/H}); relative 1e-9.
  const SpectralMedium medium = SpectralMedium::fromSettings(AtmosphereSettings{}, {440.0, 550.0, 680.0});
  const ColumnIntegrator integrator(medium, 1e-9);
  bool ground = false;
  const RaySegment up = segmentToBoundary(medium, medium.groundRadius(), 1.0, &ground);
  const ConstituentDensities d = integrator.column(up);
  const double thickness = medium.topRadius() - medium.groundRadius();
  EXPECT_NEAR(d.x, 8000.0 * -std::expm1(-thickness / 8000.0), 1e-9 * d.x);
  EXPECT_NEAR(d.y, 1200.0 * -std::expm1(-thickness / 1200.0), 1e-9 * d.y);
  // Ozone tent: column = 15 km (the tent's area at peak density 1).
  EXPECT_NEAR(d.z, 15000.0, 1e-9 * 15000.0);

  // Slanted and grazing rays against composite Simpson with 2e5 intervals (error ~1e-12 relative
  // with the kinks at the ozone breaks only O(h^2) ~ 1e-9): agreement to 1e-8.
  for (double mu : {0.3, 0.02, 0.0, -0.001}) {
    const RaySegment s = segmentToBoundary(medium, medium.groundRadius() + 500.0, mu, &ground);
    const int n = 200000;
    const double h = s.length / n;
    glm::dvec3 simpson(0.0);
    for (int i = 0; i <= n; ++i) {
      const double w = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      simpson += w * medium.densitiesAt(s.radiusAt(i * h));
    }
    simpson *= h / 3.0;
    const ConstituentDensities q = integrator.column(s);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(q[c], simpson[c], 1e-8 * simpson[c] + 1e-6) << mu << " " << c;
  }
}

TEST(ReferenceOpticalDepth, FreePathInversionHitsTheTargetOpticalDepth) {
  const SpectralMedium medium = SpectralMedium::fromSettings(AtmosphereSettings{}, {440.0, 550.0, 680.0});
  const ColumnIntegrator integrator(medium, 1e-9);
  bool ground = false;
  const RaySegment s = segmentToBoundary(medium, medium.groundRadius() + 200.0, 0.05, &ground);
  const glm::dvec3 beta = medium.extinctionPerDensity(0);
  const double total = glm::dot(beta, integrator.column(s));
  for (double fraction : {1e-6, 0.1, 0.5, 0.9, 0.999999}) {
    const FreePathSample f = sampleFreePath(integrator, s, beta, fraction * total);
    ASSERT_TRUE(f.collided) << fraction;
    RaySegment head = s;
    head.length = f.distance;
    EXPECT_NEAR(glm::dot(beta, integrator.column(head)), fraction * total, 1e-9 * total) << fraction;
    EXPECT_NEAR(glm::dot(beta, f.columnBefore), fraction * total, 1e-9 * total) << fraction;
  }
  EXPECT_FALSE(sampleFreePath(integrator, s, beta, 1.0001 * total).collided);
}

TEST(ReferenceSunDisc, ProfileIntegratesToOneAndMatchesTheSmallAngleForm) {
  // ∫_disc profile dOmega = 1 by a fine midpoint rule in theta (relative 1e-5: the limb's
  // (alpha - theta)^(1/4) behaviour limits the midpoint rule), and the centre value is close to
  // the GPU's small-angle normalisation (alpha + 2) / (2 pi a^2) for alpha = 0.5 (relative 1e-4).
  const double a = 0.00935 / 2.0;
  const SunDisc disc(a);
  const int n = 400000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double theta = (i + 0.5) * a / n;
    sum += disc.profile(std::cos(theta), std::sin(theta)) * 2.0 * kPi * std::sin(theta) * (a / n);
  }
  EXPECT_NEAR(sum, 1.0, 1e-5);
  EXPECT_NEAR(disc.profile(1.0, 0.0), 2.5 / (2.0 * kPi * a * a), 1e-4 * 2.5 / (2.0 * kPi * a * a));
  EXPECT_EQ(disc.profile(std::cos(1.001 * a), std::sin(1.001 * a)), 0.0);
}

TEST(ReferencePhaseSampling, MomentsMatchThePhaseFunctions) {
  // Rayleigh: E[nu] = 0, E[nu^2] = 3/8 (2/3 + 2/5) = 0.4. HG: E[nu] = g. 2e5 samples: standard
  // errors ~1.5e-3, tolerance 5 of them.
  Random random(7, 0);
  const int n = 200000;
  double r1 = 0.0, r2 = 0.0, h1 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double nu = sampleRayleighCosine(random.uniform());
    r1 += nu;
    r2 += nu * nu;
    h1 += sampleHenyeyGreensteinCosine(0.8, random.uniform());
  }
  EXPECT_NEAR(r1 / n, 0.0, 0.007);
  EXPECT_NEAR(r2 / n, 0.4, 0.005);
  EXPECT_NEAR(h1 / n, 0.8, 0.005);
  EXPECT_NEAR(sampleRayleighCosine(0.0), -1.0, 1e-12);
  EXPECT_NEAR(sampleRayleighCosine(1.0), 1.0, 1e-12);
  EXPECT_NEAR(sampleHenyeyGreensteinCosine(0.8, 0.0), -1.0, 1e-12);
  EXPECT_NEAR(sampleHenyeyGreensteinCosine(0.8, 1.0), 1.0, 1e-12);
}

}  // namespace
}  // namespace firmament::reference
