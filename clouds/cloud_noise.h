#pragma once
// The cloud noise textures, baked on the GPU from a seed by the shared procedural noise
// (common/cloud_noise.glsl) and cached in memory by (seed, sizes): a scene that keeps its seed reuses
// them across frames. With a context cache folder (gpu::Context::cacheDir) the baked level 0 of the
// shape, detail and curl textures is also kept on disk, keyed by the seed, the sizes, the bake
// shaders' code and the device, so a later process uploads the same bits instead of baking (about
// 2 s on lavapipe for 128^3) and rebuilds only the mip chains. Formats are RGBA8 unorm (Schneider
// 2015 uses 8 bits too): 8 MiB for the 128³ shape texture. The shape and detail textures carry
// box-filtered mip chains down to 4^3 for the march's noise LOD (CloudMarchSettings::noiseLodScale).
// The blue-noise mask is built on the CPU (clouds/blue_noise.h) and uploaded.
#include <cstdint>
#include <filesystem>
#include <string>

#include "clouds/noise_volume.h"
#include "gpu/command.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sampler.h"

namespace firmament {

struct CloudNoiseSettings {
  int shapeSize = 128;     // shape texture: size³ RGBA (Perlin-Worley, Worley x3)
  int detailSize = 32;     // detail texture: size³ RGBA (Worley x4)
  int curlSize = 128;      // curl texture: size² (RG)
  int blueNoiseSize = 64;  // blue-noise mask: size² (R)
  std::string key(uint32_t seed) const;
};

class CloudNoise {
 public:
  explicit CloudNoise(gpu::Context& context);

  // Makes the textures match (seed, settings): records the bake passes into `commands` and returns
  // true when stale (the caller submits, with a barrier before any pass that samples them), else
  // records nothing and returns false.
  bool update(uint32_t seed, const CloudNoiseSettings& settings, gpu::CommandList& commands);
  // After the commands of an update that baked were submitted and finished: writes the baked textures
  // to the disk cache (when there is one; a failure is a warning). Does nothing otherwise.
  void storeBaked();
  // Where the current textures came from: "baked", "disk cache", or "memory" when update found them
  // current.
  const std::string& source() const { return source_; }

  const gpu::Image& shape() const { return shape_; }
  const gpu::Image& detail() const { return detail_; }
  const gpu::Image& curl() const { return curl_; }
  const gpu::Image& blueNoise() const { return blueNoise_; }
  const gpu::Sampler& linearRepeat() const { return linearRepeat_; }
  const gpu::Sampler& nearestRepeat() const { return nearestRepeat_; }
  const std::string& key() const { return key_; }

  // The current textures read back for the CPU path tracer (after the bake was submitted).
  NoiseVolume downloadShape() const;
  NoiseVolume downloadDetail() const;
  NoiseVolume downloadCurl() const;

 private:
  // Records the bake of level 0 of the shape, detail and curl textures.
  void recordBake(uint32_t seed, const CloudNoiseSettings& settings, gpu::CommandList& commands);

  gpu::Context& context_;
  gpu::ComputePipeline bake3d_;
  gpu::ComputePipeline bakeCurl_;
  gpu::ComputePipeline downsample3d_;  // the shape and detail textures' mip chains
  gpu::Image shape_, detail_, curl_, blueNoise_;
  gpu::Sampler linearRepeat_, nearestRepeat_;
  std::string key_;
  std::string source_;
  std::filesystem::path pendingCacheFile_;  // set by an update that baked, cleared by storeBaked
  std::string pendingCacheKey_;
};

}  // namespace firmament
