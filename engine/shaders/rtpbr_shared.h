// The contract between the engine's C code and its GLSL shaders, included by both: constants,
// binding numbers, and the layouts of the structs both sides read, each declared once.
#ifndef RTPBR_SHARED_H
#define RTPBR_SHARED_H

// ---------------------------------------------------------------------------------------------
// Declaring a struct once for C and GLSL.
//
// A struct is an X-macro list of fields, FIELDS(F, S) = F(S, TYPE, name, array_suffix) ...,
// with S the C struct's name (passed through for the layout checks), TYPE one of MAT4,
// VEC4, UVEC4, VEC3, UVEC2, FLOAT, UINT and array_suffix empty or [count] (arrays only of
// VEC4, UVEC4 and MAT4, whose std140 and std430 strides agree). GLSL expands the list into a
// block or struct body; C into a struct with the same member names, and
// RTPBR_SHARED_CHECK_LAYOUT asserts at compile time that every member sits where std140 and
// std430 put it (vec4, vec3 and mat4 on 16 bytes, uvec2 on 8) and that the size is a multiple
// of 16, so a field added in the wrong place fails the C build instead of misreading silently.
#if defined(VULKAN) || defined(GL_core_profile) || defined(GL_es_profile)
#define RTPBR_SHARED_GLSL_MAT4 mat4
#define RTPBR_SHARED_GLSL_VEC4 vec4
#define RTPBR_SHARED_GLSL_UVEC4 uvec4
#define RTPBR_SHARED_GLSL_VEC3 vec3
#define RTPBR_SHARED_GLSL_UVEC2 uvec2
#define RTPBR_SHARED_GLSL_FLOAT float
#define RTPBR_SHARED_GLSL_UINT uint
#define RTPBR_SHARED_FIELD(S, type, name, array) RTPBR_SHARED_GLSL_##type name array;
#else
#include <stddef.h>
#include <stdint.h>
#define RTPBR_SHARED_C_MAT4(name, array) float name array[16];
#define RTPBR_SHARED_C_VEC4(name, array) float name array[4];
#define RTPBR_SHARED_C_UVEC4(name, array) uint32_t name array[4];
#define RTPBR_SHARED_C_VEC3(name, array) float name array[3];
#define RTPBR_SHARED_C_UVEC2(name, array) uint32_t name array[2];
#define RTPBR_SHARED_C_FLOAT(name, array) float name array;
#define RTPBR_SHARED_C_UINT(name, array) uint32_t name array;
#define RTPBR_SHARED_FIELD(S, type, name, array) RTPBR_SHARED_C_##type(name, array)
// The base alignment of each type in std140 and std430 (for the types allowed above they agree).
#define RTPBR_SHARED_ALIGN_MAT4 16
#define RTPBR_SHARED_ALIGN_VEC4 16
#define RTPBR_SHARED_ALIGN_UVEC4 16
#define RTPBR_SHARED_ALIGN_VEC3 16
#define RTPBR_SHARED_ALIGN_UVEC2 8
#define RTPBR_SHARED_ALIGN_FLOAT 4
#define RTPBR_SHARED_ALIGN_UINT 4
// Declares the C struct S from its field list.
#define RTPBR_SHARED_STRUCT(S, FIELDS) typedef struct S { FIELDS(RTPBR_SHARED_FIELD, S) } S;
// Compile-time layout checks of a struct declared with RTPBR_SHARED_STRUCT (C only).
#define RTPBR_SHARED_CHECK_FIELD(S, type, name, array)                                           \
    _Static_assert(offsetof(S, name) % RTPBR_SHARED_ALIGN_##type == 0,                           \
                   #S "." #name ": not where std140/std430 put a " #type);
#define RTPBR_SHARED_CHECK_LAYOUT(S, FIELDS)                                                     \
    _Static_assert(sizeof(S) % 16 == 0, #S ": size is not a multiple of 16 bytes");            \
    FIELDS(RTPBR_SHARED_CHECK_FIELD, S)
#endif

// The per-frame uniform block (std140), binding RTPBR_BINDING_*_FRAME of each pass: written once
// per frame by renderer.c, read by every pass (frame.glsl).
#define RTPBR_FRAME_FIELDS(F, S)                                                                  \
    F(S, MAT4, view_proj, )          /* clip from world, column-major */                            \
    F(S, MAT4, inv_view_proj, )      /* world from clip */                                          \
    F(S, VEC4, camera_position, )    /* xyz; w: the background's depth (1; 0: reversed-Z) */        \
    F(S, VEC4, background, )         /* rgb radiance; w unused */                                   \
    F(S, UVEC2, size, )              /* render width, height */                                     \
    F(S, UINT, light_count, )                                                                       \
    F(S, FLOAT, cull_form_factor, )  /* per-tile light culling threshold (cull.comp); < 0: off */  \
    F(S, UINT, tiles_x, )            /* lighting tiles per row */                                   \
    F(S, UINT, tile_capacity, )      /* tiles in the frame: the length of each class's queue */     \
    F(S, UINT, shadow_light_count, ) /* lights 0 .. this - 1 have a shadow ratio; 0: shadows off */ \
    F(S, UINT, extension_textures, ) /* RTPBR_EXTENSION_TEXTURES_* of the scene's materials */

// The material record (std430), an element of the materials buffer (binding
// RTPBR_BINDING_GBUFFER_MATERIALS and RTPBR_BINDING_LIGHT_MATERIALS): written by
// convert_material (engine/src/scene.c) from rtpbr_material_desc, read by gbuffer.frag and,
// through shaderlib/rtpbr/material.h's Material_Resolve, by the lighting passes
// (lighting_common.glsl). Factors as glTF stores them (the resolve applies the rules);
// defaults of the desc already applied.
#define RTPBR_MATERIAL_FIELDS(F, S)                                                                 \
    F(S, VEC3, base_color, )          /* linear RGB (baseColorFactor) */                          \
    F(S, FLOAT, metallic, )                                                                       \
    F(S, VEC3, emission, )            /* emitted radiance */                                      \
    F(S, FLOAT, roughness, )          /* perceptual (the resolve floors it) */                    \
    F(S, VEC3, specular_color, )      /* KHR_materials_specular specularColorFactor */            \
    F(S, FLOAT, ior, )                /* KHR_materials_ior; 0: Fresnel 1 at every angle */        \
    F(S, FLOAT, specular_factor, )    /* KHR_materials_specular specularFactor */                 \
    F(S, FLOAT, normal_scale, )       /* glTF normalTexture.scale */                              \
    F(S, FLOAT, anisotropy_strength, ) /* KHR_materials_anisotropy */                             \
    F(S, FLOAT, anisotropy_rotation, ) /* radians, from the tangent toward the bitangent */       \
    F(S, VEC3, sheen_color_factor, )  /* KHR_materials_sheen sheenColorFactor */                  \
    F(S, FLOAT, sheen_roughness_factor, ) /* KHR_materials_sheen, perceptual */                   \
    F(S, FLOAT, clearcoat_factor, )   /* KHR_materials_clearcoat clearcoatFactor */               \
    F(S, FLOAT, clearcoat_roughness_factor, ) /* KHR clearcoatRoughnessFactor, perceptual */      \
    F(S, UINT, flags, )               /* RTPBR_MATERIAL_FLAG_* */                                 \
    F(S, FLOAT, alpha_cutoff, )       /* RTPBR_MATERIAL_FLAG_ALPHA_MASK: cut where alpha < this */ \
    F(S, FLOAT, disney_subsurface, )  /* Burley 2012 (RTPBR_MATERIAL_FLAG_DISNEY) */              \
    F(S, FLOAT, disney_specular, )                                                                \
    F(S, FLOAT, disney_specular_tint, )                                                           \
    F(S, FLOAT, disney_sheen, )                                                                   \
    F(S, FLOAT, disney_sheen_tint, )                                                              \
    F(S, FLOAT, disney_clearcoat, )                                                               \
    F(S, FLOAT, disney_clearcoat_gloss, )                                                         \
    F(S, FLOAT, disney_anisotropic, )                                                             \
    F(S, FLOAT, alpha, )              /* glTF baseColorFactor.a (MASK and BLEND) */               \
    F(S, UINT, base_color_texture, )  /* 1-based scene texture, 0: none (the shadow rays' alpha) */ \
    F(S, UINT, pad0, )                                                                            \
    F(S, UINT, pad1, )
// Bits of the material record's flags.
#define RTPBR_MATERIAL_FLAG_DOUBLE_SIDED 1u  // drawn and emitting on both sides
#define RTPBR_MATERIAL_FLAG_NORMAL_MAPPED 2u // has a normal texture
#define RTPBR_MATERIAL_FLAG_DISNEY 4u        // Burley's model (else glTF metallic-roughness)
#define RTPBR_MATERIAL_FLAG_CLEARCOAT 8u     // KHR clearcoat_factor > 0
#define RTPBR_MATERIAL_FLAG_SHEEN 16u        // KHR sheen colour not black
#define RTPBR_MATERIAL_FLAG_ANISOTROPY 32u   // KHR anisotropy strength > 0
#define RTPBR_MATERIAL_FLAG_ALPHA_MASK 64u   // glTF alphaMode MASK: cut out below alpha_cutoff
#define RTPBR_MATERIAL_FLAG_ALPHA_BLEND 128u // glTF alphaMode BLEND: the forward pass draws it
// The features only the full lighting variant shades (material_tile_class).
#define RTPBR_MATERIAL_FLAGS_FULL                                                                 \
    (RTPBR_MATERIAL_FLAG_DISNEY | RTPBR_MATERIAL_FLAG_CLEARCOAT | RTPBR_MATERIAL_FLAG_SHEEN |     \
     RTPBR_MATERIAL_FLAG_ANISOTROPY)

// Lighting: one compute workgroup shades one screen tile.
#define RTPBR_TILE_SIZE 16

// Most lights in a scene (also RTPBR_MAX_LIGHTS in rtpbr.h): the size of a tile's light mask.
#define RTPBR_SHADER_MAX_LIGHTS 1024

// Largest polygon a light may have. Must equal RTPBR_MAX_POLYGON_VERTICES (rtpbr.h, the
// source of truth; checked in engine/src/internal.h) and RTPBR_LTC_MAX_VERTICES
// (shaderlib/rtpbr/ltc.h; checked in vertex_limit.glsl, included by lighting.comp).
#define RTPBR_SHADER_MAX_POLYGON_VERTICES 8

// G-buffer pass, descriptor set 0.
#define RTPBR_BINDING_GBUFFER_FRAME 0     // uniform: rtpbr_shader_frame
#define RTPBR_BINDING_GBUFFER_MATERIALS 1 // storage: rtpbr_shader_material[]
#define RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS 2 // storage: rtpbr_shader_texture_transforms[]

// A material's texture slots, one list (X(a, b, name, binding) per slot): the slot's
// descriptor binding in set 1 of the G-buffer pass (RTPBR_BINDING_TEXTURE_*, asserted equal in
// passes/gbuffer.c), its entry in rtpbr_shader_texture_transforms, and the C desc's fields
// name##_texture and name##_texture_transform (rtpbr_material_desc). a, b are passed to X.
#define RTPBR_MATERIAL_TEXTURE_SLOTS(X, a, b)                                                      \
    X(a, b, base_color, 0)                                                                         \
    X(a, b, metallic_roughness, 1)                                                                 \
    X(a, b, emission, 2)                                                                           \
    X(a, b, normal, 3)                                                                             \
    X(a, b, clearcoat, 4)           /* R: x clearcoat (KHR_materials_clearcoat) */                 \
    X(a, b, clearcoat_roughness, 5) /* G: x clearcoat roughness */                                 \
    X(a, b, sheen_color, 6)         /* RGB (sRGB): x sheen colour (KHR_materials_sheen) */         \
    X(a, b, sheen_roughness, 7)     /* A: x sheen roughness */                                     \
    X(a, b, specular, 8)            /* A: x specular (KHR_materials_specular) */                   \
    X(a, b, specular_color, 9)      /* RGB (sRGB): x specular colour */
// G-buffer pass, descriptor set 1: one set per material, one combined image sampler per slot.
#define RTPBR_BINDING_TEXTURE_BASE_COLOR 0
#define RTPBR_BINDING_TEXTURE_METALLIC_ROUGHNESS 1
#define RTPBR_BINDING_TEXTURE_EMISSION 2
#define RTPBR_BINDING_TEXTURE_NORMAL 3
#define RTPBR_BINDING_TEXTURE_CLEARCOAT 4
#define RTPBR_BINDING_TEXTURE_CLEARCOAT_ROUGHNESS 5
#define RTPBR_BINDING_TEXTURE_SHEEN_COLOR 6
#define RTPBR_BINDING_TEXTURE_SHEEN_ROUGHNESS 7
#define RTPBR_BINDING_TEXTURE_SPECULAR 8
#define RTPBR_BINDING_TEXTURE_SPECULAR_COLOR 9
#define RTPBR_MATERIAL_TEXTURE_COUNT 10

// Per material, the G-buffer pass's texture coordinates of each texture slot
// (rtpbr_shader_texture_transforms, gbuffer.vert; written by convert_texture_transforms in
// engine/src/scene.c from the desc's *_texture_transform): the slot's KHR_texture_transform
// as the two rows of its 2x3 matrix, uv' = (dot(row0.xyz, (uv, 1)), dot(row1.xyz, (uv, 1))),
// with row0.w = the texture coordinate set (0 or 1).
#define RTPBR_TEXTURE_TRANSFORM_FIELD(F, S, name, binding) F(S, VEC4, name, [2])
#define RTPBR_TEXTURE_TRANSFORMS_FIELDS(F, S) RTPBR_MATERIAL_TEXTURE_SLOTS(RTPBR_TEXTURE_TRANSFORM_FIELD, F, S)

// The extension textures a scene's materials use (rtpbr_shader_frame.extension_textures, set
// from the scene by renderer.c): the G-buffer pass samples them and writes the attachments
// that carry them (RTPBR_BINDING_LIGHT_GBUFFER4..6) only when the frame says so, and the
// lighting passes read those attachments only then; otherwise the attachments are not
// rendered (no image view) and the factors of the material record apply alone.
#define RTPBR_EXTENSION_TEXTURES_SPECULAR 1u   // specular / specular colour: G-buffer 4
#define RTPBR_EXTENSION_TEXTURES_COAT_SHEEN 2u // clearcoat (+ roughness), sheen colour (+ roughness): 5, 6

// G-buffer pass push constants (std430), one block per draw (rtpbr_shader_draw, gbuffer.vert).
#define RTPBR_DRAW_FIELDS(F, S)                                                                   \
    F(S, MAT4, world_from_object, )                                                                \
    F(S, VEC4, normal_matrix, [3]) /* columns of the inverse-transpose 3x3; w unused */          \
    F(S, UINT, material, )         /* index into the materials buffer */                          \
    F(S, UINT, pad0, )                                                                             \
    F(S, UINT, pad1, )                                                                             \
    F(S, UINT, pad2, )

// Lighting pass, descriptor set 0.
#define RTPBR_BINDING_LIGHT_FRAME 0       // uniform: rtpbr_shader_frame
#define RTPBR_BINDING_LIGHT_LIGHTS 1      // storage: rtpbr_shader_light[]
#define RTPBR_BINDING_LIGHT_GBUFFER0 2    // base colour rgb, metallic
#define RTPBR_BINDING_LIGHT_GBUFFER1 3    // world normal xyz, perceptual roughness
#define RTPBR_BINDING_LIGHT_GBUFFER2 4    // emitted radiance rgb, material index
#define RTPBR_BINDING_LIGHT_GBUFFER3 5    // anisotropy direction (world), 0
// (G-buffers 4 to 6, the extension textures' per-pixel values, are bindings 25 to 27 below)
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
#define RTPBR_LIGHTING_BINDING_COUNT 30 // with RTPBR_BINDING_LIGHT_SHADOW_RATIO (24), GBUFFER4..6, LIGHT_TEXTURES and LIGHTS_UNIFORM (below)

// One light, the std430 element of the lights buffer (RTPBR_BINDING_LIGHT_LIGHTS,
// RTPBR_BINDING_SHADOW_LIGHTS; rtpbr_shader_light, light.glsl): written by engine/src/scene.c.
// A polygon (shape RTPBR_LIGHT_SHAPE_POLYGON): vertices[k].w is the area of the fan polygon
// v0 .. vk, the triangles (v0, vj, vj+1) for 1 <= j < k (0 for k <= 1; the sum of every fan
// triangle at k = vertex_count - 1), summed from the light's facts
// (rtpbr_gltf_polygon_facts.fan_area): the Monte Carlo and shadow passes pick a fan triangle
// by area from it. area is the polygon's (Newell's normal, the facts').
// A punctual light (shape POINT, SPOT, DIRECTIONAL; vertex_count 0, area 0, two_sided 1,
// plane (0, 0, 0, 1)): vertices[0] = (position, 1 / range^2, 0 without a range),
// vertices[1] = (the unit direction the light travels, 0), vertices[2] = (cos of the spot's
// outer cone, 1 / max(cos inner - cos outer, 1e-3), 0, 0) (shaderlib/rtpbr/punctual.h),
// radiance = its intensity (candela; directional: lux), sphere = (position, range) or an
// infinite radius (RTPBR_LIGHT_INFINITE).
// A sphere (shape SPHERE: a point light with a radius; vertex_count 0, two_sided 1, plane
// (0, 0, 0, 1)): sphere = (centre, radius) exactly (not a bound), vertices[0] = (centre,
// 1 / range^2 or 0), radiance = its uniform radiance (intensity / (pi radius^2)), area = pi
// radius^2 (the cull's form factor); shaded by area_light.h's AreaLight_AddSphere.
// A disk (shape DISK; vertex_count 0): sphere = (centre, radius), vertices[0] = (centre, 0),
// vertices[1], vertices[2] = its orthogonal half-axes u, v (length radius, cross(u, v) along
// the emitting side's normal), plane = (unit normal, -dot(normal, centre)), area = pi radius^2,
// two_sided as a polygon's; in the tiles' disk mask (cull.comp; the spheres' lighting
// variants), shaded by area_light.h's AreaLight_AddDisk.
// A textured quad (shape POLYGON, vertex_count 4, a parallelogram; texture = 1 + its layer of
// the light textures, RTPBR_BINDING_LIGHT_TEXTURES): a polygon whose radiance is times its
// prefiltered texture at (s, t), v0 + s (v1 - v0) + t (v3 - v0); in the tiles' textured mask
// (the spheres' lighting variants), shaded by area_light.h's AreaLight_AddTexturedQuad.
// A tube (shape TUBE: rtpbr_light_type's RTPBR_LIGHT_TUBE; vertex_count 0, two_sided 1, plane
// (0, 0, 0, 1)): vertices[0], vertices[1] = its ends' centres, w the radius r (area_light.h's
// Host_LightTube), vertices[2] = (unit axis, length L), vertices[3] = (centre, 1 / range^2 or 0:
// the range window at the distance from the centre), sphere = (centre, L/2 + r) (a bound),
// radiance = its uniform radiance, area = 4 pi r^2 + 2 pi r L (its surface: the cull's bound and
// the samples' density); in the tiles' tube mask (the spheres' lighting variants), shaded by
// area_light.h's AreaLight_AddTube.
#define RTPBR_LIGHT_FIELDS(F, S)                                                                  \
    F(S, VEC4, vertices, [RTPBR_SHADER_MAX_POLYGON_VERTICES]) /* xyz; w: fan area below vertex k */ \
    F(S, VEC3, radiance, )     /* emitted radiance, rgb (punctual: intensity) */                   \
    F(S, FLOAT, two_sided, )   /* 1: emits on both sides; 0: on the front side (plane normal) */  \
    F(S, VEC4, plane, )        /* unit normal xyz, w = -dot(normal, vertex 0) */                  \
    F(S, VEC4, sphere, )       /* bounding sphere: centre xyz, radius w */                        \
    F(S, UINT, vertex_count, ) /* 3 .. RTPBR_SHADER_MAX_POLYGON_VERTICES; others: 0 */            \
    F(S, FLOAT, area, )                                                                            \
    F(S, UINT, shape, )        /* RTPBR_LIGHT_SHAPE_* (= rtpbr_light_type) */                     \
    F(S, UINT, sun, )          /* 1: a directional light's disk (a far polygon): no distance cull */ \
    F(S, UINT, texture, )      /* a textured quad: 1 + its layer of the light textures; 0: none */ \
    F(S, UINT, reserved0, )    /* (std430: the record's size a multiple of 16 bytes) */           \
    F(S, UVEC2, reserved1, )

// A light's shape (rtpbr_shader_light.shape): the values of rtpbr_light_type (rtpbr.h) and of
// the shader library's RTPBR_PUNCTUAL_* (punctual.h); both checked (internal.h, shade_lights.glsl).
#define RTPBR_LIGHT_SHAPE_POLYGON 0
#define RTPBR_LIGHT_SHAPE_POINT 1
#define RTPBR_LIGHT_SHAPE_SPOT 2
#define RTPBR_LIGHT_SHAPE_DIRECTIONAL 3
#define RTPBR_LIGHT_SHAPE_DISK 4
#define RTPBR_LIGHT_SHAPE_SPHERE 5 // a point light with a radius (not an rtpbr_light_type)
#define RTPBR_LIGHT_SHAPE_TUBE 6   // rtpbr_light_type's RTPBR_LIGHT_TUBE (5), mapped by the record
// The bounding radius of a light without a range: everything is within reach.
#define RTPBR_LIGHT_INFINITE 3.0e38

// Light culling (cull.comp): one invocation per tile, RTPBR_CULL_GROUP^2 tiles per workgroup.
#define RTPBR_CULL_GROUP 8
#define RTPBR_TILE_MASK_WORDS (RTPBR_SHADER_MAX_LIGHTS / 32)
// A tile's masks: RTPBR_TILE_MASK_WORDS words of its polygonal lights, then as many of its
// punctual lights, then of its spheres, then of its disks, then of its textured quads, then of
// its tubes (the lighting pass walks each kind
// without reading a light's shape: on lavapipe a loop choosing by shape ran both kinds' code
// for every light); then, at RTPBR_TILE_SHADOW_SLOTS, the lights whose shadows the tile traces:
// RTPBR_SHADER_MAX_SHADOWED_LIGHTS light indices in increasing order, RTPBR_TILE_NO_LIGHT for
// an empty slot (shadow_select.comp writes them when the frame has shadows; slot k's ratio is
// layer k of the shadow images).
// Then, at RTPBR_TILE_MASK_SUMMARY, one word per kind (in the masks' order): bit w set where
// the kind's word w is not zero, so that the lighting pass reads only the words that hold a
// light (with 1,024 lights, walking 32 words per kind per pixel cost more on lavapipe than the
// few lights a tile keeps).
// Then, at RTPBR_TILE_SHADOW_CLEAR, one word: bit k set where no triangle can block any shadow
// ray of the tile toward slot k's light (shadow_select.comp, shadow_cull.glsl): the trace skips
// those rays and the denoiser writes ratio 1 where its window lies in such tiles.
#define RTPBR_TILE_SHADOW_SLOTS (6 * RTPBR_TILE_MASK_WORDS)
#define RTPBR_TILE_MASK_SUMMARY (6 * RTPBR_TILE_MASK_WORDS + RTPBR_SHADER_MAX_SHADOWED_LIGHTS)
#define RTPBR_TILE_SHADOW_CLEAR (RTPBR_TILE_MASK_SUMMARY + 6)
#define RTPBR_TILE_MASK_STRIDE (6 * RTPBR_TILE_MASK_WORDS + RTPBR_SHADER_MAX_SHADOWED_LIGHTS + 7)
#define RTPBR_TILE_NO_LIGHT 0xffffffffu
#if RTPBR_TILE_MASK_WORDS > 32
#error "a summary word has a bit per mask word"
#endif
// Tile classes: each has its lighting variant, dispatched indirectly over its tile queue.
#define RTPBR_TILE_CLASS_EMPTY 0 // no surface pixel or no light left: emission and background
#define RTPBR_TILE_CLASS_BASIC 1 // metallic-roughness without clear coat, sheen, anisotropy
#define RTPBR_TILE_CLASS_FULL 2  // any material
// The same with a sphere light (a point light with a radius) among the tile's lights: the
// variants with the spheres' loop (whose registers the others do not pay).
#define RTPBR_TILE_CLASS_BASIC_SPHERES 3
#define RTPBR_TILE_CLASS_FULL_SPHERES 4
// The same with a textured quad among the tile's lights: the variants with the spheres', the
// disks' and the textured quads' loops (the spheres' variants without the textured quads' loop:
// on lavapipe its code alone slowed spheres from 61 to 72 ns per pixel-light).
#define RTPBR_TILE_CLASS_BASIC_TEXTURED 5
#define RTPBR_TILE_CLASS_FULL_TEXTURED 6
// The same with a tube among the tile's lights: the textured variants plus the tubes' loop.
#define RTPBR_TILE_CLASS_BASIC_TUBES 7
#define RTPBR_TILE_CLASS_FULL_TUBES 8
// BASIC where no light of the tile can give the streak estimate any weight at any of its
// pixels (cull.comp; shaderlib ltc_corrections.h, LTC_StreakOutside): the basic variant with the
// estimate compiled out (RTPBR_SPEC_LIGHTING_STREAK false), the same result. On lavapipe, which
// runs every branch, the estimate's two walks per pixel cost whether any pixel takes them or not.
#define RTPBR_TILE_CLASS_BASIC_NO_STREAK 9
#define RTPBR_TILE_CLASS_COUNT 10
// The tile queues' dispatch commands (lighting_common.glsl's TileLists: one per class, then the
// lists): RTPBR_TILE_CLASS_COUNT used, the array padded to 12. With 10 (the lists at byte 160)
// ACO allocated lighting_beckmann_ms1_full_spheres's registers differently and spilled 2 SGPRs
// on navi21 and gfx1100 (issue 32's no-spill bar; tests/shader-stats); with 11, 12 or 16 it
// compiles as with 9 did, instruction for instruction (Mesa 22.3.6).
#define RTPBR_TILE_QUEUE_SLOTS 12
#if RTPBR_TILE_QUEUE_SLOTS < RTPBR_TILE_CLASS_COUNT
#error "a tile queue per class"
#endif

// Monte Carlo lighting pass push constants (std430; rtpbr_shader_mc, lighting_mc.comp). The
// pass runs in dispatches over ranges of lights and of samples (lavapipe's loop budget, see
// engine/src/passes/lighting_mc.c): the one with first_light = first_sample = 0 writes the
// radiance image, the others add to it. Each light's random stream starts at its seed moved
// on by 4 first_sample steps (state * skip_mul + skip_add), so the split draws the numbers
// one dispatch would.
#define RTPBR_MC_FIELDS(F, S)                                                                     \
    F(S, UINT, samples, )      /* in all, per pixel and light, >= 1 (the sums divide by it) */    \
    F(S, UINT, seed, )                                                                             \
    F(S, UINT, first_sample, ) /* this dispatch's samples: first_sample .. + sample_count - 1 */  \
    F(S, UINT, sample_count, )                                                                     \
    F(S, UINT, first_light, )  /* this dispatch's lights: first_light .. + light_count - 1 */     \
    F(S, UINT, light_count, )  /* (those past the frame's light count are skipped) */             \
    F(S, UINT, skip_mul, )                                                                         \
    F(S, UINT, skip_add, )

// Supersampling resolve (resolve.comp), descriptor set 0.
#define RTPBR_BINDING_RESOLVE_SOURCE 0    // rgba32f storage image, (factor W) x (factor H)
#define RTPBR_BINDING_RESOLVE_TARGET 1    // rgba32f storage image, W x H
// Its push constants (std430; rtpbr_shader_resolve).
#define RTPBR_RESOLVE_FIELDS(F, S)                                                                \
    F(S, UVEC2, size, )  /* of the target */                                                       \
    F(S, UINT, factor, ) /* samples per pixel along each axis */                                   \
    F(S, UINT, pad0, )

// Tone-mapping pass, descriptor set 0.
#define RTPBR_BINDING_TONEMAP_RADIANCE 0   // rgba32f storage image, read only
// Its push constants (std430; rtpbr_shader_tonemap, tonemap.frag).
#define RTPBR_TONEMAP_FIELDS(F, S)                                                                \
    F(S, FLOAT, scale, ) /* 2^exposure */                                                          \
    F(S, UINT, pad0, )                                                                             \
    F(S, UINT, pad1, )                                                                             \
    F(S, UINT, pad2, )
// The tone-mapping pass's specialization constants (uints): the operator (RTPBR_TONEMAP_OP_*,
// default ACES) and the encoding (RTPBR_ENCODE_*, default NONE). passes/tonemap.c compiles a
// pipeline per target format, operator and encoding: on lavapipe the operators' branches all
// ran at every pixel, and the sRGB curve's powers too (docs/performance.md, "The fixed cost").
#define RTPBR_SPEC_TONEMAP_OP 10
#define RTPBR_SPEC_TONEMAP_ENCODE 11

// Tone-mapping operators (values of rtpbr_tonemap in rtpbr.h minus the default).
#define RTPBR_TONEMAP_OP_ACES 1
#define RTPBR_TONEMAP_OP_REINHARD 2
#define RTPBR_TONEMAP_OP_LINEAR 3

// Output encodings of the tone-mapping pass.
#define RTPBR_ENCODE_NONE 0 // sRGB attachment (hardware encodes) or float target
#define RTPBR_ENCODE_SRGB 1 // UNORM attachment: the shader applies the sRGB curve

// Area-light shadows (issue 17; engine/src/passes/shadow.c, shaders/shadow*.comp, bvh.glsl).
// In each tile, the RTPBR_SHADER_MAX_SHADOWED_LIGHTS lights of the largest irradiance bound at
// the tile's surface points cast shadows (shadow_select.comp; also RTPBR_MAX_SHADOWED_LIGHTS in
// rtpbr.h); the others are unshadowed there.
#define RTPBR_SHADER_MAX_SHADOWED_LIGHTS 8
// Deepest BVH node (root: depth 0) = the traversal stack's size.
#define RTPBR_BVH_MAX_DEPTH 32
// The shadow denoiser's largest window, (2 r + 1)^2 pixels (RTPBR_SHADOW_DENOISE_RADIUS in rtpbr.h).
#define RTPBR_SHADER_SHADOW_DENOISE_RADIUS 3
#define RTPBR_SHADER_SHADOW_WINDOW ((2 * RTPBR_SHADER_SHADOW_DENOISE_RADIUS + 1) * (2 * RTPBR_SHADER_SHADOW_DENOISE_RADIUS + 1))
// The specialization constant (a bool, default true) of shadow.comp that keeps bvh.glsl's alpha
// test: passes/shadow.c compiles the trace with it off for scenes without MASK or BLEND materials.
#define RTPBR_SPEC_BVH_ALPHA 0
// The specialization constant (a bool, default false) of the shadow passes that makes bvh.glsl read
// the BVH through its texel-buffer bindings (RTPBR_BINDING_SHADOW_BVH_NODE_TEXELS): set by
// passes/shadow.c on a CPU device (docs/performance.md, "Shadows on a CPU device").
#define RTPBR_SPEC_BVH_TEXELS 6
// The specialization constant (a bool, default false) of the trace that walks a pixel's rays
// toward a light as one packet also where the alpha is tested (bvh_occluded_packet's alpha; off:
// ray by ray, bvh_occluded): set by passes/shadow.c on a CPU device, where the shared walk is
// faster; on a GPU the packet's alpha took navi21's alpha-tested trace from 120 to 144 VGPRs
// and spilled 4 on gfx1100 (Mesa 22.3, bench/shader-stats).
#define RTPBR_SPEC_BVH_PACKET_ALPHA 7
// The lighting pass's specialization constants (lighting.comp's shade_lights.glsl and
// shading.glsl): the most vertices of the frame's polygons (a uint,
// RTPBR_SHADER_MAX_POLYGON_VERTICES by default), whether it has punctual lights (a bool, true by
// default) and the RTPBR_MATERIAL_FLAGS_FULL bits its materials have (a uint, all by default);
// passes/lighting.c sets them per frame from its light and material records
// (rtpbr_lighting_needs_of); and whether the device is a CPU (a bool, false by default).
#define RTPBR_SPEC_LIGHTING_MAX_VERTICES 1
#define RTPBR_SPEC_LIGHTING_PUNCTUAL 2
#define RTPBR_SPEC_LIGHTING_MATERIALS 3
#define RTPBR_SPEC_LIGHTING_CPU 4
// Whether the lighting variant reads the lights from RTPBR_BINDING_LIGHT_LIGHTS_UNIFORM (a bool,
// false by default): set by passes/lighting.c on a CPU device for frames of at most
// RTPBR_UNIFORM_LIGHTS_MAX lights (docs/performance.md, 22).
#define RTPBR_SPEC_LIGHTING_UNIFORM_LIGHTS 5
// Whether the lighting variant runs the streak estimate (a bool, true by default; the
// shader library's RTPBR_AREA_LIGHT_STREAK_ON): false in the pipeline of
// RTPBR_TILE_CLASS_BASIC_NO_STREAK, which is the basic variant's code (passes/lighting.c).
#define RTPBR_SPEC_LIGHTING_STREAK 8
// Whether the lighting variant reads the lights' shadow ratios (a bool, true by default): false
// for frames without shadows (frame.shadow_light_count 0; rtpbr_lighting_needs.shadows), whose
// variant then has no visibility code. On a GPU the run-time test of shadow_light_count skips
// it; on lavapipe both sides of a branch run, and the per-light slot search and texel read took
// 6 % of a quad light's instructions (docs/performance.md, 32).
#define RTPBR_SPEC_LIGHTING_SHADOWS 13
// Whether the empty tiles' variant (RTPBR_TILE_CLASS_EMPTY) reads the G-buffer's emission (a
// bool, true by default): false for frames none of whose materials emits
// (rtpbr_lighting_needs.emission), whose empty tiles then write 0 without the read (on lavapipe
// a third of their time; docs/performance.md, "Empty tiles without emission").
#define RTPBR_SPEC_LIGHTING_EMISSION 12
// The G-buffer pass's specialization constant (a uint, default RTPBR_GBUFFER_TEXTURES_ALL): which
// of the material's first RTPBR_GBUFFER_SPEC_SLOTS texture slots (bit 1 << binding: base colour,
// metallic-roughness, emission, normal) the pipeline samples; a slot left out reads as the white
// stand-in does, vec4(1), and without the normal slot the normal-mapping code is left out too.
// passes/gbuffer.c compiles a pipeline per set of slots the frame's materials use and binds each
// material's (rtpbr_gbuffer_material_slots): on lavapipe a texture read, or code under a
// branch not taken, costs its time (docs/performance.md, "The fixed cost", 1).
#define RTPBR_SPEC_GBUFFER_TEXTURES 9
#define RTPBR_GBUFFER_SPEC_SLOTS 4
#define RTPBR_GBUFFER_TEXTURES_ALL ((1u << RTPBR_GBUFFER_SPEC_SLOTS) - 1u)
// Lighting pass: the shadow ratios, a sampler2DArray (layer = light index), read with texelFetch.
#define RTPBR_BINDING_LIGHT_SHADOW_RATIO 24
// The extension textures' values per pixel (multipliers of the material record's factors, 1
// where a material has no such texture), written and read only when the frame's
// extension_textures has their bit (RTPBR_EXTENSION_TEXTURES_*; issue 28).
#define RTPBR_BINDING_LIGHT_GBUFFER4 25   // RGBA8 sRGB: specular colour rgb, specular a
#define RTPBR_BINDING_LIGHT_GBUFFER5 26   // RGBA8 sRGB: sheen colour rgb, sheen roughness a
#define RTPBR_BINDING_LIGHT_GBUFFER6 27   // RG8: clearcoat, clearcoat roughness
// The textured quads' prefiltered emission (RTPBR_LIGHT_FIELDS: texture): a 2D array, one layer
// per textured light (a 1-layer stand-in without any), RGBA16F, RTPBR_SHADER_LIGHT_TEXTURE_SIZE
// square with RTPBR_SHADER_LIGHT_TEXTURE_LEVELS levels, level k blurred over 2^k texels of level
// 0 (engine/src/light_texture.c); sampled linearly, clamped to the edge.
#define RTPBR_BINDING_LIGHT_TEXTURES 28
// The lights again, the first RTPBR_UNIFORM_LIGHTS_MAX records of the same buffer as a uniform
// buffer (std140: the same layout as std430 for rtpbr_shader_light), read instead of
// RTPBR_BINDING_LIGHT_LIGHTS where RTPBR_SPEC_LIGHTING_UNIFORM_LIGHTS is set: on lavapipe a
// uniform buffer's read at a varying index is a load per SIMD lane, a storage buffer's a loop
// over the lanes with a branch in each trip (docs/performance.md, 22 and 31). 315 records of
// 208 bytes fill 65,520 of 65,536 bytes, lavapipe's (and a common GPU's) maxUniformBufferRange.
#define RTPBR_BINDING_LIGHT_LIGHTS_UNIFORM 29
#define RTPBR_UNIFORM_LIGHTS_MAX 315
#define RTPBR_SHADER_LIGHT_TEXTURE_SIZE 128
#define RTPBR_SHADER_LIGHT_TEXTURE_LEVELS 8
// Shadow passes, descriptor set 0 (shadow.comp traces, shadow_denoise.comp filters).
#define RTPBR_BINDING_SHADOW_FRAME 0          // uniform: rtpbr_shader_frame
#define RTPBR_BINDING_SHADOW_LIGHTS 1         // storage: rtpbr_shader_light[]
#define RTPBR_BINDING_SHADOW_DEPTH 2          // depth (0 near .. 1 far)
#define RTPBR_BINDING_SHADOW_NORMAL 3         // G-buffer 1: world normal xyz, roughness
#define RTPBR_BINDING_SHADOW_BVH_NODES 4      // storage: rtpbr_shader_bvh_node[]
#define RTPBR_BINDING_SHADOW_BVH_TRIANGLES 5  // storage: rtpbr_shader_bvh_triangle[]
#define RTPBR_BINDING_SHADOW_ESTIMATES 6      // r32f storage image array: layer 2k shadowed, 2k + 1 unshadowed sum
#define RTPBR_BINDING_SHADOW_RATIO 7          // r32f storage image array: shadowed / unshadowed
// The alpha of MASK and BLEND occluders (bvh.glsl's bvh_alpha_blocks):
#define RTPBR_BINDING_SHADOW_VERTICES 8       // storage: the scene's vertices (RTPBR_VERTEX_FLOATS floats each)
#define RTPBR_BINDING_SHADOW_MATERIALS 9      // storage: rtpbr_shader_material[]
#define RTPBR_BINDING_SHADOW_TEXTURE_TRANSFORMS 10 // storage: rtpbr_shader_texture_transforms[]
#define RTPBR_BINDING_SHADOW_ALPHA_TEXTURES 11 // storage: rtpbr_shader_alpha_texture[], by scene texture (0: none)
#define RTPBR_BINDING_SHADOW_ALPHA_TEXELS 12  // storage: uint[], the textures' alpha bytes, 4 per uint
#define RTPBR_BINDING_SHADOW_TILES 13       // storage: the lighting pass's tile masks (RTPBR_TILE_MASK_STRIDE
                                              // uints a tile), whose shadow slots shadow_select.comp writes
#define RTPBR_BINDING_SHADOW_WORK 14        // storage: the trace's work list (shadow_list.comp)
// The same nodes and triangles as uniform texel buffers (R32G32B32A32_UINT: a node 2 texels, a
// triangle 4), read where RTPBR_SPEC_BVH_TEXELS is set (bvh.glsl).
#define RTPBR_BINDING_SHADOW_BVH_NODE_TEXELS 15
#define RTPBR_BINDING_SHADOW_BVH_TRIANGLE_TEXELS 16
#define RTPBR_SHADOW_BINDING_COUNT 17
// With ray-query shadows (rtpbr_context_desc.shadow_ray_query; engine/src/accel.c), two more:
#define RTPBR_BINDING_SHADOW_ACCEL 17           // the scene's top-level acceleration structure
#define RTPBR_BINDING_SHADOW_ACCEL_TRIANGLES 18 // storage: uint per structure triangle, its BVH triangle
#define RTPBR_SHADOW_RAY_QUERY_BINDING_COUNT 19
// The work lists of the trace and the denoiser (RTPBR_BINDING_SHADOW_WORK), uints: the trace's
// indirect dispatch arguments x, y, z (workgroup g = y * RTPBR_SHADOW_WORK_ROW + x) and entry
// count, the denoiser's four likewise (from uint 4), then from RTPBR_SHADOW_WORK_HEADER the
// trace's entries, one per workgroup to run: shadow slot k (bits 0-2), the 8 x 8 group's x (bits
// 3-16) and y (bits 17-30) in groups; after room for RTPBR_SHADER_MAX_SHADOWED_LIGHTS entries per
// group of the image, the denoiser's: a group's x (bits 0-15) and y (bits 16-31).
// shadow_list.comp writes both after the selection, leaving out the groups and slots whose
// estimates no pass reads, and the groups where no slot's estimates are read (there every
// ratio is 1: passes/shadow.c clears the ratios to 1 first).
#define RTPBR_SHADOW_WORK_HEADER 8
#define RTPBR_SHADOW_WORK_DENOISE 4
#define RTPBR_SHADOW_WORK_ROW 65535u
// The scene's vertex layout, floats per vertex: position 3, normal 3, uv 2, tangent 4, uv1 2.
#define RTPBR_VERTEX_FLOATS 14
#define RTPBR_VERTEX_UV_OFFSET 6
#define RTPBR_VERTEX_UV1_OFFSET 12
#define RTPBR_SHADOW_GROUP_SIZE 8             // 8 x 8 pixels per workgroup
// Push constants of both shadow passes (std430; rtpbr_shader_shadow).
#define RTPBR_SHADOW_FIELDS(F, S)                                                                 \
    F(S, UINT, samples, )      /* of this trace dispatch, per pixel and shadowed light, >= 1 */    \
    F(S, UINT, seed, )                                                                             \
    F(S, UINT, radius, )       /* of the denoiser's (2 radius + 1)^2 window; 0: no denoising */   \
    F(S, UINT, first_sample, ) /* index of the dispatch's first sample; 0: the sums start at 0 */ \
    F(S, UINT, cull, )         /* 1: shadow-ray culling (shadow.comp; rtpbr_render_desc.shadow_cull) */ \
    F(S, UINT, pad0, )                                                                             \
    F(S, UINT, pad1, )                                                                             \
    F(S, UINT, pad2, )
// A BVH node, the std430 element of RTPBR_BINDING_SHADOW_BVH_NODES (rtpbr_shader_bvh_node,
// bvh.glsl; engine/src/bvh.c documents the tree).
#define RTPBR_BVH_NODE_FIELDS(F, S)                                                               \
    F(S, VEC3, box_min, )                                                                          \
    F(S, UINT, left_or_first, ) /* interior: left child, the right one follows; leaf: first triangle */ \
    F(S, VEC3, box_max, )                                                                          \
    F(S, UINT, count, )         /* triangles of a leaf; 0: interior node */
// A triangle, the std430 element of RTPBR_BINDING_SHADOW_BVH_TRIANGLES: vertex 0 and the two
// edges from it, ready for the Moeller-Trumbore test. v0.w: which side lets rays through
// (glTF doubleSided false): 0 none (double-sided), +1 rays along e1 x e2, -1 rays against it
// (a mirroring transform turned the winding); e1.w: 1 where the material's alpha is tested
// (MASK or BLEND: bvh.glsl looks at its alpha only where a ray crosses it), else 0; e2.w unused.
// source: the triangle's three vertices in the scene's vertex buffer (RTPBR_BINDING_SHADOW_VERTICES)
// and its material, for the alpha of MASK and BLEND materials.
#define RTPBR_BVH_TRIANGLE_FIELDS(F, S)                                                           \
    F(S, VEC4, v0, )                                                                               \
    F(S, VEC4, e1, )                                                                               \
    F(S, VEC4, e2, )                                                                               \
    F(S, UVEC4, source, ) /* vertex indices xyz, material w */
// The alpha channel of a scene texture for the shadow rays (rtpbr_shader_alpha_texture, written
// by engine/src/scene.c): the texture's alpha bytes, rows top to bottom, 4 to a uint (the
// first in the low byte), from uint `first` of RTPBR_BINDING_SHADOW_ALPHA_TEXELS. first =
// RTPBR_ALPHA_TEXTURE_OPAQUE: every alpha is 1 (no texture, or all texels 255), no bytes stored.
#define RTPBR_ALPHA_TEXTURE_FIELDS(F, S)                                                          \
    F(S, UINT, first, )                                                                            \
    F(S, UINT, width, )                                                                            \
    F(S, UINT, height, )                                                                           \
    F(S, UINT, wrap, ) /* wrap_s | wrap_t << 2 (RTPBR_WRAP_*: 0 repeat, 1 clamp, 2 mirrored) */
#define RTPBR_ALPHA_TEXTURE_OPAQUE 0xffffffffu

#endif // RTPBR_SHARED_H
