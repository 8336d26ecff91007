#version 450
#extension GL_GOOGLE_include_directive : require
// Light culling and tile classification, a dispatch of its own before the lighting pass (so the
// shading kernel has no barriers: lavapipe runs a workgroup's invocations as coroutines that
// switch at each barrier). One invocation per RTPBR_TILE_SIZE^2 screen tile: it bounds the
// world positions of the tile's pixels by a box, keeps the lights that may reach the box (bit
// i of the tile's masks, tile_masks: one of polygons, one of punctual lights, one of spheres,
// one of disks),
// and queues the tile for the lighting variant of its class (tile_dispatch / tile_list,
// consumed by indirect dispatches), and per kind a summary word (bit w: the kind's word w is
// not zero; the lighting pass walks only those words):
//   EMPTY  no surface pixel, or no light left: emission and background only;
//   BASIC  every material of the tile is basic (material_tile_class);
//   FULL   otherwise;
//   BASIC_SPHERES, FULL_SPHERES  the same with a sphere or a disk among the tile's lights (the
//          variants with the spheres' and disks' loops); the textured and tubes' classes the
//          same for a textured quad or a tube;
//   BASIC_NO_STREAK  BASIC where no pixel can give the streak estimate any weight
//          (streak_possible): the basic variant with the estimate specialized out.
// Light i is kept unless
//   (1) the light is one-sided and every corner of the box is behind its plane: it cannot
//       light any point of the tile (exact), or
//   (2) the box is at distance d > 0 from the light's bounding sphere and A / (pi d^2) <
//       frame.cull_form_factor: A / (pi d^2) bounds the light's form factor (1/pi) int cos dw
//       at every point of the tile (the solid angle of a polygon of area A at distance >= d is
//       at most A / d^2), so the light's diffuse contribution is below Le * albedo *
//       cull_form_factor. Glossy reflections of such a light are dropped with it (a bias
//       bounded only for the diffuse term). cull_form_factor < 0 disables this test.
// A punctual light (point, spot, directional) is kept unless the box is beyond its range (3).
// A directional light's disk (a polygon far away, rtpbr_shader_light.sun) is not held to (2): its
// form factor is small (the sun's: 2e-5) but its radiance large.
// A sphere (a point light with a radius) is kept unless the box is beyond its range from its
// centre or its form factor from the whole box, at most r^2 / d^2, is below the threshold (4).
// A disk is culled as a polygon ((1) by its plane, (2) by its bounding sphere and area); a tube
// too (two-sided: (2) only; its area 4 pi r^2 + 2 pi r L bounds its projected area 2 r L + pi r^2),
// and beyond its range from its centre (5).
// Each kind goes to its own mask (polygons, punctual lights, spheres, disks, textured quads,
// tubes; the spheres' lighting variants shade spheres and disks, the textured ones textured quads too,
// the tubes' ones all four).
#include "rtpbr_shared.h"
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/kulla_conty.h"
#include "rtpbr/disney.h"
#include "rtpbr/sheen.h"
#include "rtpbr/material.h"
#include "rtpbr/ltc_corrections.h"
#include "material.glsl"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_LIGHT_FRAME
#include "frame.glsl"

layout(local_size_x = RTPBR_CULL_GROUP, local_size_y = RTPBR_CULL_GROUP) in;

#include "lighting_common.glsl"

bool light_may_contribute(uint i, vec3 boxMin, vec3 boxMax)
{
    // (3) A punctual light is kept unless the box is beyond its range (its window is 0 there:
    // exact); without a range its sphere's radius is RTPBR_LIGHT_INFINITE.
    uint shape = lights[i].shape;
    if (shape == uint(RTPBR_LIGHT_SHAPE_SPHERE)) {
        // (4) A sphere: kept unless the box is beyond its range (measured from its centre, as
        // its window) or it subtends less than the form factor threshold from the box (its
        // Lambert form factor is at most r^2 / d^2 = area / (pi d^2), d from the centre).
        vec4 sphere = lights[i].sphere;
        float d = length(sphere.xyz - clamp(sphere.xyz, boxMin, boxMax));
        float invRange2 = lights[i].vertices[0].w;
        if (invRange2 > 0.0f && d * d * invRange2 >= 1.0f) return false;
        return !(frame.cull_form_factor >= 0.0f && d > sphere.w &&
                 lights[i].area < frame.cull_form_factor * 3.14159265f * d * d);
    }
    if (shape == uint(RTPBR_LIGHT_SHAPE_TUBE)) {
        // (5) A tube beyond its range from its centre (its window, exact) lights nothing there.
        vec4 centre = lights[i].vertices[3]; // (centre, 1 / range^2 or 0)
        vec3 toBox = centre.xyz - clamp(centre.xyz, boxMin, boxMax);
        if (centre.w > 0.0f && dot(toBox, toBox) * centre.w >= 1.0f) return false;
    }
    if (shape != uint(RTPBR_LIGHT_SHAPE_POLYGON) && shape != uint(RTPBR_LIGHT_SHAPE_DISK) &&
        shape != uint(RTPBR_LIGHT_SHAPE_TUBE)) {
        vec4 reach = lights[i].sphere;
        return length(reach.xyz - clamp(reach.xyz, boxMin, boxMax)) < reach.w;
    }
    vec4 plane = lights[i].plane;
    if (lights[i].two_sided == 0.0f) {
        bool anyInFront = false;
        for (int c = 0; c < 8; ++c) {
            vec3 corner = vec3((c & 1) != 0 ? boxMax.x : boxMin.x, (c & 2) != 0 ? boxMax.y : boxMin.y,
                               (c & 4) != 0 ? boxMax.z : boxMin.z);
            anyInFront = anyInFront || dot(plane.xyz, corner) + plane.w > 0.0f;
        }
        if (!anyInFront) return false;
    }
    if (frame.cull_form_factor >= 0.0f && lights[i].sun == 0u) {
        vec4 sphere = lights[i].sphere;
        vec3 nearest = clamp(sphere.xyz, boxMin, boxMax);
        float d = length(sphere.xyz - nearest) - sphere.w;
        if (d > 0.0f && lights[i].area < frame.cull_form_factor * 3.14159265f * d * d) return false;
    }
    return true;
}

// How far lifted_point (lighting_common.glsl) moves the point of depth at ndc along N.
float lift_of(vec2 ndc, float depth)
{
    vec4 world = frame.inv_view_proj * vec4(ndc, depth, 1.0f);
    return point_lift(ndc, depth, world.xyz / world.w);
}

// Whether the streak estimate (shaderlib ltc_corrections.h; the basic variant's AreaLight_End)
// can weigh anything at a pixel of the tile (origin .. end; its points in the box, within
// maxLift of the lifted points the lighting pass shades): false (RTPBR_TILE_CLASS_BASIC_NO_STREAK)
// where every polygon light of the tile's mask lies outside the view's cone by the estimate's
// angle (LTC_StreakOutside: the cones of the directions from a ball around the box to the camera
// and from a ball around the lifted points to the light's bounding sphere), or else where every
// pixel is seen too steeply for it (LTC_StreakSteep at a lower bound of its NoV: the angle
// between its normal and the view cone's axis plus the cone's spread). Then the estimate's
// weight is 0 at every pixel and light, and the variant without it gives the same image. The
// cheap test first: the second reads the tile's normals.
bool streak_possible(uint tile, uvec2 origin, uvec2 end, vec3 boxMin, vec3 boxMax, float maxLift)
{
    const float pi = 3.14159265f; // (a cone of every direction: the camera or the light within the ball)
    vec3 centre = 0.5f * (boxMin + boxMax);
    vec3 toCamera = frame.camera_position.xyz - centre;
    float rho = 0.5f * length(boxMax - boxMin), dCamera = length(toCamera);
    float viewSpread = dCamera > rho ? asin(rho / dCamera) : pi;
    float liftRho = rho + maxLift;
    bool outside = true;
    uint maskBase = tile * uint(RTPBR_TILE_MASK_STRIDE);
    for (uint words = tile_masks[maskBase + uint(RTPBR_TILE_MASK_SUMMARY)]; words != 0u && outside; words &= words - 1u) {
        uint word = uint(findLSB(words));
        for (uint bits = tile_masks[maskBase + word]; bits != 0u && outside; bits &= bits - 1u) {
            vec4 sphere = lights[word * 32u + uint(findLSB(bits))].sphere;
            vec3 toLight = sphere.xyz - centre;
            float reach = liftRho + sphere.w, d = length(toLight);
            outside = LTC_StreakOutside(toCamera, viewSpread, toLight, d > reach ? asin(reach / d) : pi);
        }
    }
    if (outside) return false;
    // NoV >= cos(angle(N, axis) + viewSpread) (V within viewSpread of the axis), which is steep
    // (LTC_StreakSteep) where N . axis >= cos(acos(LTC_StreakSteepNoV()) - viewSpread); the
    // first pixel below that ends the loop (on lavapipe a tile of a grazing floor reads one)
    float room = acos(LTC_StreakSteepNoV()) - viewSpread;
    if (!(room > 0.0f)) return true;
    float steepest = cos(room);
    vec3 axis = toCamera / max(dCamera, 1e-30f);
    for (uint y = origin.y; y < end.y; ++y)
        for (uint x = origin.x; x < end.x; ++x)
            if (texelFetch(gbuffer_depth, ivec2(x, y), 0).r != frame.camera_position.w && // (as the lighting pass)
                !(dot(GBuffer_DecodeNormal(texelFetch(gbuffer1, ivec2(x, y), 0)), axis) >= steepest))
                return true;
    return false;
}

void main()
{
    uvec2 tileXY = gl_GlobalInvocationID.xy;
    uint tilesY = (frame.size.y + uint(RTPBR_TILE_SIZE) - 1u) / uint(RTPBR_TILE_SIZE);
    if (tileXY.x >= frame.tiles_x || tileXY.y >= tilesY) return;
    uint tile = tileXY.y * frame.tiles_x + tileXY.x;

    // The tile's world-space box.
    vec3 boxMin = vec3(3.402823466e+38f);
    vec3 boxMax = vec3(-3.402823466e+38f);
    bool anySurface = false;
    uvec2 origin = tileXY * uint(RTPBR_TILE_SIZE);
    uvec2 end = min(origin + uvec2(RTPBR_TILE_SIZE), frame.size);
    // and the pixels of the least and the greatest depth (ndc, depth), between which lies the
    // tile's largest lift (lifted_point: it grows with the distance, which grows with the
    // depth, or falls with it for reversed-Z)
    vec3 nearest = vec3(0.0f, 0.0f, 3.402823466e+38f), farthest = vec3(0.0f, 0.0f, -3.402823466e+38f);
    for (uint y = origin.y; y < end.y; ++y)
        for (uint x = origin.x; x < end.x; ++x) {
            float depth = texelFetch(gbuffer_depth, ivec2(x, y), 0).r;
            if (depth != frame.camera_position.w) { // not the background (1, or 0: reversed-Z)
                vec2 ndc = (vec2(x, y) + 0.5f) / vec2(frame.size) * 2.0f - 1.0f;
                vec4 world = frame.inv_view_proj * vec4(ndc, depth, 1.0f);
                vec3 P = world.xyz / world.w;
                boxMin = min(boxMin, P);
                boxMax = max(boxMax, P);
                anySurface = true;
                if (depth < nearest.z) nearest = vec3(ndc, depth);
                if (depth > farthest.z) farthest = vec3(ndc, depth);
            }
        }

    bool anyLight = false, anySphere = false, anyTextured = false, anyTube = false;
    // Per kind, bit w: the kind's word w is not zero (RTPBR_TILE_MASK_SUMMARY).
    uint polygonWords = 0u, punctualWords = 0u, sphereWords = 0u, diskWords = 0u, texturedWords = 0u, tubeWords = 0u;
    uint words = (frame.light_count + 31u) / 32u;
    for (uint w = 0u; w < words; ++w) {
        uint bits = 0u, punctualBits = 0u, sphereBits = 0u, diskBits = 0u, texturedBits = 0u, tubeBits = 0u; // polygons, punctual lights, spheres, disks, textured quads, tubes
        if (anySurface) {
            uint count = min(32u, frame.light_count - 32u * w);
            for (uint b = 0u; b < count; ++b)
                if (light_may_contribute(32u * w + b, boxMin, boxMax)) {
                    uint shape = lights[32u * w + b].shape;
                    if (shape == uint(RTPBR_LIGHT_SHAPE_POLYGON) && lights[32u * w + b].texture != 0u) texturedBits |= 1u << b;
                    else if (shape == uint(RTPBR_LIGHT_SHAPE_POLYGON)) bits |= 1u << b;
                    else if (shape == uint(RTPBR_LIGHT_SHAPE_SPHERE)) sphereBits |= 1u << b;
                    else if (shape == uint(RTPBR_LIGHT_SHAPE_DISK)) diskBits |= 1u << b;
                    else if (shape == uint(RTPBR_LIGHT_SHAPE_TUBE)) tubeBits |= 1u << b;
                    else punctualBits |= 1u << b;
                }
        }
        tile_masks[tile * uint(RTPBR_TILE_MASK_STRIDE) + w] = bits;
        tile_masks[tile * uint(RTPBR_TILE_MASK_STRIDE) + uint(RTPBR_TILE_MASK_WORDS) + w] = punctualBits;
        tile_masks[tile * uint(RTPBR_TILE_MASK_STRIDE) + 2u * uint(RTPBR_TILE_MASK_WORDS) + w] = sphereBits;
        tile_masks[tile * uint(RTPBR_TILE_MASK_STRIDE) + 3u * uint(RTPBR_TILE_MASK_WORDS) + w] = diskBits;
        tile_masks[tile * uint(RTPBR_TILE_MASK_STRIDE) + 4u * uint(RTPBR_TILE_MASK_WORDS) + w] = texturedBits;
        tile_masks[tile * uint(RTPBR_TILE_MASK_STRIDE) + 5u * uint(RTPBR_TILE_MASK_WORDS) + w] = tubeBits;
        polygonWords |= bits != 0u ? 1u << w : 0u;
        punctualWords |= punctualBits != 0u ? 1u << w : 0u;
        sphereWords |= sphereBits != 0u ? 1u << w : 0u;
        diskWords |= diskBits != 0u ? 1u << w : 0u;
        texturedWords |= texturedBits != 0u ? 1u << w : 0u;
        tubeWords |= tubeBits != 0u ? 1u << w : 0u;
        anyLight = anyLight || (bits | punctualBits | sphereBits | diskBits | texturedBits | tubeBits) != 0u;
        anySphere = anySphere || (sphereBits | diskBits) != 0u;
        anyTube = anyTube || tubeBits != 0u;
        anyTextured = anyTextured || texturedBits != 0u;
    }
    uint summary = tile * uint(RTPBR_TILE_MASK_STRIDE) + uint(RTPBR_TILE_MASK_SUMMARY);
    tile_masks[summary] = polygonWords;
    tile_masks[summary + 1u] = punctualWords;
    tile_masks[summary + 2u] = sphereWords;
    tile_masks[summary + 3u] = diskWords;
    tile_masks[summary + 4u] = texturedWords;
    tile_masks[summary + 5u] = tubeWords;
    // The most demanding class of the tile's materials, read only where a light is left (a
    // tile without one reads no material).
    uint tileClass = RTPBR_TILE_CLASS_EMPTY;
    if (anyLight) {
        tileClass = RTPBR_TILE_CLASS_BASIC;
        for (uint y = origin.y; y < end.y && tileClass != RTPBR_TILE_CLASS_FULL; ++y)
            for (uint x = origin.x; x < end.x && tileClass != RTPBR_TILE_CLASS_FULL; ++x)
                if (texelFetch(gbuffer_depth, ivec2(x, y), 0).r != frame.camera_position.w)
                    tileClass = max(tileClass, material_tile_class(materials[uint(texelFetch(gbuffer2, ivec2(x, y), 0).a)]));
    }
    // (a basic tile of polygons and punctual lights: the streak estimate's, polygons only)
    if (tileClass == RTPBR_TILE_CLASS_BASIC && !anySphere && !anyTextured && !anyTube &&
        // (the lift at either end of the depths, doubled: the pixels' rays differ in length
        // across a tile by a few per cent at most)
        !streak_possible(tile, origin, end, boxMin, boxMax,
                         2.0f * max(lift_of(nearest.xy, nearest.z), lift_of(farthest.xy, farthest.z))))
        tileClass = RTPBR_TILE_CLASS_BASIC_NO_STREAK;
    else if (anyTube && tileClass != RTPBR_TILE_CLASS_EMPTY)
        tileClass += uint(RTPBR_TILE_CLASS_BASIC_TUBES - RTPBR_TILE_CLASS_BASIC);
    else if (anyTextured && tileClass != RTPBR_TILE_CLASS_EMPTY)
        tileClass += uint(RTPBR_TILE_CLASS_BASIC_TEXTURED - RTPBR_TILE_CLASS_BASIC);
    else if (anySphere && tileClass != RTPBR_TILE_CLASS_EMPTY)
        tileClass += uint(RTPBR_TILE_CLASS_BASIC_SPHERES - RTPBR_TILE_CLASS_BASIC);
    uint slot = atomicAdd(tile_dispatch[tileClass].x, 1u);
    tile_list[tileClass * frame.tile_capacity + slot] = tile;
}
