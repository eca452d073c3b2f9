#pragma once
// Firmament embedded in a host's Vulkan frame (docs/api.md, "Embedded mode"): the sky adopts the host's
// VkInstance, VkPhysicalDevice, VkDevice and queue family, and per frame records its passes into the
// host's command buffer, compositing over the host's HDR colour image at the host's depth.
//
//   // device creation: add firmament::embeddedDeviceExtensions(), call enableEmbeddedDeviceFeatures()
//   auto sky = firmament::Sky::Builder().sceneFile("scenes/clear.json")
//                  .embedded({instance, physicalDevice, device, queueFamily, queue}).build();
//   sky->setCamera(camera);                                   // the host's view: same orientation and fov
//   firmament::EmbeddedFrame f = sky->record({commandBuffer, width, height, colourView,
//                                             VK_FORMAT_R16G16B16A16_SFLOAT, depthView,
//                                             VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, near, far});
//   // ... the host submits commandBuffer and waits on its own fence before the next record()
//
// Synchronisation (the host owns it; Firmament never waits inside a frame's recording):
//  - before record(): colour in VK_IMAGE_LAYOUT_GENERAL (storage usage), depth (depth aspect view,
//    sampled usage) in the layout given; the host's writes to them are recorded earlier in the same
//    command buffer or in an earlier submission. Firmament's first command is a full memory barrier
//    (all commands -> all commands), so no access barrier of the host's is needed, only its layout moves.
//  - after: Firmament's last command is a full memory barrier; the layouts are as they were.
//  - frames in flight (Sky::Builder::framesInFlight(N), default 1): the command buffer of one record()
//    must have finished executing before the record() N frames later (which reuses its uniform blocks
//    and frame buffers), and every one before the Sky is destroyed.
//  - preparation: the first record(), a new size, new atmosphere tables, new cloud noise or a new weather
//    map submit their work to the given queue and wait on Firmament's own fence inside record(), before
//    anything is recorded (EmbeddedFrame::submittedPreparation says so). The host must not use that
//    queue from another thread meanwhile (Vulkan's external synchronisation of a queue). A frame with
//    nothing to prepare submits nothing.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

#include "firmament/sky.h"

namespace firmament {

struct EmbeddedDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;  // Vulkan 1.3
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;        // with compute (a graphics family has it)
  VkQueue queue = VK_NULL_HANDLE;  // of that family: preparation work only
};

// The device extensions to enable on the host's device (VK_KHR_push_descriptor).
std::vector<const char*> embeddedDeviceExtensions();
// Turns on, in the host's feature structures (chained into its VkDeviceCreateInfo), the features
// Firmament uses that the device supports (maintenance4 always: Vulkan 1.3 has it).
void enableEmbeddedDeviceFeatures(VkPhysicalDevice physicalDevice, VkPhysicalDeviceFeatures2& features,
                                  VkPhysicalDeviceVulkan12Features& features12,
                                  VkPhysicalDeviceVulkan13Features& features13);

enum class DepthConvention {
  Standard,  // 0 at the near plane, 1 at the far plane (the sky where depth == 1)
  Reversed,  // 1 at the near plane, 0 at the far plane (the sky where depth == 0)
};

// One frame's targets. The host's projection must be Firmament's camera (cameraFrame() below): a
// perspective with the SkyCamera's orientation and horizontal field of view, square pixels, no jitter.
struct EmbeddedTargets {
  VkCommandBuffer commandBuffer = VK_NULL_HANDLE;  // recording, compute-capable queue family
  int width = 0, height = 0;                       // of colour and depth
  // Read where the host drew, written everywhere: RGB, and A the clouds' transmittance (1 without).
  VkImageView colour = VK_NULL_HANDLE;
  VkFormat colourFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // or VK_FORMAT_R32G32B32A32_SFLOAT
  VkImageView depth = VK_NULL_HANDLE;
  VkImageLayout depthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  double near_m = 0.1, far_m = 100000.0;  // the projection's planes (m)
  DepthConvention depthConvention = DepthConvention::Standard;
};

struct EmbeddedFrame {
  bool submittedPreparation = false;  // record() submitted preparation work and waited for it
  bool continued = false;             // the frame continued the previous one (temporal reprojection)
  bool cloudsReprojected = false;
  double recordMilliseconds = 0.0;  // CPU time of record(), preparation included
  // The previous record()'s passes, GPU time from timestamps Firmament wrote into that frame's command
  // buffer, read without waiting (empty when the host has not submitted it or it has not finished).
  std::vector<PassTime> previousFramePasses;
  double previousFrameGpuMilliseconds = 0.0;
  double sunZenith_deg = 0.0, sunAzimuth_deg = 0.0;
  int slot = 0;  // which of the framesInFlight sets of per-frame resources this frame used
};

// firmament/atmosphere_lookup.glsl's FirmamentAtmosphere (4 vec4, std140 and push-constant layout).
struct AtmosphereLookupParameters {
  float radii[4];           // ground radius, top radius, camera radius, aerial-perspective depth D (m)
  float sun[4];             // unit direction to the sun (camera frame: x east, y north, z up), aerosol g
  float sunIlluminance[4];  // the sun above the atmosphere (lux, Rec.709), 0
  float image[4];           // width, height, 0, 0
};

// The tables a host's shader reads to shade its own surfaces (firmament/atmosphere_lookup.glsl), as of
// the last record(): valid until the next record() (they are written by the recorded commands, so
// read them after those in the same command buffer or later). Sample with linear filtering and
// clamp to edge, in `layout`.
struct AtmosphereLookups {
  VkImageView transmittance = VK_NULL_HANDLE;      // 2D, RGBA32F (rgb used)
  VkImageView aerialPerspective = VK_NULL_HANDLE;  // 3D, RGBA32F, 3C x R x N
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
  AtmosphereLookupParameters parameters{};
};

// The camera's axes in its local frame (x east, y north, z up) and its projection: a point p (relative
// to the camera, m) is at view-space x = p.right, y = p.up, z = p.forward; the pixel x of the image
// (0 at the left edge) is (x / (z tanHalfFovX) + 1) width / 2, y (0 at the top) (1 - y / (z tanHalfFovX)
// width / height) height / 2.
struct CameraFrame {
  double forward[3], right[3], up[3];
  double tanHalfFovX;
};
CameraFrame cameraFrame(const SkyCamera& camera);

}  // namespace firmament
