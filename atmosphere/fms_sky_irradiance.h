#pragma once
// The f_ms path's ground irradiance table: the irradiance that the sky drawn by render_sky.comp
// (single scattering + Hillaire 2020's Psi_ms) brings to a horizontal surface, E_sky(r, mu_s), in the
// same 64 x 16 parametrization as Bruneton's table (common/scattering_lut.glsl). It needs only the
// transmittance and Psi_ms tables, so the f_ms path shades its ground with skylight without the
// 4D tables. Cached by the AtmosphereLuts key and its own settings.
#include <string>

#include "atmosphere/atmosphere_luts.h"
#include "gpu/command.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"

namespace firmament {

struct FmsSkyIrradianceSettings {
  int width = 64;        // mu_s samples
  int height = 16;       // r samples
  int thetaSamples = 8;  // directions over the hemisphere: theta x 2 theta
  int marchSteps = 16;   // steps along each direction (quadratic spacing, as the render)
  std::string hash() const;
};

class FmsSkyIrradiance {
 public:
  explicit FmsSkyIrradiance(gpu::Context& context);
  // Records the pass for spectral batch `batch` of `luts` and returns true when stale (luts must be
  // current). One FmsSkyIrradiance per batch.
  bool update(const AtmosphereLuts& luts, size_t batch, const FmsSkyIrradianceSettings& settings,
              gpu::CommandList& commands);
  const gpu::Image& irradiance() const { return irradiance_; }

 private:
  gpu::Context& context_;
  gpu::ComputePipeline pipeline_;
  gpu::Image irradiance_;
  std::string key_;
};

}  // namespace firmament
