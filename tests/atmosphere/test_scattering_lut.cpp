// Bruneton 2017's table parametrizations (shaders/common/scattering_lut.glsl), run on the CPU in
// double: texel -> (r, mu, mu_s, nu) -> texture coordinates gives back the texel, and
// (r, mu, mu_s, nu) -> coordinates -> (r, mu, mu_s, nu) gives back the parameters, for Earth.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "atmosphere/atmosphere_settings.h"
#include "atmosphere/atmosphere_spectra.h"
#include "common/scattering_lut.glsl"

namespace firmament {
namespace {

using shared::ScatteringTableSize;

shared::AtmosphereParameters earth() { return atmosphereParametersAt(AtmosphereSettings{}, kDefaultWavelengthsNm); }

constexpr ScatteringTableSize kSize{8, 32, 128, 32};  // Bruneton's defaults

// Every texel of the default table: its parameters map back to its own coordinates. Tolerance 1e-9
// in unit coordinates, except on the mu axis where 1e-5 (a thousandth of a texel): for the texel next
// to the horizon, d is within a texel of the grazing distance rho, where d(mu) has a square-root
// singularity (dd/dmu infinite), so mu(d) -> d loses about half of double's digits.
// Excluded: the ground half of the bottom layer (r = R_b), where every ground ray has length 0 and
// the whole half stands for one ray (its radiance is 0 whichever texel is read).
TEST(ScatteringLut, EveryTexelRoundTrips) {
  const auto atmosphere = earth();
  double worst = 0.0;
  for (int z = 0; z < kSize.r; ++z)
    for (int y = 0; y < kSize.mu; ++y)
      for (int x = 0; x < kSize.nu * kSize.mu_s; ++x) {
        if (z == 0 && y < kSize.mu / 2) continue;
        glm::dvec4 uvwz = shared::scatteringUvwzFromTexel(kSize, glm::ivec3(x, y, z));
        double r, mu, mu_s, nu;
        bool hitsGround;
        shared::rMuMuSNuFromScatteringUvwz(atmosphere, kSize, uvwz, r, mu, mu_s, nu, hitsGround);
        glm::dvec4 back = shared::scatteringUvwzFromRMuMuSNu(atmosphere, kSize, r, mu, mu_s, nu, hitsGround);
        for (int i : {0, 1, 3}) worst = std::max(worst, std::abs(back[i] - uvwz[i]));
        ASSERT_LT(std::abs(back.z - uvwz.z), 1e-5) << "texel " << x << "," << y << "," << z << " mu " << mu;
      }
  EXPECT_LT(worst, 1e-9);
}

// Random parameters inside the domain: the inverse recovers them. Tolerances: r within 1 mm, mu and
// mu_s within 1e-9 (cosines from distances of ~1e6 m in double). Near-grazing rays are excluded
// where the ground flag itself is ill-conditioned (|discriminant| tiny).
TEST(ScatteringLut, ParametersRoundTrip) {
  const auto atmosphere = earth();
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    double r = atmosphere.bottom_radius + unit(rng) * (atmosphere.top_radius - atmosphere.bottom_radius);
    double mu = 2.0 * unit(rng) - 1.0;
    double mu_s = atmosphere.mu_s_min + unit(rng) * (1.0 - atmosphere.mu_s_min);
    double nu = 2.0 * unit(rng) - 1.0;
    bool hitsGround = shared::rayIntersectsGround(atmosphere, r, mu);
    glm::dvec4 uvwz = shared::scatteringUvwzFromRMuMuSNu(atmosphere, kSize, r, mu, mu_s, nu, hitsGround);
    for (int k = 0; k < 4; ++k) ASSERT_TRUE(uvwz[k] >= 0.0 && uvwz[k] <= 1.0) << k;
    ASSERT_EQ(uvwz.z < 0.5, hitsGround);
    double r2, mu2, mu_s2, nu2;
    bool hits2;
    shared::rMuMuSNuFromScatteringUvwz(atmosphere, kSize, uvwz, r2, mu2, mu_s2, nu2, hits2);
    EXPECT_EQ(hits2, hitsGround);
    EXPECT_NEAR(r2, r, 1e-3);
    EXPECT_NEAR(mu_s2, mu_s, 1e-9);
    EXPECT_NEAR(nu2, nu, 1e-12);
    if (std::abs(shared::sphereDiscriminant(r, mu, atmosphere.bottom_radius)) > 1e6) {
      EXPECT_NEAR(mu2, mu, 1e-9) << "r " << r << " mu " << mu;
      ++checked;
    }
  }
  EXPECT_GT(checked, 190000);
}

// The mu axis: ground rays fill [0, 0.5), sky rays (0.5, 1], each decreasing with mu from the
// vertical at the middle to the horizon at the ends; mu_s: increasing, the first texel centre at
// mu_s_min = cos(108 deg), so twilight is covered.
TEST(ScatteringLut, AxesAreMonotoneAndCoverTwilight) {
  const auto atmosphere = earth();
  EXPECT_NEAR(std::acos(atmosphere.mu_s_min) * 180.0 / shared::kPi, 108.0, 1e-9);  // end of astronomical twilight
  const double r = atmosphere.bottom_radius + 1000.0;
  double previous = 2.0;
  bool previousHits = true;
  for (double mu = -1.0; mu <= 1.0; mu += 1e-3) {
    bool hitsGround = shared::rayIntersectsGround(atmosphere, r, mu);
    double u = shared::scatteringUvwzFromRMuMuSNu(atmosphere, kSize, r, mu, 0.5, 0.0, hitsGround).z;
    EXPECT_EQ(u < 0.5, hitsGround) << mu;
    if (hitsGround == previousHits) {
      EXPECT_LT(u, previous) << mu;
    }
    previous = u;
    previousHits = hitsGround;
  }
  previous = -1.0;
  for (double mu_s = atmosphere.mu_s_min; mu_s <= 1.0; mu_s += 1e-3) {
    double u = shared::scatteringUvwzFromRMuMuSNu(atmosphere, kSize, r, 0.5, mu_s, 0.0, false).y;
    EXPECT_GT(u, previous) << mu_s;
    previous = u;
  }
  double atMin = shared::scatteringUvwzFromRMuMuSNu(atmosphere, kSize, r, 0.5, atmosphere.mu_s_min, 0.0, false).y;
  EXPECT_NEAR(atMin, 0.5 / kSize.mu_s, 1e-9);
  double atZenith = shared::scatteringUvwzFromRMuMuSNu(atmosphere, kSize, r, 0.5, 1.0, 0.0, false).y;
  EXPECT_NEAR(atZenith, 1.0 - 0.5 / kSize.mu_s, 1e-9);
}

// A texel's nu is clamped to the cone that its mu and mu_s allow.
TEST(ScatteringLut, TexelNuIsGeometricallyPossible) {
  const auto atmosphere = earth();
  for (int y = 0; y < kSize.mu; y += 7)
    for (int x = 0; x < kSize.nu * kSize.mu_s; x += 3) {
      double r, mu, mu_s, nu;
      bool hitsGround;
      shared::scatteringTexelParameters(atmosphere, kSize, glm::ivec3(x, y, 5), r, mu, mu_s, nu, hitsGround);
      double spread = std::sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s));
      EXPECT_GE(nu, mu * mu_s - spread - 1e-12);
      EXPECT_LE(nu, mu * mu_s + spread + 1e-12);
    }
}

TEST(ScatteringLut, IrradianceTexelsRoundTrip) {
  const auto atmosphere = earth();
  const glm::ivec2 size(64, 16);
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      glm::dvec2 uv((x + 0.5) / size.x, (y + 0.5) / size.y);
      double r, mu_s;
      shared::rMuSFromIrradianceUv(atmosphere, uv, size, r, mu_s);
      glm::dvec2 back = shared::irradianceUvFromRMuS(atmosphere, r, mu_s, size);
      EXPECT_NEAR(back.x, uv.x, 1e-12);
      EXPECT_NEAR(back.y, uv.y, 1e-12);
    }
  double r, mu_s;
  shared::rMuSFromIrradianceUv(atmosphere, glm::dvec2(0.5 / size.x, 0.5 / size.y), size, r, mu_s);
  EXPECT_DOUBLE_EQ(r, atmosphere.bottom_radius);
  EXPECT_DOUBLE_EQ(mu_s, -1.0);
}

}  // namespace
}  // namespace firmament
