#include "gpu/image.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <utility>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/memory.h"

namespace firmament::gpu {

VkFormat vulkanFormat(Format format) {
  switch (format) {
    case Format::RGBA32F:
      return VK_FORMAT_R32G32B32A32_SFLOAT;
    case Format::RGBA16F:
      return VK_FORMAT_R16G16B16A16_SFLOAT;
    case Format::RG32F:
      return VK_FORMAT_R32G32_SFLOAT;
    case Format::RG16F:
      return VK_FORMAT_R16G16_SFLOAT;
    case Format::R32F:
      return VK_FORMAT_R32_SFLOAT;
    case Format::R16F:
      return VK_FORMAT_R16_SFLOAT;
    case Format::RGBA8:
      return VK_FORMAT_R8G8B8A8_UNORM;
  }
  return VK_FORMAT_UNDEFINED;
}

uint32_t channelCount(Format format) {
  switch (format) {
    case Format::RGBA32F:
    case Format::RGBA16F:
    case Format::RGBA8:
      return 4;
    case Format::RG32F:
    case Format::RG16F:
      return 2;
    case Format::R32F:
    case Format::R16F:
      return 1;
  }
  return 0;
}

namespace {
uint32_t bytesPerChannel(Format format) {
  switch (format) {
    case Format::RGBA32F:
    case Format::RG32F:
    case Format::R32F:
      return 4;
    case Format::RGBA16F:
    case Format::RG16F:
    case Format::R16F:
      return 2;
    case Format::RGBA8:
      return 1;
  }
  return 0;
}
}  // namespace

uint32_t bytesPerTexel(Format format) { return channelCount(format) * bytesPerChannel(format); }

const char* formatName(Format format) {
  switch (format) {
    case Format::RGBA32F:
      return "rgba32f";
    case Format::RGBA16F:
      return "rgba16f";
    case Format::RG32F:
      return "rg32f";
    case Format::RG16F:
      return "rg16f";
    case Format::R32F:
      return "r32f";
    case Format::R16F:
      return "r16f";
    case Format::RGBA8:
      return "rgba8";
  }
  return "?";
}

Image::Image(Context& context, const ImageDesc& desc) : context_(&context), desc_(desc) {
  if (desc.width == 0 || desc.height == 0 || desc.depth == 0)
    throw RuntimeError("gpu::Image " + desc.name + ": zero extent");
  if (!desc.storage && !desc.sampled) throw RuntimeError("gpu::Image " + desc.name + ": neither storage nor sampled");
  const uint32_t largest = std::max({desc.width, desc.height, desc.depth});
  uint32_t fullChain = 1;
  while ((largest >> fullChain) > 0) ++fullChain;
  if (desc.mipLevels == 0 || desc.mipLevels > fullChain)
    throw RuntimeError("gpu::Image " + desc.name + ": " + std::to_string(desc.mipLevels) +
                       " mip levels; allowed 1 to " + std::to_string(fullChain));
  VkFormat format = vulkanFormat(desc.format);
  VkFormatProperties properties;
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), format, &properties);
  VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_TRANSFER_SRC_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
  if (desc.storage) needed |= VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
  if (desc.sampled) needed |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
  if ((properties.optimalTilingFeatures & needed) != needed)
    throw RuntimeError(std::string("gpu::Image ") + desc.name + ": format " + formatName(desc.format) +
                       " lacks storage/sampled/transfer support on " + context.deviceName());

  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = is3D() ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {desc.width, desc.height, desc.depth};
  info.mipLevels = desc.mipLevels;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (desc.storage) info.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
  if (desc.sampled) info.usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkDevice device = context.device();
  FIRMAMENT_VK(vkCreateImage(device, &info, nullptr, &image_));
  try {
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device, image_, &requirements);
    VkMemoryPropertyFlags flags = 0;
    memory_ = allocateMemory(context, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, flags);
    FIRMAMENT_VK(vkBindImageMemory(device, image_, memory_, 0));

    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image_;
    viewInfo.viewType = is3D() ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, desc.mipLevels, 0, 1};
    FIRMAMENT_VK(vkCreateImageView(device, &viewInfo, nullptr, &view_));
    // A storage descriptor reads or writes one level: a view per level.
    if (desc.mipLevels > 1 && desc.storage)
      for (uint32_t level = 0; level < desc.mipLevels; ++level) {
        viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, 1};
        VkImageView levelView = VK_NULL_HANDLE;
        FIRMAMENT_VK(vkCreateImageView(device, &viewInfo, nullptr, &levelView));
        levelViews_.push_back(levelView);
      }

    // Into GENERAL once; the contents start undefined (upload or a pass fills them).
    context.submitOneShot([&](VkCommandBuffer commands) {
      VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      barrier.srcAccessMask = 0;
      barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
      barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      barrier.newLayout = VK_IMAGE_LAYOUT_GENERAL;
      barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      barrier.image = image_;
      barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1};
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                           nullptr, 0, nullptr, 1, &barrier);
    });
  } catch (...) {
    release();
    throw;
  }
  context.setObjectName(VK_OBJECT_TYPE_IMAGE, uint64_t(image_), desc.name);
  context.setObjectName(VK_OBJECT_TYPE_IMAGE_VIEW, uint64_t(view_), desc.name);
}

Image::~Image() { release(); }

void Image::release() {
  if (!context_) return;
  VkDevice device = context_->device();
  for (VkImageView levelView : levelViews_) vkDestroyImageView(device, levelView, nullptr);
  levelViews_.clear();
  if (view_) vkDestroyImageView(device, view_, nullptr);
  if (image_) vkDestroyImage(device, image_, nullptr);
  if (memory_) vkFreeMemory(device, memory_, nullptr);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  context_ = nullptr;
}

Image::Image(Image&& other) noexcept { *this = std::move(other); }

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    desc_ = std::move(other.desc_);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    levelViews_ = std::exchange(other.levelViews_, {});
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
  }
  return *this;
}

namespace {
// Layout change with a full memory dependency (transfers want their own layouts for speed on GPUs).
void transition(VkCommandBuffer commands, VkImage image, VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1};
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr,
                       0, nullptr, 1, &barrier);
}

VkBufferImageCopy wholeLevelRegion(glm::uvec3 extent, uint32_t level) {
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
  region.imageExtent = {extent.x, extent.y, extent.z};
  return region;  // buffer rows tightly packed (rowLength 0)
}
}  // namespace

void Image::upload(const void* data, size_t bytes) {
  if (!image_) throw RuntimeError("gpu::Image: upload to an empty image");
  if (bytes != byteSize())
    throw RuntimeError("gpu::Image " + desc_.name + ": upload of " + std::to_string(bytes) + " bytes, image holds " +
                       std::to_string(byteSize()));
  Buffer staging(*context_, bytes, BufferUsage::Storage, MemoryLocation::Host);
  std::memcpy(staging.mapped(), data, bytes);
  VkBufferImageCopy region = wholeLevelRegion(levelExtent(0), 0);
  context_->submitOneShot([&](VkCommandBuffer commands) {
    transition(commands, image_, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    vkCmdCopyBufferToImage(commands, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transition(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
  });
}

VkImageView Image::storageView(uint32_t level) const {
  if (level >= desc_.mipLevels)
    throw RuntimeError("gpu::Image " + desc_.name + ": level " + std::to_string(level) + " of " +
                       std::to_string(desc_.mipLevels));
  return levelViews_.empty() ? view_ : levelViews_[level];
}

glm::uvec3 Image::levelExtent(uint32_t level) const {
  return {std::max(desc_.width >> level, 1u), std::max(desc_.height >> level, 1u), std::max(desc_.depth >> level, 1u)};
}

void Image::download(void* data, size_t bytes) const { downloadLevel(data, bytes, 0); }

void Image::downloadLevel(void* data, size_t bytes, uint32_t level) const {
  if (!image_) throw RuntimeError("gpu::Image: download from an empty image");
  const glm::uvec3 extent = levelExtent(level);
  const size_t levelBytes = size_t(extent.x) * extent.y * extent.z * bytesPerTexel(desc_.format);
  if (level >= desc_.mipLevels || bytes != levelBytes)
    throw RuntimeError("gpu::Image " + desc_.name + ": download of " + std::to_string(bytes) + " bytes of level " +
                       std::to_string(level) + ", it holds " + std::to_string(levelBytes));
  Buffer staging(*context_, bytes, BufferUsage::Storage, MemoryLocation::Host);
  VkBufferImageCopy region = wholeLevelRegion(extent, level);
  context_->submitOneShot([&](VkCommandBuffer commands) {
    transition(commands, image_, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    vkCmdCopyImageToBuffer(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1, &region);
    transition(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    fullMemoryBarrier(commands);  // the staging copy is visible to the host after the fence
  });
  std::memcpy(data, staging.mapped(), bytes);
}

void Image::uploadFloats(std::span<const float> values) {
  size_t expected = texelCount() * channelCount(desc_.format);
  if (values.size() != expected)
    throw RuntimeError("gpu::Image " + desc_.name + ": " + std::to_string(values.size()) + " floats given, " +
                       std::to_string(expected) + " expected");
  switch (bytesPerChannel(desc_.format)) {
    case 4:
      upload(values.data(), values.size_bytes());
      return;
    case 2: {
      std::vector<uint16_t> halves(values.size());
      for (size_t i = 0; i < values.size(); ++i) halves[i] = glm::packHalf1x16(values[i]);
      upload(halves.data(), halves.size() * 2);
      return;
    }
    default: {
      std::vector<uint8_t> bytes(values.size());
      for (size_t i = 0; i < values.size(); ++i)
        bytes[i] = uint8_t(std::lround(std::clamp(values[i], 0.0f, 1.0f) * 255.0f));
      upload(bytes.data(), bytes.size());
      return;
    }
  }
}

std::vector<float> Image::downloadFloats(uint32_t level) const {
  const glm::uvec3 extent = levelExtent(level);
  std::vector<float> values(size_t(extent.x) * extent.y * extent.z * channelCount(desc_.format));
  switch (bytesPerChannel(desc_.format)) {
    case 4:
      downloadLevel(values.data(), values.size() * 4, level);
      break;
    case 2: {
      std::vector<uint16_t> halves(values.size());
      downloadLevel(halves.data(), halves.size() * 2, level);
      for (size_t i = 0; i < values.size(); ++i) values[i] = glm::unpackHalf1x16(halves[i]);
      break;
    }
    default: {
      std::vector<uint8_t> bytes(values.size());
      downloadLevel(bytes.data(), bytes.size(), level);
      for (size_t i = 0; i < values.size(); ++i) values[i] = float(bytes[i]) / 255.0f;
      break;
    }
  }
  return values;
}

}  // namespace firmament::gpu
