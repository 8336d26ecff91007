// The lighting passes' shadow hook (issue 17): light i's result is multiplied by
// shadow_factor(i), the denoised ratio of its shadowed to unshadowed estimate written by
// shadow_denoise.comp at this pixel (layer i), for i < frame.shadow_light_count; 1 otherwise.
// `pixel`: the shading pixel (of the lighting pass's target).
layout(set = 0, binding = RTPBR_BINDING_LIGHT_SHADOW_RATIO) uniform sampler2DArray shadow_ratio;

float shadow_factor(uint light, ivec2 pixel)
{
    if (light >= frame.shadow_light_count) return 1.0f;
    return texelFetch(shadow_ratio, ivec3(pixel, int(light)), 0).r;
}
