// What every pass file uses to build its part of the GPU contract: shader modules from the
// embedded SPIR-V, set and pipeline layouts, compute and graphics pipelines, and descriptor
// sets whose pool and writes follow the same binding table as their layout, so that each
// binding's type is written once (in the pass's table).
#ifndef RTPBR_PASSES_PIPELINE_H
#define RTPBR_PASSES_PIPELINE_H

#include <stdbool.h>
#include <stddef.h>

#include "../internal.h"

// SPIR-V compiled by the build (engine/shaders/meson.build) and embedded as uint32 arrays.
typedef struct rtpbr_spirv {
    const uint32_t *code;
    size_t size; // bytes
} rtpbr_spirv;
#define RTPBR_SPIRV(name) ((rtpbr_spirv){name, sizeof name})

// A pass's binding table: one entry per binding, descriptorCount 1, in the order of the
// binding numbers of rtpbr_shared.h.
typedef struct rtpbr_bindings {
    const VkDescriptorSetLayoutBinding *entries;
    uint32_t count;
} rtpbr_bindings;
#define RTPBR_BINDINGS(table) ((rtpbr_bindings){table, sizeof table / sizeof table[0]})

rtpbr_result rtpbr_shader_module(rtpbr_context *ctx, rtpbr_spirv spirv, VkShaderModule *out);
rtpbr_result rtpbr_set_layout_create(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSetLayout *out);
// A pipeline layout of `set_count` sets and, if push_size > 0, one push-constant range.
rtpbr_result rtpbr_pipeline_layout_create(rtpbr_context *ctx, const VkDescriptorSetLayout *sets, uint32_t set_count,
                                          VkShaderStageFlags push_stages, uint32_t push_size, VkPipelineLayout *out);
rtpbr_result rtpbr_compute_pipeline_create(rtpbr_context *ctx, rtpbr_spirv spirv, VkPipelineLayout layout,
                                           VkPipeline *out);
// The same with the shader's specialization constants set (NULL: their defaults).
rtpbr_result rtpbr_compute_pipeline_create_specialized(rtpbr_context *ctx, rtpbr_spirv spirv, VkPipelineLayout layout,
                                                       const VkSpecializationInfo *specialization, VkPipeline *out);
// A graphics pipeline with dynamic rendering, dynamic viewport and scissor, no blending (or
// premultiplied alpha blending),
// triangle lists; no culling, or with dynamic_cull the cull mode and front face set per draw
// (vkCmdSetCullMode, vkCmdSetFrontFace: core in Vulkan 1.3).
typedef struct rtpbr_graphics_desc {
    VkShaderModule vert, frag;
    VkPipelineLayout layout;
    const VkFormat *color_formats;
    uint32_t color_count;       // at most RTPBR_GBUFFER_COUNT
    VkFormat depth_format;      // VK_FORMAT_UNDEFINED: no depth
    const VkPipelineVertexInputStateCreateInfo *vertex_input; // NULL: no vertex input
    bool dynamic_cull;
    bool blend_premultiplied; // colour = src + dst (1 - src alpha), alpha alike
    bool depth_read_only;     // depth test (less or equal) without writes
    const VkSpecializationInfo *frag_specialization; // NULL: the fragment shader's defaults
} rtpbr_graphics_desc;
rtpbr_result rtpbr_graphics_pipeline_create(rtpbr_context *ctx, const rtpbr_graphics_desc *desc, VkPipeline *out);

// A pool for `sets` sets of the binding table and the sets themselves (out[0 .. sets)).
rtpbr_result rtpbr_descriptor_pool_create(rtpbr_context *ctx, rtpbr_bindings bindings, uint32_t sets,
                                          VkDescriptorPool *out);
// A descriptor set of `layout` (made from `bindings`) in a pool of its own.
rtpbr_result rtpbr_descriptor_set_create(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSetLayout layout,
                                         rtpbr_descriptor_set *out);
// Accepts a half-built or zeroed set.
void rtpbr_descriptor_set_destroy(rtpbr_context *ctx, rtpbr_descriptor_set *set);
// Points a buffer or image binding of a set made from `bindings` at a resource (the
// descriptor type from the binding table).
void rtpbr_descriptor_write_buffer(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set, uint32_t binding,
                                   VkBuffer buffer, VkDeviceSize range);
// Points buffer bindings of a set made from `bindings` at whole buffers, writes[0 .. count).
typedef struct rtpbr_buffer_write {
    uint32_t binding;
    VkBuffer buffer;
} rtpbr_buffer_write;
void rtpbr_descriptor_write_buffers(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set,
                                    const rtpbr_buffer_write *writes, uint32_t count);
// The same for the range [offset, offset + range) of the buffer.
void rtpbr_descriptor_write_buffer_range(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set,
                                         uint32_t binding, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize range);
void rtpbr_descriptor_write_image(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set, uint32_t binding,
                                  VkSampler sampler, VkImageView view, VkImageLayout layout);
void rtpbr_descriptor_write_texel_buffer(rtpbr_context *ctx, rtpbr_bindings bindings, VkDescriptorSet set,
                                         uint32_t binding, VkBufferView view);
// An acceleration structure (VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR) at `binding`.
void rtpbr_descriptor_write_accel(rtpbr_context *ctx, VkDescriptorSet set, uint32_t binding,
                                  VkAccelerationStructureKHR accel);


// A pass with one set layout (from its binding table) and a pipeline layout of that set and,
// if push_size > 0, one push-constant range.
rtpbr_result rtpbr_pass_layouts_create(rtpbr_context *ctx, rtpbr_bindings bindings, VkShaderStageFlags push_stages,
                                       uint32_t push_size, VkDescriptorSetLayout *set_layout, VkPipelineLayout *layout);
// Destroys a pass's pipelines[0 .. pipeline_count), pipeline layout and set layout (any of them
// VK_NULL_HANDLE: a half-built pass).
void rtpbr_pass_objects_destroy(rtpbr_context *ctx, const VkPipeline *pipelines, uint32_t pipeline_count,
                                VkPipelineLayout layout, VkDescriptorSetLayout set_layout);

// A dynamic-rendering attachment: `view` in `layout`, loaded and stored as said (clear value 0).
VkRenderingAttachmentInfo rtpbr_attachment(VkImageView view, VkImageLayout layout, VkAttachmentLoadOp load,
                                           VkAttachmentStoreOp store);
// Begins dynamic rendering into colors[0 .. color_count) and depth (NULL: none) over width x
// height, one layer, and sets the viewport (depth 0 to 1) and scissor to the same area.
void rtpbr_begin_rendering(VkCommandBuffer cmd, uint32_t width, uint32_t height, const VkRenderingAttachmentInfo *colors,
                           uint32_t color_count, const VkRenderingAttachmentInfo *depth);
// Draws one mesh of the scene with a pipeline of the G-buffer pass's layout shape (set 1: the
// material's textures; push constants: rtpbr_shader_draw) bound: back faces culled for a
// single-sided material (glTF doubleSided false), counter-clockwise the front face (the
// projection's y flip keeps it so), clockwise under a mirroring transform.
void rtpbr_draw_mesh(VkCommandBuffer cmd, VkPipelineLayout layout, const rtpbr_gpu_scene *scene, const rtpbr_draw *d);

#endif // RTPBR_PASSES_PIPELINE_H
