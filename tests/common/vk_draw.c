/* The tests' drawing helpers (vk_draw.h). */
#include "vk_draw.h"

#include <stdbool.h>
#include <string.h>

VkResult vk_draw_memory(const vk_host *h, VkMemoryRequirements req, VkMemoryPropertyFlags want, VkDeviceMemory *out)
{
    VkPhysicalDeviceMemoryProperties p;
    vkGetPhysicalDeviceMemoryProperties(h->physical_device, &p);
    uint32_t type = 0;
    while (type < p.memoryTypeCount &&
           (!(req.memoryTypeBits & (1u << type)) || (p.memoryTypes[type].propertyFlags & want) != want)) ++type;
    if (type == p.memoryTypeCount) return VK_ERROR_FEATURE_NOT_PRESENT;
    VkMemoryAllocateInfo info = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, NULL, req.size, type};
    return vkAllocateMemory(h->device, &info, NULL, out);
}

VkResult vk_draw_buffer_create(const vk_host *h, VkDeviceSize size, VkBufferUsageFlags usage, const void *data,
                               vk_draw_buffer *out)
{
    memset(out, 0, sizeof *out);
    VkBufferCreateInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage};
    VkResult r = vkCreateBuffer(h->device, &info, NULL, &out->buffer);
    if (r) return r;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(h->device, out->buffer, &req);
    r = vk_draw_memory(h, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, &out->memory);
    if (!r) r = vkBindBufferMemory(h->device, out->buffer, out->memory, 0);
    if (!r) r = vkMapMemory(h->device, out->memory, 0, size, 0, &out->mapped);
    if (!r && data) memcpy(out->mapped, data, size);
    return r;
}

void vk_draw_buffer_destroy(const vk_host *h, vk_draw_buffer *b)
{
    vkDestroyBuffer(h->device, b->buffer, NULL);
    vkFreeMemory(h->device, b->memory, NULL); /* unmaps */
    memset(b, 0, sizeof *b);
}

VkResult vk_draw_image_create(const vk_host *h, VkFormat format, uint32_t width, uint32_t height, uint32_t depth,
                              VkImageUsageFlags usage, vk_draw_image *out)
{
    memset(out, 0, sizeof *out);
    VkImageCreateInfo info = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D, .format = format,
        .extent = {width, height, depth}, .mipLevels = 1, .arrayLayers = 1, .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = usage, .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
    VkResult r = vkCreateImage(h->device, &info, NULL, &out->image);
    if (r) return r;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(h->device, out->image, &req);
    r = vk_draw_memory(h, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &out->memory);
    if (!r) r = vkBindImageMemory(h->device, out->image, out->memory, 0);
    if (r) return r;
    bool is_depth = format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM ||
                    format == VK_FORMAT_X8_D24_UNORM_PACK32;
    VkImageViewCreateInfo view = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = out->image,
        .viewType = depth > 1 ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D, .format = format,
        .subresourceRange = {is_depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    return vkCreateImageView(h->device, &view, NULL, &out->view);
}

void vk_draw_image_destroy(const vk_host *h, vk_draw_image *image)
{
    vkDestroyImageView(h->device, image->view, NULL);
    vkDestroyImage(h->device, image->image, NULL);
    vkFreeMemory(h->device, image->memory, NULL);
    memset(image, 0, sizeof *image);
}

VkResult vk_draw_begin(const vk_host *h, VkCommandPool pool, VkCommandBuffer *out)
{
    VkCommandBufferAllocateInfo info = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    VkResult r = vkAllocateCommandBuffers(h->device, &info, out);
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    return r ? r : vkBeginCommandBuffer(*out, &begin);
}

void vk_draw_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                     VkImageLayout to, VkPipelineStageFlags src_stage, VkAccessFlags src,
                     VkPipelineStageFlags dst_stage, VkAccessFlags dst)
{
    VkImageMemoryBarrier b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, .srcAccessMask = src,
        .dstAccessMask = dst, .oldLayout = from, .newLayout = to, .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image, .subresourceRange = {aspect, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, NULL, 0, NULL, 1, &b);
}

static VkResult module(const vk_host *h, const uint32_t *code, size_t size, VkShaderModule *out)
{
    VkShaderModuleCreateInfo info = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = size,
                                     .pCode = code};
    return vkCreateShaderModule(h->device, &info, NULL, out);
}

VkResult vk_draw_pipeline_create(const vk_host *h, const vk_draw_pipeline_desc *d, VkPipeline *out)
{
    *out = VK_NULL_HANDLE;
    if (d->attribute_count > 4 || d->color_count > 8) return VK_ERROR_INITIALIZATION_FAILED;
    VkShaderModule vs = VK_NULL_HANDLE, fs = VK_NULL_HANDLE;
    VkResult r = module(h, d->vert, d->vert_size, &vs);
    if (!r) r = module(h, d->frag, d->frag_size, &fs);
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = vs, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = fs, .pName = "main"}};
    VkVertexInputBindingDescription binding = {0, d->attribute_count * 3 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attributes[4];
    for (uint32_t i = 0; i < d->attribute_count; ++i)
        attributes[i] = (VkVertexInputAttributeDescription){i, 0, VK_FORMAT_R32G32B32_SFLOAT, i * 3 * sizeof(float)};
    VkPipelineColorBlendAttachmentState blend[8];
    for (uint32_t i = 0; i < d->color_count; ++i) blend[i] = (VkPipelineColorBlendAttachmentState){.colorWriteMask = 0xf};
    VkDynamicState dynamic[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    bool depth = d->depth_format != VK_FORMAT_UNDEFINED;
    VkGraphicsPipelineCreateInfo info = {.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .pNext = &(VkPipelineRenderingCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
            .colorAttachmentCount = d->color_count, .pColorAttachmentFormats = d->color_formats,
            .depthAttachmentFormat = d->depth_format},
        .stageCount = 2, .pStages = stages,
        .pVertexInputState = &(VkPipelineVertexInputStateCreateInfo){
            .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO, .vertexBindingDescriptionCount = 1,
            .pVertexBindingDescriptions = &binding, .vertexAttributeDescriptionCount = d->attribute_count,
            .pVertexAttributeDescriptions = attributes},
        .pInputAssemblyState = &(VkPipelineInputAssemblyStateCreateInfo){
            .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
            .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST},
        .pViewportState = &(VkPipelineViewportStateCreateInfo){
            .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO, .viewportCount = 1, .scissorCount = 1},
        .pRasterizationState = &(VkPipelineRasterizationStateCreateInfo){
            .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO, .lineWidth = 1.0f},
        .pMultisampleState = &(VkPipelineMultisampleStateCreateInfo){
            .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
            .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT},
        .pDepthStencilState = &(VkPipelineDepthStencilStateCreateInfo){
            .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO, .depthTestEnable = depth,
            .depthWriteEnable = depth, .depthCompareOp = d->depth_compare},
        .pColorBlendState = &(VkPipelineColorBlendStateCreateInfo){
            .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO, .attachmentCount = d->color_count,
            .pAttachments = blend},
        .pDynamicState = &(VkPipelineDynamicStateCreateInfo){
            .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO, .dynamicStateCount = 2,
            .pDynamicStates = dynamic},
        .layout = d->layout};
    if (!r) r = vkCreateGraphicsPipelines(h->device, VK_NULL_HANDLE, 1, &info, NULL, out);
    vkDestroyShaderModule(h->device, vs, NULL);
    vkDestroyShaderModule(h->device, fs, NULL);
    return r;
}

void vk_draw_pass_destroy(const vk_host *h, vk_draw_pass *pass)
{
    vkDestroyPipeline(h->device, pass->pipeline, NULL);
    vkDestroyPipelineLayout(h->device, pass->layout, NULL);
    vkDestroyDescriptorPool(h->device, pass->pool, NULL); /* frees the set */
    vkDestroyDescriptorSetLayout(h->device, pass->set_layout, NULL);
    memset(pass, 0, sizeof *pass);
}
