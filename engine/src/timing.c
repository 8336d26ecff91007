// GPU timestamps around a renderer's passes (rtpbr_renderer_desc.timings): one query pool of
// RTPBR_TIMESTAMP_COUNT timestamps, reset and written by every recorded frame, read back
// without waiting by rtpbr_renderer_timings.
#include "internal.h"

rtpbr_result rtpbr_timing_create(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical_device, &family_count, NULL);
    VkQueueFamilyProperties *families = NULL;
    RTPBR_ALLOC(&ctx->host, families, (family_count ? family_count : 1) * sizeof *families);
    vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical_device, &family_count, families);
    uint32_t valid_bits = ctx->queue_family < family_count ? families[ctx->queue_family].timestampValidBits : 0;
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(ctx->physical_device, &props);
    if (valid_bits == 0 || props.limits.timestampPeriod <= 0.0f)
        RTPBR_FAIL(&ctx->host, RTPBR_ERROR_MISSING_FEATURE,
                   "renderer timings: the queue family %u has no timestamp support", ctx->queue_family);
    r->timing.ns_per_tick = props.limits.timestampPeriod;
    r->timing.valid_mask = valid_bits >= 64 ? UINT64_MAX : ((uint64_t)1 << valid_bits) - 1;
    VkQueryPoolCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
        .queryType = VK_QUERY_TYPE_TIMESTAMP,
        .queryCount = RTPBR_TIMESTAMP_COUNT,
    };
    RTPBR_VK(&ctx->host, vkCreateQueryPool(ctx->device, &info, NULL, &r->timing.pool));
cleanup:
    rtpbr_free(&ctx->host, families);
    return result;
}

void rtpbr_timing_destroy(rtpbr_renderer *r)
{
    if (r->timing.pool) vkDestroyQueryPool(r->context->device, r->timing.pool, NULL);
    r->timing.pool = VK_NULL_HANDLE;
}

void rtpbr_timing_mark(rtpbr_renderer *r, VkCommandBuffer cmd, rtpbr_timestamp which)
{
    if (!r->timing.pool) return;
    if (which == RTPBR_TIMESTAMP_START) {
        vkCmdResetQueryPool(cmd, r->timing.pool, 0, RTPBR_TIMESTAMP_COUNT);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, r->timing.pool, which);
        return;
    }
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, r->timing.pool, which);
    if (which == RTPBR_TIMESTAMP_COUNT - 1) r->timing.recorded = true;
}

rtpbr_result rtpbr_renderer_timings(rtpbr_renderer *r, rtpbr_timings *out)
{
    if (!r) return rtpbr_null_object(__func__, "renderer");
    if (!out) {
        rtpbr_log(&r->context->host, RTPBR_LOG_ERROR, "rtpbr_renderer_timings: out is NULL");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    *out = (rtpbr_timings){0};
    if (!r->timing.pool) {
        rtpbr_log(&r->context->host, RTPBR_LOG_ERROR, "rtpbr_renderer_timings: the renderer was created without timings");
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (!r->timing.recorded) return RTPBR_SUCCESS; // no frame yet: valid stays 0
    uint64_t ticks[RTPBR_TIMESTAMP_COUNT];
    VkResult vr = vkGetQueryPoolResults(r->context->device, r->timing.pool, 0, RTPBR_TIMESTAMP_COUNT, sizeof ticks,
                                        ticks, sizeof ticks[0], VK_QUERY_RESULT_64_BIT);
    if (vr == VK_NOT_READY) return RTPBR_SUCCESS; // the frame is still executing
    if (vr != VK_SUCCESS) return rtpbr_vk_fail(&r->context->host, vr, "vkGetQueryPoolResults");
    double ms[RTPBR_TIMESTAMP_COUNT - 1];
    for (int i = 0; i + 1 < RTPBR_TIMESTAMP_COUNT; ++i)
        ms[i] = (double)((ticks[i + 1] - ticks[i]) & r->timing.valid_mask) * r->timing.ns_per_tick * 1e-6;
    out->gbuffer_ms = ms[RTPBR_TIMESTAMP_START];
    out->lighting_ms = ms[RTPBR_TIMESTAMP_GBUFFER];
    out->tonemap_ms = ms[RTPBR_TIMESTAMP_LIGHTING];
    out->total_ms = out->gbuffer_ms + out->lighting_ms + out->tonemap_ms;
    out->valid = 1;
    return RTPBR_SUCCESS;
}
