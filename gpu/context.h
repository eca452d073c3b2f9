#pragma once
// The Vulkan instance, the chosen physical device, one compute queue, and what every other gpu/ object
// needs from them (memory types, one-shot submissions, the pipeline cache, validation messages).
// Headless: no surface, no swapchain. Requires Vulkan 1.3 and VK_KHR_push_descriptor.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace firmament::gpu {

class PipelineCache;

enum class DeviceType { Discrete, Integrated, Virtual, Cpu, Other };
const char* deviceTypeName(DeviceType type);  // "discrete GPU", "integrated GPU", ..., "CPU"

struct DeviceInfo {
  uint32_t index = 0;  // position in vkEnumeratePhysicalDevices, what ContextOptions::device takes
  std::string name;    // "llvmpipe (LLVM 15.0.6, 256 bits)"
  DeviceType type = DeviceType::Other;
  std::string driver;  // driver name and version, "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"
  uint32_t apiVersion = 0;
};

// Every Vulkan device the loader reports (creates and destroys a short-lived instance).
std::vector<DeviceInfo> listDevices();

// True when FIRMAMENT_VALIDATION is set to anything but "0" or "".
bool validationRequestedByEnvironment();

// Optional device features, enabled when the device has them (lavapipe and NVIDIA have all).
struct DeviceFeatures {
  bool scalarBlockLayout = false;  // GL_EXT_scalar_block_layout: C++ structs with vec3 as-is
  bool shaderInt64 = false;
  bool shaderFloat64 = false;
  bool storageImageWithoutFormat = false;  // read and write storage images with no format qualifier
};

struct ContextOptions {
  // "" picks the best device: a discrete GPU, else integrated, else any other GPU, else the CPU
  // (lavapipe). A number selects by index; anything else by case-insensitive substring of the name.
  // No match -> InputError listing the devices.
  std::string device;
  // VK_LAYER_KHRONOS_validation + a debug messenger that records every warning and error.
  bool validation = validationRequestedByEnvironment();
  // Where the pipeline cache lives; empty -> FIRMAMENT_CACHE_DIR, $XDG_CACHE_HOME/firmament or
  // ~/.cache/firmament. persistentPipelineCache = false keeps it in memory only.
  std::filesystem::path cacheDir;
  bool persistentPipelineCache = true;
};

// A host application's Vulkan objects, adopted by a Context instead of creating its own (embedded mode,
// include/firmament/embed.h). The host created the device with requiredDeviceExtensions() and the
// features enableSupportedFeatures() turns on; it keeps every object alive longer than the Context.
struct AdoptedDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;        // must have compute
  VkQueue queue = VK_NULL_HANDLE;  // of queueFamily: preparation work (tables, uploads) is submitted here
};

// The device extensions Firmament needs (VK_KHR_push_descriptor).
std::vector<const char*> requiredDeviceExtensions();
// Turns on, in the given structures, the features Firmament uses that `physicalDevice` supports (what
// the Context's own device enables); the host chains them into its VkDeviceCreateInfo.
void enableSupportedFeatures(VkPhysicalDevice physicalDevice, VkPhysicalDeviceFeatures2& features,
                             VkPhysicalDeviceVulkan12Features& features12,
                             VkPhysicalDeviceVulkan13Features& features13);
// Why `physicalDevice` cannot run Firmament ("needs Vulkan 1.3, has 1.2.0"), or "".
std::string deviceIncompatibility(VkPhysicalDevice physicalDevice);

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  // Adopts the host's objects: destroys none of them, records no validation messages of its own (the
  // host's messenger sees them), and submits only to adopted.queue (preparation, never the frames).
  Context(const AdoptedDevice& adopted, const ContextOptions& options);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }

  const DeviceInfo& deviceInfo() const { return info_; }
  const DeviceFeatures& features() const { return features_; }
  const std::string& deviceName() const { return info_.name; }
  DeviceType deviceType() const { return info_.type; }
  bool isCpu() const { return info_.type == DeviceType::Cpu; }
  // "llvmpipe (LLVM 15.0.6, 256 bits), CPU, llvmpipe Mesa 22.3.6 (LLVM 15.0.6)": what outputs record.
  std::string description() const;

  // Timestamp queries on the compute queue; when false, CommandList falls back to wall clock.
  bool timestampsSupported() const { return timestampValidBits_ > 0; }
  uint32_t timestampValidBits() const { return timestampValidBits_; }
  double timestampPeriodNs() const { return properties_.limits.timestampPeriod; }

  // Validation messages (warnings and errors) recorded since creation or the last clear.
  bool validationEnabled() const { return validationEnabled_; }
  std::vector<std::string> validationMessages() const;
  void clearValidationMessages();

  // A memory type index with all `required` flags, preferring one that also has `preferred`.
  uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred = 0) const;
  VkMemoryPropertyFlags memoryTypeFlags(uint32_t typeIndex) const;

  // Records `record` into a fresh command buffer, submits it and waits (uploads, layout changes).
  void submitOneShot(const std::function<void(VkCommandBuffer)>& record);
  // Submits already-recorded command buffers and signals `fence`; serialised on the queue.
  void submit(const VkSubmitInfo& info, VkFence fence);
  // Submissions so far (one-shot and CommandList ones): an embedded frame reports whether it submitted.
  uint64_t submissionCount() const { return submissions_; }
  // The device and instance belong to a host (the adopting constructor).
  bool adopted() const { return adopted_; }

  PipelineCache& pipelineCache() { return *pipelineCache_; }
  // The folder for files cached across runs (pipelines, precomputed tables); empty = keep nothing.
  const std::filesystem::path& cacheDir() const { return cacheDir_; }

  // Labels a Vulkan object in validation messages and debuggers (no-op without debug utils).
  void setObjectName(VkObjectType type, uint64_t handle, const std::string& name) const;

  // VK_KHR_push_descriptor entry point, loaded at device creation.
  PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                       VkDebugUtilsMessageTypeFlagsEXT types,
                                                       const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  void release();
  void createInstance(bool validation);
  void pickPhysicalDevice(const std::string& selector);
  void createDevice();
  void readDevice();  // queue family properties, features, the push-descriptor entry point, the one-shot pool

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkCommandPool oneShotPool_ = VK_NULL_HANDLE;
  VkFence oneShotFence_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memoryProperties_{};
  DeviceInfo info_;
  DeviceFeatures features_;
  uint32_t timestampValidBits_ = 0;
  bool validationEnabled_ = false;
  bool adopted_ = false;
  uint64_t submissions_ = 0;
  PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
  std::unique_ptr<PipelineCache> pipelineCache_;
  std::filesystem::path cacheDir_;

  mutable std::mutex messagesMutex_;
  std::vector<std::string> messages_;
  std::mutex queueMutex_;    // vkQueueSubmit needs external synchronisation
  std::mutex oneShotMutex_;  // the one-shot pool and fence serve one submission at a time
};

}  // namespace firmament::gpu
