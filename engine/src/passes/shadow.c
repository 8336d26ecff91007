// Area-light shadows (issue 17): the ratio estimator of Heitz, Hill & McGuire 2018,
// "Combining Analytic Direct Illumination and Stochastic Shadows", as compute passes that
// run between the G-buffer and the lighting pass:
//   0. shadow_select.comp chooses, per lighting tile, the RTPBR_MAX_SHADOWED_LIGHTS lights of
//      the largest irradiance bound at the tile (issue 32; before, lights 0 .. 7 everywhere)
//      and writes them to the tile's shadow slots in the lighting pass's tile masks;
//   0b. shadow_list.comp lists the 8 x 8 pixel groups and slots whose estimates some pass
//      reads (not those where the slot's light is clear of blockers all around): the work
//      list, and the trace's indirect dispatch arguments;
//   1. shadow.comp traces, per listed group, pixel and shadow slot, rtpbr_render_desc.shadow_samples
//      rays to points on the light against the scene's BVH (../bvh.c) and writes the shadowed
//      and unshadowed sums of the light's cosine-weighted irradiance samples (layers 2 light
//      and 2 light + 1), in dispatches of at most RTPBR_SHADOW_SAMPLES_PER_DISPATCH samples
//      (one light per z slice): lavapipe ends every loop of a shader run after 65535 loop
//      iterations in all, so one dispatch tracing every sample of every light cut its loops
//      short and left later lights' texels unwritten (16 samples x a few hundred BVH steps
//      stays well inside);
//   2. shadow_denoise.comp filters both estimates with the same depth- and normal-guided
//      weights and writes their ratio (layer = light), over the groups of the denoiser's work
//      list (also shadow_list.comp): the ratios are cleared to 1 first, which every pixel of the
//      other groups would have got (on lavapipe a workgroup that returns at once still costs
//      its shader's straight-line code: the shadowed room at 480 x 360 61 -> 54 ms).
// The lighting passes multiply light i's result by the ratio of layer k where slot k of the
// pixel's tile holds light i (shaders/shadow_ratio.glsl, binding
// RTPBR_BINDING_LIGHT_SHADOW_RATIO), by 1 where no slot does. shadow_light_count of the frame
// block is the number of slots in use, min(lights, RTPBR_MAX_SHADOWED_LIGHTS).
// Memory: 12 bytes per shading pixel and shadowed-light slot (96 bytes per pixel), allocated
// with the renderer.
#include "passes.h"

#include "../internal.h"
#include "pipeline.h"
#include "rtpbr_spirv_shadow_comp.h"
#include "rtpbr_spirv_shadow_denoise_comp.h"
#include "rtpbr_spirv_shadow_list_comp.h"
#include "rtpbr_spirv_shadow_ray_query_comp.h"
#include "rtpbr_spirv_shadow_select_comp.h"

enum { RTPBR_SHADOW_SAMPLES_PER_DISPATCH = 16 };
// shadow_denoise.comp's window reaches at most the tiles beside, above or below and diagonal
// to the pixel's (their shadow slots are read once per pixel).
_Static_assert(RTPBR_SHADOW_DENOISE_RADIUS < RTPBR_TILE_SIZE, "the denoiser's window spans at most 2 x 2 tiles");
_Static_assert(RTPBR_SHADOW_DENOISE_RADIUS == RTPBR_SHADER_SHADOW_DENOISE_RADIUS, "the denoiser's window array");
// shadow.comp skips a pixel whose tiles within twice that radius are clear (shadow_clear_around).
_Static_assert(2 * RTPBR_SHADOW_DENOISE_RADIUS < RTPBR_TILE_SIZE, "twice the window spans at most 2 x 2 tiles");

#define COMPUTE(binding, type) {binding, VK_DESCRIPTOR_TYPE_##type, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL}
static const VkDescriptorSetLayoutBinding bindings[] = {
    COMPUTE(RTPBR_BINDING_SHADOW_FRAME, UNIFORM_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_LIGHTS, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_DEPTH, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_SHADOW_NORMAL, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_SHADOW_BVH_NODES, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_BVH_TRIANGLES, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_ESTIMATES, STORAGE_IMAGE),
    COMPUTE(RTPBR_BINDING_SHADOW_RATIO, STORAGE_IMAGE),
    COMPUTE(RTPBR_BINDING_SHADOW_VERTICES, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_MATERIALS, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_TEXTURE_TRANSFORMS, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_ALPHA_TEXTURES, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_ALPHA_TEXELS, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_TILES, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_WORK, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_BVH_NODE_TEXELS, UNIFORM_TEXEL_BUFFER),
    COMPUTE(RTPBR_BINDING_SHADOW_BVH_TRIANGLE_TEXELS, UNIFORM_TEXEL_BUFFER),
    // with ray-query shadows only (shadow_bindings)
    COMPUTE(RTPBR_BINDING_SHADOW_ACCEL, ACCELERATION_STRUCTURE_KHR),
    COMPUTE(RTPBR_BINDING_SHADOW_ACCEL_TRIANGLES, STORAGE_BUFFER),
};
#undef COMPUTE
_Static_assert(sizeof bindings / sizeof bindings[0] == RTPBR_SHADOW_RAY_QUERY_BINDING_COUNT, "every shadow binding");

// The set's bindings: the acceleration structure's only where the device traces with ray
// queries (its descriptor type needs VK_KHR_acceleration_structure).
static rtpbr_bindings shadow_bindings(const rtpbr_context *ctx)
{
    return (rtpbr_bindings){bindings, ctx->ray_query ? RTPBR_SHADOW_RAY_QUERY_BINDING_COUNT : RTPBR_SHADOW_BINDING_COUNT};
}

rtpbr_result rtpbr_shadow_pass_init(rtpbr_context *ctx)
{
    rtpbr_shadow_pass *pass = &ctx->shadow;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_pass_layouts_create(ctx, shadow_bindings(ctx), VK_SHADER_STAGE_COMPUTE_BIT,
                                        sizeof(rtpbr_shader_shadow), &pass->set_layout, &pass->layout));
    // On a CPU device the walks read the BVH as texel buffers (bvh.glsl: on lavapipe a storage
    // buffer's load at a varying index is a load per lane, a texel fetch a gather), where a view
    // can span any buffer the device can bind as storage (lavapipe: 2 GiB against 128 MiB).
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(ctx->physical_device, &props);
    pass->texel_view_range = (VkDeviceSize)props.limits.maxTexelBufferElements * 16u; // R32G32B32A32
    pass->cpu = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    pass->texel_reads = pass->cpu && pass->texel_view_range >= props.limits.maxStorageBufferRange;
cleanup:
    return result; // the caller finishes a half-built pass; the pipelines are made on first use
}

void rtpbr_shadow_pass_finish(rtpbr_context *ctx)
{
    rtpbr_shadow_pass *pass = &ctx->shadow;
    const VkPipeline pipelines[5] = {pass->select, pass->list, pass->trace, pass->trace_opaque, pass->denoise};
    rtpbr_pass_objects_destroy(ctx, pipelines, 5, pass->layout, pass->set_layout);
    *pass = (rtpbr_shadow_pass){0};
}

// A shadow pipeline that walks the BVH, specialized: the alpha test (RTPBR_SPEC_BVH_ALPHA), the
// texel reads (RTPBR_SPEC_BVH_TEXELS) and, on a CPU device, the packets' alpha
// (RTPBR_SPEC_BVH_PACKET_ALPHA).
static rtpbr_result bvh_pipeline_create(rtpbr_context *ctx, rtpbr_spirv spirv, bool alpha_tested, VkPipeline *out)
{
    const VkBool32 values[3] = {alpha_tested ? VK_TRUE : VK_FALSE, ctx->shadow.texel_reads ? VK_TRUE : VK_FALSE,
                                ctx->shadow.cpu ? VK_TRUE : VK_FALSE};
    const VkSpecializationMapEntry entries[3] = {{RTPBR_SPEC_BVH_ALPHA, 0, sizeof values[0]},
                                                 {RTPBR_SPEC_BVH_TEXELS, sizeof values[0], sizeof values[1]},
                                                 {RTPBR_SPEC_BVH_PACKET_ALPHA, 2 * sizeof values[0], sizeof values[2]}};
    const VkSpecializationInfo specialization = {3, entries, sizeof values, values};
    return rtpbr_compute_pipeline_create_specialized(ctx, spirv, ctx->shadow.layout, &specialization, out);
}

rtpbr_result rtpbr_shadow_pipelines_get(rtpbr_context *ctx, bool alpha_tested)
{
    rtpbr_shadow_pass *pass = &ctx->shadow;
    rtpbr_result result = RTPBR_SUCCESS;
    if (!pass->select)
        RTPBR_TRY(bvh_pipeline_create(ctx, RTPBR_SPIRV(rtpbr_spirv_shadow_select_comp), true, &pass->select));
    if (!pass->list)
        RTPBR_TRY(rtpbr_compute_pipeline_create(ctx, RTPBR_SPIRV(rtpbr_spirv_shadow_list_comp), pass->layout, &pass->list));
    // The trace by the BVH walk, or by ray queries (rtpbr_context_desc.shadow_ray_query).
    const rtpbr_spirv trace = ctx->ray_query ? RTPBR_SPIRV(rtpbr_spirv_shadow_ray_query_comp)
                                             : RTPBR_SPIRV(rtpbr_spirv_shadow_comp);
    if (alpha_tested && !pass->trace) RTPBR_TRY(bvh_pipeline_create(ctx, trace, true, &pass->trace));
    // Without MASK or BLEND materials every triangle a ray crosses blocks it: bvh.glsl's alpha
    // test compiled out (on lavapipe its code costs every step of the walk, taken or not).
    if (!alpha_tested && !pass->trace_opaque) RTPBR_TRY(bvh_pipeline_create(ctx, trace, false, &pass->trace_opaque));
    if (!pass->denoise)
        RTPBR_TRY(rtpbr_compute_pipeline_create(ctx, RTPBR_SPIRV(rtpbr_spirv_shadow_denoise_comp), pass->layout,
                                                &pass->denoise));
cleanup:
    return result;
}

// Both images from UNDEFINED to GENERAL, where they stay (the lighting set binds the ratios
// even with shadows off, so they must be in a valid layout from the start).
static void record_initial_layouts(VkCommandBuffer cmd, void *user)
{
    const rtpbr_renderer *r = user;
    const VkImage images[2] = {r->shadow_estimates.image, r->shadow_ratio.image};
    const uint32_t layers[2] = {2 * RTPBR_MAX_SHADOWED_LIGHTS, RTPBR_MAX_SHADOWED_LIGHTS};
    for (int i = 0; i < 2; ++i)
        rtpbr_image_range_barrier(cmd, images[i],
                                  (VkImageSubresourceRange){VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers[i]},
                                  VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                                  0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

rtpbr_result rtpbr_shadow_renderer_init(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_image_create_layers(ctx, r->shade_width, r->shade_height, 2 * RTPBR_MAX_SHADOWED_LIGHTS,
                                        VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, &r->shadow_estimates));
    RTPBR_TRY(rtpbr_image_create_layers(ctx, r->shade_width, r->shade_height, RTPBR_MAX_SHADOWED_LIGHTS,
                                        VK_FORMAT_R32_SFLOAT,
                                        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                            VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                        &r->shadow_ratio));
    RTPBR_TRY(rtpbr_submit_once(ctx, record_initial_layouts, r));
    // The work lists: their header, one trace entry per 8 x 8 group and shadowed light, one
    // denoiser entry per group.
    const VkDeviceSize groups = (VkDeviceSize)((r->shade_width + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE) *
                                ((r->shade_height + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE);
    RTPBR_TRY(rtpbr_buffer_create_device(
        ctx, (RTPBR_SHADOW_WORK_HEADER + groups * (RTPBR_MAX_SHADOWED_LIGHTS + 1)) * sizeof(uint32_t),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        &r->shadow_work));

    const rtpbr_bindings table = shadow_bindings(ctx);
    RTPBR_TRY(rtpbr_descriptor_set_create(ctx, table, ctx->shadow.set_layout, &r->shadow_set));
    VkDescriptorSet set = r->shadow_set.set;
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    rtpbr_descriptor_write_buffer(ctx, table, set, RTPBR_BINDING_SHADOW_FRAME, r->frame.buffer,
                                  sizeof(rtpbr_shader_frame));
    rtpbr_descriptor_write_image(ctx, table, set, RTPBR_BINDING_SHADOW_DEPTH, ctx->gbuffer_sampler, r->depth.view, read);
    rtpbr_descriptor_write_image(ctx, table, set, RTPBR_BINDING_SHADOW_NORMAL, ctx->gbuffer_sampler,
                                 r->gbuffer[1].view, read);
    rtpbr_descriptor_write_image(ctx, table, set, RTPBR_BINDING_SHADOW_ESTIMATES, VK_NULL_HANDLE,
                                 r->shadow_estimates.view, VK_IMAGE_LAYOUT_GENERAL);
    rtpbr_descriptor_write_image(ctx, table, set, RTPBR_BINDING_SHADOW_RATIO, VK_NULL_HANDLE, r->shadow_ratio.view,
                                 VK_IMAGE_LAYOUT_GENERAL);
    rtpbr_descriptor_write_buffer(ctx, table, set, RTPBR_BINDING_SHADOW_TILES, r->tile_masks.buffer, VK_WHOLE_SIZE);
    rtpbr_descriptor_write_buffer(ctx, table, set, RTPBR_BINDING_SHADOW_WORK, r->shadow_work.buffer, VK_WHOLE_SIZE);
cleanup:
    return result; // the caller destroys the renderer, and with it a half-built state
}

void rtpbr_shadow_renderer_finish(rtpbr_renderer *r)
{
    rtpbr_descriptor_set_destroy(r->context, &r->shadow_set);
    rtpbr_image_destroy(r->context, &r->shadow_estimates);
    rtpbr_image_destroy(r->context, &r->shadow_ratio);
    rtpbr_buffer_destroy(r->context, &r->shadow_work);
}

void rtpbr_shadow_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene)
{
    const rtpbr_buffer_write writes[] = {
        {RTPBR_BINDING_SHADOW_LIGHTS, scene->lights.buffer},
        {RTPBR_BINDING_SHADOW_BVH_NODES, scene->bvh_nodes.buffer},
        {RTPBR_BINDING_SHADOW_BVH_TRIANGLES, scene->bvh_triangles.buffer},
        // The alpha of MASK and BLEND occluders (bvh.glsl).
        {RTPBR_BINDING_SHADOW_VERTICES, scene->vertices.buffer},
        {RTPBR_BINDING_SHADOW_MATERIALS, scene->materials.buffer},
        {RTPBR_BINDING_SHADOW_TEXTURE_TRANSFORMS, scene->texture_transforms.buffer},
        {RTPBR_BINDING_SHADOW_ALPHA_TEXTURES, scene->alpha_textures.buffer},
        {RTPBR_BINDING_SHADOW_ALPHA_TEXELS, scene->alpha_texels.buffer},
    };
    const rtpbr_bindings table = shadow_bindings(r->context);
    rtpbr_descriptor_write_buffers(r->context, table, r->shadow_set.set, writes, sizeof writes / sizeof writes[0]);
    rtpbr_descriptor_write_texel_buffer(r->context, table, r->shadow_set.set, RTPBR_BINDING_SHADOW_BVH_NODE_TEXELS,
                                        scene->bvh_node_texels);
    rtpbr_descriptor_write_texel_buffer(r->context, table, r->shadow_set.set, RTPBR_BINDING_SHADOW_BVH_TRIANGLE_TEXELS,
                                        scene->bvh_triangle_texels);
    if (r->context->ray_query) { // the scene's acceleration structures (accel.c)
        rtpbr_descriptor_write_accel(r->context, r->shadow_set.set, RTPBR_BINDING_SHADOW_ACCEL, scene->accel_tlas);
        rtpbr_descriptor_write_buffer(r->context, table, r->shadow_set.set, RTPBR_BINDING_SHADOW_ACCEL_TRIANGLES,
                                      scene->accel_triangles.buffer, VK_WHOLE_SIZE);
    }
}

// A memory barrier between compute dispatches on one of the shadow images (all its layers).
static void compute_barrier(VkCommandBuffer cmd, VkImage image, uint32_t layers, VkAccessFlags src, VkAccessFlags dst)
{
    rtpbr_image_range_barrier(cmd, image, (VkImageSubresourceRange){VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers},
                              VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, src,
                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, dst);
}

void rtpbr_shadow_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, const rtpbr_render_desc *desc,
                         VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    const uint32_t samples = desc->shadow_samples ? desc->shadow_samples : RTPBR_DEFAULT_SHADOW_SAMPLES;
    const uint32_t lights = ((const rtpbr_shader_frame *)r->frame.mapped)->shadow_light_count; // this frame's
    const uint32_t estimate_layers = 2 * RTPBR_MAX_SHADOWED_LIGHTS;
    rtpbr_shader_shadow params = {
        .seed = desc->shadow_seed,
        .radius = desc->shadow_denoiser == RTPBR_SHADOW_DENOISER_OFF ? 0 : RTPBR_SHADOW_DENOISE_RADIUS,
        .cull = desc->shadow_cull != RTPBR_SHADOW_CULL_OFF,
    };
    uint32_t gx = (r->shade_width + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE;
    uint32_t gy = (r->shade_height + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->shadow.layout, 0, 1, &r->shadow_set.set, 0, NULL);
    // The shadow slots of each tile (in the tile masks: after the previous frame's culling and
    // lighting, before this frame's trace, denoiser, culling and lighting).
    const VkMemoryBarrier before = {VK_STRUCTURE_TYPE_MEMORY_BARRIER, NULL,
                                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_WRITE_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &before,
                         0, NULL, 0, NULL);
    // The work list's header: no entries, dispatch arguments (0, 0, 1) (the previous frame's
    // trace read them as its indirect arguments, its list pass wrote them).
    const VkMemoryBarrier reuse = {VK_STRUCTURE_TYPE_MEMORY_BARRIER, NULL,
                                   VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT |
                                       VK_ACCESS_SHADER_WRITE_BIT,
                                   VK_ACCESS_TRANSFER_WRITE_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &reuse, 0, NULL, 0, NULL);
    const uint32_t header[RTPBR_SHADOW_WORK_HEADER] = {0, 0, 1, 0, 0, 0, 1, 0};
    vkCmdUpdateBuffer(cmd, r->shadow_work.buffer, 0, sizeof header, header);
    const VkMemoryBarrier reset = {VK_STRUCTURE_TYPE_MEMORY_BARRIER, NULL, VK_ACCESS_TRANSFER_WRITE_BIT,
                                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &reset, 0,
                         NULL, 0, NULL);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->shadow.select);
    vkCmdPushConstants(cmd, ctx->shadow.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
    vkCmdDispatch(cmd, (r->tiles_x + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE,
                  (r->tiles_y + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE, 1);
    const VkMemoryBarrier selected = {VK_STRUCTURE_TYPE_MEMORY_BARRIER, NULL, VK_ACCESS_SHADER_WRITE_BIT,
                                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                         &selected, 0, NULL, 0, NULL);
    // The work list: the groups and slots whose estimates some pass reads.
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->shadow.list);
    vkCmdDispatch(cmd, (gx + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE,
                  (gy + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE, lights);
    const VkMemoryBarrier listed = {VK_STRUCTURE_TYPE_MEMORY_BARRIER, NULL, VK_ACCESS_SHADER_WRITE_BIT,
                                    VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &listed, 0,
                         NULL, 0, NULL);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                      rtpbr_scene_has_alpha_test(scene) ? ctx->shadow.trace : ctx->shadow.trace_opaque);
    // The previous frame's denoise read the sums; each dispatch adds to the previous one's.
    for (uint32_t first = 0; first < samples; first += RTPBR_SHADOW_SAMPLES_PER_DISPATCH) {
        compute_barrier(cmd, r->shadow_estimates.image, estimate_layers,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        params.first_sample = first;
        params.samples = samples - first < RTPBR_SHADOW_SAMPLES_PER_DISPATCH ? samples - first
                                                                            : RTPBR_SHADOW_SAMPLES_PER_DISPATCH;
        vkCmdPushConstants(cmd, ctx->shadow.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
        vkCmdDispatchIndirect(cmd, r->shadow_work.buffer, 0); // one workgroup per entry of the list
    }
    compute_barrier(cmd, r->shadow_estimates.image, estimate_layers, VK_ACCESS_SHADER_WRITE_BIT,
                    VK_ACCESS_SHADER_READ_BIT);
    // Every ratio 1 (the previous frame's lighting pass read them), then the listed groups'.
    if (lights > 0) {
        const VkImageSubresourceRange used = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, lights};
        rtpbr_image_range_barrier(cmd, r->shadow_ratio.image, used, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT,
                                  VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        const VkClearColorValue one = {.float32 = {1.0f, 0.0f, 0.0f, 0.0f}};
        vkCmdClearColorImage(cmd, r->shadow_ratio.image, VK_IMAGE_LAYOUT_GENERAL, &one, 1, &used);
        rtpbr_image_range_barrier(cmd, r->shadow_ratio.image, used, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                                  VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->shadow.denoise);
    vkCmdDispatchIndirect(cmd, r->shadow_work.buffer, RTPBR_SHADOW_WORK_DENOISE * sizeof(uint32_t));
    compute_barrier(cmd, r->shadow_ratio.image, RTPBR_MAX_SHADOWED_LIGHTS, VK_ACCESS_SHADER_WRITE_BIT,
                    VK_ACCESS_SHADER_READ_BIT);
}
