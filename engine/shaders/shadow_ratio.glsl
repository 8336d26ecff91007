// The lighting passes' shadow hook (issue 17): light i's result is multiplied by the denoised
// ratio of its shadowed to unshadowed estimate written by shadow_denoise.comp at this pixel,
// where light i holds one of the shadow slots of the pixel's tile (tile_masks at
// RTPBR_TILE_SHADOW_SLOTS, chosen by shadow_select.comp: slot k, layer k); by 1 otherwise, and
// for every light when the frame has no shadows (shadow_light_count 0). `pixel`: the shading
// pixel (of the lighting pass's target). Include after lighting_common.glsl (tile_masks).
layout(set = 0, binding = RTPBR_BINDING_LIGHT_SHADOW_RATIO) uniform sampler2DArray shadow_ratio;

#if RTPBR_SHADER_MAX_SHADOWED_LIGHTS != 8
#error "a tile's shadow slots are two uvec4"
#endif

// Tile `tile`'s shadow slots: light indices, increasing, RTPBR_TILE_NO_LIGHT where empty.
void shadow_slots(uint tile, out uvec4 lo, out uvec4 hi)
{
    uint base = tile * uint(RTPBR_TILE_MASK_STRIDE) + uint(RTPBR_TILE_SHADOW_SLOTS);
    lo = uvec4(tile_masks[base], tile_masks[base + 1u], tile_masks[base + 2u], tile_masks[base + 3u]);
    hi = uvec4(tile_masks[base + 4u], tile_masks[base + 5u], tile_masks[base + 6u], tile_masks[base + 7u]);
}

// The shadow factor of `light` at `pixel` of a tile whose slots are lo, hi (shadow_slots: the
// lighting pass loads them once per pixel; a tile's are uniform over its workgroup). No loop:
// it would count against lavapipe's loop budget in every light's evaluation (shadow.c).
float shadow_factor_slots(uint light, ivec2 pixel, uvec4 lo, uvec4 hi)
{
    if (frame.shadow_light_count == 0u) return 1.0f;
    int layer = lo.x == light ? 0 : lo.y == light ? 1 : lo.z == light ? 2 : lo.w == light ? 3 : -1;
    layer = hi.x == light ? 4 : hi.y == light ? 5 : hi.z == light ? 6 : hi.w == light ? 7 : layer;
    return layer < 0 ? 1.0f : texelFetch(shadow_ratio, ivec3(pixel, layer), 0).r;
}

// The same for a pixel whose tile is not at hand (the Monte Carlo pass).
float shadow_factor(uint light, ivec2 pixel)
{
    if (frame.shadow_light_count == 0u) return 1.0f;
    uvec2 tileXY = uvec2(pixel) / uint(RTPBR_TILE_SIZE);
    uvec4 lo, hi;
    shadow_slots(tileXY.y * frame.tiles_x + tileXY.x, lo, hi);
    return shadow_factor_slots(light, pixel, lo, hi);
}
