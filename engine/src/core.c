// Results, allocation, logging and the context's life cycle.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

uint32_t rtpbr_version(void)
{
    return RTPBR_VERSION;
}

const char *rtpbr_result_string(rtpbr_result result)
{
    switch (result) {
    case RTPBR_SUCCESS: return "success";
    case RTPBR_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTPBR_ERROR_OUT_OF_HOST_MEMORY: return "out of host memory";
    case RTPBR_ERROR_OUT_OF_DEVICE_MEMORY: return "out of device memory";
    case RTPBR_ERROR_NO_DEVICE: return "no suitable Vulkan device";
    case RTPBR_ERROR_MISSING_FEATURE: return "missing Vulkan feature";
    case RTPBR_ERROR_LIMIT_EXCEEDED: return "limit exceeded";
    case RTPBR_ERROR_SCENE_LOAD: return "scene could not be loaded";
    case RTPBR_ERROR_IO: return "input/output error";
    case RTPBR_ERROR_DEVICE_LOST: return "Vulkan device lost";
    case RTPBR_ERROR_VULKAN: return "Vulkan error";
    }
    return "unknown result";
}

void *rtpbr_alloc(const rtpbr_context *ctx, size_t size)
{
    void *p = ctx->allocator.alloc ? ctx->allocator.alloc(size, ctx->allocator.user_data) : malloc(size);
    if (p) memset(p, 0, size);
    else rtpbr_log(ctx, RTPBR_LOG_ERROR, "out of host memory: an allocation of %zu bytes failed", size);
    return p;
}

void rtpbr_free(const rtpbr_context *ctx, void *ptr)
{
    if (!ptr) return;
    if (ctx->allocator.free) ctx->allocator.free(ptr, ctx->allocator.user_data);
    else free(ptr);
}

void rtpbr_logv(const rtpbr_logger *logger, rtpbr_log_level level, const char *fmt, va_list args)
{
    char message[1024];
    vsnprintf(message, sizeof message, fmt, args);
    if (logger->func) logger->func(level, message, logger->user_data);
    else if (level <= RTPBR_LOG_WARNING)
        fprintf(stderr, "rtpbr: %s: %s\n", level == RTPBR_LOG_ERROR ? "error" : "warning", message);
}

void rtpbr_log(const rtpbr_context *ctx, rtpbr_log_level level, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    rtpbr_logv(&ctx->logger, level, fmt, args);
    va_end(args);
}

const char *rtpbr_vk_result_name(VkResult vr)
{
    switch (vr) {
#define NAME(x) case x: return #x;
    NAME(VK_SUCCESS) NAME(VK_NOT_READY) NAME(VK_TIMEOUT) NAME(VK_INCOMPLETE)
    NAME(VK_ERROR_OUT_OF_HOST_MEMORY) NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    NAME(VK_ERROR_INITIALIZATION_FAILED) NAME(VK_ERROR_DEVICE_LOST)
    NAME(VK_ERROR_MEMORY_MAP_FAILED) NAME(VK_ERROR_LAYER_NOT_PRESENT)
    NAME(VK_ERROR_EXTENSION_NOT_PRESENT) NAME(VK_ERROR_FEATURE_NOT_PRESENT)
    NAME(VK_ERROR_INCOMPATIBLE_DRIVER) NAME(VK_ERROR_TOO_MANY_OBJECTS)
    NAME(VK_ERROR_FORMAT_NOT_SUPPORTED) NAME(VK_ERROR_FRAGMENTED_POOL)
    NAME(VK_ERROR_OUT_OF_POOL_MEMORY) NAME(VK_ERROR_UNKNOWN)
#undef NAME
    default: return "VkResult (unnamed)";
    }
}

rtpbr_result rtpbr_vk_fail(const rtpbr_context *ctx, VkResult vr, const char *what)
{
    rtpbr_log(ctx, RTPBR_LOG_ERROR, "%s failed: %s (%d)", what, rtpbr_vk_result_name(vr), (int)vr);
    switch (vr) {
    case VK_ERROR_OUT_OF_HOST_MEMORY: return RTPBR_ERROR_OUT_OF_HOST_MEMORY;
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return RTPBR_ERROR_OUT_OF_DEVICE_MEMORY;
    case VK_ERROR_DEVICE_LOST: return RTPBR_ERROR_DEVICE_LOST;
    case VK_ERROR_INCOMPATIBLE_DRIVER: return RTPBR_ERROR_NO_DEVICE;
    case VK_ERROR_LAYER_NOT_PRESENT:
    case VK_ERROR_EXTENSION_NOT_PRESENT:
    case VK_ERROR_FEATURE_NOT_PRESENT:
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return RTPBR_ERROR_MISSING_FEATURE;
    default: return RTPBR_ERROR_VULKAN;
    }
}

rtpbr_result rtpbr_context_create(const rtpbr_context_desc *desc, rtpbr_context **out_context)
{
    static const rtpbr_logger stderr_logger = {0};
    if (!out_context) {
        rtpbr_log(&(rtpbr_context){.logger = desc ? desc->logger : stderr_logger}, RTPBR_LOG_ERROR,
                  "rtpbr_context_create: out_context is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    *out_context = NULL;
    if (!desc) {
        rtpbr_log(&(rtpbr_context){0}, RTPBR_LOG_ERROR, "rtpbr_context_create: desc is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if ((desc->allocator.alloc == NULL) != (desc->allocator.free == NULL)) {
        rtpbr_log(&(rtpbr_context){.logger = desc->logger}, RTPBR_LOG_ERROR,
                  "rtpbr_context_create: allocator needs both alloc and free, or neither");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }

    rtpbr_context bootstrap = {.allocator = desc->allocator, .logger = desc->logger};
    rtpbr_context *ctx = rtpbr_alloc(&bootstrap, sizeof *ctx);
    if (!ctx) return RTPBR_ERROR_OUT_OF_HOST_MEMORY;
    *ctx = bootstrap;

    rtpbr_result result;
    if (desc->embedded.device != VK_NULL_HANDLE || desc->embedded.instance != VK_NULL_HANDLE)
        RTPBR_TRY(rtpbr_device_init_embedded(ctx, &desc->embedded));
    else
        RTPBR_TRY(rtpbr_device_init_standalone(ctx, desc));

    VkCommandPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = ctx->queue_family,
    };
    RTPBR_VK(ctx, vkCreateCommandPool(ctx->device, &pool_info, NULL, &ctx->command_pool));
    VkCommandBufferAllocateInfo cmd_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = ctx->command_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    RTPBR_VK(ctx, vkAllocateCommandBuffers(ctx->device, &cmd_info, &ctx->upload_cmd));
    VkFenceCreateInfo fence_info = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    RTPBR_VK(ctx, vkCreateFence(ctx->device, &fence_info, NULL, &ctx->upload_fence));

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
    RTPBR_VK(ctx, vkCreateSampler(ctx->device, &sampler_info, NULL, &ctx->lut_sampler));
    sampler_info.magFilter = sampler_info.minFilter = VK_FILTER_NEAREST;
    RTPBR_VK(ctx, vkCreateSampler(ctx->device, &sampler_info, NULL, &ctx->gbuffer_sampler));
    sampler_info.magFilter = sampler_info.minFilter = VK_FILTER_LINEAR;
    sampler_info.addressModeU = sampler_info.addressModeV = sampler_info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    RTPBR_VK(ctx, vkCreateSampler(ctx->device, &sampler_info, NULL, &ctx->texture_sampler));
    RTPBR_TRY(rtpbr_luts_create(ctx));
    RTPBR_TRY(rtpbr_pipelines_create(ctx));

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
        rtpbr_log(ctx, RTPBR_LOG_WARNING,
                  "rtpbr_context_destroy: destroying %u scene(s) and %u renderer(s) the host did not destroy",
                  scenes, renderers);
        while (ctx->renderers) rtpbr_renderer_destroy(ctx->renderers);
        while (ctx->scenes) rtpbr_gpu_scene_destroy(ctx->scenes);
    }
    if (ctx->device) {
        if (ctx->upload_fence) vkWaitForFences(ctx->device, 1, &ctx->upload_fence, VK_TRUE, UINT64_MAX);
        rtpbr_pipelines_destroy(ctx);
        rtpbr_luts_destroy(ctx);
        vkDestroySampler(ctx->device, ctx->lut_sampler, NULL);
        vkDestroySampler(ctx->device, ctx->gbuffer_sampler, NULL);
        vkDestroySampler(ctx->device, ctx->texture_sampler, NULL);
        vkDestroyFence(ctx->device, ctx->upload_fence, NULL);
        vkDestroyCommandPool(ctx->device, ctx->command_pool, NULL);
    }
    rtpbr_device_finish(ctx);
    rtpbr_free(ctx, ctx);
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

const char *rtpbr_context_device_name(const rtpbr_context *ctx)
{
    return ctx ? ctx->device_name : "";
}
