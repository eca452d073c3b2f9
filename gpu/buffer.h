#pragma once
// A VkBuffer with its own memory. Device buffers are filled and read through a staging copy (or a
// plain memcpy where device memory is host-visible, as on lavapipe); host buffers stay mapped, for
// small uniform data rewritten every frame. All transfers are synchronous.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace firmament::gpu {

class Context;

// What a shader sees the buffer as; transfers in and out are always allowed.
enum class BufferUsage : uint32_t { Storage = 1, Uniform = 2 };
constexpr BufferUsage operator|(BufferUsage a, BufferUsage b) { return BufferUsage(uint32_t(a) | uint32_t(b)); }
constexpr bool hasUsage(BufferUsage set, BufferUsage bit) { return (uint32_t(set) & uint32_t(bit)) != 0; }

enum class MemoryLocation {
  Device,  // fastest for shaders; filled by upload()
  Host,    // host-visible, coherent, persistently mapped (staging, small uniform blocks, readback)
};

class Buffer {
 public:
  Buffer() = default;
  Buffer(Context& context, VkDeviceSize size, BufferUsage usage, MemoryLocation location = MemoryLocation::Device,
         const std::string& name = {});
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  BufferUsage usage() const { return usage_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }
  // Non-null when the memory is mapped (always for MemoryLocation::Host).
  void* mapped() const { return mapped_; }

  // Copies `bytes` bytes between host memory and the buffer at `offset`. Waits for completion; the
  // caller makes sure no submitted work still uses the buffer (every CommandList submit waits).
  void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  void download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;

  template <class T>
  void upload(std::span<const T> values, VkDeviceSize offset = 0) {
    upload(values.data(), values.size_bytes(), offset);
  }
  template <class T>
  void upload(const std::vector<T>& values, VkDeviceSize offset = 0) {
    upload(values.data(), values.size() * sizeof(T), offset);
  }
  // The whole buffer as an array of T (size() / sizeof(T) elements).
  template <class T>
  std::vector<T> download() const {
    std::vector<T> values(size_ / sizeof(T));
    download(values.data(), values.size() * sizeof(T));
    return values;
  }

 private:
  void release();
  void checkRange(VkDeviceSize bytes, VkDeviceSize offset) const;

  Context* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  BufferUsage usage_ = BufferUsage::Storage;
  void* mapped_ = nullptr;
};

}  // namespace firmament::gpu
