// Internal declarations shared by the engine's source files.
#ifndef RTPBR_INTERNAL_H
#define RTPBR_INTERNAL_H

#include <stdarg.h>
#include <stdbool.h>

#include "rtpbr/rtpbr.h"
#include "rtpbr_shared.h"

#if defined(__GNUC__)
#define RTPBR_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define RTPBR_PRINTF(f, a)
#endif

// ---------------------------------------------------------------------------------------------
// GPU-side structs (std140 / std430; layouts must match the shaders)

// The per-frame uniform block (fields in rtpbr_shared.h).
RTPBR_SHARED_STRUCT(rtpbr_shader_frame, RTPBR_FRAME_FIELDS)
RTPBR_SHARED_CHECK_LAYOUT(rtpbr_shader_frame, RTPBR_FRAME_FIELDS)

// The material record (fields in rtpbr_shared.h).
RTPBR_SHARED_STRUCT(rtpbr_shader_material, RTPBR_MATERIAL_FIELDS)
RTPBR_SHARED_CHECK_LAYOUT(rtpbr_shader_material, RTPBR_MATERIAL_FIELDS)

// std430 element of the lights buffer (lighting.comp).
typedef struct rtpbr_shader_light {
    float vertices[RTPBR_SHADER_MAX_POLYGON_VERTICES][4]; // xyz, w unused
    float emission[4];         // rgb radiance, w: 1 if two-sided
    float plane[4];            // unit normal xyz, w = -dot(normal, vertex0)
    float sphere[4];           // bounding sphere: centre xyz, radius w
    uint32_t vertex_count;
    float area;
    uint32_t pad[2];
} rtpbr_shader_light;

// Push constants of the G-buffer pass (per draw).
typedef struct rtpbr_shader_draw {
    float world_from_object[16];
    float normal_matrix[12];   // inverse-transpose 3x3 as three vec4 columns (std430)
    uint32_t material;
    uint32_t pad[3];
} rtpbr_shader_draw;

// Push constants of the supersampling resolve (resolve.comp).
typedef struct rtpbr_shader_resolve {
    uint32_t size[2];
    uint32_t factor;
    uint32_t pad;
} rtpbr_shader_resolve;

// Push constants of the tone-mapping pass.
typedef struct rtpbr_shader_tonemap {
    float scale;               // 2^exposure
    uint32_t op;               // RTPBR_TONEMAP_OP_*
    uint32_t encode;           // RTPBR_ENCODE_*
    uint32_t pad;
} rtpbr_shader_tonemap;

// Push constants of the Monte Carlo lighting pass (lighting_mc.comp).
typedef struct rtpbr_shader_mc {
    uint32_t samples;          // per pixel and light, >= 1
    uint32_t seed;
} rtpbr_shader_mc;

// std430 element of a scene's BVH node buffer (bvh.c, shaders/bvh.glsl).
typedef struct rtpbr_shader_bvh_node {
    float min[3];
    uint32_t left_or_first;    // interior (count 0): left child, the right one follows; leaf: first triangle
    float max[3];
    uint32_t count;            // triangles of a leaf; 0: interior node
} rtpbr_shader_bvh_node;

// std430 element of a scene's BVH triangle buffer: vertex 0 and the two edges from it.
typedef struct rtpbr_shader_bvh_triangle {
    float v0[4], e1[4], e2[4];
} rtpbr_shader_bvh_triangle;

// Push constants of the shadow passes (shadow.comp, shadow_denoise.comp).
typedef struct rtpbr_shader_shadow {
    uint32_t samples;          // per pixel and shadowed light, >= 1
    uint32_t seed;
    uint32_t radius;           // of the denoiser's (2 radius + 1)^2 window; 0: no denoising
    uint32_t pad;
} rtpbr_shader_shadow;

// The shaders' std140 / std430 sizes of the same structs.
_Static_assert(sizeof(rtpbr_shader_frame) == 192, "Frame block layout");
_Static_assert(sizeof(rtpbr_shader_bvh_node) == 32, "BVH node layout");
_Static_assert(sizeof(rtpbr_shader_bvh_triangle) == 48, "BVH triangle layout");
_Static_assert(RTPBR_SHADER_MAX_SHADOWED_LIGHTS == RTPBR_MAX_SHADOWED_LIGHTS, "shadowed light limit shared by C and shaders");
_Static_assert(sizeof(rtpbr_shader_material) == 128, "Material layout");
_Static_assert(sizeof(rtpbr_shader_light) == 192, "Light layout");
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

// A lookup table: an RGBA float image sampled with linear filtering, built from a C array.
typedef struct rtpbr_lut {
    rtpbr_image image;
} rtpbr_lut;

// ---------------------------------------------------------------------------------------------
// Context (core.c, device.c)

#define RTPBR_LIGHTING_VARIANT_COUNT 4 // (GGX, Beckmann) x (multiscatter off, on)
// LTC lighting pipelines: per variant, one per lit tile class (BASIC, FULL); the EMPTY class
// has one pipeline of its own (it shades no light).
#define RTPBR_LIT_CLASS_COUNT (RTPBR_TILE_CLASS_COUNT - 1)
#define RTPBR_TONEMAP_PIPELINE_CACHE 8 // tone-mapping pipelines, one per target format

typedef struct rtpbr_tonemap_pipeline {
    VkFormat format;
    VkPipeline pipeline;
} rtpbr_tonemap_pipeline;

struct rtpbr_context {
    rtpbr_allocator allocator;
    rtpbr_logger logger;
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

    VkCommandPool command_pool;   // the context's and every renderer's command buffers
    VkCommandBuffer upload_cmd;   // one-shot uploads (rtpbr_submit_once)
    VkFence upload_fence;
    VkSampler lut_sampler;        // linear, clamp to edge
    VkSampler gbuffer_sampler;    // nearest (the G-buffer is read with texelFetch)
    VkSampler texture_sampler;    // material textures: linear, repeat
    VkDescriptorSetLayout material_set_layout; // set 1 of the G-buffer pass
    rtpbr_lut luts[RTPBR_LUT_COUNT]; // in binding order RTPBR_BINDING_LUT_LTC_GGX_1 ...

    VkDescriptorSetLayout gbuffer_set_layout;
    VkPipelineLayout gbuffer_layout;
    VkPipeline gbuffer_pipeline;
    VkDescriptorSetLayout lighting_set_layout;
    VkPipelineLayout lighting_layout;
    VkPipeline lighting_pipelines[RTPBR_LIGHTING_VARIANT_COUNT][RTPBR_LIT_CLASS_COUNT];
    VkPipeline lighting_empty_pipeline; // tiles without light: emission and background
    VkPipeline cull_pipeline;           // cull.comp: tile light masks and class queues
    // The Monte Carlo lighting pass: same set layout, plus push constants rtpbr_shader_mc.
    VkPipelineLayout lighting_mc_layout;
    VkPipeline lighting_mc_pipelines[RTPBR_LIGHTING_VARIANT_COUNT];
    VkDescriptorSetLayout resolve_set_layout;
    VkPipelineLayout resolve_layout;
    VkPipeline resolve_pipeline;
    VkDescriptorSetLayout tonemap_set_layout;
    VkPipelineLayout tonemap_layout;
    VkShaderModule tonemap_vert, tonemap_frag;
    rtpbr_tonemap_pipeline tonemap_pipelines[RTPBR_TONEMAP_PIPELINE_CACHE];
    // Live children, so that rtpbr_context_destroy can destroy what the host left behind
    // (rtpbr.h states the teardown order). Linked through their own prev/next fields.
    rtpbr_gpu_scene *scenes;
    rtpbr_renderer *renderers;
    // The shadow passes (shadow.c): one set layout and pipeline layout, pipelines on first use.
    VkDescriptorSetLayout shadow_set_layout;
    VkPipelineLayout shadow_layout;
    VkPipeline shadow_trace_pipeline, shadow_denoise_pipeline;
};

// ---------------------------------------------------------------------------------------------
// Scene (scene.c)

typedef struct rtpbr_draw {
    uint32_t first_index, index_count;
    rtpbr_shader_draw push;
} rtpbr_draw;

struct rtpbr_gpu_scene {
    rtpbr_context *context;
    rtpbr_gpu_scene *prev, *next; // in context->scenes
    rtpbr_buffer vertices;     // RTPBR_VERTEX_FLOATS per vertex: position, normal, uv, tangent
    rtpbr_buffer indices;      // uint32, vertex indices already offset per mesh
    rtpbr_buffer materials;    // rtpbr_shader_material[max(material_count, 1)]
    rtpbr_buffer lights;       // rtpbr_shader_light[RTPBR_MAX_LIGHTS], host visible
    rtpbr_image *textures;     // texture_count images, then a 1x1 white one
    uint32_t texture_count;
    VkDescriptorPool material_pool;
    VkDescriptorSet *material_sets; // one per material slot: its three textures
    rtpbr_draw *draws;
    uint32_t draw_count;
    uint32_t light_count;
    uint32_t material_count;   // of the desc (the buffer has max(material_count, 1) slots)
    rtpbr_camera_desc *cameras;
    uint32_t camera_count;
    rtpbr_buffer bvh_nodes;     // rtpbr_shader_bvh_node[bvh_node_count] (bvh.c)
    rtpbr_buffer bvh_triangles; // rtpbr_shader_bvh_triangle[max(bvh_triangle_count, 1)]
    uint32_t bvh_node_count, bvh_triangle_count;
};

// ---------------------------------------------------------------------------------------------
// Renderer (renderer.c and the passes)

enum { RTPBR_GBUFFER_COUNT = 4 };
enum { RTPBR_VERTEX_FLOATS = 12 }; // float3 position, float3 normal, float2 uv, float4 tangent

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
    VkDescriptorSet resolve_set;
    rtpbr_image gbuffer[RTPBR_GBUFFER_COUNT];
    rtpbr_image depth;
    rtpbr_image radiance;      // rgba32f, GENERAL layout between passes
    rtpbr_image display;       // R8G8B8A8_SRGB, the target of rtpbr_render
    rtpbr_buffer frame;        // rtpbr_shader_frame, host visible
    uint32_t tiles_x, tiles_y; // lighting tiles of the shaded image (RTPBR_TILE_SIZE pixels a side)
    rtpbr_buffer tile_masks;   // RTPBR_TILE_MASK_WORDS uints per tile (cull.comp)
    rtpbr_buffer tile_lists;   // per class: indirect dispatch arguments, then the tile queues
    rtpbr_buffer radiance_readback, display_readback;
    VkDescriptorPool descriptor_pool;
    VkDescriptorSet gbuffer_set, lighting_set, tonemap_set;
    VkCommandBuffer cmd;
    VkFence fence;
    bool has_frame;            // rtpbr_render completed at least once
    rtpbr_timing timing;       // GPU timestamps (rtpbr_renderer_desc.timings), else all zero
    bool has_radiance;         // rtpbr_render or rtpbr_record has filled radiance_readback
    // Shadows (shadow.c), at the shading size, RTPBR_MAX_SHADOWED_LIGHTS layers, GENERAL layout:
    rtpbr_image shadow_estimates; // R32_UINT: packHalf2x16(shadowed, unshadowed estimate)
    rtpbr_image shadow_ratio;     // R32_SFLOAT: denoised shadowed / unshadowed (lighting binding)
    VkDescriptorSet shadow_set;
};

extern const VkFormat rtpbr_gbuffer_formats[RTPBR_GBUFFER_COUNT];
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
// Helpers (core.c)

// Zeroed; on failure logs "out of host memory" with the size, so every caller's
// RTPBR_ERROR_OUT_OF_HOST_MEMORY has a message.
void *rtpbr_alloc(const rtpbr_context *ctx, size_t size);
void rtpbr_free(const rtpbr_context *ctx, void *ptr);
void rtpbr_log(const rtpbr_context *ctx, rtpbr_log_level level, const char *fmt, ...) RTPBR_PRINTF(3, 4);
void rtpbr_logv(const rtpbr_logger *logger, rtpbr_log_level level, const char *fmt, va_list args);
// Logs "<what> failed: <VkResult name>" and maps the VkResult to an rtpbr_result.
rtpbr_result rtpbr_vk_fail(const rtpbr_context *ctx, VkResult vr, const char *what);
const char *rtpbr_vk_result_name(VkResult vr);

// Checks a VkResult inside a function with a `result` variable and a `cleanup` label.
#define RTPBR_VK(ctx, call)                                   \
    do {                                                      \
        VkResult vr_ = (call);                                \
        if (vr_ != VK_SUCCESS) {                              \
            result = rtpbr_vk_fail((ctx), vr_, #call);        \
            goto cleanup;                                     \
        }                                                     \
    } while (0)
// Propagates an rtpbr_result inside such a function.
#define RTPBR_TRY(call)                                       \
    do {                                                      \
        result = (call);                                      \
        if (result != RTPBR_SUCCESS) goto cleanup;            \
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
// Records into ctx->upload_cmd, submits, waits. record(cmd, user) records the work.
rtpbr_result rtpbr_submit_once(rtpbr_context *ctx, void (*record)(VkCommandBuffer cmd, void *user),
                               void *user);
// A lookup table from a C array of width*height*depth RGBA floats (x fastest, then y, then
// z): an RGBA32F image, 3D when depth > 1 (RGBA16F when the device cannot filter 32-bit
// floats), SHADER_READ_ONLY_OPTIMAL, sampled through ctx->lut_sampler.
rtpbr_result rtpbr_lut_create(rtpbr_context *ctx, uint32_t width, uint32_t height, uint32_t depth, const float *rgba,
                              rtpbr_lut *out);
void rtpbr_lut_destroy(rtpbr_context *ctx, rtpbr_lut *lut);
// Every table of ctx->luts (luts.c): the shader library's tables, or placeholders.
rtpbr_result rtpbr_luts_create(rtpbr_context *ctx);
void rtpbr_luts_destroy(rtpbr_context *ctx);
// Uploads tightly packed texels into a new sampled image (SHADER_READ_ONLY_OPTIMAL).
rtpbr_result rtpbr_image_create_with_data(rtpbr_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                                          const void *texels, size_t bytes, rtpbr_image *out);
// An image memory barrier on a colour or depth image (one mip, one layer).
void rtpbr_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                         VkImageLayout old_layout, VkImageLayout new_layout,
                         VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                         VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);

// ---------------------------------------------------------------------------------------------
// Shaders and pipelines (shaders.c); SPIR-V is embedded by the build (spirv.c, generated)

typedef struct rtpbr_spirv {
    const uint32_t *code;
    size_t size;               // bytes
} rtpbr_spirv;

rtpbr_result rtpbr_shader_module(rtpbr_context *ctx, rtpbr_spirv spirv, VkShaderModule *out);
rtpbr_result rtpbr_pipelines_create(rtpbr_context *ctx);
void rtpbr_pipelines_destroy(rtpbr_context *ctx);
// The lighting pipelines of a model variant, compiled on first use: the Monte Carlo pass's
// (out[0]), or the LTC pass's per tile class (out[RTPBR_TILE_CLASS_*]).
rtpbr_result rtpbr_lighting_pipelines_get(rtpbr_context *ctx, bool monte_carlo, rtpbr_ndf ndf, rtpbr_multiscatter ms,
                                          VkPipeline out[RTPBR_TILE_CLASS_COUNT]);

// The tone-mapping pipeline for a colour-attachment format (created on first use).
rtpbr_result rtpbr_tonemap_pipeline_get(rtpbr_context *ctx, VkFormat format, VkPipeline *out);

// ---------------------------------------------------------------------------------------------
// Passes (gbuffer.c, lighting.c, tonemap.c)

void rtpbr_gbuffer_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, VkCommandBuffer cmd);
void rtpbr_lighting_record(rtpbr_renderer *r, const VkPipeline pipelines[RTPBR_TILE_CLASS_COUNT], VkCommandBuffer cmd);
void rtpbr_lighting_mc_record(rtpbr_renderer *r, VkPipeline pipeline, const rtpbr_shader_mc *params,
                              VkCommandBuffer cmd);
void rtpbr_tonemap_record(rtpbr_renderer *r, VkPipeline pipeline, const rtpbr_shader_tonemap *params,
                          VkImageView target, VkCommandBuffer cmd);

// ---------------------------------------------------------------------------------------------
// Shadows: the scene's BVH (bvh.c) and the shadow passes (shadow.c)

// Builds the BVH of the scene's uploaded triangles (world space) into scene->bvh_*.
rtpbr_result rtpbr_bvh_create(rtpbr_gpu_scene *scene);
void rtpbr_bvh_destroy(rtpbr_gpu_scene *scene); // accepts a half-built scene
// The set and pipeline layouts (context creation); the pipelines are made on first use.
rtpbr_result rtpbr_shadow_layouts_create(rtpbr_context *ctx);
void rtpbr_shadow_pipelines_destroy(rtpbr_context *ctx);
rtpbr_result rtpbr_shadow_pipelines_get(rtpbr_context *ctx);
// The renderer's shadow images (in GENERAL layout) and descriptor set (from r->descriptor_pool).
rtpbr_result rtpbr_shadow_targets_create(rtpbr_renderer *r);
void rtpbr_shadow_targets_destroy(rtpbr_renderer *r);
// Writes the scene's buffers into the shadow set (prepare_frame).
void rtpbr_shadow_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene);
// Records the trace and denoise dispatches; the ratios are ready for the lighting pass after.
void rtpbr_shadow_record(rtpbr_renderer *r, const rtpbr_shader_shadow *params, VkCommandBuffer cmd);

// ---------------------------------------------------------------------------------------------
// Math (math.c): column-major 4x4 matrices

void rtpbr_mat4_identity(float m[16]);
void rtpbr_mat4_mul(float out[16], const float a[16], const float b[16]);
bool rtpbr_mat4_invert(float out[16], const float m[16]);
// Vulkan clip space (y down, depth 0..1), right-handed view looking down -Z.
void rtpbr_camera_matrices(const rtpbr_camera_desc *camera, float aspect, float view_proj[16]);
bool rtpbr_finite(const float *v, size_t n);

#endif // RTPBR_INTERNAL_H
