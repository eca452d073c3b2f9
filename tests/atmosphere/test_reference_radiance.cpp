// The reference renderer against analytic cases, energy conservation, robustness over the whole
// range of sun and camera positions, Monte Carlo convergence and determinism (docs/reference.md,
// "Tests" lists each with its tolerance).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "atmosphere/reference_geometry.h"
#include "atmosphere/reference_optical_depth.h"
#include "atmosphere/reference_random.h"
#include "atmosphere/reference_renderer.h"
#include "atmosphere/reference_single_scattering.h"

namespace firmament {
namespace {

using reference::SpectralMedium;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

// Constant density 1 everywhere below the top, with the given coefficients at all three
// wavelengths (Earth geometry, sun radius and phase asymmetry).
shared::AtmosphereParameters constantMedium(glm::dvec3 rayleigh, double albedo) {
  shared::AtmosphereParameters a = atmosphereParametersAt(AtmosphereSettings{}, glm::dvec3(680.0, 550.0, 440.0));
  const shared::DensityLayer constant{0.0, 0.0, 0.0, 0.0, 1.0};
  a.rayleigh_density = {constant, constant};
  a.mie_density = {constant, constant};
  a.absorption_density = {constant, constant};
  a.rayleigh_scattering = rayleigh;
  a.mie_extinction = glm::dvec3(0.0);
  a.mie_scattering = glm::dvec3(0.0);
  a.absorption_extinction = glm::dvec3(0.0);
  a.ground_albedo = glm::dvec3(albedo);
  return a;
}

SpectralMedium mediumOf(const shared::AtmosphereParameters& p) {
  return SpectralMedium::fromParameters({p}, {680.0, 550.0, 440.0});
}

ReferenceQuality deterministicOnly() {
  ReferenceQuality q;
  q.multipleScattering = false;
  q.quadratureTolerance = 1e-10;
  q.threads = 1;
  return q;
}

TEST(ReferenceRadiance, SunAtZenithSingleScatteringInConstantMediumIsExact) {
  // Camera at 10 m looking up, sun at the zenith, constant Rayleigh beta: along the vertical ray
  // T_view(t) T_sun(t) = e^{-beta t} e^{-beta (H - t)} = e^{-beta H}, so
  //   L_1 = E p_R(1) beta H e^{-beta H},  H = top - (ground + 10 m).
  // Tolerance 1e-9 relative (quadrature tolerance 1e-10).
  const glm::dvec3 beta(1e-5, 2e-5, 4e-5);
  const shared::AtmosphereParameters p = constantMedium(beta, 0.0);
  const ReferenceRenderer renderer(mediumOf(p), glm::dvec3(0.0, 0.0, 1.0), deterministicOnly());
  const double cameraRadius = p.bottom_radius + 10.0;
  const ReferenceRadiance r = renderer.radiance({0.0, 0.0, cameraRadius}, {0.0, 0.0, 1.0}, 0);
  const double height = p.top_radius - cameraRadius;
  for (int i = 0; i < 3; ++i) {
    const double expected =
        p.solar_irradiance[i] * shared::rayleighPhase(1.0) * beta[i] * height * std::exp(-beta[i] * height);
    EXPECT_NEAR(r.singleScattering[size_t(i)], expected, 1e-9 * expected) << i;
  }
}

TEST(ReferenceRadiance, OpticallyThinSingleScatteringMatchesFirstOrderFormula) {
  // beta ~ 1e-10 m^-1: the first-order (no attenuation) formula L_1 = E p_R(nu) beta H neglects
  // 1 - T_view T_sun <= tau_view + tau_sun <= beta H (1 + 1/cos theta_s) (the plane-parallel sun
  // path is the longer one), 2e-5 .. 1.2e-4 relative here, for a view at the zenith and the sun 60
  // degrees down (nu = 0.5) or at 80 degrees (nu = cos 80).
  const glm::dvec3 beta(1e-10, 2e-10, 3e-10);
  const shared::AtmosphereParameters p = constantMedium(beta, 0.0);
  for (double sunZenith : {60.0 * kDegree, 80.0 * kDegree}) {
    const glm::dvec3 sun(std::sin(sunZenith), 0.0, std::cos(sunZenith));
    const ReferenceRenderer renderer(mediumOf(p), sun, deterministicOnly());
    const double cameraRadius = p.bottom_radius + 10.0;
    const ReferenceRadiance r = renderer.radiance({0.0, 0.0, cameraRadius}, {0.0, 0.0, 1.0}, 0);
    const double height = p.top_radius - cameraRadius;
    for (int i = 0; i < 3; ++i) {
      const double expected = p.solar_irradiance[i] * shared::rayleighPhase(std::cos(sunZenith)) * beta[i] * height;
      const double bound = beta[i] * height * (1.0 + 1.0 / std::cos(sunZenith));
      EXPECT_NEAR(r.singleScattering[size_t(i)], expected, bound * expected) << sunZenith << " " << i;
      EXPECT_LE(r.singleScattering[size_t(i)], expected);  // attenuation only removes light
    }
  }
}

TEST(ReferenceRadiance, EmptyAtmosphereShowsOnlyTheSunDiscAndTheGround) {
  // All coefficients 0: the disc's radiance is E profile(theta) (its centre E / Omega_eff), the
  // ground a/pi E mu_s, everything else exactly 0, the Monte Carlo part included (1e-12 relative).
  const shared::AtmosphereParameters p = constantMedium(glm::dvec3(0.0), 0.3);
  const double sunZenith = 30.0 * kDegree;
  const glm::dvec3 sun(0.0, std::sin(sunZenith), std::cos(sunZenith));
  ReferenceQuality q;
  q.samplesPerPixel = 16;
  q.threads = 1;
  const ReferenceRenderer renderer(mediumOf(p), sun, q);
  const reference::SunDisc disc(p.sun_angular_radius);
  for (double height : {2.0, 10000.0, 1e7}) {
    const glm::dvec3 camera(0.0, 0.0, p.bottom_radius + height);
    const ReferenceRadiance atSun = renderer.radiance(camera, sun, 1);
    const ReferenceRadiance sky = renderer.radiance(camera, glm::normalize(glm::dvec3(0.3, -0.5, 0.8)), 2);
    const ReferenceRadiance down = renderer.radiance(camera, {0.0, 0.0, -1.0}, 3);
    for (int i = 0; i < 3; ++i) {
      const double e = p.solar_irradiance[i];
      EXPECT_NEAR(atSun.total()[size_t(i)], e / disc.effectiveSolidAngle(), 1e-12 * e / disc.effectiveSolidAngle());
      EXPECT_EQ(sky.total()[size_t(i)], 0.0);
      EXPECT_NEAR(down.total()[size_t(i)], 0.3 / kPi * e * std::cos(sunZenith), 1e-12 * e);
      EXPECT_EQ(down.multipleScattering[size_t(i)], 0.0);
      EXPECT_EQ(down.multipleScatteringStandardError[size_t(i)], 0.0);
    }
  }
}

// Energy conservation. With no absorption (ozone 0, Mie single-scattering albedo 1) and a ground
// of albedo 1, every watt the planet intercepts, E pi R_top^2, leaves through the top sphere:
//   ∫_{top sphere} ∫_{outward hemisphere} L cos dOmega dA  +  P_direct  =  E pi R_top^2,
// P_direct the sunlight that crosses the atmosphere unscattered through the annulus R_g < b < R_top
// (it never meets the ground): P_direct = E ∫_{R_g}^{R_top} T(b) 2 pi b db, by quadrature here.
// The double integral is estimated by Monte Carlo: a point uniform on the top sphere (pdf
// 1/(4 pi R^2)) and an outward direction with pdf cos/pi, the radiance there from the reference
// (orders 1 and up, the disc excluded as it is P_direct):  X = 4 pi L / E,
//   E[X] = 1 - P_direct / (E pi R_top^2).
// By symmetry about the sun axis the point's azimuth does not matter; (cos psi, the direction's two
// numbers) are stratified 16 x 8 x 4 in each of 16 independent batches, and the standard error
// comes from the spread of the 16 batch means. Rayleigh is 4x Earth's so that multiple scattering
// carries a large share (vertical optical depth ~1.4 at 440 nm). Tolerance: 4 standard errors.
TEST(ReferenceRadiance, NonAbsorbingAtmosphereOverWhiteGroundConservesEnergy) {
  AtmosphereSettings settings;
  settings.rayleighScatteringUm4 *= 4.0;
  settings.ozoneColumnDobson = 0.0;
  settings.mieSingleScatteringAlbedo = 1.0;
  settings.groundAlbedo = 1.0;
  const std::vector<double> wavelengths = {440.0, 550.0, 680.0};
  const glm::dvec3 sun(0.0, 0.0, 1.0);
  ReferenceQuality q;
  q.samplesPerPixel = 8;
  q.sunDisc = false;
  q.quadratureTolerance = 1e-6;
  q.threads = 1;
  const ReferenceRenderer renderer(SpectralMedium::fromSettings(settings, wavelengths), sun, q);
  const SpectralMedium& medium = renderer.medium();
  const double rTop = medium.topRadius(), rGround = medium.groundRadius();

  // P_direct / (E pi R_top^2) = (2 / R_top^2) ∫_{R_g}^{R_top} T(b) b db, composite K15 on 64 panels
  // of the chord's transmittance (T(b) is smooth; it vanishes towards b = R_g).
  const reference::ColumnIntegrator columns(medium, 1e-9);
  const reference::GaussKronrod15& rule = reference::gaussKronrod15();
  glm::dvec3 direct(0.0);
  const int panels = 64;
  for (int k = 0; k < panels; ++k) {
    const double a = rGround + (rTop - rGround) * k / panels, b = rGround + (rTop - rGround) * (k + 1) / panels;
    for (int m = 0; m < reference::kKronrodPoints; ++m) {
      const double impact = 0.5 * (a + b) + 0.5 * (b - a) * rule.nodes[m];
      reference::RaySegment chord{rTop, -std::sqrt(1.0 - (impact / rTop) * (impact / rTop)),
                                  2.0 * std::sqrt((rTop - impact) * (rTop + impact))};
      const reference::ConstituentDensities d = columns.column(chord);
      for (int i = 0; i < 3; ++i)
        direct[i] += 0.5 * (b - a) * rule.kronrodWeights[m] * std::exp(-glm::dot(medium.extinctionPerDensity(i), d)) *
                     2.0 * impact / (rTop * rTop);
    }
  }

  reference::Random random(12345, 0);
  const int batches = 16, nPsi = 16, nU = 8, nV = 4;
  glm::dvec3 sum(0.0), sumSquares(0.0);
  uint64_t stream = 0;
  for (int batch = 0; batch < batches; ++batch) {
    glm::dvec3 batchSum(0.0);
    for (int a = 0; a < nPsi; ++a)
      for (int c = 0; c < nU; ++c)
        for (int e = 0; e < nV; ++e) {
          // Point: cos(angle from the subsolar point) uniform in [-1, 1] (jittered strata).
          const double cosPsi = -1.0 + 2.0 * (a + random.uniform()) / nPsi;
          const double sinPsi = std::sqrt(std::max(0.0, 1.0 - cosPsi * cosPsi));
          const glm::dvec3 normal(sinPsi, 0.0, cosPsi);
          // Outgoing direction, cosine-weighted about the normal; the camera looks the other way.
          const double u = (c + random.uniform()) / nU, v = 2.0 * kPi * (e + random.uniform()) / nV;
          glm::dvec3 t, b;
          reference::orthonormalBasis(normal, &t, &b);
          const double cosTheta = std::sqrt(u), sinTheta = std::sqrt(1.0 - u);
          const glm::dvec3 outgoing = cosTheta * normal + sinTheta * (std::cos(v) * t + std::sin(v) * b);
          const ReferenceRadiance r = renderer.radiance(normal * rTop, -outgoing, stream++);
          for (int i = 0; i < 3; ++i) batchSum[i] += 4.0 * kPi * r.total()[size_t(i)] / medium.solarIrradiance(i);
        }
    const glm::dvec3 batchMean = batchSum / double(nPsi * nU * nV);
    sum += batchMean;
    sumSquares += batchMean * batchMean;
  }
  for (int i = 0; i < 3; ++i) {
    const double mean = sum[i] / batches;
    const double standardError = std::sqrt((sumSquares[i] / batches - mean * mean) / (batches - 1));
    EXPECT_LT(standardError, 0.01) << i;
    std::printf("energy at %g nm: scattered %.5f + direct %.5f = %.5f (SE %.5f)\n", wavelengths[size_t(i)], mean,
                direct[i], mean + direct[i], standardError);
    EXPECT_NEAR(mean, 1.0 - direct[i], 4.0 * standardError)
        << "wavelength " << wavelengths[size_t(i)] << " nm: scattered " << mean << " + direct " << direct[i] << " (SE "
        << standardError << ")";
  }
}

TEST(ReferenceRadiance, FiniteAndNonNegativeEverywhere) {
  // Sun zenith 0..180 degrees (and 1e-5 rad around 90), cameras below the ground to far in space,
  // views at the zenith, nadir, horizontal, within 1e-5 rad of the horizontal, of the ground's
  // tangent and of the top's tangent, toward and away from the sun. Every term finite and >= 0.
  const AtmosphereSettings settings;
  const std::vector<double> wavelengths = {360.0, 550.0, 830.0};
  const SpectralMedium medium = SpectralMedium::fromSettings(settings, wavelengths);
  const double rg = medium.groundRadius(), rt = medium.topRadius();
  std::vector<double> sunZeniths;
  for (int z = 0; z <= 180; z += 15) sunZeniths.push_back(z * kDegree);
  sunZeniths.push_back(0.5 * kPi - 1e-5);
  sunZeniths.push_back(0.5 * kPi + 1e-5);
  int checked = 0;
  for (double sunZenith : sunZeniths) {
    const glm::dvec3 sun(std::sin(sunZenith), 0.0, std::cos(sunZenith));
    ReferenceQuality q;
    q.samplesPerPixel = 2;
    q.quadratureTolerance = 1e-6;
    q.threads = 1;
    const ReferenceRenderer renderer(SpectralMedium::fromSettings(settings, wavelengths), sun, q);
    for (double height : {-100.0, 0.0, 1e4, 1e5, 1e6, 1e8}) {
      const double r = rg + height;
      std::vector<double> viewZeniths = {
          0.0, 45.0 * kDegree, 0.5 * kPi - 1e-5, 0.5 * kPi, 0.5 * kPi + 1e-5, 135.0 * kDegree, kPi};
      // The ground's and the top's tangent directions from this height (view zenith = pi - asin(R / r)).
      for (double radius : {rg, rt})
        if (r > radius)
          for (double d : {-1e-5, 0.0, 1e-5}) viewZeniths.push_back(kPi - std::asin(radius / r) + d);
      for (double viewZenith : viewZeniths)
        for (double azimuth : {0.5 * kPi, -0.5 * kPi}) {  // toward the sun's side (+x) and away
          const glm::dvec3 direction = reference::enuFromZenithAzimuth(viewZenith, azimuth);
          const ReferenceRadiance result = renderer.radiance({0.0, 0.0, r}, direction, uint64_t(checked));
          for (const auto* v : {&result.sunDisc, &result.singleScattering, &result.multipleScattering,
                                &result.multipleScatteringStandardError})
            for (double x : *v) {
              ASSERT_TRUE(std::isfinite(x) && x >= 0.0)
                  << x << " at sun zenith " << sunZenith << ", height " << height << ", view zenith " << viewZenith;
            }
          for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(result.xyz[c]) && result.xyz[c] >= 0.0);
          ++checked;
        }
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(ReferenceRadiance, MonteCarloErrorShrinksAsOneOverSquareRootOfSamples) {
  // 16x the samples: the standard error falls 4x (accepted 3..5.3, summed over 6 directions to
  // steady the estimates), and the two means agree within 4 combined standard errors.
  AtmosphereSettings settings;
  const glm::dvec3 sun = reference::enuFromZenithAzimuth(40.0 * kDegree, 0.0);
  double se64 = 0.0, se1024 = 0.0;
  for (int spp : {64, 1024}) {
    ReferenceQuality q;
    q.samplesPerPixel = spp;
    q.wavelengthCount = 12;
    q.threads = 1;
    q.singleScattering = false;
    q.sunDisc = false;
    const ReferenceRenderer renderer(settings, sun, q);
    ReferenceQuality q2 = q;
    q2.samplesPerPixel = 64;
    q2.seed = 99;
    const ReferenceRenderer other(settings, sun, q2);
    for (int k = 0; k < 6; ++k) {
      const glm::dvec3 direction = reference::enuFromZenithAzimuth((20.0 + 12.0 * k) * kDegree, 0.9 * k);
      const ReferenceRadiance r = renderer.radiance({0.0, 0.0, settings.bottomRadius + 2.0}, direction, uint64_t(k));
      (spp == 64 ? se64 : se1024) += r.luminanceStandardError;
      if (spp == 1024) {
        const ReferenceRadiance small = other.radiance({0.0, 0.0, settings.bottomRadius + 2.0}, direction, uint64_t(k));
        const double combined = std::hypot(r.luminanceStandardError, small.luminanceStandardError);
        EXPECT_NEAR(small.luminance(), r.luminance(), 4.0 * combined) << k;
        EXPECT_GT(r.luminance(), 0.0);
      }
    }
  }
  EXPECT_GT(se64 / se1024, 3.0);
  EXPECT_LT(se64 / se1024, 5.3);
}

TEST(ReferenceRadiance, DeterministicForASeedAndIndependentOfThreads) {
  const AtmosphereSettings settings;
  const glm::dvec3 sun = reference::enuFromZenithAzimuth(50.0 * kDegree, 1.0);
  shared::CameraParameters camera{};
  shared::cameraBasis(0.8, 0.1, 0.0, camera.forward, camera.right, camera.up);
  camera.fov = 1.2;
  camera.projection = shared::kProjectionPerspective;
  camera.width = 12;
  camera.height = 8;
  auto render = [&](int threads, uint64_t seed) {
    ReferenceQuality q;
    q.samplesPerPixel = 4;
    q.wavelengthCount = 9;
    q.threads = threads;
    q.seed = seed;
    const ReferenceRenderer renderer(settings, sun, q);
    return renderReferenceImage(renderer, settings.bottomRadius + 2.0, camera);
  };
  const ReferenceImage one = render(1, 5), three = render(3, 5), again = render(3, 5), other = render(2, 6);
  ASSERT_EQ(one.image.pixels.size(), three.image.pixels.size());
  EXPECT_EQ(one.image.pixels, three.image.pixels);
  EXPECT_EQ(three.image.pixels, again.image.pixels);
  EXPECT_EQ(one.luminanceStandardError, three.luminanceStandardError);
  EXPECT_NE(one.image.pixels, other.image.pixels);
  for (float v : one.image.pixels) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
}

TEST(ReferenceRadiance, DirectionListMatchesSingleRadianceCalls) {
  const AtmosphereSettings settings;
  ReferenceQuality q;
  q.samplesPerPixel = 4;
  q.wavelengthCount = 6;
  q.threads = 2;
  const glm::dvec3 sun = reference::enuFromZenithAzimuth(30.0 * kDegree, 0.5 * kPi);
  const ReferenceRenderer renderer(settings, sun, q);
  const double radius = settings.bottomRadius + 2.0;
  const std::vector<ViewDirection> directions = {{0.0, 0.0}, {0.5, 1.0}, {1.2, 4.0}, {1.5, 0.5 * kPi}};
  const std::vector<ReferenceRadiance> list = renderReferenceDirections(renderer, radius, directions);
  ASSERT_EQ(list.size(), directions.size());
  for (size_t k = 0; k < directions.size(); ++k) {
    const ReferenceRadiance single = renderer.radiance(
        {0.0, 0.0, radius}, reference::enuFromZenithAzimuth(directions[k].zenith, directions[k].azimuth), k);
    EXPECT_EQ(list[k].total(), single.total());
  }
  // Azimuth clockwise from north: 90 degrees is east (+x).
  const glm::dvec3 east = reference::enuFromZenithAzimuth(0.5 * kPi, 0.5 * kPi);
  EXPECT_NEAR(east.x, 1.0, 1e-15);
  EXPECT_NEAR(east.y, 0.0, 1e-15);
}

}  // namespace
}  // namespace firmament
