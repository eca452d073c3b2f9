// What the per-frame maps share: where they lie (placeMaps: their plane and rows this frame) and
// how a bake is bound and dispatched (bindBake, recordLevelMap).
#include "clouds/cloud_pass.h"
#include "clouds/cloud_pass_internal.h"

#include <algorithm>
#include <cmath>

namespace firmament {
using namespace cloud_pass_detail;

void CloudPass::placeMaps(const CloudSettings& settings, const CloudView& view, const AtmosphereLuts& luts,
                          const std::vector<uint8_t>& settingsKey, const TemporalPlan& plan, bool continueSequence,
                          double aerialDistance_m) {
  // The per-frame maps: one in w of their rows when the frame continues one that baked them with the
  // same settings and the clouds, the sun and the camera moved little (kMapRowStrides); else all of
  // them, placed at the camera and the sun of this frame.
  if (usesMaps(settings)) {
    const glm::dvec3 sun = glm::normalize(view.sunDirection);
    const double sunMove = std::acos(std::clamp(glm::dot(sun, maps_.sun), -1.0, 1.0));
    const double drift = glm::length(plan.windOffset - history_.windOffset);
    int stride = 0;
    for (int w : kMapRowStrides)
      if (stride == 0 && drift * w < kMapDrift_m) stride = w;
    const bool partial = continueSequence && maps_.baked && history_.settings == settingsKey && plan.sameWeather &&
                         sunMove < kMapSunMove_rad &&
                         glm::length(view.cameraPosition - maps_.origin) < kMapCameraMove_m && stride > 0 &&
                         (maps_.rowStride == 1 || maps_.rowStride == stride);
    if (partial) {
      maps_.firstRow = (maps_.firstRow + 1) % stride;
      maps_.rowStride = stride;
    } else {
      maps_.origin = view.cameraPosition;
      maps_.sun = sun;
      maps_.u = perpendicularAxis(sun);
      maps_.v = glm::cross(sun, maps_.u);
      const glm::dvec3 c = glm::normalize(view.cameraPosition);
      maps_.column = c;
      maps_.columnU = perpendicularAxis(c);
      maps_.columnV = glm::cross(c, maps_.columnU);
      maps_.firstRow = 0;
      maps_.rowStride = 1;
    }
    uploadBlock(settings, view, luts, aerialDistance_m);
  }
  maps_.baked = usesMaps(settings);
}

void CloudPass::bindBake(gpu::ComputePipeline& pipeline, const gpu::Image& target, const AtmosphereLuts& luts,
                         const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                         gpu::CommandList& commands) {
  const AtmosphereLuts::Batch& lut = luts.batch(0);
  commands.bind(pipeline, {lightBlock(luts, 0),
                           {lut.transmittance, luts.linearClamp()},
                           {lut.multipleScattering, luts.linearClamp()},
                           {*skyIrradiance[0], luts.linearClamp()},
                           {noise_.shape(), noise_.linearRepeat()},
                           {noise_.detail(), noise_.linearRepeat()},
                           {noise_.curl(), noise_.linearRepeat()},
                           {noise_.blueNoise(), noise_.nearestRepeat()},
                           skyFrame,
                           cloudFrames_[current_],
                           block_,
                           counters_,
                           {weatherImage_, noise_.linearRepeat()},
                           target});
}

void CloudPass::recordLevelMap(gpu::ComputePipeline& pipeline, gpu::Image& image, bool bake, int size, int levels,
                               size_t layers, int extraSlices, const char* name, const char* pass,
                               const AtmosphereLuts& luts, const std::vector<const gpu::Image*>& skyIrradiance,
                               gpu::Buffer& skyFrame, gpu::CommandList& commands) {
  const uint32_t width = bake ? uint32_t(size) : 1u;
  const uint32_t depth = bake ? uint32_t(layers) * uint32_t(levels + 1) + uint32_t(extraSlices) : 2u;
  if (!image || image.width() != width || image.depth() != depth)
    image = gpu::Image(context_, {width, width, depth, gpu::Format::R32F, true, true, name});
  if (!bake) return;
  bindBake(pipeline, image, luts, skyIrradiance, skyFrame, commands);
  const uint32_t rows = bakedRows(width);
  commands.dispatch((width + 7) / 8, (rows + 7) / 8, uint32_t(layers), pass);
  commands.barrier();
}

}  // namespace firmament
