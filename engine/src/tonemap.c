// Tone-mapping pass: a full-screen triangle from linear radiance into a display target
// (the renderer's own sRGB image or the host's image in rtpbr_record).
#include "internal.h"

void rtpbr_tonemap_record(rtpbr_renderer *r, VkPipeline pipeline, const rtpbr_shader_tonemap *params,
                          VkImageView target, VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    VkRenderingAttachmentInfo color = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = target,
        .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        .loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
    };
    VkRenderingInfo rendering = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, {r->width, r->height}},
        .layerCount = 1,
        .colorAttachmentCount = 1,
        .pColorAttachments = &color,
    };
    vkCmdBeginRendering(cmd, &rendering);
    VkViewport viewport = {0.0f, 0.0f, (float)r->width, (float)r->height, 0.0f, 1.0f};
    VkRect2D scissor = {{0, 0}, {r->width, r->height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ctx->tonemap_layout, 0, 1, &r->tonemap_set, 0,
                            NULL);
    vkCmdPushConstants(cmd, ctx->tonemap_layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof *params, params);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
}
