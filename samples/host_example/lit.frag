#version 450
#extension GL_GOOGLE_include_directive : require
// The example host shading its own triangle with Firmament's air: the triangle's colour seen through the
// aerial-perspective volume (firmament/atmosphere_lookup.glsl), the same L T + S Firmament's composite
// gives the host's pixels it draws before record().
layout(push_constant) uniform Triangle {
  vec4 corners[3];
  vec4 colour;
} triangle;
#include "lit_block.glsl"
// A host lights its surfaces with firmamentSunIlluminance(transmittanceTable, host.atmosphere, height).
layout(set = 0, binding = 1) uniform sampler2D transmittanceTable;
layout(set = 0, binding = 2) uniform sampler3D aerialVolume;
layout(location = 0) in vec3 position;
layout(location = 0) out vec4 colour;

void main() {
  float d = length(position);
  float nu = dot(position / d, host.atmosphere.sun.xyz);
  vec3 seen = firmamentApplyAerialPerspective(aerialVolume, host.atmosphere, gl_FragCoord.xy, d, nu, triangle.colour.rgb);
  colour = vec4(seen, 1.0);
}
