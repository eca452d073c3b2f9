// The transmittance a host's shader reads with firmament/atmosphere_lookup.glsl
// (firmamentTransmittanceToTop over the table Sky::lookups() exports, which is the renderer's own
// transmittance table: sky/sky_renderer.cpp, recordHostDepth) against the atmosphere's transmittance
// integral, exp(-opticalDepthToTop) of shaders/common/atmosphere_lut.glsl in double with 4096 intervals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "atmosphere/atmosphere_luts.h"
#include "atmosphere/atmosphere_settings.h"
#include "common/atmosphere_lut.glsl"
#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/pipeline.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

class LookupTransmittanceTest : public test::GpuTest {};

struct Push {
  float radii[4];
  uint32_t count;
};

// The include's transmittance at each (r, mu), evaluated on the GPU over the embedded mode's table.
std::vector<float> includeTransmittance(gpu::Context& context, const AtmosphereLuts& luts,
                                        const std::vector<float>& rMu) {
  const shared::AtmosphereParameters& a = luts.parameters();
  const uint32_t count = uint32_t(rMu.size() / 2);
  gpu::Buffer in(context, rMu.size() * sizeof(float), gpu::BufferUsage::Storage);
  in.upload(rMu);
  gpu::Buffer out(context, size_t(count) * 4 * sizeof(float), gpu::BufferUsage::Storage);
  gpu::ComputePipeline pipeline(
      context, {"api/lookup_transmittance_test",
                {gpu::BindingType::SampledImage, gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer},
                sizeof(Push)});
  gpu::CommandList list(context);
  list.bind(pipeline, {{luts.transmittance(), luts.linearClamp()}, in, out});
  list.pushConstants(Push{{float(a.bottom_radius), float(a.top_radius), 0.0f, 0.0f}, count});
  list.dispatch((count + 63) / 64);
  list.submitAndWait();
  return out.download<float>();
}

// The include's T against exp(-optical depth) over the points, each channel: the largest absolute error,
// and the largest relative error where the ray rises (mu >= 0: the sun above a host's horizon).
struct Errors {
  double absolute = 0.0;
  double risingRelative = 0.0;
  double r = 0.0, mu = 0.0;    // where the largest relative error of the rising rays is
  double steepRelative = 0.0;  // the largest relative error where mu >= 0.1 (the sun 5.7 deg up or more)
};
Errors errorsOf(const AtmosphereLuts& luts, const std::vector<float>& rMu, const std::vector<float>& t) {
  const shared::AtmosphereParameters& a = luts.parameters();
  Errors e;
  for (size_t i = 0; i < rMu.size() / 2; ++i) {
    const double r = rMu[2 * i], mu = rMu[2 * i + 1];
    const glm::dvec3 depth = shared::opticalDepthToTop(a, r, mu, 4096);
    for (int c = 0; c < 3; ++c) {
      const double expected = std::exp(-depth[c]);
      EXPECT_TRUE(std::isfinite(t[4 * i + c]));
      const double error = std::abs(double(t[4 * i + c]) - expected);
      e.absolute = std::max(e.absolute, error);
      if (mu >= 0.1) e.steepRelative = std::max(e.steepRelative, error / expected);
      if (mu >= 0.0 && error / expected > e.risingRelative) {
        e.risingRelative = error / expected;
        e.r = r;
        e.mu = mu;
      }
    }
  }
  return e;
}

TEST_F(LookupTransmittanceTest, IncludeMatchesTheAtmosphereIntegral) {
  gpu::Context& context = this->context();
  AtmosphereLuts luts(context);
  luts.update(AtmosphereSettings{}, AtmosphereLutSettings{});  // the embedded mode's: 680, 550, 440 nm, 256x64
  const shared::AtmosphereParameters& a = luts.parameters();
  const glm::ivec2 size(256, 64);

  // At the texel centres the bilinear fetch returns the texel: the include's parameterisation must land
  // there, and the table's value is its 100-interval trapezoid integral.
  std::vector<float> centres;
  for (int y = 0; y < size.y; y += 3)
    for (int x = 0; x < size.x; x += 5) {
      double r = 0.0, mu = 0.0;
      shared::rMuFromTransmittanceUv(a, glm::dvec2((x + 0.5) / size.x, (y + 0.5) / size.y), size, r, mu);
      centres.insert(centres.end(), {float(r), float(mu)});
    }
  const Errors atCentres = errorsOf(luts, centres, includeTransmittance(context, luts, centres));
  EXPECT_LT(atCentres.absolute, 1e-3);
  EXPECT_LT(atCentres.risingRelative, 3e-3) << "at r = " << atCentres.r << " m, mu = " << atCentres.mu;
  EXPECT_LT(atCentres.steepRelative, 3e-3);

  // Anywhere between them: heights from the ground to the top, directions from the zenith to the
  // horizon; bilinear interpolation adds its error.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<float> anywhere;
  for (int i = 0; i < 4096; ++i) {
    double r = 0.0, mu = 0.0;
    const glm::dvec2 uv(0.5 / size.x + unit(random) * (1.0 - 1.0 / size.x),
                        0.5 / size.y + unit(random) * (1.0 - 1.0 / size.y));
    shared::rMuFromTransmittanceUv(a, uv, size, r, mu);
    anywhere.insert(anywhere.end(), {float(r), float(mu)});
  }
  const Errors between = errorsOf(luts, anywhere, includeTransmittance(context, luts, anywhere));
  EXPECT_LT(between.absolute, 1e-2);
  EXPECT_LT(between.risingRelative, 5e-2) << "at r = " << between.r << " m, mu = " << between.mu;
  EXPECT_LT(between.steepRelative, 5e-3);
  std::printf(
      "include vs integral: texel centres: absolute %.3g, rising rays relative %.3g (r %.0f m, mu %.4f), mu >= "
      "0.1 %.3g; anywhere: absolute %.3g, rising rays relative %.3g (r %.0f m, mu %.4f), mu >= 0.1 %.3g\n",
      atCentres.absolute, atCentres.risingRelative, atCentres.r, atCentres.mu, atCentres.steepRelative,
      between.absolute, between.risingRelative, between.r, between.mu, between.steepRelative);
}

}  // namespace
}  // namespace firmament
