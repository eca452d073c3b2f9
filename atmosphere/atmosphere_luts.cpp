#include "atmosphere/atmosphere_luts.h"

#include <cstdio>

#include "atmosphere/atmosphere_spectra.h"
#include "atmosphere/table_file.h"

namespace firmament {
namespace {
std::string fnv1aHex(const std::string& text) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char out[17];
  std::snprintf(out, sizeof(out), "%016llx", static_cast<unsigned long long>(h));
  return out;
}
}  // namespace

std::string AtmosphereLutSettings::hash() const {
  char text[256];
  std::snprintf(text, sizeof(text), "T%dx%ds%d-M%dd%ds%d-L%.3f,%.3f,%.3f", transmittanceWidth, transmittanceHeight,
                transmittanceSteps, multipleScatteringSize, multipleScatteringDirectionsSqrt, multipleScatteringSteps,
                wavelengthsNm.x, wavelengthsNm.y, wavelengthsNm.z);
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

AtmosphereLuts::Update AtmosphereLuts::update(const AtmosphereSettings& atmosphere,
                                              const AtmosphereLutSettings& settings) {
  std::string key = "atmosphere-luts-v1/" + atmosphere.hash() + "/" + settings.hash() + "/" + context_.description();
  Update result;
  if (key == key_) return result;

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

  std::filesystem::path file;
  if (!context_.cacheDir().empty())
    file = context_.cacheDir() / "tables" / ("atmosphere-" + atmosphere.hash() + "-" + fnv1aHex(key) + ".bin");
  if (!file.empty()) {
    auto tables = readTableFile(file, key);
    if (tables && tables->size() == 2 && (*tables)[0].width == transmittance_.width() &&
        (*tables)[0].height == transmittance_.height() && (*tables)[1].width == multipleScattering_.width() &&
        (*tables)[1].height == multipleScattering_.height()) {
      transmittance_.uploadFloats((*tables)[0].values);
      multipleScattering_.uploadFloats((*tables)[1].values);
      key_ = key;
      result.source = Source::Disk;
      return result;
    }
  }

  gpu::CommandList commands(context_);
  auto groups = [](int n) { return uint32_t((n + 7) / 8); };
  commands.bind(transmittancePipeline_, {block_, transmittance_});
  commands.pushConstants(int32_t(settings.transmittanceSteps));
  commands.dispatch(groups(settings.transmittanceWidth), groups(settings.transmittanceHeight), 1,
                    "atmosphere/transmittance_lut");
  commands.barrier();
  struct {
    int32_t directionsSqrt;
    int32_t steps;
  } push{settings.multipleScatteringDirectionsSqrt, settings.multipleScatteringSteps};
  commands.bind(multipleScatteringPipeline_, {block_, {transmittance_, linearClamp_}, multipleScattering_});
  commands.pushConstants(push);
  commands.dispatch(groups(settings.multipleScatteringSize), groups(settings.multipleScatteringSize), 1,
                    "atmosphere/multiple_scattering_lut");
  commands.submitAndWait();
  result.timings = commands.passTimings();
  result.source = Source::Computed;
  key_ = key;
  if (!file.empty()) {
    writeTableFile(file, key,
                   {TableData{transmittance_.width(), transmittance_.height(), 1, 4, transmittance_.downloadFloats()},
                    TableData{multipleScattering_.width(), multipleScattering_.height(), 1, 4,
                              multipleScattering_.downloadFloats()}});
  }
  return result;
}

}  // namespace firmament
