#version 450
#extension GL_GOOGLE_include_directive : require
// The example host's triangle shaded by the host itself with Firmament's air (lit.frag): the clip-space
// corners from the push constants, and each corner's position relative to the camera (m, east-north-up)
// from the camera's axes, for the fragment's distance and view-sun angle.
layout(push_constant) uniform Triangle {
  vec4 corners[3];
  vec4 colour;
} triangle;
#include "lit_block.glsl"
layout(location = 0) out vec3 position;

void main() {
  vec4 c = triangle.corners[gl_VertexIndex];
  gl_Position = c;
  float t = host.forward.w;  // tan(horizontal fov / 2)
  float aspect = host.atmosphere.image.y / host.atmosphere.image.x;
  position = c.x * t * host.right.xyz - c.y * t * aspect * host.up.xyz + c.w * host.forward.xyz;
}
