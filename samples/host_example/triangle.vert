#version 450
// The example host's triangle: three clip-space corners from the push constants.
layout(push_constant) uniform Triangle {
  vec4 corners[3];
  vec4 colour;
} triangle;

void main() { gl_Position = triangle.corners[gl_VertexIndex]; }
