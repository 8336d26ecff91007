// Reflected radiance from the lights at a surface point (shade_lights), shared by the LTC
// lighting pass (lighting.comp) and the forward pass of BLEND surfaces (forward.frag). The
// per-light evaluation is the shader library's (shaderlib/rtpbr/area_light.h): this file binds
// the LTC tables, says how the library reads a light and a table (its host bridge), and loops
// over the lights. Include after shading.glsl (and, in the lighting pass,
// lighting_common.glsl), with RTPBR_LIGHTING_FULL set and a shadow_factor(uint light,
// ivec2 pixel) defined.

layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_1) uniform sampler2D lut_ltc_ggx_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_GGX_2) uniform sampler2D lut_ltc_ggx_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_1) uniform sampler2D lut_ltc_beckmann_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_BECKMANN_2) uniform sampler2D lut_ltc_beckmann_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_DISNEY_1) uniform sampler2D lut_ltc_disney_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_DISNEY_2) uniform sampler2D lut_ltc_disney_2;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_SHEEN_1) uniform sampler2D lut_ltc_sheen_1;
layout(set = 0, binding = RTPBR_BINDING_LUT_LTC_SHEEN_2) uniform sampler2D lut_ltc_sheen_2;
#ifndef RTPBR_LIGHTING_TEXTURED
#define RTPBR_LIGHTING_TEXTURED RTPBR_LIGHTING_SPHERES // (the forward pass: its spheres' variant)
#endif
#ifndef RTPBR_LIGHTING_TUBES
#define RTPBR_LIGHTING_TUBES RTPBR_LIGHTING_SPHERES // (the forward pass: its spheres' variant)
#endif
#if RTPBR_LIGHTING_TEXTURED
layout(set = 0, binding = RTPBR_BINDING_LIGHT_TEXTURES) uniform sampler2DArray light_textures;
#endif

// The LTC tables of the NDF this variant is built for.
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
#define LUT_LTC_1 lut_ltc_beckmann_1
#define LUT_LTC_2 lut_ltc_beckmann_2
#else
#define LUT_LTC_1 lut_ltc_ggx_1
#define LUT_LTC_2 lut_ltc_ggx_2
#endif

// A field of light i's record (RTPBR_LIGHT_FIELDS): from the storage buffer, or in the lighting
// pass on a CPU device, for a frame of at most RTPBR_UNIFORM_LIGHTS_MAX lights, from the same
// records bound as a uniform buffer (RTPBR_SPEC_LIGHTING_UNIFORM_LIGHTS, set by
// passes/lighting.c; rtpbr_shared.h, RTPBR_BINDING_LIGHT_LIGHTS_UNIFORM): on lavapipe a uniform
// buffer's read at an index that varies is a load per SIMD lane, a storage buffer's a loop over
// the lanes with a branch in each trip (docs/performance.md, 22 and 31). The GPU's code (false,
// the default) reads the storage buffer as before.
#ifdef RTPBR_SHADE_ALL_LIGHTS
#define LIGHT(i, field) lights[i].field
#else
layout(constant_id = RTPBR_SPEC_LIGHTING_UNIFORM_LIGHTS) const bool shade_uniform_lights = false;
layout(set = 0, binding = RTPBR_BINDING_LIGHT_LIGHTS_UNIFORM, std140) uniform LightsUniform {
    Light lights_uniform[RTPBR_UNIFORM_LIGHTS_MAX];
};
#define LIGHT(i, field) (shade_uniform_lights ? lights_uniform[i].field : lights[i].field)
#endif

// bench/shader-stats' per-light builds over textured quads (not a record's shape: a polygon
// with a texture).
#define RTPBR_STATS_SHAPE_TEXTURED_QUAD 16
// and over tube (capsule) lights (area_light.h's AreaLight_AddTube; its ends and radius read
// from vertices[0], vertices[1], as the engine's tube records: RTPBR_LIGHT_FIELDS).
#define RTPBR_STATS_SHAPE_TUBE 17

// The library's host bridge (area_light.h): lights from the lights buffer, tables from the
// bindings above (a polygon's vertex count below, after the specialization constants).
// RTPBR_STATS_FIXED_LIGHTS (bench/shader-stats) makes every light a quad.
// On a CPU device (RTPBR_SPEC_LIGHTING_CPU, set by passes/lighting.c: lavapipe) the full
// variant reads a polygon's first four vertices once per light (shade_light_vertices, before
// AreaLight_Add) and its lobes' walks take them from there: on lavapipe each storage-buffer read
// is a loop over the SIMD lanes, and the full evaluation walks the polygon once per lobe (up to
// five times; docs/performance.md, 21). On a GPU a uniform light's read is a scalar load, and
// vertices held through the lobes would cost registers: there (false, the default) each walk
// reads its own.
layout(constant_id = RTPBR_SPEC_LIGHTING_CPU) const bool shade_cpu = false;
#if RTPBR_LIGHTING_FULL && !defined(RTPBR_SHADE_ALL_LIGHTS) && !defined(RTPBR_STATS_FIXED_LIGHTS)
vec3 shade_v0, shade_v1, shade_v2, shade_v3; // light shade_light_vertices(i)'s vertices 0 to 3
void shade_light_vertices(uint i)
{
    if (shade_cpu) { // (a triangle's vertex 3 is read but never used: the record has 8 slots)
        shade_v0 = LIGHT(i, vertices[0]).xyz;
        shade_v1 = LIGHT(i, vertices[1]).xyz;
        shade_v2 = LIGHT(i, vertices[2]).xyz;
        shade_v3 = LIGHT(i, vertices[3]).xyz;
    }
}
vec3 Host_LightVertex(uint i, uint k)
{
    if (shade_cpu && k < 4u) return k == 0u ? shade_v0 : k == 1u ? shade_v1 : k == 2u ? shade_v2 : shade_v3;
    return LIGHT(i, vertices[k]).xyz;
}
#else
void shade_light_vertices(uint i) {}
vec3 Host_LightVertex(uint i, uint k) { return LIGHT(i, vertices[k]).xyz; }
#endif
vec4 Host_LightPlane(uint i) { return LIGHT(i, plane); }
vec4 Host_LightSphere(uint i) { return LIGHT(i, sphere); }
bool Host_LightTwoSided(uint i) { return LIGHT(i, two_sided) != 0.0f; }
vec3 Host_LightRadiance(uint i) { return LIGHT(i, radiance); }
// Punctual lights (shaderlib punctual.h; the record's layout: rtpbr_shared.h, RTPBR_LIGHT_FIELDS).
uint Host_LightShape(uint i)
{
#ifdef RTPBR_STATS_FIXED_LIGHTS
    return 0u; // the per-quad-light figures
#else
    return LIGHT(i, shape);
#endif
}
vec4 Host_LightPosition(uint i) { return LIGHT(i, vertices[0]); }
vec3 Host_LightDirection(uint i) { return LIGHT(i, vertices[1]).xyz; }
vec2 Host_LightSpotCone(uint i) { return LIGHT(i, vertices[2]).xy; }
// A disk's half-axes (RTPBR_LIGHT_FIELDS, DISK: vertices[1], vertices[2]).
vec3 Host_LightDiskAxis(uint i, uint k) { return LIGHT(i, vertices[1u + k]).xyz; }
#if RTPBR_LIGHTING_TEXTURED
// A textured quad's emission factor at lookup = (s, t, footprint) (area_light.h): its chain's
// level k is blurred over 2^k texels (rtpbr_shared.h, RTPBR_BINDING_LIGHT_TEXTURES), so the
// footprint's radius of footprint x size texels reads lod log2 of it.
vec3 Host_LightTexture(uint i, vec3 lookup)
{
    float lod = clamp(log2(max(lookup.z * float(RTPBR_SHADER_LIGHT_TEXTURE_SIZE), 1e-6f)), 0.0f,
                      float(RTPBR_SHADER_LIGHT_TEXTURE_LEVELS - 1));
    return textureLod(light_textures, vec3(lookup.xy, float(LIGHT(i, texture) - 1u)), lod).rgb;
}
#endif
ivec2 shade_pixel; // the pixel shade_lights shades (for its shadow ratios)
#ifdef RTPBR_SHADE_ALL_LIGHTS
vec3 Host_LightVisibility(uint i) { return vec3(shadow_factor(i, shade_pixel)); }
#else
// Whether the frame has shadows (false: no visibility code; rtpbr_shared.h,
// RTPBR_SPEC_LIGHTING_SHADOWS, set by passes/lighting.c).
layout(constant_id = RTPBR_SPEC_LIGHTING_SHADOWS) const bool shade_shadows = true;
uvec4 shade_slots_lo, shade_slots_hi; // its tile's shadow slots (shadow_ratio.glsl), loaded once
vec3 Host_LightVisibility(uint i)
{
    return shade_shadows ? vec3(shadow_factor_slots(i, shade_pixel, shade_slots_lo, shade_slots_hi)) : vec3(1.0f);
}
#endif
vec4 Host_TableLtc1(int table, vec2 uv)
{
    if (table == RTPBR_TABLE_LTC_DISNEY_DIFFUSE) return textureLod(lut_ltc_disney_1, uv, 0.0f);
    if (table == RTPBR_TABLE_LTC_SHEEN) return textureLod(lut_ltc_sheen_1, uv, 0.0f);
    return textureLod(LUT_LTC_1, uv, 0.0f);
}
vec4 Host_TableLtc2(int table, vec2 uv)
{
    if (table == RTPBR_TABLE_LTC_DISNEY_DIFFUSE) return textureLod(lut_ltc_disney_2, uv, 0.0f);
    if (table == RTPBR_TABLE_LTC_SHEEN) return textureLod(lut_ltc_sheen_2, uv, 0.0f);
    return textureLod(LUT_LTC_2, uv, 0.0f);
}

// What the frame's lights need, set per frame by the lighting pass's pipelines
// (passes/lighting.c, rtpbr_lighting_needs; the defaults: anything, as the forward
// pass): the most vertices of a polygon (3 .. RTPBR_SHADER_MAX_POLYGON_VERTICES; the walk's
// code for more is compiled out: area_light.h, RTPBR_AREA_LIGHT_MAX_VERTICES), and whether a
// punctual light is among them (false: the punctual lights' loop compiled out). On lavapipe
// that code costs wherever it is, run or not: a loop runs its first trip, and both sides of a
// branch run, for every pixel (docs/performance.md, 20).
layout(constant_id = RTPBR_SPEC_LIGHTING_MAX_VERTICES) const uint shade_max_vertices = RTPBR_SHADER_MAX_POLYGON_VERTICES;
layout(constant_id = RTPBR_SPEC_LIGHTING_PUNCTUAL) const bool shade_punctual = true;
// Whether the streak estimate runs (false: the pipeline of RTPBR_TILE_CLASS_BASIC_NO_STREAK,
// tiles where the cull proved it changes nothing; rtpbr_shared.h, RTPBR_SPEC_LIGHTING_STREAK).
layout(constant_id = RTPBR_SPEC_LIGHTING_STREAK) const bool shade_streak = true;
uint Host_LightVertexCount(uint i)
{
#ifdef RTPBR_STATS_FIXED_LIGHTS
    return 4u;
#else
    // A frame whose polygons have at most 3 vertices has triangles only (a polygon has 3 at
    // least): its count a constant, the record's read and the walk's tests on it folded away
    // (lavapipe: every read of a light's record is a load per SIMD lane; docs/performance.md, 32).
    return shade_max_vertices <= 3u ? 3u : LIGHT(i, vertex_count);
#endif
}
#define RTPBR_AREA_LIGHT_MAX_VERTICES shade_max_vertices
#define RTPBR_AREA_LIGHT_STREAK_ON (shade_streak ? 1 : 0)
#define RTPBR_AREA_LIGHT_FULL RTPBR_LIGHTING_FULL
#define RTPBR_AREA_LIGHT_PUNCTUAL 2 // punctual lights summed first, apart (area_light.h)
#define RTPBR_AREA_LIGHT_SPHERES 1  // AreaLight_AddSphere for the spheres' mask (RTPBR_LIGHTING_SPHERES)
#define RTPBR_AREA_LIGHT_DISKS 1    // AreaLight_AddDisk for the disks' mask
#define RTPBR_AREA_LIGHT_ROUND_DISKS 1 // (round disks' closed form; ellipses, disk_radius2, the cone's)
#define RTPBR_AREA_LIGHT_TEXTURED RTPBR_LIGHTING_TEXTURED // AreaLight_AddTexturedQuad for the textured quads' mask
// The specular lobe's inverse horizon mass once per point in the basic variant over polygons
// alone; per light where the other shapes' code holds the loop's registers (the basic spheres',
// textured and tubes' variants went from 96 to 104 VGPRs on navi21 with it: tests/shader-stats)
#define RTPBR_AREA_LIGHT_INV_MASS_PER_POINT (!RTPBR_LIGHTING_FULL && !RTPBR_LIGHTING_SPHERES)
// A polygon's first four edges walked without a loop (lavapipe), but every edge in one loop in
// the full variants over textured quads or tubes (registers: those spilled 2 to 4 SGPRs on
// navi21 and gfx1100 without it; tests/shader-stats)
#define RTPBR_AREA_LIGHT_WALK_LOOP (RTPBR_LIGHTING_FULL && (RTPBR_LIGHTING_TEXTURED || RTPBR_LIGHTING_TUBES))
#if RTPBR_LIGHTING_TUBES || (defined(RTPBR_STATS_FIXED_SHAPE) && RTPBR_STATS_FIXED_SHAPE == RTPBR_STATS_SHAPE_TUBE)
#define RTPBR_AREA_LIGHT_TUBES 1 // AreaLight_AddTube for the tubes' mask (RTPBR_LIGHTING_TUBES)
// (RTPBR_AREA_LIGHT_TUBE_UNROLL: a tube's three parts in a loop, one copy of the evaluation
// for a GPU's registers; unrolled in the _cpu variants a CPU device runs, engine/shaders/meson.build)
// A tube's ends' centres and radius (RTPBR_LIGHT_FIELDS, TUBE: vertices[0], vertices[1]).
vec4 Host_LightTube(uint i, uint k) { return LIGHT(i, vertices[k]); }
#define RTPBR_AREA_LIGHT_TUBE_RANGE 1 // a tube's range window (RTPBR_LIGHT_FIELDS, TUBE: vertices[3].w)
float Host_LightTubeInvRange2(uint i) { return LIGHT(i, vertices[3]).w; }
#endif
// A sphere's or a disk's polygons where the horizon cuts it walked in loops on a CPU device,
// unrolled under a branch on a GPU (on lavapipe both sides of a branch run, a loop's trips only
// as many as some lane needs, one at least; docs/performance.md, 24)
#define RTPBR_AREA_LIGHT_CLIP_LOOPS (shade_cpu ? 1 : 0)
// A sphere the horizon cuts: clipped exactly in the basic variant; the full variant's registers
// take the sphere proxy (area_light.h; no spills: tests/shader-stats)
#define RTPBR_AREA_LIGHT_SPHERE_CLIP (!RTPBR_LIGHTING_FULL)
// The forward pass (every light in one shader): the sheen lobe's LTC row read per light, not
// kept through the loops (registers: its sphere variants spilled 2 VGPRs on gfx1100 with it kept;
// the lighting pass keeps it: read per light there, a sphere variant spilled 2 SGPRs)
#ifdef RTPBR_SHADE_ALL_LIGHTS
#define RTPBR_AREA_LIGHT_SHEEN_REFETCH 1
#endif
#define RTPBR_UNROLL [[unroll]]
#define RTPBR_DONT_UNROLL [[dont_unroll]]
#include "rtpbr/area_light.h"
#if RTPBR_LIGHT_SHAPE_SPHERE <= RTPBR_PUNCTUAL_DIRECTIONAL
#error "a sphere's shape value must differ from every punctual light's"
#endif
#if RTPBR_PUNCTUAL_POINT != RTPBR_LIGHT_SHAPE_POINT || RTPBR_PUNCTUAL_SPOT != RTPBR_LIGHT_SHAPE_SPOT || \
    RTPBR_PUNCTUAL_DIRECTIONAL != RTPBR_LIGHT_SHAPE_DIRECTIONAL || RTPBR_LIGHT_SHAPE_POLYGON != 0
#error "light shapes differ between rtpbr_shared.h and shaderlib/rtpbr/punctual.h"
#endif

// Reflected radiance from the tile's lights (those of the tile's mask in the lighting pass;
// with RTPBR_SHADE_ALL_LIGHTS every light of the frame: the forward pass's surfaces are not in
// the G-buffer the masks were culled by), each weighted by its shadow ratio
// shadow_factor(i, pixel) (shadow_ratio.glsl, or 1), added to result (the emission): punctual
// lights first, straight into it (AreaLight_AddPunctual), then the polygons (AreaLight_Add),
// the spheres (AreaLight_AddSphere), the disks (AreaLight_AddDisk), the textured quads
// (AreaLight_AddTexturedQuad) and the tubes (AreaLight_AddTube), their sum held to the energy bound (registers:
// docs/performance.md, 11).
void shade_lights(vec3 P, vec3 N, vec3 V, ShadingSurface s, uint tile, ivec2 pixel, inout vec3 result)
{
    shade_pixel = pixel;
#ifndef RTPBR_SHADE_ALL_LIGHTS
    shade_slots_lo = shade_slots_hi = uvec4(RTPBR_TILE_NO_LIGHT);
    if (shade_shadows && frame.shadow_light_count != 0u) shadow_slots(tile, shade_slots_lo, shade_slots_hi);
#endif
    AreaLightSum acc = AreaLight_SumBegin();
#ifdef RTPBR_STATS_FIXED_LIGHTS
#if defined(RTPBR_STATS_FIXED_SHAPE) && RTPBR_STATS_FIXED_SHAPE == RTPBR_LIGHT_SHAPE_SPHERE // every light a sphere
    AreaLightPixel px = AreaLight_Begin(s, N, V);
    [[unroll]] for (uint i = 0u; i < uint(RTPBR_STATS_FIXED_LIGHTS); ++i)
        AreaLight_AddSphere(px, acc, s, P, N, i);
#elif defined(RTPBR_STATS_FIXED_SHAPE) && RTPBR_STATS_FIXED_SHAPE == RTPBR_LIGHT_SHAPE_DISK // every light a disk
    AreaLightPixel px = AreaLight_Begin(s, N, V);
    [[unroll]] for (uint i = 0u; i < uint(RTPBR_STATS_FIXED_LIGHTS); ++i)
        AreaLight_AddDisk(px, acc, s, P, N, i);
#elif defined(RTPBR_STATS_FIXED_SHAPE) && RTPBR_STATS_FIXED_SHAPE == RTPBR_STATS_SHAPE_TEXTURED_QUAD // every light a textured quad
    AreaLightPixel px = AreaLight_Begin(s, N, V);
    [[unroll]] for (uint i = 0u; i < uint(RTPBR_STATS_FIXED_LIGHTS); ++i)
        AreaLight_AddPolygonShape(px, acc, s, P, N, i, true);
#elif defined(RTPBR_STATS_FIXED_SHAPE) && RTPBR_STATS_FIXED_SHAPE == RTPBR_STATS_SHAPE_TUBE // every light a tube
    AreaLightPixel px = AreaLight_Begin(s, N, V);
    [[unroll]] for (uint i = 0u; i < uint(RTPBR_STATS_FIXED_LIGHTS); ++i)
        AreaLight_AddTube(px, acc, s, P, N, i);
#elif defined(RTPBR_STATS_FIXED_SHAPE) // every light a punctual light of this shape (bench/shader-stats)
    mat3 frame3 = LTC_Frame(N, V);
    [[unroll]] for (uint i = 0u; i < uint(RTPBR_STATS_FIXED_LIGHTS); ++i)
        AreaLight_AddPunctual(result, s, frame3, P, i, uint(RTPBR_STATS_FIXED_SHAPE));
    AreaLightPixel px = AreaLight_Begin(s, N, V);
#else
    AreaLightPixel px = AreaLight_Begin(s, N, V);
    [[unroll]] for (uint i = 0u; i < uint(RTPBR_STATS_FIXED_LIGHTS); ++i)
        AreaLight_Add(px, acc, s, P, N, i);
#endif
#elif defined(RTPBR_SHADE_ALL_LIGHTS)
    // Punctual lights first (the whole BRDF's terms live), then the polygons (their per-point
    // state live): registers, docs/performance.md, 11.
    mat3 frame3 = LTC_Frame(N, V);
    for (uint i = 0u; i < frame.light_count; ++i) {
        uint shape = LIGHT(i, shape);
        if (shape != uint(RTPBR_LIGHT_SHAPE_POLYGON) && shape != uint(RTPBR_LIGHT_SHAPE_SPHERE) &&
            shape != uint(RTPBR_LIGHT_SHAPE_DISK) && shape != uint(RTPBR_LIGHT_SHAPE_TUBE))
            AreaLight_AddPunctual(result, s, frame3, P, i, shape);
    }
    AreaLightPixel px = AreaLight_Begin(s, N, V);
    for (uint i = 0u; i < frame.light_count; ++i)
        if (LIGHT(i, shape) == uint(RTPBR_LIGHT_SHAPE_POLYGON) && LIGHT(i, texture) == 0u) AreaLight_Add(px, acc, s, P, N, i);
#if RTPBR_LIGHTING_SPHERES
    for (uint i = 0u; i < frame.light_count; ++i)
        if (LIGHT(i, shape) == uint(RTPBR_LIGHT_SHAPE_SPHERE)) AreaLight_AddSphere(px, acc, s, P, N, i);
    for (uint i = 0u; i < frame.light_count; ++i)
        if (LIGHT(i, shape) == uint(RTPBR_LIGHT_SHAPE_DISK)) AreaLight_AddDisk(px, acc, s, P, N, i);
#if RTPBR_LIGHTING_TUBES
    for (uint i = 0u; i < frame.light_count; ++i)
        if (LIGHT(i, shape) == uint(RTPBR_LIGHT_SHAPE_TUBE)) AreaLight_AddTube(px, acc, s, P, N, i);
#endif
#if RTPBR_LIGHTING_TEXTURED
    for (uint i = 0u; i < frame.light_count; ++i)
        if (LIGHT(i, texture) != 0u) AreaLight_AddTexturedQuad(px, acc, s, P, N, i);
#endif
#endif
#else
    // The tile's masks (cull.comp): its punctual lights', then its polygons', its spheres', its
    // disks', its textured quads' and its tubes'; in each, only the words that the kind's summary
    // word marks (the others are zero).
    uint maskBase = tile * uint(RTPBR_TILE_MASK_STRIDE);
    uint summaryBase = maskBase + uint(RTPBR_TILE_MASK_SUMMARY);
    mat3 frame3 = LTC_Frame(N, V);
    if (shade_punctual) { // (a frame without punctual lights: compiled out)
        for (uint words = tile_masks[summaryBase + 1u]; words != 0u; words &= words - 1u) {
            uint word = uint(findLSB(words));
            for (uint bits = tile_masks[maskBase + uint(RTPBR_TILE_MASK_WORDS) + word]; bits != 0u; bits &= bits - 1u) {
                uint i = word * 32u + uint(findLSB(bits));
                AreaLight_AddPunctual(result, s, frame3, P, i, LIGHT(i, shape));
            }
        }
    }
    AreaLightPixel px = AreaLight_Begin(s, N, V);
#if RTPBR_LIGHTING_TEXTURED && RTPBR_LIGHTING_FULL
    // The full variant shades its textured quads in the polygons' loop (one copy of the
    // evaluation, the texel read at its end where texturedLight: a loop of their own spilled 3
    // VGPRs on gfx1100); the basic variant in a loop of their own, below.
    for (uint words = tile_masks[summaryBase] | tile_masks[summaryBase + 4u]; words != 0u; words &= words - 1u) {
        uint word = uint(findLSB(words));
        uint textured = tile_masks[maskBase + 4u * uint(RTPBR_TILE_MASK_WORDS) + word];
        for (uint bits = tile_masks[maskBase + word] | textured; bits != 0u; bits &= bits - 1u) {
            uint b = uint(findLSB(bits));
            shade_light_vertices(word * 32u + b);
            AreaLight_AddPolygonShape(px, acc, s, P, N, word * 32u + b, ((textured >> b) & 1u) != 0u);
        }
    }
#else
    for (uint words = tile_masks[summaryBase]; words != 0u; words &= words - 1u) {
        uint word = uint(findLSB(words));
        for (uint bits = tile_masks[maskBase + word]; bits != 0u; bits &= bits - 1u) {
            uint i = word * 32u + uint(findLSB(bits));
            shade_light_vertices(i);
            AreaLight_Add(px, acc, s, P, N, i);
        }
    }
#endif
#if RTPBR_LIGHTING_SPHERES
    // Spheres and disks: a mask and a loop each, so that each loop compiles with its kind
    // fixed (one loop choosing at run time took the basic variant's registers from 96 to 104
    // on navi21, and lavapipe ran both kinds' code for every light).
    for (uint words = tile_masks[summaryBase + 2u]; words != 0u; words &= words - 1u) {
        uint word = uint(findLSB(words));
        for (uint bits = tile_masks[maskBase + 2u * uint(RTPBR_TILE_MASK_WORDS) + word]; bits != 0u; bits &= bits - 1u)
            AreaLight_AddSphere(px, acc, s, P, N, word * 32u + uint(findLSB(bits)));
    }
    for (uint words = tile_masks[summaryBase + 3u]; words != 0u; words &= words - 1u) {
        uint word = uint(findLSB(words));
        for (uint bits = tile_masks[maskBase + 3u * uint(RTPBR_TILE_MASK_WORDS) + word]; bits != 0u; bits &= bits - 1u)
            AreaLight_AddDisk(px, acc, s, P, N, word * 32u + uint(findLSB(bits)));
    }
#if RTPBR_LIGHTING_TEXTURED && !RTPBR_LIGHTING_FULL
    for (uint words = tile_masks[summaryBase + 4u]; words != 0u; words &= words - 1u) {
        uint word = uint(findLSB(words));
        for (uint bits = tile_masks[maskBase + 4u * uint(RTPBR_TILE_MASK_WORDS) + word]; bits != 0u; bits &= bits - 1u)
            AreaLight_AddTexturedQuad(px, acc, s, P, N, word * 32u + uint(findLSB(bits)));
    }
#endif
#if RTPBR_LIGHTING_TUBES
    for (uint words = tile_masks[summaryBase + 5u]; words != 0u; words &= words - 1u) {
        uint word = uint(findLSB(words));
        for (uint bits = tile_masks[maskBase + 5u * uint(RTPBR_TILE_MASK_WORDS) + word]; bits != 0u; bits &= bits - 1u)
            AreaLight_AddTube(px, acc, s, P, N, word * 32u + uint(findLSB(bits)));
    }
#endif
#endif
#endif
    result += AreaLight_End(px, acc, s, P);
}
