// Area-light shadows (issue 17): the ratio estimator of Heitz, Hill & McGuire 2018,
// "Combining Analytic Direct Illumination and Stochastic Shadows", as two compute passes that
// run between the G-buffer and the lighting pass:
//   1. shadow.comp traces, per pixel and shadowed light, rtpbr_render_desc.shadow_samples
//      rays to points on the light against the scene's BVH (bvh.c) and writes the shadowed
//      and unshadowed estimates of the light's cosine-weighted irradiance (layer = light);
//   2. shadow_denoise.comp filters both estimates with the same depth- and normal-guided
//      weights and writes their ratio (layer = light).
// The lighting passes multiply light i's result by the ratio of layer i (shaders/
// shadow_ratio.glsl, binding RTPBR_BINDING_LIGHT_SHADOW_RATIO) for i < shadow_light_count
// of the frame block. Lights 0 .. RTPBR_MAX_SHADOWED_LIGHTS - 1 cast shadows.
// Memory: 8 bytes per shading pixel and shadowed-light slot (64 bytes per pixel), allocated
// with the renderer.
#include <string.h>

#include "internal.h"

#include "rtpbr_spirv_shadow_comp.h"
#include "rtpbr_spirv_shadow_denoise_comp.h"

#define SPIRV(name) ((rtpbr_spirv){name, sizeof name})

rtpbr_result rtpbr_shadow_layouts_create(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkDescriptorSetLayoutBinding bindings[RTPBR_SHADOW_BINDING_COUNT];
    for (uint32_t i = 0; i < RTPBR_SHADOW_BINDING_COUNT; ++i)
        bindings[i] = (VkDescriptorSetLayoutBinding){i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                                                     VK_SHADER_STAGE_COMPUTE_BIT, NULL};
    bindings[RTPBR_BINDING_SHADOW_FRAME].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    bindings[RTPBR_BINDING_SHADOW_DEPTH].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    bindings[RTPBR_BINDING_SHADOW_NORMAL].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    bindings[RTPBR_BINDING_SHADOW_ESTIMATES].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    bindings[RTPBR_BINDING_SHADOW_RATIO].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    VkDescriptorSetLayoutCreateInfo set_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = RTPBR_SHADOW_BINDING_COUNT,
        .pBindings = bindings,
    };
    RTPBR_VK(ctx, vkCreateDescriptorSetLayout(ctx->device, &set_info, NULL, &ctx->shadow_set_layout));
    VkPushConstantRange push = {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(rtpbr_shader_shadow)};
    VkPipelineLayoutCreateInfo layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &ctx->shadow_set_layout,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push,
    };
    RTPBR_VK(ctx, vkCreatePipelineLayout(ctx->device, &layout_info, NULL, &ctx->shadow_layout));
cleanup:
    return result; // rtpbr_shadow_pipelines_destroy destroys a half-built set
}

void rtpbr_shadow_pipelines_destroy(rtpbr_context *ctx)
{
    vkDestroyPipeline(ctx->device, ctx->shadow_trace_pipeline, NULL);
    vkDestroyPipeline(ctx->device, ctx->shadow_denoise_pipeline, NULL);
    vkDestroyPipelineLayout(ctx->device, ctx->shadow_layout, NULL);
    vkDestroyDescriptorSetLayout(ctx->device, ctx->shadow_set_layout, NULL);
}

static rtpbr_result create_compute(rtpbr_context *ctx, rtpbr_spirv spirv, VkPipeline *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkShaderModule module = VK_NULL_HANDLE;
    RTPBR_TRY(rtpbr_shader_module(ctx, spirv, &module));
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = module, .pName = "main"},
        .layout = ctx->shadow_layout,
    };
    RTPBR_VK(ctx, vkCreateComputePipelines(ctx->device, VK_NULL_HANDLE, 1, &info, NULL, out));
cleanup:
    vkDestroyShaderModule(ctx->device, module, NULL);
    return result;
}

rtpbr_result rtpbr_shadow_pipelines_get(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    if (!ctx->shadow_trace_pipeline)
        result = create_compute(ctx, SPIRV(rtpbr_spirv_shadow_comp), &ctx->shadow_trace_pipeline);
    if (result == RTPBR_SUCCESS && !ctx->shadow_denoise_pipeline)
        result = create_compute(ctx, SPIRV(rtpbr_spirv_shadow_denoise_comp), &ctx->shadow_denoise_pipeline);
    return result;
}

// Both images from UNDEFINED to GENERAL, where they stay (the lighting set binds the ratios
// even with shadows off, so they must be in a valid layout from the start).
static void record_initial_layouts(VkCommandBuffer cmd, void *user)
{
    const rtpbr_renderer *r = user;
    VkImageMemoryBarrier barriers[2];
    const VkImage images[2] = {r->shadow_estimates.image, r->shadow_ratio.image};
    for (int i = 0; i < 2; ++i)
        barriers[i] = (VkImageMemoryBarrier){
            .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
            .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
            .oldLayout = VK_IMAGE_LAYOUT_UNDEFINED,
            .newLayout = VK_IMAGE_LAYOUT_GENERAL,
            .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .image = images[i],
            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, RTPBR_MAX_SHADOWED_LIGHTS},
        };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, NULL, 0,
                         NULL, 2, barriers);
}

rtpbr_result rtpbr_shadow_targets_create(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_image_create_layers(ctx, r->shade_width, r->shade_height, RTPBR_MAX_SHADOWED_LIGHTS,
                                        VK_FORMAT_R32_UINT, VK_IMAGE_USAGE_STORAGE_BIT, &r->shadow_estimates));
    RTPBR_TRY(rtpbr_image_create_layers(ctx, r->shade_width, r->shade_height, RTPBR_MAX_SHADOWED_LIGHTS,
                                        VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                        &r->shadow_ratio));
    RTPBR_TRY(rtpbr_submit_once(ctx, record_initial_layouts, r));

    VkDescriptorSetAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = r->descriptor_pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &ctx->shadow_set_layout,
    };
    RTPBR_VK(ctx, vkAllocateDescriptorSets(ctx->device, &alloc, &r->shadow_set));
    VkDescriptorBufferInfo frame = {r->frame.buffer, 0, sizeof(rtpbr_shader_frame)};
    VkDescriptorImageInfo depth = {ctx->gbuffer_sampler, r->depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo normal = {ctx->gbuffer_sampler, r->gbuffer[1].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo estimates = {VK_NULL_HANDLE, r->shadow_estimates.view, VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorImageInfo ratio = {VK_NULL_HANDLE, r->shadow_ratio.view, VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorImageInfo ratio_sampled = {ctx->gbuffer_sampler, r->shadow_ratio.view, VK_IMAGE_LAYOUT_GENERAL};
#define WRITE(set, binding, type, field, info)                                                                \
    (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = (set), .dstBinding = (binding), \
                           .descriptorCount = 1, .descriptorType = (type), .field = (info)}
    VkWriteDescriptorSet writes[6] = {
        WRITE(r->shadow_set, RTPBR_BINDING_SHADOW_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, pBufferInfo, &frame),
        WRITE(r->shadow_set, RTPBR_BINDING_SHADOW_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pImageInfo, &depth),
        WRITE(r->shadow_set, RTPBR_BINDING_SHADOW_NORMAL, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pImageInfo, &normal),
        WRITE(r->shadow_set, RTPBR_BINDING_SHADOW_ESTIMATES, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pImageInfo, &estimates),
        WRITE(r->shadow_set, RTPBR_BINDING_SHADOW_RATIO, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pImageInfo, &ratio),
        WRITE(r->lighting_set, RTPBR_BINDING_LIGHT_SHADOW_RATIO, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pImageInfo,
              &ratio_sampled),
    };
    vkUpdateDescriptorSets(ctx->device, 6, writes, 0, NULL);
cleanup:
    return result; // the caller destroys the renderer, and with it a half-built state
}

void rtpbr_shadow_targets_destroy(rtpbr_renderer *r)
{
    rtpbr_image_destroy(r->context, &r->shadow_estimates);
    rtpbr_image_destroy(r->context, &r->shadow_ratio);
}

void rtpbr_shadow_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene)
{
    VkDescriptorBufferInfo lights = {scene->lights.buffer, 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo nodes = {scene->bvh_nodes.buffer, 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo triangles = {scene->bvh_triangles.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet writes[3] = {
        WRITE(r->shadow_set, RTPBR_BINDING_SHADOW_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pBufferInfo, &lights),
        WRITE(r->shadow_set, RTPBR_BINDING_SHADOW_BVH_NODES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pBufferInfo, &nodes),
        WRITE(r->shadow_set, RTPBR_BINDING_SHADOW_BVH_TRIANGLES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pBufferInfo,
              &triangles),
    };
    vkUpdateDescriptorSets(r->context->device, 3, writes, 0, NULL);
}
#undef WRITE

// A memory barrier between compute dispatches on one of the shadow images (all layers).
static void compute_barrier(VkCommandBuffer cmd, VkImage image, VkAccessFlags src, VkAccessFlags dst)
{
    VkImageMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
        .srcAccessMask = src,
        .dstAccessMask = dst,
        .oldLayout = VK_IMAGE_LAYOUT_GENERAL,
        .newLayout = VK_IMAGE_LAYOUT_GENERAL,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image,
        .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, RTPBR_MAX_SHADOWED_LIGHTS},
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, NULL,
                         0, NULL, 1, &barrier);
}

void rtpbr_shadow_record(rtpbr_renderer *r, const rtpbr_shader_shadow *params, VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    uint32_t gx = (r->shade_width + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE;
    uint32_t gy = (r->shade_height + RTPBR_SHADOW_GROUP_SIZE - 1) / RTPBR_SHADOW_GROUP_SIZE;
    // The previous frame's denoise read the estimates, its lighting pass read the ratios.
    compute_barrier(cmd, r->shadow_estimates.image, VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->shadow_layout, 0, 1, &r->shadow_set, 0, NULL);
    vkCmdPushConstants(cmd, ctx->shadow_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *params, params);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->shadow_trace_pipeline);
    vkCmdDispatch(cmd, gx, gy, 1);
    compute_barrier(cmd, r->shadow_estimates.image, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
    compute_barrier(cmd, r->shadow_ratio.image, VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->shadow_denoise_pipeline);
    vkCmdDispatch(cmd, gx, gy, 1);
    compute_barrier(cmd, r->shadow_ratio.image, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
}
