#include "clouds/cloud_noise.h"

#include "clouds/blue_noise.h"

namespace firmament {
namespace {

struct BakePush {
  int32_t size;
  uint32_t seed;
  int32_t kind;
  int32_t pad;
};

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
      linearRepeat_(context, gpu::Filter::Linear, gpu::AddressMode::Repeat),
      nearestRepeat_(context, gpu::Filter::Nearest, gpu::AddressMode::Repeat) {}

bool CloudNoise::update(uint32_t seed, const CloudNoiseSettings& settings, gpu::CommandList& commands) {
  const std::string key = settings.key(seed);
  if (key == key_) return false;
  auto make = [&](int size, int depth, const char* name) {
    return gpu::Image(context_, {uint32_t(size), uint32_t(size), uint32_t(depth), gpu::Format::RGBA8, true, true, name});
  };
  shape_ = make(settings.shapeSize, settings.shapeSize, "cloud shape noise");
  detail_ = make(settings.detailSize, settings.detailSize, "cloud detail noise");
  curl_ = make(settings.curlSize, 1, "cloud curl noise");
  blueNoise_ = gpu::Image(context_, {uint32_t(settings.blueNoiseSize), uint32_t(settings.blueNoiseSize), 1,
                                     gpu::Format::R32F, false, true, "blue noise"});
  blueNoise_.uploadFloats(blueNoiseMask(settings.blueNoiseSize, seed));

  auto groups = [](int n, int local) { return uint32_t((n + local - 1) / local); };
  BakePush push{settings.shapeSize, seed, 0, 0};
  commands.bind(bake3d_, {shape_});
  commands.pushConstants(push);
  const uint32_t s = groups(settings.shapeSize, 4);
  commands.dispatch(s, s, s, "clouds/bake_noise_3d");
  push = {settings.detailSize, seed, 1, 0};
  commands.bind(bake3d_, {detail_});
  commands.pushConstants(push);
  const uint32_t d = groups(settings.detailSize, 4);
  commands.dispatch(d, d, d, "clouds/bake_noise_3d");
  push = {settings.curlSize, seed, 0, 0};
  commands.bind(bakeCurl_, {curl_});
  commands.pushConstants(push);
  const uint32_t c = groups(settings.curlSize, 8);
  commands.dispatch(c, c, 1, "clouds/bake_curl");
  key_ = key;
  return true;
}

NoiseVolume CloudNoise::downloadShape() const { return download(shape_); }
NoiseVolume CloudNoise::downloadDetail() const { return download(detail_); }
NoiseVolume CloudNoise::downloadCurl() const { return download(curl_); }

}  // namespace firmament
