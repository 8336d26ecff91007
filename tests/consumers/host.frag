#version 450
#extension GL_GOOGLE_include_directive : require
// A host's GLSL shader that includes the whole installed shader library and keeps its own
// helpers under the names engines usually give them (float3, lerp, saturate, ...): the library
// defines none of them in GLSL (issue 15). Compiled by tests/consumers against the installed
// headers:  glslangValidator -V -I<prefix>/include host.frag
// The host's helpers before the library, as macros ...
#define saturate(x) clamp((x), 0.0, 1.0)
#define lerp(a, b, t) mix((a), (b), (t))
#define rsqrt(x) inversesqrt(x)
#define RTPBR_GLSL 1 // the language said explicitly (detection would pick GLSL too)
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/ndf.h"
#include "rtpbr/smith.h"
#include "rtpbr/microfacet.h"
#include "rtpbr/sampling.h"
#include "rtpbr/kulla_conty.h"
#include "rtpbr/ltc.h"
#include "rtpbr/ltc_anisotropy.h"
#include "rtpbr/ltc_clipless.h"
#include "rtpbr/ltc_corrections.h"
#include "rtpbr/ltc_shapes.h"
#include "rtpbr/ltc_lines.h"
#include "rtpbr/ltc_textured.h"
#include "rtpbr/disney.h"
#include "rtpbr/sheen.h"
#include "rtpbr/material.h"
#include "rtpbr/gbuffer.h"

// ... and after it, as types and functions of its own.
struct float2 { float x, y; };
struct float3 { float x, y, z; };
struct float4 { float x, y, z, w; };
struct float3x3 { float3 c0, c1, c2; };
float sq(float3 v) { return v.x * v.x + v.y * v.y + v.z * v.z; }
float safe_sqrt(float x) { return sqrt(max(x, 0.0)); }
float atan2(float y, float x) { return atan(y, x); }

layout(location = 0) in vec3 inNormal;
layout(location = 0) out vec4 outColor;

void main()
{
    float3 v = float3(inNormal.x, inNormal.y, inNormal.z);
    float NoH = saturate(inNormal.z);
    float alpha = lerp(0.1, 0.5, 0.5);
    float d = D_GGX(NoH, alpha) * V_SmithGGXCorrelated(NoH, NoH, alpha);
    outColor = vec4(d, safe_sqrt(sq(v)), atan2(v.y, v.x), rsqrt(2.0));
}
