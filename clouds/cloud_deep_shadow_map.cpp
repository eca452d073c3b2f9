// The deep shadow map's bake (clouds/deep_shadow_map.glsl, clouds/bake_deep_shadow.comp; decision 0134).
#include "clouds/cloud_pass.h"
#include "clouds/cloud_pass_internal.h"

#include <string>

#include "core/error.h"

namespace firmament {
using namespace cloud_pass_detail;

void CloudPass::recordDeepShadowMap(const CloudSettings& settings, const AtmosphereLuts& luts,
                                    const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                                    gpu::CommandList& commands) {
  const CloudMarchSettings& m = settings.march;
  const int size = m.deepShadowMapSize, levels = m.deepShadowMapLevels;
  if (m.deepShadowMap && (size < 8 || size > 4096))
    throw InputError("clouds: deep_shadow_map_size " + std::to_string(size) + "; allowed: 8 to 4096 texels");
  if (m.deepShadowMap && (levels < 1 || levels > 128))
    throw InputError("clouds: deep_shadow_map_levels " + std::to_string(levels) + "; allowed: 1 to 128");
  if (m.deepShadowMap && m.deepShadowNearSteps < 0)
    throw InputError("clouds: deep_shadow_near_steps " + std::to_string(m.deepShadowNearSteps) +
                     "; allowed: 0 or more");
  recordLevelMap(bakeDeepShadow_, deepShadowImage_, usesDeepShadowMap(settings), size, levels, settings.layers.size(),
                 0, "cloud deep shadow map", "clouds/bake_deep_shadow", luts, skyIrradiance, skyFrame, commands);
}

}  // namespace firmament
