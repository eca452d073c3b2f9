#include "gpu/buffer.h"

#include <cstring>
#include <utility>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/memory.h"

namespace firmament::gpu {

Buffer::Buffer(Context& context, VkDeviceSize size, BufferUsage usage, MemoryLocation location, const std::string& name)
    : context_(&context), size_(size), usage_(usage) {
  if (size == 0) throw RuntimeError("gpu::Buffer " + name + ": size 0");
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  if (hasUsage(usage, BufferUsage::Storage)) info.usage |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (hasUsage(usage, BufferUsage::Uniform)) info.usage |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkDevice device = context.device();
  FIRMAMENT_VK(vkCreateBuffer(device, &info, nullptr, &buffer_));
  try {
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device, buffer_, &requirements);
    constexpr VkMemoryPropertyFlags hostFlags =
        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    VkMemoryPropertyFlags flags = 0;
    if (location == MemoryLocation::Host)
      memory_ = allocateMemory(context, requirements, hostFlags, 0, flags);
    else
      memory_ = allocateMemory(context, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, flags);
    FIRMAMENT_VK(vkBindBufferMemory(device, buffer_, memory_, 0));
    // Device memory that happens to be host-visible and coherent (lavapipe, unified memory) is mapped
    // too, so transfers become a memcpy instead of a staging copy.
    if ((flags & hostFlags) == hostFlags) FIRMAMENT_VK(vkMapMemory(device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
  } catch (...) {
    release();
    throw;
  }
  context.setObjectName(VK_OBJECT_TYPE_BUFFER, uint64_t(buffer_), name);
}

Buffer::~Buffer() { release(); }

void Buffer::release() {
  if (!context_) return;
  VkDevice device = context_->device();
  if (buffer_) vkDestroyBuffer(device, buffer_, nullptr);
  if (memory_) vkFreeMemory(device, memory_, nullptr);  // unmaps implicitly
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  context_ = nullptr;
}

Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    usage_ = other.usage_;
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

void Buffer::checkRange(VkDeviceSize bytes, VkDeviceSize offset) const {
  if (!buffer_) throw RuntimeError("gpu::Buffer: transfer on an empty buffer");
  if (offset > size_ || bytes > size_ - offset)
    throw RuntimeError("gpu::Buffer: transfer of " + std::to_string(bytes) + " bytes at offset " +
                       std::to_string(offset) + " overruns a buffer of " + std::to_string(size_));
}

void Buffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  checkRange(bytes, offset);
  if (bytes == 0) return;
  if (mapped_) {
    std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
    return;
  }
  Buffer staging(*context_, bytes, BufferUsage::Storage, MemoryLocation::Host);
  std::memcpy(staging.mapped(), data, bytes);
  context_->submitOneShot([&](VkCommandBuffer commands) {
    fullMemoryBarrier(commands);  // earlier shader reads of this buffer finish before it is overwritten
    VkBufferCopy region{0, offset, bytes};
    vkCmdCopyBuffer(commands, staging.handle(), buffer_, 1, &region);
    fullMemoryBarrier(commands);
  });
}

void Buffer::download(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
  checkRange(bytes, offset);
  if (bytes == 0) return;
  if (mapped_) {
    std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
    return;
  }
  Buffer staging(*context_, bytes, BufferUsage::Storage, MemoryLocation::Host);
  context_->submitOneShot([&](VkCommandBuffer commands) {
    fullMemoryBarrier(commands);
    VkBufferCopy region{offset, 0, bytes};
    vkCmdCopyBuffer(commands, buffer_, staging.handle(), 1, &region);
    fullMemoryBarrier(commands);  // the copy is visible to the host after the fence
  });
  std::memcpy(data, staging.mapped(), bytes);
}

}  // namespace firmament::gpu
