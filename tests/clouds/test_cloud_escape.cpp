// The escape function of a thick conservatively scattering layer (common/cloud_lighting.glsl
// cloudEscapeFunction, cloudEscapeCorrection, cloudTopEntryWeight) against Chandrasekhar's H function
// for albedo 1, solved here in double: K(mu) = (sqrt 3 / 4) H(mu).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "common/cloud_lighting.glsl"

namespace firmament {
namespace {

// H(mu) for isotropic conservative scattering from 1 / H(mu) = (1/2) integral_0^1 mu' H(mu') / (mu + mu')
// dmu' (Chandrasekhar 1960, the form that converges for albedo 1), by damped fixed-point iteration on a
// 64-point Gauss-Legendre rule over [0, 1].
class HFunction {
 public:
  HFunction() {
    const int n = 64;
    for (int i = 1; i <= n; ++i) {  // Legendre roots by Newton's method
      double z = std::cos(M_PI * (i - 0.25) / (n + 0.5)), dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p1 = 1.0, p2 = 0.0;
        for (int j = 1; j <= n; ++j) {
          const double p3 = p2;
          p2 = p1;
          p1 = ((2.0 * j - 1.0) * z * p2 - (j - 1.0) * p3) / j;
        }
        dp = n * (z * p1 - p2) / (z * z - 1.0);
        const double step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-15) break;
      }
      nodes_.push_back(0.5 * (1.0 - z));
      weights_.push_back(1.0 / ((1.0 - z * z) * dp * dp));  // (2 / ((1 - z^2) P'^2)) / 2 for [0, 1]
    }
    h_.assign(nodes_.size(), 1.0);
    for (int it = 0; it < 3000; ++it)
      for (size_t k = 0; k < h_.size(); ++k) h_[k] = 0.5 * h_[k] + 0.5 * (*this)(nodes_[k]);
  }
  double operator()(double mu) const {
    double s = 0.0;
    for (size_t k = 0; k < nodes_.size(); ++k) s += weights_[k] * nodes_[k] * h_[k] / (mu + nodes_[k]);
    return 2.0 / s;
  }
  // The first moment integral_0^1 H mu dmu (2 / sqrt 3 for albedo 1).
  double firstMoment() const {
    double s = 0.0;
    for (size_t k = 0; k < nodes_.size(); ++k) s += weights_[k] * nodes_[k] * (*this)(nodes_[k]);
    return s;
  }

 private:
  std::vector<double> nodes_, weights_, h_;
};

TEST(CloudEscape, SolvedHFunctionMatchesChandrasekharsTable) {
  const HFunction h;
  // Chandrasekhar (1960), Table for the isotropic conservative H function.
  const std::array<std::pair<double, double>, 5> table = {
      {{0.1, 1.2474}, {0.3, 1.6425}, {0.5, 2.0128}, {0.8, 2.5527}, {1.0, 2.9078}}};
  for (const auto& [mu, value] : table) EXPECT_NEAR(h(mu), value, 2e-4) << mu;
  EXPECT_NEAR(h.firstMoment(), 2.0 / std::sqrt(3.0), 1e-9);
}

TEST(CloudEscape, FunctionIsTheHFunctionsToOnePercent) {
  const HFunction h;
  double worst = 0.0, worstEddington = 0.0, moment = 0.0;
  const int n = 1000;
  for (int i = 1; i <= n; ++i) {
    const double mu = (i - 0.5) / n;
    const double exact = std::sqrt(3.0) / 4.0 * h(mu);
    worst = std::max(worst, std::abs(shared::cloudEscapeFunction(mu) / exact - 1.0));
    worstEddington = std::max(worstEddington, std::abs((0.5 + 0.75 * mu) / exact - 1.0));
    moment += 2.0 * shared::cloudEscapeFunction(mu) * mu / n;
  }
  std::printf("escape function: worst relative error %.4f (the Eddington factor's: %.4f); 2 int K mu dmu = %.5f\n",
              worst, worstEddington, moment);
  EXPECT_LT(worst, 0.01);
  EXPECT_GT(worstEddington, 0.1);  // what it replaces: 15 % at the horizon
  EXPECT_NEAR(moment, 1.0, 2e-3);  // normalised like the exact one
  // The correction of the Eddington floor is the ratio of the two, finite and positive everywhere.
  const double exact087 = std::sqrt(3.0) / 4.0 * h(0.087) / (0.5 + 0.75 * 0.087);
  EXPECT_NEAR(shared::cloudEscapeCorrection(0.087), exact087, 0.01);
  for (double mu : {-1.0, 0.0, 1e-8, 0.5, 1.0, 2.0}) {
    EXPECT_TRUE(std::isfinite(shared::cloudEscapeCorrection(mu))) << mu;
    EXPECT_GT(shared::cloudEscapeCorrection(mu), 0.8) << mu;
    EXPECT_LT(shared::cloudEscapeCorrection(mu), 1.05) << mu;
  }
}

TEST(CloudEscape, TopEntryWeightIsOneAtTheZenithAndFallsWithTheSun) {
  EXPECT_NEAR(shared::cloudTopEntryWeight(1.0), 1.0, 1e-12);
  EXPECT_EQ(shared::cloudTopEntryWeight(0.0), 0.0);
  EXPECT_EQ(shared::cloudTopEntryWeight(-0.3), 0.0);  // sun below the horizon
  double previous = 0.0;
  for (int i = 1; i <= 100; ++i) {
    const double w = shared::cloudTopEntryWeight(i / 100.0);
    EXPECT_GT(w, previous) << i;
    EXPECT_LE(w, 1.0 + 1e-12) << i;
    previous = w;
  }
}

}  // namespace
}  // namespace firmament
