// The column map's bake (clouds/column_map.glsl, clouds/bake_columns.comp and bake_column_ambient.comp;
// decision 0133).
#include "clouds/cloud_pass.h"
#include "clouds/cloud_pass_internal.h"

#include <string>

#include "core/error.h"

namespace firmament {
using namespace cloud_pass_detail;

void CloudPass::recordColumnMap(const CloudSettings& settings, const AtmosphereLuts& luts,
                                const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                                gpu::CommandList& commands) {
  const bool bake = usesColumnMap(settings);
  const int size = settings.march.columnMapSize, levels = settings.march.columnMapLevels;
  if (bake && (size < 8 || size > 4096))
    throw InputError("clouds: column_map_size " + std::to_string(size) + "; allowed: 8 to 4096 texels");
  if (bake && (levels < 1 || levels > 64))
    throw InputError("clouds: column_map_levels " + std::to_string(levels) + "; allowed: 1 to 64");
  // Two more slices per layer: the ambient's view of the other layers (bake_column_ambient.comp), baked
  // from the levels' whole columns where there are other layers and the ambient's slab looks through them.
  const size_t layers = settings.layers.size();
  recordLevelMap(bakeColumns_, columnImage_, bake, size, levels, layers, 2 * int(layers), "cloud column map",
                 "clouds/bake_columns", luts, skyIrradiance, skyFrame, commands);
  if (bake && usesColumnAmbient(settings)) {
    bindBake(bakeColumnAmbient_, columnImage_, luts, skyIrradiance, skyFrame, commands);
    const uint32_t width = uint32_t(size);
    const uint32_t rows = bakedRows(width);
    commands.dispatch((width + 7) / 8, (rows + 7) / 8, uint32_t(layers), "clouds/bake_column_ambient");
    commands.barrier();
  }
}

}  // namespace firmament
