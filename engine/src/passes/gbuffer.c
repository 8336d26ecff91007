// G-buffer pass: rasterises every mesh into base colour + metallic, world normal + perceptual
// roughness, emission + material index, anisotropy direction, and depth; and, for scenes whose
// materials have them, the clearcoat, sheen and specular textures' values.
#include "passes.h"

#include "../internal.h"
#include "pipeline.h"
#include "rtpbr_spirv_gbuffer_frag.h"
#include "rtpbr_spirv_gbuffer_vert.h"

const VkFormat rtpbr_gbuffer_formats[RTPBR_GBUFFER_COUNT] = {
    VK_FORMAT_R8G8B8A8_UNORM,      // base colour, metallic
    VK_FORMAT_R16G16B16A16_SFLOAT, // normal, roughness
    VK_FORMAT_R32G32B32A32_SFLOAT, // emission, material index (exact as a float up to 2^24)
    VK_FORMAT_R16G16B16A16_SFLOAT, // anisotropy direction
    // The extension textures' values (rendered only for scenes that have them):
    VK_FORMAT_R8G8B8A8_SRGB,       // specular colour (sRGB, as its texture), specular (linear alpha)
    VK_FORMAT_R8G8B8A8_SRGB,       // sheen colour (sRGB), sheen roughness (linear alpha)
    VK_FORMAT_R8G8_UNORM,          // clearcoat, clearcoat roughness
};
// The extension bit (RTPBR_EXTENSION_TEXTURES_*) under which each G-buffer from
// RTPBR_GBUFFER_FIRST_EXTENSION on is rendered (gbuffer.frag writes it under the same bit).
static const uint32_t extension_gbuffer_bits[RTPBR_GBUFFER_COUNT - RTPBR_GBUFFER_FIRST_EXTENSION] = {
    RTPBR_EXTENSION_TEXTURES_SPECULAR, RTPBR_EXTENSION_TEXTURES_COAT_SHEEN, RTPBR_EXTENSION_TEXTURES_COAT_SHEEN};

// The scene's vertex layout (RTPBR_VERTEX_FLOATS): position, normal, uv, tangent, uv1.
static const VkVertexInputBindingDescription vertex_binding = {0, RTPBR_VERTEX_FLOATS * sizeof(float),
                                                               VK_VERTEX_INPUT_RATE_VERTEX};
static const VkVertexInputAttributeDescription vertex_attributes[5] = {
    {0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
    {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 3 * sizeof(float)},
    {2, 0, VK_FORMAT_R32G32_SFLOAT, RTPBR_VERTEX_UV_OFFSET * sizeof(float)},
    {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 8 * sizeof(float)},
    {4, 0, VK_FORMAT_R32G32_SFLOAT, RTPBR_VERTEX_UV1_OFFSET * sizeof(float)},
};
const VkPipelineVertexInputStateCreateInfo rtpbr_scene_vertex_input = {
    .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
    .vertexBindingDescriptionCount = 1,
    .pVertexBindingDescriptions = &vertex_binding,
    .vertexAttributeDescriptionCount = 5,
    .pVertexAttributeDescriptions = vertex_attributes,
};

// Set 0, one per renderer.
static const VkDescriptorSetLayoutBinding frame_bindings[] = {
    {RTPBR_BINDING_GBUFFER_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
     VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, NULL},
    {RTPBR_BINDING_GBUFFER_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, NULL},
    {RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, NULL},
};
// Set 1, one per material slot of a scene: a combined image sampler per texture slot
// (rtpbr_shared.h's slot list), binding = slot.
#define SLOT_BINDING(unused_a, unused_b, name, slot)                                              \
    {slot, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, NULL},
static const VkDescriptorSetLayoutBinding material_bindings[RTPBR_MATERIAL_TEXTURE_COUNT] = {
    RTPBR_MATERIAL_TEXTURE_SLOTS(SLOT_BINDING, 0, 0)};
#undef SLOT_BINDING
// Every slot once, at its place in the list (binding = its index).
#define SLOT_CHECK(unused_a, unused_b, name, slot) +((slot) < RTPBR_MATERIAL_TEXTURE_COUNT ? 1 << (slot) : 0)
_Static_assert((0 RTPBR_MATERIAL_TEXTURE_SLOTS(SLOT_CHECK, 0, 0)) == (1 << RTPBR_MATERIAL_TEXTURE_COUNT) - 1,
               "texture slots: bindings 0 .. RTPBR_MATERIAL_TEXTURE_COUNT - 1, each once");
#undef SLOT_CHECK

rtpbr_result rtpbr_gbuffer_vertex_module(rtpbr_context *ctx, VkShaderModule *out)
{
    return rtpbr_shader_module(ctx, RTPBR_SPIRV(rtpbr_spirv_gbuffer_vert), out);
}

rtpbr_result rtpbr_gbuffer_pass_init(rtpbr_context *ctx)
{
    rtpbr_gbuffer_pass *pass = &ctx->gbuffer;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_set_layout_create(ctx, RTPBR_BINDINGS(frame_bindings), &pass->set_layout));
    RTPBR_TRY(rtpbr_set_layout_create(ctx, RTPBR_BINDINGS(material_bindings), &pass->material_set_layout));
    VkDescriptorSetLayout sets[2] = {pass->set_layout, pass->material_set_layout};
    RTPBR_TRY(rtpbr_pipeline_layout_create(ctx, sets, 2, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                           sizeof(rtpbr_shader_draw), &pass->layout));
cleanup:
    return result; // the caller finishes a half-built pass; the pipelines are made on first use
}

void rtpbr_gbuffer_pass_finish(rtpbr_context *ctx)
{
    rtpbr_gbuffer_pass *pass = &ctx->gbuffer;
    rtpbr_pass_objects_destroy(ctx, pass->pipelines, RTPBR_GBUFFER_TEXTURES_ALL + 1, pass->layout, pass->set_layout);
    vkDestroyDescriptorSetLayout(ctx->device, pass->material_set_layout, NULL);
    *pass = (rtpbr_gbuffer_pass){0};
}

uint8_t rtpbr_gbuffer_material_slots(const rtpbr_material_desc *m)
{
    // (the slot list's first RTPBR_GBUFFER_SPEC_SLOTS entries, by binding: rtpbr_shared.h)
    _Static_assert(RTPBR_BINDING_TEXTURE_BASE_COLOR < RTPBR_GBUFFER_SPEC_SLOTS &&
                       RTPBR_BINDING_TEXTURE_METALLIC_ROUGHNESS < RTPBR_GBUFFER_SPEC_SLOTS &&
                       RTPBR_BINDING_TEXTURE_EMISSION < RTPBR_GBUFFER_SPEC_SLOTS &&
                       RTPBR_BINDING_TEXTURE_NORMAL < RTPBR_GBUFFER_SPEC_SLOTS && RTPBR_GBUFFER_SPEC_SLOTS <= 8,
                   "the G-buffer's specialized texture slots");
    uint32_t slots = (m->base_color_texture ? 1u << RTPBR_BINDING_TEXTURE_BASE_COLOR : 0u) |
                     (m->metallic_roughness_texture ? 1u << RTPBR_BINDING_TEXTURE_METALLIC_ROUGHNESS : 0u) |
                     (m->emission_texture ? 1u << RTPBR_BINDING_TEXTURE_EMISSION : 0u) |
                     // (normal-mapped: rtpbr_material_record's RTPBR_MATERIAL_FLAG_NORMAL_MAPPED)
                     (m->normal_texture ? 1u << RTPBR_BINDING_TEXTURE_NORMAL : 0u);
    return (uint8_t)slots;
}

rtpbr_result rtpbr_gbuffer_pipelines_get(rtpbr_context *ctx, const rtpbr_gpu_scene *scene)
{
    rtpbr_gbuffer_pass *pass = &ctx->gbuffer;
    rtpbr_result result = RTPBR_SUCCESS;
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    const rtpbr_shader_material *materials = scene->materials.mapped;
    for (uint32_t i = 0; i < scene->draw_count; ++i) {
        uint32_t m = scene->draws[i].push.material;
        if (materials[m].flags & RTPBR_MATERIAL_FLAG_ALPHA_BLEND) continue; // the forward pass's
        uint32_t slots = scene->material_gbuffer_slots[m];
        if (pass->pipelines[slots]) continue;
        if (!vert) RTPBR_TRY(rtpbr_gbuffer_vertex_module(ctx, &vert));
        if (!frag) RTPBR_TRY(rtpbr_shader_module(ctx, RTPBR_SPIRV(rtpbr_spirv_gbuffer_frag), &frag));
        const VkSpecializationMapEntry entry = {RTPBR_SPEC_GBUFFER_TEXTURES, 0, sizeof slots};
        const VkSpecializationInfo specialization = {1, &entry, sizeof slots, &slots};
        rtpbr_graphics_desc d = {
            .vert = vert,
            .frag = frag,
            .layout = pass->layout,
            .color_formats = rtpbr_gbuffer_formats,
            .color_count = RTPBR_GBUFFER_COUNT,
            .depth_format = RTPBR_DEPTH_FORMAT,
            .vertex_input = &rtpbr_scene_vertex_input,
            .dynamic_cull = true, // back faces of single-sided materials (rtpbr_gbuffer_record)
            .frag_specialization = &specialization,
        };
        RTPBR_TRY(rtpbr_graphics_pipeline_create(ctx, &d, &pass->pipelines[slots]));
    }
cleanup:
    vkDestroyShaderModule(ctx->device, vert, NULL);
    vkDestroyShaderModule(ctx->device, frag, NULL);
    return result;
}

rtpbr_result rtpbr_gbuffer_renderer_init(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_descriptor_set_create(ctx, RTPBR_BINDINGS(frame_bindings), ctx->gbuffer.set_layout,
                                          &r->gbuffer_set));
    rtpbr_descriptor_write_buffer(ctx, RTPBR_BINDINGS(frame_bindings), r->gbuffer_set.set,
                                  RTPBR_BINDING_GBUFFER_FRAME, r->frame.buffer, sizeof(rtpbr_shader_frame));
cleanup:
    return result;
}

void rtpbr_gbuffer_renderer_finish(rtpbr_renderer *r)
{
    rtpbr_descriptor_set_destroy(r->context, &r->gbuffer_set);
}

rtpbr_result rtpbr_gbuffer_material_sets_create(rtpbr_gpu_scene *scene, uint32_t material_slots)
{
    rtpbr_context *ctx = scene->context;
    rtpbr_result result = RTPBR_SUCCESS;
    VkDescriptorSetLayout *layouts = NULL;
    RTPBR_ALLOC(&ctx->host, scene->material_sets, material_slots * sizeof *scene->material_sets);
    RTPBR_ALLOC(&ctx->host, layouts, material_slots * sizeof *layouts);
    RTPBR_TRY(rtpbr_descriptor_pool_create(ctx, RTPBR_BINDINGS(material_bindings), material_slots,
                                           &scene->material_pool));
    for (uint32_t i = 0; i < material_slots; ++i) layouts[i] = ctx->gbuffer.material_set_layout;
    VkDescriptorSetAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = scene->material_pool,
        .descriptorSetCount = material_slots,
        .pSetLayouts = layouts,
    };
    RTPBR_VK(&ctx->host, vkAllocateDescriptorSets(ctx->device, &alloc, scene->material_sets));
cleanup:
    rtpbr_free(&ctx->host, layouts);
    return result; // rtpbr_gbuffer_material_sets_destroy frees a half-built state
}

void rtpbr_gbuffer_material_sets_destroy(rtpbr_gpu_scene *scene)
{
    rtpbr_context *ctx = scene->context;
    if (scene->material_pool) vkDestroyDescriptorPool(ctx->device, scene->material_pool, NULL);
    rtpbr_free(&ctx->host, scene->material_sets);
    scene->material_pool = VK_NULL_HANDLE;
    scene->material_sets = NULL;
}

void rtpbr_gbuffer_write_material_textures(rtpbr_gpu_scene *scene, uint32_t m,
                                           const uint32_t texture[RTPBR_MATERIAL_TEXTURE_COUNT])
{
    rtpbr_context *ctx = scene->context;
    for (uint32_t b = 0; b < RTPBR_MATERIAL_TEXTURE_COUNT; ++b)
        rtpbr_descriptor_write_image(ctx, RTPBR_BINDINGS(material_bindings), scene->material_sets[m], b,
                                     scene->samplers[scene->texture_samplers[texture[b]]],
                                     scene->textures[texture[b]].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

void rtpbr_gbuffer_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene)
{
    rtpbr_descriptor_write_buffer(r->context, RTPBR_BINDINGS(frame_bindings), r->gbuffer_set.set,
                                  RTPBR_BINDING_GBUFFER_MATERIALS, scene->materials.buffer, VK_WHOLE_SIZE);
    rtpbr_descriptor_write_buffer(r->context, RTPBR_BINDINGS(frame_bindings), r->gbuffer_set.set,
                                  RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS, scene->texture_transforms.buffer,
                                  VK_WHOLE_SIZE);
}

void rtpbr_gbuffer_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    // The previous frame's lighting pass read these images: wait for it, discard contents.
    for (uint32_t i = 0; i < RTPBR_GBUFFER_COUNT; ++i)
        rtpbr_image_barrier(cmd, r->gbuffer[i].image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    rtpbr_image_barrier(cmd, r->depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);

    // The extension textures' G-buffers only where the scene's materials have such textures
    // (no image view: the shader's writes are discarded, and the lighting passes do not read them).
    uint32_t extensions = rtpbr_gpu_scene_extension_textures(scene);
    VkRenderingAttachmentInfo colors[RTPBR_GBUFFER_COUNT];
    for (uint32_t i = 0; i < RTPBR_GBUFFER_COUNT; ++i) {
        bool rendered = i < RTPBR_GBUFFER_FIRST_EXTENSION ||
                        (extensions & extension_gbuffer_bits[i - RTPBR_GBUFFER_FIRST_EXTENSION]);
        colors[i] = rtpbr_attachment(rendered ? r->gbuffer[i].view : VK_NULL_HANDLE,
                                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                     VK_ATTACHMENT_STORE_OP_STORE);
    }
    VkRenderingAttachmentInfo depth = rtpbr_attachment(r->depth.view, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                                       VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE);
    depth.clearValue.depthStencil = (VkClearDepthStencilValue){1.0f, 0};
    rtpbr_begin_rendering(cmd, r->shade_width, r->shade_height, colors, RTPBR_GBUFFER_COUNT, &depth);
    if (scene->draw_count) {
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ctx->gbuffer.layout, 0, 1, &r->gbuffer_set.set,
                                0, NULL);
        VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &scene->vertices.buffer, &offset);
        vkCmdBindIndexBuffer(cmd, scene->indices.buffer, 0, VK_INDEX_TYPE_UINT32);
        const rtpbr_shader_material *materials = scene->materials.mapped;
        VkPipeline bound = VK_NULL_HANDLE;
        for (uint32_t i = 0; i < scene->draw_count; ++i) {
            const rtpbr_draw *d = &scene->draws[i];
            if (materials[d->push.material].flags & RTPBR_MATERIAL_FLAG_ALPHA_BLEND) continue; // the forward pass's
            // the pipeline of the material's texture slots (rtpbr_gbuffer_pipelines_get made it)
            VkPipeline pipeline = ctx->gbuffer.pipelines[scene->material_gbuffer_slots[d->push.material]];
            if (pipeline != bound) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
            bound = pipeline;
            rtpbr_draw_mesh(cmd, ctx->gbuffer.layout, scene, d);
        }
    }
    vkCmdEndRendering(cmd);

    for (uint32_t i = 0; i < RTPBR_GBUFFER_COUNT; ++i)
        rtpbr_image_barrier(cmd, r->gbuffer[i].image, VK_IMAGE_ASPECT_COLOR_BIT,
                            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    rtpbr_image_barrier(cmd, r->depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                        VK_ACCESS_SHADER_READ_BIT);
}
