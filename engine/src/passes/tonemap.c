// Tone-mapping pass: a full-screen triangle from linear radiance into a display target (the
// renderer's own sRGB image, or the host's image in rtpbr_record): exposure, the operator of
// rtpbr_render_desc.tonemap, and the sRGB curve when the target's format does not encode.
#include <math.h>

#include "passes.h"

#include "../internal.h"
#include "pipeline.h"
#include "rtpbr_spirv_tonemap_frag.h"
#include "rtpbr_spirv_tonemap_vert.h"

static const VkDescriptorSetLayoutBinding bindings[] = {
    {RTPBR_BINDING_TONEMAP_RADIANCE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_FRAGMENT_BIT, NULL},
};

rtpbr_result rtpbr_tonemap_pass_init(rtpbr_context *ctx)
{
    rtpbr_tonemap_pass *pass = &ctx->tonemap;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_pass_layouts_create(ctx, RTPBR_BINDINGS(bindings), VK_SHADER_STAGE_FRAGMENT_BIT,
                                        sizeof(rtpbr_shader_tonemap), &pass->set_layout, &pass->layout));
    RTPBR_TRY(rtpbr_shader_module(ctx, RTPBR_SPIRV(rtpbr_spirv_tonemap_vert), &pass->vert));
    RTPBR_TRY(rtpbr_shader_module(ctx, RTPBR_SPIRV(rtpbr_spirv_tonemap_frag), &pass->frag));
    // The renderer's own display target now (the default operator), so that a bad driver fails early.
    VkPipeline unused;
    RTPBR_TRY(rtpbr_tonemap_pipeline_get(ctx, RTPBR_DISPLAY_FORMAT, &(rtpbr_render_desc){0}, RTPBR_ENCODE_NONE, &unused));
cleanup:
    return result; // the caller finishes a half-built pass
}

void rtpbr_tonemap_pass_finish(rtpbr_context *ctx)
{
    rtpbr_tonemap_pass *pass = &ctx->tonemap;
    for (uint32_t i = 0; i < RTPBR_TONEMAP_PIPELINE_CACHE; ++i)
        vkDestroyPipeline(ctx->device, pass->pipelines[i].pipeline, NULL);
    vkDestroyShaderModule(ctx->device, pass->vert, NULL);
    vkDestroyShaderModule(ctx->device, pass->frag, NULL);
    rtpbr_pass_objects_destroy(ctx, NULL, 0, pass->layout, pass->set_layout);
    *pass = (rtpbr_tonemap_pass){0};
}

// The operator of a desc (RTPBR_TONEMAP_OP_*).
static uint32_t tonemap_op(const rtpbr_render_desc *desc)
{
    return desc->tonemap == RTPBR_TONEMAP_DEFAULT ? RTPBR_TONEMAP_OP_ACES : (uint32_t)desc->tonemap;
}

rtpbr_result rtpbr_tonemap_pipeline_get(rtpbr_context *ctx, VkFormat format, const rtpbr_render_desc *desc,
                                        uint32_t encode, VkPipeline *out)
{
    rtpbr_tonemap_pass *pass = &ctx->tonemap;
    rtpbr_result result = RTPBR_SUCCESS;
    uint32_t op = tonemap_op(desc);
    uint32_t slot = RTPBR_TONEMAP_PIPELINE_CACHE;
    for (uint32_t i = 0; i < RTPBR_TONEMAP_PIPELINE_CACHE; ++i) {
        const rtpbr_tonemap_pipeline *p = &pass->pipelines[i];
        if (p->pipeline && p->format == format && p->op == op && p->encode == encode) {
            *out = pass->pipelines[i].pipeline;
            return RTPBR_SUCCESS;
        }
        if (!pass->pipelines[i].pipeline && slot == RTPBR_TONEMAP_PIPELINE_CACHE) slot = i;
    }
    if (slot == RTPBR_TONEMAP_PIPELINE_CACHE)
        RTPBR_FAIL(&ctx->host, RTPBR_ERROR_LIMIT_EXCEEDED,
                   "more than %u different target formats and tone-mapping operators used with rtpbr_record",
                   RTPBR_TONEMAP_PIPELINE_CACHE);
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx->physical_device, format, &props);
    if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT))
        RTPBR_FAIL(&ctx->host, RTPBR_ERROR_MISSING_FEATURE, "target format %d does not support colour attachments",
                   (int)format);
    // (on lavapipe every branch runs: the operator and the encoding compiled in)
    const uint32_t values[2] = {op, encode};
    const VkSpecializationMapEntry entries[2] = {{RTPBR_SPEC_TONEMAP_OP, 0, sizeof values[0]},
                                                 {RTPBR_SPEC_TONEMAP_ENCODE, sizeof values[0], sizeof values[1]}};
    const VkSpecializationInfo specialization = {2, entries, sizeof values, values};
    rtpbr_graphics_desc d = {
        .vert = pass->vert,
        .frag = pass->frag,
        .layout = pass->layout,
        .color_formats = &format,
        .color_count = 1,
        .depth_format = VK_FORMAT_UNDEFINED,
        .frag_specialization = &specialization,
    };
    RTPBR_TRY(rtpbr_graphics_pipeline_create(ctx, &d, &pass->pipelines[slot].pipeline));
    pass->pipelines[slot].format = format;
    pass->pipelines[slot].op = op;
    pass->pipelines[slot].encode = encode;
    *out = pass->pipelines[slot].pipeline;
cleanup:
    return result;
}

rtpbr_result rtpbr_tonemap_renderer_init(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_descriptor_set_create(ctx, RTPBR_BINDINGS(bindings), ctx->tonemap.set_layout, &r->tonemap_set));
    rtpbr_descriptor_write_image(ctx, RTPBR_BINDINGS(bindings), r->tonemap_set.set, RTPBR_BINDING_TONEMAP_RADIANCE,
                                 VK_NULL_HANDLE, r->radiance.view, VK_IMAGE_LAYOUT_GENERAL);
cleanup:
    return result;
}

void rtpbr_tonemap_renderer_finish(rtpbr_renderer *r)
{
    rtpbr_descriptor_set_destroy(r->context, &r->tonemap_set);
}

void rtpbr_tonemap_record(rtpbr_renderer *r, VkPipeline pipeline, const rtpbr_render_desc *desc, VkImageView target,
                          VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    rtpbr_shader_tonemap params = {.scale = exp2f(desc->exposure)};
    VkRenderingAttachmentInfo color = rtpbr_attachment(target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                                       VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_STORE);
    rtpbr_begin_rendering(cmd, r->width, r->height, &color, 1, NULL);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ctx->tonemap.layout, 0, 1, &r->tonemap_set.set, 0,
                            NULL);
    vkCmdPushConstants(cmd, ctx->tonemap.layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof params, &params);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
}
