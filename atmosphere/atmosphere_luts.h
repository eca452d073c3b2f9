#pragma once
// The atmosphere's precomputed tables on the GPU, per spectral batch (three wavelengths each, see
// atmosphere_spectra.h): transmittance T(r, mu) and Hillaire 2020's multiple-scattering Psi_ms(r, mu_s),
// plus the sun disc's transmitted centre radiance in Rec.709 summed over the batches. They depend on
// the atmosphere's parameters and the table settings only, so they are computed once and reused until
// either changes (keyed by hash, in memory and on disk).
#include <glm/glm.hpp>
#include <string>
#include <vector>

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
  int transmittanceWidth = 256;             // mu samples (Hillaire 2020: 256 x 64)
  int transmittanceHeight = 64;             // r samples
  int transmittanceSteps = 100;             // trapezoid intervals along each ray
  int multipleScatteringSize = 32;          // 32 x 32 (Hillaire 2020)
  int multipleScatteringThetaSamples = 32;  // zenith bands of the sphere of directions
  int multipleScatteringPhiSamples = 2;     // azimuth samples per band (32 x 2 = 64 directions)
  int multipleScatteringSteps = 20;         // march steps per direction
  // Scattering orders iterated explicitly before the geometric tail (shaders/atmosphere/
  // multiple_scattering_lut.glsl); 1 = Hillaire 2020 exactly (isotropic phase, f_ms series). From 2
  // on the first order also uses the real phase functions.
  int multipleScatteringOrders = 3;
  bool multipleScatteringLut = true;  // false: Psi_ms is not computed (the 4D tables replace it)
  // 3: three wavelengths (below) with Bruneton's conversion to Rec.709; 6..48 (multiples of 3):
  // that many wavelengths over 360-830 nm, integrated to luminance exactly (atmosphere_spectra.h).
  int spectralSamples = 3;
  glm::dvec3 wavelengthsNm{680.0, 550.0, 440.0};
  std::string hash() const;
};

class AtmosphereLuts {
 public:
  explicit AtmosphereLuts(gpu::Context& context);

  enum class Source { Memory, Disk, Computed };
  struct Update {
    Source source = Source::Memory;
    std::vector<gpu::PassTiming> timings;  // GPU time of the passes when computed
  };
  // Makes the tables match `atmosphere` and `settings`: kept in memory while the key is unchanged,
  // else read from the disk cache (Context::cacheDir) when a file for the key exists, else computed
  // on the GPU (and then written to the disk cache). The key covers every parameter, every table
  // setting and the device, so cached tables are bit-identical to freshly computed ones.
  Update update(const AtmosphereSettings& atmosphere, const AtmosphereLutSettings& settings);

  struct Batch {
    gpu::Buffer block;  // the AtmosphereBlock of this batch's wavelengths
    gpu::Image transmittance;
    gpu::Image multipleScattering;
    // (kAnisotropyTiles size) x size: the multiple-scattering field's anisotropy over Psi_ms, five RGB
    // coefficients packed into RGBA tiles (atmosphere/atmosphere_sampling.glsl); zero for Hillaire's
    // one-order form.
    gpu::Image multipleScatteringAnisotropy;
    shared::AtmosphereParameters parameters{};
  };
  size_t batchCount() const { return batches_.size(); }
  const Batch& batch(size_t i) const { return batches_.at(i); }
  const gpu::Image& sunRadiance() const { return sunRadiance_; }
  // The first batch: with three wavelengths (spectralSamples = 3), the only one (the 4D tables use it).
  const gpu::Buffer& atmosphereBlock() const { return batch(0).block; }
  const gpu::Image& transmittance() const { return batch(0).transmittance; }
  const gpu::Image& multipleScattering() const { return batch(0).multipleScattering; }
  const gpu::Sampler& linearClamp() const { return linearClamp_; }
  // Wavelength-independent geometry (radii) of the current atmosphere.
  const shared::AtmosphereParameters& parameters() const { return batches_.at(0).parameters; }
  const std::string& key() const { return key_; }
  // The key with the atmosphere's solar irradiance scale (the Sun's distance) and the Psi_ms switch left
  // out, and that scale: tables built on the transmittance and linear in the light (scattering_tables.h)
  // are keyed by the first and rescaled by the second.
  const std::string& unscaledKey() const { return unscaledKey_; }
  double solarIrradianceScale() const { return solarIrradianceScale_; }

 private:
  gpu::Context& context_;
  gpu::ComputePipeline transmittancePipeline_;
  gpu::ComputePipeline multipleScatteringPipeline_;       // order 1 (from the sun)
  gpu::ComputePipeline multipleScatteringOrderPipeline_;  // orders 2 and up
  std::vector<Batch> batches_;
  // Scratch of the order iteration: J_k and the ground irradiance E_k, ping-pong (shared by batches).
  gpu::Image orders_[2];
  gpu::Image groundOrders_[2];
  gpu::Image sunRadiance_;
  gpu::Sampler linearClamp_;
  std::string key_;  // atmosphere hash + settings hash + device of the current tables
  std::string unscaledKey_;
  double solarIrradianceScale_ = 1.0;
};

}  // namespace firmament
