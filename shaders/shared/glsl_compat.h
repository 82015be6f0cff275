// The C++/GLSL common subset. Every header in shaders/shared/ is compiled twice: as GLSL by
// glslangValidator (for the kernels) and as C++ by the host (for unit tests and the CPU twin).
// Write shared code with these rules:
//   - float literals carry an `f` suffix, unsigned ones a `u` suffix (both languages accept them);
//   - functions are declared VKP_FN (inline in C++), output parameters use INOUT(T)/OUT(T);
//   - no swizzles, no constructors of structs (assign the fields), no `const` arrays;
//   - VKP_PRECISE on a variable keeps its arithmetic exactly as written (GLSL `precise`: no fma
//     contraction, no algebraic rewriting such as (a + b) - a -> b by the driver's compiler);
//   - GPU structs are made of vec4/uvec4/ivec4 members only, so std140/std430/texel layouts agree.
#ifndef VKP_GLSL_COMPAT_H
#define VKP_GLSL_COMPAT_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
namespace vkp::gpu {
using namespace glm;
using uint = std::uint32_t;
}  // namespace vkp::gpu
#define VKP_PRECISE
#define VKP_BEGIN namespace vkp::gpu {
#define VKP_END }
#define VKP_FN inline
#define INOUT(T) T&
#define OUT(T) T&
#else
#define VKP_PRECISE precise
#define VKP_BEGIN
#define VKP_END
#define VKP_FN
#define INOUT(T) inout T
#define OUT(T) out T
#endif

VKP_BEGIN
const float VKP_PI = 3.14159265358979323846f;
const float VKP_INV_PI = 0.31830988618379067154f;
const float VKP_TWO_PI = 6.28318530717958647692f;
const float VKP_FAR = 3.0e38f;  // "no hit yet" distance; finite so arithmetic on it stays finite
VKP_END

#endif
