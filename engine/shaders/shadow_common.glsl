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

// The first word of the shadow slots of the workgroup's tile: a workgroup's
// RTPBR_SHADOW_GROUP_SIZE^2 pixels lie in one tile, and an index the compiler sees is uniform
// keeps the light's record in scalar registers (from the pixel's tile: 96 -> 128 VGPRs on navi21).
#if RTPBR_TILE_SIZE % RTPBR_SHADOW_GROUP_SIZE != 0
#error "a shadow workgroup must lie in one lighting tile"
#endif
uint shadow_group_slot_base()
{
    uvec2 tileXY = gl_WorkGroupID.xy / uint(RTPBR_TILE_SIZE / RTPBR_SHADOW_GROUP_SIZE);
    return (tileXY.y * frame.tiles_x + tileXY.x) * uint(RTPBR_TILE_MASK_STRIDE) + uint(RTPBR_TILE_SHADOW_SLOTS);
}
