// The droplets' phase function (common/cloud_lighting.glsl cloudPhase): dual Henyey-Greenstein and
// Jendersie and d'Eon 2023's approximate Mie (HG + Draine), and the path tracer's sampler for both.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "clouds/cloud_settings.h"
#include "clouds/reference_clouds.h"
#include "common/cloud_lighting.glsl"
#include "core/error.h"
#include "core/scene.h"

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;

CloudLightingSettings approximateMie(double d) {
  CloudLightingSettings l;
  l.phase = CloudPhaseModel::ApproximateMie;
  l.dropletDiameter_um = d;
  const glm::dvec4 lobes = shared::cloudApproximateMie(d);
  l.gForward = lobes.x, l.gBack = lobes.y, l.backWeight = lobes.z, l.alpha = lobes.w;
  return l;
}

double phase(const CloudLightingSettings& l, double nu) {
  return shared::cloudPhase(l.gForward, l.gBack, l.backWeight, l.alpha, nu);
}

// 2 pi times the integral of the phase over nu in [a, b], by the midpoint rule in the scattering angle
// on a grid that crowds towards theta = 0 (the 20 um forward peak, g = 0.995, is ~0.6 degrees wide).
double integral(const CloudLightingSettings& l, double thetaFrom, double thetaTo) {
  const int n = 200000;
  double sum = 0.0;
  const double s0 = std::sqrt(thetaFrom), s1 = std::sqrt(thetaTo);
  for (int i = 0; i < n; ++i) {
    const double u0 = s0 + (s1 - s0) * i / n, u1 = s0 + (s1 - s0) * (i + 1) / n;
    const double t0 = u0 * u0, t1 = u1 * u1, t = 0.5 * (t0 + t1);
    sum += phase(l, std::cos(t)) * std::sin(t) * (t1 - t0);
  }
  return 2.0 * kPi * sum;
}

// Normalised (1/sr): the integral over the sphere is 1 for both models, at the fit's range ends.
TEST(CloudPhase, NormalisedForBothModels) {
  CloudLightingSettings dual;  // 0.8, -0.3, 0.3
  EXPECT_NEAR(integral(dual, 0.0, kPi), 1.0, 1e-6);
  for (double d : {5.0, 20.0, 50.0}) EXPECT_NEAR(integral(approximateMie(d), 0.0, kPi), 1.0, 1e-5) << d;
}

// Draine's lobe with alpha = 0 is the Henyey-Greenstein lobe; the approximate Mie's fits at 20 um have
// the published behaviour: a narrow forward HG lobe (g_HG > 0.99), a broad Draine lobe, about half the weight each.
TEST(CloudPhase, DraineReducesToHenyeyGreensteinAndTheFitIsInRange) {
  for (double nu : {-1.0, -0.3, 0.0, 0.5, 0.99, 1.0})
    EXPECT_DOUBLE_EQ(shared::drainePhase(0.6, 0.0, nu), shared::henyeyGreensteinPhase(0.6, nu));
  const CloudLightingSettings mie = approximateMie(20.0);
  EXPECT_GT(mie.gForward, 0.99);
  EXPECT_GT(mie.gBack, 0.5);
  EXPECT_LT(mie.gBack, 0.7);
  EXPECT_NEAR(mie.backWeight, 0.5, 0.05);
  EXPECT_GT(mie.alpha, 10.0);
  // More forward than the dual-HG default inside 5 degrees (the diffraction peak), and a backward glory-like rise
  // from 160 to 180 degrees that HG lobes lack (Draine's 1 + alpha nu^2).
  EXPECT_GT(integral(mie, 0.0, 5.0 * kPi / 180.0), integral(CloudLightingSettings{}, 0.0, 5.0 * kPi / 180.0));
  EXPECT_GT(phase(mie, -1.0), phase(mie, std::cos(160.0 * kPi / 180.0)));
}

// The path tracer's sampler draws cosines with the phase's own density: binned frequencies of 400 000
// draws against the integral of the phase over each bin (within 5 standard deviations of a binomial count).
TEST(CloudPhase, PathTracerSamplesThePhaseExactly) {
  for (const CloudLightingSettings& l : {CloudLightingSettings{}, approximateMie(20.0), approximateMie(5.0)}) {
    const int draws = 400000, bins = 24;
    std::vector<int> count(bins, 0);
    reference::Random random(11, 0);
    for (int i = 0; i < draws; ++i) {
      const double nu = sampleCloudPhaseCosine(l, random);
      ASSERT_TRUE(nu >= -1.0 && nu <= 1.0);
      // Bins equal in the angle, so the forward peak gets its own.
      const int b = std::min(int(std::acos(nu) / kPi * bins), bins - 1);
      ++count[b];
    }
    for (int b = 0; b < bins; ++b) {
      const double p = integral(l, kPi * b / bins, kPi * (b + 1) / bins);
      const double expected = p * draws, sigma = std::sqrt(draws * p * (1.0 - p));
      EXPECT_NEAR(count[b], expected, 5.0 * sigma + 1.0) << "alpha " << l.alpha << " bin " << b;
    }
  }
}

// The scene: "approximate_mie" fills the lobes from the droplet diameter; unknown names and diameters
// outside the fit's 5-50 um are refused.
TEST(CloudPhase, SceneSelectsTheModel) {
  const std::string text =
      R"({"clouds": {"layers": [{"kind": "cumulus"}], "lighting": {"phase": "approximate_mie", "droplet_diameter_um": 30}}})";
  const CloudSettings s = CloudSettings::fromScene(Scene::parse(text, "<phase>"));
  EXPECT_EQ(s.lighting.phase, CloudPhaseModel::ApproximateMie);
  EXPECT_DOUBLE_EQ(s.lighting.gForward, shared::cloudApproximateMie(30.0).x);
  EXPECT_DOUBLE_EQ(s.lighting.alpha, shared::cloudApproximateMie(30.0).w);
  const CloudSettings dual =
      CloudSettings::fromScene(Scene::parse(R"({"clouds": {"layers": [{"kind": "cumulus"}]}})", "<phase>"));
  EXPECT_EQ(dual.lighting.phase, CloudPhaseModel::DualHenyeyGreenstein);
  EXPECT_EQ(dual.lighting.alpha, 0.0);
  EXPECT_THROW(Scene::parse(R"({"clouds": {"lighting": {"phase": "mie"}}})", "<phase>"), InputError);
  EXPECT_THROW(Scene::parse(R"({"clouds": {"lighting": {"droplet_diameter_um": 60}}})", "<phase>"), InputError);
}

}  // namespace
}  // namespace firmament
