// What every header compiled both as GLSL (glslc) and as C++ (with GLM) needs: the C++ side's
// GLSL vocabulary in namespace penumbra::gpu, and the parameter markers. Rules for shared code:
// float literals carry an f, conversions are explicit, `OUT(T)` and `OUT_ARRAY(T, name, n)` mark
// out parameters, `INOUT(T)` in-out ones, `IN(T)` passes a struct (by value in GLSL, by reference
// in C++). Each shared header wraps its functions in PENUMBRA_GPU_BEGIN / PENUMBRA_GPU_END and
// marks them SHARED (inline in C++).
// clang-format off
#ifndef PENUMBRA_SHARED_PRELUDE_H
#define PENUMBRA_SHARED_PRELUDE_H

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <glm/integer.hpp>

#include <cstddef>
#include <cstdint>
#include <iterator>
namespace penumbra::gpu {
using glm::ivec2;
using glm::ivec4;
using glm::mat4;
using glm::uvec2;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = uint32_t;
using glm::abs;
using glm::asin;
using glm::ceil;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::findMSB;
using glm::floor;
using glm::fract;
using glm::length;
using glm::log;
using glm::log2;
using glm::max;
using glm::min;
using glm::mix;
using glm::sin;
using glm::sqrt;
} // namespace penumbra::gpu
#define PENUMBRA_GPU_BEGIN namespace penumbra::gpu {
#define PENUMBRA_GPU_END }
#define OUT(T) T&
#define INOUT(T) T&
#define OUT_ARRAY(T, name, n) T (&name)[n]
#define IN(T) const T&
#define SHARED inline
#define PRECISE
#else
#define PENUMBRA_GPU_BEGIN
#define PENUMBRA_GPU_END
#define OUT(T) out T
#define INOUT(T) inout T
#define OUT_ARRAY(T, name, n) out T name[n]
#define IN(T) T
#define SHARED
// No contraction into fused multiply-adds: with only correctly rounded adds and multiplies
// (Vulkan's precision rules) every device computes what the CPU does, bit for bit. (The C++
// side is built for x86-64 without FMA, so it contracts nothing.)
#define PRECISE precise
#endif

#endif
// clang-format on
