#include "gpu/context.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <thread>

#include "core/error.h"
#include "core/log.h"
#include "gpu/check.h"
#include "gpu/pipeline_cache.h"

namespace firmament::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

DeviceType toDeviceType(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return DeviceType::Discrete;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return DeviceType::Integrated;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return DeviceType::Virtual;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return DeviceType::Cpu;
    default:
      return DeviceType::Other;
  }
}

// Lower is better: a discrete GPU, then integrated, then any other GPU, then the CPU (lavapipe).
int preferenceRank(DeviceType type) {
  switch (type) {
    case DeviceType::Discrete:
      return 0;
    case DeviceType::Integrated:
      return 1;
    case DeviceType::Virtual:
      return 2;
    case DeviceType::Other:
      return 3;
    case DeviceType::Cpu:
      return 4;
  }
  return 5;
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

std::string versionString(uint32_t version) {
  char text[32];
  std::snprintf(text, sizeof text, "%u.%u.%u", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                VK_API_VERSION_PATCH(version));
  return text;
}

DeviceInfo describe(VkPhysicalDevice device, uint32_t index) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
  vkGetPhysicalDeviceProperties2(device, &properties);
  DeviceInfo info;
  info.index = index;
  info.name = properties.properties.deviceName;
  info.type = toDeviceType(properties.properties.deviceType);
  info.apiVersion = properties.properties.apiVersion;
  // driverInfo carries the version in the vendor's own words ("Mesa 22.3.6", "535.104.05"); the
  // packed driverVersion field is encoded differently by every vendor.
  info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  return info;
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// Why a device cannot run Firmament, or nothing.
std::optional<std::string> incompatibility(VkPhysicalDevice device, const DeviceInfo& info) {
  if (info.apiVersion < VK_API_VERSION_1_3) return "needs Vulkan 1.3, has " + versionString(info.apiVersion);
  if (!hasDeviceExtension(device, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
    return std::string("lacks ") + VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
  return std::nullopt;
}

std::string deviceList(const std::vector<DeviceInfo>& devices) {
  std::string text;
  for (const auto& d : devices)
    text += "\n  " + std::to_string(d.index) + ": " + d.name + " (" + deviceTypeName(d.type) + ", " + d.driver + ")";
  return devices.empty() ? "\n  (none: is a Vulkan driver such as mesa-vulkan-drivers installed?)" : text;
}

VkInstance createBareInstance() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "firmament";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  FIRMAMENT_VK(vkCreateInstance(&info, nullptr, &instance));
  return instance;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t count = 0;
  FIRMAMENT_VK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  FIRMAMENT_VK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  devices.resize(count);
  return devices;
}

}  // namespace

const char* deviceTypeName(DeviceType type) {
  switch (type) {
    case DeviceType::Discrete:
      return "discrete GPU";
    case DeviceType::Integrated:
      return "integrated GPU";
    case DeviceType::Virtual:
      return "virtual GPU";
    case DeviceType::Cpu:
      return "CPU";
    case DeviceType::Other:
      return "other";
  }
  return "other";
}

std::vector<DeviceInfo> listDevices() {
  VkInstance instance = createBareInstance();
  std::vector<DeviceInfo> out;
  auto devices = physicalDevices(instance);
  for (uint32_t i = 0; i < devices.size(); ++i) out.push_back(describe(devices[i], i));
  vkDestroyInstance(instance, nullptr);
  return out;
}

bool validationRequestedByEnvironment() {
  const char* value = std::getenv("FIRMAMENT_VALIDATION");
  return value && *value && std::strcmp(value, "0") != 0;
}

Context::Context(const ContextOptions& options) {
  try {
    createInstance(options.validation);
    pickPhysicalDevice(options.device);
    createDevice();
    if (options.persistentPipelineCache) cacheDir_ = options.cacheDir.empty() ? defaultCacheDir() : options.cacheDir;
    pipelineCache_ = std::make_unique<PipelineCache>(device_, properties_, cacheDir_);
  } catch (...) {
    release();  // the destructor does not run for a half-built object
    throw;
  }
  logVerbose("gpu: " + description());
}

Context::Context(const AdoptedDevice& adopted, const ContextOptions& options) : adopted_(true) {
  if (!adopted.instance || !adopted.physicalDevice || !adopted.device || !adopted.queue)
    throw InputError("embedded mode: the host's VkInstance, VkPhysicalDevice, VkDevice and VkQueue must all be given");
  if (std::string why = deviceIncompatibility(adopted.physicalDevice); !why.empty())
    throw InputError("embedded mode: the host's Vulkan device cannot run Firmament: " + why);
  instance_ = adopted.instance;
  physicalDevice_ = adopted.physicalDevice;
  device_ = adopted.device;
  queue_ = adopted.queue;
  queueFamily_ = adopted.queueFamily;
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
  if (queueFamily_ >= familyCount || !(families[queueFamily_].queueFlags & VK_QUEUE_COMPUTE_BIT))
    throw InputError("embedded mode: queue family " + std::to_string(queueFamily_) + " has no compute queue");
  info_ = describe(physicalDevice_, 0);
  vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
  try {
    readDevice();
    if (options.persistentPipelineCache) cacheDir_ = options.cacheDir.empty() ? defaultCacheDir() : options.cacheDir;
    pipelineCache_ = std::make_unique<PipelineCache>(device_, properties_, cacheDir_);
  } catch (...) {
    release();
    throw;
  }
  logVerbose("gpu (the host's device): " + description());
}

Context::~Context() { release(); }

void Context::release() {
  pipelineCache_.reset();
  if (device_) {
    // An adopted device's other work is the host's: only this context's objects go, and the host has
    // waited for the frames that used them (docs/api.md, "Synchronisation").
    if (!adopted_) vkDeviceWaitIdle(device_);
    if (oneShotFence_) vkDestroyFence(device_, oneShotFence_, nullptr);
    if (oneShotPool_) vkDestroyCommandPool(device_, oneShotPool_, nullptr);
    if (!adopted_) vkDestroyDevice(device_, nullptr);
  }
  if (adopted_) {
    oneShotFence_ = VK_NULL_HANDLE;
    oneShotPool_ = VK_NULL_HANDLE;
    device_ = VK_NULL_HANDLE;
    instance_ = VK_NULL_HANDLE;
    return;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  oneShotFence_ = VK_NULL_HANDLE;
  oneShotPool_ = VK_NULL_HANDLE;
  device_ = VK_NULL_HANDLE;
  messenger_ = VK_NULL_HANDLE;
  instance_ = VK_NULL_HANDLE;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                       VkDebugUtilsMessageTypeFlagsEXT types,
                                                       const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* self = static_cast<Context*>(user);
  std::string text = data && data->pMessage ? data->pMessage : "(no message)";
  // The loader reports its own housekeeping (drivers it skipped) through the same messenger; those
  // are not faults of this program.
  bool fromLoader = data && data->pMessageIdName && std::strcmp(data->pMessageIdName, "Loader Message") == 0;
  bool serious = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
  if (serious && !fromLoader) {
    const char* kind = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    const char* area = (types & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT)    ? "validation"
                       : (types & VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT) ? "performance"
                                                                                   : "general";
    std::string message = std::string("vulkan ") + area + " " + kind + ": " + text;
    logWarning(message);
    std::lock_guard lock(self->messagesMutex_);
    self->messages_.push_back(std::move(message));
  } else {
    logVerbose("vulkan: " + text);
  }
  return VK_FALSE;
}

namespace {
// lavapipe runs a dispatch on LP_NUM_THREADS threads (default: one per core), each taking one
// contiguous block of workgroups. Twice as many threads as cores measured 1.5x faster on a 2-core
// machine whose cores were contended, and the same when they were not (docs/gpu.md), so that is the
// default unless the user set the variable. It must be set before the driver loads; GPUs ignore it.
void preferMoreLavapipeThreads() {
  if (std::getenv("LP_NUM_THREADS") != nullptr) return;
  unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  setenv("LP_NUM_THREADS", std::to_string(std::min(2u * cores, 32u)).c_str(), 0);
}
}  // namespace

void Context::createInstance(bool validation) {
  preferMoreLavapipeThreads();
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  if (validation) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> available(count);
    vkEnumerateInstanceLayerProperties(&count, available.data());
    bool found = std::any_of(available.begin(), available.end(), [](const VkLayerProperties& l) {
      return std::strcmp(l.layerName, kValidationLayer) == 0;
    });
    if (!found)
      throw RuntimeError(std::string("Vulkan validation was requested (FIRMAMENT_VALIDATION=1 or the "
                                     "validation option) but the layer ") +
                         kValidationLayer +
                         " is not installed; install the Debian package vulkan-validationlayers "
                         "(sudo apt-get install vulkan-validationlayers) or turn validation off");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }

  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messengerInfo.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_VERBOSE_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT |
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messengerInfo.pfnUserCallback = &Context::onDebugMessage;
  messengerInfo.pUserData = this;

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "firmament";
  app.pEngineName = "firmament";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  // Chained messenger: also catches messages from vkCreateInstance / vkDestroyInstance themselves.
  if (validation) info.pNext = &messengerInfo;
  FIRMAMENT_VK(vkCreateInstance(&info, nullptr, &instance_));

  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (!create) throw RuntimeError("VK_EXT_debug_utils is missing although the validation layer is present");
    FIRMAMENT_VK(create(instance_, &messengerInfo, nullptr, &messenger_));
    setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
    validationEnabled_ = true;
  }
}

void Context::pickPhysicalDevice(const std::string& selector) {
  auto devices = physicalDevices(instance_);
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));

  std::optional<uint32_t> chosen;
  if (!selector.empty()) {
    bool numeric = std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); });
    if (numeric) {
      unsigned long index = selector.size() < 10 ? std::stoul(selector) : devices.size();
      if (index < devices.size()) chosen = uint32_t(index);
    } else {
      std::string needle = lowercase(selector);
      // Among several matches, the one auto-selection would prefer.
      for (const auto& d : infos)
        if (lowercase(d.name).find(needle) != std::string::npos &&
            (!chosen || preferenceRank(d.type) < preferenceRank(infos[*chosen].type)))
          chosen = d.index;
    }
    if (!chosen)
      throw InputError("no Vulkan device matches \"" + selector +
                       "\" (give an index or part of a name); available devices:" + deviceList(infos));
    if (auto why = incompatibility(devices[*chosen], infos[*chosen]))
      throw InputError("Vulkan device " + std::to_string(*chosen) + " (" + infos[*chosen].name +
                       ") cannot run Firmament: " + *why + "; available devices:" + deviceList(infos));
  } else {
    std::string rejected;
    for (const auto& d : infos) {
      if (auto why = incompatibility(devices[d.index], d)) {
        rejected += "\n  " + d.name + ": " + *why;
        continue;
      }
      if (!chosen || preferenceRank(d.type) < preferenceRank(infos[*chosen].type)) chosen = d.index;
    }
    if (!chosen)
      throw RuntimeError(
          "no Vulkan device can run Firmament (Vulkan 1.3 compute with push descriptors); "
          "install mesa-vulkan-drivers for lavapipe, the CPU fallback. Devices:" +
          deviceList(infos) + rejected);
  }
  physicalDevice_ = devices[*chosen];
  info_ = infos[*chosen];
  vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
}

void enableSupportedFeatures(VkPhysicalDevice physicalDevice, VkPhysicalDeviceFeatures2& enable,
                             VkPhysicalDeviceVulkan12Features& enable12, VkPhysicalDeviceVulkan13Features& enable13) {
  VkPhysicalDeviceVulkan13Features supported13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &supported13};
  VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &supported12};
  vkGetPhysicalDeviceFeatures2(physicalDevice, &supported);
  // Nothing here costs speed (robustBufferAccess does, so it stays off). maintenance4 is mandatory in
  // Vulkan 1.3 and needed: glslang's vulkan1.3 target emits LocalSizeId.
  enable13.maintenance4 = VK_TRUE;
  enable13.synchronization2 |= supported13.synchronization2;
  enable12.scalarBlockLayout |= supported12.scalarBlockLayout;
  enable12.hostQueryReset |= supported12.hostQueryReset;
  enable.features.shaderInt64 |= supported.features.shaderInt64;
  enable.features.shaderFloat64 |= supported.features.shaderFloat64;
  const bool withoutFormat =
      supported.features.shaderStorageImageReadWithoutFormat && supported.features.shaderStorageImageWriteWithoutFormat;
  enable.features.shaderStorageImageReadWithoutFormat |= withoutFormat;
  enable.features.shaderStorageImageWriteWithoutFormat |= withoutFormat;
}

std::vector<const char*> requiredDeviceExtensions() { return {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME}; }

std::string deviceIncompatibility(VkPhysicalDevice physicalDevice) {
  return incompatibility(physicalDevice, describe(physicalDevice, 0)).value_or("");
}

void Context::createDevice() {
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
  std::optional<uint32_t> family;
  for (uint32_t i = 0; i < familyCount; ++i) {
    if (!(families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
    // Prefer a family that can time its work.
    if (!family || (families[i].timestampValidBits > 0 && families[*family].timestampValidBits == 0)) family = i;
  }
  if (!family) throw RuntimeError("Vulkan device " + info_.name + " has no compute queue");
  queueFamily_ = *family;

  VkPhysicalDeviceVulkan13Features enable13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features enable12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &enable13};
  VkPhysicalDeviceFeatures2 enable{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &enable12};
  enableSupportedFeatures(physicalDevice_, enable, enable12, enable13);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  const std::vector<const char*> extensions = requiredDeviceExtensions();
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &enable};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queueInfo;
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  FIRMAMENT_VK(vkCreateDevice(physicalDevice_, &info, nullptr, &device_));
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  readDevice();
}

// What the rest of gpu/ needs from a device, created here or adopted: the queue family's timestamps,
// the features in use (those enableSupportedFeatures() turns on), the push-descriptor entry point and
// the one-shot pool and fence.
void Context::readDevice() {
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
  timestampValidBits_ = families.at(queueFamily_).timestampValidBits;
  VkPhysicalDeviceVulkan13Features enable13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features enable12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &enable13};
  VkPhysicalDeviceFeatures2 enable{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &enable12};
  enableSupportedFeatures(physicalDevice_, enable, enable12, enable13);
  features_.scalarBlockLayout = enable12.scalarBlockLayout;
  features_.shaderInt64 = enable.features.shaderInt64;
  features_.shaderFloat64 = enable.features.shaderFloat64;
  features_.storageImageWithoutFormat = enable.features.shaderStorageImageReadWithoutFormat;

  cmdPushDescriptorSet =
      reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
  if (!cmdPushDescriptorSet)
    throw RuntimeError("vkCmdPushDescriptorSetKHR is missing on " + info_.name +
                       (adopted_ ? " (enable VK_KHR_push_descriptor on the host's device)" : ""));

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  FIRMAMENT_VK(vkCreateCommandPool(device_, &poolInfo, nullptr, &oneShotPool_));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  FIRMAMENT_VK(vkCreateFence(device_, &fenceInfo, nullptr, &oneShotFence_));
}

std::string Context::description() const {
  return info_.name + ", " + deviceTypeName(info_.type) + ", " + info_.driver;
}

std::vector<std::string> Context::validationMessages() const {
  std::lock_guard lock(messagesMutex_);
  return messages_;
}

void Context::clearValidationMessages() {
  std::lock_guard lock(messagesMutex_);
  messages_.clear();
}

uint32_t Context::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                 VkMemoryPropertyFlags preferred) const {
  std::optional<uint32_t> fallback;
  for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
    if (!(typeBits & (1u << i))) continue;
    VkMemoryPropertyFlags flags = memoryProperties_.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (!fallback) fallback = i;
  }
  if (!fallback) throw RuntimeError("no Vulkan memory type fits (required flags " + std::to_string(required) + ")");
  return *fallback;
}

VkMemoryPropertyFlags Context::memoryTypeFlags(uint32_t typeIndex) const {
  return memoryProperties_.memoryTypes[typeIndex].propertyFlags;
}

void Context::submit(const VkSubmitInfo& info, VkFence fence) {
  std::lock_guard lock(queueMutex_);
  FIRMAMENT_VK(vkQueueSubmit(queue_, 1, &info, fence));
  ++submissions_;
}

void Context::submitOneShot(const std::function<void(VkCommandBuffer)>& record) {
  std::lock_guard lock(oneShotMutex_);
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = oneShotPool_;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  FIRMAMENT_VK(vkAllocateCommandBuffers(device_, &allocInfo, &commands));
  struct Free {  // returns the buffer to the pool even when recording throws
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer commands;
    ~Free() { vkFreeCommandBuffers(device, pool, 1, &commands); }
  } release{device_, oneShotPool_, commands};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  FIRMAMENT_VK(vkBeginCommandBuffer(commands, &begin));
  record(commands);
  FIRMAMENT_VK(vkEndCommandBuffer(commands));

  VkSubmitInfo submitInfo{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submitInfo.commandBufferCount = 1;
  submitInfo.pCommandBuffers = &commands;
  FIRMAMENT_VK(vkResetFences(device_, 1, &oneShotFence_));
  submit(submitInfo, oneShotFence_);
  FIRMAMENT_VK(vkWaitForFences(device_, 1, &oneShotFence_, VK_TRUE, UINT64_MAX));
}

void Context::setObjectName(VkObjectType type, uint64_t handle, const std::string& name) const {
  if (!setObjectName_ || name.empty()) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  setObjectName_(device_, &info);
}

}  // namespace firmament::gpu
