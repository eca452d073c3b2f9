// Clear-sky render: sky, ground and sun disc in linear Rec.709 cd/m². Two ways to the same integral
// (sky/sky_march.glsl): read the per-frame sky-view LUT (fast; cameras inside the atmosphere), or
// march every pixel (any camera, including space). Then the sun's disc, attenuated by T(camera, top).
//
// The way is chosen at compile time (SKY_FROM_LUT 1 in render_sky.comp, 0 in render_sky_march.comp),
// not by a uniform: lavapipe runs both sides of a branch under an execution mask, so a never-taken
// march still cost ~40 % of the LUT pass (bench_sky_frame, docs/gpu.md).
#ifndef SKY_FROM_LUT
#error "define SKY_FROM_LUT before including sky/render_sky.glsl"
#endif
#include "sky/sky_march.glsl"
#include "common/camera.glsl"
#include "common/dispatch.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler2D multipleScatteringLut;
// The frame: one vec4 per pixel, row-major (a storage buffer: on lavapipe a storage-image store costs
// ~4x a buffer store, bench/output_write.cpp).
layout(std430, set = 0, binding = 3) buffer OutputFrame { vec4 pixels[]; } outputFrame;
#define SKY_FRAME_BLOCK_BINDING 4
#include "sky/frame_block.glsl"
layout(set = 0, binding = 5) uniform sampler2D skyViewLut;
layout(set = 0, binding = 6) uniform sampler2D sunRadianceLut;  // see atmosphere/transmittance_lut.comp
layout(set = 0, binding = 7) uniform sampler2D skyIrradianceLut;  // see atmosphere/fms_sky_irradiance.comp
layout(set = 0, binding = 8) uniform sampler2D multipleScatteringAnisotropy;  // see atmosphere/multiple_scattering_lut.glsl
layout(push_constant) uniform Push {
  TileDispatch tiles;
  int accumulate;  // add to the pixel: per-pixel marching runs once per spectral batch
  int draw_sun;    // add the sun's disc (once)
  int last;        // the last pass: clamp (spectral batches may add negative Rec.709 lobes before it)
} push;

// The sky-view LUT's texel for a direction seen from `origin` (on the +z axis of the frame).
vec3 skyFromLut(AtmosphereParameters atmosphere, vec3 origin, vec3 dir, vec3 sun) {
  vec3 up = normalize(origin);
  float r = length(origin);
  float theta = acos(clamp(dot(dir, up), -1.0, 1.0));
  // azimuth between the view and the sun, measured in the plane of the local horizon
  vec3 dir_h = dir - dot(dir, up) * up;
  vec3 sun_h = sun - dot(sun, up) * up;
  float norms = length(dir_h) * length(sun_h);
  float cos_phi = norms > 1e-8 ? clamp(dot(dir_h, sun_h) / norms, -1.0, 1.0) : 1.0;
  return textureLod(skyViewLut, skyViewUvFromAngles(atmosphere, r, theta, cos_phi), 0.0).rgb;
}

void main() {
  // Tiles in interleaved order on lavapipe (balances sky against ground), row order on GPUs.
  uvec2 tile_pixel;
  if (!tilePixel(push.tiles, tile_pixel)) return;
  ivec2 pixel = ivec2(tile_pixel);
  uint index = tile_pixel.y * push.tiles.width + tile_pixel.x;

  AtmosphereParameters atmosphere = atmosphereFromBlock();
  CameraParameters camera = cameraFromBlock(frame.camera_forward, frame.camera_right, frame.camera_up, frame.image);
  bool valid;
  vec3 dir = cameraRayDirection(camera, vec2(pixel) + 0.5, valid);
  if (!valid) {
    outputFrame.pixels[index] = vec4(0.0);
    return;
  }
  vec3 sun = frame.sun_direction.xyz;
  vec3 origin = frame.camera_position.xyz;
  float r = length(origin);
  float mu = dot(origin, dir) / r;
  vec3 rgb;
  bool hits_ground;
#if SKY_FROM_LUT
  rgb = skyFromLut(atmosphere, origin, dir, sun);
  hits_ground = rayIntersectsGround(atmosphere, max(r, atmosphere.bottom_radius + 0.01), mu);
#else
  SkyMarch m = marchSky(atmosphere, transmittanceLut, multipleScatteringLut, multipleScatteringAnisotropy, skyIrradianceLut, origin, dir, sun, frame.image.w);
  rgb = m.rgb;
  hits_ground = m.hits_ground;
#endif
  if (push.draw_sun != 0 && !hits_ground) {
    float limb = sunLimbDarkening(dot(dir, sun), atmosphere.sun_angular_radius);
    if (limb > 0.0) {
      // Transmittance to the sun from where the ray is in the atmosphere: the camera, or from space
      // the ray's entry point (a ray that misses the atmosphere sees the sun unattenuated: r = top,
      // mu = 1 has T = 1).
      float r_t = max(r, atmosphere.bottom_radius + 0.01);
      float mu_t = mu;
      if (r > atmosphere.top_radius) {
        r_t = atmosphere.top_radius;
        mu_t = rayIntersectsGround(r, mu, atmosphere.top_radius)
                   ? dot(origin + dir * distanceToBottomAtmosphereBoundary(r, mu, atmosphere.top_radius), dir) /
                         atmosphere.top_radius
                   : 1.0;
      }
      vec2 uv = transmittanceUvFromRMu(atmosphere, r_t, mu_t, textureSize(sunRadianceLut, 0));
      rgb += textureLod(sunRadianceLut, uv, 0.0).rgb * limb;
    }
  }
#if !SKY_FROM_LUT
  // Per-pixel marching runs once per spectral batch; the sky-view table already holds their sum.
  if (push.accumulate != 0) rgb += outputFrame.pixels[index].rgb;
  if (push.last != 0) rgb = max(rgb, vec3(0.0));
#else
  rgb = max(rgb, vec3(0.0));
#endif
  outputFrame.pixels[index] = vec4(rgb, 1.0);
}
