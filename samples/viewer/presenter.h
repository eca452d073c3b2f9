#pragma once
// The viewer's window output: a Vulkan instance and device of its own on the window's surface (GLFW),
// a swapchain, and per frame the sky image (8-bit sRGB, already tone-mapped) uploaded, scaled to the
// window with a blit, Dear ImGui drawn over it in a render pass, then presented. One frame in flight.
// The renderer keeps its own headless context (include/firmament/sky.h); sharing one device is the
// embedding phase's work (docs/api.md).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

struct GLFWwindow;
struct ImDrawData;

namespace firmament::viewer {

class Presenter {
 public:
  // validation: VK_LAYER_KHRONOS_validation with a messenger that records warnings and errors.
  Presenter(GLFWwindow* window, bool validation);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // Initialises Dear ImGui's Vulkan backend on this device (after ImGui::CreateContext) and uploads its fonts.
  void initImGui();
  void shutdownImGui();

  // Draws `rgba8` (width x height, 4 bytes a pixel, sRGB-encoded) over the whole window, then `ui`, and
  // presents. Recreates the swapchain when the window changed size.
  void present(const uint8_t* rgba8, int width, int height, ImDrawData* ui);

  std::string deviceName() const;
  std::vector<std::string> validationMessages() const;

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT types,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  void createSwapchain();
  void destroySwapchain();
  void ensureUpload(int width, int height);
  void destroyUpload();
  uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const;

  GLFWwindow* window_ = nullptr;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkDevice device_ = VK_NULL_HANDLE;
  uint32_t family_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  VkDescriptorPool imguiPool_ = VK_NULL_HANDLE;
  bool imgui_ = false;

  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  std::vector<VkSemaphore> rendered_;  // one per swapchain image

  // The sky's pixels: a host-visible staging buffer and an image the blit reads.
  int uploadWidth_ = 0, uploadHeight_ = 0;
  VkBuffer staging_ = VK_NULL_HANDLE;
  VkDeviceMemory stagingMemory_ = VK_NULL_HANDLE;
  void* stagingMapped_ = nullptr;
  VkImage upload_ = VK_NULL_HANDLE;
  VkDeviceMemory uploadMemory_ = VK_NULL_HANDLE;

  mutable std::mutex messagesMutex_;
  std::vector<std::string> messages_;
};

}  // namespace firmament::viewer
