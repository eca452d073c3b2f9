#include "atmosphere/atmosphere_luts.h"

#include <algorithm>
#include <cstdio>

#include "atmosphere/atmosphere_spectra.h"
#include "atmosphere/table_file.h"
#include "common/atmosphere_lut.glsl"  // kAnisotropyTiles
#include "core/hash.h"
#include "gpu/shaders.h"

namespace firmament {
namespace {

gpu::Image makeTable(gpu::Context& context, int width, int height, const char* name) {
  return gpu::Image(context, {uint32_t(width), uint32_t(height), 1, gpu::Format::RGBA32F, true, true, name});
}

TableData download(const gpu::Image& image) {
  return TableData{image.width(), image.height(), image.depth(), 4, image.downloadFloats()};
}

bool fits(const TableData& data, const gpu::Image& image) {
  return data.width == image.width() && data.height == image.height() && data.depth == image.depth() &&
         data.channels == 4 && data.values.size() == size_t(data.width) * data.height * data.depth * 4;
}

// Both variants of shaders/atmosphere/multiple_scattering_lut.glsl share one layout.
gpu::PipelineDesc multipleScatteringPipeline(const char* shader) {
  return {shader,
          {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::StorageImage,
           gpu::BindingType::SampledImage, gpu::BindingType::SampledImage, gpu::BindingType::StorageImage,
           gpu::BindingType::StorageImage, gpu::BindingType::StorageImage},
          6 * sizeof(int32_t)};
}

}  // namespace

std::string AtmosphereLutSettings::hash() const {
  char text[256];
  std::snprintf(text, sizeof(text), "T%dx%ds%d-M%dd%dx%ds%do%d%s-S%d-L%.3f,%.3f,%.3f", transmittanceWidth,
                transmittanceHeight, transmittanceSteps, multipleScatteringSize, multipleScatteringThetaSamples,
                multipleScatteringPhiSamples, multipleScatteringSteps, multipleScatteringOrders,
                multipleScatteringLut ? "" : "-off", spectralSamples, wavelengthsNm.x, wavelengthsNm.y,
                wavelengthsNm.z);
  return text;
}

AtmosphereLuts::AtmosphereLuts(gpu::Context& context)
    : context_(context),
      transmittancePipeline_(
          context, {"atmosphere/transmittance_lut",
                    {gpu::BindingType::UniformBuffer, gpu::BindingType::StorageImage, gpu::BindingType::StorageImage},
                    2 * sizeof(int32_t)}),
      multipleScatteringPipeline_(context, multipleScatteringPipeline("atmosphere/multiple_scattering_lut")),
      multipleScatteringOrderPipeline_(context, multipleScatteringPipeline("atmosphere/multiple_scattering_order")),
      linearClamp_(context, gpu::Filter::Linear, gpu::AddressMode::Clamp) {}

AtmosphereLuts::Update AtmosphereLuts::update(const AtmosphereSettings& atmosphere,
                                              const AtmosphereLutSettings& settings) {
  static const std::string code = gpu::shaderCodeHash(
      {"atmosphere/transmittance_lut", "atmosphere/multiple_scattering_lut", "atmosphere/multiple_scattering_order"});
  std::string key =
      "atmosphere-luts-v3/" + atmosphere.hash() + "/" + settings.hash() + "/" + context_.description() + "/" + code;
  Update result;
  if (key == key_) return result;
  // Without the Sun's distance, and with or without Psi_ms alike (the transmittance and the blocks the
  // tables read do not depend on either).
  AtmosphereSettings unscaled = atmosphere;
  unscaled.solarIrradianceScale = 1.0;
  AtmosphereLutSettings withPsi = settings;
  withPsi.multipleScatteringLut = true;
  unscaledKey_ =
      "atmosphere-luts-v3/" + unscaled.hash() + "/" + withPsi.hash() + "/" + context_.description() + "/" + code;
  solarIrradianceScale_ = atmosphere.solarIrradianceScale;

  // Parameters and tables of every batch (kept when only their contents change).
  std::vector<SpectralBatch> spectra = spectralBatches(settings.spectralSamples, settings.wavelengthsNm);
  batches_.resize(spectra.size());
  for (size_t b = 0; b < spectra.size(); ++b) {
    Batch& batch = batches_[b];
    batch.parameters = atmosphereParametersAt(atmosphere, spectra[b].wavelengthsNm);
    AtmosphereBlock block = packAtmosphereBlock(batch.parameters, spectra[b].skyToRgb, spectra[b].sunToRgb);
    if (!batch.block)
      batch.block = gpu::Buffer(context_, sizeof(AtmosphereBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host,
                                "atmosphere block");
    batch.block.upload(&block, sizeof(block));
    if (!batch.transmittance || int(batch.transmittance.width()) != settings.transmittanceWidth ||
        int(batch.transmittance.height()) != settings.transmittanceHeight)
      batch.transmittance =
          makeTable(context_, settings.transmittanceWidth, settings.transmittanceHeight, "transmittance LUT");
    if (!batch.multipleScattering || int(batch.multipleScattering.width()) != settings.multipleScatteringSize)
      batch.multipleScattering = makeTable(context_, settings.multipleScatteringSize, settings.multipleScatteringSize,
                                           "multiple-scattering LUT");
    if (!batch.multipleScatteringAnisotropy ||
        int(batch.multipleScatteringAnisotropy.height()) != settings.multipleScatteringSize)
      batch.multipleScatteringAnisotropy =
          gpu::Image(context_, {uint32_t(kAnisotropyTiles * settings.multipleScatteringSize),
                                uint32_t(settings.multipleScatteringSize), 1, gpu::Format::RGBA32F, true, true,
                                "multiple-scattering anisotropy"});
  }
  if (!sunRadiance_ || int(sunRadiance_.width()) != settings.transmittanceWidth ||
      int(sunRadiance_.height()) != settings.transmittanceHeight)
    sunRadiance_ = makeTable(context_, settings.transmittanceWidth, settings.transmittanceHeight, "sun radiance LUT");

  std::filesystem::path file;
  if (!context_.cacheDir().empty())
    file = context_.cacheDir() / "tables" / ("atmosphere-" + atmosphere.hash() + "-" + hex16(fnv1a(key)) + ".bin");
  if (!file.empty()) {
    auto tables = readTableFile(file, key);
    if (tables && tables->size() == 3 * batches_.size() + 1) {
      bool ok = fits(tables->back(), sunRadiance_);
      for (size_t b = 0; b < batches_.size() && ok; ++b)
        ok = fits((*tables)[3 * b], batches_[b].transmittance) &&
             fits((*tables)[3 * b + 1], batches_[b].multipleScattering) &&
             fits((*tables)[3 * b + 2], batches_[b].multipleScatteringAnisotropy);
      if (ok) {
        for (size_t b = 0; b < batches_.size(); ++b) {
          batches_[b].transmittance.uploadFloats((*tables)[3 * b].values);
          batches_[b].multipleScattering.uploadFloats((*tables)[3 * b + 1].values);
          batches_[b].multipleScatteringAnisotropy.uploadFloats((*tables)[3 * b + 2].values);
        }
        sunRadiance_.uploadFloats(tables->back().values);
        key_ = key;
        result.source = Source::Disk;
        return result;
      }
    }
  }

  gpu::CommandList commands(context_);
  auto groups = [](int n) { return uint32_t((n + 7) / 8); };
  for (size_t b = 0; b < batches_.size(); ++b) {
    const Batch& batch = batches_[b];
    struct {
      int32_t steps;
      int32_t accumulate;
    } transmittancePush{settings.transmittanceSteps, b > 0 ? 1 : 0};
    commands.bind(transmittancePipeline_, {batch.block, batch.transmittance, sunRadiance_});
    commands.pushConstants(transmittancePush);
    commands.dispatch(groups(settings.transmittanceWidth), groups(settings.transmittanceHeight), 1,
                      "atmosphere/transmittance_lut");
    commands.barrier();
    if (!settings.multipleScatteringLut) continue;
    // Psi_ms order by order: order k reads J_{k-1} and E_{k-1} from one scratch pair, writes J_k and E_k
    // to the other, and adds J_k (the last order also its geometric tail) to the table.
    const int size = settings.multipleScatteringSize;
    for (int i = 0; i < 2; ++i) {
      if (!orders_[i] || int(orders_[i].width()) != size) {
        orders_[i] = makeTable(context_, size, size, "multiple-scattering order");
        groundOrders_[i] = makeTable(context_, size, 1, "multiple-scattering ground irradiance order");
      }
    }
    const int orders = std::max(settings.multipleScatteringOrders, 1);
    for (int k = 1; k <= orders; ++k) {
      struct {
        int32_t thetaSamples;
        int32_t phiSamples;
        int32_t steps;
        int32_t order;
        int32_t last;
        int32_t realPhase;
      } multiplePush{settings.multipleScatteringThetaSamples,
                     settings.multipleScatteringPhiSamples,
                     settings.multipleScatteringSteps,
                     k,
                     k == orders ? 1 : 0,
                     orders > 1 ? 1 : 0};
      const int read = k % 2, write = 1 - k % 2;
      commands.bind(k == 1 ? multipleScatteringPipeline_ : multipleScatteringOrderPipeline_,
                    {batch.block,
                     {batch.transmittance, linearClamp_},
                     batch.multipleScattering,
                     {orders_[read], linearClamp_},
                     {groundOrders_[read], linearClamp_},
                     orders_[write],
                     groundOrders_[write],
                     batch.multipleScatteringAnisotropy});
      commands.pushConstants(multiplePush);
      commands.dispatch(groups(size), groups(size), 1,
                        k == 1 ? "atmosphere/multiple_scattering_lut" : "atmosphere/multiple_scattering_order");
      commands.barrier();
    }
  }
  commands.submitAndWait();
  result.timings = commands.passTimings();
  result.source = Source::Computed;
  key_ = key;
  if (!file.empty()) {
    std::vector<TableData> tables;
    for (const auto& batch : batches_) {
      tables.push_back(download(batch.transmittance));
      tables.push_back(download(batch.multipleScattering));
      tables.push_back(download(batch.multipleScatteringAnisotropy));
    }
    tables.push_back(download(sunRadiance_));
    writeTableFile(file, key, tables);
  }
  return result;
}

}  // namespace firmament
