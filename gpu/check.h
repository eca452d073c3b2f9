#pragma once
// Turns a failed Vulkan call into a RuntimeError that names the call and the result code.
#include <vulkan/vulkan.h>

#include <string>

#include "core/error.h"

namespace firmament::gpu {

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" for a result code; the number for codes it does not know.
std::string resultName(VkResult result);

[[noreturn]] void throwVulkanError(VkResult result, const char* call, const char* file, int line);

}  // namespace firmament::gpu

// FIRMAMENT_VK(vkCreateBuffer(...)): throws firmament::RuntimeError unless the call returned VK_SUCCESS.
#define FIRMAMENT_VK(call)                                                                 \
  do {                                                                                     \
    VkResult firmament_vk_result_ = (call);                                                \
    if (firmament_vk_result_ != VK_SUCCESS)                                                \
      ::firmament::gpu::throwVulkanError(firmament_vk_result_, #call, __FILE__, __LINE__); \
  } while (0)
