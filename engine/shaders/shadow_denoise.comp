#version 450
#extension GL_GOOGLE_include_directive : require
// Shadow pass, step 2 of 2 (issue 17): the spatial denoiser and the ratio. Per pixel and
// shadowed light, the shadowed and unshadowed estimates of shadow.comp are filtered
// separately over the (2 radius + 1)^2 window with the same weights (Heitz, Hill & McGuire
// 2018 denoise numerator and denominator apart), and the ratio S / U is written (1 where U
// is 0: the light does not reach the pixel, its LTC result is 0 too). A neighbour q of pixel
// p weighs
//   exp(-(|n_p . (x_q - x_p)| / (0.01 |x_p - camera|))^2) max(n_p . n_q, 0)^16
// (its distance to p's tangent plane relative to the viewing distance, and the agreement of
// the normals: a cross-bilateral filter guided by the G-buffer); background pixels weigh 0.
// radius 0: the pixel's own estimates.
#include "rtpbr_shared.h"
#include "shadow_common.glsl"

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), frame.size))) return;
    uint lightCount = min(frame.shadow_light_count, frame.light_count);
    float depth = texelFetch(gbuffer_depth, pixel, 0).r;
    if (depth >= 1.0f) {
        for (uint k = 0u; k < lightCount; ++k) imageStore(shadow_ratio_out, ivec3(pixel, int(k)), vec4(1.0f));
        return;
    }
    vec3 P = shadow_world_point(pixel, depth);
    vec3 N = normalize(texelFetch(gbuffer_normal, pixel, 0).xyz);
    float planeScale = 1.0f / (0.01f * length(frame.camera_position.xyz - P));
    int r = int(params.radius);
    ivec2 lo = max(pixel - r, ivec2(0)), hi = min(pixel + r, ivec2(frame.size) - 1);
    for (uint k = 0u; k < lightCount; ++k) {
        vec2 sum = vec2(0.0f);
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
                ivec2 q = ivec2(x, y);
                float dq = texelFetch(gbuffer_depth, q, 0).r;
                if (dq >= 1.0f) continue;
                float plane = dot(N, shadow_world_point(q, dq) - P) * planeScale;
                float nq = max(dot(N, normalize(texelFetch(gbuffer_normal, q, 0).xyz)), 0.0f);
                float n2 = nq * nq, n4 = n2 * n2, n8 = n4 * n4;
                float w = exp(-plane * plane) * n8 * n8;
                sum += w * vec2(imageLoad(shadow_estimates, ivec3(q, int(2u * k))).r,
                                imageLoad(shadow_estimates, ivec3(q, int(2u * k + 1u))).r);
            }
        imageStore(shadow_ratio_out, ivec3(pixel, int(k)), vec4(sum.y > 0.0f ? sum.x / sum.y : 1.0f));
    }
}
