#version 450
#extension GL_GOOGLE_include_directive : require
// Shadow pass, step 0b (issue 32): the trace's work list. One invocation per 8 x 8 pixel group
// (the trace's workgroups; x, y) and shadow slot k (z) < the frame's shadowed lights: the group
// and slot go on the list (RTPBR_SHADOW_WORK_HEADER) unless no pass reads their estimates, which
// is so when the slot's light is clear of blockers (shadow_select.comp) in the group's tile and
// in every tile within twice the denoiser's radius of its pixels that shadows the light
// (shadow_clear_around at the group's pixel nearest its tile's corner: the other pixels' tiles
// within that radius are among that pixel's). The trace then runs as an indirect dispatch over
// the list: on lavapipe a workgroup that exits at once still pays for the shader's whole
// straight-line code (llvmpipe runs both sides of a branch under a lane mask), so the groups
// left out must not run at all. The dispatch arguments x, y grow with the entries (atomicMax),
// z is 1 (written by the host with x = y = 0 and the count before this pass).
// The group also goes on the denoiser's list, once: by the invocation of its first listed slot.
// The denoiser filters a pixel's slot unless its light is clear in every tile within the
// radius that shadows it (shadow_clear_around(pixel, radius)); at the group's corner pixel that
// is the test above (radius or twice it: for any radius >= 1 the corner's square reaches the
// same three other tiles), so a group left out has every slot clear around every pixel, and
// each ratio 1.
#include "rtpbr_shared.h"
#include "shadow_common.glsl"

void main()
{
    uvec2 group = gl_GlobalInvocationID.xy;
    uint k = gl_GlobalInvocationID.z;
    uvec2 groups = shadow_groups();
    if (any(greaterThanEqual(group, groups)) || k >= min(frame.shadow_light_count, frame.light_count)) return;
    // The group's pixel at its tile's corner (the group is a quadrant of its tile).
    uvec2 perTile = uvec2(RTPBR_TILE_SIZE / RTPBR_SHADOW_GROUP_SIZE);
    uvec2 quadrant = group % perTile;
    uvec2 corner = (group / perTile) * uint(RTPBR_TILE_SIZE) +
                   uvec2(quadrant.x == 0u ? 0u : uint(RTPBR_TILE_SIZE) - 1u, quadrant.y == 0u ? 0u : uint(RTPBR_TILE_SIZE) - 1u);
#if RTPBR_TILE_SIZE != 2 * RTPBR_SHADOW_GROUP_SIZE
#error "a group is a quadrant of its tile"
#endif
    if (shadow_clear_around(ivec2(corner), 2 * int(params.radius), k)) return;
    uint index = atomicAdd(shadow_work[3], 1u);
    shadow_work[RTPBR_SHADOW_WORK_HEADER + index] = k | (group.x << 3u) | (group.y << 17u);
    atomicMax(shadow_work[0], min(index + 1u, RTPBR_SHADOW_WORK_ROW));
    atomicMax(shadow_work[1], index / RTPBR_SHADOW_WORK_ROW + 1u);
    bool first = true; // no lower slot of the group listed
    for (uint j = 0u; j < k; ++j)
        if (!shadow_clear_around(ivec2(corner), 2 * int(params.radius), j)) first = false;
    if (!first) return;
    const uint d = uint(RTPBR_SHADOW_WORK_DENOISE);
    index = atomicAdd(shadow_work[d + 3u], 1u);
    shadow_work[shadow_denoise_entries() + index] = group.x | (group.y << 16u);
    atomicMax(shadow_work[d], min(index + 1u, RTPBR_SHADOW_WORK_ROW));
    atomicMax(shadow_work[d + 1u], index / RTPBR_SHADOW_WORK_ROW + 1u);
}
