#version 460
// Test kernel: values[i] = i * scale + offset for i < count (tests/gpu/test_runtime.cpp).
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Values { float values[]; };
layout(push_constant) uniform Push {
  float scale;
  float offset;
  uint count;
} push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < push.count) values[i] = float(i) * push.scale + push.offset;
}
