#include "sky/aerial_perspective_volume.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "common/aerial_perspective.glsl"
#include "core/error.h"
#include "gpu/buffer.h"

namespace firmament {
namespace {

// std140 mirror of AerialBlock in shaders/sky/aerial_perspective_volume.comp.
struct AerialBlock {
  float cameraPosition[4];  // w = maximum distance D
  float cameraForward[4];   // w = fov
  float cameraRight[4];     // w = yaw
  float cameraUp[4];
  float sunDirection[4];
  int32_t image[4];       // width, height, projection, steps per slice
  int32_t size[4];        // columns, rows, slices, unused
  float steps[4];         // largest altitude change per step (m), its altitude cap (m), unused x2
  float shadowCentre[4];  // Beer shadow map centre (cloud frame, m); w = extent (m)
  float shadowAxisU[4];   // w = start distance L (m)
  float shadowAxisV[4];   // w = 1: cloud shadows on, 0: off
};
static_assert(sizeof(AerialBlock) == 11 * 16);

void put(float (&out)[4], const glm::dvec3& v, double w = 0.0) {
  out[0] = float(v.x), out[1] = float(v.y), out[2] = float(v.z), out[3] = float(w);
}

}  // namespace

AerialPerspectiveVolume::AerialPerspectiveVolume(gpu::Context& context)
    : context_(context),
      pipeline_(context,
                {"sky/aerial_perspective_volume",
                 {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
                  gpu::BindingType::SampledImage, gpu::BindingType::StorageImage, gpu::BindingType::UniformBuffer,
                  gpu::BindingType::SampledImage},
                 0}) {}

void AerialPerspectiveVolume::record(const AerialPerspectiveVolumeSettings& settings, const glm::dvec3& cameraPosition,
                                     const glm::dvec3& sun, const shared::CameraParameters& camera,
                                     const AtmosphereLuts& luts, gpu::CommandList& commands,
                                     const AerialCloudShadow* shadow,
                                     const std::vector<const gpu::Buffer*>& lightBlocks) {
  if (settings.columns < 2 || settings.rows < 2 || settings.slices < 2 || settings.columns > 1024 ||
      settings.rows > 1024 || settings.slices > 1024)
    throw InputError("aerial-perspective volume: columns, rows and slices must be 2..1024 (got " +
                     std::to_string(settings.columns) + " x " + std::to_string(settings.rows) + " x " +
                     std::to_string(settings.slices) + ")");
  if (!(settings.maxDistance_m > 0.0))
    throw InputError("aerial-perspective volume: the maximum distance must be > 0 m");
  if (settings.stepsPerSlice < 1 || settings.stepsPerSlice > 64)
    throw InputError("aerial-perspective volume: steps per slice must be 1..64");
  settings_ = settings;
  const size_t batches = luts.batchCount();
  const uint32_t width = uint32_t(shared::kAerialTiles * settings.columns), height = uint32_t(settings.rows),
                 depth = uint32_t(settings.slices);
  volumes_.resize(batches);
  blocks_.resize(batches);
  for (size_t b = 0; b < batches; ++b) {
    if (!volumes_[b] || volumes_[b].width() != width || volumes_[b].height() != height || volumes_[b].depth() != depth)
      volumes_[b] =
          gpu::Image(context_, {width, height, depth, gpu::Format::RGBA32F, true, true, "aerial-perspective volume"});
    if (!blocks_[b])
      blocks_[b] = gpu::Buffer(context_, sizeof(AerialBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host,
                               "aerial-perspective block");
  }
  AerialBlock block{};
  put(block.cameraPosition, cameraPosition, settings.maxDistance_m);
  put(block.cameraForward, camera.forward, camera.fov);
  put(block.cameraRight, camera.right, camera.yaw);
  put(block.cameraUp, camera.up);
  put(block.sunDirection, sun);
  block.image[0] = camera.width;
  block.image[1] = camera.height;
  block.image[2] = camera.projection;
  block.image[3] = settings.stepsPerSlice;
  block.size[0] = settings.columns;
  block.size[1] = settings.rows;
  block.size[2] = settings.slices;
  block.steps[0] = float(std::max(settings.maxStepRise_m, 0.0));
  block.steps[1] = float(settings.stepRiseCap_m);
  if (shadow && (!shadow->map || !shadow->sampler))
    throw std::logic_error("AerialPerspectiveVolume: a cloud shadow needs its map and sampler");
  if (shadow) {
    put(block.shadowCentre, shadow->centre, shadow->extent_m);
    put(block.shadowAxisU, shadow->u, shadow->start_m);
    put(block.shadowAxisV, shadow->v, 1.0);
  }
  if (!shadowPlaceholder_)
    shadowPlaceholder_ = gpu::Image(context_, {1, 1, 1, gpu::Format::RGBA32F, false, true, "no cloud shadow"});
  for (size_t b = 0; b < batches; ++b) {
    blocks_[b].upload(&block, sizeof(block));
    const AtmosphereLuts::Batch& batch = luts.batch(b);
    commands.bind(pipeline_,
                  {b < lightBlocks.size() ? *lightBlocks[b] : batch.block,
                   {batch.transmittance, luts.linearClamp()},
                   {batch.multipleScattering, luts.linearClamp()},
                   {batch.multipleScatteringAnisotropy, luts.linearClamp()},
                   volumes_[b],
                   blocks_[b],
                   {shadow ? *shadow->map : shadowPlaceholder_, shadow ? *shadow->sampler : luts.linearClamp()}});
    commands.dispatch(uint32_t((settings.columns + 7) / 8), uint32_t((settings.rows + 7) / 8), 1,
                      "sky/aerial_perspective_volume");
  }
}

std::vector<const gpu::Image*> AerialPerspectiveVolume::volumes() const {
  std::vector<const gpu::Image*> out;
  for (const auto& v : volumes_) out.push_back(&v);
  return out;
}

}  // namespace firmament
