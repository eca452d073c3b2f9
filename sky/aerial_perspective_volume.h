#pragma once
// The aerial-perspective volume (Hillaire 2020, section 5.4): per frame and per spectral batch, the
// air between the camera and every point of a camera-frustum grid of C x R froxel columns by N depth
// slices, marched once per column (shaders/sky/aerial_perspective_volume.comp; layout and
// parametrisation in shaders/common/aerial_perspective.glsl, lookup in
// shaders/atmosphere/aerial_perspective_sampling.glsl). Its first reader is the cloud march
// (clouds/cloud_pass.h, aerial perspective "volume"); docs/atmosphere.md has the measurements.
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/atmosphere_luts.h"
#include "common/camera.glsl"
#include "gpu/command.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"

namespace firmament {

struct AerialPerspectiveVolumeSettings {
  int columns = 32;  // C: across the image's width (corner-aligned: the first and last on its edges)
  int rows = 32;     // R: down its height
  int slices = 32;   // N: depth slices, d_k = D ((k + 1) / N)^2
  // D (m). 0: the reader's own far limit (the cloud march's, 80 km by default), so every depth a
  // reader can ask for lies inside the volume.
  double maxDistance_m = 0.0;
  int stepsPerSlice = 1;  // march steps inside each slice at least (equal steps over the slice's stretch)
  // More steps in a slice where the ray climbs or descends: at most this change of scaled altitude
  // per step (m; 0: none), the altitude up to stepRiseCap_m and an eighth of it above (at most 64
  // steps per slice; shaders/sky/aerial_perspective_volume.comp).
  double maxStepRise_m = 500.0;
  double stepRiseCap_m = 10000.0;
};

// Cloud shadows in the air (light shafts): the Beer shadow map (common/cloud_shadow.glsl) and its
// placement in the camera's cloud frame. With it, each step's single scattering of sunlight is
// multiplied by the clouds' transmittance towards the sun, and what that removes is accumulated too
// (the volume's alpha channels, common/aerial_perspective.glsl) for the sky behind
// (sky/cloud_light_shafts.comp).
struct AerialCloudShadow {
  const gpu::Image* map = nullptr;        // RGBA32F: front depth, mean extinction, total optical depth
  const gpu::Sampler* sampler = nullptr;  // linear, clamp
  glm::dvec3 centre{0.0}, u{1.0, 0.0, 0.0}, v{0.0, 1.0, 0.0};
  double extent_m = 1.0, start_m = 0.0;
};

class AerialPerspectiveVolume {
 public:
  explicit AerialPerspectiveVolume(gpu::Context& context);

  // Records one dispatch per spectral batch of `luts` (labelled "sky/aerial_perspective_volume"): the
  // volume for a camera at cameraPosition (planet-centred, m) with `camera`'s pixel mapping, and the
  // sun direction `sun`. settings.maxDistance_m must be > 0 here (resolved by the caller). The tables
  // must be ready; a reader needs a barrier after.
  // shadow: cloud shadows in the air (null: none; the alpha channels hold 0). lightBlocks: per batch the
  // atmosphere block carrying the light when it is not the Sun (the Moon at night, sky/frame_light.h).
  void record(const AerialPerspectiveVolumeSettings& settings, const glm::dvec3& cameraPosition, const glm::dvec3& sun,
              const shared::CameraParameters& camera, const AtmosphereLuts& luts, gpu::CommandList& commands,
              const AerialCloudShadow* shadow = nullptr, const std::vector<const gpu::Buffer*>& lightBlocks = {});

  // RGBA32F, 3C x R x N (three tiles), one per spectral batch of the last record() (valid after its commands ran).
  std::vector<const gpu::Image*> volumes() const;
  const gpu::Image& volume(size_t batch) const { return volumes_.at(batch); }
  // The settings of the last record().
  const AerialPerspectiveVolumeSettings& settings() const { return settings_; }

 private:
  gpu::Context& context_;
  gpu::ComputePipeline pipeline_;
  std::vector<gpu::Buffer> blocks_;  // one uniform block per batch (the batches' dispatches share a submission)
  std::vector<gpu::Image> volumes_;
  gpu::Image shadowPlaceholder_;  // 1x1, bound without cloud shadows
  AerialPerspectiveVolumeSettings settings_;
};

}  // namespace firmament
