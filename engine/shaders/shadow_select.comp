#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
// Shadow pass, step 0 (issue 32): which lights cast shadows in each tile. One invocation per
// RTPBR_TILE_SIZE^2 tile of the shading image (the lighting pass's tiles): it bounds the
// world positions of the tile's surface pixels by a box (as cull.comp does), bounds each
// light's irradiance at any point of the box, and keeps the RTPBR_SHADER_MAX_SHADOWED_LIGHTS
// lights of the largest bounds (ties: the lower index), written in increasing light order to
// the tile's shadow slots (tile_masks at RTPBR_TILE_SHADOW_SLOTS; RTPBR_TILE_NO_LIGHT for
// empty ones). A light whose bound is 0 (out of reach) is never kept. The bound, in luminance
// (Rec. 709 weights of the light's emission):
//   polygon (and a directional light's disk), sphere: L min(A / d^2, pi), d the distance from
//     the box to the light's bounding sphere (from its centre for a sphere); pi where they
//     meet (E = L int cos dw <= L * solid angle <= L A / d^2, and <= pi L); 0 for a one-sided
//     polygon with the whole box behind its plane;
//   point, spot: I / max(d^2, 1e-4), d from the box to the light; 0 beyond its range;
//   directional: its illuminance E.
// A bound, not the contribution (materials and occlusion are not known here): a light that
// could reach a tile brightly is shadowed there before a dim or distant one, whatever the
// lights' order in the scene (before: lights 0 .. 7 everywhere).
// Then, with shadow-ray culling on (params.cull), the slots whose light no triangle can keep
// from any of the tile's shadow-ray origins (shadow_cull.glsl, on the box of the origins):
// bit k of the tile's RTPBR_TILE_SHADOW_CLEAR word (0 with culling off).
#include "rtpbr_shared.h"
#include "shadow_common.glsl"

#include "material.glsl"
#include "bvh.glsl"
#include "light.glsl"
layout(set = 0, binding = RTPBR_BINDING_SHADOW_LIGHTS, std430) readonly buffer Lights {
    Light lights[];
};
#include "shadow_cull.glsl"

float luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

float irradiance_bound(uint i, vec3 boxMin, vec3 boxMax)
{
    uint shape = lights[i].shape;
    float L = luminance(max(lights[i].radiance, vec3(0.0f)));
    vec4 sphere = lights[i].sphere;
    float toCentre = length(sphere.xyz - clamp(sphere.xyz, boxMin, boxMax));
    if (shape == uint(RTPBR_LIGHT_SHAPE_DIRECTIONAL)) return L;
    if (shape == uint(RTPBR_LIGHT_SHAPE_POINT) || shape == uint(RTPBR_LIGHT_SHAPE_SPOT)) {
        // the light's reach: its position and range (RTPBR_LIGHT_INFINITE without one)
        if (!(toCentre < sphere.w)) return 0.0f;
        return L / max(toCentre * toCentre, 1e-4f);
    }
    if (shape == uint(RTPBR_LIGHT_SHAPE_SPHERE)) {
        float invRange2 = lights[i].vertices[0].w; // 1 / range^2 (0: none), from the centre
        if (invRange2 > 0.0f && toCentre * toCentre * invRange2 >= 1.0f) return 0.0f;
        return toCentre <= sphere.w ? 3.14159265f * L : L * min(lights[i].area / (toCentre * toCentre), 3.14159265f);
    }
    if (shape == uint(RTPBR_LIGHT_SHAPE_TUBE)) {
        float invRange2 = lights[i].vertices[3].w; // 1 / range^2 (0: none), from the centre
        if (invRange2 > 0.0f && toCentre * toCentre * invRange2 >= 1.0f) return 0.0f;
    }
    vec4 plane = lights[i].plane;
    if (lights[i].two_sided == 0.0f) {
        // the box's corner furthest in front of the plane
        vec3 corner = mix(boxMin, boxMax, greaterThan(plane.xyz, vec3(0.0f)));
        if (!(dot(plane.xyz, corner) + plane.w > 0.0f)) return 0.0f;
    }
    float d = toCentre - sphere.w;
    return d <= 0.0f ? 3.14159265f * L : L * min(lights[i].area / (d * d), 3.14159265f);
}

void main()
{
    uvec2 tileXY = gl_GlobalInvocationID.xy;
    uint tilesY = (frame.size.y + uint(RTPBR_TILE_SIZE) - 1u) / uint(RTPBR_TILE_SIZE);
    if (tileXY.x >= frame.tiles_x || tileXY.y >= tilesY) return;
    uint base = (tileXY.y * frame.tiles_x + tileXY.x) * uint(RTPBR_TILE_MASK_STRIDE) + uint(RTPBR_TILE_SHADOW_SLOTS);

    // The tile's world-space box (its surface pixels), and its shadow rays' origins' box.
    vec3 boxMin = vec3(3.402823466e+38f), boxMax = vec3(-3.402823466e+38f);
    vec3 originMin = boxMin, originMax = boxMax;
    uvec2 origin = tileXY * uint(RTPBR_TILE_SIZE);
    uvec2 end = min(origin + uvec2(RTPBR_TILE_SIZE), frame.size);
    for (uint y = origin.y; y < end.y; ++y)
        for (uint x = origin.x; x < end.x; ++x) {
            float depth = texelFetch(gbuffer_depth, ivec2(x, y), 0).r;
            if (depth < 1.0f) { // rtpbr's own passes: 1 is the background
                vec3 P = shadow_world_point(ivec2(x, y), depth);
                boxMin = min(boxMin, P);
                boxMax = max(boxMax, P);
                if (params.cull != 0u) {
                    vec3 N = normalize(texelFetch(gbuffer_normal, ivec2(x, y), 0).xyz);
                    vec3 o = shadow_ray_origin(ivec2(x, y), depth, P, N);
                    originMin = min(originMin, o);
                    originMax = max(originMax, o);
                }
            }
        }

    // The kept lights and their bounds; the smallest kept bound and its place, replaced when a
    // larger one comes (slots unrolled by hand: no loop against lavapipe's loop budget).
#if RTPBR_SHADER_MAX_SHADOWED_LIGHTS != 8
#error "the selection keeps 8 slots"
#endif
    uint kept[8] = uint[8](RTPBR_TILE_NO_LIGHT, RTPBR_TILE_NO_LIGHT, RTPBR_TILE_NO_LIGHT, RTPBR_TILE_NO_LIGHT,
                           RTPBR_TILE_NO_LIGHT, RTPBR_TILE_NO_LIGHT, RTPBR_TILE_NO_LIGHT, RTPBR_TILE_NO_LIGHT);
    float bound[8] = float[8](0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
    uint weakest = 0u; // the place of the smallest bound (an empty slot's is 0)
    bool anySurface = boxMin.x <= boxMax.x;
    for (uint i = 0u; anySurface && i < frame.light_count; ++i) {
        float b = irradiance_bound(i, boxMin, boxMax);
        if (!(b > bound[weakest])) continue; // ties and NaN: the kept (lower-index) light stays
        kept[weakest] = i;
        bound[weakest] = b;
        weakest = 0u;
#define RTPBR_WEAKER(k) weakest = bound[k] < bound[weakest] ? (k) : weakest;
        RTPBR_WEAKER(1u) RTPBR_WEAKER(2u) RTPBR_WEAKER(3u) RTPBR_WEAKER(4u) RTPBR_WEAKER(5u) RTPBR_WEAKER(6u)
        RTPBR_WEAKER(7u)
#undef RTPBR_WEAKER
    }
    // Increasing light order (empty slots last): neighbouring tiles that keep the same lights
    // keep them in the same slots. An odd-even transposition sort of 8 (8 rounds).
#define RTPBR_ORDER(a, b) { uint lo_ = min(kept[a], kept[b]), hi_ = max(kept[a], kept[b]); kept[a] = lo_; kept[b] = hi_; }
#define RTPBR_EVEN RTPBR_ORDER(0, 1) RTPBR_ORDER(2, 3) RTPBR_ORDER(4, 5) RTPBR_ORDER(6, 7)
#define RTPBR_ODD RTPBR_ORDER(1, 2) RTPBR_ORDER(3, 4) RTPBR_ORDER(5, 6)
    RTPBR_EVEN RTPBR_ODD RTPBR_EVEN RTPBR_ODD RTPBR_EVEN RTPBR_ODD RTPBR_EVEN RTPBR_ODD
#undef RTPBR_ORDER
#undef RTPBR_EVEN
#undef RTPBR_ODD
#define RTPBR_STORE(k) shadow_tiles[base + (k)] = kept[k];
    RTPBR_STORE(0u) RTPBR_STORE(1u) RTPBR_STORE(2u) RTPBR_STORE(3u) RTPBR_STORE(4u) RTPBR_STORE(5u) RTPBR_STORE(6u)
    RTPBR_STORE(7u)
#undef RTPBR_STORE
    // The slots whose light no triangle can keep from any of the tile's ray origins, and the
    // empty slots (no rays: so is every slot of a tile without a surface pixel).
    uint clear = 0u;
    for (uint k = 0u; params.cull != 0u && k < 8u; ++k) {
        if (kept[k] >= frame.light_count) {
            clear |= 1u << k;
            continue;
        }
        Light light = lights[kept[k]];
        if (shadow_cull_applies(light) && !shadow_cull_may_block(originMin, originMax, light)) clear |= 1u << k;
    }
    shadow_tiles[base - uint(RTPBR_TILE_SHADOW_SLOTS) + uint(RTPBR_TILE_SHADOW_CLEAR)] = clear;
}
