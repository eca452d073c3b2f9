#pragma once
// A 2D or 3D VkImage with its own memory and a view, usable as a storage image and a sampled texture.
// Between operations it is always in VK_IMAGE_LAYOUT_GENERAL, where compute writes and sampling are
// both legal, so passes never track layouts (upload/download switch to transfer layouts and back).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace firmament::gpu {

class Context;

enum class Format {
  RGBA32F,  // VK_FORMAT_R32G32B32A32_SFLOAT, GLSL rgba32f
  RGBA16F,  // VK_FORMAT_R16G16B16A16_SFLOAT, GLSL rgba16f
  RG32F,    // VK_FORMAT_R32G32_SFLOAT, GLSL rg32f
  RG16F,    // VK_FORMAT_R16G16_SFLOAT, GLSL rg16f
  R32F,     // VK_FORMAT_R32_SFLOAT, GLSL r32f
  R16F,     // VK_FORMAT_R16_SFLOAT, GLSL r16f
  RGBA8,    // VK_FORMAT_R8G8B8A8_UNORM, GLSL rgba8
};
VkFormat vulkanFormat(Format format);
uint32_t channelCount(Format format);
uint32_t bytesPerTexel(Format format);
const char* formatName(Format format);

struct ImageDesc {
  uint32_t width = 1;
  uint32_t height = 1;
  uint32_t depth = 1;  // > 1 makes a 3D image
  Format format = Format::RGBA32F;
  bool storage = true;  // imageLoad / imageStore
  bool sampled = true;  // texture() through a Sampler
  std::string name;     // shows in validation messages
  // Levels of the mip chain (level k is max(1, size >> k) per axis). Sampling sees every level; a
  // storage binding sees one (CommandList::bind with MipLevel). upload/download reach level 0 only
  // (downloadFloats(level) any).
  uint32_t mipLevels = 1;
};

class Image {
 public:
  Image() = default;
  Image(Context& context, const ImageDesc& desc);
  ~Image();
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }      // every mip level
  VkImageView storageView(uint32_t level) const;  // one level, for a storage binding
  uint32_t mipLevels() const { return desc_.mipLevels; }
  const ImageDesc& desc() const { return desc_; }
  uint32_t width() const { return desc_.width; }
  uint32_t height() const { return desc_.height; }
  uint32_t depth() const { return desc_.depth; }
  bool is3D() const { return desc_.depth > 1; }
  Format format() const { return desc_.format; }
  size_t texelCount() const { return size_t(desc_.width) * desc_.height * desc_.depth; }
  size_t byteSize() const { return texelCount() * bytesPerTexel(desc_.format); }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

  // The whole image as tightly packed texels in the image's own format (x fastest, then y, then z).
  void upload(const void* data, size_t bytes);
  void download(void* data, size_t bytes) const;
  // The same, as floats (channelCount() per texel), converted to and from half or 8-bit unorm.
  void uploadFloats(std::span<const float> values);
  std::vector<float> downloadFloats() const { return downloadFloats(0); }
  std::vector<float> downloadFloats(uint32_t level) const;

 private:
  void release();
  void downloadLevel(void* data, size_t bytes, uint32_t level) const;
  glm::uvec3 levelExtent(uint32_t level) const;

  Context* context_ = nullptr;
  ImageDesc desc_;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  std::vector<VkImageView> levelViews_;  // one per level when mipLevels > 1
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
};

}  // namespace firmament::gpu
