#version 450
#extension GL_GOOGLE_include_directive : require
// Tone mapping: exposure (push constants: rtpbr_shader_tonemap), a display operator and optional
// sRGB encoding (specialization constants: RTPBR_SPEC_TONEMAP_*).
#include "rtpbr_shared.h"

// Fields declared once, in rtpbr_shared.h (RTPBR_TONEMAP_FIELDS; C: rtpbr_shader_tonemap).
layout(push_constant, std430) uniform Params {
    RTPBR_TONEMAP_FIELDS(RTPBR_SHARED_FIELD, Params)
} params;

layout(constant_id = RTPBR_SPEC_TONEMAP_OP) const uint tonemap_op = RTPBR_TONEMAP_OP_ACES;
layout(constant_id = RTPBR_SPEC_TONEMAP_ENCODE) const uint tonemap_encode = RTPBR_ENCODE_NONE;

layout(set = 0, binding = RTPBR_BINDING_TONEMAP_RADIANCE, rgba32f) readonly uniform image2D radiance;

layout(location = 0) out vec4 out_color;

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve".
vec3 aces_fit(vec3 x)
{
    return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// IEC 61966-2-1 sRGB transfer function.
vec3 srgb_encode(vec3 c)
{
    vec3 lo = 12.92 * c;
    vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
    return mix(hi, lo, lessThanEqual(c, vec3(0.0031308)));
}

void main()
{
    vec3 c = max(imageLoad(radiance, ivec2(gl_FragCoord.xy)).rgb * params.scale, vec3(0.0));
    if (tonemap_op == RTPBR_TONEMAP_OP_REINHARD) c = c / (1.0 + c);
    else if (tonemap_op == RTPBR_TONEMAP_OP_LINEAR) c = clamp(c, 0.0, 1.0);
    else c = aces_fit(c);
    if (tonemap_encode == RTPBR_ENCODE_SRGB) c = srgb_encode(c);
    out_color = vec4(c, 1.0);
}
