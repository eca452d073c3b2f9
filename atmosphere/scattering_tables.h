#pragma once
// Bruneton 2017's precomputed scattering ("Precomputed Atmospheric Scattering: a New Implementation"):
// N scattering orders summed into a 4D table S(r, mu, mu_s, nu), single Mie scattering in a second
// 4D table, and the sky's irradiance on the ground E_sky(r, mu_s). Built on the GPU from the
// transmittance table of one of AtmosphereLuts' spectral batches, and kept until the atmosphere or the
// settings change (keyed by both hashes). The tables are linear in the solar irradiance, so the Sun's
// distance is not in the key: they keep the scale they were computed at (solarIrradianceScale()) and a
// reader multiplies by the current scale over it. docs/atmosphere-tables.md describes the algorithm,
// the choices and their cost.
//
//   ScatteringTables tables(context);
//   gpu::CommandList list(context);
//   if (luts.update(atmosphere, lutSettings, list) | tables.update(luts, tableSettings, list)) list.submitAndWait();
#include <filesystem>
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

// The tables the default frame reads in twilight (SkyRenderOptions::twilightTables, decision 0158): four
// orders (8 and 16 change the twilight's ground illuminance by under 3 %) at a quarter of the default
// size (mu and r halved: under 1 % there).
inline constexpr ScatteringTableSettings kTwilightTableSettings = [] {
  ScatteringTableSettings s;
  s.muSize = 64;
  s.rSize = 16;
  return s;
}();

class ScatteringTables {
 public:
  explicit ScatteringTables(gpu::Context& context);

  // Makes the tables match `luts` (its parameters, block and transmittance, which must already be
  // current or recorded earlier into `commands`) and `settings`. Records the passes and returns true
  // when stale; false when the tables are current (in memory, or read from the disk cache,
  // Context::cacheDir, when a file for the key exists). After recorded passes have run, store() writes
  // them to the disk cache.
  bool update(const AtmosphereLuts& luts, const ScatteringTableSettings& settings, gpu::CommandList& commands) {
    return update(luts, 0, settings, commands);
  }
  // The same from the wavelengths of `luts`' spectral batch `batch`.
  bool update(const AtmosphereLuts& luts, size_t batch, const ScatteringTableSettings& settings,
              gpu::CommandList& commands);

  // Rayleigh single scattering + every higher order divided by p_R(nu) (multiply by p_R at lookup).
  const gpu::Image& scattering() const { return scattering_; }
  // Single Mie scattering without its phase function (multiply by p_M at lookup).
  const gpu::Image& singleMieScattering() const { return deltaMie_; }
  // The sky's irradiance on a horizontal surface (orders 1..N-1; the sun's direct part is not in it).
  const gpu::Image& irradiance() const { return irradiance_; }
  const ScatteringTableSettings& settings() const { return settings_; }
  const std::string& key() const { return key_; }
  // The atmosphere's solar irradiance scale the tables hold (AtmosphereLuts::solarIrradianceScale).
  double solarIrradianceScale() const { return solarIrradianceScale_; }
  // "memory", "disk cache" or "computed": where the last update() found the tables.
  const std::string& source() const { return source_; }
  void store();  // the computed tables to the disk cache (nothing when none are pending or no cache)

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
  double solarIrradianceScale_ = 1.0;
  std::string source_ = "memory";
  std::filesystem::path pendingFile_;  // where store() writes the tables just recorded (empty: nothing)
};

}  // namespace firmament
