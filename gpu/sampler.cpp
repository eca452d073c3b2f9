#include "gpu/sampler.h"

#include <utility>

#include "gpu/check.h"
#include "gpu/context.h"

namespace firmament::gpu {
namespace {
VkSamplerAddressMode toVulkan(AddressMode mode) {
  return mode == AddressMode::Repeat ? VK_SAMPLER_ADDRESS_MODE_REPEAT : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
}
}  // namespace

Sampler::Sampler(Context& context, const SamplerDesc& desc) : context_(&context), desc_(desc) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  VkFilter filter = desc.filter == Filter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  info.magFilter = filter;
  info.minFilter = filter;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = toVulkan(desc.u);
  info.addressModeV = toVulkan(desc.v);
  info.addressModeW = toVulkan(desc.w);
  info.maxLod = desc.mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
  info.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
  FIRMAMENT_VK(vkCreateSampler(context.device(), &info, nullptr, &sampler_));
}

Sampler::~Sampler() { release(); }

void Sampler::release() {
  if (context_ && sampler_) vkDestroySampler(context_->device(), sampler_, nullptr);
  sampler_ = VK_NULL_HANDLE;
  context_ = nullptr;
}

Sampler::Sampler(Sampler&& other) noexcept { *this = std::move(other); }

Sampler& Sampler::operator=(Sampler&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    desc_ = other.desc_;
    sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
  }
  return *this;
}

}  // namespace firmament::gpu
