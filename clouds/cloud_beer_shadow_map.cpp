// The Beer shadow map's bake (common/cloud_shadow.glsl, clouds/bake_shadow_map.comp; decision 0135).
#include "clouds/cloud_pass.h"
#include "clouds/cloud_pass_internal.h"

#include "core/error.h"

namespace firmament {
using namespace cloud_pass_detail;

void CloudPass::allocateShadowImage(const CloudMarchSettings& m) {
  const uint32_t shadowSize = m.beerShadowMap ? uint32_t(std::max(m.shadowMapSize, 1)) : 1u;
  if (!shadowImage_ || shadowImage_.width() != shadowSize)
    shadowImage_ =
        gpu::Image(context_, {shadowSize, shadowSize, 1, gpu::Format::RGBA32F, true, true, "cloud shadow map"});
}

void CloudPass::recordBake(const AtmosphereLuts& luts, const std::vector<const gpu::Image*>& skyIrradiance,
                           gpu::Buffer& skyFrame, gpu::CommandList& commands) {
  const uint32_t shadowSize = shadowImage_.width();
  // The shadow bake and the march share their first 13 bindings; the bake's 14th is the shadow map it
  // writes, which the march reads, and the march has two more: the anisotropy table (its per-pixel
  // air march) and the aerial-perspective volume.
  bindBake(bakeShadow_, shadowImage_, luts, skyIrradiance, skyFrame, commands);
  const uint32_t groups = (shadowSize + 7) / 8;
  commands.dispatch(groups, groups, 1, "clouds/bake_shadow_map");
  commands.barrier();
}

void CloudPass::recordShadowMap(const CloudSettings& settings, const CloudView& view, const AtmosphereLuts& luts,
                                const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                                double aerialDistance_m, gpu::CommandList& commands) {
  if (!settings.march.beerShadowMap) return;
  if (settings.layers.size() > size_t(kMaxLayers))
    throw InputError("clouds: at most " + std::to_string(kMaxLayers) + " layers");
  lightBlocks_ = view.lightBlocks;
  uploadBlock(settings, view, luts, aerialDistance_m);
  for (gpu::Buffer& frame : cloudFrames_)  // bound (unused) by the bake
    if (!frame || frame.size() != skyFrame.size())
      frame =
          gpu::Buffer(context_, skyFrame.size(), gpu::BufferUsage::Storage, gpu::MemoryLocation::Device, "cloud frame");
  allocateShadowImage(settings.march);
  recordBake(luts, skyIrradiance, skyFrame, commands);
  shadowBaked_ = true;
}

}  // namespace firmament
