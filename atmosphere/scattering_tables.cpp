#include "atmosphere/scattering_tables.h"

#include <cstdio>

#include "atmosphere/table_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "gpu/shaders.h"

namespace firmament {
namespace {

using gpu::BindingType;

// Push constants: the 4D table size first (std430: ivec4 at offset 0), then the pass's integers.
struct TablePush {
  int32_t tableSize[4];  // nu, mu_s, mu, r
  int32_t value0;        // steps, or the scattering order
  int32_t value1;        // direction samples
};

TablePush tablePush(const ScatteringTableSettings& s, int value0, int value1 = 0) {
  return {{s.nuSize, s.muSSize, s.muSize, s.rSize}, value0, value1};
}

uint32_t groups(int n, int local) { return uint32_t((n + local - 1) / local); }

TableData download(const gpu::Image& image) {
  return TableData{image.width(), image.height(), image.depth(), 4, image.downloadFloats()};
}

bool fits(const TableData& data, const gpu::Image& image) {
  return data.width == image.width() && data.height == image.height() && data.depth == image.depth() &&
         data.channels == 4 && data.values.size() == size_t(data.width) * data.height * data.depth * 4;
}

}  // namespace

std::string ScatteringTableSettings::hash() const {
  char text[160];
  std::snprintf(text, sizeof(text), "N%d-S%dx%dx%dx%d-E%dx%d-s%d-d%d-i%d", scatteringOrders, nuSize, muSSize, muSize,
                rSize, irradianceWidth, irradianceHeight, integrationSteps, densityThetaSamples,
                irradianceThetaSamples);
  return text;
}

ScatteringTables::ScatteringTables(gpu::Context& context)
    : context_(context),
      directIrradiancePipeline_(context, {"atmosphere/direct_irradiance",
                                          {BindingType::UniformBuffer, BindingType::SampledImage,
                                           BindingType::StorageImage, BindingType::StorageImage},
                                          0}),
      singleScatteringPipeline_(context,
                                {"atmosphere/single_scattering",
                                 {BindingType::UniformBuffer, BindingType::SampledImage, BindingType::StorageImage,
                                  BindingType::StorageImage, BindingType::StorageImage},
                                 sizeof(TablePush)}),
      scatteringDensityPipeline_(
          context,
          {"atmosphere/scattering_density",
           {BindingType::UniformBuffer, BindingType::SampledImage, BindingType::SampledImage, BindingType::SampledImage,
            BindingType::SampledImage, BindingType::SampledImage, BindingType::StorageImage},
           sizeof(TablePush)}),
      indirectIrradiancePipeline_(context,
                                  {"atmosphere/indirect_irradiance",
                                   {BindingType::UniformBuffer, BindingType::SampledImage, BindingType::SampledImage,
                                    BindingType::SampledImage, BindingType::StorageImage, BindingType::StorageImage},
                                   sizeof(TablePush)}),
      multipleScatteringPipeline_(context,
                                  {"atmosphere/multiple_scattering",
                                   {BindingType::UniformBuffer, BindingType::SampledImage, BindingType::SampledImage,
                                    BindingType::StorageImage, BindingType::StorageImage},
                                   sizeof(TablePush)}) {}

void ScatteringTables::allocate(const ScatteringTableSettings& s) {
  auto table = [&](const char* name) {
    return gpu::Image(context_, {uint32_t(s.nuSize * s.muSSize), uint32_t(s.muSize), uint32_t(s.rSize),
                                 gpu::Format::RGBA32F, true, true, name});
  };
  auto plane = [&](const char* name) {
    return gpu::Image(context_, {uint32_t(s.irradianceWidth), uint32_t(s.irradianceHeight), 1, gpu::Format::RGBA32F,
                                 true, true, name});
  };
  bool sameTables = scattering_ && settings_.nuSize == s.nuSize && settings_.muSSize == s.muSSize &&
                    settings_.muSize == s.muSize && settings_.rSize == s.rSize;
  if (!sameTables) {
    deltaRayleigh_ = table("delta Rayleigh scattering");
    deltaMie_ = table("single Mie scattering");
    deltaMultiple_ = table("delta multiple scattering");
    scatteringDensity_ = table("scattering density");
    scattering_ = table("scattering");
  }
  bool samePlanes =
      irradiance_ && settings_.irradianceWidth == s.irradianceWidth && settings_.irradianceHeight == s.irradianceHeight;
  if (!samePlanes) {
    deltaIrradiance_ = plane("delta irradiance");
    irradiance_ = plane("ground irradiance");
  }
}

bool ScatteringTables::update(const AtmosphereLuts& luts, size_t batch, const ScatteringTableSettings& s,
                              gpu::CommandList& commands) {
  static const std::string code = gpu::shaderCodeHash(
      {"atmosphere/direct_irradiance", "atmosphere/single_scattering", "atmosphere/scattering_density",
       "atmosphere/indirect_irradiance", "atmosphere/multiple_scattering"});
  std::string key =
      "scattering-tables-v1/" + luts.unscaledKey() + "/batch" + std::to_string(batch) + "/" + s.hash() + "/" + code;
  source_ = "memory";
  if (key == key_) return false;
  if (s.scatteringOrders < 1 || s.nuSize < 2 || s.muSSize < 2 || s.muSize < 4 || s.muSize % 2 != 0 || s.rSize < 2 ||
      s.irradianceWidth < 2 || s.irradianceHeight < 2 || s.integrationSteps < 1 || s.densityThetaSamples < 1 ||
      s.densityThetaSamples > 16 || s.irradianceThetaSamples < 1)
    throw InputError("scattering table settings out of range (" + s.hash() +
                     "): orders >= 1, sizes >= 2 with mu even, density theta samples 1..16");
  allocate(s);
  settings_ = s;
  solarIrradianceScale_ = luts.solarIrradianceScale();
  // The disk cache: the summed scattering, single Mie and ground irradiance, at the scale they hold.
  pendingFile_.clear();
  if (!context_.cacheDir().empty()) {
    const std::filesystem::path file = context_.cacheDir() / "tables" / ("scattering-" + hex16(fnv1a(key)) + ".bin");
    const auto tables = readTableFile(file, key);
    if (tables && tables->size() == 4 && fits((*tables)[0], scattering_) && fits((*tables)[1], deltaMie_) &&
        fits((*tables)[2], irradiance_) && (*tables)[3].values.size() == 1) {
      scattering_.uploadFloats((*tables)[0].values);
      deltaMie_.uploadFloats((*tables)[1].values);
      irradiance_.uploadFloats((*tables)[2].values);
      solarIrradianceScale_ = (*tables)[3].values[0];
      key_ = key;
      source_ = "disk cache";
      return false;
    }
    pendingFile_ = file;
  }
  source_ = "computed";

  const int tableWidth = s.nuSize * s.muSSize;
  const gpu::Sampler& linear = luts.linearClamp();
  const gpu::Buffer& block = luts.batch(batch).block;
  const gpu::Image& transmittance = luts.batch(batch).transmittance;

  // 1. Direct irradiance (lights the ground for order 2); the sky irradiance table starts at zero.
  commands.bind(directIrradiancePipeline_, {block, {transmittance, linear}, deltaIrradiance_, irradiance_});
  commands.dispatch(groups(s.irradianceWidth, 8), groups(s.irradianceHeight, 8), 1, "atmosphere/direct_irradiance");
  commands.barrier();

  // 2. Single scattering.
  commands.bind(singleScatteringPipeline_, {block, {transmittance, linear}, deltaRayleigh_, deltaMie_, scattering_});
  commands.pushConstants(tablePush(s, s.integrationSteps));
  commands.dispatch(groups(tableWidth, 4), groups(s.muSize, 4), groups(s.rSize, 4), "atmosphere/single_scattering");
  commands.barrier();

  // 3. Orders 2..N: density of order n, ground irradiance of order n - 1, radiance of order n.
  for (int order = 2; order <= s.scatteringOrders; ++order) {
    commands.bind(scatteringDensityPipeline_, {block,
                                               {transmittance, linear},
                                               {deltaRayleigh_, linear},
                                               {deltaMie_, linear},
                                               {deltaMultiple_, linear},
                                               {deltaIrradiance_, linear},
                                               scatteringDensity_});
    commands.pushConstants(tablePush(s, order, s.densityThetaSamples));
    commands.dispatch(uint32_t(s.muSSize), uint32_t(s.rSize), 1, "atmosphere/scattering_density");
    commands.barrier();

    commands.bind(indirectIrradiancePipeline_, {block,
                                                {deltaRayleigh_, linear},
                                                {deltaMie_, linear},
                                                {deltaMultiple_, linear},
                                                deltaIrradiance_,
                                                irradiance_});
    commands.pushConstants(tablePush(s, order - 1, s.irradianceThetaSamples));
    commands.dispatch(groups(s.irradianceWidth, 8), groups(s.irradianceHeight, 8), 1, "atmosphere/indirect_irradiance");
    commands.barrier();

    commands.bind(multipleScatteringPipeline_,
                  {block, {transmittance, linear}, {scatteringDensity_, linear}, deltaMultiple_, scattering_});
    commands.pushConstants(tablePush(s, s.integrationSteps));
    commands.dispatch(groups(tableWidth, 4), groups(s.muSize, 4), groups(s.rSize, 4), "atmosphere/multiple_scattering");
    commands.barrier();
  }
  key_ = key;
  return true;
}

void ScatteringTables::store() {
  if (pendingFile_.empty()) return;
  TableData scale{1, 1, 1, 1, {float(solarIrradianceScale_)}};
  writeTableFile(pendingFile_, key_, {download(scattering_), download(deltaMie_), download(irradiance_), scale});
  pendingFile_.clear();
}

}  // namespace firmament
