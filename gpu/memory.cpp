#include "gpu/memory.h"

#include "gpu/check.h"
#include "gpu/context.h"

namespace firmament::gpu {

VkDeviceMemory allocateMemory(const Context& context, const VkMemoryRequirements& requirements,
                              VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred,
                              VkMemoryPropertyFlags& flags) {
  uint32_t type = context.findMemoryType(requirements.memoryTypeBits, required, preferred);
  flags = context.memoryTypeFlags(type);
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  FIRMAMENT_VK(vkAllocateMemory(context.device(), &info, nullptr, &memory));
  return memory;
}

void fullMemoryBarrier(VkCommandBuffer commands) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT | VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0,
                       nullptr);
}

}  // namespace firmament::gpu
