#include "clouds/cloud_noise.h"

#include "atmosphere/table_file.h"
#include "clouds/blue_noise.h"
#include "core/hash.h"
#include "gpu/shaders.h"

namespace firmament {
namespace {

struct BakePush {
  int32_t size;
  uint32_t seed;
  int32_t kind;
  int32_t pad;
};

struct DownsamplePush {
  int32_t size;  // of the level written
  int32_t pad[3];
};

// Levels down to 4^3 (a 128^3 shape texture: 6, a 32^3 detail texture: 4): the coarsest still holds a
// few cells of the coarsest noise octave.
uint32_t noiseMipLevels(int size) {
  uint32_t levels = 1;
  while ((size >> levels) >= 4) ++levels;
  return levels;
}

// Workgroups of `local` invocations covering n.
uint32_t workgroups(int n, int local) { return uint32_t((n + local - 1) / local); }

NoiseVolume download(const gpu::Image& image) {
  NoiseVolume v;
  v.size = int(image.width());
  v.depth = int(image.depth());
  v.texels = image.downloadFloats();
  return v;
}

}  // namespace

std::string CloudNoiseSettings::key(uint32_t seed) const {
  return std::to_string(seed) + "/" + std::to_string(shapeSize) + "/" + std::to_string(detailSize) + "/" +
         std::to_string(curlSize) + "/" + std::to_string(blueNoiseSize);
}

CloudNoise::CloudNoise(gpu::Context& context)
    : context_(context),
      bake3d_(context, {"clouds/bake_noise_3d", {gpu::BindingType::StorageImage}, sizeof(BakePush)}),
      bakeCurl_(context, {"clouds/bake_curl", {gpu::BindingType::StorageImage}, sizeof(BakePush)}),
      downsample3d_(context, {"clouds/downsample_noise_3d",
                              {gpu::BindingType::StorageImage, gpu::BindingType::StorageImage},
                              sizeof(DownsamplePush)}),
      linearRepeat_(context, gpu::SamplerDesc{gpu::Filter::Linear, gpu::AddressMode::Repeat, gpu::AddressMode::Repeat,
                                              gpu::AddressMode::Repeat, true}),
      nearestRepeat_(context, gpu::Filter::Nearest, gpu::AddressMode::Repeat) {}

bool CloudNoise::update(uint32_t seed, const CloudNoiseSettings& settings, gpu::CommandList& commands) {
  const std::string key = settings.key(seed);
  if (key == key_) {
    source_ = "memory";
    return false;
  }
  auto make = [&](int size, int depth, const char* name, uint32_t levels) {
    return gpu::Image(context_,
                      {uint32_t(size), uint32_t(size), uint32_t(depth), gpu::Format::RGBA8, true, true, name, levels});
  };
  shape_ = make(settings.shapeSize, settings.shapeSize, "cloud shape noise", noiseMipLevels(settings.shapeSize));
  detail_ = make(settings.detailSize, settings.detailSize, "cloud detail noise", noiseMipLevels(settings.detailSize));
  curl_ = make(settings.curlSize, 1, "cloud curl noise", 1);
  blueNoise_ = gpu::Image(context_, {uint32_t(settings.blueNoiseSize), uint32_t(settings.blueNoiseSize), 1,
                                     gpu::Format::R32F, false, true, "blue noise"});
  blueNoise_.uploadFloats(blueNoiseMask(settings.blueNoiseSize, seed));

  // The disk cache: the same bits as a bake on this device with these shaders, or nothing.
  static const std::string code = gpu::shaderCodeHash({"clouds/bake_noise_3d", "clouds/bake_curl"});
  const std::string diskKey = "cloud-noise-v1/" + key + "/" + context_.description() + "/" + code;
  const std::filesystem::path file =
      context_.cacheDir().empty() ? std::filesystem::path()
                                  : context_.cacheDir() / "noise" / ("cloud-noise-" + hex16(fnv1a(diskKey)) + ".bin");
  pendingCacheFile_.clear();
  std::optional<std::vector<TableData>> cached;
  if (!file.empty()) cached = readTableFile(file, diskKey);
  auto fits = [](const TableData& t, const gpu::Image& image) {
    return t.width == image.width() && t.height == image.height() && t.depth == image.depth() && t.channels == 4 &&
           t.bytes.size() == image.byteSize();
  };
  if (cached && cached->size() == 3 && fits((*cached)[0], shape_) && fits((*cached)[1], detail_) &&
      fits((*cached)[2], curl_)) {
    shape_.upload((*cached)[0].bytes.data(), (*cached)[0].bytes.size());
    detail_.upload((*cached)[1].bytes.data(), (*cached)[1].bytes.size());
    curl_.upload((*cached)[2].bytes.data(), (*cached)[2].bytes.size());
    source_ = "disk cache";
  } else {
    recordBake(seed, settings, commands);
    source_ = "baked";
    pendingCacheFile_ = file;
    pendingCacheKey_ = diskKey;
  }
  // The mip chains, level by level (each reads the one before).
  for (gpu::Image* image : {&shape_, &detail_})
    for (uint32_t level = 1; level < image->mipLevels(); ++level) {
      commands.barrier();
      const int size = std::max(int(image->width() >> level), 1);
      commands.bind(downsample3d_, {{*image, gpu::MipLevel{level - 1}}, {*image, gpu::MipLevel{level}}});
      commands.pushConstants(DownsamplePush{size, {0, 0, 0}});
      const uint32_t g = workgroups(size, 4);
      commands.dispatch(g, g, g, "clouds/downsample_noise_3d");
    }
  key_ = key;
  return true;
}

void CloudNoise::recordBake(uint32_t seed, const CloudNoiseSettings& settings, gpu::CommandList& commands) {
  BakePush push{settings.shapeSize, seed, 0, 0};
  commands.bind(bake3d_, {shape_});
  commands.pushConstants(push);
  const uint32_t s = workgroups(settings.shapeSize, 4);
  commands.dispatch(s, s, s, "clouds/bake_noise_3d");
  push = {settings.detailSize, seed, 1, 0};
  commands.bind(bake3d_, {detail_});
  commands.pushConstants(push);
  const uint32_t d = workgroups(settings.detailSize, 4);
  commands.dispatch(d, d, d, "clouds/bake_noise_3d");
  push = {settings.curlSize, seed, 0, 0};
  commands.bind(bakeCurl_, {curl_});
  commands.pushConstants(push);
  const uint32_t c = workgroups(settings.curlSize, 8);
  commands.dispatch(c, c, 1, "clouds/bake_curl");
}

void CloudNoise::storeBaked() {
  if (pendingCacheFile_.empty()) return;
  std::vector<TableData> tables;
  for (const gpu::Image* image : {&shape_, &detail_, &curl_}) {
    TableData t{image->width(), image->height(), image->depth(), 4, {}, std::vector<uint8_t>(image->byteSize())};
    image->download(t.bytes.data(), t.bytes.size());
    tables.push_back(std::move(t));
  }
  writeTableFile(pendingCacheFile_, pendingCacheKey_, tables);
  pendingCacheFile_.clear();
}

NoiseVolume CloudNoise::downloadShape() const { return download(shape_); }
NoiseVolume CloudNoise::downloadDetail() const { return download(detail_); }
NoiseVolume CloudNoise::downloadCurl() const { return download(curl_); }

}  // namespace firmament
