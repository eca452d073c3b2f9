#include "atmosphere/atmosphere_luts.h"

#include <cstdio>

#include "atmosphere/atmosphere_spectra.h"

namespace firmament {

std::string AtmosphereLutSettings::hash() const {
  char text[256];
  std::snprintf(text, sizeof(text), "T%dx%ds%d-M%dd%ds%d%s-L%.3f,%.3f,%.3f", transmittanceWidth,
                transmittanceHeight, transmittanceSteps, multipleScatteringSize, multipleScatteringDirectionsSqrt, multipleScatteringSteps,
                multipleScatteringLut ? "" : "-off", wavelengthsNm.x, wavelengthsNm.y, wavelengthsNm.z);
  return text;
}

AtmosphereLuts::AtmosphereLuts(gpu::Context& context)
    : context_(context),
      transmittancePipeline_(context, {"atmosphere/transmittance_lut",
                                       {gpu::BindingType::UniformBuffer, gpu::BindingType::StorageImage},
                                       sizeof(int32_t)}),
      multipleScatteringPipeline_(context, {"atmosphere/multiple_scattering_lut",
                                            {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage,
                                             gpu::BindingType::StorageImage},
                                            2 * sizeof(int32_t)}),
      block_(context, sizeof(AtmosphereBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host, "atmosphere block"),
      linearClamp_(context, gpu::Filter::Linear, gpu::AddressMode::Clamp) {}

bool AtmosphereLuts::update(const AtmosphereSettings& atmosphere, const AtmosphereLutSettings& settings,
                            gpu::CommandList& commands) {
  std::string key = atmosphere.hash() + "/" + settings.hash();
  if (key == key_) return false;

  parameters_ = atmosphereParametersAt(atmosphere, settings.wavelengthsNm);
  AtmosphereBlock block = packAtmosphereBlock(parameters_,
                                              threeWavelengthRadianceToRgb(settings.wavelengthsNm, kSkyLambdaPower),
                                              threeWavelengthRadianceToRgb(settings.wavelengthsNm, kSunLambdaPower));
  block_.upload(&block, sizeof(block));

  if (!transmittance_ || int(transmittance_.width()) != settings.transmittanceWidth ||
      int(transmittance_.height()) != settings.transmittanceHeight)
    transmittance_ = gpu::Image(context_, {uint32_t(settings.transmittanceWidth), uint32_t(settings.transmittanceHeight), 1,
                                           gpu::Format::RGBA32F, true, true, "transmittance LUT"});
  if (!multipleScattering_ || int(multipleScattering_.width()) != settings.multipleScatteringSize)
    multipleScattering_ = gpu::Image(context_, {uint32_t(settings.multipleScatteringSize), uint32_t(settings.multipleScatteringSize),
                                                1, gpu::Format::RGBA32F, true, true, "multiple-scattering LUT"});

  auto groups = [](int n) { return uint32_t((n + 7) / 8); };
  commands.bind(transmittancePipeline_, {block_, transmittance_});
  commands.pushConstants(int32_t(settings.transmittanceSteps));
  commands.dispatch(groups(settings.transmittanceWidth), groups(settings.transmittanceHeight), 1,
                    "atmosphere/transmittance_lut");
  commands.barrier();
  if (!settings.multipleScatteringLut) {
    key_ = key;
    return true;
  }
  struct {
    int32_t directionsSqrt;
    int32_t steps;
  } push{settings.multipleScatteringDirectionsSqrt, settings.multipleScatteringSteps};
  commands.bind(multipleScatteringPipeline_, {block_, {transmittance_, linearClamp_}, multipleScattering_});
  commands.pushConstants(push);
  commands.dispatch(groups(settings.multipleScatteringSize), groups(settings.multipleScatteringSize), 1,
                    "atmosphere/multiple_scattering_lut");
  commands.barrier();
  key_ = key;
  return true;
}

}  // namespace firmament
