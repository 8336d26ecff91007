// The passes of a frame, one file each in passes/, in the order a frame records them. Each
// file owns its pass's part of the GPU contract: the set layout (one binding table, from
// which the descriptor pool and every write take their types), the pipeline layout and
// pipelines, the descriptor writes, and the recording. The frame's orchestration (which
// passes run, barriers between the renderer's images, submission) is renderer.c's.
//
// Life cycle of each pass:
//   *_pass_init(ctx) / *_pass_finish(ctx)   layouts and pipelines in the context (finish
//                                           accepts a half-built pass);
//   *_renderer_init(r) / *_renderer_finish(r) the pass's descriptor set of a renderer, written
//                                           once with the renderer's images;
//   *_bind_scene(r, scene)                  the scene's buffers, written before recording;
//   *_record(r, ..., cmd)                   the commands.
// Pipelines not made at init are compiled on first use (*_get), before any recording starts.
#ifndef RTPBR_PASSES_H
#define RTPBR_PASSES_H

#include <stdbool.h>

#include "rtpbr/rtpbr.h"
#include "rtpbr_shared.h"

// ---- G-buffer (passes/gbuffer.c): rasterises every mesh into the G-buffer and depth. -----
rtpbr_result rtpbr_gbuffer_pass_init(rtpbr_context *ctx);
void rtpbr_gbuffer_pass_finish(rtpbr_context *ctx);
// gbuffer.vert's module (the forward pass draws with it too); the caller destroys it.
rtpbr_result rtpbr_gbuffer_vertex_module(rtpbr_context *ctx, VkShaderModule *out);
rtpbr_result rtpbr_gbuffer_renderer_init(rtpbr_renderer *r);
void rtpbr_gbuffer_renderer_finish(rtpbr_renderer *r);
// A scene's per-material texture sets (set 1): scene->material_pool and material_sets, one
// per material slot; then rtpbr_gbuffer_write_material_textures points slot m at its
// textures (indices into scene->textures, 0: the white stand-in).
rtpbr_result rtpbr_gbuffer_material_sets_create(rtpbr_gpu_scene *scene, uint32_t material_slots);
void rtpbr_gbuffer_material_sets_destroy(rtpbr_gpu_scene *scene);
void rtpbr_gbuffer_write_material_textures(rtpbr_gpu_scene *scene, uint32_t m,
                                           const uint32_t texture[RTPBR_MATERIAL_TEXTURE_COUNT]);
void rtpbr_gbuffer_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene);
// The G-buffer pipeline's texture slots for a material (RTPBR_SPEC_GBUFFER_TEXTURES): bit
// 1 << binding for each of the first RTPBR_GBUFFER_SPEC_SLOTS slots that has a texture (the
// normal slot's: RTPBR_MATERIAL_FLAG_NORMAL_MAPPED, the normal mapping compiled in with it).
uint8_t rtpbr_gbuffer_material_slots(const rtpbr_material_desc *material);
// Compiles, on first use, the G-buffer pipeline of each set of texture slots the scene's
// G-buffer draws use (scene->material_gbuffer_slots); before any recording (it may fail).
rtpbr_result rtpbr_gbuffer_pipelines_get(rtpbr_context *ctx, const rtpbr_gpu_scene *scene);
// After rtpbr_gbuffer_pipelines_get for the scene.
void rtpbr_gbuffer_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, VkCommandBuffer cmd);

// ---- Shadows (passes/shadow.c): ray-traced shadow ratios per shadowed light. -------------
rtpbr_result rtpbr_shadow_pass_init(rtpbr_context *ctx);
void rtpbr_shadow_pass_finish(rtpbr_context *ctx);
rtpbr_result rtpbr_shadow_pipelines_get(rtpbr_context *ctx, bool alpha_tested);
// The renderer's shadow images (in GENERAL layout from here on) and descriptor set.
rtpbr_result rtpbr_shadow_renderer_init(rtpbr_renderer *r);
void rtpbr_shadow_renderer_finish(rtpbr_renderer *r);
void rtpbr_shadow_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene);
// The trace and denoise dispatches; the ratios are ready for the lighting pass after them.
// The trace pipeline rtpbr_shadow_pipelines_get made for the scene's alpha modes.
void rtpbr_shadow_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, const rtpbr_render_desc *desc,
                         VkCommandBuffer cmd);

// ---- Lighting (passes/lighting.c): the tile cull, then the LTC pass per tile class. -------
// The Monte Carlo reference (passes/lighting_mc.c) shares its set layout and descriptor set.
rtpbr_result rtpbr_lighting_pass_init(rtpbr_context *ctx);
void rtpbr_lighting_pass_finish(rtpbr_context *ctx);
// The LTC pipelines of a model variant, one per tile class (out[RTPBR_TILE_CLASS_*]),
// compiled on first use, for a frame that needs what needs says (rtpbr_lighting_needs_of): its
// lights' classes (the spheres', textured quads' and tubes' classes are compiled only for a
// frame with such lights; without, their slots hold the others'), specialized to its polygons'
// most vertices, to whether it has punctual lights and (the full classes) to its materials'
// features.
struct rtpbr_lighting_needs; // internal.h
rtpbr_result rtpbr_lighting_pipelines_get(rtpbr_context *ctx, rtpbr_ndf ndf, rtpbr_multiscatter ms,
                                          const struct rtpbr_lighting_needs *needs,
                                          VkPipeline out[RTPBR_TILE_CLASS_COUNT]);
// Index of a model variant in rtpbr_lighting_pass's arrays.
uint32_t rtpbr_lighting_variant(rtpbr_ndf ndf, rtpbr_multiscatter ms);
struct rtpbr_buffer; // internal.h
// The culling pass's outputs for tiles_x x tiles_y tiles (a renderer's, the host path's
// targets'): six light masks per tile and its shadow slots (RTPBR_TILE_MASK_STRIDE uints:
// polygons, punctual lights, spheres, disks, textured quads and tubes, 8 slots), and
// per tile class its indirect dispatch arguments (a uvec4) and a queue as long as the tile count.
rtpbr_result rtpbr_lighting_tile_buffers_create(rtpbr_context *ctx, uint32_t tiles_x, uint32_t tiles_y,
                                                struct rtpbr_buffer *masks, struct rtpbr_buffer *lists);
// After rtpbr_shadow_renderer_init (the set binds the shadow ratios).
rtpbr_result rtpbr_lighting_renderer_init(rtpbr_renderer *r);
void rtpbr_lighting_renderer_finish(rtpbr_renderer *r);
void rtpbr_lighting_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene);
void rtpbr_lighting_ltc_record(rtpbr_renderer *r, const VkPipeline pipelines[RTPBR_TILE_CLASS_COUNT], VkCommandBuffer cmd);
// What the cull and LTC dispatches need of their target: a renderer's (rtpbr_lighting_ltc_record),
// or the host's G-buffer and output (lightpass.c, rtpbr_lighting_record). The output is
// moved from output_old_layout to GENERAL after output_src_stages / output_src_access.
typedef struct rtpbr_lighting_target {
    VkDescriptorSet set;          // of ctx->lighting.set_layout
    VkBuffer tile_lists;          // the class queues (VkDispatchIndirectCommand each, then tiles)
    uint32_t tiles_x, tiles_y;
    VkImage output;
    VkImageLayout output_old_layout;
    VkPipelineStageFlags output_src_stages;
    VkAccessFlags output_src_access;
} rtpbr_lighting_target;
void rtpbr_lighting_record_target(const rtpbr_context *ctx, const rtpbr_lighting_target *t,
                                  const VkPipeline pipelines[RTPBR_TILE_CLASS_COUNT], VkCommandBuffer cmd);
// The host path's sets (lightpass.c): `count` sets of the lighting layout in one pool (the
// caller destroys the pool), and their writes: a buffer range; an image view read through the
// G-buffer sampler (or, for RTPBR_BINDING_LIGHT_RADIANCE, as a storage image); the tables.
rtpbr_result rtpbr_lighting_sets_create(rtpbr_context *ctx, uint32_t count, VkDescriptorPool *pool,
                                        VkDescriptorSet *sets);
void rtpbr_lighting_write_buffer(rtpbr_context *ctx, VkDescriptorSet set, uint32_t binding, VkBuffer buffer,
                                 VkDeviceSize offset, VkDeviceSize range);
void rtpbr_lighting_write_image(rtpbr_context *ctx, VkDescriptorSet set, uint32_t binding, VkImageView view,
                                VkImageLayout layout);
void rtpbr_lighting_write_luts(rtpbr_context *ctx, VkDescriptorSet set);
// The binding of G-buffer target i (g0 .. g6).
uint32_t rtpbr_lighting_gbuffer_binding(uint32_t i);
// Shared by both lighting passes: the barrier and binds before their dispatches, and after
// them (and the forward pass) the resolve (supersampling) and the barrier before tone mapping
// and readback (renderer.c calls it).
void rtpbr_lighting_begin(rtpbr_renderer *r, VkPipeline pipeline, VkPipelineLayout layout, VkCommandBuffer cmd);
void rtpbr_lighting_end(rtpbr_renderer *r, VkCommandBuffer cmd);

// ---- Monte Carlo lighting (passes/lighting_mc.c). ------------------------------------------
rtpbr_result rtpbr_lighting_mc_pass_init(rtpbr_context *ctx); // after rtpbr_lighting_pass_init
void rtpbr_lighting_mc_pass_finish(rtpbr_context *ctx);
// The pipeline of a model variant, compiled on first use.
rtpbr_result rtpbr_lighting_mc_pipeline_get(rtpbr_context *ctx, rtpbr_ndf ndf, rtpbr_multiscatter ms, VkPipeline *out);
void rtpbr_lighting_mc_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, VkPipeline pipeline,
                              const rtpbr_render_desc *desc, VkCommandBuffer cmd);

// ---- Forward pass of BLEND surfaces (passes/forward.c), after the lighting pass. ----------
rtpbr_result rtpbr_forward_pass_init(rtpbr_context *ctx); // after rtpbr_gbuffer_pass_init
void rtpbr_forward_pass_finish(rtpbr_context *ctx);
// The pipeline of a model variant, compiled on first use; spheres: the variant that shades
// sphere lights (the others skip them).
rtpbr_result rtpbr_forward_pipeline_get(rtpbr_context *ctx, rtpbr_ndf ndf, rtpbr_multiscatter ms, bool spheres,
                                        VkPipeline *out);
rtpbr_result rtpbr_forward_renderer_init(rtpbr_renderer *r);
void rtpbr_forward_renderer_finish(rtpbr_renderer *r);
void rtpbr_forward_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene);
// Draws the scene's BLEND meshes back to front over the lighting pass's image; nothing when
// it has none (pipeline may then be VK_NULL_HANDLE).
void rtpbr_forward_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, VkPipeline pipeline, VkCommandBuffer cmd);
// Whether any material of the scene is BLEND (the forward pipeline is needed).
bool rtpbr_scene_has_blend(const rtpbr_gpu_scene *scene);
// Has the scene a MASK or BLEND material (whose alpha the shadow rays test)?
bool rtpbr_scene_has_alpha_test(const rtpbr_gpu_scene *scene);

// ---- Supersampling resolve (passes/resolve.c): box filter from the shading size. ----------
rtpbr_result rtpbr_resolve_pass_init(rtpbr_context *ctx);
void rtpbr_resolve_pass_finish(rtpbr_context *ctx);
rtpbr_result rtpbr_resolve_renderer_init(rtpbr_renderer *r); // no set without supersampling
void rtpbr_resolve_renderer_finish(rtpbr_renderer *r);
void rtpbr_resolve_record(rtpbr_renderer *r, VkCommandBuffer cmd);

// ---- Tone mapping (passes/tonemap.c): radiance into a display target. ---------------------
rtpbr_result rtpbr_tonemap_pass_init(rtpbr_context *ctx);
void rtpbr_tonemap_pass_finish(rtpbr_context *ctx);
// The pipeline for a colour-attachment format, the desc's operator and an encoding
// (RTPBR_ENCODE_*: the target's format decides), created on first use.
rtpbr_result rtpbr_tonemap_pipeline_get(rtpbr_context *ctx, VkFormat format, const rtpbr_render_desc *desc,
                                        uint32_t encode, VkPipeline *out);
rtpbr_result rtpbr_tonemap_renderer_init(rtpbr_renderer *r);
void rtpbr_tonemap_renderer_finish(rtpbr_renderer *r);
// With a pipeline rtpbr_tonemap_pipeline_get made for the same desc.
void rtpbr_tonemap_record(rtpbr_renderer *r, VkPipeline pipeline, const rtpbr_render_desc *desc, VkImageView target,
                          VkCommandBuffer cmd);

#endif // RTPBR_PASSES_H
