#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Lighting pass: one workgroup per RTPBR_TILE_SIZE^2 screen tile, dispatched indirectly over
// the tiles that the culling pass (cull.comp) queued for this variant's class
// (RTPBR_LIGHTING_CLASS: EMPTY, BASIC or FULL); reads the G-buffer, the tile's light mask and
// the scene's materials and writes linear radiance. Model flags (RTPBR_NDF,
// RTPBR_MULTISCATTER) come from the build, one SPIR-V variant per combination and class
// (engine/shaders/meson.build). All BRDF and polygon-integration math comes from the shader
// library (shaderlib/rtpbr); this file only fetches, loops and sums. No barriers, no shared
// memory, and no private array indexed at run time: a light's vertices are read from the
// light buffer edge by edge and streamed through one horizon clip into every lobe (ltc.h,
// "streamed integration").
// RTPBR_STATS_FIXED_LIGHTS=N (bench/shader-stats only) replaces the tile's light list by
// lights 0 .. N-1, a compile-time count, unrolled, and every light by a quad (4 vertices,
// unrolled), so that compile statistics of builds with one and two lights differ by exactly
// one quad light in straight-line code (the yardstick's form: bench/shader-stats).
#include "rtpbr_shared.h"
#include "rtpbr/lang.h"
#include "rtpbr/config.h"
#include "rtpbr/fresnel.h"
#include "rtpbr/ltc.h"
#include "rtpbr/ltc_corrections.h"
#include "rtpbr/kulla_conty.h"
#include "rtpbr/disney.h"
#include "rtpbr/sheen.h"
#include "rtpbr/material.h"
#include "material.glsl"
#define RTPBR_FRAME_BINDING RTPBR_BINDING_LIGHT_FRAME
#include "frame.glsl"
#include "vertex_limit.glsl"

#ifndef RTPBR_LIGHTING_CLASS
#define RTPBR_LIGHTING_CLASS RTPBR_TILE_CLASS_FULL
#endif
#define RTPBR_LIGHTING_FULL (RTPBR_LIGHTING_CLASS == RTPBR_TILE_CLASS_FULL || RTPBR_LIGHTING_CLASS == RTPBR_TILE_CLASS_FULL_SPHERES || \
                             RTPBR_LIGHTING_CLASS == RTPBR_TILE_CLASS_FULL_TEXTURED || RTPBR_LIGHTING_CLASS == RTPBR_TILE_CLASS_FULL_TUBES)
// The classes with a sphere among their lights (shade_lights' spheres loop).
#define RTPBR_LIGHTING_SPHERES (RTPBR_LIGHTING_CLASS >= RTPBR_TILE_CLASS_BASIC_SPHERES)
#define RTPBR_LIGHTING_TEXTURED (RTPBR_LIGHTING_CLASS >= RTPBR_TILE_CLASS_BASIC_TEXTURED)
#define RTPBR_LIGHTING_TUBES (RTPBR_LIGHTING_CLASS >= RTPBR_TILE_CLASS_BASIC_TUBES)

layout(local_size_x = RTPBR_TILE_SIZE, local_size_y = RTPBR_TILE_SIZE) in;
#if RTPBR_LIGHTING_CLASS == RTPBR_TILE_CLASS_EMPTY
// Whether a material of the frame emits (RTPBR_SPEC_LIGHTING_EMISSION): if none does, every
// surface pixel's emission is 0 and the empty tiles do not read it.
layout(constant_id = RTPBR_SPEC_LIGHTING_EMISSION) const bool shade_emission = true;
#endif

#include "lighting_common.glsl"
#include "shadow_ratio.glsl"

#include "shade_lights.glsl"

void main()
{
#if RTPBR_LIGHTING_CLASS == RTPBR_TILE_CLASS_BASIC
    // (the basic variant without the streak estimate is the basic class's code: its own queue)
    uint queue = shade_streak ? uint(RTPBR_TILE_CLASS_BASIC) : uint(RTPBR_TILE_CLASS_BASIC_NO_STREAK);
#else
    uint queue = uint(RTPBR_LIGHTING_CLASS);
#endif
    uint tile = tile_list[queue * frame.tile_capacity + gl_WorkGroupID.x];
    ivec2 pixel = ivec2(uvec2(tile % frame.tiles_x, tile / frame.tiles_x) * uint(RTPBR_TILE_SIZE) + gl_LocalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), frame.size))) return;
    float depth = texelFetch(gbuffer_depth, pixel, 0).r;
    if (depth == frame.camera_position.w) { // the background (1, or 0: reversed-Z)
        imageStore(radiance, pixel, vec4(frame.background.rgb, 0.0));
        return;
    }
#if RTPBR_LIGHTING_CLASS == RTPBR_TILE_CLASS_EMPTY
    vec3 result = vec3(0.0f); // emitted radiance
    if (shade_emission) result = GBuffer_DecodeEmission(texelFetch(gbuffer2, pixel, 0));
#else
    vec4 g2 = texelFetch(gbuffer2, pixel, 0);
    vec3 result = GBuffer_DecodeEmission(g2); // emitted radiance
    vec2 ndc = (vec2(pixel) + 0.5f) / vec2(frame.size) * 2.0f - 1.0f;
    vec4 world = frame.inv_view_proj * vec4(ndc, depth, 1.0f);
    vec3 P = world.xyz / world.w;
    GBufferSurface g = gbuffer_surface(pixel, g2);
    vec3 V = normalize(frame.camera_position.xyz - P);
    vec3 N = g.normal;
    ShadingSurface s = surface_terms(g, materials[g.materialIndex], rtpbr_saturate(dot(N, V)));
    shade_lights(lifted_point(ndc, depth, P, N), N, V, s, tile, pixel, result);
#endif
    imageStore(radiance, pixel, vec4(result, 1.0));
}
