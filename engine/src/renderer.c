// Renderers: per-resolution targets, frame recording, submission and readback.
#include <math.h>
#include <string.h>

#include "internal.h"
#include "passes/passes.h"

rtpbr_result rtpbr_renderer_create(rtpbr_context *ctx, const rtpbr_renderer_desc *desc, rtpbr_renderer **out)
{
    if (!ctx) return rtpbr_null_object(__func__, "context");
    if (!desc || !out) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_renderer_create: desc or out_renderer is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    *out = NULL;
    if (desc->width == 0 || desc->height == 0 || desc->width > RTPBR_MAX_RENDER_SIZE ||
        desc->height > RTPBR_MAX_RENDER_SIZE) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "renderer size %ux%u; each side must be 1..%u", desc->width, desc->height,
                  RTPBR_MAX_RENDER_SIZE);
        return desc->width == 0 || desc->height == 0 ? RTPBR_ERROR_INVALID_ARGUMENT : RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    uint32_t ss = desc->supersample ? desc->supersample : 1;
    if (ss > RTPBR_MAX_SUPERSAMPLE || desc->width * ss > RTPBR_MAX_RENDER_SIZE ||
        desc->height * ss > RTPBR_MAX_RENDER_SIZE) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "renderer supersample %u at %ux%u; at most %u, and %u per side supersampled",
                  desc->supersample, desc->width, desc->height, RTPBR_MAX_SUPERSAMPLE, RTPBR_MAX_RENDER_SIZE);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_renderer *r = NULL;
    RTPBR_ALLOC(&ctx->host, r, sizeof *r);
    r->context = ctx;
    RTPBR_LIST_LINK(ctx->renderers, r);
    r->width = desc->width;
    r->height = desc->height;
    r->supersample = ss;
    r->shade_width = desc->width * ss;
    r->shade_height = desc->height * ss;
    uint32_t w = desc->width, h = desc->height, sw = r->shade_width, sh = r->shade_height;

    for (uint32_t i = 0; i < RTPBR_GBUFFER_COUNT; ++i)
        RTPBR_TRY(rtpbr_image_create(ctx, sw, sh, rtpbr_gbuffer_formats[i],
                                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                     &r->gbuffer[i]));
    RTPBR_TRY(rtpbr_image_create(ctx, sw, sh, RTPBR_DEPTH_FORMAT,
                                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, &r->depth));
    RTPBR_TRY(rtpbr_image_create(ctx, w, h, RTPBR_RADIANCE_FORMAT,
                                 VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, // the forward pass blends into it
                                 &r->radiance));
    if (ss > 1)
        RTPBR_TRY(rtpbr_image_create(ctx, sw, sh, RTPBR_RADIANCE_FORMAT,
                                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, &r->radiance_ss));
    RTPBR_TRY(rtpbr_image_create(ctx, w, h, RTPBR_DISPLAY_FORMAT,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &r->display));
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, sizeof(rtpbr_shader_frame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, &r->frame));
    // The culling pass's outputs: a light mask per tile (128 bytes per 256 pixels), and per
    // tile class its indirect dispatch arguments (a uvec4) and a queue as long as the tile count.
    r->tiles_x = (sw + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE;
    r->tiles_y = (sh + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE;
    RTPBR_TRY(rtpbr_lighting_tile_buffers_create(ctx, r->tiles_x, r->tiles_y, &r->tile_masks, &r->tile_lists));
    // Each pass's descriptor set (the lighting set binds the shadow ratios: after the shadows).
    RTPBR_TRY(rtpbr_gbuffer_renderer_init(r));
    RTPBR_TRY(rtpbr_shadow_renderer_init(r));
    RTPBR_TRY(rtpbr_lighting_renderer_init(r));
    RTPBR_TRY(rtpbr_forward_renderer_init(r));
    RTPBR_TRY(rtpbr_resolve_renderer_init(r));
    RTPBR_TRY(rtpbr_tonemap_renderer_init(r));

    RTPBR_TRY(rtpbr_command_buffer_create(ctx, &r->cmd, &r->fence));
    if (desc->timings) RTPBR_TRY(rtpbr_timing_create(r));
    *out = r;
    return RTPBR_SUCCESS;
cleanup:
    rtpbr_renderer_destroy(r);
    return result;
}

void rtpbr_renderer_destroy(rtpbr_renderer *r)
{
    if (!r) return;
    rtpbr_context *ctx = r->context;
    if (r->fence) {
        VkResult vr = r->fence_pending ? vkWaitForFences(ctx->device, 1, &r->fence, VK_TRUE, UINT64_MAX) : VK_SUCCESS;
        if (vr != VK_SUCCESS) rtpbr_vk_fail(&ctx->host, vr, "vkWaitForFences (rtpbr_renderer_destroy)");
        vkDestroyFence(ctx->device, r->fence, NULL);
    }
    if (r->cmd) vkFreeCommandBuffers(ctx->device, ctx->command_pool, 1, &r->cmd);
    rtpbr_timing_destroy(r);
    rtpbr_tonemap_renderer_finish(r);
    rtpbr_resolve_renderer_finish(r);
    rtpbr_forward_renderer_finish(r);
    rtpbr_lighting_renderer_finish(r);
    rtpbr_shadow_renderer_finish(r);
    rtpbr_gbuffer_renderer_finish(r);
    rtpbr_buffer_destroy(ctx, &r->frame);
    rtpbr_buffer_destroy(ctx, &r->tile_masks);
    rtpbr_buffer_destroy(ctx, &r->tile_lists);
    rtpbr_buffer_destroy(ctx, &r->radiance_readback);
    rtpbr_buffer_destroy(ctx, &r->display_readback);
    for (uint32_t i = 0; i < RTPBR_GBUFFER_COUNT; ++i) rtpbr_image_destroy(ctx, &r->gbuffer[i]);
    rtpbr_image_destroy(ctx, &r->depth);
    rtpbr_image_destroy(ctx, &r->radiance);
    rtpbr_image_destroy(ctx, &r->radiance_ss);
    rtpbr_image_destroy(ctx, &r->display);
    RTPBR_LIST_UNLINK(ctx->renderers, r);
    rtpbr_free(&ctx->host, r);
}

// ---------------------------------------------------------------------------------------------

// Checks the arguments shared by rtpbr_render and rtpbr_record, then writes the frame
// constants and the scene's descriptors.
static rtpbr_result prepare_frame(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, const rtpbr_render_desc *desc)
{
    rtpbr_context *ctx = r->context;
    if (!scene || !desc) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "render: scene or desc is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (scene->context != ctx) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "render: the scene belongs to another context");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    const rtpbr_camera_desc *camera = desc->camera;
    if (!camera) {
        if (desc->camera_index >= scene->camera_count) {
            rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "render: camera %u requested, the scene has %u", desc->camera_index,
                      scene->camera_count);
            return RTPBR_ERROR_INVALID_ARGUMENT;
        }
        camera = &scene->cameras[desc->camera_index];
    }
    if (!rtpbr_finite((const float *)camera, sizeof *camera / sizeof(float)) || !isfinite(desc->exposure) ||
        !isfinite(desc->light_cull_form_factor) ||
        !rtpbr_finite(desc->background, 3)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "render: NaN or infinite camera, exposure or background");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if ((unsigned)desc->tonemap > RTPBR_TONEMAP_LINEAR || (unsigned)desc->ndf > RTPBR_NDF_BECKMANN_MODEL ||
        (unsigned)desc->multiscatter > RTPBR_MULTISCATTER_OFF) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "render: unknown tonemap, ndf or multiscatter value");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (desc->mc_samples > RTPBR_MAX_MC_SAMPLES) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "render: mc_samples %u; at most %u", desc->mc_samples, RTPBR_MAX_MC_SAMPLES);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    if ((unsigned)desc->shadows > RTPBR_SHADOWS_ON || (unsigned)desc->shadow_denoiser > RTPBR_SHADOW_DENOISER_OFF ||
        (unsigned)desc->shadow_cull > RTPBR_SHADOW_CULL_OFF) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "render: unknown shadows, shadow_denoiser or shadow_cull value");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (desc->shadow_samples > RTPBR_MAX_SHADOW_SAMPLES) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "render: shadow_samples %u; at most %u", desc->shadow_samples,
                  RTPBR_MAX_SHADOW_SAMPLES);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    bool shadows = desc->shadows == RTPBR_SHADOWS_ON;
    if (shadows && ctx->ray_query && !scene->accel_tlas) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR,
                  "render: the scene has no acceleration structures for its shadow rays (their rebuild in "
                  "rtpbr_gpu_scene_set_material or _set_transform failed)");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (shadows) {
        // before any recording: may compile (the trace with the alpha test where the scene has
        // a MASK or BLEND material)
        rtpbr_result result = rtpbr_shadow_pipelines_get(ctx, rtpbr_scene_has_alpha_test(scene));
        if (result != RTPBR_SUCCESS) return result;
    }
    // the G-buffer pipelines of the scene's materials' texture slots (may compile)
    rtpbr_result gbuffer = rtpbr_gbuffer_pipelines_get(ctx, scene);
    if (gbuffer != RTPBR_SUCCESS) return gbuffer;

    rtpbr_shader_frame frame = {0};
    rtpbr_camera_matrices(camera, (float)r->width / (float)r->height, frame.view_proj);
    if (!rtpbr_mat4_invert(frame.inv_view_proj, frame.view_proj)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "render: degenerate camera");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    memcpy(frame.camera_position, camera->position, 3 * sizeof(float));
    frame.camera_position[3] = 1.0f; // the background's depth (rtpbr's own passes: 0 near .. 1 far)
    memcpy(frame.background, desc->background, 3 * sizeof(float));
    frame.size[0] = r->shade_width;
    frame.size[1] = r->shade_height;
    frame.light_count = scene->light_count;
    frame.cull_form_factor = desc->light_cull_form_factor == 0.0f ? RTPBR_DEFAULT_CULL_FORM_FACTOR
                                                                   : desc->light_cull_form_factor;
    frame.tiles_x = r->tiles_x;
    frame.tile_capacity = r->tiles_x * r->tiles_y;
    frame.shadow_light_count = !shadows ? 0
                               : scene->light_count < RTPBR_MAX_SHADOWED_LIGHTS ? scene->light_count
                                                                                : RTPBR_MAX_SHADOWED_LIGHTS;
    frame.extension_textures = rtpbr_gpu_scene_extension_textures(scene);
    memcpy(r->frame.mapped, &frame, sizeof frame);
    rtpbr_gbuffer_bind_scene(r, scene);
    rtpbr_lighting_bind_scene(r, scene);
    rtpbr_forward_bind_scene(r, scene);
    if (shadows) rtpbr_shadow_bind_scene(r, scene);
    return RTPBR_SUCCESS;
}

// The pipelines of the lighting passes: the lighting variants and the forward pass's.
typedef struct lighting_pipelines {
    VkPipeline lighting[RTPBR_TILE_CLASS_COUNT];
    VkPipeline forward; // VK_NULL_HANDLE when the scene has no BLEND material
} lighting_pipelines;

// The lighting pass the desc asks for: LTC, or the Monte Carlo reference (mc_samples > 0),
// after the shadow passes when shadows are on; then the forward pass of BLEND surfaces over
// its image, and the resolve.
static void record_lighting(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, const rtpbr_render_desc *desc,
                            const lighting_pipelines *pipelines, VkCommandBuffer cmd)
{
    if (desc->shadows == RTPBR_SHADOWS_ON) rtpbr_shadow_record(r, scene, desc, cmd); // the ratios lighting multiplies by
    if (desc->mc_samples == 0) rtpbr_lighting_ltc_record(r, pipelines->lighting, cmd);
    else rtpbr_lighting_mc_record(r, scene, pipelines->lighting[0], desc, cmd);
    if (pipelines->forward) rtpbr_forward_record(r, scene, pipelines->forward, cmd);
    rtpbr_lighting_end(r, cmd);
}

// The pipelines the desc and the scene ask for, compiled on first use (before any recording).
static rtpbr_result get_lighting(rtpbr_context *ctx, const rtpbr_gpu_scene *scene, const rtpbr_render_desc *desc,
                                 lighting_pipelines *out)
{
    out->forward = VK_NULL_HANDLE;
    rtpbr_lighting_needs needs = rtpbr_lighting_needs_of(scene->lights.mapped, scene->light_count, scene->materials.mapped,
                                                         scene->material_count);
    needs.shadows = desc->shadows == RTPBR_SHADOWS_ON; // (as frame_constants' shadow_light_count)
    uint32_t shapes = needs.shapes;
    rtpbr_result result = desc->mc_samples == 0
                              ? rtpbr_lighting_pipelines_get(ctx, desc->ndf, desc->multiscatter, &needs, out->lighting)
                              : rtpbr_lighting_mc_pipeline_get(ctx, desc->ndf, desc->multiscatter, &out->lighting[0]);
    if (result == RTPBR_SUCCESS && rtpbr_scene_has_blend(scene))
        result = rtpbr_forward_pipeline_get(ctx, desc->ndf, desc->multiscatter, shapes > 0, &out->forward);
    return result;
}

// Resets r->cmd and begins its recording, once its last submission has completed.
static rtpbr_result begin_commands(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    if (r->fence_pending) RTPBR_VK(&ctx->host, vkWaitForFences(ctx->device, 1, &r->fence, VK_TRUE, UINT64_MAX));
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    RTPBR_VK(&ctx->host, vkResetCommandBuffer(r->cmd, 0));
    RTPBR_VK(&ctx->host, vkBeginCommandBuffer(r->cmd, &begin));
cleanup:
    return result;
}

// Submits r->cmd (recorded) on the context's queue with r->fence, and waits for it.
static rtpbr_result submit_and_wait(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &r->cmd,
    };
    RTPBR_VK(&ctx->host, vkResetFences(ctx->device, 1, &r->fence));
    r->fence_pending = false; // the fence is unsignalled until the submission below succeeds
    RTPBR_VK(&ctx->host, vkQueueSubmit(ctx->queue, 1, &submit, r->fence));
    r->fence_pending = true;
    RTPBR_VK(&ctx->host, vkWaitForFences(ctx->device, 1, &r->fence, VK_TRUE, UINT64_MAX));
cleanup:
    return result;
}

rtpbr_result rtpbr_render(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, const rtpbr_render_desc *desc)
{
    if (!r) return rtpbr_null_object(__func__, "renderer");
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    VkPipeline tonemap;
    if (r->fence_pending) RTPBR_VK(&ctx->host, vkWaitForFences(ctx->device, 1, &r->fence, VK_TRUE, UINT64_MAX));
    RTPBR_TRY(prepare_frame(r, scene, desc));
    RTPBR_TRY(rtpbr_tonemap_pipeline_get(ctx, RTPBR_DISPLAY_FORMAT, desc, RTPBR_ENCODE_NONE, &tonemap));
    // Before any recording: a variant's first use compiles it, which may fail.
    lighting_pipelines lighting;
    RTPBR_TRY(get_lighting(ctx, scene, desc, &lighting));

    VkCommandBuffer cmd = r->cmd;
    RTPBR_TRY(begin_commands(r));
    rtpbr_timing_mark(r, cmd, RTPBR_TIMESTAMP_START);
    rtpbr_gbuffer_record(r, scene, cmd);
    rtpbr_timing_mark(r, cmd, RTPBR_TIMESTAMP_GBUFFER);
    record_lighting(r, scene, desc, &lighting, cmd);
    rtpbr_timing_mark(r, cmd, RTPBR_TIMESTAMP_LIGHTING);
    rtpbr_image_barrier(cmd, r->display.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    rtpbr_tonemap_record(r, tonemap, desc, r->display.view, cmd);
    rtpbr_timing_mark(r, cmd, RTPBR_TIMESTAMP_TONEMAP);
    // (no readback: rtpbr_read_* copy the images they are asked for, copy_back)
    RTPBR_VK(&ctx->host, vkEndCommandBuffer(cmd));
    r->has_frame = r->has_radiance = false; // until the frame below has completed
    RTPBR_TRY(submit_and_wait(r));
    r->has_frame = r->has_radiance = true;
    r->radiance_copied = r->display_copied = false;
cleanup:
    return result;
}

rtpbr_result rtpbr_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, const rtpbr_render_desc *desc,
                          const rtpbr_record_desc *target)
{
    if (!r) return rtpbr_null_object(__func__, "renderer");
    rtpbr_context *ctx = r->context;
    if (!target || !target->command_buffer || !target->image || !target->view ||
        target->format == VK_FORMAT_UNDEFINED) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "rtpbr_record: command_buffer, image, view and format are required");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    rtpbr_result result = RTPBR_SUCCESS;
    VkPipeline tonemap;
    if (r->fence_pending) RTPBR_VK(&ctx->host, vkWaitForFences(ctx->device, 1, &r->fence, VK_TRUE, UINT64_MAX));
    RTPBR_TRY(prepare_frame(r, scene, desc));
    // UNORM targets need the sRGB curve in the shader; sRGB targets encode in hardware.
    bool unorm = target->format == VK_FORMAT_R8G8B8A8_UNORM || target->format == VK_FORMAT_B8G8R8A8_UNORM ||
                 target->format == VK_FORMAT_A8B8G8R8_UNORM_PACK32 || target->format == VK_FORMAT_A2B10G10R10_UNORM_PACK32 ||
                 target->format == VK_FORMAT_A2R10G10B10_UNORM_PACK32;
    RTPBR_TRY(rtpbr_tonemap_pipeline_get(ctx, target->format, desc, unorm ? RTPBR_ENCODE_SRGB : RTPBR_ENCODE_NONE,
                                         &tonemap));
    // Before recording into the host's command buffer: a variant's first use compiles it.
    lighting_pipelines lighting;
    RTPBR_TRY(get_lighting(ctx, scene, desc, &lighting));

    VkImageLayout new_layout = target->new_layout ? target->new_layout : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkCommandBuffer cmd = target->command_buffer;
    rtpbr_timing_mark(r, cmd, RTPBR_TIMESTAMP_START);
    rtpbr_gbuffer_record(r, scene, cmd);
    rtpbr_timing_mark(r, cmd, RTPBR_TIMESTAMP_GBUFFER);
    record_lighting(r, scene, desc, &lighting, cmd);
    rtpbr_timing_mark(r, cmd, RTPBR_TIMESTAMP_LIGHTING);
    rtpbr_image_barrier(cmd, target->image, VK_IMAGE_ASPECT_COLOR_BIT, target->old_layout,
                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
                        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    rtpbr_tonemap_record(r, tonemap, desc, target->view, cmd);
    rtpbr_timing_mark(r, cmd, RTPBR_TIMESTAMP_TONEMAP);
    if (new_layout != VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL)
        rtpbr_image_barrier(cmd, target->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                            new_layout, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                            VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    // (no readback: rtpbr_read_radiance copies the radiance once the host's submission has
    // completed, copy_back)
    r->has_radiance = true; // once the host's submission completes (rtpbr.h)
    r->radiance_copied = false;
    r->has_frame = false; // rtpbr_read_display has nothing of this frame: the host owns its target
cleanup:
    return result;
}

// Copies the last frame's radiance image (display: its display image) into its readback buffer,
// made on first use: a submission of r->cmd of its own, made by the first rtpbr_read_* of a
// frame, so that a frame no one reads back (a real-time loop, a host's frame) pays for no copy
// (at 640 x 480 the radiance alone is 4.9 MB). The frame's writes completed before (rtpbr_render
// waited for them; the host waits for rtpbr_record's), on this queue: the barrier's first scope
// holds them. Each image is left in TRANSFER_SRC_OPTIMAL (the radiance from the lighting pass's
// GENERAL, the display from the tone mapping's COLOR_ATTACHMENT_OPTIMAL), at most once per
// frame; the next frame starts both from UNDEFINED.
static rtpbr_result copy_back(rtpbr_renderer *r, bool display)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_buffer *dst = display ? &r->display_readback : &r->radiance_readback;
    if (!dst->buffer)
        RTPBR_TRY(rtpbr_buffer_create_host(ctx, (VkDeviceSize)r->width * r->height * (display ? 4u : 16u),
                                           VK_BUFFER_USAGE_TRANSFER_DST_BIT, dst));
    VkCommandBuffer cmd = r->cmd;
    RTPBR_TRY(begin_commands(r));
    VkImage image = display ? r->display.image : r->radiance.image;
    if (display) // after the tone mapping's writes
        rtpbr_image_barrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                            VK_ACCESS_TRANSFER_READ_BIT);
    else // after the lighting pass's, the resolve's and the forward pass's writes
        rtpbr_image_barrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferImageCopy region = {
        .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .imageExtent = {r->width, r->height, 1},
    };
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst->buffer, 1, &region);
    VkMemoryBarrier to_host = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, NULL,
                         0, NULL);
    RTPBR_VK(&ctx->host, vkEndCommandBuffer(cmd));
    RTPBR_TRY(submit_and_wait(r));
    if (display) r->display_copied = true;
    else r->radiance_copied = true;
cleanup:
    return result;
}

// rtpbr_read_radiance and rtpbr_read_display (named by `who`): copies the image into dst, as
// bytes_per_pixel per output pixel, once `ready`, else says what has not been rendered.
static rtpbr_result read_back(rtpbr_renderer *r, const char *who, bool display, size_t bytes_per_pixel, bool ready,
                              const char *not_ready, void *dst, size_t size_bytes)
{
    rtpbr_result result = RTPBR_SUCCESS;
    size_t need = (size_t)r->width * r->height * bytes_per_pixel;
    if (!dst || size_bytes < need) {
        rtpbr_log(&r->context->host, RTPBR_LOG_ERROR, "%s: need a buffer of %zu bytes, got %zu%s", who, need,
                  size_bytes, dst ? "" : " (NULL)");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (!ready) {
        rtpbr_log(&r->context->host, RTPBR_LOG_ERROR, "%s: nothing rendered with %s yet", who, not_ready);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (!(display ? r->display_copied : r->radiance_copied)) RTPBR_TRY(copy_back(r, display));
    memcpy(dst, (display ? &r->display_readback : &r->radiance_readback)->mapped, need);
cleanup:
    return result;
}

rtpbr_result rtpbr_read_radiance(rtpbr_renderer *r, float *rgba, size_t size_bytes)
{
    if (!r) return rtpbr_null_object(__func__, "renderer");
    return read_back(r, __func__, false, 16, r->has_radiance, "rtpbr_render or rtpbr_record", rgba, size_bytes);
}

rtpbr_result rtpbr_read_display(rtpbr_renderer *r, uint8_t *rgba, size_t size_bytes)
{
    if (!r) return rtpbr_null_object(__func__, "renderer");
    return read_back(r, __func__, true, 4, r->has_frame, "rtpbr_render", rgba, size_bytes);
}
