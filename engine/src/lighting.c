// Lighting pass: a compute dispatch over screen tiles that turns the G-buffer into linear
// radiance (the shader variant selects the shader-library models), then, with supersampling,
// the resolve that box-filters it down to the output.
#include "internal.h"

// The image the lighting pass writes: the output, or its supersampled version.
static VkImage shade_target(const rtpbr_renderer *r)
{
    return r->supersample > 1 ? r->radiance_ss.image : r->radiance.image;
}

static void begin_lighting(rtpbr_renderer *r, VkPipeline pipeline, VkPipelineLayout layout, VkCommandBuffer cmd)
{
    // The previous frame's tone mapping, readback or resolve read the image.
    rtpbr_image_barrier(cmd, shade_target(r), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                        0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &r->lighting_set, 0, NULL);
}

static void end_lighting(rtpbr_renderer *r, VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    vkCmdDispatch(cmd, (r->shade_width + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE,
                  (r->shade_height + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE, 1);
    if (r->supersample > 1) {
        rtpbr_image_barrier(cmd, r->radiance_ss.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                            VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
        rtpbr_image_barrier(cmd, r->radiance.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_GENERAL,
                            VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
        rtpbr_shader_resolve params = {.size = {r->width, r->height}, .factor = r->supersample};
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->resolve_pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->resolve_layout, 0, 1, &r->resolve_set, 0,
                                NULL);
        vkCmdPushConstants(cmd, ctx->resolve_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
        vkCmdDispatch(cmd, (r->width + 7) / 8, (r->height + 7) / 8, 1);
    }
    rtpbr_image_barrier(cmd, r->radiance.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                        VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

void rtpbr_lighting_record(rtpbr_renderer *r, VkPipeline pipeline, VkCommandBuffer cmd)
{
    begin_lighting(r, pipeline, r->context->lighting_layout, cmd);
    end_lighting(r, cmd);
}

// The Monte Carlo lighting pass (lighting_mc.comp): the same dispatch and barriers, with the
// sample count and seed as push constants.
void rtpbr_lighting_mc_record(rtpbr_renderer *r, VkPipeline pipeline, const rtpbr_shader_mc *params,
                              VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    begin_lighting(r, pipeline, ctx->lighting_mc_layout, cmd);
    vkCmdPushConstants(cmd, ctx->lighting_mc_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *params, params);
    end_lighting(r, cmd);
}
