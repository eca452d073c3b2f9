#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: evaluates common/geometry.glsl in float for tests/gpu/test_shared_functions.cpp, which
// runs the same header in double on the CPU. One row of 8 floats per (r, mu) input.
#include "common/geometry.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { vec2 inputs[]; };  // (r, mu)
layout(std430, binding = 1) writeonly buffer Outputs { float outputs[]; };
layout(push_constant) uniform Push {
  float bottomRadius;
  float topRadius;
  float shellInner;
  float shellOuter;
  uint count;
} push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  float r = inputs[i].x;
  float mu = inputs[i].y;
  bool ground = rayIntersectsGround(r, mu, push.bottomRadius);
  float enter;
  float exit;
  bool shell = rayShellSegment(r, mu, push.shellInner, push.shellOuter, enter, exit);
  uint o = 8u * i;
  outputs[o + 0u] = distanceToTopAtmosphereBoundary(r, mu, push.topRadius);
  outputs[o + 1u] = distanceToBottomAtmosphereBoundary(r, mu, push.bottomRadius);
  outputs[o + 2u] = ground ? 1.0 : 0.0;
  outputs[o + 3u] = distanceToNearestAtmosphereBoundary(r, mu, push.bottomRadius, push.topRadius, ground);
  outputs[o + 4u] = shell ? 1.0 : 0.0;
  outputs[o + 5u] = enter;
  outputs[o + 6u] = exit;
  outputs[o + 7u] = sphereDiscriminant(r, mu, push.bottomRadius);
}
