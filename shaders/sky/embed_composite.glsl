// Embedded mode (include/firmament/embed.h, docs/api.md): the host's pixels in Firmament's frame, and the
// frame out to the host's colour image. One kernel, three modes (push.depth.w):
//  0 (after the sky, the night and the terrain, before the clouds): where the host's depth is nearer than
//    the far plane (and the terrain), the frame's pixel becomes the host's colour seen through the air to
//    that distance, L T + in-scattered light (firmament/atmosphere_lookup.glsl, the aerial-perspective
//    volume), and the distance (m along the ray) goes to the clouds, whose march stops there; elsewhere
//    the sky stays and the distance is the terrain's (1e30 without).
//  1 (last): the frame to the host's colour image (alpha: the clouds' transmittance, 1 without).
//  2 (a frame without clouds): 0 and 1 in one pass, no distances written.
// On lavapipe each storage-image access costs more than the pass's arithmetic (640x360: ~24 ms for 0,
// ~39 ms for 1 with a load and a store per pixel), so 1 only stores and 2 loads only the host's pixels.
// Depth to distance: a perspective depth buffer in Vulkan's [0, 1] range, view-space z = n f / (f - z (f - n))
// (standard: 0 at the near plane n, 1 at the far plane f) or n f / (n + z (f - n)) (reversed), then the
// distance along the ray z / (ray . forward). The far plane (1, reversed 0) is the sky.
#include "common/camera.glsl"
#include "common/dispatch.glsl"
#include "firmament/atmosphere_lookup.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
#define SKY_FRAME_BLOCK_BINDING 0
#include "sky/frame_block.glsl"
layout(set = 0, binding = 1) uniform sampler2D hostDepth;  // nearest
layout(set = 0, binding = 2, EMBED_COLOUR_FORMAT) uniform image2D hostColour;
layout(set = 0, binding = 3) uniform sampler3D aerialVolume;  // linear, clamp
layout(std430, set = 0, binding = 4) buffer SkyFrame { vec4 pixels[]; } skyFrame;
layout(std430, set = 0, binding = 5) buffer HostDistance { float t[]; } hostDistance;
layout(std430, set = 0, binding = 6) readonly buffer TerrainDepth { float t[]; } terrainDepth;
layout(push_constant) uniform Push {
  TileDispatch tiles;
  vec4 depth;  // near (m), far (m), 1: reversed depth, mode
  FirmamentAtmosphere atmosphere;
} push;

void main() {
  uvec2 tiled;
  if (!tilePixel(push.tiles, tiled)) return;
  uint index = tiled.y * push.tiles.width + tiled.x;
  ivec2 texel = ivec2(tiled);
  int mode = int(push.depth.w + 0.5);
  if (mode == 1) {
    imageStore(hostColour, texel, skyFrame.pixels[index]);
    return;
  }
  bool fused = mode == 2;
  float terrain = index < uint(terrainDepth.t.length()) ? terrainDepth.t[index] : 1.0e30;
  float z = texelFetch(hostDepth, texel, 0).r;
  bool reversed = push.depth.z > 0.5;
  bool far = reversed ? z <= 0.0 : z >= 1.0;
  if (!fused) hostDistance.t[index] = terrain;
  if (far) {
    if (fused) imageStore(hostColour, texel, skyFrame.pixels[index]);
    return;
  }
  float n = push.depth.x, f = push.depth.y;
  float viewZ = reversed ? n * f / (n + z * (f - n)) : n * f / (f - z * (f - n));
  CameraParameters camera = cameraFromBlock(frame.camera_forward, frame.camera_right, frame.camera_up, frame.image);
  vec2 pixel = vec2(tiled) + 0.5;
  bool valid;
  vec3 dir = cameraRayDirection(camera, pixel, valid);
  float distance = viewZ / max(dot(dir, camera.forward), 1e-6);
  if (distance >= terrain) {
    if (fused) imageStore(hostColour, texel, skyFrame.pixels[index]);
    return;
  }
  vec3 colour = imageLoad(hostColour, texel).rgb;
  float nu = dot(dir, frame.sun_direction.xyz);
  vec3 seen = firmamentApplyAerialPerspective(aerialVolume, push.atmosphere, pixel, distance, nu, colour);
  if (fused) {
    imageStore(hostColour, texel, vec4(seen, 1.0));
    return;
  }
  skyFrame.pixels[index] = vec4(seen, 1.0);
  hostDistance.t[index] = distance;
}
