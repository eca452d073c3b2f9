// An application embedding Firmament (docs/api.md, "Example host"). It owns its Vulkan instance and
// device, an RGBA16F colour image and a D32 depth image; it draws triangles in front of the sky with
// a tiny graphics pipeline, then calls firmament::Sky::record() to put the sky and the aerial
// perspective into its own command buffer, submits, reads the colour back and writes an EXR.
//
//   host_example [--out FILE.exr] [--width W] [--height H] [--scene FILE] [--frames N]
//                [--colour rgba16f|rgba32f] [--reversed-depth] [--check] [--frames-in-flight N]
//
// --scene: a scene file instead of the built-in clear view (the camera's orientation is the scene's);
// --frames N: N frames more after the first, timed (the host's submit to fence, median) beside N
// offline renders of the same view (Sky::render's GPU time and wall time, medians).
// --frames-in-flight N (2 to 4): then 3N frames with N in flight (Sky::Builder::framesInFlight), the camera
// turned 20 degrees each frame, each frame checked against the offline render of its view.
//
// The triangles: two at 1 km and two at 8 km, each pair side by side. --check (the CTest entry
// host_example) renders the frame three times: the triangles bright and black before record()
// (Firmament composites them), then bright after record(), shaded by the host's own shader (lit.frag)
// with Firmament's exported lookups (firmament/atmosphere_lookup.glsl), and checks:
//  - where no triangle is, the pixels equal Firmament's offline render of the same view (Sky::render)
//    within 0.2 % (the RGBA16F image: a conversion may truncate, 2^-10 relative);
//  - on the triangles, the black frame gives the in-scattered light L and the difference of the two the
//    air's transmittance T (bright = C T + L): T matches the Beer-Lambert law along each pixel's ray
//    through Bruneton 2017's Earth (Rayleigh and aerosol extinction with their scale heights) within
//    1 %, and the far pair has the lower T and the higher L (more haze);
//  - the host's own shading equals Firmament's composite on the triangles within 0.2 % (RGBA16F);
//  - the second frame submits no preparation work;
//  - the validation layer (FIRMAMENT_VALIDATION=1) reports no message on the host's instance.
// With --scene the checks are the sky's, the triangles' presence, the repeated frame's and the
// validation's (the scene's clouds may cover the triangles, and its air is not Bruneton's Earth's).
// Exit code 0 when every check passes, 1 when one fails, 2 for bad arguments.
#include <vulkan/vulkan.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "firmament/embed.h"
#include "firmament/sky.h"
#include "lit_frag.h"
#include "lit_vert.h"
#include "triangle_frag.h"
#include "triangle_vert.h"

namespace {

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed: VkResult " + std::to_string(result));
}

std::vector<std::string> validationMessages;
bool reversedDepth = false;  // --reversed-depth: the host's depth is 1 at the near plane, 0 at the far one

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                         VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  const bool loader = data->pMessageIdName && std::strcmp(data->pMessageIdName, "Loader Message") == 0;
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT && !loader) {
    validationMessages.push_back(data->pMessage ? data->pMessage : "");
    std::fprintf(stderr, "validation: %s\n", data->pMessage ? data->pMessage : "");
  }
  return VK_FALSE;
}

// The view: a clear sky, the sun high in the south-east, the camera 300 m above the ground looking east.
const char* kScene = R"({
  "location": {"latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 500},
  "time": {"utc": "2026-06-21T09:00:00Z"},
  "camera": {"height_above_ground_m": 300, "yaw_deg": 90, "pitch_deg": 2, "fov_deg": 60},
  "atmosphere": {"preset": "earth"}
})";

struct Host {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory{};

  uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const {
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
      if ((bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw std::runtime_error("no memory type fits");
  }
};

Host createHost(bool validation) {
  Host h;
  std::vector<const char*> layers, extensions;
  if (validation) {
    layers.push_back("VK_LAYER_KHRONOS_validation");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "firmament host example";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  check(vkCreateInstance(&info, nullptr, &h.instance), "vkCreateInstance");
  if (validation) {
    VkDebugUtilsMessengerCreateInfoEXT m{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    m.pfnUserCallback = onMessage;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(h.instance, "vkCreateDebugUtilsMessengerEXT"));
    check(create(h.instance, &m, nullptr, &h.messenger), "vkCreateDebugUtilsMessengerEXT");
  }
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(h.instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(h.instance, &count, devices.data());
  if (devices.empty()) throw std::runtime_error("no Vulkan device");
  h.physical = devices[0];
  vkGetPhysicalDeviceMemoryProperties(h.physical, &h.memory);
  vkGetPhysicalDeviceQueueFamilyProperties(h.physical, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(h.physical, &count, families.data());
  const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  while (h.family < count && (families[h.family].queueFlags & wanted) != wanted) ++h.family;
  if (h.family == count) throw std::runtime_error("no graphics + compute queue family");

  // The host's own needs (dynamic rendering) plus what Firmament asks for.
  VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  features13.dynamicRendering = VK_TRUE;
  VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &features13};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features12};
  firmament::enableEmbeddedDeviceFeatures(h.physical, features, features12, features13);
  std::vector<const char*> deviceExtensions = firmament::embeddedDeviceExtensions();
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = h.family;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = uint32_t(deviceExtensions.size());
  deviceInfo.ppEnabledExtensionNames = deviceExtensions.data();
  check(vkCreateDevice(h.physical, &deviceInfo, nullptr, &h.device), "vkCreateDevice");
  vkGetDeviceQueue(h.device, h.family, 0, &h.queue);
  return h;
}

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

Image createImage(const Host& h, int width, int height, VkFormat format, VkImageUsageFlags usage,
                  VkImageAspectFlags aspect) {
  Image im;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {uint32_t(width), uint32_t(height), 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  check(vkCreateImage(h.device, &info, nullptr, &im.image), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(h.device, im.image, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = h.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  check(vkAllocateMemory(h.device, &alloc, nullptr, &im.memory), "vkAllocateMemory");
  check(vkBindImageMemory(h.device, im.image, im.memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = im.image;
  view.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {aspect, 0, 1, 0, 1};
  check(vkCreateImageView(h.device, &view, nullptr, &im.view), "vkCreateImageView");
  return im;
}

void destroyImage(const Host& h, Image& im) {
  vkDestroyImageView(h.device, im.view, nullptr);
  vkDestroyImage(h.device, im.image, nullptr);
  vkFreeMemory(h.device, im.memory, nullptr);
}

VkShaderModule shaderModule(const Host& h, const uint32_t* words, size_t bytes) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = bytes;
  info.pCode = words;
  VkShaderModule module = VK_NULL_HANDLE;
  check(vkCreateShaderModule(h.device, &info, nullptr, &module), "vkCreateShaderModule");
  return module;
}

struct TrianglePush {
  float corners[3][4];  // clip space
  float colour[4];
};

struct Pipeline {
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
};

// A graphics pipeline with dynamic rendering: no vertex input, one colour, and with a depth format a
// depth test and write (less). set: the descriptor set layout of lit.vert and lit.frag, or none.
template <size_t V, size_t F>
Pipeline createPipeline(const Host& h, const uint32_t (&vertWords)[V], const uint32_t (&fragWords)[F],
                        VkFormat colourFormat, VkFormat depthFormat, VkDescriptorSetLayout set) {
  Pipeline p;
  VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(TrianglePush)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = set ? 1 : 0;
  layoutInfo.pSetLayouts = &set;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &range;
  check(vkCreatePipelineLayout(h.device, &layoutInfo, nullptr, &p.layout), "vkCreatePipelineLayout");
  VkShaderModule vert = shaderModule(h, vertWords, sizeof(vertWords));
  VkShaderModule frag = shaderModule(h, fragWords, sizeof(fragWords));
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vert;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = frag;
  stages[1].pName = "main";
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = depthFormat != VK_FORMAT_UNDEFINED;
  depth.depthWriteEnable = depthFormat != VK_FORMAT_UNDEFINED;
  depth.depthCompareOp = reversedDepth ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState attachment{};
  attachment.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = 1;
  blend.pAttachments = &attachment;
  VkDynamicState dynamics[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamics;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachmentFormats = &colourFormat;
  rendering.depthAttachmentFormat = depthFormat;
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = p.layout;
  check(vkCreateGraphicsPipelines(h.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline),
        "vkCreateGraphicsPipelines");
  vkDestroyShaderModule(h.device, vert, nullptr);
  vkDestroyShaderModule(h.device, frag, nullptr);
  return p;
}

void imageBarrier(VkCommandBuffer cb, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cb, &dependency);
}

// A triangle facing the camera at view-space depth z (m), centred on the ray through image point
// (u, v) (fractions of the width and height), `size` m across, in clip space of Firmament's projection
// (firmament::CameraFrame) with a standard depth range [near, far].
TrianglePush triangleAt(double u, double v, double z, double size, const firmament::CameraFrame& camera, int width,
                        int height, double near, double far, const float colour[4]) {
  TrianglePush t{};
  const double t2 = camera.tanHalfFovX;
  // The centre's view-space x, y from its image point (the inverse of CameraFrame's mapping).
  const double cx = (2.0 * u - 1.0) * z * t2;
  const double cy = (1.0 - 2.0 * v) * z * t2 * double(height) / double(width);
  const double corners[3][2] = {{cx - size, cy - size}, {cx + size, cy - size}, {cx, cy + size}};
  for (int i = 0; i < 3; ++i) {
    const double x = corners[i][0], y = corners[i][1];
    t.corners[i][0] = float(x / t2);
    t.corners[i][1] = float(-y * double(width) / double(height) / t2);
    // Vulkan's depth z_clip / w: 0 at the near plane and 1 at the far one, or the reverse.
    t.corners[i][2] = float(reversedDepth ? near * (far - z) / (far - near) : far * (z - near) / (far - near));
    t.corners[i][3] = float(z);
  }
  std::memcpy(t.colour, colour, sizeof(t.colour));
  return t;
}

struct Options {
  std::string out = "host_example.exr";
  std::string scene;  // empty: kScene
  int width = 64, height = 36;
  int frames = 0;
  int inFlight = 0;  // --frames-in-flight N (2 to 4): the check of N frames in flight, after the first frame
  bool check = false;
  bool full = false;  // an RGBA32F colour image (else RGBA16F)
};

struct Frame {
  std::vector<float> rgba;  // read back from the host's colour image
  firmament::EmbeddedFrame info;
  double submitMilliseconds = 0.0;  // the host's submit to its fence: the triangles, the sky, the copy
  double skyMilliseconds = 0.0;     // GPU time between the host's timestamps around record()'s commands
};

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

struct Triangle {
  double u, v, z;  // image point of its centre and its view-space depth
};
// What the host's own shading with Firmament's air needs (lit.vert, lit.frag): a uniform buffer with the
// lookups' parameters and the camera's axes, a sampler, a descriptor set, the pipeline.
struct LitBlock {
  firmament::AtmosphereLookupParameters atmosphere;
  float forward[4], right[4], up[4];
};

struct Lit {
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;
  VkBuffer block = VK_NULL_HANDLE;
  VkDeviceMemory blockMemory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  Pipeline pipeline;
};

Lit createLit(const Host& h, VkFormat colourFormat) {
  Lit l;
  VkDescriptorSetLayoutBinding bindings[3] = {
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = 3;
  setInfo.pBindings = bindings;
  check(vkCreateDescriptorSetLayout(h.device, &setInfo, nullptr, &l.setLayout), "vkCreateDescriptorSetLayout");
  VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                   {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 2;
  poolInfo.pPoolSizes = sizes;
  check(vkCreateDescriptorPool(h.device, &poolInfo, nullptr, &l.pool), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = l.pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &l.setLayout;
  check(vkAllocateDescriptorSets(h.device, &alloc, &l.set), "vkAllocateDescriptorSets");
  // Linear filtering, clamp to edge: what the lookups expect (docs/api.md, "Atmosphere lookups").
  VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  samplerInfo.magFilter = samplerInfo.minFilter = VK_FILTER_LINEAR;
  samplerInfo.addressModeU = samplerInfo.addressModeV = samplerInfo.addressModeW =
      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  check(vkCreateSampler(h.device, &samplerInfo, nullptr, &l.sampler), "vkCreateSampler");
  VkBufferCreateInfo bufferInfo{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bufferInfo.size = sizeof(LitBlock);
  bufferInfo.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  check(vkCreateBuffer(h.device, &bufferInfo, nullptr, &l.block), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(h.device, l.block, &req);
  VkMemoryAllocateInfo memoryInfo{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  memoryInfo.allocationSize = req.size;
  memoryInfo.memoryTypeIndex =
      h.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  check(vkAllocateMemory(h.device, &memoryInfo, nullptr, &l.blockMemory), "vkAllocateMemory");
  check(vkBindBufferMemory(h.device, l.block, l.blockMemory, 0), "vkBindBufferMemory");
  check(vkMapMemory(h.device, l.blockMemory, 0, sizeof(LitBlock), 0, &l.mapped), "vkMapMemory");
  l.pipeline = createPipeline(h, lit_vert, lit_frag, colourFormat, VK_FORMAT_UNDEFINED, l.setLayout);
  return l;
}

void destroyLit(const Host& h, Lit& l) {
  vkDestroyPipeline(h.device, l.pipeline.pipeline, nullptr);
  vkDestroyPipelineLayout(h.device, l.pipeline.layout, nullptr);
  vkDestroyBuffer(h.device, l.block, nullptr);
  vkFreeMemory(h.device, l.blockMemory, nullptr);
  vkDestroySampler(h.device, l.sampler, nullptr);
  vkDestroyDescriptorPool(h.device, l.pool, nullptr);
  vkDestroyDescriptorSetLayout(h.device, l.setLayout, nullptr);
}

// Two pairs: at 1 km (left), at 8 km (right); the second of each pair is lit the same (one colour).
const Triangle kTriangles[4] = {{0.2, 0.5, 1000.0}, {0.35, 0.5, 1000.0}, {0.65, 0.5, 8000.0}, {0.8, 0.5, 8000.0}};
constexpr double kNear = 1.0, kFar = 100000.0;
constexpr float kBright = 2000.0f;  // cd/m^2: a sunlit grey wall

// One frame: the triangles drawn before record() (Firmament composites them), or with `lit` after it,
// shaded by the host with Firmament's lookups (lit.frag).
// A frame recorded and submitted, not yet waited for (its command buffer, fence and read-back buffer).
struct PendingFrame {
  Frame frame;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cb = VK_NULL_HANDLE;
  VkBuffer readback = VK_NULL_HANDLE;
  VkDeviceMemory readbackMemory = VK_NULL_HANDLE;
  VkDeviceSize bytes = 0;
  VkQueryPool queries = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  bool full = false;
  int width = 0, height = 0;
  std::chrono::steady_clock::time_point submitted;
};

// Records the frame (geometry: the triangles, else only the cleared colour and depth) and submits it.
PendingFrame beginFrame(const Host& h, firmament::Sky& sky, const Pipeline& pipeline, Image& colour, Image& depth,
                        int width, int height, float brightness, VkFormat colourFormat, Lit* lit,
                        bool geometry = true) {
  const bool full = colourFormat == VK_FORMAT_R32G32B32A32_SFLOAT;
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.queueFamilyIndex = h.family;
  VkCommandPool pool = VK_NULL_HANDLE;
  check(vkCreateCommandPool(h.device, &poolInfo, nullptr, &pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cb = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(h.device, &alloc, &cb), "vkAllocateCommandBuffers");
  const VkDeviceSize bytes = VkDeviceSize(width) * VkDeviceSize(height) * (full ? 16 : 8);
  VkBufferCreateInfo bufferInfo{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bufferInfo.size = bytes;
  bufferInfo.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer readback = VK_NULL_HANDLE;
  check(vkCreateBuffer(h.device, &bufferInfo, nullptr, &readback), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(h.device, readback, &req);
  VkMemoryAllocateInfo memoryInfo{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  memoryInfo.allocationSize = req.size;
  memoryInfo.memoryTypeIndex =
      h.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory readbackMemory = VK_NULL_HANDLE;
  check(vkAllocateMemory(h.device, &memoryInfo, nullptr, &readbackMemory), "vkAllocateMemory");
  check(vkBindBufferMemory(h.device, readback, readbackMemory, 0), "vkBindBufferMemory");

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cb, &begin), "vkBeginCommandBuffer");
  // Two timestamps around Firmament's commands: its GPU time inside the host's frame.
  VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
  queryInfo.queryCount = 2;
  VkQueryPool queries = VK_NULL_HANDLE;
  check(vkCreateQueryPool(h.device, &queryInfo, nullptr, &queries), "vkCreateQueryPool");
  vkCmdResetQueryPool(cb, queries, 0, 2);
  // 1. The host's geometry: clear, draw the triangles.
  imageBarrier(cb, colour.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
               VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  imageBarrier(cb, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
               VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  VkRenderingAttachmentInfo colourAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  colourAttachment.imageView = colour.view;
  colourAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colourAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  colourAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colourAttachment.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};
  VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depthAttachment.imageView = depth.view;
  depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depthAttachment.clearValue.depthStencil = {reversedDepth ? 0.0f : 1.0f, 0};
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, {uint32_t(width), uint32_t(height)}};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &colourAttachment;
  rendering.pDepthAttachment = &depthAttachment;
  vkCmdBeginRendering(cb, &rendering);
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline);
  VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
  VkRect2D scissor{{0, 0}, {uint32_t(width), uint32_t(height)}};
  vkCmdSetViewport(cb, 0, 1, &viewport);
  vkCmdSetScissor(cb, 0, 1, &scissor);
  const firmament::CameraFrame camera = firmament::cameraFrame(sky.camera());
  const float shade[4] = {brightness, brightness, brightness, 1.0f};
  auto drawTriangles = [&](const Pipeline& with) {
    for (const Triangle& t : kTriangles) {
      // Half the width of a column of the image at that depth times 3: a few pixels across.
      const double size = 3.0 * t.z * camera.tanHalfFovX / double(width) * 2.0;
      TrianglePush push = triangleAt(t.u, t.v, t.z, size, camera, width, height, kNear, kFar, shade);
      vkCmdPushConstants(cb, with.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                         &push);
      vkCmdDraw(cb, 3, 1, 0, 0);
    }
  };
  if (!lit && geometry) drawTriangles(pipeline);
  vkCmdEndRendering(cb);
  // 2. The layouts Firmament expects (docs/api.md): colour GENERAL, depth read-only.
  imageBarrier(cb, colour.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
               VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  imageBarrier(cb, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
               VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  // 3. The sky, the aerial perspective over the triangles.
  firmament::EmbeddedTargets targets;
  targets.commandBuffer = cb;
  targets.width = width;
  targets.height = height;
  targets.colour = colour.view;
  targets.colourFormat = colourFormat;
  targets.depth = depth.view;
  targets.depthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  targets.near_m = kNear;
  targets.far_m = kFar;
  targets.depthConvention = reversedDepth ? firmament::DepthConvention::Reversed : firmament::DepthConvention::Standard;
  PendingFrame pending;
  Frame& frame = pending.frame;
  vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries, 0);
  frame.info = sky.record(targets);
  vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries, 1);
  VkImageLayout colourLayout = VK_IMAGE_LAYOUT_GENERAL;
  if (lit) {
    // 3b. The host shades its own triangles with Firmament's air, over the sky: the lookups of this
    // record() (written by its commands, which come first in this command buffer).
    const firmament::AtmosphereLookups lookups = sky.lookups();
    LitBlock block{};
    block.atmosphere = lookups.parameters;
    for (int i = 0; i < 3; ++i) {
      block.forward[i] = float(camera.forward[i]);
      block.right[i] = float(camera.right[i]);
      block.up[i] = float(camera.up[i]);
    }
    block.forward[3] = float(camera.tanHalfFovX);
    std::memcpy(lit->mapped, &block, sizeof(block));
    VkDescriptorBufferInfo blockInfo{lit->block, 0, sizeof(LitBlock)};
    VkDescriptorImageInfo tables[2] = {{lit->sampler, lookups.transmittance, lookups.layout},
                                       {lit->sampler, lookups.aerialPerspective, lookups.layout}};
    VkWriteDescriptorSet writes[3] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                      {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                      {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    for (uint32_t i = 0; i < 3; ++i) {
      writes[i].dstSet = lit->set;
      writes[i].dstBinding = i;
      writes[i].descriptorCount = 1;
      writes[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      if (i == 0) writes[i].pBufferInfo = &blockInfo;
      if (i > 0) writes[i].pImageInfo = &tables[i - 1];
    }
    vkUpdateDescriptorSets(h.device, 3, writes, 0, nullptr);
    imageBarrier(cb, colour.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
    colourAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    rendering.pDepthAttachment = nullptr;
    vkCmdBeginRendering(cb, &rendering);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, lit->pipeline.pipeline);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, lit->pipeline.layout, 0, 1, &lit->set, 0, nullptr);
    vkCmdSetViewport(cb, 0, 1, &viewport);
    vkCmdSetScissor(cb, 0, 1, &scissor);
    drawTriangles(lit->pipeline);
    vkCmdEndRendering(cb);
    colourLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  }
  // 4. Read back (Firmament's last command made its writes visible; the layout is still GENERAL).
  imageBarrier(cb, colour.image, VK_IMAGE_ASPECT_COLOR_BIT, colourLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               lit ? VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT : VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
               lit ? VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT : VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
               VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {uint32_t(width), uint32_t(height), 1};
  vkCmdCopyImageToBuffer(cb, colour.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1, &copy);
  check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  check(vkCreateFence(h.device, &fenceInfo, nullptr, &fence), "vkCreateFence");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cb;
  pending.submitted = std::chrono::steady_clock::now();
  check(vkQueueSubmit(h.queue, 1, &submit, fence), "vkQueueSubmit");
  pending.pool = pool;
  pending.cb = cb;
  pending.readback = readback;
  pending.readbackMemory = readbackMemory;
  pending.bytes = bytes;
  pending.queries = queries;
  pending.fence = fence;
  pending.full = full;
  pending.width = width;
  pending.height = height;
  return pending;
}

// Waits for the frame, reads its image back and frees what beginFrame made.
Frame finishFrame(const Host& h, PendingFrame& p) {
  Frame frame = std::move(p.frame);
  const VkFence fence = p.fence;
  const VkQueryPool queries = p.queries;
  const VkDeviceMemory readbackMemory = p.readbackMemory;
  const VkDeviceSize bytes = p.bytes;
  const bool full = p.full;
  const int width = p.width, height = p.height;
  check(vkWaitForFences(h.device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  frame.submitMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - p.submitted).count();

  uint64_t ticks[2] = {0, 0};
  check(vkGetQueryPoolResults(h.device, queries, 0, 2, sizeof(ticks), ticks, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(h.physical, &properties);
  frame.skyMilliseconds = double(ticks[1] - ticks[0]) * properties.limits.timestampPeriod * 1e-6;
  vkDestroyQueryPool(h.device, queries, nullptr);
  void* mapped = nullptr;
  check(vkMapMemory(h.device, readbackMemory, 0, bytes, 0, &mapped), "vkMapMemory");
  const uint16_t* halves = static_cast<const uint16_t*>(mapped);
  frame.rgba.resize(size_t(width) * size_t(height) * 4);
  if (full) std::memcpy(frame.rgba.data(), mapped, bytes);
  for (size_t i = 0; i < frame.rgba.size() && !full; ++i) {  // IEEE half to float
    const uint16_t v = halves[i];
    const int exponent = (v >> 10) & 31, mantissa = v & 1023;
    const float magnitude = exponent == 0    ? std::ldexp(float(mantissa), -24)
                            : exponent == 31 ? INFINITY
                                             : std::ldexp(float(mantissa | 1024), exponent - 25);
    frame.rgba[i] = (v & 0x8000) ? -magnitude : magnitude;
  }
  vkUnmapMemory(h.device, readbackMemory);
  vkDestroyFence(h.device, fence, nullptr);
  vkDestroyBuffer(h.device, p.readback, nullptr);
  vkFreeMemory(h.device, readbackMemory, nullptr);
  vkDestroyCommandPool(h.device, p.pool, nullptr);
  return frame;
}

Frame renderFrame(const Host& h, firmament::Sky& sky, const Pipeline& pipeline, Image& colour, Image& depth, int width,
                  int height, float brightness, VkFormat colourFormat, Lit* lit = nullptr) {
  PendingFrame pending = beginFrame(h, sky, pipeline, colour, depth, width, height, brightness, colourFormat, lit);
  return finishFrame(h, pending);
}

// Beer-Lambert transmittance of the air along a ray from the camera (height h0 above the ground sphere
// of radius R) at elevation sin(elevation) = s, over distance d: Bruneton 2017's Earth ("Precomputed
// Atmospheric Scattering: a New Implementation", its demo's constants): Rayleigh 5.802, 13.558,
// 33.1 / Mm at 680, 550, 440 nm with scale height 8 km, aerosols' extinction 4.44 / Mm (beta 5.328e-3
// over 1.2 km), no ozone below 10 km.
void beerLambert(double h0, double s, double d, double R, double out[3]) {
  const double rayleigh[3] = {5.802e-6, 13.558e-6, 33.1e-6};
  const double mie = 5.328e-3 / 1200.0;
  double tau[3] = {0.0, 0.0, 0.0};
  const int steps = 256;
  for (int i = 0; i <= steps; ++i) {
    const double x = d * double(i) / steps;
    const double r = std::sqrt(x * x + 2.0 * (R + h0) * s * x + (R + h0) * (R + h0));
    const double h = r - R;
    const double w = (i == 0 || i == steps ? 0.5 : 1.0) * d / steps;
    for (int c = 0; c < 3; ++c) tau[c] += w * (rayleigh[c] * std::exp(-h / 8000.0) + mie * std::exp(-h / 1200.0));
  }
  for (int c = 0; c < 3; ++c) out[c] = std::exp(-tau[c]);
}

int run(const Options& options) {
  const char* env = std::getenv("FIRMAMENT_VALIDATION");
  const bool validation = env && *env && std::strcmp(env, "0") != 0;
  Host h = createHost(validation);
  const int width = options.width, height = options.height;
  const VkFormat colourFormat = options.full ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
  Image colour =
      createImage(h, width, height, colourFormat,
                  VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                  VK_IMAGE_ASPECT_COLOR_BIT);
  Image depth =
      createImage(h, width, height, VK_FORMAT_D32_SFLOAT,
                  VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  Pipeline pipeline =
      createPipeline(h, triangle_vert, triangle_frag, colourFormat, VK_FORMAT_D32_SFLOAT, VK_NULL_HANDLE);
  Lit lit = createLit(h, colourFormat);
  int failures = 0;
  {
    firmament::Sky::Builder builder;
    if (options.scene.empty()) {
      builder.sceneJson(kScene);
    } else {
      builder.sceneFile(options.scene);
    }
    auto sky = builder.temporalReprojection(options.frames > 0)
                   .embedded({h.instance, h.physical, h.device, h.family, h.queue})
                   .build();
    Frame bright = renderFrame(h, *sky, pipeline, colour, depth, width, height, kBright, colourFormat);
    std::printf("frame 1: record %.1f ms, preparation submitted: %s\n", bright.info.recordMilliseconds,
                bright.info.submittedPreparation ? "yes" : "no");
    firmament::SkyFrame image{width, height, bright.rgba};
    firmament::saveExr(image, options.out);
    std::printf("wrote %s\n", options.out.c_str());

    if (options.frames > 0) {
      std::vector<double> submit, record, skyGpu, gpu, wall;
      std::vector<std::vector<double>> passes;  // per pass label of the first timed frame
      std::vector<std::string> labels;
      for (int i = 0; i < options.frames; ++i) {
        Frame f = renderFrame(h, *sky, pipeline, colour, depth, width, height, kBright, colourFormat);
        submit.push_back(f.submitMilliseconds);
        record.push_back(f.info.recordMilliseconds);
        skyGpu.push_back(f.skyMilliseconds);
        // Firmament's own timestamps of the frame before (read at this record(), without waiting).
        for (const firmament::PassTime& p : f.info.previousFramePasses) {
          auto at = std::find(labels.begin(), labels.end(), p.label);
          if (at == labels.end()) {
            labels.push_back(p.label);
            passes.emplace_back();
            at = labels.end() - 1;
          }
          passes[size_t(at - labels.begin())].push_back(p.milliseconds);
        }
      }
      for (size_t i = 0; i < labels.size(); ++i)
        std::printf("  pass %s: %.1f ms GPU (median)\n", labels[i].c_str(), median(passes[i]));
      firmament::Sky::Builder offlineBuilder;
      if (options.scene.empty()) {
        offlineBuilder.sceneJson(kScene);
      } else {
        offlineBuilder.sceneFile(options.scene);
      }
      auto offline = offlineBuilder.build();
      offline->setCamera(sky->camera());
      offline->render(width, height);  // the first frame builds the tables, as the embedded one did
      for (int i = 0; i < options.frames; ++i) {
        firmament::SkyFrame f = offline->render(width, height);
        gpu.push_back(f.gpuMilliseconds);
        wall.push_back(f.wallMilliseconds);
      }
      std::printf(
          "%dx%d, %d frames: embedded: Firmament's commands %.1f ms GPU, host submit to fence %.1f ms, "
          "record() %.2f ms CPU; offline render(): GPU %.1f ms, wall %.1f ms (medians)\n",
          width, height, options.frames, median(skyGpu), median(submit), median(record), median(gpu), median(wall));
    }

    if (options.check) {
      Frame black = renderFrame(h, *sky, pipeline, colour, depth, width, height, 0.0f, colourFormat);
      std::printf("frame 2: record %.1f ms, preparation submitted: %s\n", black.info.recordMilliseconds,
                  black.info.submittedPreparation ? "yes" : "no");
      if (black.info.submittedPreparation) {
        std::printf("FAIL: a second frame of the same view submitted preparation work\n");
        ++failures;
      }
      // Firmament's timestamps of frame 1, read at frame 2's record() (frame 1 had finished).
      uint32_t familyCount = 0;
      vkGetPhysicalDeviceQueueFamilyProperties(h.physical, &familyCount, nullptr);
      std::vector<VkQueueFamilyProperties> families(familyCount);
      vkGetPhysicalDeviceQueueFamilyProperties(h.physical, &familyCount, families.data());
      std::printf("frame 1's passes, read at frame 2: %zu, %.1f ms GPU\n", black.info.previousFramePasses.size(),
                  black.info.previousFrameGpuMilliseconds);
      if (families[h.family].timestampValidBits > 0 &&
          (black.info.previousFramePasses.empty() || !(black.info.previousFrameGpuMilliseconds > 0.0))) {
        std::printf("FAIL: no pass timings of the previous frame\n");
        ++failures;
      }
      // Equal values through the image: an RGBA16F store may truncate (2^-10 relative), RGBA32F keeps floats.
      const double tolerance = options.full ? 1e-5 : 2e-3;
      // The built-in clear view checks the air over the triangles; a scene of the user's (clouds may
      // cover the triangles) checks the sky and that the triangles are there.
      const bool builtIn = options.scene.empty();
      // The host's own shading with the exported lookups: the same triangles drawn after record().
      Frame shaded;
      if (builtIn) shaded = renderFrame(h, *sky, pipeline, colour, depth, width, height, kBright, colourFormat, &lit);
      double worstShaded = 0.0;
      int shadedPixels = 0;
      for (size_t i = 0; i < shaded.rgba.size(); i += 4) {
        if (!(std::fabs(bright.rgba[i + 1] - black.rgba[i + 1]) > 1.0f)) continue;  // not a triangle
        ++shadedPixels;
        for (int c = 0; c < 3; ++c)
          worstShaded = std::max(worstShaded, double(std::fabs(shaded.rgba[i + c] - bright.rgba[i + c])) /
                                                  std::max(double(std::fabs(bright.rgba[i + c])), 1e-3));
      }
      if (builtIn)
        std::printf(
            "the host's own shading with the lookups vs Firmament's composite: %d pixels, worst relative "
            "difference %.2e (tolerance %.0e)\n",
            shadedPixels, worstShaded, tolerance);
      if (builtIn && (shadedPixels < 8 || !(worstShaded <= tolerance))) {
        std::printf("FAIL: the host's shading with the exported lookups differs from the composite\n");
        ++failures;
      }
      // The offline render of the same view (its own device).
      firmament::Sky::Builder offlineBuilder;
      if (builtIn) {
        offlineBuilder.sceneJson(kScene);
      } else {
        offlineBuilder.sceneFile(options.scene);
      }
      // A still, but with one cloud march as the embedded frames have (its sub-frames would differ by the jitter).
      auto offline = offlineBuilder.temporalReprojection(false).quality("/clouds/march/still_samples=1").build();
      firmament::SkyFrame reference = offline->render(width, height);
      // Which pixels the triangles cover: where the bright and the black frame differ.
      double skyWorst = 0.0;
      int skyPixels = 0, covered[2] = {0, 0};
      double meanT[2][3] = {}, meanL[2][3] = {}, worstBeer = 0.0;
      const firmament::CameraFrame camera = firmament::cameraFrame(sky->camera());
      const double R = std::stod(sky->get("/atmosphere/bottom_radius_m"));
      const double h0 = std::stod(sky->get("/location/height_m")) + sky->camera().heightAboveGround_m;
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const size_t i = (size_t(y) * width + x) * 4;
          const bool triangle = std::fabs(bright.rgba[i + 1] - black.rgba[i + 1]) > 1.0f;
          if (!triangle) {
            for (int c = 0; c < 3; ++c) {
              const double a = bright.rgba[i + c], b = reference.rgba[i + c];
              skyWorst = std::max(skyWorst, std::fabs(a - b) / std::max(std::fabs(b), 1e-3));
            }
            ++skyPixels;
            continue;
          }
          const int pair = x < width / 2 ? 0 : 1;
          const double z = pair == 0 ? 1000.0 : 8000.0;
          // The pixel's ray and its distance to the triangle's plane (view-space depth z).
          const double px = (2.0 * (x + 0.5) / width - 1.0) * camera.tanHalfFovX;
          const double py = (1.0 - 2.0 * (y + 0.5) / height) * camera.tanHalfFovX * double(height) / double(width);
          double dir[3], length = 0.0;
          for (int k = 0; k < 3; ++k) {
            dir[k] = camera.forward[k] + px * camera.right[k] + py * camera.up[k];
            length += dir[k] * dir[k];
          }
          length = std::sqrt(length);
          const double distance = z * length;  // z / cos(angle to the axis)
          double expected[3];
          beerLambert(h0, dir[2] / length, distance, R, expected);
          ++covered[pair];
          for (int c = 0; c < 3; ++c) {
            const double T = (bright.rgba[i + c] - black.rgba[i + c]) / kBright;
            meanT[pair][c] += T;
            meanL[pair][c] += black.rgba[i + c];
            worstBeer = std::max(worstBeer, std::fabs(T - expected[c]) / expected[c]);
          }
        }
      for (int p = 0; p < 2; ++p)
        for (int c = 0; c < 3; ++c) {
          meanT[p][c] /= std::max(covered[p], 1);
          meanL[p][c] /= std::max(covered[p], 1);
        }
      std::printf("sky: %d pixels, worst relative difference from the offline render %.2e (tolerance %.0e)\n",
                  skyPixels, skyWorst, tolerance);
      std::printf("triangles at 1 km: %d pixels, T %.4f %.4f %.4f, L %.1f %.1f %.1f cd/m^2\n", covered[0], meanT[0][0],
                  meanT[0][1], meanT[0][2], meanL[0][0], meanL[0][1], meanL[0][2]);
      std::printf("triangles at 8 km: %d pixels, T %.4f %.4f %.4f, L %.1f %.1f %.1f cd/m^2\n", covered[1], meanT[1][0],
                  meanT[1][1], meanT[1][2], meanL[1][0], meanL[1][1], meanL[1][2]);
      if (builtIn)
        std::printf(
            "transmittance vs Beer-Lambert through Bruneton's Earth: worst relative error %.2e (tolerance 1e-2)\n",
            worstBeer);
      if (!(skyWorst <= tolerance) || skyPixels < width * height / 2) {
        std::printf("FAIL: the sky differs from the offline render\n");
        ++failures;
      }
      if (covered[0] < 4 || covered[1] < 4) {
        std::printf("FAIL: a triangle pair is missing from the image (overwritten?)\n");
        ++failures;
      }
      if (builtIn && !(worstBeer <= 1e-2)) {
        std::printf("FAIL: the transmittance over the triangles is not the air's\n");
        ++failures;
      }
      for (int c = 0; c < 3; ++c)
        if (builtIn && (!(meanT[1][c] < meanT[0][c]) || !(meanL[1][c] > meanL[0][c]))) {
          std::printf("FAIL: the far triangles are not hazier than the near ones (channel %d)\n", c);
          ++failures;
        }
      if (!offline->validationMessages().empty()) {
        std::printf("FAIL: %zu validation messages on the offline device\n", offline->validationMessages().size());
        ++failures;
      }
    }
    firmament::AtmosphereLookups lookups = sky->lookups();
    std::printf("lookups: transmittance %s, aerial perspective %s, volume depth %.0f m\n",
                lookups.transmittance ? "ok" : "missing", lookups.aerialPerspective ? "ok" : "missing",
                lookups.parameters.radii[3]);
  }  // the sky goes before the device (every frame it recorded has finished)
  if (options.inFlight > 1) {
    // N frames in flight (docs/api.md, "Frames in flight"): frame i is recorded and submitted while the
    // N - 1 before it may still run, each into its own colour and depth images; the camera turns 20 degrees a
    // frame (no preparation: nothing waits for the queue), so a frame that read another's resources would look the
    // wrong way. Each frame, waited for only when its slot comes round again, must equal the offline render of its own
    // view.
    const int n = options.inFlight, count = 3 * n;
    firmament::Sky::Builder builder, offlineBuilder;
    if (options.scene.empty()) {
      builder.sceneJson(kScene);
      offlineBuilder.sceneJson(kScene);
    } else {
      builder.sceneFile(options.scene);
      offlineBuilder.sceneFile(options.scene);
    }
    auto sky = builder.temporalReprojection(false)
                   .framesInFlight(n)
                   .embedded({h.instance, h.physical, h.device, h.family, h.queue})
                   .build();
    // A still, but with one cloud march as the embedded frames have (its sub-frames would differ by the jitter).
    auto offline = offlineBuilder.temporalReprojection(false).quality("/clouds/march/still_samples=1").build();
    std::vector<Image> colours, depths;
    for (int i = 0; i < n; ++i) {
      colours.push_back(createImage(
          h, width, height, colourFormat,
          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
          VK_IMAGE_ASPECT_COLOR_BIT));
      depths.push_back(createImage(h, width, height, VK_FORMAT_D32_SFLOAT,
                                   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                   VK_IMAGE_ASPECT_DEPTH_BIT));
    }
    const firmament::SkyCamera start = sky->camera();
    std::vector<std::optional<PendingFrame>> pending(static_cast<size_t>(n));
    std::vector<firmament::SkyCamera> cameras(static_cast<size_t>(n));
    std::vector<firmament::SkyFrame> references;
    const double tolerance = options.full ? 1e-5 : 2e-3;
    double worst = 0.0;
    int overlapped = 0;    // frames submitted while an earlier one had not finished
    int preparations = 0;  // frames whose record() submitted preparation work (and so waited for the queue)
    auto relative = [](const std::vector<float>& a, const std::vector<float>& b) {
      double w = 0.0;
      for (size_t i = 0; i < a.size(); i += 4)
        for (int c = 0; c < 3; ++c)
          w = std::max(w, std::fabs(double(a[i + c]) - b[i + c]) / std::max(std::fabs(double(b[i + c])), 1e-3));
      return w;
    };
    std::vector<std::vector<float>> images;  // in frame order
    std::vector<firmament::SkyCamera> frameCameras;
    auto finish = [&](int slot) {
      Frame f = finishFrame(h, *pending[size_t(slot)]);
      preparations += f.info.submittedPreparation ? 1 : 0;
      images.push_back(std::move(f.rgba));
      frameCameras.push_back(cameras[size_t(slot)]);
      pending[size_t(slot)].reset();
    };
    for (int i = 0; i < count + n; ++i) {
      const int slot = i % n;
      if (pending[size_t(slot)]) finish(slot);
      if (i >= count) continue;
      for (const auto& p : pending)
        if (p && vkGetFenceStatus(h.device, p->fence) == VK_NOT_READY) {
          ++overlapped;
          break;
        }
      cameras[size_t(slot)] = start;
      cameras[size_t(slot)].yaw_deg = start.yaw_deg + 20.0 * i;
      sky->setCamera(cameras[size_t(slot)]);
      pending[size_t(slot)] = beginFrame(h, *sky, pipeline, colours[size_t(slot)], depths[size_t(slot)], width, height,
                                         kBright, colourFormat, nullptr, false);
    }
    for (size_t i = 0; i < images.size(); ++i) {  // the references after the frames: no wait between them
      offline->setCamera(frameCameras[i]);
      references.push_back(offline->render(width, height));
      worst = std::max(worst, relative(images[i], references.back().rgba));
    }
    double change = 1e30;  // the smallest change of the sky from one frame's time to the next
    for (size_t i = 1; i < references.size(); ++i)
      change = std::min(change, relative(references[i].rgba, references[i - 1].rgba));
    std::printf(
        "%d frames in flight: %d frames, %d recorded while an earlier one ran, %d prepared; worst relative "
        "difference from the offline render of each frame's view %.2e (tolerance %.0e); the sky changes by at "
        "least %.2e a frame\n",
        n, count, overlapped, preparations, worst, tolerance, change);
    if (!(worst <= tolerance)) {
      std::printf("FAIL: a frame in flight differs from the offline render of its view\n");
      ++failures;
    }
    if (!(change > 10.0 * tolerance)) {
      std::printf("FAIL: consecutive frames differ too little for the check to see a mix-up\n");
      ++failures;
    }
    if (!offline->validationMessages().empty()) ++failures;
    for (int i = 0; i < n; ++i) {
      destroyImage(h, colours[size_t(i)]);
      destroyImage(h, depths[size_t(i)]);
    }
  }
  destroyLit(h, lit);
  vkDestroyPipeline(h.device, pipeline.pipeline, nullptr);
  vkDestroyPipelineLayout(h.device, pipeline.layout, nullptr);
  destroyImage(h, colour);
  destroyImage(h, depth);
  vkDestroyDevice(h.device, nullptr);
  if (h.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(h.instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(h.instance, h.messenger, nullptr);
  }
  vkDestroyInstance(h.instance, nullptr);
  if (validation) std::printf("validation messages on the host's instance: %zu\n", validationMessages.size());
  if (!validationMessages.empty()) ++failures;
  if (options.check) std::printf(failures == 0 ? "all checks passed\n" : "%d checks failed\n", failures);
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "host_example: %s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--out") {
      options.out = value();
    } else if (arg == "--width") {
      options.width = std::atoi(value().c_str());
    } else if (arg == "--height") {
      options.height = std::atoi(value().c_str());
    } else if (arg == "--scene") {
      options.scene = value();
    } else if (arg == "--frames") {
      options.frames = std::atoi(value().c_str());
    } else if (arg == "--colour") {
      const std::string format = value();
      if (format != "rgba16f" && format != "rgba32f") {
        std::fprintf(stderr, "host_example: --colour %s: allowed: rgba16f, rgba32f\n", format.c_str());
        return 2;
      }
      options.full = format == "rgba32f";
    } else if (arg == "--reversed-depth") {
      reversedDepth = true;
    } else if (arg == "--frames-in-flight") {
      options.inFlight = std::atoi(value().c_str());
      if (options.inFlight < 2 || options.inFlight > 4) {
        std::fprintf(stderr, "host_example: --frames-in-flight %d: allowed: 2 to 4\n", options.inFlight);
        return 2;
      }
    } else if (arg == "--check") {
      options.check = true;
    } else {
      std::fprintf(stderr,
                   "host_example: unknown option %s (allowed: --out FILE.exr --width W --height H --scene FILE "
                   "--frames N --frames-in-flight N --colour rgba16f|rgba32f --reversed-depth --check)\n",
                   arg.c_str());
      return 2;
    }
  }
  if (options.check && options.frames > 0) {
    std::fprintf(stderr, "host_example: --check and --frames exclude each other\n");
    return 2;
  }
  if (options.frames < 0 || options.frames > 1000) {
    std::fprintf(stderr, "host_example: --frames %d: allowed: 0 to 1000\n", options.frames);
    return 2;
  }
  if (options.width < 16 || options.height < 16 || options.width > 8192 || options.height > 8192) {
    std::fprintf(stderr, "host_example: size %dx%d: allowed: 16 to 8192 pixels a side\n", options.width,
                 options.height);
    return 2;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "host_example: %s\n", e.what());
    return 1;
  }
}
