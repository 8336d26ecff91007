// Shader modules, layouts, pipelines and descriptor sets for the pass files (pipeline.h).
#include "pipeline.h"

#include "../internal.h"

enum { RTPBR_MAX_COLOR_ATTACHMENTS = RTPBR_GBUFFER_COUNT }; // the G-buffer pass has the most

rtpbr_result rtpbr_shader_module(rtpbr_context *ctx, rtpbr_spirv spirv, VkShaderModule *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkShaderModuleCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = spirv.size,
        .pCode = spirv.code,
    };
    RTPBR_VK(&ctx->host, vkCreateShaderModule(ctx->device, &info, NULL, out));
cleanup:
    return result;
}

rtpbr_result rtpbr_set_layout_create(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSetLayout *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkDescriptorSetLayoutCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = bindings.count,
        .pBindings = bindings.entries,
    };
    RTPBR_VK(&ctx->host, vkCreateDescriptorSetLayout(ctx->device, &info, NULL, out));
cleanup:
    return result;
}

rtpbr_result rtpbr_pipeline_layout_create(rtpbr_context *ctx, const VkDescriptorSetLayout *sets, uint32_t set_count,
                                          VkShaderStageFlags push_stages, uint32_t push_size, VkPipelineLayout *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkPushConstantRange push = {push_stages, 0, push_size};
    VkPipelineLayoutCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = set_count,
        .pSetLayouts = sets,
        .pushConstantRangeCount = push_size ? 1 : 0,
        .pPushConstantRanges = &push,
    };
    RTPBR_VK(&ctx->host, vkCreatePipelineLayout(ctx->device, &info, NULL, out));
cleanup:
    return result;
}

rtpbr_result rtpbr_compute_pipeline_create(rtpbr_context *ctx, rtpbr_spirv spirv, VkPipelineLayout layout,
                                           VkPipeline *out)
{
    return rtpbr_compute_pipeline_create_specialized(ctx, spirv, layout, NULL, out);
}

rtpbr_result rtpbr_compute_pipeline_create_specialized(rtpbr_context *ctx, rtpbr_spirv spirv, VkPipelineLayout layout,
                                                       const VkSpecializationInfo *specialization, VkPipeline *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkShaderModule module = VK_NULL_HANDLE;
    RTPBR_TRY(rtpbr_shader_module(ctx, spirv, &module));
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = module, .pName = "main", .pSpecializationInfo = specialization},
        .layout = layout,
    };
    RTPBR_VK(&ctx->host, vkCreateComputePipelines(ctx->device, VK_NULL_HANDLE, 1, &info, NULL, out));
cleanup:
    vkDestroyShaderModule(ctx->device, module, NULL);
    return result;
}

rtpbr_result rtpbr_graphics_pipeline_create(rtpbr_context *ctx, const rtpbr_graphics_desc *d, VkPipeline *out)
{
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = d->vert, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = d->frag, .pName = "main", .pSpecializationInfo = d->frag_specialization},
    };
    VkPipelineVertexInputStateCreateInfo no_vertex_input = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
    };
    VkPipelineInputAssemblyStateCreateInfo assembly = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
        .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
    };
    VkPipelineViewportStateCreateInfo viewport = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
        .viewportCount = 1,
        .scissorCount = 1,
    };
    VkPipelineRasterizationStateCreateInfo raster = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .polygonMode = VK_POLYGON_MODE_FILL,
        .cullMode = VK_CULL_MODE_NONE,
        .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
        .lineWidth = 1.0f,
    };
    VkPipelineMultisampleStateCreateInfo multisample = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT,
    };
    VkPipelineDepthStencilStateCreateInfo depth = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
        .depthTestEnable = d->depth_format != VK_FORMAT_UNDEFINED,
        .depthWriteEnable = d->depth_format != VK_FORMAT_UNDEFINED && !d->depth_read_only,
        .depthCompareOp = d->depth_read_only ? VK_COMPARE_OP_LESS_OR_EQUAL : VK_COMPARE_OP_LESS,
    };
    VkPipelineColorBlendAttachmentState blend[RTPBR_MAX_COLOR_ATTACHMENTS];
    for (uint32_t i = 0; i < RTPBR_MAX_COLOR_ATTACHMENTS; ++i)
        blend[i] = (VkPipelineColorBlendAttachmentState){
            .blendEnable = d->blend_premultiplied,
            .srcColorBlendFactor = VK_BLEND_FACTOR_ONE,
            .dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
            .colorBlendOp = VK_BLEND_OP_ADD,
            .srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE,
            .dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
            .alphaBlendOp = VK_BLEND_OP_ADD,
            .colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                              VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT,
        };
    VkPipelineColorBlendStateCreateInfo blending = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        .attachmentCount = d->color_count,
        .pAttachments = blend,
    };
    VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR, VK_DYNAMIC_STATE_CULL_MODE,
                                       VK_DYNAMIC_STATE_FRONT_FACE};
    VkPipelineDynamicStateCreateInfo dynamic = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
        .dynamicStateCount = d->dynamic_cull ? 4 : 2,
        .pDynamicStates = dynamic_states,
    };
    VkPipelineRenderingCreateInfo rendering = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
        .colorAttachmentCount = d->color_count,
        .pColorAttachmentFormats = d->color_formats,
        .depthAttachmentFormat = d->depth_format,
    };
    VkGraphicsPipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .pNext = &rendering,
        .stageCount = 2,
        .pStages = stages,
        .pVertexInputState = d->vertex_input ? d->vertex_input : &no_vertex_input,
        .pInputAssemblyState = &assembly,
        .pViewportState = &viewport,
        .pRasterizationState = &raster,
        .pMultisampleState = &multisample,
        .pDepthStencilState = &depth,
        .pColorBlendState = &blending,
        .pDynamicState = &dynamic,
        .layout = d->layout,
    };
    rtpbr_result result = RTPBR_SUCCESS;
    if (d->color_count > RTPBR_MAX_COLOR_ATTACHMENTS)
        RTPBR_FAIL(&ctx->host, RTPBR_ERROR_LIMIT_EXCEEDED, "graphics pipeline: %u colour attachments, at most %u",
                   d->color_count, RTPBR_MAX_COLOR_ATTACHMENTS);
    RTPBR_VK(&ctx->host, vkCreateGraphicsPipelines(ctx->device, VK_NULL_HANDLE, 1, &info, NULL, out));
cleanup:
    return result;
}

rtpbr_result rtpbr_descriptor_pool_create(rtpbr_context *ctx, rtpbr_bindings bindings, uint32_t sets,
                                          VkDescriptorPool *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    // One pool size per descriptor type of the table (types in table order, no repeats).
    VkDescriptorPoolSize sizes[8];
    uint32_t size_count = 0;
    for (uint32_t i = 0; i < bindings.count; ++i) {
        const VkDescriptorSetLayoutBinding *b = &bindings.entries[i];
        uint32_t s = 0;
        while (s < size_count && sizes[s].type != b->descriptorType) ++s;
        if (s == size_count) {
            if (size_count == sizeof sizes / sizeof sizes[0])
                RTPBR_FAIL(&ctx->host, RTPBR_ERROR_LIMIT_EXCEEDED, "descriptor pool: more than %u descriptor types",
                           size_count);
            sizes[size_count++] = (VkDescriptorPoolSize){b->descriptorType, 0};
        }
        sizes[s].descriptorCount += b->descriptorCount * sets;
    }
    VkDescriptorPoolCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = sets,
        .poolSizeCount = size_count,
        .pPoolSizes = sizes,
    };
    RTPBR_VK(&ctx->host, vkCreateDescriptorPool(ctx->device, &info, NULL, out));
cleanup:
    return result;
}

rtpbr_result rtpbr_descriptor_set_create(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSetLayout layout,
                                         rtpbr_descriptor_set *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_descriptor_pool_create(ctx, bindings, 1, &out->pool));
    VkDescriptorSetAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = out->pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &layout,
    };
    RTPBR_VK(&ctx->host, vkAllocateDescriptorSets(ctx->device, &alloc, &out->set));
cleanup:
    return result; // the caller destroys a half-built set (rtpbr_descriptor_set_destroy)
}

void rtpbr_descriptor_set_destroy(rtpbr_context *ctx, rtpbr_descriptor_set *set)
{
    if (set->pool) vkDestroyDescriptorPool(ctx->device, set->pool, NULL);
    *set = (rtpbr_descriptor_set){0};
}

// The type of `binding` in the table (the tables are written in binding order, but a search
// keeps them free to be written otherwise).
static VkDescriptorType binding_type(rtpbr_bindings bindings, uint32_t binding)
{
    for (uint32_t i = 0; i < bindings.count; ++i)
        if (bindings.entries[i].binding == binding) return bindings.entries[i].descriptorType;
    return VK_DESCRIPTOR_TYPE_MAX_ENUM; // a binding the layout lacks: the validation layer says so
}

// One descriptor of `binding` (its type from the table): a buffer or an image.
static void write_descriptor(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set, uint32_t binding,
                             const VkDescriptorBufferInfo *buffer, const VkDescriptorImageInfo *image,
                             const VkBufferView *texels)
{
    VkWriteDescriptorSet write = {
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .dstSet = set,
        .dstBinding = binding,
        .descriptorCount = 1,
        .descriptorType = binding_type(bindings, binding),
        .pImageInfo = image,
        .pBufferInfo = buffer,
        .pTexelBufferView = texels,
    };
    vkUpdateDescriptorSets(ctx->device, 1, &write, 0, NULL);
}

void rtpbr_descriptor_write_buffer(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set, uint32_t binding,
                                   VkBuffer buffer, VkDeviceSize range)
{
    write_descriptor(ctx, bindings, set, binding, &(VkDescriptorBufferInfo){buffer, 0, range}, NULL, NULL);
}

void rtpbr_descriptor_write_buffer_range(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set,
                                         uint32_t binding, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize range)
{
    write_descriptor(ctx, bindings, set, binding, &(VkDescriptorBufferInfo){buffer, offset, range}, NULL, NULL);
}

void rtpbr_descriptor_write_buffers(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set,
                                    const rtpbr_buffer_write *writes, uint32_t count)
{
    for (uint32_t i = 0; i < count; ++i)
        rtpbr_descriptor_write_buffer(ctx, bindings, set, writes[i].binding, writes[i].buffer, VK_WHOLE_SIZE);
}

void rtpbr_descriptor_write_image(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set, uint32_t binding,
                                  VkSampler sampler, VkImageView view, VkImageLayout layout)
{
    write_descriptor(ctx, bindings, set, binding, NULL, &(VkDescriptorImageInfo){sampler, view, layout}, NULL);
}

void rtpbr_descriptor_write_texel_buffer(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set,
                                         uint32_t binding, VkBufferView view)
{
    write_descriptor(ctx, bindings, set, binding, NULL, NULL, &view);
}

void rtpbr_descriptor_write_accel(rtpbr_context *ctx, VkDescriptorSet set, uint32_t binding,
                                  VkAccelerationStructureKHR accel)
{
    const VkWriteDescriptorSetAccelerationStructureKHR structures = {
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR,
        .accelerationStructureCount = 1,
        .pAccelerationStructures = &accel,
    };
    const VkWriteDescriptorSet write = {
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .pNext = &structures,
        .dstSet = set,
        .dstBinding = binding,
        .descriptorCount = 1,
        .descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR,
    };
    vkUpdateDescriptorSets(ctx->device, 1, &write, 0, NULL);
}

rtpbr_result rtpbr_pass_layouts_create(rtpbr_context *ctx, rtpbr_bindings bindings, VkShaderStageFlags push_stages,
                                       uint32_t push_size, VkDescriptorSetLayout *set_layout, VkPipelineLayout *layout)
{
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_set_layout_create(ctx, bindings, set_layout));
    RTPBR_TRY(rtpbr_pipeline_layout_create(ctx, set_layout, 1, push_stages, push_size, layout));
cleanup:
    return result; // the caller destroys what was made (rtpbr_pass_objects_destroy)
}

void rtpbr_pass_objects_destroy(rtpbr_context *ctx, const VkPipeline *pipelines, uint32_t pipeline_count,
                                VkPipelineLayout layout, VkDescriptorSetLayout set_layout)
{
    for (uint32_t i = 0; i < pipeline_count; ++i) vkDestroyPipeline(ctx->device, pipelines[i], NULL);
    vkDestroyPipelineLayout(ctx->device, layout, NULL);
    vkDestroyDescriptorSetLayout(ctx->device, set_layout, NULL);
}

VkRenderingAttachmentInfo rtpbr_attachment(VkImageView view, VkImageLayout layout, VkAttachmentLoadOp load,
                                           VkAttachmentStoreOp store)
{
    return (VkRenderingAttachmentInfo){
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = view,
        .imageLayout = layout,
        .loadOp = load,
        .storeOp = store,
    };
}

void rtpbr_begin_rendering(VkCommandBuffer cmd, uint32_t width, uint32_t height, const VkRenderingAttachmentInfo *colors,
                           uint32_t color_count, const VkRenderingAttachmentInfo *depth)
{
    VkRenderingInfo rendering = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, {width, height}},
        .layerCount = 1,
        .colorAttachmentCount = color_count,
        .pColorAttachments = colors,
        .pDepthAttachment = depth,
    };
    vkCmdBeginRendering(cmd, &rendering);
    VkViewport viewport = {0.0f, 0.0f, (float)width, (float)height, 0.0f, 1.0f};
    VkRect2D scissor = {{0, 0}, {width, height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void rtpbr_draw_mesh(VkCommandBuffer cmd, VkPipelineLayout layout, const rtpbr_gpu_scene *scene, const rtpbr_draw *d)
{
    const rtpbr_shader_material *materials = scene->materials.mapped;
    bool single_sided = !(materials[d->push.material].flags & RTPBR_MATERIAL_FLAG_DOUBLE_SIDED);
    vkCmdSetCullMode(cmd, single_sided ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE);
    vkCmdSetFrontFace(cmd, rtpbr_mat4_mirrors(d->push.world_from_object) ? VK_FRONT_FACE_CLOCKWISE
                                                                          : VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &scene->material_sets[d->push.material],
                            0, NULL);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof d->push,
                       &d->push);
    vkCmdDrawIndexed(cmd, d->index_count, 1, d->first_index, 0, 0);
}
