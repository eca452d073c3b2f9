#version 450
#extension GL_GOOGLE_include_directive : require
// Cloud shadows in the sky (light shafts; docs/clouds/aerial-perspective-and-light-shafts.md): the sky image came from the
// sky-view table, which knows no clouds. The aerial-perspective volume, marched with the clouds' Beer
// shadow map, holds the luminance of the sunlight that their shadows remove from the air between the
// camera and each depth (its alpha channels; sky/aerial_perspective_volume.comp). Each pixel takes it
// along its ray up to the volume's depth D, or to the ground where the ray meets it first, and scales
// the sky by
//     max(1 - removed / L_sky, 0)
// (grey: the removed single scattering is bluish, the sky too, and a scale keeps the sky's colour
// rather than subtracting one colour's excess). Shadows only remove light: the factor is at most 1,
// and exactly 1 where no cloud shades the ray. Beyond D (the clouds' 80 km march limit) and off the
// shadow map's square nothing changes. The clouds composite over this sky afterwards (their own air in
// front is shadowed in the volume's colour channels).
#include "atmosphere/aerial_perspective_sampling.glsl"
#include "atmosphere/atmosphere_sampling.glsl"
#include "common/camera.glsl"
#include "common/dispatch.glsl"
#include "common/geometry.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(set = 0, binding = 1) uniform sampler3D aerialVolume;  // linear, clamp
layout(std430, set = 0, binding = 2) buffer SkyFrame { vec4 pixels[]; } skyFrame;  // read, scaled, written
#define SKY_FRAME_BLOCK_BINDING 3
#include "sky/frame_block.glsl"
layout(push_constant) uniform Push {
  TileDispatch tiles;
  float maxDistance;  // the volume's D (m)
  float pad0, pad1, pad2;
} push;

void main() {
  uvec2 tiled;
  if (!tilePixel(push.tiles, tiled)) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  CameraParameters camera = cameraFromBlock(frame.camera_forward, frame.camera_right, frame.camera_up, frame.image);
  vec2 pixel = vec2(tiled) + 0.5;
  bool valid;
  vec3 dir = cameraRayDirection(camera, pixel, valid);
  if (!valid) return;
  vec3 origin = frame.camera_position.xyz;
  float r = max(length(origin), atmosphere.bottom_radius + 0.01);
  float mu = clamp(dot(origin, dir) / length(origin), -1.0, 1.0);
  float depth = push.maxDistance;
  if (rayIntersectsGround(r, mu, atmosphere.bottom_radius)) depth = min(depth, distanceToBottomAtmosphereBoundary(r, mu, atmosphere.bottom_radius));
  float nu = dot(dir, frame.sun_direction.xyz);
  float removed = aerialPerspectiveShadowedLuminance(aerialVolume, pixel, frame.image.xy, depth, push.maxDistance,
                                                     cornetteShanksPhase(atmosphere.mie_phase_g, nu));
  uint index = tiled.y * push.tiles.width + tiled.x;
  vec4 sky = skyFrame.pixels[index];
  float luminance = dot(sky.rgb, vec3(0.2126, 0.7152, 0.0722));
  float scale = luminance > 0.0 ? clamp(1.0 - removed / luminance, 0.0, 1.0) : 1.0;
  skyFrame.pixels[index] = vec4(sky.rgb * scale, sky.a);
}
