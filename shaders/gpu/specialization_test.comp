#version 460
// Test kernel: values[i] = kScale * i + kOffset for i < count, kScale and kOffset specialization
// constants (tests/gpu/test_runtime.cpp); kNegate, when true, negates the result.
layout(local_size_x = 64) in;
layout(constant_id = 0) const float kScale = 1.0;
layout(constant_id = 1) const int kOffset = 0;
layout(constant_id = 2) const bool kNegate = false;
layout(std430, binding = 0) buffer Values { float values[]; };
layout(push_constant) uniform Push {
  uint count;
} push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  float v = float(i) * kScale + float(kOffset);
  values[i] = kNegate ? -v : v;
}
