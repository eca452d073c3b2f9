#pragma once
// The atmosphere's precomputed tables on the GPU: transmittance T(r, mu) and Hillaire 2020's
// multiple-scattering Psi_ms(r, mu_s). They depend on the atmosphere's parameters and the table
// settings only, so they are computed once and reused until either changes (keyed by hash).
#include <glm/glm.hpp>
#include <optional>
#include <string>

#include "atmosphere/atmosphere_block.h"
#include "atmosphere/atmosphere_settings.h"
#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sampler.h"

namespace firmament {

// Quality knobs of the tables (each is swept by `firmament bench atmosphere`).
struct AtmosphereLutSettings {
  int transmittanceWidth = 256;   // mu samples (Hillaire 2020: 256 x 64)
  int transmittanceHeight = 64;   // r samples
  int transmittanceSteps = 100;   // trapezoid intervals along each ray
  int multipleScatteringSize = 32;            // 32 x 32 (Hillaire 2020)
  int multipleScatteringDirectionsSqrt = 8;   // 8 x 8 = 64 directions
  int multipleScatteringSteps = 20;           // march steps per direction
  bool multipleScatteringLut = true;          // false: Psi_ms is not computed (the 4D tables replace it)
  glm::dvec3 wavelengthsNm{680.0, 550.0, 440.0};
  std::string hash() const;
};

class AtmosphereLuts {
 public:
  explicit AtmosphereLuts(gpu::Context& context);

  // Makes the tables match `atmosphere` and `settings`, recording their passes into `commands` when
  // they are stale. Returns true when passes were recorded (the caller submits), false when the cached
  // tables are current.
  bool update(const AtmosphereSettings& atmosphere, const AtmosphereLutSettings& settings, gpu::CommandList& commands);

  const gpu::Buffer& atmosphereBlock() const { return block_; }
  const gpu::Image& transmittance() const { return transmittance_; }
  const gpu::Image& multipleScattering() const { return multipleScattering_; }
  const gpu::Sampler& linearClamp() const { return linearClamp_; }
  const shared::AtmosphereParameters& parameters() const { return parameters_; }
  const std::string& key() const { return key_; }

 private:
  gpu::Context& context_;
  gpu::ComputePipeline transmittancePipeline_;
  gpu::ComputePipeline multipleScatteringPipeline_;
  gpu::Buffer block_;
  gpu::Image transmittance_;
  gpu::Image multipleScattering_;
  gpu::Sampler linearClamp_;
  shared::AtmosphereParameters parameters_{};
  std::string key_;  // atmosphere hash + settings hash of the current tables
};

}  // namespace firmament
