// The frame pair that temporal reprojection relates (docs/clouds.md "Temporal reprojection"), shared by
// clouds/temporal_neighbourhood.comp and clouds/temporal_resolve.comp (binding 5 of both).
#ifndef FIRMAMENT_TEMPORAL_BLOCK_GLSL
#define FIRMAMENT_TEMPORAL_BLOCK_GLSL

#include "common/camera.glsl"

layout(std140, set = 0, binding = 5) uniform TemporalBlock {
  vec4 camera_position;  // planet-centred, m
  vec4 camera_forward;   // w = fov
  vec4 camera_right;     // w = yaw
  vec4 camera_up;
  ivec4 image;           // width, height, projection
  vec4 previous_position;
  vec4 previous_forward;
  vec4 previous_right;
  vec4 previous_up;
  ivec4 previous_image;
  vec4 motion;           // xyz: P_previous = P + motion (m); w: the least clamp weight (the sun moved)
} frame;

// Where the point at `depth` along this frame's ray `dir` was seen in the previous frame (pixel units):
// the cloud field drifts with the wind, so the piece of cloud now at P = camera + depth dir was at
// P + motion then (motion = the change of the noise's wind offset, common/cloud_density.glsl), seen
// through the previous camera's cameraPixelOfDirection. `seen` false where no previous pixel looks that way.
vec2 previousPixel(float depth, vec3 dir, out bool seen) {
  vec3 toPoint = frame.camera_position.xyz + depth * dir + frame.motion.xyz - frame.previous_position.xyz;
  float distance = length(toPoint);
  CameraParameters previous = cameraFromBlock(frame.previous_forward, frame.previous_right, frame.previous_up, frame.previous_image);
  seen = false;
  return distance > 0.0 ? cameraPixelOfDirection(previous, toPoint / distance, seen) : vec2(-1.0);
}

#endif  // FIRMAMENT_TEMPORAL_BLOCK_GLSL
