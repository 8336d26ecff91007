#version 450
// Supersampling resolve: the box filter over each factor x factor block of the lighting
// pass's radiance (rtpbr_renderer_desc.supersample), the pixel filter the oracle uses too
// (uniform samples over the pixel's area). Alpha, 1 on surfaces and 0 on background, becomes
// the pixel's coverage.
#extension GL_GOOGLE_include_directive : require
#include "rtpbr_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = RTPBR_BINDING_RESOLVE_SOURCE, rgba32f) readonly uniform image2D source;
layout(set = 0, binding = RTPBR_BINDING_RESOLVE_TARGET, rgba32f) writeonly uniform image2D target;
// Fields declared once, in rtpbr_shared.h (RTPBR_RESOLVE_FIELDS; C: rtpbr_shader_resolve).
layout(push_constant, std430) uniform Resolve {
    RTPBR_RESOLVE_FIELDS(RTPBR_SHARED_FIELD, Resolve)
} params;

void main()
{
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size))) return;
    vec4 sum = vec4(0.0f);
    for (uint y = 0u; y < params.factor; ++y)
        for (uint x = 0u; x < params.factor; ++x)
            sum += imageLoad(source, ivec2(pixel * params.factor + uvec2(x, y)));
    imageStore(target, ivec2(pixel), sum / float(params.factor * params.factor));
}
