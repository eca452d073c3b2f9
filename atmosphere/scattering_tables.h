#pragma once
// Bruneton 2017's precomputed scattering ("Precomputed Atmospheric Scattering: a New Implementation"):
// N scattering orders summed into a 4D table S(r, mu, mu_s, nu), single Mie scattering in a second
// 4D table, and the sky's irradiance on the ground E_sky(r, mu_s). Built on the GPU from the
// transmittance table of AtmosphereLuts, and kept until the atmosphere or the settings change (keyed by
// both hashes). docs/atmosphere-tables.md describes the algorithm, the choices and their cost.
//
//   ScatteringTables tables(context);
//   gpu::CommandList list(context);
//   if (luts.update(atmosphere, lutSettings, list) | tables.update(luts, tableSettings, list)) list.submitAndWait();
#include <string>

#include "atmosphere/atmosphere_luts.h"
#include "common/scattering_lut.glsl"
#include "gpu/command.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"

namespace firmament {

// Quality knobs of the tables; defaults are Bruneton's.
struct ScatteringTableSettings {
  int scatteringOrders = 4;         // N: single scattering plus N - 1 orders of multiple scattering
  int nuSize = 8;                   // 4D table: nu samples (folded into the texture's x axis)
  int muSSize = 32;                 //           mu_s samples
  int muSize = 128;                 //           mu samples (even: half ground, half sky)
  int rSize = 32;                   //           r samples
  int irradianceWidth = 64;         // ground irradiance: mu_s samples
  int irradianceHeight = 16;        //                    r samples
  int integrationSteps = 50;        // trapezoid intervals along each ray (single and multiple scattering)
  int densityThetaSamples = 16;     // scattering density: theta x 2 theta directions over the sphere (<= 16)
  int irradianceThetaSamples = 16;  // ground irradiance: theta x 4 theta directions over the hemisphere
  std::string hash() const;
  shared::ScatteringTableSize tableSize() const { return {nuSize, muSSize, muSize, rSize}; }
};

class ScatteringTables {
 public:
  explicit ScatteringTables(gpu::Context& context);

  // Makes the tables match `luts` (its parameters, block and transmittance, which must already be
  // current or recorded earlier into `commands`) and `settings`. Records the passes and returns true
  // when stale; false when the cached tables are current.
  bool update(const AtmosphereLuts& luts, const ScatteringTableSettings& settings, gpu::CommandList& commands);

  // Rayleigh single scattering + every higher order divided by p_R(nu) (multiply by p_R at lookup).
  const gpu::Image& scattering() const { return scattering_; }
  // Single Mie scattering without its phase function (multiply by p_M at lookup).
  const gpu::Image& singleMieScattering() const { return deltaMie_; }
  // The sky's irradiance on a horizontal surface (orders 1..N-1; the sun's direct part is not in it).
  const gpu::Image& irradiance() const { return irradiance_; }
  const ScatteringTableSettings& settings() const { return settings_; }
  const std::string& key() const { return key_; }

 private:
  void allocate(const ScatteringTableSettings& settings);

  gpu::Context& context_;
  gpu::ComputePipeline directIrradiancePipeline_;
  gpu::ComputePipeline singleScatteringPipeline_;
  gpu::ComputePipeline scatteringDensityPipeline_;
  gpu::ComputePipeline indirectIrradiancePipeline_;
  gpu::ComputePipeline multipleScatteringPipeline_;
  gpu::Image deltaIrradiance_;
  gpu::Image irradiance_;
  gpu::Image deltaRayleigh_;
  gpu::Image deltaMie_;
  gpu::Image deltaMultiple_;
  gpu::Image scatteringDensity_;
  gpu::Image scattering_;
  ScatteringTableSettings settings_;
  std::string key_;
};

}  // namespace firmament
