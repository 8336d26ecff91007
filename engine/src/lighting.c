// Lighting pass: compute dispatches over screen tiles that turn the G-buffer into linear
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

// After the lighting dispatches: the resolve (supersampling), and the barrier before tone
// mapping and readback.
static void end_lighting(rtpbr_renderer *r, VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
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

// The LTC pass: the culling pass (cull.comp) writes each tile's light mask and queues the tile
// for its class; then one indirect dispatch per class runs that class's lighting variant over
// its queue (no barrier inside either kernel).
void rtpbr_lighting_record(rtpbr_renderer *r, const VkPipeline pipelines[RTPBR_TILE_CLASS_COUNT], VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    // Empty queues: VkDispatchIndirectCommand (0, 1, 1) per class (the previous frame's lighting
    // read them as indirect arguments and as storage).
    uint32_t empty[RTPBR_TILE_CLASS_COUNT][4];
    for (uint32_t c = 0; c < RTPBR_TILE_CLASS_COUNT; ++c) {
        empty[c][0] = 0;
        empty[c][1] = empty[c][2] = 1;
        empty[c][3] = 0;
    }
    VkBufferMemoryBarrier before = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT,
        .dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = r->tile_lists.buffer,
        .size = VK_WHOLE_SIZE,
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, NULL, 1, &before, 0, NULL);
    vkCmdUpdateBuffer(cmd, r->tile_lists.buffer, 0, sizeof empty, empty);
    VkBufferMemoryBarrier cleared = before;
    cleared.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    cleared.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, NULL, 1,
                         &cleared, 0, NULL);

    begin_lighting(r, ctx->cull_pipeline, ctx->lighting_layout, cmd);
    vkCmdDispatch(cmd, (r->tiles_x + RTPBR_CULL_GROUP - 1) / RTPBR_CULL_GROUP,
                  (r->tiles_y + RTPBR_CULL_GROUP - 1) / RTPBR_CULL_GROUP, 1);
    VkMemoryBarrier culled = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT,
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1, &culled, 0,
                         NULL, 0, NULL);
    for (uint32_t c = 0; c < RTPBR_TILE_CLASS_COUNT; ++c) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[c]);
        vkCmdDispatchIndirect(cmd, r->tile_lists.buffer, c * 4 * sizeof(uint32_t));
    }
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
    vkCmdDispatch(cmd, r->tiles_x, r->tiles_y, 1);
    end_lighting(r, cmd);
}
