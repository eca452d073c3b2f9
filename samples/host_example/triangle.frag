#version 450
// The example host's triangle: one colour, linear Rec.709 cd/m^2 (what the host's own lighting gave).
layout(push_constant) uniform Triangle {
  vec4 corners[3];
  vec4 colour;
} triangle;
layout(location = 0) out vec4 colour;

void main() { colour = triangle.colour; }
