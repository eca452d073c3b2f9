#pragma once
// Device memory for one resource (a plain allocation per buffer or image: simple, and the resource
// counts here are small) and the barrier that orders transfers against compute work.
#include <vulkan/vulkan.h>

namespace firmament::gpu {

class Context;

// Allocates memory for `requirements`, with all `required` property flags, preferably `preferred`
// too; returns the chosen type's flags through `flags`.
VkDeviceMemory allocateMemory(const Context& context, const VkMemoryRequirements& requirements,
                              VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred,
                              VkMemoryPropertyFlags& flags);

// Every earlier write (any stage) is visible to every later read or write, the host's included.
// Heavy-handed on purpose: the passes are few and large, so correctness wins over overlap.
void fullMemoryBarrier(VkCommandBuffer commands);

}  // namespace firmament::gpu
