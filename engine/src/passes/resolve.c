// Supersampling resolve (resolve.comp): the box filter over each s x s block of the lighting
// pass's radiance (rtpbr_renderer_desc.supersample) into the output radiance image.
#include "passes.h"

#include "../internal.h"
#include "pipeline.h"
#include "rtpbr_spirv_resolve_comp.h"

static const VkDescriptorSetLayoutBinding bindings[] = {
    {RTPBR_BINDING_RESOLVE_SOURCE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL},
    {RTPBR_BINDING_RESOLVE_TARGET, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL},
};

rtpbr_result rtpbr_resolve_pass_init(rtpbr_context *ctx)
{
    rtpbr_resolve_pass *pass = &ctx->resolve;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_pass_layouts_create(ctx, RTPBR_BINDINGS(bindings), VK_SHADER_STAGE_COMPUTE_BIT,
                                        sizeof(rtpbr_shader_resolve), &pass->set_layout, &pass->layout));
    RTPBR_TRY(rtpbr_compute_pipeline_create(ctx, RTPBR_SPIRV(rtpbr_spirv_resolve_comp), pass->layout, &pass->pipeline));
cleanup:
    return result; // the caller finishes a half-built pass
}

void rtpbr_resolve_pass_finish(rtpbr_context *ctx)
{
    rtpbr_resolve_pass *pass = &ctx->resolve;
    rtpbr_pass_objects_destroy(ctx, &pass->pipeline, 1, pass->layout, pass->set_layout);
    *pass = (rtpbr_resolve_pass){0};
}

rtpbr_result rtpbr_resolve_renderer_init(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    if (r->supersample <= 1) return RTPBR_SUCCESS; // the lighting pass writes the output itself
    RTPBR_TRY(rtpbr_descriptor_set_create(ctx, RTPBR_BINDINGS(bindings), ctx->resolve.set_layout, &r->resolve_set));
    rtpbr_descriptor_write_image(ctx, RTPBR_BINDINGS(bindings), r->resolve_set.set, RTPBR_BINDING_RESOLVE_SOURCE,
                                 VK_NULL_HANDLE, r->radiance_ss.view, VK_IMAGE_LAYOUT_GENERAL);
    rtpbr_descriptor_write_image(ctx, RTPBR_BINDINGS(bindings), r->resolve_set.set, RTPBR_BINDING_RESOLVE_TARGET,
                                 VK_NULL_HANDLE, r->radiance.view, VK_IMAGE_LAYOUT_GENERAL);
cleanup:
    return result;
}

void rtpbr_resolve_renderer_finish(rtpbr_renderer *r)
{
    rtpbr_descriptor_set_destroy(r->context, &r->resolve_set);
}

// After the lighting dispatches into radiance_ss; radiance is written here.
void rtpbr_resolve_record(rtpbr_renderer *r, VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    rtpbr_image_barrier(cmd, r->radiance_ss.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                        VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    rtpbr_image_barrier(cmd, r->radiance.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                        0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    rtpbr_shader_resolve params = {.size = {r->width, r->height}, .factor = r->supersample};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->resolve.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->resolve.layout, 0, 1, &r->resolve_set.set, 0,
                            NULL);
    vkCmdPushConstants(cmd, ctx->resolve.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
    vkCmdDispatch(cmd, (r->width + 7) / 8, (r->height + 7) / 8, 1);
}
