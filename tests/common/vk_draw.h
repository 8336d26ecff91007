/* rtpbr tests: the few Vulkan objects a test that draws with its own pipeline needs (a host of
 * its own: tests/samples/test_shader_include_image.c, tests/engine/test_engine_lightpass.c),
 * made on a vk_host's device. Every function returns the first failing VkResult (VK_SUCCESS
 * otherwise) and leaves what it made in *out for the caller to destroy, also after a failure.
 */
#ifndef RTPBR_TEST_VK_DRAW_H
#define RTPBR_TEST_VK_DRAW_H

#include <stddef.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

#include "vk_host.h"

/* Memory of a type in req.memoryTypeBits with every flag of `want`
 * (VK_ERROR_FEATURE_NOT_PRESENT when there is none). */
VkResult vk_draw_memory(const vk_host *h, VkMemoryRequirements req, VkMemoryPropertyFlags want, VkDeviceMemory *out);

/* A host-visible, host-coherent buffer holding `data` (if not NULL), left mapped in *mapped
 * when mapped is not NULL. */
typedef struct vk_draw_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
} vk_draw_buffer;
VkResult vk_draw_buffer_create(const vk_host *h, VkDeviceSize size, VkBufferUsageFlags usage, const void *data,
                               vk_draw_buffer *out);
void vk_draw_buffer_destroy(const vk_host *h, vk_draw_buffer *b);

/* A device-local image of one mip level and one layer, 3D when depth > 1, with a view of its
 * format (the depth aspect for D32_SFLOAT, D16_UNORM and X8_D24_UNORM_PACK32, else colour). */
typedef struct vk_draw_image {
    VkImage image;
    VkImageView view;
    VkDeviceMemory memory;
} vk_draw_image;
VkResult vk_draw_image_create(const vk_host *h, VkFormat format, uint32_t width, uint32_t height, uint32_t depth,
                              VkImageUsageFlags usage, vk_draw_image *out);
void vk_draw_image_destroy(const vk_host *h, vk_draw_image *image);

/* A primary command buffer of `pool`, begun for one submission. */
VkResult vk_draw_begin(const vk_host *h, VkCommandPool pool, VkCommandBuffer *out);

/* One image memory barrier (one mip level, one layer). */
void vk_draw_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                     VkImageLayout to, VkPipelineStageFlags src_stage, VkAccessFlags src,
                     VkPipelineStageFlags dst_stage, VkAccessFlags dst);

/* A graphics pipeline for dynamic rendering: vertex and fragment SPIR-V, one vertex binding of
 * `attribute_count` R32G32B32_SFLOAT attributes at locations 0.. packed in order, triangle
 * lists, no culling, depth test and write with depth_compare (depth_format UNDEFINED: none),
 * colour writes without blending, dynamic viewport and scissor. */
typedef struct vk_draw_pipeline_desc {
    const uint32_t *vert, *frag;
    size_t vert_size, frag_size; /* bytes */
    uint32_t attribute_count;    /* vec3 attributes, at most 4 */
    const VkFormat *color_formats;
    uint32_t color_count;        /* at most 8 */
    VkFormat depth_format;
    VkCompareOp depth_compare;
    VkPipelineLayout layout;
} vk_draw_pipeline_desc;
VkResult vk_draw_pipeline_create(const vk_host *h, const vk_draw_pipeline_desc *desc, VkPipeline *out);

/* A test's own pass: its one descriptor set (layout, pool, set), pipeline layout and pipeline,
 * destroyed together (VK_NULL_HANDLE members are skipped). */
typedef struct vk_draw_pass {
    VkDescriptorSetLayout set_layout;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
} vk_draw_pass;
void vk_draw_pass_destroy(const vk_host *h, vk_draw_pass *pass);

#endif /* RTPBR_TEST_VK_DRAW_H */
