// The example host's uniform block for lit.vert and lit.frag: Firmament's lookup parameters
// (firmament::AtmosphereLookupParameters) and the camera's axes (firmament::CameraFrame).
#include "firmament/atmosphere_lookup.glsl"
layout(std140, set = 0, binding = 0) uniform Host {
  FirmamentAtmosphere atmosphere;
  vec4 forward;  // w: tan(horizontal fov / 2)
  vec4 right;
  vec4 up;
} host;
