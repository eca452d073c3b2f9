#version 450
#extension GL_GOOGLE_include_directive : require
// The daytime Moon (docs/night.md, "The daytime Moon"): with the sun above the night's limit no night pass
// runs, and only the Moon's disc is added to the sky frame, over the disc's pixel rectangle. The disc's
// radiance above the air per pixel (common/moon_disc.glsl, 4x4 samples per pixel, or a point of the Moon's
// illuminance splatted energy-conserving when the disc is under two pixels in radius) comes from the CPU
// (sky/night_pass.cpp, DayMoonDiscPass); here it is extincted along the view as the night pass extincts it
// (the sun disc's table over its value outside the air, per Rec.709 channel) and added before the clouds
// composite over the sky (so the clouds' transmittance dims it). Rays that meet the ground add nothing.
#include "atmosphere/atmosphere_block.glsl"
#include "common/camera.glsl"
#include "common/dispatch.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(set = 0, binding = 1) uniform sampler2D sunRadianceLut;
layout(std430, set = 0, binding = 2) buffer OutputFrame { vec4 pixels[]; } outputFrame;
#define SKY_FRAME_BLOCK_BINDING 3
#include "sky/frame_block.glsl"
// The rectangle's radiance above the air (Rec.709, cd/m^2), row by row over the rectangle.
layout(std430, set = 0, binding = 4) readonly buffer DiscRadiance { vec4 pixels[]; } disc;
layout(push_constant) uniform Push {
  TileDispatch tiles;  // over the rectangle
  ivec4 rect;          // x0, y0 (pixels), the frame's width, unused
} push;

void main() {
  uvec2 local;
  if (!tilePixel(push.tiles, local)) return;
  vec3 above = disc.pixels[local.y * push.tiles.width + local.x].rgb;
  if (all(lessThanEqual(above, vec3(0.0)))) return;
  ivec2 pixel = push.rect.xy + ivec2(local);
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  CameraParameters camera = cameraFromBlock(frame.camera_forward, frame.camera_right, frame.camera_up, frame.image);
  bool valid;
  vec3 dir = cameraRayDirection(camera, vec2(pixel) + 0.5, valid);
  if (!valid) return;
  float r = max(length(frame.camera_position.xyz), atmosphere.bottom_radius + 0.01);
  float mu = dir.z;
  if (rayIntersectsGround(atmosphere, r, mu)) return;
  ivec2 size = textureSize(sunRadianceLut, 0);
  vec3 outside = textureLod(sunRadianceLut, transmittanceUvFromRMu(atmosphere, atmosphere.top_radius, 1.0, size), 0.0).rgb;
  vec3 inside = textureLod(sunRadianceLut, transmittanceUvFromRMu(atmosphere, r, mu, size), 0.0).rgb;
  vec3 transmittance = clamp(inside / max(outside, vec3(1e-30)), vec3(0.0), vec3(1.0));
  uint index = uint(pixel.y) * uint(push.rect.z) + uint(pixel.x);
  vec4 value = outputFrame.pixels[index];
  outputFrame.pixels[index] = vec4(value.rgb + max(above * transmittance, vec3(0.0)), value.a);
}
