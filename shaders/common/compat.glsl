// compat.glsl: lets a physics header compile both as GLSL (glslang -> SPIR-V, single precision) and
// as C++ (GLM, double precision), so the GPU fast path, the CPU reference and the tests call the
// very same functions. Rules for shared headers (docs/shared-physics.md):
//   - wrap the body in SHARED_BEGIN / SHARED_END (a C++ namespace, nothing in GLSL);
//   - scalars are `Real`; vectors vec2/vec3/vec4 (double in C++); write every literal with a point
//     (2.0, not 2), since C++ templates do not convert int to double;
//   - prefix every function with SHARED_INLINE (`inline` in C++: headers are included by many
//     translation units);
//   - out/inout parameters through OUT(T) / INOUT(T); no swizzles (v.xy) and no struct constructors:
//     build vectors with vec2(v.x, v.y) and fill structs field by field;
//   - only GLSL built-ins that GLM also has (exp, sqrt, max, min, clamp, mix, dot, cross, length,
//     normalize, abs, pow, floor, fract, step, smoothstep, sign, sin, cos, acos, atan);
//   - where GLSL leaves a built-in undefined, C++ and lavapipe still give a number, but a GPU may
//     not: pow(x, y) with x < 0, or x = 0 and y <= 0 (NaN on NVIDIA: exp2(y log2 x)), acos/asin
//     outside [-1, 1], sqrt of a negative. Guard or clamp such arguments (docs/gpu.md, "Checking on
//     a real GPU").
#ifndef FIRMAMENT_COMPAT_GLSL
#define FIRMAMENT_COMPAT_GLSL

#ifdef __cplusplus
#include <glm/glm.hpp>

namespace firmament::shared {
using Real = double;
using vec2 = glm::dvec2;
using vec3 = glm::dvec3;
using vec4 = glm::dvec4;
using ivec2 = glm::ivec2;
using ivec3 = glm::ivec3;
using uvec2 = glm::uvec2;
using uvec3 = glm::uvec3;
using uint = unsigned int;
using glm::abs; using glm::acos; using glm::atan; using glm::clamp; using glm::cos; using glm::cross;
using glm::dot; using glm::exp; using glm::floor; using glm::fract; using glm::length; using glm::log;
using glm::max; using glm::min; using glm::mix; using glm::normalize; using glm::pow; using glm::sign;
using glm::sin; using glm::smoothstep; using glm::sqrt; using glm::step; using glm::tan; using glm::asin;
using glm::exp2; using glm::log2; using glm::distance; using glm::reflect;
}  // namespace firmament::shared

#define SHARED_INLINE inline
#define SHARED_BEGIN namespace firmament::shared {
#define SHARED_END }
#define OUT(T) T&
#define INOUT(T) T&
#else
#define Real float
#define SHARED_INLINE
#define SHARED_BEGIN
#define SHARED_END
#define OUT(T) out T
#define INOUT(T) inout T
#endif

SHARED_BEGIN
const Real kPi = 3.14159265358979323846;
SHARED_END

#endif  // FIRMAMENT_COMPAT_GLSL
