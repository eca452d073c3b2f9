// One source of physics: the atmosphere's shared headers evaluated on the GPU in float
// (shaders/gpu/atmosphere_functions_test.comp) and on the CPU in double agree within tolerances set by
// float precision: coefficients, phases and table coordinates to 1e-4 relative (a few float ulps
// through exp/pow), optical depth to 2e-3 relative (64 float trapezoid steps over paths up to 1000 km),
// and the inverse table mapping within 1 m and 1e-3 in mu (the mapping's conditioning near the ground).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "atmosphere/atmosphere_block.h"
#include "atmosphere/atmosphere_settings.h"
#include "atmosphere/atmosphere_spectra.h"
#include "common/atmosphere_lut.glsl"
#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/pipeline.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

class AtmosphereSharedFunctionsTest : public test::GpuTest {};

double relativeError(double gpu, double cpu, double floor) {
  return std::abs(gpu - cpu) / std::max(std::abs(cpu), floor);
}

TEST_F(AtmosphereSharedFunctionsTest, GpuFloatAgreesWithCpuDouble) {
  gpu::Context& context = this->context();
  AtmosphereSettings settings;
  settings.groundHeight = 1200.0;  // exercise the shifted profiles
  shared::AtmosphereParameters cpu = atmosphereParametersAt(settings, kDefaultWavelengthsNm);
  // The GPU sees the float-rounded parameters; evaluate the CPU side with the same rounding.
  AtmosphereBlock block = packAtmosphereBlock(cpu, glm::dmat3(1.0), glm::dmat3(1.0));
  gpu::Buffer blockBuffer(context, sizeof(block), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host);
  blockBuffer.upload(&block, sizeof(block));

  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<float> inputs;
  const double bottom = cpu.bottom_radius, top = cpu.top_radius;
  for (int i = 0; i < 2048; ++i) {
    double h = (i % 4 == 0) ? unit(random) * 100.0 : unit(random) * (top - bottom);
    double mu = 2.0 * unit(random) - 1.0;
    if (i % 8 == 1)
      mu = -std::sqrt(1.0 - std::pow(bottom / (bottom + h), 2.0)) + (unit(random) - 0.5) * 2e-5;  // grazing
    inputs.insert(inputs.end(),
                  {float(bottom + h), float(mu), float(2.0 * unit(random) - 1.0), float(2.0 * unit(random) - 1.0)});
  }
  const uint32_t count = uint32_t(inputs.size() / 4);
  gpu::Buffer in(context, inputs.size() * sizeof(float), gpu::BufferUsage::Storage);
  in.upload(inputs);
  gpu::Buffer out(context, size_t(count) * 16 * sizeof(float), gpu::BufferUsage::Storage);
  gpu::ComputePipeline pipeline(
      context, {"gpu/atmosphere_functions_test",
                {gpu::BindingType::UniformBuffer, gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer},
                sizeof(uint32_t)});
  gpu::CommandList list(context);
  list.bind(pipeline, {blockBuffer, in, out});
  list.pushConstants(count);
  list.dispatch((count + 63) / 64);
  list.submitAndWait();
  std::vector<float> results = out.download<float>();

  int checked = 0;
  for (uint32_t i = 0; i < count; ++i) {
    double r = inputs[4 * i], mu = inputs[4 * i + 1], muS = inputs[4 * i + 2], nu = inputs[4 * i + 3];
    const float* g = &results[16 * size_t(i)];
    glm::dvec3 extinction = shared::extinctionAt(cpu, r);
    for (int c = 0; c < 3; ++c) EXPECT_LT(relativeError(g[c], extinction[c], 1e-12), 1e-4) << "extinction r=" << r;
    EXPECT_LT(relativeError(g[3], shared::rayleighPhase(nu), 1e-6), 1e-5);
    EXPECT_LT(relativeError(g[4], shared::cornetteShanksPhase(cpu.mie_phase_g, nu), 1e-6), 1e-4);
    EXPECT_LT(relativeError(g[15], shared::henyeyGreensteinPhase(0.7, nu), 1e-6), 1e-4);
    glm::dvec3 depth = shared::opticalDepthToTop(cpu, r, mu, 64);
    for (int c = 0; c < 3; ++c)
      EXPECT_LT(relativeError(g[5 + c], depth[c], 1e-6), 2e-3) << "depth r=" << r << " mu=" << mu;
    glm::dvec2 uv = shared::transmittanceUvFromRMu(cpu, r, mu, glm::ivec2(256, 64));
    EXPECT_NEAR(g[8], uv.x, 2e-3) << "u r=" << r << " mu=" << mu;
    EXPECT_NEAR(g[9], uv.y, 1e-4);
    EXPECT_NEAR(g[10], r, 1.0 + 1e-6 * r);  // the float round trip of r
    glm::dvec2 ms = shared::multipleScatteringUv(cpu, r, muS, glm::ivec2(32, 32));
    EXPECT_NEAR(g[12], ms.x, 1e-5);
    EXPECT_NEAR(g[13], ms.y, 1e-4);
    EXPECT_NEAR(g[14], shared::sunLimbDarkening(nu, cpu.sun_angular_radius), 1e-4);
    ++checked;
  }
  EXPECT_EQ(checked, int(count));
}

// The table parametrization is a bijection on its domain: (r, mu) -> uv -> (r, mu) in double.
TEST(AtmosphereSharedFunctions, TransmittanceMappingRoundTrips) {
  shared::AtmosphereParameters a = atmosphereParametersAt(AtmosphereSettings{}, kDefaultWavelengthsNm);
  for (double h : {0.0, 1.0, 1000.0, 30000.0, 59999.0})
    for (double mu = -1.0; mu <= 1.0; mu += 0.01) {
      double r = a.bottom_radius + h;
      // the table stores rays that reach the top (Bruneton 2017); ground-hitting ones are clamped
      if (shared::rayIntersectsGround(a, r, mu)) continue;
      glm::dvec2 uv = shared::transmittanceUvFromRMu(a, r, mu, glm::ivec2(256, 64));
      double r2, mu2;
      shared::rMuFromTransmittanceUv(a, uv, glm::ivec2(256, 64), r2, mu2);
      EXPECT_NEAR(r2, r, 1e-3 * std::max(1.0, h)) << "h=" << h << " mu=" << mu;
      EXPECT_NEAR(mu2, mu, 1e-6) << "h=" << h << " mu=" << mu;
    }
}

}  // namespace
}  // namespace firmament
