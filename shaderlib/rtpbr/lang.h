// rtpbr shader library: portability layer.
//
// The library is written once in a small common vocabulary that this header maps onto
//   - GLSL (glslang),
//   - HLSL (glslang's HLSL front end, DXC, Slang),
//   - C++17 on GLM (everything lives in namespace rtpbr).
// The host may say which by defining RTPBR_GLSL, RTPBR_HLSL or RTPBR_CPP (one of them) before
// the first include; otherwise it is detected: C++ by __cplusplus, HLSL by __HLSL_VERSION (DXC
// defines it, glslang's HLSL front end does not: define RTPBR_HLSL there), else GLSL.
// In the spirit of AMD FidelityFX's ffx_core.h.
//
// In GLSL and HLSL every name the library defines lands in the including shader's global
// scope, so every helper carries the rtpbr_ / RTPBR_ prefix and a host keeps its own float3,
// lerp, saturate, ... (the complete list of global names: shaderlib/names.txt).
// Vocabulary used by every other rtpbr header:
//   types        rtpbr_float2 rtpbr_float3 rtpbr_float4 rtpbr_float3x3, uint
//   functions    rtpbr_lerp rtpbr_saturate rtpbr_rsqrt rtpbr_atan2 rtpbr_sq rtpbr_safe_sqrt
//                rtpbr_pos + the common GLSL/HLSL built-ins (dot cross normalize length sqrt
//                abs min max clamp exp log pow sin cos acos asin atan floor)
//   splats       RTPBR_F2(x) RTPBR_F3(x) RTPBR_F4(x): a vector with every component = x
//   matrices     rtpbr_mat3_rows(r0, r1, r2) builds a matrix from rows;
//                rtpbr_mul(M, v) is the matrix-vector product M v;
//                rtpbr_mat3_at(M, row, col) reads one element (constant indices).
//   parameters   RTPBR_INOUT(T) name, RTPBR_OUT(T) name; RTPBR_UNUSED(name) marks a parameter
//                a flag set leaves unused (C++ warns; nothing in GLSL and HLSL)
//   constants    RTPBR_CONST float NAME = value;
//   functions    RTPBR_FN marks every library function (inline in C++)
// In C++ the unprefixed names (rtpbr::float3, rtpbr::lerp, rtpbr::saturate, rtpbr::sq, ...)
// stay as aliases: namespace rtpbr keeps them out of the host's way.
// Literals carry the f suffix (1.0f): GLSL >= 1.30, HLSL and C++ all accept it, and it keeps
// C++ overloads on float.
#ifndef RTPBR_LANG_H
#define RTPBR_LANG_H

#if defined(RTPBR_GLSL) || defined(RTPBR_HLSL) || defined(RTPBR_CPP)
#if (defined(RTPBR_GLSL) && defined(RTPBR_HLSL)) || (defined(RTPBR_GLSL) && defined(RTPBR_CPP)) || \
    (defined(RTPBR_HLSL) && defined(RTPBR_CPP))
#error "rtpbr/lang.h: define only one of RTPBR_GLSL, RTPBR_HLSL, RTPBR_CPP"
#endif
#if defined(RTPBR_CPP) && !defined(__cplusplus)
#error "rtpbr/lang.h: RTPBR_CPP needs a C++ compiler"
#endif
#elif defined(__cplusplus)
#define RTPBR_CPP 1
#elif defined(__HLSL_VERSION)
#define RTPBR_HLSL 1
#else
#define RTPBR_GLSL 1
#endif

// ---------------------------------------------------------------------------------------------
#if defined(RTPBR_CPP)

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

// Several model variants can live in one C++ program: compile each translation unit with its
// own RTPBR_CPP_VARIANT (an identifier) so that the inline functions of different flag
// settings get different mangled names (otherwise the linker would keep one of them).
#ifndef RTPBR_CPP_VARIANT
#define RTPBR_CPP_VARIANT variant_default
#endif
#define RTPBR_NAMESPACE_BEGIN namespace rtpbr { inline namespace RTPBR_CPP_VARIANT {
#define RTPBR_NAMESPACE_END } }
#define RTPBR_FN inline
#define RTPBR_CONST static constexpr
#define RTPBR_INOUT(T) T &
#define RTPBR_OUT(T) T &
#define RTPBR_F2(x) rtpbr::rtpbr_float2(x)
#define RTPBR_F3(x) rtpbr::rtpbr_float3(x)
#define RTPBR_F4(x) rtpbr::rtpbr_float4(x)

namespace rtpbr {
using rtpbr_float2 = glm::vec2;
using rtpbr_float3 = glm::vec3;
using rtpbr_float4 = glm::vec4;
using rtpbr_float3x3 = glm::mat3;
using float2 = glm::vec2;
using float3 = glm::vec3;
using float4 = glm::vec4;
using float3x3 = glm::mat3;
using uint = std::uint32_t;

using glm::abs;
using glm::acos;
using glm::asin;
using glm::atan;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::floor;
using glm::length;
using glm::log;
using glm::max;
using glm::min;
using glm::normalize;
using glm::pow;
using glm::sin;
using glm::sqrt;
using std::isinf;
using std::isnan;

inline float rtpbr_atan2(float y, float x) { return std::atan2(y, x); }
inline float rtpbr_lerp(float a, float b, float t) { return a + (b - a) * t; }
inline float3 rtpbr_lerp(float3 a, float3 b, float t) { return a + (b - a) * t; }
inline float3 rtpbr_lerp(float3 a, float3 b, float3 t) { return a + (b - a) * t; }
inline float rtpbr_saturate(float x) { return glm::clamp(x, 0.0f, 1.0f); }
inline float3 rtpbr_saturate(float3 x) { return glm::clamp(x, float3(0.0f), float3(1.0f)); }
inline float rtpbr_rsqrt(float x) { return 1.0f / std::sqrt(x); }
// The unprefixed names of C++ users' code (namespace rtpbr keeps them private).
inline float atan2(float y, float x) { return rtpbr_atan2(y, x); }
inline float lerp(float a, float b, float t) { return rtpbr_lerp(a, b, t); }
inline float3 lerp(float3 a, float3 b, float t) { return rtpbr_lerp(a, b, t); }
inline float3 lerp(float3 a, float3 b, float3 t) { return rtpbr_lerp(a, b, t); }
inline float saturate(float x) { return rtpbr_saturate(x); }
inline float3 saturate(float3 x) { return rtpbr_saturate(x); }
inline float rsqrt(float x) { return rtpbr_rsqrt(x); }
inline float3x3 rtpbr_mat3_rows(float3 r0, float3 r1, float3 r2) { return glm::transpose(float3x3(r0, r1, r2)); }
inline float3 rtpbr_mul(const float3x3 &m, float3 v) { return m * v; }
inline float rtpbr_mat3_at(const float3x3 &m, int row, int col) { return m[col][row]; }
#define RTPBR_UNUSED(x) static_cast<void>(x)
} // namespace rtpbr

// ---------------------------------------------------------------------------------------------
#elif defined(RTPBR_HLSL)

#define RTPBR_NAMESPACE_BEGIN
#define RTPBR_NAMESPACE_END
#define RTPBR_FN
#define RTPBR_CONST static const
#define RTPBR_INOUT(T) inout T
#define RTPBR_OUT(T) out T
#define RTPBR_F2(x) ((float2)(x))
#define RTPBR_F3(x) ((float3)(x))
#define RTPBR_F4(x) ((float4)(x))
#define rtpbr_float2 float2
#define rtpbr_float3 float3
#define rtpbr_float4 float4
#define rtpbr_float3x3 float3x3
#define rtpbr_lerp lerp
#define rtpbr_saturate saturate
#define rtpbr_rsqrt rsqrt
#define rtpbr_atan2 atan2
#define rtpbr_mat3_rows(r0, r1, r2) float3x3(r0, r1, r2)
#define rtpbr_mul(m, v) mul(m, v)
#define rtpbr_mat3_at(m, row, col) (m)[row][col]
#define RTPBR_UNUSED(x)

// ---------------------------------------------------------------------------------------------
#else // GLSL

#define RTPBR_NAMESPACE_BEGIN
#define RTPBR_NAMESPACE_END
#define RTPBR_FN
#define RTPBR_CONST const
#define RTPBR_INOUT(T) inout T
#define RTPBR_OUT(T) out T
#define RTPBR_F2(x) vec2(x)
#define RTPBR_F3(x) vec3(x)
#define RTPBR_F4(x) vec4(x)
#define rtpbr_float2 vec2
#define rtpbr_float3 vec3
#define rtpbr_float4 vec4
#define rtpbr_float3x3 mat3
#define rtpbr_lerp mix
#define rtpbr_atan2(y, x) atan(y, x)
#define rtpbr_rsqrt inversesqrt
#define rtpbr_mat3_rows(r0, r1, r2) transpose(mat3(r0, r1, r2))
#define rtpbr_mul(m, v) ((m) * (v))
#define rtpbr_mat3_at(m, row, col) (m)[col][row]
#define RTPBR_UNUSED(x)
float rtpbr_saturate(float x) { return clamp(x, 0.0f, 1.0f); }
vec3 rtpbr_saturate(vec3 x) { return clamp(x, vec3(0.0f), vec3(1.0f)); }

#endif

RTPBR_NAMESPACE_BEGIN

RTPBR_CONST float RTPBR_PI = 3.14159265358979323846f;
RTPBR_CONST float RTPBR_INV_PI = 0.31830988618379067154f;
RTPBR_CONST float RTPBR_TWO_PI = 6.28318530717958647692f;
RTPBR_CONST float RTPBR_SQRT_PI = 1.77245385090551602730f;
// The largest finite float; used to clamp instead of producing Inf.
RTPBR_CONST float RTPBR_FLT_MAX = 3.402823466e+38f;

// x * x, spelled once.
RTPBR_FN float rtpbr_sq(float x) { return x * x; }

// A NaN-safe max(x, 0): returns 0 for NaN input (max(NaN, 0) is implementation-defined on GPUs).
RTPBR_FN float rtpbr_pos(float x) { return x > 0.0f ? x : 0.0f; }

// sqrt that never sees a negative argument (rounding can make 1 - x*x slightly negative).
RTPBR_FN float rtpbr_safe_sqrt(float x) { return sqrt(rtpbr_pos(x)); }

#if defined(RTPBR_CPP)
RTPBR_FN float sq(float x) { return rtpbr_sq(x); }
RTPBR_FN float safe_sqrt(float x) { return rtpbr_safe_sqrt(x); }
#endif

RTPBR_NAMESPACE_END


#endif // RTPBR_LANG_H
