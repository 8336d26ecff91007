// Shared by the shadow passes (shadow.comp, shadow_denoise.comp): descriptor set, push
// constants and the G-buffer's surface point. Include after rtpbr_shared.h.
#define RTPBR_FRAME_BINDING RTPBR_BINDING_SHADOW_FRAME
#include "frame.glsl"

layout(local_size_x = RTPBR_SHADOW_GROUP_SIZE, local_size_y = RTPBR_SHADOW_GROUP_SIZE) in;

// Fields declared once, in rtpbr_shared.h (RTPBR_SHADOW_FIELDS; C: rtpbr_shader_shadow).
layout(push_constant, std430) uniform ShadowParams {
    RTPBR_SHADOW_FIELDS(RTPBR_SHARED_FIELD, ShadowParams)
} params;

layout(set = 0, binding = RTPBR_BINDING_SHADOW_DEPTH) uniform sampler2D gbuffer_depth;
layout(set = 0, binding = RTPBR_BINDING_SHADOW_NORMAL) uniform sampler2D gbuffer_normal;
layout(set = 0, binding = RTPBR_BINDING_SHADOW_ESTIMATES, r32f) uniform image2DArray shadow_estimates;
layout(set = 0, binding = RTPBR_BINDING_SHADOW_RATIO, r32f) writeonly uniform image2DArray shadow_ratio_out;

// The world-space point of a pixel at a depth (as lighting.comp).
vec3 shadow_world_point(ivec2 pixel, float depth)
{
    vec2 ndc = (vec2(pixel) + 0.5f) / vec2(frame.size) * 2.0f - 1.0f;
    vec4 world = frame.inv_view_proj * vec4(ndc, depth, 1.0f);
    return world.xyz / world.w;
}

// A shadow ray's origin: the pixel's point P lifted along its normal N by the world distance of
// 4 depth ulps (as lighting_common.glsl's lifted_point) plus a small fraction of the viewing
// distance: no self-shadowing. shadow.comp traces from it; shadow_select.comp bounds a tile's.
vec3 shadow_ray_origin(ivec2 pixel, float depth, vec3 P, vec3 N)
{
    vec2 ndc = (vec2(pixel) + 0.5f) / vec2(frame.size) * 2.0f - 1.0f;
    vec4 further = frame.inv_view_proj * vec4(ndc, min(depth * (1.0f + 4.0f / 16777216.0f), 1.0f), 1.0f);
    float lift = length(further.xyz / further.w - P) + 1e-4f * length(frame.camera_position.xyz - P);
    return P + N * lift;
}

// The lighting pass's tile masks, whose shadow slots (RTPBR_TILE_SHADOW_SLOTS) shadow_select.comp
// writes and the other two passes read.
layout(set = 0, binding = RTPBR_BINDING_SHADOW_TILES, std430) buffer ShadowTiles {
    uint shadow_tiles[];
};

// The first word of the shadow slots of an 8 x 8 group's tile: a group's
// RTPBR_SHADOW_GROUP_SIZE^2 pixels lie in one tile, and an index the compiler sees is uniform
// keeps the light's record in scalar registers (from the pixel's tile: 96 -> 128 VGPRs on navi21).
#if RTPBR_TILE_SIZE % RTPBR_SHADOW_GROUP_SIZE != 0
#error "a shadow workgroup must lie in one lighting tile"
#endif
uint shadow_group_slot_base(uvec2 group)
{
    uvec2 tileXY = group / uint(RTPBR_TILE_SIZE / RTPBR_SHADOW_GROUP_SIZE);
    return (tileXY.y * frame.tiles_x + tileXY.x) * uint(RTPBR_TILE_MASK_STRIDE) + uint(RTPBR_TILE_SHADOW_SLOTS);
}

// The work lists of the trace and the denoiser (rtpbr_shared.h, RTPBR_SHADOW_WORK_HEADER).
layout(set = 0, binding = RTPBR_BINDING_SHADOW_WORK, std430) buffer ShadowWork {
    uint shadow_work[];
};

// The image's 8 x 8 groups (x, y), and the first word of the denoiser's entries.
uvec2 shadow_groups()
{
    return (frame.size + uint(RTPBR_SHADOW_GROUP_SIZE) - 1u) / uint(RTPBR_SHADOW_GROUP_SIZE);
}
uint shadow_denoise_entries()
{
    uvec2 groups = shadow_groups();
    return uint(RTPBR_SHADOW_WORK_HEADER) + groups.x * groups.y * uint(RTPBR_SHADER_MAX_SHADOWED_LIGHTS);
}

#if RTPBR_SHADER_MAX_SHADOWED_LIGHTS != 8
#error "a tile's slots are two uvec4"
#endif

// The shadow slots of tile t (tile coordinates) and its clear slots (RTPBR_TILE_SHADOW_CLEAR);
// outside the image's tiles, no light and every slot clear (an empty slot of the pixel's own
// tile, RTPBR_TILE_NO_LIGHT, finds itself in such a tile's slots: clear, as it is in its own).
uint shadow_tile_slots(ivec2 t, ivec2 tiles, out uvec4 slots[2])
{
    slots[0] = slots[1] = uvec4(RTPBR_TILE_NO_LIGHT);
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, tiles))) return ~0u;
    uint tileBase = (uint(t.y) * frame.tiles_x + uint(t.x)) * uint(RTPBR_TILE_MASK_STRIDE);
    uint base = tileBase + uint(RTPBR_TILE_SHADOW_SLOTS);
    slots[0] = uvec4(shadow_tiles[base], shadow_tiles[base + 1u], shadow_tiles[base + 2u], shadow_tiles[base + 3u]);
    slots[1] = uvec4(shadow_tiles[base + 4u], shadow_tiles[base + 5u], shadow_tiles[base + 6u], shadow_tiles[base + 7u]);
    return shadow_tiles[tileBase + uint(RTPBR_TILE_SHADOW_CLEAR)];
}

// Is the light of a tile's slot (-1: the tile does not shadow it) clear there, or absent?
bool shadow_slot_clear(int slot, uint clear)
{
    return slot < 0 || ((clear >> uint(slot)) & 1u) != 0u;
}

// The slot holding `light` among slots, or -1 (no loop: lavapipe's loop budget).
int shadow_slot_of(uint light, uvec4 slots[2])
{
    int k = slots[0].x == light ? 0 : slots[0].y == light ? 1 : slots[0].z == light ? 2 : slots[0].w == light ? 3 : -1;
    return slots[1].x == light ? 4 : slots[1].y == light ? 5 : slots[1].z == light ? 6 : slots[1].w == light ? 7 : k;
}

// Is the light of slot k of the pixel's tile clear of blockers (RTPBR_TILE_SHADOW_CLEAR) in
// every tile within `radius` pixels (< RTPBR_TILE_SIZE) of the pixel that shadows it? Those
// are the pixel's tile and at most three others (beside, above or below, diagonal).
bool shadow_clear_around(ivec2 pixel, int radius, uint k)
{
    ivec2 tileP = pixel / RTPBR_TILE_SIZE, inTile = pixel - tileP * RTPBR_TILE_SIZE;
    ivec2 side = ivec2(inTile.x < radius ? -1 : inTile.x >= RTPBR_TILE_SIZE - radius ? 1 : 0,
                       inTile.y < radius ? -1 : inTile.y >= RTPBR_TILE_SIZE - radius ? 1 : 0);
    ivec2 tiles = (ivec2(frame.size) + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE;
    uvec4 own[2], beside[2], across[2], diagonal[2];
    uint ownClear = shadow_tile_slots(tileP, tiles, own);
    if (!shadow_slot_clear(int(k), ownClear)) return false;
    uint light = own[k / 4u][k % 4u];
    uint besideClear = shadow_tile_slots(side.x != 0 ? tileP + ivec2(side.x, 0) : ivec2(-1), tiles, beside);
    uint acrossClear = shadow_tile_slots(side.y != 0 ? tileP + ivec2(0, side.y) : ivec2(-1), tiles, across);
    uint diagonalClear = shadow_tile_slots(side.x != 0 && side.y != 0 ? tileP + side : ivec2(-1), tiles, diagonal);
    return shadow_slot_clear(shadow_slot_of(light, beside), besideClear) &&
           shadow_slot_clear(shadow_slot_of(light, across), acrossClear) &&
           shadow_slot_clear(shadow_slot_of(light, diagonal), diagonalClear);
}
