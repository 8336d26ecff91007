#version 450
#extension GL_GOOGLE_include_directive : require
// Lighting pass: one workgroup per RTPBR_TILE_SIZE^2 screen tile; reads the G-buffer and
// writes linear radiance. Model flags (RTPBR_NDF, RTPBR_MULTISCATTER) come from the build,
// one SPIR-V variant per combination. All BRDF and polygon-integration math comes from the
// shader library (shaderlib/rtpbr); this file only fetches, loops and sums.
#include "rtpbr_shared.h"
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_LIGHT_FRAME
#include "frame.glsl"

layout(local_size_x = RTPBR_TILE_SIZE, local_size_y = RTPBR_TILE_SIZE) in;

// C mirror: rtpbr_shader_light.
struct Light {
    vec4 vertices[RTPBR_SHADER_MAX_POLYGON_VERTICES];
    vec4 emission; // rgb radiance, w: two-sided
    vec4 plane;    // unit normal, -dot(normal, vertex 0)
    uint vertex_count;
    uint pad0, pad1, pad2;
};
layout(set = 0, binding = RTPBR_BINDING_LIGHT_LIGHTS, std430) readonly buffer Lights {
    Light lights[];
};

layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER0) uniform sampler2D gbuffer0;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER1) uniform sampler2D gbuffer1;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER2) uniform sampler2D gbuffer2;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_GBUFFER3) uniform sampler2D gbuffer3;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_DEPTH) uniform sampler2D gbuffer_depth;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_RADIANCE, rgba32f) writeonly uniform image2D radiance;

layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_1) uniform sampler2D lut_ltc_ggx_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_2) uniform sampler2D lut_ltc_ggx_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_1) uniform sampler2D lut_ltc_beckmann_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_2) uniform sampler2D lut_ltc_beckmann_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_E) uniform sampler2D lut_kc_e;
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_EAVG) uniform sampler2D lut_kc_eavg;

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), frame.size))) return;

    float depth = texelFetch(gbuffer_depth, pixel, 0).r;
    if (depth >= 1.0) {
        imageStore(radiance, pixel, vec4(frame.background.rgb, 0.0));
        return;
    }
    vec4 g2 = texelFetch(gbuffer2, pixel, 0);

    // Emissive surfaces. Polygonal lights are summed here once shaderlib/rtpbr/ltc.h exists;
    // until then lights contribute nothing but their own emissive geometry.
    vec3 result = g2.rgb;

    imageStore(radiance, pixel, vec4(result, 1.0));
}
