/* rtpbr_gltf.h — glTF 2.0 scene loader shared by the engine (C11) and the
 * oracle (C++). One loader, one material mapping (docs/materials.md).
 *
 * The loader flattens a glTF scene into plain data in WORLD space:
 * triangle primitives (node transforms applied), materials mapped onto the
 * rtpbr material model, decoded RGBA8 textures, polygonal area lights
 * (emissive primitives + EXT_lights_area), point, spot and directional lights
 * (KHR_lights_punctual, in their own array), perspective cameras, a bounding
 * box.
 *
 *   rtpbr_gltf_load_desc desc = {0};               // zero = defaults
 *   char err[RTPBR_GLTF_ERROR_MESSAGE_SIZE];
 *   desc.error_message = err; desc.error_message_size = sizeof err;
 *   rtpbr_gltf_scene* scene = NULL;
 *   rtpbr_gltf_result r = rtpbr_gltf_load("room.gltf", &desc, &scene);
 *   if (r != RTPBR_GLTF_SUCCESS) fprintf(stderr, "%s: %s\n",
 *                                         rtpbr_gltf_result_string(r), err);
 *   ...
 *   rtpbr_gltf_destroy(scene);                     // NULL is a no-op
 *
 * Conventions:
 * - glTF units: metres, right-handed, +Y up; cameras look down their local -Z.
 * - Colours are linear RGB (glTF factors are linear). Radiance is in the
 *   renderer's (relative) unit: emission = emissiveFactor × emissive_strength;
 *   EXT_lights_area: nits × desc.area_light_radiance_scale (docs/materials.md);
 *   KHR_lights_punctual: candela (point, spot) or lux (directional) ×
 *   desc.area_light_radiance_scale, the same unit rule.
 * - Triangles are counter-clockwise seen from the side their geometric normal
 *   points to (glTF front face). Nodes with a negative-determinant transform
 *   get their index winding flipped so this stays true in world space.
 * - Sparse accessors are applied. TEXCOORD_0 and TEXCOORD_1 are read.
 *   KHR_texture_transform is read on every texture slot. Skins, morph
 *   targets, occlusion textures and non-triangle
 *   primitive modes (points, lines) are ignored with a warning;
 *   TRIANGLE_STRIP and TRIANGLE_FAN are converted to triangle lists.
 * - Degenerate triangles (repeated index, or |e1×e2| <= 1e-7·|e1|·|e2| in
 *   world space) are dropped from the index list, one warning per primitive.
 * - Scene: glTF "scene" (default 0); without scenes, every root node.
 * - Input is untrusted: every accessor, buffer view, index and reference is
 *   validated; external files resolve only inside the folder of the .gltf/.glb
 *   (or desc.base_dir); failures return a specific result code and a message
 *   naming the offending object. No global state in the loader: concurrent
 *   loads are independent.
 */
#ifndef RTPBR_GLTF_H
#define RTPBR_GLTF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- limits --------------------------------------------------------------
 * Hard limits; a desc may lower (never raise) the first three.              */
#define RTPBR_GLTF_MAX_VERTICES (1u << 24)          /* total, all primitives  */
#define RTPBR_GLTF_MAX_LIGHTS 65536u                /* area + punctual lights */
#define RTPBR_GLTF_MAX_TEXTURE_DIMENSION 16384u     /* width and height       */
#define RTPBR_GLTF_MAX_INDICES (3u * (1u << 25))    /* total, after triangulation */
#define RTPBR_GLTF_MAX_FILE_SIZE ((uint64_t)1 << 30)/* any one file or data: URI */
#define RTPBR_GLTF_MAX_NODE_DEPTH 256u              /* node hierarchy depth   */
#define RTPBR_GLTF_MAX_JSON_DEPTH 256u              /* JSON array/object nesting */
/* Vertices of one light. Must equal the engine's RTPBR_MAX_POLYGON_VERTICES
 * (rtpbr/rtpbr.h, the source of truth); checked in engine/src/scene_gltf.c. */
#define RTPBR_GLTF_MAX_POLYGON_VERTICES 8u
#define RTPBR_GLTF_ERROR_MESSAGE_SIZE 512u          /* suggested buffer size  */
/* Default budget of decoded texel memory (RGBA8, all textures of a scene,
 * desc.texture_memory_budget): 256 MiB, e.g. one 8192² or sixteen 2048²
 * textures. Checked against each image's header before it is decoded.    */
#define RTPBR_GLTF_DEFAULT_TEXTURE_BUDGET ((uint64_t)256 << 20)

/* ---- results ------------------------------------------------------------ */
typedef enum rtpbr_gltf_result {
    RTPBR_GLTF_SUCCESS = 0,
    RTPBR_GLTF_ERROR_INVALID_ARGUMENT,   /* NULL path/out, bad desc values   */
    RTPBR_GLTF_ERROR_FILE_NOT_FOUND,     /* scene or referenced file missing */
    RTPBR_GLTF_ERROR_IO,                 /* unreadable, a directory, too big */
    RTPBR_GLTF_ERROR_INVALID_GLB,        /* bad GLB magic/version/chunks     */
    RTPBR_GLTF_ERROR_INVALID_JSON,       /* JSON syntax or glTF schema error */
    RTPBR_GLTF_ERROR_URI_REJECTED,       /* absolute path, '..' escape, shell
                                             characters, unsupported scheme   */
    RTPBR_GLTF_ERROR_INVALID_REFERENCE,  /* index to a missing node, mesh,
                                             material, texture, camera, image,
                                             light                            */
    RTPBR_GLTF_ERROR_INVALID_ACCESSOR,   /* accessor/bufferView/buffer bounds,
                                             type, stride, count mismatch     */
    RTPBR_GLTF_ERROR_INDEX_OUT_OF_RANGE, /* vertex index >= vertex count     */
    RTPBR_GLTF_ERROR_NONFINITE,          /* NaN/Inf position, transform,
                                             camera or light parameter        */
    RTPBR_GLTF_ERROR_UNSUPPORTED,        /* extensionsRequired we cannot do,
                                             a node cycle, too deep hierarchy,
                                             an unknown light type            */
    RTPBR_GLTF_ERROR_IMAGE_DECODE,       /* image data could not be decoded  */
    RTPBR_GLTF_ERROR_TOO_MANY_VERTICES,  /* > max_vertices or max indices    */
    RTPBR_GLTF_ERROR_TOO_MANY_LIGHTS,    /* > max_lights                     */
    RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE,  /* > max_texture_dimension, or over
                                             desc.texture_memory_budget       */
    RTPBR_GLTF_ERROR_OUT_OF_MEMORY,
    RTPBR_GLTF_RESULT_COUNT
} rtpbr_gltf_result;

/* Static English name of a result ("RTPBR_GLTF_ERROR_URI_REJECTED");
 * "RTPBR_GLTF_RESULT_UNKNOWN" for values out of range. */
const char* rtpbr_gltf_result_string(rtpbr_gltf_result result);

/* ---- host callbacks ----------------------------------------------------- */
typedef struct rtpbr_gltf_allocator {
    /* Both set or both NULL (NULL = malloc/free). Used for everything the
     * returned scene owns; tinygltf's own temporaries use C++ new/delete. */
    void* (*alloc)(size_t size, void* user_data);
    void (*free)(void* ptr, void* user_data);
    void* user_data;
} rtpbr_gltf_allocator;

typedef enum rtpbr_gltf_log_level {
    RTPBR_GLTF_LOG_ERROR = 0,   /* the message also written to error_message */
    RTPBR_GLTF_LOG_WARNING = 1, /* something ignored or repaired             */
    RTPBR_GLTF_LOG_INFO = 2,    /* summary of what was loaded                */
} rtpbr_gltf_log_level;

typedef struct rtpbr_gltf_logger {
    /* NULL = silent. message is NUL-terminated, valid during the call only. */
    void (*func)(rtpbr_gltf_log_level level, const char* message, void* user_data);
    void* user_data;
} rtpbr_gltf_logger;

/* How emissive primitives become area lights.
 * BOUNDED (default; real-time renderers): a primitive whose coplanar regions
 *   merge into at most RTPBR_GLTF_MAX_EXACT_EMITTER_POLYGONS convex polygons
 *   of at most 8 vertices (as EXACT merges them) becomes those polygons
 *   exactly (with an emission texture: at the texture's mean radiance over
 *   the primitive); any other emissive primitive becomes at most
 *   RTPBR_GLTF_MAX_EMITTER_CLUSTERS proxy lights (rtpbr_gltf_light.proxy):
 *   its triangles clustered by position and normal, each cluster an
 *   equal-area regular octagon facing its mean normal at its centroid, at
 *   the cluster's mean radiance (texture-averaged), so that each keeps the
 *   cluster's power. The surface itself still draws its emission.
 * EXACT (path tracers, the oracle): every emissive triangle is an emitter:
 *   coplanar regions merged into convex polygons (greedy pieces where needed,
 *   at worst one per triangle), each triangle alone where the material has an
 *   emission texture (rtpbr_gltf_light.triangle says which). */
typedef enum rtpbr_gltf_emissive_mode {
    RTPBR_GLTF_EMISSIVE_BOUNDED = 0,
    RTPBR_GLTF_EMISSIVE_EXACT = 1,
} rtpbr_gltf_emissive_mode;
#define RTPBR_GLTF_MAX_EXACT_EMITTER_POLYGONS 16u /* per primitive, BOUNDED  */
#define RTPBR_GLTF_MAX_EMITTER_CLUSTERS 8u        /* per primitive, BOUNDED  */

/* ---- load description (zero-initialise; zero = default) ------------------ */
typedef struct rtpbr_gltf_load_desc {
    rtpbr_gltf_allocator allocator; /* default: malloc/free                 */
    rtpbr_gltf_logger logger;       /* default: no logging                  */
    /* Optional caller buffer receiving the detailed message of a failure
     * ("accessor 3: byteOffset+count*stride exceeds bufferView 2 (1024
     * bytes)"); always NUL-terminated when size > 0, "" on success. */
    char* error_message;
    size_t error_message_size;
    /* Limits; 0 = the RTPBR_GLTF_MAX_* default, larger values are clamped. */
    uint32_t max_vertices;
    uint32_t max_lights;
    uint32_t max_texture_dimension;
    /* Folder against which external URIs resolve, for
     * rtpbr_gltf_load_memory (NULL there = external URIs are rejected) and
     * as an override for rtpbr_gltf_load (NULL = the scene file's folder). */
    const char* base_dir;
    /* true = do not decode images: textures get width/height 0, pixels NULL
     * (texture indices in materials stay valid). Default false = decode. */
    bool skip_images;
    /* true = no lights from emissive primitives (EXT_lights_area only).
     * Default false: every primitive whose material emits becomes lights,
     * as emissive_mode says. */
    bool no_emissive_lights;
    /* How emissive primitives become lights (docs/materials.md, "Lights from
     * materials"). Default BOUNDED. */
    rtpbr_gltf_emissive_mode emissive_mode;
    /* EXT_lights_area gives luminance in nits (cd/m²). Radiance written to
     * rtpbr_gltf_light = color × intensity × area_light_radiance_scale;
     * 0 = 1 (nits used as the renderer's radiance unit, like emissive
     * materials). 1/683 gives W/(sr·m²) at 555 nm. The same scale multiplies
     * KHR_lights_punctual intensities (rtpbr_gltf_punctual_light.intensity). */
    float area_light_radiance_scale;
    /* Bytes of decoded texels (4 per texel, 8 while a 16-bit PNG is reduced)
     * the scene's textures may take together; an image that would exceed it
     * is RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE, refused from its header before
     * any pixel memory is reserved. 0 = RTPBR_GLTF_DEFAULT_TEXTURE_BUDGET;
     * any other value is used as given (a 16384² texture needs 1 GiB). Only
     * PNG and JPEG images are decoded; other formats are
     * RTPBR_GLTF_ERROR_IMAGE_DECODE. */
    uint64_t texture_memory_budget;
} rtpbr_gltf_load_desc;

/* ---- scene data ---------------------------------------------------------
 * Everything is plain data; a host may fill these structs by hand (a scene
 * built by hand belongs to its builder: never pass it to rtpbr_gltf_destroy).
 */

/* One triangle list in world space. Arrays are structure-of-arrays with
 * vertex_count entries each (positions/normals xyz, texcoords uv, tangents
 * xyzw); never NULL when vertex_count > 0 (indices: when index_count > 0).
 * A glTF primitive left without a triangle (a node scaled by 0, only
 * degenerate triangles, no POSITION) is not listed (a warning is logged), so
 * index_count > 0 for every loaded primitive. */
typedef struct rtpbr_gltf_primitive {
    uint32_t vertex_count;
    uint32_t index_count;  /* multiple of 3; degenerate triangles removed   */
    float* positions;      /* 3 × vertex_count, world space                 */
    float* normals;        /* 3 × vertex_count, world space, unit length
                              (normal matrix = inverse transpose of the node
                              matrix). Generated when missing: area-weighted
                              smooth normals over shared indices, i.e. flat
                              for unindexed geometry; also replaces zero or
                              non-finite normals of the file.              */
    float* texcoords;      /* 2 × vertex_count, TEXCOORD_0; zeros if
                              has_texcoords false                          */
    float* texcoords1;     /* 2 × vertex_count, TEXCOORD_1; zeros if
                              has_texcoords1 false                         */
    float* tangents;       /* 4 × vertex_count, world space xyz unit, w = ±1
                              bitangent sign (B = w · cross(N, T)). From the
                              file, else generated per vertex from UVs when
                              the material has a normal texture and UVs
                              exist (per-vertex accumulation after Lengyel
                              2001; not MikkTSpace), else all zero.        */
    uint32_t* indices;     /* index_count entries, each < vertex_count      */
    uint32_t material;     /* index into scene->materials (always valid:
                              a default material is appended if needed)    */
    int32_t gltf_mesh;     /* source glTF mesh index                        */
    int32_t gltf_primitive;/* index of the primitive inside that mesh       */
    int32_t gltf_node;     /* source node (meshes instanced by several nodes
                              yield one primitive per node)                */
    bool has_texcoords;
    bool has_texcoords1;
    bool normals_generated;
    bool tangents_generated;
    bool has_tangents;     /* tangents are meaningful (file or generated)   */
    float bounds_min[3];   /* world-space AABB of the referenced vertices   */
    float bounds_max[3];
} rtpbr_gltf_primitive;

typedef enum rtpbr_gltf_alpha_mode {
    RTPBR_GLTF_ALPHA_OPAQUE = 0, /* coverage (base_color[3] x the base     */
    RTPBR_GLTF_ALPHA_MASK = 1,   /* colour texture's alpha): docs/materials.md, "Alpha" */
    RTPBR_GLTF_ALPHA_BLEND = 2,
} rtpbr_gltf_alpha_mode;

/* KHR_texture_transform of one texture slot, and the texture coordinate set
 * the slot reads. With has_transform false the slot reads TEXCOORD_texcoord
 * unchanged (a zeroed struct: TEXCOORD_0, identity). Otherwise
 *   uv' = T R S uv:  u' = cos(r) sx u + sin(r) sy v + ox,
 *                    v' = -sin(r) sx u + cos(r) sy v + oy,
 * the extension's translation × rotation × scale, r counter-clockwise in UV
 * space (the spec's example: offset (0, 1), rotation pi/2, scale 0.5 shows
 * the lower-left quadrant rotated clockwise). */
typedef struct rtpbr_gltf_texture_transform {
    float offset[2];          /* default 0, 0                               */
    float rotation;           /* radians, default 0                         */
    float scale[2];           /* default 1, 1                               */
    uint32_t texcoord;        /* TEXCOORD_n: textureInfo.texCoord, or the
                                 extension's texCoord override; 0 or 1 (a
                                 set the primitive lacks reads zeros)      */
    bool has_transform;       /* the extension is present                   */
} rtpbr_gltf_texture_transform;

/* The material extensions, each in its own struct with a has_ flag in
 * rtpbr_gltf_material (as cgltf does). Values as the file stores them;
 * when has_ is false the struct holds the extension's defaults. Scalars
 * documented in [0,1] are clamped (with a warning). */
typedef struct rtpbr_gltf_ior {              /* KHR_materials_ior          */
    float ior;                /* >= 1, default 1.5; 0: the spec's infinite
                                 IOR (Fresnel 1 at every angle)            */
} rtpbr_gltf_ior;
/* Extension textures: indices into scene->textures, -1 = none (the default;
 * read them only when the extension's has_ flag is set). Each multiplies its
 * factor, in the channels the extension names. */
typedef struct rtpbr_gltf_specular {         /* KHR_materials_specular     */
    float specular_factor;          /* [0,1], default 1                     */
    float specular_color_factor[3]; /* linear RGB >= 0 (may exceed 1),
                                       default 1, 1, 1                     */
    int32_t specular_texture;       /* A x specular_factor (linear)         */
    int32_t specular_color_texture; /* RGB x specular_color_factor (sRGB)   */
    rtpbr_gltf_texture_transform specular_texture_transform;
    rtpbr_gltf_texture_transform specular_color_texture_transform;
} rtpbr_gltf_specular;
typedef struct rtpbr_gltf_clearcoat {        /* KHR_materials_clearcoat    */
    float clearcoat_factor;           /* [0,1], default 0                   */
    float clearcoat_roughness_factor; /* perceptual, [0,1], default 0       */
    int32_t clearcoat_texture;        /* R x clearcoat_factor (linear)      */
    int32_t clearcoat_roughness_texture; /* G x clearcoat_roughness_factor  */
    int32_t clearcoat_normal_texture; /* tangent space, like normal_texture */
    float clearcoat_normal_scale;     /* clearcoatNormalTexture.scale, 1    */
    rtpbr_gltf_texture_transform clearcoat_texture_transform;
    rtpbr_gltf_texture_transform clearcoat_roughness_texture_transform;
    rtpbr_gltf_texture_transform clearcoat_normal_texture_transform;
} rtpbr_gltf_clearcoat;
typedef struct rtpbr_gltf_sheen {            /* KHR_materials_sheen        */
    float sheen_color_factor[3];      /* linear RGB, [0,1], default 0       */
    float sheen_roughness_factor;     /* perceptual, [0,1], default 0       */
    int32_t sheen_color_texture;      /* RGB x sheen_color_factor (sRGB)    */
    int32_t sheen_roughness_texture;  /* A x sheen_roughness_factor (linear) */
    rtpbr_gltf_texture_transform sheen_color_texture_transform;
    rtpbr_gltf_texture_transform sheen_roughness_texture_transform;
} rtpbr_gltf_sheen;
typedef struct rtpbr_gltf_anisotropy {       /* KHR_materials_anisotropy   */
    float anisotropy_strength;        /* [0,1], default 0                   */
    float anisotropy_rotation;        /* radians, counter-clockwise from the
                                         tangent, default 0                */
} rtpbr_gltf_anisotropy;
typedef struct rtpbr_gltf_emissive_strength { /* KHR_materials_emissive_strength */
    float emissive_strength;          /* >= 0, default 1                    */
} rtpbr_gltf_emissive_strength;
/* Burley 2012's principled BRDF: material.extras.rtpbr_disney (its
 * baseColor, metallic and roughness keys set the core fields, which mean
 * the same in both models). Burley's defaults. */
typedef struct rtpbr_gltf_disney {
    float subsurface;         /* [0,1], default 0                           */
    float specular;           /* F0 = 0.08 specular, [0,1]; default from the
                                 IOR: F0(ior) x specular_factor / 0.08 (0.5
                                 for ior 1.5), ior = extras' "ior" key, else
                                 KHR_materials_ior's                       */
    float specular_tint;      /* default 0                                  */
    float anisotropic;        /* aspect sqrt(1 - 0.9 anisotropic), default 0 */
    float sheen;              /* default 0                                  */
    float sheen_tint;         /* default 0                                  */
    float clearcoat;          /* GTR1 coat of weight 0.25 clearcoat, default 0 */
    float clearcoat_gloss;    /* GTR1 alpha mix(0.1, 0.001, gloss), default 1 */
} rtpbr_gltf_disney;

/* A glTF material: the core metallic-roughness fields, then each supported
 * extension in its own struct (docs/materials.md has the table). The
 * renderers resolve it with shaderlib/rtpbr/material.h: Disney's model when
 * has_disney, else glTF metallic-roughness with the KHR extensions. */
typedef struct rtpbr_gltf_material {
    float base_color[4];      /* linear RGBA, baseColorFactor, [0,1]        */
    float metallic;           /* metallicFactor, [0,1]                      */
    float roughness;          /* PERCEPTUAL roughness (α = roughness²), [0,1] */
    float emission[3];        /* radiance = emissiveFactor (clamped to
                                 [0,1]) × emissive_strength                */
    float normal_scale;       /* normalTexture.scale, default 1             */
    float alpha_cutoff;       /* default 0.5                                */
    rtpbr_gltf_alpha_mode alpha_mode;
    bool double_sided;
    bool has_ior, has_specular, has_clearcoat, has_sheen, has_anisotropy, has_emissive_strength, has_disney;
    rtpbr_gltf_ior ior;
    rtpbr_gltf_specular specular;
    rtpbr_gltf_clearcoat clearcoat;
    rtpbr_gltf_sheen sheen;
    rtpbr_gltf_anisotropy anisotropy;
    rtpbr_gltf_emissive_strength emissive_strength;
    rtpbr_gltf_disney disney;
    /* Indices into scene->textures, -1 = none. Colour textures (base colour,
     * emission) are flagged sRGB; the others linear. */
    int32_t base_color_texture;
    int32_t metallic_roughness_texture; /* G = roughness, B = metallic     */
    int32_t normal_texture;             /* tangent space, needs tangents   */
    int32_t emission_texture;           /* multiplies emission; lights from
                                           the primitive take its mean
                                           (emissive_mode BOUNDED) or leave
                                           it to the renderer per point
                                           (EXACT, rtpbr_gltf_light.triangle) */
    /* Each slot's KHR_texture_transform and texture coordinate set. */
    rtpbr_gltf_texture_transform base_color_texture_transform;
    rtpbr_gltf_texture_transform metallic_roughness_texture_transform;
    rtpbr_gltf_texture_transform normal_texture_transform;
    rtpbr_gltf_texture_transform emission_texture_transform;
    int32_t gltf_material;    /* source glTF material, -1 = default material */
} rtpbr_gltf_material;

typedef enum rtpbr_gltf_wrap {
    RTPBR_GLTF_WRAP_REPEAT = 0,
    RTPBR_GLTF_WRAP_CLAMP_TO_EDGE = 1,
    RTPBR_GLTF_WRAP_MIRRORED_REPEAT = 2,
} rtpbr_gltf_wrap;

/* glTF sampler.minFilter. Absent (DEFAULT): the renderer's choice; the
 * engine reads it as LINEAR_MIPMAP_LINEAR (trilinear). */
typedef enum rtpbr_gltf_min_filter {
    RTPBR_GLTF_MIN_FILTER_DEFAULT = 0,
    RTPBR_GLTF_MIN_FILTER_NEAREST = 1,                /* 9728, no mipmaps */
    RTPBR_GLTF_MIN_FILTER_LINEAR = 2,                 /* 9729, no mipmaps */
    RTPBR_GLTF_MIN_FILTER_NEAREST_MIPMAP_NEAREST = 3, /* 9984 */
    RTPBR_GLTF_MIN_FILTER_LINEAR_MIPMAP_NEAREST = 4,  /* 9985 */
    RTPBR_GLTF_MIN_FILTER_NEAREST_MIPMAP_LINEAR = 5,  /* 9986 */
    RTPBR_GLTF_MIN_FILTER_LINEAR_MIPMAP_LINEAR = 6,   /* 9987 */
} rtpbr_gltf_min_filter;

/* A decoded texture: always RGBA8, rows top to bottom, width × height × 4
 * bytes. A glTF texture used both as colour and as data appears twice. */
typedef struct rtpbr_gltf_texture {
    uint32_t width, height;    /* 0 × 0 when desc.skip_images              */
    uint8_t* pixels;           /* NULL when desc.skip_images                */
    bool srgb;                 /* true: texels are sRGB-encoded colour      */
    rtpbr_gltf_wrap wrap_s, wrap_t;       /* sampler.wrapS/T, default REPEAT */
    bool nearest;              /* sampler.magFilter NEAREST (else linear)   */
    rtpbr_gltf_min_filter min_filter;     /* sampler.minFilter            */
    int32_t gltf_texture;      /* source glTF texture index                 */
} rtpbr_gltf_texture;

typedef enum rtpbr_gltf_light_shape {
    RTPBR_GLTF_LIGHT_POLYGON = 0, /* convex planar polygon, vertices[]      */
    RTPBR_GLTF_LIGHT_DISK = 1,    /* disk: center, radius, normal; vertices[]
                                      holds an equal-area regular octagon
                                      for polygon-only consumers            */
} rtpbr_gltf_light_shape;

/* The facts about a light polygon that its users need besides its vertices,
 * derived from the (float) vertices once, where the light is made, by
 * rtpbr_gltf_polygon_facts: the loader for its lights (stored in
 * rtpbr_gltf_light), the engine for lights given through its API. Everyone
 * else reads them: the engine's light record (plane, area, bounding sphere),
 * the path tracer's light sampling (area, fan), the hit side (normal). */
typedef struct rtpbr_gltf_polygon_facts {
    float normal[3];       /* unit, Newell's: the side about which the
                              vertices turn counter-clockwise; 0 when the
                              polygon has no area                          */
    float center[3];       /* vertex mean, the bounding sphere's centre     */
    float bound_radius;    /* bounding sphere radius about center, rounded
                              up (never smaller than the farthest vertex)  */
    float area;            /* half the length of Newell's normal            */
    float fan_area[RTPBR_GLTF_MAX_POLYGON_VERTICES - 2];
                           /* triangles (v0, v[k+1], v[k+2]) of the fan,
                              k < vertex_count - 2; 0 beyond                */
} rtpbr_gltf_polygon_facts;

/* The facts of the polygon vertices[0 .. vertex_count) (3 to
 * RTPBR_GLTF_MAX_POLYGON_VERTICES; outside that range, all zero), computed in
 * double precision and rounded to float. */
void rtpbr_gltf_polygon_facts_of(const float (*vertices)[3], uint32_t vertex_count,
                                 rtpbr_gltf_polygon_facts* out);

/* One planar area light in world space, emitting radiance uniformly
 * (Lambertian emitter) from its front side (and back if two_sided). */
typedef struct rtpbr_gltf_light {
    rtpbr_gltf_light_shape shape;
    uint32_t vertex_count;  /* 3..8 */
    float vertices[RTPBR_GLTF_MAX_POLYGON_VERTICES][3];
                            /* convex, counter-clockwise seen from the side
                               normal points to: normal ∝ (v1-v0)×(v2-v0)   */
    rtpbr_gltf_polygon_facts facts;
                            /* normal (unit, emitting side), centre (vertex
                               mean; a disk's: its centre to rounding),
                               area (a disk's: π r² to rounding), bounding
                               sphere, fan: rtpbr_gltf_polygon_facts_of the
                               vertices, computed by the loader            */
    float radius;           /* disk radius (an ellipse's half-axis along
                               `axis`, below), 0 for polygons              */
    float radiance[3];      /* W/(sr·m²), linear RGB                        */
    bool two_sided;         /* emits from both faces (material doubleSided) */
    int32_t primitive;      /* index into scene->primitives, -1 for
                               EXT_lights_area lights                      */
    int32_t material;       /* emitting material, -1 for EXT_lights_area    */
    bool proxy;             /* a cluster of an emissive mesh standing in for
                               it (RTPBR_GLTF_EMISSIVE_BOUNDED): not its
                               shape; path tracers emit from the mesh      */
    int32_t triangle;       /* the primitive's triangle (indices[3 t ..])
                               this light is, or -1 (RTPBR_GLTF_EMISSIVE_EXACT
                               with an emission texture)                   */
    int32_t gltf_node;      /* node carrying an EXT_lights_area light, or the
                               primitive's node                            */
    float radius2;          /* disk: its other half-axis, across `axis`
                               (radius is the one along it): an ellipse, the
                               image of the light's circle under a node
                               scaled unevenly; radius for a circle; 0 for
                               polygons                                    */
    float axis[3];          /* disk: unit, in its plane, the direction of
                               the half-axis `radius` (axis x the direction
                               of radius2 = normal); 0 for polygons        */
} rtpbr_gltf_light;

/* A KHR_lights_punctual light on a node, in world space: a point, a spot or
 * a directional light (the extension's text). Point and spot lights are
 * evaluated exactly as delta lights (no size), unless a point light carries a
 * radius (a sphere, below); a directional light is the
 * sun's disk, of angular_diameter (the extension has no size: every
 * directional light gets RTPBR_GLTF_SUN_ANGULAR_DIAMETER; a program may set 0,
 * a true direction, evaluated exactly). One per node that references
 * a light (two nodes referencing one light: two entries), in node traversal
 * order; the node's scale changes neither intensity, range nor cones. The
 * angles and range are checked in double precision, as written in the file,
 * then rounded to float. */
/* The sun's mean angular diameter seen from the Earth, 0.53 degrees, in
 * radians (the default angular_diameter of a directional light). */
#define RTPBR_GLTF_SUN_ANGULAR_DIAMETER 0.00925f

typedef enum rtpbr_gltf_punctual_type {
    RTPBR_GLTF_PUNCTUAL_POINT = 0,
    RTPBR_GLTF_PUNCTUAL_SPOT = 1,
    RTPBR_GLTF_PUNCTUAL_DIRECTIONAL = 2,
} rtpbr_gltf_punctual_type;

typedef struct rtpbr_gltf_punctual_light {
    rtpbr_gltf_punctual_type type;
    float position[3];      /* the node's origin (point, spot; directional:
                               the node's origin too, unused)               */
    float direction[3];     /* unit: the node's -Z, the way the light travels
                               (spot, directional; point: the same, unused,
                               or (0,0,-1) where the node's Z axis is
                               degenerate, which a spot or directional light
                               refuses: RTPBR_GLTF_ERROR_NONFINITE)         */
    float intensity[3];     /* color × intensity × area_light_radiance_scale:
                               candela (lm/sr) for point and spot, lux
                               (lm/m²) for directional; radiance of a surface
                               lit head-on at distance d: I / d² × BRDF      */
    float range;            /* distance where the light ends, > 0, windowed
                               by the spec's recommended clamp(1 - (d/range)^4,
                               0, 1); 0 = infinite (no window): absent, and
                               always for directional lights (ignored there
                               with a warning)                              */
    float inner_cone_angle; /* spot: radians, 0 <= inner < outer <= pi/2    */
    float outer_cone_angle; /* (defaults 0, pi/4, also without a "spot"
                               object); the spec's falloff: t =
                               clamp((cos - cos outer) / max(cos inner - cos
                               outer, 1e-3), 0, 1), times t². Both 0 for
                               point and directional lights                 */
    float angular_diameter; /* directional: the disk's full apex angle,
                               radians, in [0, pi/2): its illuminance at
                               normal incidence is `intensity`, its radiance
                               intensity / (pi sin^2(angular_diameter / 2));
                               0 = a true direction. Point, spot: 0         */
    float radius;           /* point: the radius of the sphere it is, > 0, of
                               uniform radiance intensity / (pi radius^2)
                               (the same intensity far away), times W(d) at
                               the distance d from its centre; from the
                               light's "extras": {"radius": r} (metres; the
                               extension has no size: Blender writes a light's
                               custom property "radius" there). 0 = a true
                               point (absent), evaluated exactly. Spot,
                               directional: 0 (a spot's radius is ignored
                               with a warning). A point light's radius must
                               be a number >= 0 (RTPBR_GLTF_ERROR_INVALID_JSON)
                               whose sphere's area and radiance fit a float
                               (RTPBR_GLTF_ERROR_NONFINITE); one that is not a
                               number is ignored with a warning (extras are
                               free-form). The node's scale does not change it */
    int32_t gltf_node;      /* the node carrying it                         */
    int32_t gltf_light;     /* index in KHR_lights_punctual.lights          */
    float length;           /* point with radius > 0: a capsule (a tube, UE's
                               "source length"): the segment position +-
                               axis length/2 swept by the ball of radius
                               `radius` (a cylinder of length `length` and
                               two hemispherical caps), of uniform radiance
                               2 intensity / (pi radius (2 radius + length))
                               (its power stays 4 pi intensity; at length 0
                               the sphere's), times W(d), d from its centre
                               `position`. From the light's "extras":
                               {"length": L} (metres), read like the radius:
                               a number >= 0 (RTPBR_GLTF_ERROR_INVALID_JSON)
                               whose capsule's area 2 pi r (2 r + L) and
                               radiance fit a float (RTPBR_GLTF_ERROR_NONFINITE),
                               not a number: ignored with a warning, not
                               scaled by the node. 0 = the sphere (absent);
                               ignored with a warning (left 0) without a
                               radius and on spot and directional lights   */
    float axis[3];          /* unit: the node's local +X in world space, the
                               capsule's axis (every light; (1,0,0) where the
                               node's X axis is degenerate)                 */
} rtpbr_gltf_punctual_light;

/* A perspective camera, world space. */
typedef struct rtpbr_gltf_camera {
    float position[3];
    float forward[3];      /* unit, node's -Z                               */
    float up[3];           /* unit, node's +Y, orthogonalised              */
    float right[3];        /* unit, forward × up (node's +X)                */
    float yfov;            /* radians                                       */
    float aspect;          /* width / height; 0 = not given in the file     */
    float znear;
    float zfar;            /* 0 = infinite                                  */
    int32_t gltf_node;
    int32_t gltf_camera;
} rtpbr_gltf_camera;

typedef struct rtpbr_gltf_scene {
    rtpbr_gltf_primitive* primitives; uint32_t primitive_count;
    rtpbr_gltf_material* materials;   uint32_t material_count; /* [i] = glTF
                                          material i; a default one last if used */
    rtpbr_gltf_texture* textures;     uint32_t texture_count;
    rtpbr_gltf_light* lights;         uint32_t light_count;
    rtpbr_gltf_punctual_light* punctual_lights; uint32_t punctual_light_count;
                                      /* KHR_lights_punctual, in node order */
    rtpbr_gltf_camera* cameras;       uint32_t camera_count; /* 0 = none   */
    uint32_t total_vertex_count;
    uint32_t total_index_count;
    /* World AABB of all primitives and area lights (disk lights: the disk
     * and its octagon); all zero when empty. Punctual lights are not in it
     * (not even a point light's position). */
    float bounds_min[3];
    float bounds_max[3];
    /* Set by the loader (how to free); ignored in hand-built scenes. */
    rtpbr_gltf_allocator allocator;
} rtpbr_gltf_scene;

/* Loads a .gltf (JSON, external or data: URIs) or .glb file. On success
 * *out receives the scene; on failure *out is NULL, the result says why and
 * desc->error_message (if given) names the offending object. desc may be
 * NULL (all defaults). */
rtpbr_gltf_result rtpbr_gltf_load(const char* path, const rtpbr_gltf_load_desc* desc,
                                    rtpbr_gltf_scene** out);

/* Same from memory: GLB if data starts with "glTF", else JSON. External
 * URIs resolve under desc->base_dir, or are rejected when it is NULL. */
rtpbr_gltf_result rtpbr_gltf_load_memory(const void* data, size_t size,
                                           const rtpbr_gltf_load_desc* desc,
                                           rtpbr_gltf_scene** out);

/* Frees a scene returned by a load function. NULL is a no-op. */
void rtpbr_gltf_destroy(rtpbr_gltf_scene* scene);

/* A slot's texture coordinates through its KHR_texture_transform (the
 * extension's matrix T R S: uv' = (c sx u + s sy v + ox, -s sx u + c sy v + oy),
 * c, s = cos, sin of rotation); unchanged without one. */
void rtpbr_gltf_texture_transform_apply(const rtpbr_gltf_texture_transform* t, float uv[2]);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* RTPBR_GLTF_H */
