// Buffers, images, one-shot submissions and lookup-table textures.
#include <string.h>

#include "internal.h"
#include "light_texture.h"

static uint32_t find_memory_type(const rtpbr_context *ctx, uint32_t type_bits, VkMemoryPropertyFlags want)
{
    const VkPhysicalDeviceMemoryProperties *mp = &ctx->memory_properties;
    for (uint32_t i = 0; i < mp->memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (mp->memoryTypes[i].propertyFlags & want) == want) return i;
    return UINT32_MAX;
}

static rtpbr_result allocate_flags(rtpbr_context *ctx, VkMemoryRequirements req, VkMemoryPropertyFlags want,
                                   VkMemoryPropertyFlags fallback, bool device_address, VkDeviceMemory *out)
{
    uint32_t type = find_memory_type(ctx, req.memoryTypeBits, want);
    if (type == UINT32_MAX) type = find_memory_type(ctx, req.memoryTypeBits, fallback);
    if (type == UINT32_MAX) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "no Vulkan memory type with properties 0x%x", (unsigned)fallback);
        return RTPBR_ERROR_OUT_OF_DEVICE_MEMORY;
    }
    // Memory a buffer's device address (vkGetBufferDeviceAddress) may point into.
    VkMemoryAllocateFlagsInfo flags = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
        .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT,
    };
    VkMemoryAllocateInfo info = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .pNext = device_address ? &flags : NULL,
        .allocationSize = req.size,
        .memoryTypeIndex = type,
    };
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_VK(&ctx->host, vkAllocateMemory(ctx->device, &info, NULL, out));
cleanup:
    return result;
}

static rtpbr_result allocate(rtpbr_context *ctx, VkMemoryRequirements req, VkMemoryPropertyFlags want,
                             VkMemoryPropertyFlags fallback, VkDeviceMemory *out)
{
    return allocate_flags(ctx, req, want, fallback, false, out);
}

// A buffer in memory with the properties `want` (else `fallback`), mapped when host-visible;
// with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT in usage, its memory may be addressed.
static rtpbr_result buffer_create(rtpbr_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                                  VkMemoryPropertyFlags want, VkMemoryPropertyFlags fallback, bool map,
                                  rtpbr_buffer *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    memset(out, 0, sizeof *out);
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    RTPBR_VK(&ctx->host, vkCreateBuffer(ctx->device, &info, NULL, &out->buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx->device, out->buffer, &req);
    RTPBR_TRY(allocate_flags(ctx, req, want, fallback, (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0,
                             &out->memory));
    RTPBR_VK(&ctx->host, vkBindBufferMemory(ctx->device, out->buffer, out->memory, 0));
    if (map) RTPBR_VK(&ctx->host, vkMapMemory(ctx->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped));
    out->size = size;
    return RTPBR_SUCCESS;
cleanup:
    rtpbr_buffer_destroy(ctx, out);
    return result;
}

rtpbr_result rtpbr_buffer_create_host(rtpbr_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                                      rtpbr_buffer *out)
{
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    return buffer_create(ctx, size, usage, host | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, host, true, out);
}

rtpbr_result rtpbr_buffer_create_device(rtpbr_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                                        rtpbr_buffer *out)
{
    return buffer_create(ctx, size, usage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, false, out);
}

void rtpbr_buffer_destroy(rtpbr_context *ctx, rtpbr_buffer *buffer)
{
    if (buffer->buffer) vkDestroyBuffer(ctx->device, buffer->buffer, NULL);
    if (buffer->memory) vkFreeMemory(ctx->device, buffer->memory, NULL); // unmaps implicitly
    memset(buffer, 0, sizeof *buffer);
}

static VkImageAspectFlags aspect_of(VkFormat format)
{
    return format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM ? VK_IMAGE_ASPECT_DEPTH_BIT
                                                                          : VK_IMAGE_ASPECT_COLOR_BIT;
}

// A 2D image with a view: 3D when depth > 1, a 2D array of `layers` layers when layers > 0,
// `levels` mip levels (2D only).
static rtpbr_result image_create_levels(rtpbr_context *ctx, uint32_t width, uint32_t height, uint32_t depth,
                                        uint32_t layers, uint32_t levels, VkFormat format, VkImageUsageFlags usage,
                                        rtpbr_image *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    memset(out, 0, sizeof *out);
    VkImageCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D,
        .format = format,
        .extent = {width, height, depth},
        .mipLevels = levels,
        .arrayLayers = layers ? layers : 1,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL,
        .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
        .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    RTPBR_VK(&ctx->host, vkCreateImage(ctx->device, &info, NULL, &out->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx->device, out->image, &req);
    RTPBR_TRY(allocate(ctx, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, &out->memory));
    RTPBR_VK(&ctx->host, vkBindImageMemory(ctx->device, out->image, out->memory, 0));
    VkImageViewCreateInfo view_info = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = out->image,
        .viewType = depth > 1 ? VK_IMAGE_VIEW_TYPE_3D : layers ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D,
        .format = format,
        .subresourceRange = {aspect_of(format), 0, levels, 0, layers ? layers : 1},
    };
    RTPBR_VK(&ctx->host, vkCreateImageView(ctx->device, &view_info, NULL, &out->view));
    out->format = format;
    out->width = width;
    out->height = height;
    return RTPBR_SUCCESS;
cleanup:
    rtpbr_image_destroy(ctx, out);
    return result;
}

static rtpbr_result image_create(rtpbr_context *ctx, uint32_t width, uint32_t height, uint32_t depth, uint32_t layers,
                                 VkFormat format, VkImageUsageFlags usage, rtpbr_image *out)
{
    return image_create_levels(ctx, width, height, depth, layers, 1, format, usage, out);
}

rtpbr_result rtpbr_image_create(rtpbr_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                                VkImageUsageFlags usage, rtpbr_image *out)
{
    return image_create(ctx, width, height, 1, 0, format, usage, out);
}

rtpbr_result rtpbr_image_create_layers(rtpbr_context *ctx, uint32_t width, uint32_t height, uint32_t layers,
                                       VkFormat format, VkImageUsageFlags usage, rtpbr_image *out)
{
    return image_create(ctx, width, height, 1, layers, format, usage, out);
}

void rtpbr_image_destroy(rtpbr_context *ctx, rtpbr_image *image)
{
    if (image->view) vkDestroyImageView(ctx->device, image->view, NULL);
    if (image->image) vkDestroyImage(ctx->device, image->image, NULL);
    if (image->memory) vkFreeMemory(ctx->device, image->memory, NULL);
    memset(image, 0, sizeof *image);
}

void rtpbr_image_range_barrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range,
                               VkImageLayout old_layout, VkImageLayout new_layout,
                               VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                               VkPipelineStageFlags dst_stage, VkAccessFlags dst_access)
{
    VkImageMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
        .srcAccessMask = src_access,
        .dstAccessMask = dst_access,
        .oldLayout = old_layout,
        .newLayout = new_layout,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image,
        .subresourceRange = range,
    };
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, NULL, 0, NULL, 1, &barrier);
}

void rtpbr_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                         VkImageLayout old_layout, VkImageLayout new_layout,
                         VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                         VkPipelineStageFlags dst_stage, VkAccessFlags dst_access)
{
    rtpbr_image_range_barrier(cmd, image, (VkImageSubresourceRange){aspect, 0, 1, 0, 1}, old_layout, new_layout,
                              src_stage, src_access, dst_stage, dst_access);
}

rtpbr_result rtpbr_command_buffer_create(rtpbr_context *ctx, VkCommandBuffer *cmd, VkFence *fence)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkCommandBufferAllocateInfo cmd_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = ctx->command_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    RTPBR_VK(&ctx->host, vkAllocateCommandBuffers(ctx->device, &cmd_info, cmd));
    VkFenceCreateInfo fence_info = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    RTPBR_VK(&ctx->host, vkCreateFence(ctx->device, &fence_info, NULL, fence));
cleanup:
    return result; // the caller frees what was made
}

rtpbr_result rtpbr_submit_once(rtpbr_context *ctx, void (*record)(VkCommandBuffer cmd, void *user), void *user)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    RTPBR_VK(&ctx->host, vkResetCommandBuffer(ctx->upload_cmd, 0));
    RTPBR_VK(&ctx->host, vkBeginCommandBuffer(ctx->upload_cmd, &begin));
    record(ctx->upload_cmd, user);
    RTPBR_VK(&ctx->host, vkEndCommandBuffer(ctx->upload_cmd));
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &ctx->upload_cmd,
    };
    RTPBR_VK(&ctx->host, vkResetFences(ctx->device, 1, &ctx->upload_fence));
    RTPBR_VK(&ctx->host, vkQueueSubmit(ctx->queue, 1, &submit, ctx->upload_fence));
    RTPBR_VK(&ctx->host, vkWaitForFences(ctx->device, 1, &ctx->upload_fence, VK_TRUE, UINT64_MAX));
cleanup:
    return result;
}

// ---------------------------------------------------------------------------------------------
// Lookup tables

typedef struct lut_upload {
    VkBuffer staging;
    VkImage image;
    uint32_t width, height, depth;
} lut_upload;

static void record_lut_upload(VkCommandBuffer cmd, void *user)
{
    const lut_upload *u = user;
    rtpbr_image_barrier(cmd, u->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region = {
        .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .imageExtent = {u->width, u->height, u->depth},
    };
    vkCmdCopyBufferToImage(cmd, u->staging, u->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    rtpbr_image_barrier(cmd, u->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                        VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                        VK_ACCESS_SHADER_READ_BIT);
}

rtpbr_result rtpbr_image_create_with_data(rtpbr_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                                          const void *texels, size_t bytes, rtpbr_image *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_buffer staging = {0};
    memset(out, 0, sizeof *out);
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, &staging));
    memcpy(staging.mapped, texels, bytes);
    RTPBR_TRY(rtpbr_image_create(ctx, width, height, format, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                 out));
    lut_upload upload = {staging.buffer, out->image, width, height, 1};
    RTPBR_TRY(rtpbr_submit_once(ctx, record_lut_upload, &upload));
cleanup:
    if (result != RTPBR_SUCCESS) rtpbr_image_destroy(ctx, out); // accepts a zeroed or half-built image
    rtpbr_buffer_destroy(ctx, &staging);
    return result;
}

// ---------------------------------------------------------------------------------------------
// Material textures with mip chains

typedef struct mip_upload {
    VkBuffer staging;
    VkImage image;
    uint32_t width, height, levels;
} mip_upload;

static void mip_barrier(VkCommandBuffer cmd, VkImage image, uint32_t level, VkImageLayout old_layout,
                        VkImageLayout new_layout, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                        VkPipelineStageFlags dst_stage, VkAccessFlags dst_access)
{
    rtpbr_image_range_barrier(cmd, image, (VkImageSubresourceRange){VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, 1},
                              old_layout, new_layout, src_stage, src_access, dst_stage, dst_access);
}

// Level 0 from the staging buffer, then each level blitted (linear filter) from the one above
// it; every level ends in SHADER_READ_ONLY_OPTIMAL. Blits of sRGB formats filter linear values
// (the Vulkan spec: sRGB texels are converted to linear before filtering and back after).
static void record_mip_upload(VkCommandBuffer cmd, void *user)
{
    const mip_upload *u = user;
    const VkPipelineStageFlags shaders = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    for (uint32_t level = 0; level < u->levels; ++level)
        mip_barrier(cmd, u->image, level, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region = {
        .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .imageExtent = {u->width, u->height, 1},
    };
    vkCmdCopyBufferToImage(cmd, u->staging, u->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    int32_t w = (int32_t)u->width, h = (int32_t)u->height;
    for (uint32_t level = 1; level < u->levels; ++level) {
        mip_barrier(cmd, u->image, level - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        int32_t nw = w > 1 ? w / 2 : 1, nh = h > 1 ? h / 2 : 1;
        VkImageBlit blit = {
            .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1},
            .srcOffsets = {{0, 0, 0}, {w, h, 1}},
            .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1},
            .dstOffsets = {{0, 0, 0}, {nw, nh, 1}},
        };
        vkCmdBlitImage(cmd, u->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, u->image,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
        mip_barrier(cmd, u->image, level - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_READ_BIT, shaders, VK_ACCESS_SHADER_READ_BIT);
        w = nw;
        h = nh;
    }
    mip_barrier(cmd, u->image, u->levels - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                shaders, VK_ACCESS_SHADER_READ_BIT);
}

rtpbr_result rtpbr_texture_create(rtpbr_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                                  const void *texels, size_t bytes, bool mipmaps, rtpbr_image *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_buffer staging = {0};
    memset(out, 0, sizeof *out);
    uint32_t levels = 1;
    if (mipmaps) {
        VkFormatProperties props;
        vkGetPhysicalDeviceFormatProperties(ctx->physical_device, format, &props);
        const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                          VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
        if ((props.optimalTilingFeatures & need) == need) {
            for (uint32_t size = width > height ? width : height; size > 1; size /= 2) ++levels;
        } else {
            rtpbr_log(&ctx->host, RTPBR_LOG_INFO, "format %d cannot be blitted with linear filtering: texture "
                      "without mipmaps", (int)format);
        }
    }
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, &staging));
    memcpy(staging.mapped, texels, bytes);
    RTPBR_TRY(image_create_levels(ctx, width, height, 1, 0, levels, format,
                                  VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                      (levels > 1 ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0),
                                  out));
    mip_upload upload = {staging.buffer, out->image, width, height, levels};
    RTPBR_TRY(rtpbr_submit_once(ctx, record_mip_upload, &upload));
cleanup:
    if (result != RTPBR_SUCCESS) rtpbr_image_destroy(ctx, out); // accepts a zeroed or half-built image
    rtpbr_buffer_destroy(ctx, &staging);
    return result;
}

// IEEE binary16 from binary32, round to nearest even (values here are finite table entries).
static uint16_t half_from_float(float f)
{
    uint32_t x;
    memcpy(&x, &f, sizeof x);
    uint32_t sign = (x >> 16) & 0x8000u;
    int32_t exponent = (int32_t)((x >> 23) & 0xffu) - 127 + 15;
    uint32_t mantissa = x & 0x7fffffu;
    if (exponent >= 31) return (uint16_t)(sign | 0x7c00u);           // overflow: infinity
    if (exponent <= 0) {                                             // subnormal or zero
        if (exponent < -10) return (uint16_t)sign;
        mantissa |= 0x800000u;
        uint32_t shift = (uint32_t)(14 - exponent);
        uint32_t half = mantissa >> shift;
        uint32_t rest = mantissa & ((1u << shift) - 1u), midpoint = 1u << (shift - 1u);
        if (rest > midpoint || (rest == midpoint && (half & 1u))) ++half;
        return (uint16_t)(sign | half);
    }
    uint32_t half = sign | ((uint32_t)exponent << 10) | (mantissa >> 13);
    uint32_t rest = mantissa & 0x1fffu;
    if (rest > 0x1000u || (rest == 0x1000u && (half & 1u))) ++half; // may carry into the exponent: correct
    return (uint16_t)half;
}

// ---------------------------------------------------------------------------------------------
// Light textures (the textured quads' prefiltered chains, light_texture.h)

typedef struct light_texture_upload {
    VkBuffer staging;
    VkImage image;
    uint32_t layers;
} light_texture_upload;

static void record_light_texture_upload(VkCommandBuffer cmd, void *user)
{
    const light_texture_upload *u = user;
    const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, RTPBR_LIGHT_TEXTURE_LEVELS, 0, u->layers};
    rtpbr_image_range_barrier(cmd, u->image, all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                              VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                              VK_ACCESS_TRANSFER_WRITE_BIT);
    // one region per level and layer: the staging buffer holds the chains one after the other
    VkBufferImageCopy regions[RTPBR_LIGHT_TEXTURE_LEVELS];
    for (uint32_t layer = 0; layer < u->layers; ++layer) {
        for (uint32_t k = 0; k < RTPBR_LIGHT_TEXTURE_LEVELS; ++k) {
            uint32_t size = RTPBR_LIGHT_TEXTURE_SIZE >> k;
            regions[k] = (VkBufferImageCopy){
                .bufferOffset = ((VkDeviceSize)layer * rtpbr_light_texture_floats() +
                                 rtpbr_light_texture_level_offset(k)) * sizeof(uint16_t),
                .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, k, layer, 1},
                .imageExtent = {size, size, 1},
            };
        }
        vkCmdCopyBufferToImage(cmd, u->staging, u->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               RTPBR_LIGHT_TEXTURE_LEVELS, regions);
    }
    rtpbr_image_range_barrier(cmd, u->image, all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                              VK_ACCESS_TRANSFER_WRITE_BIT,
                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                              VK_ACCESS_SHADER_READ_BIT);
}

rtpbr_result rtpbr_light_textures_create(rtpbr_context *ctx, const float *chains, uint32_t layers, rtpbr_image *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_buffer staging = {0};
    memset(out, 0, sizeof *out);
    // RGBA16F: linear filtering is required of it (not of RGBA32F); the chains are emission
    // factors in [0, 1] (sRGB-decoded 8-bit texels), which half floats hold to 2^-11.
    size_t count = rtpbr_light_texture_floats() * layers;
    RTPBR_TRY(rtpbr_buffer_create_host(ctx, count * sizeof(uint16_t), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, &staging));
    uint16_t *dst = staging.mapped;
    for (size_t i = 0; i < count; ++i) dst[i] = half_from_float(chains[i]);
    RTPBR_TRY(image_create_levels(ctx, RTPBR_LIGHT_TEXTURE_SIZE, RTPBR_LIGHT_TEXTURE_SIZE, 1, layers,
                                  RTPBR_LIGHT_TEXTURE_LEVELS, VK_FORMAT_R16G16B16A16_SFLOAT,
                                  VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, out));
    light_texture_upload upload = {staging.buffer, out->image, layers};
    RTPBR_TRY(rtpbr_submit_once(ctx, record_light_texture_upload, &upload));
    rtpbr_buffer_destroy(ctx, &staging);
    return RTPBR_SUCCESS;
cleanup:
    rtpbr_buffer_destroy(ctx, &staging);
    rtpbr_image_destroy(ctx, out);
    return result;
}

rtpbr_result rtpbr_lut_create(rtpbr_context *ctx, uint32_t width, uint32_t height, uint32_t depth, const float *rgba,
                              rtpbr_lut *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    rtpbr_buffer staging = {0};
    memset(out, 0, sizeof *out);
    if (!rgba || width == 0 || height == 0 || depth == 0) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "lookup table: no data or zero size (%ux%ux%u)", width, height, depth);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    if (!rtpbr_finite(rgba, (size_t)width * height * depth * 4)) {
        rtpbr_log(&ctx->host, RTPBR_LOG_ERROR, "lookup table %ux%ux%u holds a NaN or infinite value", width, height, depth);
        return RTPBR_ERROR_INVALID_ARGUMENT;
    }
    // Linear filtering of 32-bit floats is optional in Vulkan; fall back to half floats.
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx->physical_device, VK_FORMAT_R32G32B32A32_SFLOAT, &props);
    bool full = props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    VkFormat format = full ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
    size_t count = (size_t)width * height * depth * 4;
    size_t bytes = count * (full ? sizeof(float) : sizeof(uint16_t));

    RTPBR_TRY(rtpbr_buffer_create_host(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, &staging));
    if (full) {
        memcpy(staging.mapped, rgba, bytes);
    } else {
        uint16_t *dst = staging.mapped;
        for (size_t i = 0; i < count; ++i) dst[i] = half_from_float(rgba[i]);
    }
    RTPBR_TRY(image_create(ctx, width, height, depth, 0, format,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, &out->image));
    lut_upload upload = {staging.buffer, out->image.image, width, height, depth};
    RTPBR_TRY(rtpbr_submit_once(ctx, record_lut_upload, &upload));
    rtpbr_buffer_destroy(ctx, &staging);
    return RTPBR_SUCCESS;
cleanup:
    rtpbr_buffer_destroy(ctx, &staging);
    rtpbr_lut_destroy(ctx, out);
    return result;
}

void rtpbr_lut_destroy(rtpbr_context *ctx, rtpbr_lut *lut)
{
    rtpbr_image_destroy(ctx, &lut->image);
}
