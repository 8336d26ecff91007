// The context's life cycle: device, command pool, samplers, lookup tables and the passes'
// pipelines; it destroys the scenes and renderers the host left alive.
#include "internal.h"
#include "light_texture.h"
#include "passes/passes.h"

rtpbr_result rtpbr_context_create(const rtpbr_context_desc *desc, rtpbr_context **out_context)
{
    // Before the context exists, messages go to the desc's logger (stderr without one).
    rtpbr_host host = {.logger = desc ? desc->logger : (rtpbr_logger){0}};
    if (!out_context || !desc) {
        rtpbr_log(&host, RTPBR_LOG_ERROR, "rtpbr_context_create: %s is NULL", desc ? "out_context" : "desc");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    *out_context = NULL;
    if ((desc->allocator.alloc == NULL) != (desc->allocator.free == NULL)) {
        rtpbr_log(&host, RTPBR_LOG_ERROR, "rtpbr_context_create: allocator needs both alloc and free, or neither");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    host.allocator = desc->allocator;
    rtpbr_context *ctx = rtpbr_alloc(&host, sizeof *ctx);
    if (!ctx) return RTPBR_ERROR_OUT_OF_HOST_MEMORY; // logged by rtpbr_alloc
    ctx->host = host;

    rtpbr_result result;
    if (desc->shadow_ray_query < RTPBR_SHADOW_RAY_QUERY_AUTO || desc->shadow_ray_query > RTPBR_SHADOW_RAY_QUERY_ON)
        RTPBR_FAIL(&ctx->host, RTPBR_ERROR_INVALID_ARGUMENT,
                   "rtpbr_context_create: shadow_ray_query %d is not an rtpbr_shadow_ray_query", desc->shadow_ray_query);
    ctx->ray_query_mode = desc->shadow_ray_query;
    if (desc->embedded.device != VK_NULL_HANDLE || desc->embedded.instance != VK_NULL_HANDLE)
        RTPBR_TRY(rtpbr_device_init_embedded(ctx, &desc->embedded));
    else
        RTPBR_TRY(rtpbr_device_init_standalone(ctx, desc));

    VkCommandPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = ctx->queue_family,
    };
    RTPBR_VK(&ctx->host, vkCreateCommandPool(ctx->device, &pool_info, NULL, &ctx->command_pool));
    RTPBR_TRY(rtpbr_command_buffer_create(ctx, &ctx->upload_cmd, &ctx->upload_fence));

    VkSamplerCreateInfo sampler_info = {
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = VK_FILTER_LINEAR,
        .minFilter = VK_FILTER_LINEAR,
        .mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST,
        .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .maxLod = 0.0f,
    };
    RTPBR_VK(&ctx->host, vkCreateSampler(ctx->device, &sampler_info, NULL, &ctx->lut_sampler));
    sampler_info.magFilter = sampler_info.minFilter = VK_FILTER_NEAREST;
    RTPBR_VK(&ctx->host, vkCreateSampler(ctx->device, &sampler_info, NULL, &ctx->gbuffer_sampler));
    sampler_info.magFilter = sampler_info.minFilter = VK_FILTER_LINEAR;
    sampler_info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    sampler_info.maxLod = (float)(RTPBR_LIGHT_TEXTURE_LEVELS - 1);
    RTPBR_VK(&ctx->host, vkCreateSampler(ctx->device, &sampler_info, NULL, &ctx->light_texture_sampler));
    RTPBR_TRY(rtpbr_luts_create(ctx));
    {
        // (a chain of ones: what an untextured light would read)
        size_t floats = rtpbr_light_texture_floats();
        float *ones;
        RTPBR_ALLOC(&ctx->host, ones, floats * sizeof(float));
        for (size_t i = 0; i < floats; ++i) ones[i] = 1.0f;
        result = rtpbr_light_textures_create(ctx, ones, 1, &ctx->light_texture_stand_in);
        rtpbr_free(&ctx->host, ones);
        if (result != RTPBR_SUCCESS) goto cleanup;
    }
    // The passes' layouts and pipelines (variants other than the defaults: on first use).
    RTPBR_TRY(rtpbr_gbuffer_pass_init(ctx));
    RTPBR_TRY(rtpbr_lighting_pass_init(ctx));
    RTPBR_TRY(rtpbr_lighting_mc_pass_init(ctx));
    RTPBR_TRY(rtpbr_resolve_pass_init(ctx));
    RTPBR_TRY(rtpbr_tonemap_pass_init(ctx));
    RTPBR_TRY(rtpbr_shadow_pass_init(ctx));
    RTPBR_TRY(rtpbr_forward_pass_init(ctx));

    *out_context = ctx;
    return RTPBR_SUCCESS;

cleanup:
    rtpbr_context_destroy(ctx);
    return result;
}

void rtpbr_context_destroy(rtpbr_context *ctx)
{
    if (!ctx) return;
    if (ctx->scenes || ctx->renderers) {
        uint32_t scenes = 0, renderers = 0;
        for (const rtpbr_gpu_scene *s = ctx->scenes; s; s = s->next) ++scenes;
        for (const rtpbr_renderer *r = ctx->renderers; r; r = r->next) ++renderers;
        rtpbr_log(&ctx->host, RTPBR_LOG_WARNING,
                  "rtpbr_context_destroy: destroying %u scene(s) and %u renderer(s) the host did not destroy",
                  scenes, renderers);
        while (ctx->renderers) rtpbr_renderer_destroy(ctx->renderers);
        while (ctx->scenes) rtpbr_gpu_scene_destroy(ctx->scenes);
    }
    if (ctx->light_sets || ctx->lighting_targets) {
        rtpbr_log(&ctx->host, RTPBR_LOG_WARNING,
                  "rtpbr_context_destroy: destroying light sets or lighting targets the host did not destroy");
        while (ctx->lighting_targets) rtpbr_lighting_targets_destroy(ctx->lighting_targets);
        while (ctx->light_sets) rtpbr_light_set_destroy(ctx->light_sets);
    }
    if (ctx->device) {
        if (ctx->upload_fence) {
            VkResult vr = vkWaitForFences(ctx->device, 1, &ctx->upload_fence, VK_TRUE, UINT64_MAX);
            if (vr != VK_SUCCESS) rtpbr_vk_fail(&ctx->host, vr, "vkWaitForFences (rtpbr_context_destroy)");
        }
        rtpbr_forward_pass_finish(ctx);
        rtpbr_tonemap_pass_finish(ctx);
        rtpbr_resolve_pass_finish(ctx);
        rtpbr_lighting_mc_pass_finish(ctx);
        rtpbr_lighting_pass_finish(ctx);
        rtpbr_shadow_pass_finish(ctx);
        rtpbr_gbuffer_pass_finish(ctx);
        rtpbr_luts_destroy(ctx);
        rtpbr_image_destroy(ctx, &ctx->light_texture_stand_in);
        vkDestroySampler(ctx->device, ctx->light_texture_sampler, NULL);
        vkDestroySampler(ctx->device, ctx->lut_sampler, NULL);
        vkDestroySampler(ctx->device, ctx->gbuffer_sampler, NULL);
        vkDestroyFence(ctx->device, ctx->upload_fence, NULL);
        vkDestroyCommandPool(ctx->device, ctx->command_pool, NULL);
    }
    rtpbr_device_finish(ctx);
    rtpbr_free(&ctx->host, ctx);
}

uint32_t rtpbr_context_validation_message_count(const rtpbr_context *ctx)
{
    return ctx ? ctx->validation_messages : 0;
}

rtpbr_vulkan_device rtpbr_context_vulkan_device(const rtpbr_context *ctx)
{
    rtpbr_vulkan_device d = {0};
    if (!ctx) return d;
    d.instance = ctx->instance;
    d.physical_device = ctx->physical_device;
    d.device = ctx->device;
    d.queue = ctx->queue;
    d.queue_family_index = ctx->queue_family;
    return d;
}

int rtpbr_context_shadow_ray_query(const rtpbr_context *ctx)
{
    return ctx && ctx->ray_query;
}

const char *rtpbr_context_device_name(const rtpbr_context *ctx)
{
    return ctx ? ctx->device_name : "";
}
