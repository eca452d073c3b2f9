#pragma once
// A VkSampler for texture() lookups in compute shaders: filter, per-axis wrap, and optionally mip
// levels (the nearest level to textureLod's lod; without, level 0 always).
#include <vulkan/vulkan.h>

namespace firmament::gpu {

class Context;

enum class Filter { Nearest, Linear };
enum class AddressMode { Clamp, Repeat };  // clamp to edge; repeat (e.g. azimuth of a sky-view LUT)

struct SamplerDesc {
  Filter filter = Filter::Linear;
  AddressMode u = AddressMode::Clamp;
  AddressMode v = AddressMode::Clamp;
  AddressMode w = AddressMode::Clamp;
  bool mipmaps = false;
};

class Sampler {
 public:
  Sampler() = default;
  Sampler(Context& context, const SamplerDesc& desc);
  Sampler(Context& context, Filter filter, AddressMode mode)
      : Sampler(context, SamplerDesc{filter, mode, mode, mode}) {}
  ~Sampler();
  Sampler(Sampler&& other) noexcept;
  Sampler& operator=(Sampler&& other) noexcept;
  Sampler(const Sampler&) = delete;
  Sampler& operator=(const Sampler&) = delete;

  VkSampler handle() const { return sampler_; }
  const SamplerDesc& desc() const { return desc_; }

 private:
  void release();
  Context* context_ = nullptr;
  SamplerDesc desc_;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace firmament::gpu
