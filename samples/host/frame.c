// rtpbr-sample-host's Vulkan side: its images and passes on its device (sample_vk.h), one frame.
// The frame, in one command buffer of the host's:
//   1. its geometry pass (geometry.vert / .frag): the G-buffer contract g0 .. g3 and D32 depth
//   2. rtpbr_lighting_record: rtpbr's culling and lighting of that G-buffer into the HDR image
//   3. its tone mapping (tonemap.comp): Reinhard on luminance, sRGB encode, into an RGBA8 image
//   4. copies of the HDR and display images into host-visible buffers (headless, sh_render_frame),
//      or of the display image into the window's swapchain image (windowed.c)
#include "host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host_geometry_frag.spv.h"
#include "host_geometry_vert.spv.h"
#include "host_tonemap_comp.spv.h"

const size_t sh_geometry_vert_size = sizeof host_geometry_vert, sh_geometry_frag_size = sizeof host_geometry_frag;

static const VkFormat gbuffer_formats[4] = { // gbuffer.h's RTPBR_GBUFFER_FORMAT_G0 .. G3
    VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT,
    VK_FORMAT_R16G16B16A16_SFLOAT};

// geometry.frag's HostMaterial (std430): the host's own material table.
typedef struct host_material { float base_metallic[4], emission_roughness[4]; } host_material;
// geometry.vert / .frag's push constants.
typedef struct geometry_push { float view_proj[16], camera[4]; uint32_t material; } geometry_push;
enum { GEOMETRY_PUSH_SIZE = 84 };
// tonemap.comp's push constants.
typedef struct tonemap_push { float scale; uint32_t width, height, swap_rb; } tonemap_push;

// ---------------------------------------------------------------------------------------------
// Images and buffers

static int memory_type(const sample_device *d, uint32_t bits, VkMemoryPropertyFlags flags, uint32_t *out)
{
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(d->vk.physical_device, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return *out = i, 0;
    return 1;
}

static int image_create(sample_device *d, VkFormat format, uint32_t w, uint32_t h, VkImageUsageFlags usage, sh_image *img,
                        char *error, size_t error_size)
{
    VkImageCreateInfo info = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D, .format = format,
        .extent = {w, h, 1}, .mipLevels = 1, .arrayLayers = 1, .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = usage, .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
    SAMPLE_VK(vkCreateImage(d->vk.device, &info, NULL, &img->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(d->vk.device, img->image, &req);
    uint32_t type;
    if (memory_type(d, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &type) &&
        memory_type(d, req.memoryTypeBits, 0, &type))
        return sample_vk_fail(error, error_size, "no memory type for an image");
    SAMPLE_VK(vkAllocateMemory(d->vk.device, &(VkMemoryAllocateInfo){.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size, .memoryTypeIndex = type}, NULL, &img->memory));
    SAMPLE_VK(vkBindImageMemory(d->vk.device, img->image, img->memory, 0));
    VkImageAspectFlags aspect = format == VK_FORMAT_D32_SFLOAT ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    SAMPLE_VK(vkCreateImageView(d->vk.device, &(VkImageViewCreateInfo){.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = img->image, .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
        .subresourceRange = {aspect, 0, 1, 0, 1}}, NULL, &img->view));
    return 0;
}

static void image_destroy(sample_device *d, sh_image *img)
{
    if (img->view) vkDestroyImageView(d->vk.device, img->view, NULL);
    if (img->image) vkDestroyImage(d->vk.device, img->image, NULL);
    if (img->memory) vkFreeMemory(d->vk.device, img->memory, NULL);
    memset(img, 0, sizeof *img);
}

// A host-visible, coherent, persistently mapped buffer, filled from data if given.
static int buffer_create(sample_device *d, VkDeviceSize size, VkBufferUsageFlags usage, const void *data, sh_buffer *b,
                         char *error, size_t error_size)
{
    SAMPLE_VK(vkCreateBuffer(d->vk.device, &(VkBufferCreateInfo){.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size,
        .usage = usage}, NULL, &b->buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(d->vk.device, b->buffer, &req);
    uint32_t type;
    if (memory_type(d, req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, &type))
        return sample_vk_fail(error, error_size, "no host-visible coherent memory");
    SAMPLE_VK(vkAllocateMemory(d->vk.device, &(VkMemoryAllocateInfo){.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size, .memoryTypeIndex = type}, NULL, &b->memory));
    SAMPLE_VK(vkBindBufferMemory(d->vk.device, b->buffer, b->memory, 0));
    SAMPLE_VK(vkMapMemory(d->vk.device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped));
    if (data) memcpy(b->mapped, data, (size_t)size);
    return 0;
}

static void buffer_destroy(sample_device *d, sh_buffer *b)
{
    if (b->buffer) vkDestroyBuffer(d->vk.device, b->buffer, NULL);
    if (b->memory) vkFreeMemory(d->vk.device, b->memory, NULL); // unmaps
    memset(b, 0, sizeof *b);
}

static VkShaderModule shader(sample_device *d, const uint32_t *code, size_t size)
{
    VkShaderModule m = VK_NULL_HANDLE;
    vkCreateShaderModule(d->vk.device, &(VkShaderModuleCreateInfo){.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = size, .pCode = code}, NULL, &m);
    return m;
}

// ---------------------------------------------------------------------------------------------
// Pipelines

static int descriptors_create(sh_renderer *r, char *error, size_t error_size)
{
    VkDevice dev = r->device->vk.device;
    VkDescriptorSetLayoutBinding material = {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, NULL};
    SAMPLE_VK(vkCreateDescriptorSetLayout(dev, &(VkDescriptorSetLayoutCreateInfo){
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, .bindingCount = 1, .pBindings = &material},
        NULL, &r->geometry_set_layout));
    VkDescriptorSetLayoutBinding images[2] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL},
                                              {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL}};
    SAMPLE_VK(vkCreateDescriptorSetLayout(dev, &(VkDescriptorSetLayoutCreateInfo){
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, .bindingCount = 2, .pBindings = images},
        NULL, &r->tonemap_set_layout));
    VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}};
    SAMPLE_VK(vkCreateDescriptorPool(dev, &(VkDescriptorPoolCreateInfo){.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 2, .poolSizeCount = 2, .pPoolSizes = sizes}, NULL, &r->pool));
    VkDescriptorSetLayout layouts[2] = {r->geometry_set_layout, r->tonemap_set_layout};
    VkDescriptorSet sets[2];
    SAMPLE_VK(vkAllocateDescriptorSets(dev, &(VkDescriptorSetAllocateInfo){.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = r->pool, .descriptorSetCount = 2, .pSetLayouts = layouts}, sets));
    r->geometry_set = sets[0], r->tonemap_set = sets[1];
    VkDescriptorBufferInfo buffer = {r->materials.buffer, 0, VK_WHOLE_SIZE};
    VkDescriptorImageInfo hdr = {VK_NULL_HANDLE, r->hdr.view, VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorImageInfo ldr = {VK_NULL_HANDLE, r->ldr.view, VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet writes[3] = {
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = r->geometry_set, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &buffer},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = r->tonemap_set, .dstBinding = 0, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .pImageInfo = &hdr},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = r->tonemap_set, .dstBinding = 1, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .pImageInfo = &ldr}};
    vkUpdateDescriptorSets(dev, 3, writes, 0, NULL);
    return 0;
}

static int geometry_pipeline_create(sh_renderer *r, char *error, size_t error_size)
{
    VkDevice dev = r->device->vk.device;
    VkPushConstantRange push = {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, GEOMETRY_PUSH_SIZE};
    SAMPLE_VK(vkCreatePipelineLayout(dev, &(VkPipelineLayoutCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1, .pSetLayouts = &r->geometry_set_layout, .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push}, NULL, &r->geometry_layout));
    VkShaderModule vert = shader(r->device, host_geometry_vert, sizeof host_geometry_vert);
    VkShaderModule frag = shader(r->device, host_geometry_frag, sizeof host_geometry_frag);
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT, .module = vert, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT, .module = frag, .pName = "main"}};
    VkVertexInputBindingDescription binding = {0, sizeof(sh_vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attributes[2] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                                                       {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 3 * sizeof(float)}};
    VkPipelineVertexInputStateCreateInfo input = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        .vertexBindingDescriptionCount = 1, .pVertexBindingDescriptions = &binding,
        .vertexAttributeDescriptionCount = 2, .pVertexAttributeDescriptions = attributes};
    VkPipelineInputAssemblyStateCreateInfo assembly = {.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
        .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
    VkPipelineViewportStateCreateInfo viewport = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
        .viewportCount = 1, .scissorCount = 1};
    VkPipelineRasterizationStateCreateInfo raster = {.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .polygonMode = VK_POLYGON_MODE_FILL, .cullMode = VK_CULL_MODE_NONE, .lineWidth = 1.0f}; // both sides seen
    VkPipelineMultisampleStateCreateInfo multisample = {.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT};
    VkPipelineDepthStencilStateCreateInfo depth = {.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
        .depthTestEnable = VK_TRUE, .depthWriteEnable = VK_TRUE, .depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL};
    VkPipelineColorBlendAttachmentState blend[4];
    for (int i = 0; i < 4; ++i) blend[i] = (VkPipelineColorBlendAttachmentState){.colorWriteMask = 0xf};
    VkPipelineColorBlendStateCreateInfo colour = {.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        .attachmentCount = 4, .pAttachments = blend};
    // The depth test's direction is set per frame (Vulkan 1.3 core): reversed-Z or not.
    VkDynamicState dynamic_states[3] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                        VK_DYNAMIC_STATE_DEPTH_COMPARE_OP};
    VkPipelineDynamicStateCreateInfo dynamic = {.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
        .dynamicStateCount = 3, .pDynamicStates = dynamic_states};
    VkPipelineRenderingCreateInfo rendering = {.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
        .colorAttachmentCount = 4, .pColorAttachmentFormats = gbuffer_formats, .depthAttachmentFormat = VK_FORMAT_D32_SFLOAT};
    VkResult vr = vert && frag ? vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &(VkGraphicsPipelineCreateInfo){
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, .pNext = &rendering, .stageCount = 2, .pStages = stages,
        .pVertexInputState = &input, .pInputAssemblyState = &assembly, .pViewportState = &viewport,
        .pRasterizationState = &raster, .pMultisampleState = &multisample, .pDepthStencilState = &depth,
        .pColorBlendState = &colour, .pDynamicState = &dynamic, .layout = r->geometry_layout}, NULL, &r->geometry_pipeline)
        : VK_ERROR_INITIALIZATION_FAILED;
    if (vert) vkDestroyShaderModule(dev, vert, NULL);
    if (frag) vkDestroyShaderModule(dev, frag, NULL);
    if (vr != VK_SUCCESS) return sample_vk_fail(error, error_size, "geometry pipeline: VkResult %d", (int)vr);
    return 0;
}

static int tonemap_pipeline_create(sh_renderer *r, char *error, size_t error_size)
{
    VkDevice dev = r->device->vk.device;
    VkPushConstantRange push = {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(tonemap_push)};
    SAMPLE_VK(vkCreatePipelineLayout(dev, &(VkPipelineLayoutCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1, .pSetLayouts = &r->tonemap_set_layout, .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push}, NULL, &r->tonemap_layout));
    VkShaderModule comp = shader(r->device, host_tonemap_comp, sizeof host_tonemap_comp);
    VkResult vr = comp ? vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &(VkComputePipelineCreateInfo){
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = comp, .pName = "main"},
        .layout = r->tonemap_layout}, NULL, &r->tonemap_pipeline) : VK_ERROR_INITIALIZATION_FAILED;
    if (comp) vkDestroyShaderModule(dev, comp, NULL);
    if (vr != VK_SUCCESS) return sample_vk_fail(error, error_size, "tone-mapping pipeline: VkResult %d", (int)vr);
    return 0;
}

// ---------------------------------------------------------------------------------------------
// Renderer

static int renderer_make(sh_renderer *r, const sh_scene *s, char *error, size_t error_size)
{
    sample_device *d = r->device;
    uint32_t w = s->width, h = s->height;
    for (int i = 0; i < 4; ++i)
        if (image_create(d, gbuffer_formats[i], w, h, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                         &r->gbuffer[i], error, error_size))
            return 1;
    if (image_create(d, VK_FORMAT_D32_SFLOAT, w, h, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                     &r->depth, error, error_size) ||
        image_create(d, VK_FORMAT_R32G32B32A32_SFLOAT, w, h, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                     &r->hdr, error, error_size) ||
        image_create(d, VK_FORMAT_R8G8B8A8_UNORM, w, h, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                     &r->ldr, error, error_size))
        return 1;
    host_material table[SH_MAX_MATERIALS];
    memset(table, 0, sizeof table);
    for (uint32_t m = 0; m < s->material_count; ++m) {
        const sh_material *src = &s->materials[m];
        memcpy(table[m].base_metallic, src->base_color, 3 * sizeof(float));
        table[m].base_metallic[3] = src->metallic;
        memcpy(table[m].emission_roughness, src->emission, 3 * sizeof(float));
        table[m].emission_roughness[3] = src->roughness;
    }
    if (buffer_create(d, (VkDeviceSize)s->vertex_count * sizeof(sh_vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, s->vertices,
                      &r->vertices, error, error_size) ||
        buffer_create(d, sizeof table, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, table, &r->materials, error, error_size) ||
        buffer_create(d, (VkDeviceSize)w * h * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, NULL, &r->hdr_readback, error, error_size) ||
        buffer_create(d, (VkDeviceSize)w * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, NULL, &r->ldr_readback, error, error_size))
        return 1;
    if (descriptors_create(r, error, error_size) || geometry_pipeline_create(r, error, error_size) ||
        tonemap_pipeline_create(r, error, error_size))
        return 1;
    SAMPLE_VK(vkCreateCommandPool(d->vk.device, &(VkCommandPoolCreateInfo){.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, .queueFamilyIndex = d->vk.queue_family_index}, NULL, &r->command_pool));
    SAMPLE_VK(vkCreateFence(d->vk.device, &(VkFenceCreateInfo){.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO}, NULL, &r->fence));

    // rtpbr's side, made once: a light set of the host's capacity (one frame in flight: this
    // host waits for each frame) and the targets: the host's images and material records.
    rtpbr_result rr = rtpbr_light_set_create(r->rtpbr, &(rtpbr_light_set_desc){.capacity = SH_MAX_LIGHTS,
                                                                              .frames_in_flight = 1}, &r->lights);
    if (rr != RTPBR_SUCCESS) return sample_vk_fail(error, error_size, "rtpbr_light_set_create: %s", rtpbr_result_string(rr));
    rtpbr_material_desc records[SH_MAX_MATERIALS];
    for (uint32_t m = 0; m < s->material_count; ++m) records[m] = sh_material_record(&s->materials[m]);
    rtpbr_lighting_targets_desc td = {.width = w, .height = h, .frames_in_flight = 1,
        .depth = {r->depth.image, r->depth.view, VK_FORMAT_D32_SFLOAT},
        .output = {r->hdr.image, r->hdr.view, VK_FORMAT_R32G32B32A32_SFLOAT},
        .materials = records, .material_count = s->material_count};
    for (int i = 0; i < 4; ++i) td.gbuffer[i] = (rtpbr_host_image){r->gbuffer[i].image, r->gbuffer[i].view, gbuffer_formats[i]};
    rr = rtpbr_lighting_targets_create(r->rtpbr, &td, &r->targets);
    if (rr != RTPBR_SUCCESS) return sample_vk_fail(error, error_size, "rtpbr_lighting_targets_create: %s", rtpbr_result_string(rr));
    return 0;
}

int sh_renderer_create(sh_renderer *r, sample_device *device, rtpbr_context *rtpbr, const sh_scene *s, char *error,
                       size_t error_size)
{
    memset(r, 0, sizeof *r);
    r->device = device, r->rtpbr = rtpbr, r->width = s->width, r->height = s->height;
    if (renderer_make(r, s, error, error_size)) {
        sh_renderer_destroy(r);
        return 1;
    }
    return 0;
}

void sh_renderer_destroy(sh_renderer *r)
{
    sample_device *d = r->device;
    if (!d) return;
    rtpbr_lighting_targets_destroy(r->targets); // rtpbr's objects first, then the host's images
    rtpbr_light_set_destroy(r->lights);
    VkDevice dev = d->vk.device;
    if (r->fence) vkDestroyFence(dev, r->fence, NULL);
    if (r->command_pool) vkDestroyCommandPool(dev, r->command_pool, NULL);
    if (r->geometry_pipeline) vkDestroyPipeline(dev, r->geometry_pipeline, NULL);
    if (r->tonemap_pipeline) vkDestroyPipeline(dev, r->tonemap_pipeline, NULL);
    if (r->geometry_layout) vkDestroyPipelineLayout(dev, r->geometry_layout, NULL);
    if (r->tonemap_layout) vkDestroyPipelineLayout(dev, r->tonemap_layout, NULL);
    if (r->pool) vkDestroyDescriptorPool(dev, r->pool, NULL);
    if (r->geometry_set_layout) vkDestroyDescriptorSetLayout(dev, r->geometry_set_layout, NULL);
    if (r->tonemap_set_layout) vkDestroyDescriptorSetLayout(dev, r->tonemap_set_layout, NULL);
    for (int i = 0; i < 4; ++i) image_destroy(d, &r->gbuffer[i]);
    image_destroy(d, &r->depth);
    image_destroy(d, &r->hdr);
    image_destroy(d, &r->ldr);
    buffer_destroy(d, &r->vertices);
    buffer_destroy(d, &r->materials);
    buffer_destroy(d, &r->hdr_readback);
    buffer_destroy(d, &r->ldr_readback);
    memset(r, 0, sizeof *r);
}

static void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                          VkPipelineStageFlags src_stage, VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                          VkAccessFlags dst_access)
{
    VkImageMemoryBarrier b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, .srcAccessMask = src_access,
        .dstAccessMask = dst_access, .oldLayout = from, .newLayout = to, .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image, .subresourceRange = {aspect, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, NULL, 0, NULL, 1, &b);
}

void sh_begin_gbuffer_pass(VkCommandBuffer cmd, const VkImage images[5], const VkImageView views[5], uint32_t width,
                           uint32_t height, float clear_depth)
{
    for (int i = 0; i < 5; ++i) // after rtpbr's compute reads of the previous frame; contents discarded
        image_barrier(cmd, images[i], i < 4 ? VK_IMAGE_ASPECT_COLOR_BIT : VK_IMAGE_ASPECT_DEPTH_BIT,
                      VK_IMAGE_LAYOUT_UNDEFINED,
                      i < 4 ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                      i < 4 ? VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT
                            : VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                      i < 4 ? VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT
                            : VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo attachments[5];
    for (int i = 0; i < 5; ++i)
        attachments[i] = (VkRenderingAttachmentInfo){.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
            .imageView = views[i],
            .imageLayout = i < 4 ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
            .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR, .storeOp = VK_ATTACHMENT_STORE_OP_STORE};
    attachments[4].clearValue.depthStencil = (VkClearDepthStencilValue){clear_depth, 0}; // the background (rtpbr.h)
    vkCmdBeginRendering(cmd, &(VkRenderingInfo){.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, {width, height}}, .layerCount = 1, .colorAttachmentCount = 4,
        .pColorAttachments = attachments, .pDepthAttachment = &attachments[4]});
}

// The host's geometry pass: every material's triangles into g0 .. g3 and depth.
static void record_geometry(sh_renderer *r, VkCommandBuffer cmd, const sh_scene *s, const float view_proj[16])
{
    VkImage images[5] = {r->gbuffer[0].image, r->gbuffer[1].image, r->gbuffer[2].image, r->gbuffer[3].image, r->depth.image};
    VkImageView views[5] = {r->gbuffer[0].view, r->gbuffer[1].view, r->gbuffer[2].view, r->gbuffer[3].view, r->depth.view};
    const int reversed = r->camera_mode == SH_CAMERA_REVERSED_Z;
    sh_begin_gbuffer_pass(cmd, images, views, r->width, r->height, reversed ? 0.0f : 1.0f);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r->geometry_pipeline);
    vkCmdSetDepthCompareOp(cmd, reversed ? VK_COMPARE_OP_GREATER_OR_EQUAL : VK_COMPARE_OP_LESS_OR_EQUAL);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r->geometry_layout, 0, 1, &r->geometry_set, 0, NULL);
    vkCmdSetViewport(cmd, 0, 1, &(VkViewport){0.0f, 0.0f, (float)r->width, (float)r->height, 0.0f, 1.0f});
    vkCmdSetScissor(cmd, 0, 1, &(VkRect2D){{0, 0}, {r->width, r->height}});
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &r->vertices.buffer, &offset);
    geometry_push push;
    memcpy(push.view_proj, view_proj, sizeof push.view_proj);
    memcpy(push.camera, s->camera.position, 3 * sizeof(float));
    push.camera[3] = 1.0f;
    for (uint32_t m = 0; m < s->material_count; ++m) { // one draw per material (the material index in g2.a)
        if (!s->draws[m].vertex_count) continue;
        push.material = m;
        vkCmdPushConstants(cmd, r->geometry_layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           GEOMETRY_PUSH_SIZE, &push);
        vkCmdDraw(cmd, s->draws[m].vertex_count, 1, s->draws[m].first_vertex, 0);
    }
    vkCmdEndRendering(cmd);
}

// The host's tone mapping (tonemap.comp) of rtpbr's output (GENERAL, its writes visible to
// every stage after rtpbr's exit barrier: no barrier before the dispatch). Both images are left
// in TRANSFER_SRC_OPTIMAL for the copies that follow. The HDR image's next user is rtpbr's next
// recording, which takes it from any layout (output_old_layout; UNDEFINED here: every pixel is
// rewritten).
static void record_tonemap(sh_renderer *r, VkCommandBuffer cmd, float exposure, int bgra)
{
    image_barrier(cmd, r->ldr.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->tonemap_pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->tonemap_layout, 0, 1, &r->tonemap_set, 0, NULL);
    tonemap_push push = {exp2f(exposure), r->width, r->height, bgra ? 1u : 0u};
    vkCmdPushConstants(cmd, r->tonemap_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, (r->width + 7) / 8, (r->height + 7) / 8, 1);
    image_barrier(cmd, r->ldr.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT);
    image_barrier(cmd, r->hdr.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
}

// Both images copied out for the CPU (after record_tonemap).
static void record_readback(sh_renderer *r, VkCommandBuffer cmd)
{
    VkBufferImageCopy copy = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {r->width, r->height, 1}};
    vkCmdCopyImageToBuffer(cmd, r->hdr.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r->hdr_readback.buffer, 1, &copy);
    vkCmdCopyImageToBuffer(cmd, r->ldr.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r->ldr_readback.buffer, 1, &copy);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
        &(VkMemoryBarrier){VK_STRUCTURE_TYPE_MEMORY_BARRIER, NULL, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT},
        0, NULL, 0, NULL);
}

int sh_record_frame(sh_renderer *r, VkCommandBuffer cmd, const sh_scene *s, float exposure, int bgra, char *error,
                    size_t error_size)
{
    // The lights of this frame: written into the light set's mapped memory, nothing else.
    rtpbr_light_desc lights[SH_MAX_LIGHTS];
    for (uint32_t i = 0; i < s->light_count; ++i) lights[i] = sh_light_record(&s->lights[i]);
    rtpbr_result rr = rtpbr_light_set_update(r->lights, 0, lights, s->light_count);
    if (rr != RTPBR_SUCCESS) return sample_vk_fail(error, error_size, "rtpbr_light_set_update: %s", rtpbr_result_string(rr));

    float view[16], projection[16], view_proj[16];
    sh_camera_matrices(&s->camera, (float)r->width / (float)r->height, r->camera_mode == SH_CAMERA_REVERSED_Z, view,
                       projection, view_proj);
    record_geometry(r, cmd, s, view_proj);
    // rtpbr's lighting of the host's G-buffer. By default the camera as rtpbr's camera
    // description: its matrices are the host's (sh_camera_matrices follows rtpbr_camera_desc's
    // convention), and the result is rtpbr_render's bit for bit. Handing the host's `view` and
    // `projection` instead (.camera = NULL) works too, but reconstructs positions through the
    // inverse of another float product, and the bundled room then differs from rtpbr_render by
    // 5e-6 relative on average but up to 0.35 at a few dark pixels (measured on lavapipe). A
    // reversed-Z host must hand its matrices.
    rtpbr_lighting_record_desc rec = {.command_buffer = cmd, .frame = 0, .lights = r->lights,
        .gbuffer_old_layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        .depth_old_layout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
        .output_old_layout = VK_IMAGE_LAYOUT_UNDEFINED, .output_new_layout = VK_IMAGE_LAYOUT_GENERAL};
    rtpbr_camera_desc cam = {.yfov = s->camera.yfov, .znear = SH_ZNEAR, .zfar = SH_ZFAR};
    memcpy(cam.position, s->camera.position, sizeof cam.position);
    memcpy(cam.target, s->camera.target, sizeof cam.target);
    if (r->camera_mode == SH_CAMERA_RTPBR) {
        rec.camera = &cam;
    } else {
        memcpy(rec.view, view, sizeof rec.view);
        memcpy(rec.projection, projection, sizeof rec.projection);
        rec.reversed_z = r->camera_mode == SH_CAMERA_REVERSED_Z;
    }
    memcpy(rec.background, s->background, sizeof rec.background);
    rr = rtpbr_lighting_record(r->targets, &rec);
    if (rr != RTPBR_SUCCESS) return sample_vk_fail(error, error_size, "rtpbr_lighting_record: %s", rtpbr_result_string(rr));
    record_tonemap(r, cmd, exposure, bgra);
    return 0;
}

int sh_render_frame(sh_renderer *r, const sh_scene *s, float exposure, float *hdr, uint8_t *ldr, char *error,
                    size_t error_size)
{
    VkDevice dev = r->device->vk.device;
    VkCommandBuffer cmd;
    SAMPLE_VK(vkAllocateCommandBuffers(dev, &(VkCommandBufferAllocateInfo){.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = r->command_pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1}, &cmd));
    VkResult vr = vkBeginCommandBuffer(cmd, &(VkCommandBufferBeginInfo){.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT});
    int failed = 0;
    if (vr == VK_SUCCESS) {
        failed = sh_record_frame(r, cmd, s, exposure, 0, error, error_size);
        if (!failed) record_readback(r, cmd);
        vr = vkEndCommandBuffer(cmd);
    }
    if (vr == VK_SUCCESS && !failed) {
        vr = vkResetFences(dev, 1, &r->fence);
        if (vr == VK_SUCCESS)
            vr = vkQueueSubmit(r->device->vk.queue, 1, &(VkSubmitInfo){.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
                .commandBufferCount = 1, .pCommandBuffers = &cmd}, r->fence);
        if (vr == VK_SUCCESS) vr = vkWaitForFences(dev, 1, &r->fence, VK_TRUE, UINT64_MAX);
    }
    vkFreeCommandBuffers(dev, r->command_pool, 1, &cmd);
    if (failed) return 1;
    if (vr != VK_SUCCESS) return sample_vk_fail(error, error_size, "frame submission failed (VkResult %d)", (int)vr);
    if (hdr) memcpy(hdr, r->hdr_readback.mapped, (size_t)r->width * r->height * 16);
    if (ldr) memcpy(ldr, r->ldr_readback.mapped, (size_t)r->width * r->height * 4);
    return 0;
}
