// Lighting pass: a compute dispatch over screen tiles that turns the G-buffer into linear
// radiance (the shader variant selects the shader-library models).
#include "internal.h"

void rtpbr_lighting_record(rtpbr_renderer *r, VkPipeline pipeline, VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    // The previous frame's tone mapping and readback read the radiance image.
    rtpbr_image_barrier(cmd, r->radiance.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->lighting_layout, 0, 1, &r->lighting_set,
                            0, NULL);
    vkCmdDispatch(cmd, (r->width + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE,
                  (r->height + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE, 1);
    rtpbr_image_barrier(cmd, r->radiance.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                        VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

// The Monte Carlo lighting pass (lighting_mc.comp): the same dispatch and barriers, with the
// sample count and seed as push constants.
void rtpbr_lighting_mc_record(rtpbr_renderer *r, VkPipeline pipeline, const rtpbr_shader_mc *params,
                              VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    rtpbr_image_barrier(cmd, r->radiance.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->lighting_mc_layout, 0, 1, &r->lighting_set,
                            0, NULL);
    vkCmdPushConstants(cmd, ctx->lighting_mc_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *params, params);
    vkCmdDispatch(cmd, (r->width + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE,
                  (r->height + RTPBR_TILE_SIZE - 1) / RTPBR_TILE_SIZE, 1);
    rtpbr_image_barrier(cmd, r->radiance.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                        VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}
