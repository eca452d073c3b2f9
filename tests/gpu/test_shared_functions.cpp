// One source of physics: shaders/common/geometry.glsl runs on the GPU in float
// (shaders/gpu/shared_functions_test.comp) and here in double, on the same inputs (the float inputs
// widened exactly), and the two must agree within the forward error bound of the float formulas.
//
// Tolerance, derived per sample for each sphere of radius R (ε = 2⁻²⁴, b = r mu, c = (r − R)(r + R)):
//   Δ = (R − r)(R + r) + b²:   |δΔ| ≤ 4ε (b² + |c|)       (each product and sum rounds once; R − r exact)
//   s = √max(Δ, 0):            |δs| ≤ min(δΔ / 2s, √δΔ) + ε s
//   root as a sum |b| + s:     |δt| ≤ δs + 2ε (|b| + s)
//   root as c / q, |q| = |b|+s: |δt| ≤ |t| (4ε + (δs + 2ε (|b| + s)) / |q|)
// The test allows 8× that bound (Vulkan lets sqrt and division be off by 2.5 ulp, and a driver may
// fuse multiply-adds). Away from tangency the bound is a few ε relative (~1e-6); within ~1e-5 rad of
// grazing, δΔ / 2s grows as the problem itself becomes ill-conditioned, and the bound follows it.
// Booleans (hits ground, hits shell) are compared only where Δ is farther from 0 than its error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "common/geometry.glsl"
#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/pipeline.h"
#include "tests/support/gpu_test.h"

namespace firmament::gpu {
namespace {

constexpr float kBottom = 6360e3f, kTop = 6420e3f, kShellInner = 6361.5e3f, kShellOuter = 6364e3f;
constexpr double kEpsilon = 1.0 / (1 << 24);
constexpr double kSafety = 8.0;

struct Push {
  float bottomRadius, topRadius, shellInner, shellOuter;
  uint32_t count;
};

// Error bounds of the float evaluation for one sphere (see the top of the file).
struct SphereErrors {
  double discriminant = 0;      // |δΔ|
  double sum = 0;               // a root formed as |b| + s
  double quotientRelative = 0;  // relative error of a root formed as c / q
  double root(double t, bool formedAsSum) const { return formedAsSum ? sum : std::abs(t) * quotientRelative; }
  double anyRoot(double t) const { return std::max(sum, std::abs(t) * quotientRelative); }
};

SphereErrors sphereErrors(double r, double mu, double radius) {
  double b = r * mu, c = (r - radius) * (r + radius);
  double delta = b * b - c;
  SphereErrors e;
  e.discriminant = 4 * kEpsilon * (b * b + std::abs(c));
  double s = std::sqrt(std::max(delta, 0.0));
  double ds = (s > 0 ? std::min(e.discriminant / (2 * s), std::sqrt(e.discriminant)) : std::sqrt(e.discriminant)) +
              kEpsilon * s;
  e.sum = ds + 2 * kEpsilon * (std::abs(b) + s);
  double q = std::abs(b) + s;
  e.quotientRelative = 4 * kEpsilon + (q > 0 ? e.sum / q : 1.0);
  return e;
}

std::vector<glm::vec2> makeInputs() {
  std::mt19937_64 rng(20170101);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto logUniform = [&](double lo, double hi) { return std::exp(std::log(lo) + unit(rng) * std::log(hi / lo)); };
  auto grazing = [&](double r, double radius) {  // within 1e-5 rad of the tangent to the sphere
    double muTangent = -std::sqrt(std::max(0.0, 1.0 - (radius / r) * (radius / r)));
    return std::cos(std::acos(muTangent) + (unit(rng) * 2 - 1) * 1e-5);
  };
  std::vector<glm::vec2> inputs;
  auto add = [&](double r, double mu) { inputs.emplace_back(float(r), float(std::clamp(mu, -1.0, 1.0))); };
  for (int i = 0; i < 2000; ++i) add(logUniform(6360e3, 1e8), unit(rng) * 2 - 1);         // anywhere
  for (int i = 0; i < 1000; ++i) add(kBottom + logUniform(0.1, 1e5), unit(rng) * 2 - 1);  // near the ground
  for (int i = 0; i < 1000; ++i) {  // grazing the ground, from low and from far
    double r = i % 2 ? kBottom + logUniform(0.1, 1e5) : logUniform(6360e3, 1e8);
    add(r, grazing(r, kBottom));
  }
  for (int i = 0; i < 500; ++i) {  // grazing the top of the atmosphere from space
    double r = logUniform(6420e3, 1e8);
    add(r, grazing(r, kTop));
  }
  for (float radius : {kShellInner, kShellOuter})
    for (int i = 0; i < 500; ++i) {  // grazing each side of the cloud shell from above it
      double r = radius + logUniform(0.1, 1e6);
      add(r, grazing(r, radius));
    }
  for (int i = 0; i < 500; ++i)  // horizontal rays inside the atmosphere and the shell
    add(kBottom + logUniform(0.1, 6e4), (unit(rng) * 2 - 1) * 1e-5);
  for (float r : {kBottom, kShellInner, kShellOuter, kTop, 1e8f})
    for (double mu : {-1.0, -0.5, -1e-6, 0.0, 1e-6, 0.5, 1.0}) add(r, mu);
  return inputs;
}

class SharedFunctionsTest : public test::GpuTest {};

TEST_F(SharedFunctionsTest, GeometryAgreesBetweenGpuFloatAndCpuDouble) {
  Context& gpu = context();
  std::vector<glm::vec2> inputs = makeInputs();
  const uint32_t count = uint32_t(inputs.size());
  ComputePipeline pipeline(gpu, {.shader = "gpu/shared_functions_test",
                                 .bindings = {BindingType::StorageBuffer, BindingType::StorageBuffer},
                                 .pushConstantSize = sizeof(Push)});
  Buffer inputBuffer(gpu, count * sizeof(glm::vec2), BufferUsage::Storage);
  inputBuffer.upload(inputs);
  Buffer outputBuffer(gpu, count * 8 * sizeof(float), BufferUsage::Storage);
  CommandList list(gpu);
  list.bind(pipeline, {inputBuffer, outputBuffer});
  list.pushConstants(Push{kBottom, kTop, kShellInner, kShellOuter, count});
  list.dispatch((count + 63) / 64);
  list.submitAndWait();
  std::vector<float> out = outputBuffer.download<float>();

  double worstRatio = 0, worstBulkRelative = 0;
  int compared = 0, ambiguousGround = 0, ambiguousShell = 0;
  auto check = [&](const char* what, size_t i, double gpuValue, double cpuValue, double bound) {
    ASSERT_TRUE(std::isfinite(gpuValue)) << what << " sample " << i;
    double error = std::abs(gpuValue - cpuValue);
    double allowed = kSafety * bound + 1e-30;
    worstRatio = std::max(worstRatio, error / allowed);
    ++compared;
    ASSERT_LE(error, allowed) << what << " sample " << i << ": r = " << inputs[i].x << ", mu = " << inputs[i].y
                              << ", gpu " << gpuValue << ", cpu " << cpuValue << ", bound " << bound;
  };

  for (size_t i = 0; i < count; ++i) {
    double r = inputs[i].x, mu = inputs[i].y;
    const float* g = &out[8 * i];
    SphereErrors bottom = sphereErrors(r, mu, kBottom), top = sphereErrors(r, mu, kTop);
    SphereErrors inner = sphereErrors(r, mu, kShellInner), outer = sphereErrors(r, mu, kShellOuter);

    double dTop = shared::distanceToTopAtmosphereBoundary(r, mu, kTop);
    check("distanceToTopAtmosphereBoundary", i, g[0], dTop, top.root(dTop, mu <= 0));
    double dBottom = shared::distanceToBottomAtmosphereBoundary(r, mu, kBottom);
    check("distanceToBottomAtmosphereBoundary", i, g[1], dBottom, bottom.root(dBottom, false));
    double discriminant = shared::sphereDiscriminant(r, mu, kBottom);
    check("sphereDiscriminant", i, g[7], discriminant, bottom.discriminant);
    for (int k = 0; k < 7; ++k) ASSERT_GE(g[k], 0.0f) << "output " << k << " sample " << i;
    if (std::abs(mu) < 0.5 && std::abs(shared::sphereDiscriminant(r, mu, kTop)) > 1e3 * top.discriminant) {
      worstBulkRelative = std::max(worstBulkRelative, std::abs(g[0] - dTop) / std::max(dTop, 1.0));
    }

    bool ground = shared::rayIntersectsGround(r, mu, kBottom);
    if (std::abs(discriminant) <= kSafety * bottom.discriminant) {
      ++ambiguousGround;  // tangent to within float precision: either answer is right
    } else {
      ASSERT_EQ(g[2] != 0.0f, ground) << "rayIntersectsGround sample " << i << ": r = " << r << ", mu = " << mu;
      double nearest = shared::distanceToNearestAtmosphereBoundary(r, mu, kBottom, kTop, ground);
      check("distanceToNearestAtmosphereBoundary", i, g[3], nearest,
            ground ? bottom.root(nearest, false) : top.root(nearest, mu <= 0));
    }

    double enter = 0, exit = 0;
    bool shell = shared::rayShellSegment(r, mu, kShellInner, kShellOuter, enter, exit);
    // Bound from the spheres the ray clearly hits; a clear miss contributes exact zeros on both sides.
    double shellBound = 0;
    bool tangent = false;
    for (auto [radius, errors] : {std::pair{kShellInner, inner}, std::pair{kShellOuter, outer}}) {
      double delta = shared::sphereDiscriminant(r, mu, radius);
      tangent |= std::abs(delta) <= kSafety * errors.discriminant;
      if (delta > 0) shellBound = std::max({shellBound, errors.anyRoot(enter), errors.anyRoot(exit)});
    }
    tangent |= shell && exit - enter <= kSafety * shellBound;  // a segment of length ~0 may vanish in float
    if (tangent) {
      ++ambiguousShell;
    } else {
      ASSERT_EQ(g[4] != 0.0f, shell) << "rayShellSegment sample " << i << ": r = " << r << ", mu = " << mu;
      check("rayShellSegment enter", i, g[5], enter, shellBound);
      check("rayShellSegment exit", i, g[6], exit, shellBound);
    }
  }
  std::printf(
      "%u samples, %d comparisons; worst error / allowed = %.3f; worst relative error of the top "
      "distance away from tangency = %.2e; tangent within float precision (booleans not compared): "
      "ground %d, shell %d\n",
      count, compared, worstRatio, worstBulkRelative, ambiguousGround, ambiguousShell);
  EXPECT_LT(worstBulkRelative, 2e-6);
  // Grazing within 1e-5 rad is often undecidable in float from far away (mu itself is only good to
  // ~6e-8, ~1e-6 rad at r = 1e8 m); most grazing rays from near the ground are still decided.
  EXPECT_LT(ambiguousGround, 700);
  EXPECT_LT(ambiguousShell, 300);
}

// Why the stable forms: the textbook distance to the ground in float, −r mu − √(r²(mu² − 1) + R²),
// against the same double reference, on grazing rays just above the ground.
TEST(SharedFunctions, StableGroundDistanceBeatsTheTextbookFormInFloat) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worstStable = 0, worstTextbook = 0;
  for (int i = 0; i < 2000; ++i) {
    double h = std::exp(std::log(1.0) + unit(rng) * std::log(1e4));
    float r = float(kBottom + h);
    double muTangent = -std::sqrt(1.0 - (double(kBottom) / r) * (double(kBottom) / r));
    float mu = float(std::cos(std::acos(muTangent) - unit(rng) * 1e-3));  // just below the horizon
    double reference = shared::distanceToBottomAtmosphereBoundary(double(r), double(mu), double(kBottom));
    if (!(reference > 0)) continue;
    // The float path of the shader, written out: Δ and the c / q root.
    float b = r * mu;
    float stableDisc = (kBottom - r) * (kBottom + r) + b * b;
    float stable = (r - kBottom) * (r + kBottom) / (std::sqrt(std::max(stableDisc, 0.0f)) - b);
    float textbookDisc = r * r * (mu * mu - 1.0f) + kBottom * kBottom;
    float textbook = -r * mu - std::sqrt(std::max(textbookDisc, 0.0f));
    worstStable = std::max(worstStable, std::abs(stable - reference) / reference);
    worstTextbook = std::max(worstTextbook, std::abs(textbook - reference) / reference);
  }
  std::printf("grazing ground distance in float, worst relative error: stable %.2e, textbook %.2e\n", worstStable,
              worstTextbook);
  EXPECT_LT(worstStable, 1e-3);
  EXPECT_GT(worstTextbook, 100 * worstStable);
}

TEST(SharedFunctions, RayRadiusAndCosine) {
  double r = 0, mu = 0;
  shared::rayRadiusAndCosine(glm::dvec3(0, 0, 6371e3), glm::dvec3(1, 0, 0), r, mu);
  EXPECT_DOUBLE_EQ(r, 6371e3);
  EXPECT_DOUBLE_EQ(mu, 0.0);
  shared::rayRadiusAndCosine(glm::dvec3(3, 4, 0), glm::dvec3(0.6, 0.8, 0), r, mu);
  EXPECT_DOUBLE_EQ(r, 5.0);
  EXPECT_DOUBLE_EQ(mu, 1.0);
}

}  // namespace
}  // namespace firmament::gpu
