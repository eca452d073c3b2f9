// The other layers' map's bake (clouds/other_layer_map.glsl, clouds/bake_other_layers.comp; decision 0132).
#include "clouds/cloud_pass.h"
#include "clouds/cloud_pass_internal.h"

#include <string>

#include "core/error.h"

namespace firmament {
using namespace cloud_pass_detail;

void CloudPass::recordOtherLayerMap(const CloudSettings& settings, const AtmosphereLuts& luts,
                                    const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                                    gpu::CommandList& commands) {
  const bool bake = usesOtherLayerMap(settings);
  const int size = settings.march.otherLayerMapSize;
  if (bake && (size < 8 || size > 4096))
    throw InputError("clouds: other_layer_map_size " + std::to_string(size) + "; allowed: 8 to 4096 texels");
  const uint32_t width = bake ? uint32_t(size) : 1u;
  const uint32_t height = bake ? uint32_t(size) * uint32_t((settings.layers.size() + 3) / 4) : 1u;
  if (!otherLayerImage_ || otherLayerImage_.width() != width || otherLayerImage_.height() != height)
    otherLayerImage_ =
        gpu::Image(context_, {width, height, 1, gpu::Format::RGBA32F, true, true, "cloud other layers' map"});
  if (!bake) return;
  bindBake(bakeOtherLayers_, otherLayerImage_, luts, skyIrradiance, skyFrame, commands);
  const uint32_t rows = bakedRows(height);
  commands.dispatch((width + 7) / 8, (rows + 7) / 8, 1, "clouds/bake_other_layers");
  commands.barrier();
}

}  // namespace firmament
