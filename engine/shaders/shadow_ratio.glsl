// The lighting passes' shadow hook (issue 17): light i's result is multiplied by
// shadow_factor(i), the denoised ratio of its shadowed to unshadowed estimate written by
// shadow_denoise.comp at this pixel (layer i), for i < frame.shadow_light_count; 1 otherwise.
// One invocation shades one pixel (gl_GlobalInvocationID.xy), as in both lighting passes.
layout(set = 0, binding = RTPBR_BINDING_LIGHT_SHADOW_RATIO) uniform sampler2DArray shadow_ratio;

float shadow_factor(uint light)
{
    if (light >= frame.shadow_light_count) return 1.0f;
    return texelFetch(shadow_ratio, ivec3(gl_GlobalInvocationID.xy, int(light)), 0).r;
}
