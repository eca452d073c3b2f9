// One source of physics for the night: shaders/common/moon_disc.glsl and night_sky.glsl run on the GPU in
// float (shaders/gpu/night_functions_test.comp) and here in double, on the same inputs (the float inputs
// widened exactly). The functions are smooth products, quotients and transcendentals of well-scaled
// arguments, so float agrees to a few 1e-6 relative where the built-ins are exact to a few ulp; lavapipe's
// sin, cos and atan are polynomial fits good to ~1e-5 (its measured worst below), so the test allows 1e-3
// relative, and skips only the samples within 1e-3 of a discontinuity (the disc's limb and terminator, an
// airglow band's edge). The disc's per-frame constants (C and the earthshine: the disc-integrated phase law
// cancels catastrophically in float near new Moon) come from the CPU in double, as in the renderer.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "common/moon_disc.glsl"
#include "common/night_sky.glsl"
#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/pipeline.h"
#include "tests/support/gpu_test.h"

namespace firmament::gpu {
namespace {

struct Push {
  float angularRadius, observerRadius, planetRadius;
  uint32_t count;
};

class NightFunctionsTest : public test::GpuTest {};

TEST_F(NightFunctionsTest, MoonDiscAndNightSkyAgreeBetweenGpuFloatAndCpuDouble) {
  const float rho = 0.0045f, observer = 6361.2e3f, planet = 6360e3f;
  std::mt19937_64 rng(38);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<glm::vec4> inputs;
  const int count = 4096;
  for (int i = 0; i < count; ++i) {
    glm::vec3 direction;
    if (i % 2 == 0) {  // around the Moon's disc, up to 1.2 radii
      const double r = 1.2 * std::sqrt(unit(rng)), phi = 2 * 3.14159265358979 * unit(rng);
      direction = glm::normalize(
          glm::vec3(float(r * std::cos(phi) * std::tan(rho)), float(r * std::sin(phi) * std::tan(rho)), 1.0f));
    } else {  // anywhere on the sphere
      const double z = 2 * unit(rng) - 1, phi = 2 * 3.14159265358979 * unit(rng), s = std::sqrt(1 - z * z);
      direction = glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
    }
    const float wavelength = float(360.0 + 470.0 * unit(rng));
    inputs.emplace_back(direction, wavelength);
    const float alpha = float(3.1 * unit(rng));
    const double scale = shared::moonLitRadianceScale(0.3, rho, alpha);
    inputs.emplace_back(float(2 * unit(rng) - 1), alpha, float(scale),
                        float(shared::moonEarthshineRadiance(scale, alpha)));
  }
  ComputePipeline pipeline(context(), {.shader = "gpu/night_functions_test",
                                       .bindings = {BindingType::StorageBuffer, BindingType::StorageBuffer},
                                       .pushConstantSize = sizeof(Push)});
  Buffer inputBuffer(context(), inputs.size() * sizeof(glm::vec4), BufferUsage::Storage);
  inputBuffer.upload(inputs);
  Buffer outputBuffer(context(), size_t(count) * 4 * sizeof(float), BufferUsage::Storage);
  CommandList list(context());
  list.bind(pipeline, {inputBuffer, outputBuffer});
  list.pushConstants(Push{rho, observer, planet, uint32_t(count)});
  list.dispatch((uint32_t(count) + 63) / 64);
  list.submitAndWait();
  const std::vector<float> out = outputBuffer.download<float>();

  double worst[4] = {0, 0, 0, 0};
  int compared[4] = {0, 0, 0, 0};
  for (int i = 0; i < count; ++i) {
    const glm::dvec3 direction(inputs[2 * i].x, inputs[2 * i].y, inputs[2 * i].z);
    const double wavelength = inputs[2 * i].w, cosZenith = inputs[2 * i + 1].x, alpha = inputs[2 * i + 1].y;
    const glm::dvec3 moonDir(0, 0, 1), sunFromMoon(std::sin(alpha), 0.0, -std::cos(alpha));
    double cpu[4];
    cpu[0] =
        shared::moonDiscRadiance(direction, moonDir, sunFromMoon, rho, inputs[2 * i + 1].z, inputs[2 * i + 1].w, 1.0);
    cpu[1] = shared::airglowSpectralRadiance(wavelength, 10.0, cosZenith, observer, planet, 1.0);
    cpu[2] = shared::zodiacalSolarSpectrumFactor(direction);
    cpu[3] = shared::stellarBackgroundSolarSpectrumFactor(direction.z);
    // Near a discontinuity the two sides may fall differently: skip those samples.
    glm::dvec3 normal;
    double mu = 0, mu0 = 0;
    const double offset = glm::length(glm::cross(direction, moonDir)) / std::sin(double(rho));
    const bool onDisc = shared::moonDiscPoint(direction, moonDir, sunFromMoon, rho, normal, mu, mu0);
    const bool nearDiscEdge = std::abs(offset - 1.0) < 1e-3 || (onDisc && std::abs(mu0) < 1e-3);
    bool nearBandEdge = false;
    for (double line : {557.7, 589.3, 630.0, 636.4}) nearBandEdge |= std::abs(std::abs(wavelength - line) - 5.0) < 1e-3;
    for (int k = 0; k < 4; ++k) {
      if ((k == 0 && nearDiscEdge) || (k == 1 && nearBandEdge)) continue;
      const double g = out[size_t(4 * i + k)];
      ASSERT_TRUE(std::isfinite(g)) << "output " << k << " sample " << i;
      ASSERT_GE(g, 0.0) << "output " << k << " sample " << i;
      const double error = std::abs(g - cpu[k]) / std::max(std::abs(cpu[k]), 1e-30);
      worst[k] = std::max(worst[k], cpu[k] == 0.0 ? std::abs(g) : error);
      ++compared[k];
      EXPECT_LE(cpu[k] == 0.0 ? std::abs(g) : error, 1e-3)
          << "output " << k << " sample " << i << ": gpu " << g << ", cpu " << cpu[k];
    }
  }
  std::printf(
      "worst relative error, float vs double: moon disc %.1e (%d), airglow %.1e (%d), zodiacal %.1e (%d), "
      "stellar %.1e (%d)\n",
      worst[0], compared[0], worst[1], compared[1], worst[2], compared[2], worst[3], compared[3]);
}

}  // namespace
}  // namespace firmament::gpu
