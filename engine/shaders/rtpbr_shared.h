// Constants shared by the engine's C code and its GLSL shaders (included by both).
// Only #defines live here: layouts of the structs below are spelled out twice, in
// engine/src/internal.h (C) and in the shaders, next to a comment pointing here.
#ifndef RTPBR_SHARED_H
#define RTPBR_SHARED_H

// Lighting: one compute workgroup shades one screen tile.
#define RTPBR_TILE_SIZE 16

// Most lights in a scene (also RTPBR_MAX_LIGHTS in rtpbr.h): the size of a tile's light mask.
#define RTPBR_SHADER_MAX_LIGHTS 1024

// Lower clamp of perceptual roughness (also RTPBR_MIN_ROUGHNESS in rtpbr.h).
#define RTPBR_SHADER_MIN_ROUGHNESS 0.045

// Largest polygon a light may have (also RTPBR_MAX_POLYGON_VERTICES in rtpbr.h).
#define RTPBR_SHADER_MAX_POLYGON_VERTICES 8

// G-buffer pass, descriptor set 0.
#define RTPBR_BINDING_GBUFFER_FRAME 0     // uniform: rtpbr_shader_frame
#define RTPBR_BINDING_GBUFFER_MATERIALS 1 // storage: rtpbr_shader_material[]

// G-buffer pass, descriptor set 1: one set per material.
#define RTPBR_BINDING_TEXTURE_BASE_COLOR 0
#define RTPBR_BINDING_TEXTURE_METALLIC_ROUGHNESS 1
#define RTPBR_BINDING_TEXTURE_EMISSION 2
#define RTPBR_BINDING_TEXTURE_NORMAL 3
#define RTPBR_MATERIAL_TEXTURE_COUNT 4

// Lighting pass, descriptor set 0.
#define RTPBR_BINDING_LIGHT_FRAME 0       // uniform: rtpbr_shader_frame
#define RTPBR_BINDING_LIGHT_LIGHTS 1      // storage: rtpbr_shader_light[]
#define RTPBR_BINDING_LIGHT_GBUFFER0 2    // base colour rgb, metallic
#define RTPBR_BINDING_LIGHT_GBUFFER1 3    // world normal xyz, perceptual roughness
#define RTPBR_BINDING_LIGHT_GBUFFER2 4    // emitted radiance rgb, material index
#define RTPBR_BINDING_LIGHT_GBUFFER3 5    // anisotropy direction (world), 0
#define RTPBR_BINDING_LIGHT_DEPTH 6       // depth (0 near .. 1 far)
#define RTPBR_BINDING_LIGHT_RADIANCE 7    // output, rgba32f storage image
// Lookup tables (combined image samplers, linear filtering, clamp to edge).
#define RTPBR_BINDING_LUT_LTC_GGX_1 8      // M^-1 of the GGX LTC fit
#define RTPBR_BINDING_LUT_LTC_GGX_2 9      // norm, fresnel, 0, sphere form factor
#define RTPBR_BINDING_LUT_LTC_BECKMANN_1 10
#define RTPBR_BINDING_LUT_LTC_BECKMANN_2 11
#define RTPBR_BINDING_LUT_KC_E 12          // Kulla-Conty E(mu, r)
#define RTPBR_BINDING_LUT_KC_EAVG 13       // Kulla-Conty E_avg(r)
#define RTPBR_BINDING_LUT_KC_EF 14         // 3D: E_F(mu, r, eta) and E(mu, r) (engine/src/luts.c)
#define RTPBR_BINDING_LUT_KC_EFAVG 15      // E_F_avg(r, eta)
#define RTPBR_BINDING_LUT_LTC_DISNEY_1 16  // M^-1 of the Burley diffuse LTC fit
#define RTPBR_BINDING_LUT_LTC_DISNEY_2 17  // norm, 0, 0, sphere form factor
#define RTPBR_BINDING_LUT_SHEEN_E 18       // KHR sheen albedo E_sheen(mu, r) (Charlie), r channel
#define RTPBR_BINDING_LUT_LTC_SHEEN_1 19   // M^-1 of the sheen LTC fit
#define RTPBR_BINDING_LUT_LTC_SHEEN_2 20   // norm, 0, 0, sphere form factor
#define RTPBR_LUT_COUNT 13                 // LUT bindings 8 .. 20, in this order
#define RTPBR_BINDING_LIGHT_MATERIALS 21   // storage: rtpbr_shader_material[]
#define RTPBR_BINDING_LIGHT_TILE_MASKS 22  // storage: per-tile light masks (cull.comp)
#define RTPBR_BINDING_LIGHT_TILE_LISTS 23  // storage: per-class tile queues (cull.comp)
#define RTPBR_LIGHTING_BINDING_COUNT 25 // with RTPBR_BINDING_LIGHT_SHADOW_RATIO (24, below)

// Light culling (cull.comp): one invocation per tile, RTPBR_CULL_GROUP^2 tiles per workgroup.
#define RTPBR_CULL_GROUP 8
#define RTPBR_TILE_MASK_WORDS (RTPBR_SHADER_MAX_LIGHTS / 32)
// Tile classes: each has its lighting variant, dispatched indirectly over its tile queue.
#define RTPBR_TILE_CLASS_EMPTY 0 // no surface pixel or no light left: emission and background
#define RTPBR_TILE_CLASS_BASIC 1 // metallic-roughness without clear coat, sheen, anisotropy
#define RTPBR_TILE_CLASS_FULL 2  // any material
#define RTPBR_TILE_CLASS_COUNT 3

// rtpbr_shader_material.coat.z: the material model.
#define RTPBR_SHADER_MODEL_METALLIC_ROUGHNESS 0
#define RTPBR_SHADER_MODEL_DISNEY 1

// Supersampling resolve (resolve.comp), descriptor set 0.
#define RTPBR_BINDING_RESOLVE_SOURCE 0    // rgba32f storage image, (factor W) x (factor H)
#define RTPBR_BINDING_RESOLVE_TARGET 1    // rgba32f storage image, W x H

// Tone-mapping pass, descriptor set 0.
#define RTPBR_BINDING_TONEMAP_RADIANCE 0   // rgba32f storage image, read only

// Tone-mapping operators (values of rtpbr_tonemap in rtpbr.h minus the default).
#define RTPBR_TONEMAP_OP_ACES 1
#define RTPBR_TONEMAP_OP_REINHARD 2
#define RTPBR_TONEMAP_OP_LINEAR 3

// Output encodings of the tone-mapping pass.
#define RTPBR_ENCODE_NONE 0 // sRGB attachment (hardware encodes) or float target
#define RTPBR_ENCODE_SRGB 1 // UNORM attachment: the shader applies the sRGB curve

// Area-light shadows (issue 17; engine/src/shadow.c, shaders/shadow*.comp, bvh.glsl).
// Lights 0 .. RTPBR_SHADER_MAX_SHADOWED_LIGHTS - 1 of a scene cast shadows (also
// RTPBR_MAX_SHADOWED_LIGHTS in rtpbr.h); the others are unshadowed.
#define RTPBR_SHADER_MAX_SHADOWED_LIGHTS 8
// Deepest BVH node (root: depth 0) = the traversal stack's size.
#define RTPBR_BVH_MAX_DEPTH 32
// Lighting pass: the shadow ratios, a sampler2DArray (layer = light index), read with texelFetch.
#define RTPBR_BINDING_LIGHT_SHADOW_RATIO 24
// Shadow passes, descriptor set 0 (shadow.comp traces, shadow_denoise.comp filters).
#define RTPBR_BINDING_SHADOW_FRAME 0          // uniform: rtpbr_shader_frame
#define RTPBR_BINDING_SHADOW_LIGHTS 1         // storage: rtpbr_shader_light[]
#define RTPBR_BINDING_SHADOW_DEPTH 2          // depth (0 near .. 1 far)
#define RTPBR_BINDING_SHADOW_NORMAL 3         // G-buffer 1: world normal xyz, roughness
#define RTPBR_BINDING_SHADOW_BVH_NODES 4      // storage: rtpbr_shader_bvh_node[]
#define RTPBR_BINDING_SHADOW_BVH_TRIANGLES 5  // storage: rtpbr_shader_bvh_triangle[]
#define RTPBR_BINDING_SHADOW_ESTIMATES 6      // r32ui storage image array: packHalf2x16(shadowed, unshadowed)
#define RTPBR_BINDING_SHADOW_RATIO 7          // r32f storage image array: shadowed / unshadowed
#define RTPBR_SHADOW_BINDING_COUNT 8
#define RTPBR_SHADOW_GROUP_SIZE 8             // 8 x 8 pixels per workgroup

#endif // RTPBR_SHARED_H
