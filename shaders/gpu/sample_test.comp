#version 460
// Test kernel: reads a 2D and a 3D texture through samplers at the given coordinates.
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2D lut2D;
layout(binding = 1) uniform sampler3D lut3D;
layout(std430, binding = 2) readonly buffer Coordinates { vec4 coordinates[]; };  // 2 per sample: 2D, 3D
layout(std430, binding = 3) writeonly buffer Results { vec4 results[]; };         // 2 per coordinate
layout(push_constant) uniform Push { uint count; } push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  results[2 * i] = textureLod(lut2D, coordinates[2 * i].xy, 0.0);
  results[2 * i + 1] = textureLod(lut3D, coordinates[2 * i + 1].xyz, 0.0);
}
