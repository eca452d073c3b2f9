#include "gpu/check.h"

#include <filesystem>

namespace firmament::gpu {

std::string resultName(VkResult result) {
  switch (result) {
#define FIRMAMENT_RESULT(name) \
  case name:                   \
    return #name;
    FIRMAMENT_RESULT(VK_SUCCESS)
    FIRMAMENT_RESULT(VK_NOT_READY)
    FIRMAMENT_RESULT(VK_TIMEOUT)
    FIRMAMENT_RESULT(VK_INCOMPLETE)
    FIRMAMENT_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    FIRMAMENT_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    FIRMAMENT_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    FIRMAMENT_RESULT(VK_ERROR_DEVICE_LOST)
    FIRMAMENT_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    FIRMAMENT_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    FIRMAMENT_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    FIRMAMENT_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    FIRMAMENT_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    FIRMAMENT_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
    FIRMAMENT_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    FIRMAMENT_RESULT(VK_ERROR_FRAGMENTED_POOL)
    FIRMAMENT_RESULT(VK_ERROR_UNKNOWN)
    FIRMAMENT_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef FIRMAMENT_RESULT
    default:
      return "VkResult " + std::to_string(int(result));
  }
}

void throwVulkanError(VkResult result, const char* call, const char* file, int line) {
  throw RuntimeError("Vulkan call failed with " + resultName(result) + ": " + call + " (" +
                     std::filesystem::path(file).filename().string() + ":" + std::to_string(line) + ")");
}

}  // namespace firmament::gpu
