// The frame's uniform block (std140; mirrored by FrameBlock in sky/sky_renderer.cpp): the camera and
// the sun as the sky passes read them. Define SKY_FRAME_BLOCK_BINDING (the binding in the including
// shader's set 0) before including.
#ifndef FIRMAMENT_SKY_FRAME_BLOCK_GLSL
#define FIRMAMENT_SKY_FRAME_BLOCK_GLSL
#ifndef SKY_FRAME_BLOCK_BINDING
#error "define SKY_FRAME_BLOCK_BINDING before including sky/frame_block.glsl"
#endif

layout(std140, set = 0, binding = SKY_FRAME_BLOCK_BINDING) uniform FrameBlock {
  vec4 camera_position;  // planet-centred, m (the ground point's ENU axes)
  vec4 camera_forward;   // xyz; w = horizontal fov (rad)
  vec4 camera_right;     // xyz; w = yaw (rad)
  vec4 camera_up;        // xyz
  vec4 sun_direction;    // xyz, unit
  ivec4 image;           // width, height, projection, view march steps
  ivec4 options;         // x: 1 when the sky-view LUT is read (informational: SKY_FROM_LUT decides)
} frame;

#endif  // FIRMAMENT_SKY_FRAME_BLOCK_GLSL
