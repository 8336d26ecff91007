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
// One workgroup per entry of the denoiser's work list (shadow_list.comp: the 8 x 8 groups where
// some slot's estimates are read); passes/shadow.c has set every ratio of the other groups to 1.
// Slot k of the pixel's tile holds light L (shadow_select.comp); a neighbour in another tile
// contributes its estimates of L from the slot where its tile holds L, and nothing where its
// tile does not shadow L (no estimates of L there).
#include "rtpbr_shared.h"
#include "shadow_common.glsl"

void main()
{
    uint g = gl_WorkGroupID.y * RTPBR_SHADOW_WORK_ROW + gl_WorkGroupID.x;
    if (g >= shadow_work[RTPBR_SHADOW_WORK_DENOISE + 3]) return; // the last row's rest (uniform)
    uint entry = shadow_work[shadow_denoise_entries() + g];
    uvec2 group = uvec2(entry & 0xffffu, entry >> 16u);
    ivec2 pixel = ivec2(group * uint(RTPBR_SHADOW_GROUP_SIZE) + gl_LocalInvocationID.xy);
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
    // The window (radius < RTPBR_TILE_SIZE, shadow.c) reaches at most three other tiles: the
    // one beside the pixel's tile on the side of the nearer vertical edge (when within r of
    // it), the one above or below, and the one on the diagonal. Their slots, read once.
    ivec2 tileP = pixel / RTPBR_TILE_SIZE, inTile = pixel - tileP * RTPBR_TILE_SIZE;
    ivec2 side = ivec2(inTile.x < r ? -1 : inTile.x >= RTPBR_TILE_SIZE - r ? 1 : 0,
                       inTile.y < r ? -1 : inTile.y >= RTPBR_TILE_SIZE - r ? 1 : 0);
    ivec2 tiles = (ivec2(frame.size) + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE;
    uvec4 own[2], beside[2], across[2], diagonal[2];
    uint ownClear = shadow_tile_slots(tileP, tiles, own);
    uint besideClear = shadow_tile_slots(side.x != 0 ? tileP + ivec2(side.x, 0) : ivec2(-1), tiles, beside);
    uint acrossClear = shadow_tile_slots(side.y != 0 ? tileP + ivec2(0, side.y) : ivec2(-1), tiles, across);
    uint diagonalClear = shadow_tile_slots(side.x != 0 && side.y != 0 ? tileP + side : ivec2(-1), tiles, diagonal);
    // The lights to filter: not those for which every tile of the window that holds the light
    // is clear of blockers (each neighbour's shadowed sum equals its unshadowed one, so the
    // filtered ratio is 1 exactly).
    uint filtered = 0u;
    for (uint k = 0u; k < lightCount; ++k) {
        uint light = own[k / 4u][k % 4u];
        if (!(shadow_slot_clear(int(k), ownClear) && shadow_slot_clear(shadow_slot_of(light, beside), besideClear) &&
              shadow_slot_clear(shadow_slot_of(light, across), acrossClear) &&
              shadow_slot_clear(shadow_slot_of(light, diagonal), diagonalClear)))
            filtered |= 1u << k;
    }
    // The guide's weights of the window's pixels, computed once for all the lights (they do
    // not depend on the light; on lavapipe, recomputed per light they took half the pass with 5
    // lights): -1 for a background pixel, which adds nothing. None where no light is filtered.
    float weights[RTPBR_SHADER_SHADOW_WINDOW];
    int t = 0;
    for (int y = lo.y; filtered != 0u && y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x, ++t) {
            ivec2 q = ivec2(x, y);
            float dq = texelFetch(gbuffer_depth, q, 0).r;
            float plane = dot(N, shadow_world_point(q, dq) - P) * planeScale;
            float nq = max(dot(N, normalize(texelFetch(gbuffer_normal, q, 0).xyz)), 0.0f);
            float n2 = nq * nq, n4 = n2 * n2, n8 = n4 * n4;
            weights[t] = dq >= 1.0f ? -1.0f : exp(-plane * plane) * n8 * n8;
        }
    for (uint k = 0u; k < lightCount; ++k) {
        uint light = own[k / 4u][k % 4u];
        // where each of those tiles holds this light (-1: it does not shadow it there)
        int slotBeside = shadow_slot_of(light, beside), slotAcross = shadow_slot_of(light, across),
            slotDiagonal = shadow_slot_of(light, diagonal);
        if ((filtered & (1u << k)) == 0u) {
            imageStore(shadow_ratio_out, ivec3(pixel, int(k)), vec4(1.0f));
            continue;
        }
        vec2 sum = vec2(0.0f);
        t = 0;
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x, ++t) {
                float w = weights[t];
                if (w < 0.0f) continue; // background
                // q's tile: the pixel's, or one of the three: its estimates of this light
                ivec2 q = ivec2(x, y);
                bvec2 other = notEqual(q / RTPBR_TILE_SIZE, tileP);
                int kq = other.x ? (other.y ? slotDiagonal : slotBeside) : (other.y ? slotAcross : int(k));
                if (kq < 0 || uint(kq) >= lightCount) continue;
                sum += w * vec2(imageLoad(shadow_estimates, ivec3(q, 2 * kq)).r,
                                imageLoad(shadow_estimates, ivec3(q, 2 * kq + 1)).r);
            }
        imageStore(shadow_ratio_out, ivec3(pixel, int(k)), vec4(sum.y > 0.0f ? sum.x / sum.y : 1.0f));
    }
}
