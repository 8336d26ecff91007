// Internal declarations shared by the engine's source files.
#ifndef RTPBR_INTERNAL_H
#define RTPBR_INTERNAL_H

#include <stdbool.h>

#include "rtpbr/rtpbr.h"
#include "rtpbr_shared.h"
#include "util.h"

// ---------------------------------------------------------------------------------------------
// GPU-side structs (std140 / std430; layouts must match the shaders)

// The per-frame uniform block (fields in rtpbr_shared.h).
RTPBR_SHARED_STRUCT(rtpbr_shader_frame, RTPBR_FRAME_FIELDS)
RTPBR_SHARED_CHECK_LAYOUT(rtpbr_shader_frame, RTPBR_FRAME_FIELDS)

// The material record (fields in rtpbr_shared.h).
RTPBR_SHARED_STRUCT(rtpbr_shader_material, RTPBR_MATERIAL_FIELDS)
RTPBR_SHARED_CHECK_LAYOUT(rtpbr_shader_material, RTPBR_MATERIAL_FIELDS)

// The rest of the contract (fields and meaning in rtpbr_shared.h, next to each pass's bindings).
#define RTPBR_DECLARE_SHARED(S, FIELDS) RTPBR_SHARED_STRUCT(S, FIELDS) RTPBR_SHARED_CHECK_LAYOUT(S, FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_light, RTPBR_LIGHT_FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_draw, RTPBR_DRAW_FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_resolve, RTPBR_RESOLVE_FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_tonemap, RTPBR_TONEMAP_FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_mc, RTPBR_MC_FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_bvh_node, RTPBR_BVH_NODE_FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_bvh_triangle, RTPBR_BVH_TRIANGLE_FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_alpha_texture, RTPBR_ALPHA_TEXTURE_FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_shadow, RTPBR_SHADOW_FIELDS)
RTPBR_DECLARE_SHARED(rtpbr_shader_texture_transforms, RTPBR_TEXTURE_TRANSFORMS_FIELDS)

// The shaders' std140 / std430 sizes of the same structs.
_Static_assert(sizeof(rtpbr_shader_frame) == 192, "Frame block layout");
_Static_assert(sizeof(rtpbr_shader_bvh_node) == 32, "BVH node layout");
_Static_assert(sizeof(rtpbr_shader_bvh_triangle) == 64, "BVH triangle layout");
_Static_assert(sizeof(rtpbr_shader_alpha_texture) == 16, "Alpha texture layout");
_Static_assert(RTPBR_SHADER_MAX_SHADOWED_LIGHTS == RTPBR_MAX_SHADOWED_LIGHTS, "shadowed light limit shared by C and shaders");
// One vertex limit (rtpbr.h's is the source of truth; the shaders' against ltc.h's:
// engine/shaders/vertex_limit.glsl).
_Static_assert(RTPBR_SHADER_MAX_POLYGON_VERTICES == RTPBR_MAX_POLYGON_VERTICES,
               "RTPBR_SHADER_MAX_POLYGON_VERTICES (rtpbr_shared.h) differs from RTPBR_MAX_POLYGON_VERTICES (rtpbr.h)");
_Static_assert(sizeof(rtpbr_shader_material) == 144, "Material layout");
_Static_assert(sizeof(rtpbr_shader_light) == 208, "Light layout");
_Static_assert(RTPBR_LIGHT_SHAPE_POLYGON == RTPBR_LIGHT_POLYGON && RTPBR_LIGHT_SHAPE_POINT == RTPBR_LIGHT_POINT &&
                   RTPBR_LIGHT_SHAPE_SPOT == RTPBR_LIGHT_SPOT && RTPBR_LIGHT_SHAPE_DIRECTIONAL == RTPBR_LIGHT_DIRECTIONAL,
               "light shapes (rtpbr_shared.h) equal rtpbr_light_type (rtpbr.h)");
_Static_assert(sizeof(rtpbr_shader_draw) == 128, "Draw push constants (128 bytes: the guaranteed minimum)");
_Static_assert(RTPBR_SHADER_MAX_LIGHTS == RTPBR_MAX_LIGHTS, "light limit shared by C and shaders");
_Static_assert(RTPBR_TILE_SIZE == RTPBR_TILE_SIZE_PIXELS, "tile size shared by C and shaders");

// ---------------------------------------------------------------------------------------------
// Resources (resources.c)

typedef struct rtpbr_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    VkDeviceSize size;
    void *mapped;              // non-NULL for host-visible buffers (persistently mapped)
} rtpbr_buffer;

typedef struct rtpbr_image {
    VkImage image;
    VkImageView view;
    VkDeviceMemory memory;
    VkFormat format;
    uint32_t width, height;
} rtpbr_image;

// One descriptor set of a renderer, in a pool of its own sized from its pass's binding table
// (passes/pipeline.c).
typedef struct rtpbr_descriptor_set {
    VkDescriptorPool pool;
    VkDescriptorSet set;
} rtpbr_descriptor_set;

// A lookup table: an RGBA float image sampled with linear filtering, built from a C array.
typedef struct rtpbr_lut {
    rtpbr_image image;
} rtpbr_lut;

// ---------------------------------------------------------------------------------------------
// Context (context.c, device.c)

#define RTPBR_LIGHTING_VARIANT_COUNT 4 // (GGX, Beckmann) x (multiscatter off, on)
// LTC lighting pipelines: per variant, one per lit tile class (BASIC, FULL); the EMPTY class
// has one pipeline of its own (it shades no light).
#define RTPBR_LIT_CLASS_COUNT (RTPBR_TILE_CLASS_COUNT - 1)
// The LTC pipelines' specializations (RTPBR_SPEC_LIGHTING_*): a frame's polygons of at most 3,
// 4 or RTPBR_SHADER_MAX_POLYGON_VERTICES vertices, without or with punctual lights, its
// materials with any of the 16 combinations of the full variant's features, the lights read
// from the storage or the uniform buffer, with or without shadows.
#define RTPBR_LIGHTING_SPEC_COUNT (3 * 2 * 16 * 2 * 2)
// The bytes of the lights' uniform binding (RTPBR_BINDING_LIGHT_LIGHTS_UNIFORM).
#define RTPBR_UNIFORM_LIGHTS_BYTES (RTPBR_UNIFORM_LIGHTS_MAX * sizeof(rtpbr_shader_light))
#define RTPBR_TONEMAP_PIPELINE_CACHE 24 // tone-mapping pipelines, per target format (8) and operator (3)

// Each pass's layouts and pipelines, made and destroyed by its file in passes/ (init at
// context creation, finish at its destruction; a half-built one is finished like a whole one).
typedef struct rtpbr_gbuffer_pass {              // passes/gbuffer.c
    VkDescriptorSetLayout set_layout;            // set 0: frame, materials (one set per renderer)
    VkDescriptorSetLayout material_set_layout;   // set 1: a material's textures (per scene material)
    VkPipelineLayout layout;                     // + push constants rtpbr_shader_draw
    // per set of texture slots (RTPBR_SPEC_GBUFFER_TEXTURES), compiled on first use
    VkPipeline pipelines[RTPBR_GBUFFER_TEXTURES_ALL + 1];
} rtpbr_gbuffer_pass;

typedef struct rtpbr_lighting_pass {             // passes/lighting.c, passes/lighting_mc.c
    VkDescriptorSetLayout set_layout;            // shared by cull, LTC and Monte Carlo
    VkPipelineLayout layout;                     // cull and LTC: no push constants
    VkPipeline cull;                             // cull.comp: tile light masks and class queues
    VkPipeline empty[2];                         // tiles without light: background, emission ([1]) or 0 ([0])
    // compiled on first use, per specialization (rtpbr_lighting_pipelines_get: RTPBR_SPEC_LIGHTING_*)
    VkPipeline ltc[RTPBR_LIGHTING_VARIANT_COUNT][RTPBR_LIT_CLASS_COUNT][RTPBR_LIGHTING_SPEC_COUNT];
    bool cpu_device;                             // RTPBR_SPEC_LIGHTING_CPU of every LTC pipeline
    bool uniform_lights;                         // a CPU device that binds RTPBR_UNIFORM_LIGHTS_BYTES:
                                                 // RTPBR_SPEC_LIGHTING_UNIFORM_LIGHTS where a frame's lights fit
    VkDeviceSize uniform_lights_range;           // its binding's bytes: at most the device's maxUniformBufferRange
    VkPipelineLayout mc_layout;                  // + push constants rtpbr_shader_mc
    VkPipeline mc[RTPBR_LIGHTING_VARIANT_COUNT]; // compiled on first use
} rtpbr_lighting_pass;

typedef struct rtpbr_forward_pass {              // passes/forward.c
    VkDescriptorSetLayout set_layout;            // set 0 (set 1: the G-buffer pass's material sets)
    VkPipelineLayout layout;                     // + push constants rtpbr_shader_draw
    VkPipeline pipelines[2 * RTPBR_LIGHTING_VARIANT_COUNT]; // compiled on first use; the second
                                                 // half: with the spheres' loop
} rtpbr_forward_pass;

typedef struct rtpbr_resolve_pass {              // passes/resolve.c
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;                     // + push constants rtpbr_shader_resolve
    VkPipeline pipeline;
} rtpbr_resolve_pass;

typedef struct rtpbr_tonemap_pipeline {
    VkFormat format;
    uint32_t op, encode; // RTPBR_TONEMAP_OP_*, RTPBR_ENCODE_* (its specialization)
    VkPipeline pipeline;
} rtpbr_tonemap_pipeline;

typedef struct rtpbr_tonemap_pass {              // passes/tonemap.c
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;                     // + push constants rtpbr_shader_tonemap
    VkShaderModule vert, frag;
    rtpbr_tonemap_pipeline pipelines[RTPBR_TONEMAP_PIPELINE_CACHE]; // per target format and operator, on first use
} rtpbr_tonemap_pass;

typedef struct rtpbr_shadow_pass {               // passes/shadow.c
    VkDescriptorSetLayout set_layout;            // shared by the selection, the trace and the denoiser
    VkPipelineLayout layout;                     // + push constants rtpbr_shader_shadow
    VkPipeline select, list, trace, denoise;     // compiled on first use
    VkPipeline trace_opaque;                     // the trace without the alpha test (RTPBR_SPEC_BVH_ALPHA off)
    bool texel_reads;                            // RTPBR_SPEC_BVH_TEXELS of the selection and the trace
    bool cpu;                                    // a CPU device: RTPBR_SPEC_BVH_PACKET_ALPHA of the trace
    VkDeviceSize texel_view_range;               // the most bytes a BVH texel view may span (the device's limit)
} rtpbr_shadow_pass;

struct rtpbr_context {
    rtpbr_host host;              // the desc's allocator and logger
    bool embedded;
    uint32_t validation_messages;
    char device_name[VK_MAX_PHYSICAL_DEVICE_NAME_SIZE];

    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    VkPhysicalDeviceMemoryProperties memory_properties;
    // Shadow rays by VK_KHR_ray_query (device.c; rtpbr_context_desc.shadow_ray_query): the
    // extension's entry points, and the scratch alignment of acceleration-structure builds.
    int ray_query_mode;           // rtpbr_shadow_ray_query
    bool ray_query;               // the shadow pass traces with ray queries (accel.c)
    struct {
        PFN_vkCreateAccelerationStructureKHR create;
        PFN_vkDestroyAccelerationStructureKHR destroy;
        PFN_vkGetAccelerationStructureBuildSizesKHR build_sizes;
        PFN_vkCmdBuildAccelerationStructuresKHR cmd_build;
        PFN_vkGetAccelerationStructureDeviceAddressKHR address;
        uint32_t scratch_alignment;
    } accel;

    VkCommandPool command_pool;   // the context's and every renderer's command buffers
    VkCommandBuffer upload_cmd;   // one-shot uploads (rtpbr_submit_once)
    VkFence upload_fence;
    VkSampler lut_sampler;        // linear, clamp to edge
    VkSampler gbuffer_sampler;    // nearest (the G-buffer is read with texelFetch)
    VkSampler light_texture_sampler; // trilinear, clamp to edge, every level (light textures)
    rtpbr_image light_texture_stand_in; // a 1-layer chain of ones: RTPBR_BINDING_LIGHT_TEXTURES
                                        // where no textured light is bound (light sets)
    float max_anisotropy;         // material textures' sampler anisotropy; 0: samplerAnisotropy not enabled
    rtpbr_lut luts[RTPBR_LUT_COUNT]; // in binding order RTPBR_BINDING_LUT_LTC_GGX_1 ...

    rtpbr_gbuffer_pass gbuffer;
    rtpbr_lighting_pass lighting;
    rtpbr_resolve_pass resolve;
    rtpbr_tonemap_pass tonemap;
    rtpbr_shadow_pass shadow;
    rtpbr_forward_pass forward;
    // Live children, so that rtpbr_context_destroy can destroy what the host left behind
    // (rtpbr.h: the context owns them). Linked through their own prev/next fields.
    rtpbr_gpu_scene *scenes;
    rtpbr_renderer *renderers;
    rtpbr_light_set *light_sets;               // lightpass.c
    rtpbr_lighting_targets *lighting_targets;  // lightpass.c
    uint64_t serial;                           // the last light set's serial (lightpass.c)
};

// ---------------------------------------------------------------------------------------------
// Scene (scene.c)

typedef struct rtpbr_draw {
    uint32_t first_index, index_count;
    rtpbr_shader_draw push;
    float center[3]; // of the mesh's bounding box, object space (the forward pass sorts by it)
} rtpbr_draw;

// A BLEND draw and its squared view distance (passes/forward.c sorts them).
typedef struct rtpbr_draw_depth {
    float distance2;
    uint32_t draw;
} rtpbr_draw_depth;

// The samplers of material textures, one per combination of the rtpbr_texture_desc fields:
// key = ((wrap_s * 3 + wrap_t) * 2 + mag_filter) * 2 + min_filter) * 3 + mipmap.
enum { RTPBR_SAMPLER_KEY_COUNT = 3 * 3 * 2 * 2 * 3 };

struct rtpbr_gpu_scene {
    rtpbr_context *context;
    rtpbr_gpu_scene *prev, *next; // in context->scenes
    rtpbr_buffer vertices;     // RTPBR_VERTEX_FLOATS per vertex: position, normal, uv, tangent, uv1
    rtpbr_buffer indices;      // uint32, vertex indices already offset per mesh
    rtpbr_buffer materials;    // rtpbr_shader_material[max(material_count, 1)]
    rtpbr_buffer lights;       // rtpbr_shader_light[RTPBR_MAX_LIGHTS], host visible
    rtpbr_image *textures;     // texture_count images, then a 1x1 white one
    uint32_t *texture_samplers; // per image: its key into samplers (rtpbr_sampler_key)
    uint32_t texture_count;
    VkSampler samplers[RTPBR_SAMPLER_KEY_COUNT]; // created on first use by a texture
    rtpbr_buffer texture_transforms; // rtpbr_shader_texture_transforms[max(material_count, 1)]
    VkDescriptorPool material_pool;  // passes/gbuffer.c
    VkDescriptorSet *material_sets; // one per material slot: its RTPBR_MATERIAL_TEXTURE_COUNT textures
    uint8_t *material_extension_textures; // per material slot: its RTPBR_EXTENSION_TEXTURES_* bits
    uint8_t *material_gbuffer_slots; // per material slot: the G-buffer pipeline's texture slots (rtpbr_gbuffer_material_slots)
    rtpbr_draw *draws;
    uint32_t draw_count;
    rtpbr_draw_depth *blend_order; // draw_count entries: the forward pass's scratch
    uint32_t light_count;
    uint32_t material_count;   // of the desc (the buffer has max(material_count, 1) slots)
    rtpbr_camera_desc *cameras;
    uint32_t camera_count;
    rtpbr_buffer bvh_nodes;     // rtpbr_shader_bvh_node[bvh_node_count] (bvh.c)
    rtpbr_buffer bvh_triangles; // rtpbr_shader_bvh_triangle[max(bvh_triangle_count, 1)]
    VkBufferView bvh_node_texels;     // the same as texel buffers (R32G32B32A32_UINT; at most
    VkBufferView bvh_triangle_texels; // ctx->shadow.texel_view_range bytes of each)
    uint32_t *bvh_triangle_draws; // the draw of each BVH triangle (its sidedness and alpha flag follow the material)
    uint32_t bvh_node_count, bvh_triangle_count;
    // With ctx->ray_query, the same triangles as acceleration structures (accel.c):
    rtpbr_buffer accel_vertices;   // host: 3 world-space vertices per triangle, by class
    rtpbr_buffer accel_triangles;  // storage: uint per triangle, its BVH triangle
    rtpbr_buffer accel_instances;  // host: VkAccelerationStructureInstanceKHR per bottom level
    rtpbr_buffer accel_storage;    // device: every level's storage
    VkAccelerationStructureKHR accel_blas[6], accel_tlas; // a bottom level per class of triangle
    rtpbr_buffer alpha_textures; // rtpbr_shader_alpha_texture[texture_count] (scene.c), for the shadow rays
    rtpbr_buffer alpha_texels;   // uint[]: the alpha bytes of the textures that have any below 255
    // The textured quads' prefiltered emission (light_texture.h): one layer per distinct
    // (texture, coordinates) of the creation's lights, in light_texture_keys; no image (the
    // context's stand-in is bound) without any.
    rtpbr_image light_textures;
    struct rtpbr_light_texture_key *light_texture_keys;
    uint32_t light_texture_layers;
};
// A textured light's chain: its texture (1 + index) and coordinates (defaults applied).
typedef struct rtpbr_light_texture_key {
    uint32_t texture;
    float uv[3][2];
} rtpbr_light_texture_key;
// The image a scene's lights read at RTPBR_BINDING_LIGHT_TEXTURES (its own, or the stand-in).
VkImageView rtpbr_gpu_scene_light_texture_view(const rtpbr_gpu_scene *scene);

// rtpbr_gpu_scene_create with the lights' derived facts (normal, centre, area, bounding sphere,
// fan; scene/rtpbr/rtpbr_gltf.h) given, one per light, as the loader computed them
// (rtpbr_gpu_scene_from_loaded); NULL: derived here from the vertices (rtpbr_gpu_scene_create).
struct rtpbr_gltf_polygon_facts;
rtpbr_result rtpbr_gpu_scene_create_with_light_facts(rtpbr_context *ctx, const rtpbr_gpu_scene_desc *desc,
                                                     const struct rtpbr_gltf_polygon_facts *light_facts,
                                                     rtpbr_gpu_scene **out_scene);

// What scenes and the lighting-only path (lightpass.c) share (scene.c): a material's record
// (the desc's defaults and flags applied) and its checks; a light's checks against its derived
// facts (index: for the message) and its record.
rtpbr_shader_material rtpbr_material_record(const rtpbr_material_desc *m);
rtpbr_result rtpbr_material_validate(const rtpbr_context *ctx, const rtpbr_material_desc *m, uint32_t index);
rtpbr_result rtpbr_light_validate(const rtpbr_context *ctx, const rtpbr_light_desc *l,
                                  const struct rtpbr_gltf_polygon_facts *f, uint32_t index);
void rtpbr_light_record(const rtpbr_light_desc *l, const struct rtpbr_gltf_polygon_facts *f, rtpbr_shader_light *out);
// Whether any of count light records is a sphere or a disk (the spheres' lighting variants
// are needed: their loop shades both).
bool rtpbr_lights_have_spheres(const rtpbr_shader_light *lights, uint32_t count);
// The lighting variants count lights need (rtpbr_lighting_pipelines_get): 3 with a tube, 2 with a textured quad,
// else 1 with a sphere or a disk, else 0.
uint32_t rtpbr_lights_shapes(const rtpbr_shader_light *lights, uint32_t count);
// What a frame needs of the LTC pipelines (rtpbr_lighting_pipelines_get): its lights' classes
// (rtpbr_lights_shapes) and the specialization (RTPBR_SPEC_LIGHTING_*) to its lights and materials.
typedef struct rtpbr_lighting_needs {
    uint32_t shapes;
    uint32_t max_vertices;      // the most vertices of a polygon: 3, 4 or RTPBR_SHADER_MAX_POLYGON_VERTICES
    bool punctual;              // a point, spot or directional light is among them
    uint32_t material_features; // the RTPBR_MATERIAL_FLAGS_FULL bits of any of its materials
    uint32_t light_count;       // its lights (records 0 .. light_count - 1)
    bool emission;              // a material emits (any emission not 0): the G-buffer's emission is read
    bool shadows;               // the frame's desc asks for shadows (its shadow_light_count may be
                                // > 0); false from rtpbr_lighting_needs_of: the caller sets it
} rtpbr_lighting_needs;
// A frame of count lights and material_count materials (every RTPBR_MATERIAL_FLAGS_FULL bit
// where one is Disney's: its coat and sheen are not the KHR ones).
rtpbr_lighting_needs rtpbr_lighting_needs_of(const rtpbr_shader_light *lights, uint32_t count,
                                             const rtpbr_shader_material *materials, uint32_t material_count);

// The RTPBR_EXTENSION_TEXTURES_* bits of the scene's materials together (scene.c): which of
// G-buffers 4 to 6 its frames render and read.
uint32_t rtpbr_gpu_scene_extension_textures(const rtpbr_gpu_scene *scene);

// ---------------------------------------------------------------------------------------------
// Renderer (renderer.c and the passes)

// G-buffers 0 to 3 (every frame), then 4 to 6: the extension textures' values, rendered only
// when the scene's materials have such textures (rtpbr_gpu_scene_extension_textures).
enum { RTPBR_GBUFFER_COUNT = 7, RTPBR_GBUFFER_FIRST_EXTENSION = 4 };

// GPU timestamps around the passes (timing.c): taken at the start and after each pass.
typedef enum rtpbr_timestamp {
    RTPBR_TIMESTAMP_START = 0,
    RTPBR_TIMESTAMP_GBUFFER,
    RTPBR_TIMESTAMP_LIGHTING,  // after the tile cull, the lighting pass and the supersampling resolve
    RTPBR_TIMESTAMP_TONEMAP,
    RTPBR_TIMESTAMP_COUNT
} rtpbr_timestamp;

typedef struct rtpbr_timing {
    VkQueryPool pool;          // RTPBR_TIMESTAMP_COUNT timestamps; VK_NULL_HANDLE: timings off
    float ns_per_tick;         // VkPhysicalDeviceLimits.timestampPeriod
    uint64_t valid_mask;       // the queue family's timestampValidBits
    bool recorded;             // a frame has written every timestamp
} rtpbr_timing;

struct rtpbr_renderer;
rtpbr_result rtpbr_timing_create(struct rtpbr_renderer *r);
void rtpbr_timing_destroy(struct rtpbr_renderer *r);
// Records timestamp `which` (START also resets the pool: outside any render pass). No-op
// when timings are off.
void rtpbr_timing_mark(struct rtpbr_renderer *r, VkCommandBuffer cmd, rtpbr_timestamp which);

struct rtpbr_renderer {
    rtpbr_context *context;
    rtpbr_renderer *prev, *next; // in context->renderers
    uint32_t width, height;    // of the output (radiance, display, readback)
    uint32_t supersample;      // >= 1
    uint32_t shade_width, shade_height; // of the G-buffer and lighting: supersample x the output
    rtpbr_image radiance_ss;   // the lighting pass's target when supersample > 1 (else unused)
    rtpbr_image gbuffer[RTPBR_GBUFFER_COUNT];
    rtpbr_image depth;
    rtpbr_image radiance;      // rgba32f, GENERAL layout between passes
    rtpbr_image display;       // R8G8B8A8_SRGB, the target of rtpbr_render
    rtpbr_buffer frame;        // rtpbr_shader_frame, host visible
    uint32_t tiles_x, tiles_y; // lighting tiles of the shaded image (RTPBR_TILE_SIZE pixels a side)
    rtpbr_buffer tile_masks;   // RTPBR_TILE_MASK_STRIDE uints per tile (cull.comp)
    rtpbr_buffer tile_lists;   // per class: indirect dispatch arguments, then the tile queues
    // Made by the first rtpbr_read_radiance / rtpbr_read_display (a renderer never read
    // back, e.g. one drawing into the host's frame, holds none).
    rtpbr_buffer radiance_readback, display_readback;
    // Each pass's descriptor set (made and written by its file in passes/).
    rtpbr_descriptor_set gbuffer_set, lighting_set, resolve_set, tonemap_set, shadow_set, forward_set;
    VkCommandBuffer cmd;       // rtpbr_render's frame, or a readback's copy (copy_back)
    VkFence fence;
    bool fence_pending;        // fence is signalled by a submission of cmd (wait before reusing it)
    bool has_frame;            // the display image holds the last rtpbr_render's frame
    rtpbr_timing timing;       // GPU timestamps (rtpbr_renderer_desc.timings), else all zero
    bool has_radiance;         // the radiance image holds the last rtpbr_render's or rtpbr_record's frame
    bool radiance_copied;      // radiance_readback holds that frame (copied by its first read)
    bool display_copied;       // display_readback holds the display image's frame
    // Shadows (passes/shadow.c), at the shading size, RTPBR_MAX_SHADOWED_LIGHTS layers, GENERAL layout:
    rtpbr_image shadow_estimates; // R32_SFLOAT, 2 layers per light: shadowed, unshadowed sum
    rtpbr_image shadow_ratio;     // R32_SFLOAT: denoised shadowed / unshadowed (lighting binding)
    rtpbr_buffer shadow_work;     // the trace's work list and indirect arguments (shadow_list.comp)
};

extern const VkFormat rtpbr_gbuffer_formats[RTPBR_GBUFFER_COUNT];
extern const VkPipelineVertexInputStateCreateInfo rtpbr_scene_vertex_input; // passes/gbuffer.c
#define RTPBR_DEPTH_FORMAT VK_FORMAT_D32_SFLOAT
#define RTPBR_RADIANCE_FORMAT VK_FORMAT_R32G32B32A32_SFLOAT
#define RTPBR_DISPLAY_FORMAT VK_FORMAT_R8G8B8A8_SRGB

// Intrusive doubly linked lists of a context's children (prev/next fields, head pointer).
#define RTPBR_LIST_LINK(head, node)                                                                 \
    do {                                                                                            \
        (node)->prev = NULL;                                                                        \
        (node)->next = (head);                                                                      \
        if (head) (head)->prev = (node);                                                            \
        (head) = (node);                                                                            \
    } while (0)
#define RTPBR_LIST_UNLINK(head, node)                                                               \
    do {                                                                                            \
        if ((node)->prev) (node)->prev->next = (node)->next;                                        \
        else if ((head) == (node)) (head) = (node)->next;                                           \
        if ((node)->next) (node)->next->prev = (node)->prev;                                        \
        (node)->prev = (node)->next = NULL;                                                         \
    } while (0)

// ---------------------------------------------------------------------------------------------
// Device (device.c)

rtpbr_result rtpbr_device_init_standalone(rtpbr_context *ctx, const rtpbr_context_desc *desc);
rtpbr_result rtpbr_device_init_embedded(rtpbr_context *ctx, const rtpbr_vulkan_device *host);
void rtpbr_device_finish(rtpbr_context *ctx);

// ---------------------------------------------------------------------------------------------
// Resources (resources.c)

// A buffer in host-visible coherent memory (device-local too when available), mapped.
rtpbr_result rtpbr_buffer_create_host(rtpbr_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                                      rtpbr_buffer *out);
void rtpbr_buffer_destroy(rtpbr_context *ctx, rtpbr_buffer *buffer);
// A buffer in device-local memory (any memory when there is none), not mapped.
rtpbr_result rtpbr_buffer_create_device(rtpbr_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                                        rtpbr_buffer *out);
// A 2D device-local image with a view (aspect from the format).
rtpbr_result rtpbr_image_create(rtpbr_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                                VkImageUsageFlags usage, rtpbr_image *out);
void rtpbr_image_destroy(rtpbr_context *ctx, rtpbr_image *image);
// The same with `layers` array layers and a 2D-array view (layers 0: rtpbr_image_create's).
rtpbr_result rtpbr_image_create_layers(rtpbr_context *ctx, uint32_t width, uint32_t height, uint32_t layers,
                                       VkFormat format, VkImageUsageFlags usage, rtpbr_image *out);
// A primary command buffer from ctx->command_pool and an unsignalled fence for its submissions
// (the caller frees both, also after a failure).
rtpbr_result rtpbr_command_buffer_create(rtpbr_context *ctx, VkCommandBuffer *cmd, VkFence *fence);
// Records into ctx->upload_cmd, submits, waits. record(cmd, user) records the work.
rtpbr_result rtpbr_submit_once(rtpbr_context *ctx, void (*record)(VkCommandBuffer cmd, void *user),
                               void *user);
// A lookup table from a C array of width*height*depth RGBA floats (x fastest, then y, then
// z): an RGBA32F image, 3D when depth > 1 (RGBA16F when the device cannot filter 32-bit
// floats), SHADER_READ_ONLY_OPTIMAL, sampled through ctx->lut_sampler.
rtpbr_result rtpbr_lut_create(rtpbr_context *ctx, uint32_t width, uint32_t height, uint32_t depth, const float *rgba,
                              rtpbr_lut *out);
void rtpbr_lut_destroy(rtpbr_context *ctx, rtpbr_lut *lut);
// Every table of ctx->luts (luts.c), from the shader library's generated arrays.
rtpbr_result rtpbr_luts_create(rtpbr_context *ctx);
void rtpbr_luts_destroy(rtpbr_context *ctx);
// The textured quads' prefiltered chains (light_texture.h: `layers` chains of
// RTPBR_LIGHT_TEXTURE_LEVELS levels, RGBA floats, one after the other) as one RGBA16F 2D-array
// image (SHADER_READ_ONLY_OPTIMAL), a layer per chain (RTPBR_BINDING_LIGHT_TEXTURES).
rtpbr_result rtpbr_light_textures_create(rtpbr_context *ctx, const float *chains, uint32_t layers, rtpbr_image *out);
// Uploads tightly packed texels into a new sampled image (SHADER_READ_ONLY_OPTIMAL).
rtpbr_result rtpbr_image_create_with_data(rtpbr_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                                          const void *texels, size_t bytes, rtpbr_image *out);
// A material texture: tightly packed texels into a new sampled image (SHADER_READ_ONLY_OPTIMAL),
// with its full mip chain built by linear blits when `mipmaps` and the format allows them.
rtpbr_result rtpbr_texture_create(rtpbr_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                                  const void *texels, size_t bytes, bool mipmaps, rtpbr_image *out);
// An image memory barrier on a colour or depth image (one mip, one layer).
void rtpbr_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                         VkImageLayout old_layout, VkImageLayout new_layout,
                         VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                         VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);
// The same on a range of mips and layers.
void rtpbr_image_range_barrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range,
                               VkImageLayout old_layout, VkImageLayout new_layout,
                               VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                               VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);

// ---------------------------------------------------------------------------------------------
// The scene's BVH for the shadow rays (bvh.c)

// Builds the BVH of the scene's uploaded triangles (world space) into scene->bvh_*.
rtpbr_result rtpbr_bvh_create(rtpbr_gpu_scene *scene);
void rtpbr_bvh_destroy(rtpbr_gpu_scene *scene); // accepts a half-built scene
// Rewrites each triangle's sidedness (v0.w) from its material and its draw's transform, and
// whether its material's alpha is tested (e1.w: MASK or BLEND).
void rtpbr_bvh_update_material_flags(rtpbr_gpu_scene *scene);
// The BVH's triangles again from the meshes' current transforms, and its boxes refitted to them
// (the tree kept: rtpbr_gpu_scene_set_transform); also their sidedness (a transform may mirror).
void rtpbr_bvh_refit(rtpbr_gpu_scene *scene);
// The acceleration structures of the BVH's triangles, with ctx->ray_query (accel.c; nothing
// without); rebuilt where the triangles' flags change.
rtpbr_result rtpbr_accel_create(rtpbr_gpu_scene *scene);
void rtpbr_accel_destroy(rtpbr_gpu_scene *scene); // accepts a half-built scene

#endif // RTPBR_INTERNAL_H
