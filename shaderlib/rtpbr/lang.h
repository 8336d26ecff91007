// rtpbr shader library: portability layer.
//
// The library is written once in a small common vocabulary that this header maps onto
//   - GLSL (glslang; the default when neither of the others is detected),
//   - HLSL (define RTPBR_HLSL before including: glslang's HLSL front end does not define
//     __HLSL_VERSION, DXC does, so either one selects HLSL),
//   - C++17 on GLM (detected by __cplusplus; everything lives in namespace rtpbr).
// In the spirit of AMD FidelityFX's ffx_core.h.
//
// Vocabulary used by every other rtpbr header:
//   types        float2 float3 float4 float3x3 uint
//   functions    lerp saturate rsqrt atan2 + the common GLSL/HLSL built-ins
//                (dot cross normalize length sqrt abs min max clamp exp log pow sin cos
//                 acos asin atan floor)
//   splats       RTPBR_F2(x) RTPBR_F3(x) RTPBR_F4(x): a vector with every component = x
//   matrices     rtpbr_mat3_rows(r0, r1, r2) builds a matrix from rows;
//                rtpbr_mul(M, v) is the matrix-vector product M v.
//   parameters   RTPBR_INOUT(T) name, RTPBR_OUT(T) name
//   constants    RTPBR_CONST float NAME = value;
//   functions    RTPBR_FN marks every library function (inline in C++)
// Literals carry the f suffix (1.0f): GLSL >= 1.30, HLSL and C++ all accept it, and it keeps
// C++ overloads on float.
#ifndef RTPBR_LANG_H
#define RTPBR_LANG_H

#if defined(__cplusplus)
#define RTPBR_CPP 1
#elif defined(RTPBR_HLSL) || defined(__HLSL_VERSION)
#ifndef RTPBR_HLSL
#define RTPBR_HLSL 1
#endif
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
#define RTPBR_F2(x) rtpbr::float2(x)
#define RTPBR_F3(x) rtpbr::float3(x)
#define RTPBR_F4(x) rtpbr::float4(x)

namespace rtpbr {
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

inline float atan2(float y, float x) { return std::atan2(y, x); }
inline float lerp(float a, float b, float t) { return a + (b - a) * t; }
inline float3 lerp(float3 a, float3 b, float t) { return a + (b - a) * t; }
inline float3 lerp(float3 a, float3 b, float3 t) { return a + (b - a) * t; }
inline float saturate(float x) { return glm::clamp(x, 0.0f, 1.0f); }
inline float3 saturate(float3 x) { return glm::clamp(x, float3(0.0f), float3(1.0f)); }
inline float rsqrt(float x) { return 1.0f / std::sqrt(x); }
inline float3x3 rtpbr_mat3_rows(float3 r0, float3 r1, float3 r2) { return glm::transpose(float3x3(r0, r1, r2)); }
inline float3 rtpbr_mul(const float3x3 &m, float3 v) { return m * v; }
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
#define rtpbr_mat3_rows(r0, r1, r2) float3x3(r0, r1, r2)
#define rtpbr_mul(m, v) mul(m, v)

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
#define float2 vec2
#define float3 vec3
#define float4 vec4
#define float3x3 mat3
#define lerp mix
#define atan2(y, x) atan(y, x)
#define rsqrt inversesqrt
#define rtpbr_mat3_rows(r0, r1, r2) transpose(mat3(r0, r1, r2))
#define rtpbr_mul(m, v) ((m) * (v))
float saturate(float x) { return clamp(x, 0.0f, 1.0f); }
vec3 saturate(vec3 x) { return clamp(x, vec3(0.0f), vec3(1.0f)); }

#endif

RTPBR_NAMESPACE_BEGIN

RTPBR_CONST float RTPBR_PI = 3.14159265358979323846f;
RTPBR_CONST float RTPBR_INV_PI = 0.31830988618379067154f;
RTPBR_CONST float RTPBR_TWO_PI = 6.28318530717958647692f;
RTPBR_CONST float RTPBR_SQRT_PI = 1.77245385090551602730f;
// The largest finite float; used to clamp instead of producing Inf.
RTPBR_CONST float RTPBR_FLT_MAX = 3.402823466e+38f;

// x * x, spelled once.
RTPBR_FN float sq(float x) { return x * x; }

// A NaN-safe max(x, 0): returns 0 for NaN input (max(NaN, 0) is implementation-defined on GPUs).
RTPBR_FN float rtpbr_pos(float x) { return x > 0.0f ? x : 0.0f; }

// sqrt that never sees a negative argument (rounding can make 1 - x*x slightly negative).
RTPBR_FN float safe_sqrt(float x) { return sqrt(rtpbr_pos(x)); }

RTPBR_NAMESPACE_END

#endif // RTPBR_LANG_H
