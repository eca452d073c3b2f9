#include "atmosphere/fms_sky_irradiance.h"

#include <cstdio>

namespace firmament {

std::string FmsSkyIrradianceSettings::hash() const {
  char text[96];
  std::snprintf(text, sizeof(text), "E%dx%d-d%d-s%d", width, height, thetaSamples, marchSteps);
  return text;
}

FmsSkyIrradiance::FmsSkyIrradiance(gpu::Context& context)
    : context_(context),
      pipeline_(context, {"atmosphere/fms_sky_irradiance",
                          {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage,
                           gpu::BindingType::SampledImage, gpu::BindingType::StorageImage},
                          2 * sizeof(int32_t)}) {}

bool FmsSkyIrradiance::update(const AtmosphereLuts& luts, size_t batch, const FmsSkyIrradianceSettings& s,
                              gpu::CommandList& commands) {
  std::string key = luts.key() + "/" + s.hash() + "/batch" + std::to_string(batch);
  if (key == key_) return false;
  if (!irradiance_ || int(irradiance_.width()) != s.width || int(irradiance_.height()) != s.height)
    irradiance_ = gpu::Image(
        context_, {uint32_t(s.width), uint32_t(s.height), 1, gpu::Format::RGBA32F, true, true, "f_ms sky irradiance"});
  struct {
    int32_t thetaSamples;
    int32_t marchSteps;
  } push{s.thetaSamples, s.marchSteps};
  const AtmosphereLuts::Batch& b = luts.batch(batch);
  commands.bind(
      pipeline_,
      {b.block, {b.transmittance, luts.linearClamp()}, {b.multipleScattering, luts.linearClamp()}, irradiance_});
  commands.pushConstants(push);
  commands.dispatch(uint32_t((s.width + 7) / 8), uint32_t((s.height + 7) / 8), 1, "atmosphere/fms_sky_irradiance");
  commands.barrier();
  key_ = key;
  return true;
}

}  // namespace firmament
