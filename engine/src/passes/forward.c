// Forward pass of glTF alphaMode BLEND surfaces (shaders/forward.frag): after the lighting
// pass (and before the supersampling resolve), the BLEND meshes are drawn at the shading size
// over the lit radiance image, sorted back to front by the view distance of their bounds'
// centres (per mesh: a mesh whose parts overlap itself is not sorted within), depth-tested
// against the G-buffer's depth (they do not write it) and blended premultiplied:
// colour = radiance x alpha + below x (1 - alpha). Each fragment is shaded by the lighting
// pass's own per-light loop (shade_lights.glsl) over every light of the frame, unshadowed:
// its cost is one light loop per BLEND fragment and layer, O(lights), where the lighting pass
// loops over a tile's culled lights only.
#include <stdlib.h>

#include "passes.h"

#include "../internal.h"
#include "pipeline.h"
#include "rtpbr_spirv_forward_beckmann_ms0.h"
#include "rtpbr_spirv_forward_beckmann_ms1.h"
#include "rtpbr_spirv_forward_ggx_ms0.h"
#include "rtpbr_spirv_forward_ggx_ms1.h"
#include "rtpbr_spirv_forward_beckmann_ms0_spheres.h"
#include "rtpbr_spirv_forward_beckmann_ms1_spheres.h"
#include "rtpbr_spirv_forward_ggx_ms0_spheres.h"
#include "rtpbr_spirv_forward_ggx_ms1_spheres.h"

// Set 0: the lighting set's numbering for what shading needs (shading.glsl), and the G-buffer
// vertex shader's texture transforms (gbuffer.vert) at a number the lighting set leaves free.
#define FRAGMENT(binding, type) {binding, VK_DESCRIPTOR_TYPE_##type, 1, VK_SHADER_STAGE_FRAGMENT_BIT, NULL}
static const VkDescriptorSetLayoutBinding bindings[] = {
    {RTPBR_BINDING_LIGHT_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
     VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, NULL},
    FRAGMENT(RTPBR_BINDING_LIGHT_LIGHTS, STORAGE_BUFFER),
    {RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, NULL},
    FRAGMENT(RTPBR_BINDING_LUT_LTC_GGX_1, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_LTC_GGX_2, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_LTC_BECKMANN_1, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_LTC_BECKMANN_2, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_KC_E, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_KC_EAVG, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_KC_EF, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_KC_EFAVG, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_LTC_DISNEY_1, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_LTC_DISNEY_2, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_SHEEN_E, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_LTC_SHEEN_1, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LUT_LTC_SHEEN_2, COMBINED_IMAGE_SAMPLER),
    FRAGMENT(RTPBR_BINDING_LIGHT_MATERIALS, STORAGE_BUFFER),
    FRAGMENT(RTPBR_BINDING_LIGHT_TEXTURES, COMBINED_IMAGE_SAMPLER),
};
#undef FRAGMENT
_Static_assert(RTPBR_BINDING_GBUFFER_FRAME == RTPBR_BINDING_LIGHT_FRAME, "gbuffer.vert's frame binding");
_Static_assert(RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS != RTPBR_BINDING_LIGHT_LIGHTS &&
                   RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS != RTPBR_BINDING_LIGHT_MATERIALS &&
                   (RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS < RTPBR_BINDING_LUT_LTC_GGX_1 ||
                    RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS >= RTPBR_BINDING_LUT_LTC_GGX_1 + RTPBR_LUT_COUNT),
               "the texture transforms' binding is free in the forward set");

rtpbr_result rtpbr_forward_pass_init(rtpbr_context *ctx)
{
    rtpbr_forward_pass *pass = &ctx->forward;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_set_layout_create(ctx, RTPBR_BINDINGS(bindings), &pass->set_layout));
    VkDescriptorSetLayout sets[2] = {pass->set_layout, ctx->gbuffer.material_set_layout};
    RTPBR_TRY(rtpbr_pipeline_layout_create(ctx, sets, 2, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                           sizeof(rtpbr_shader_draw), &pass->layout));
cleanup:
    return result; // the caller finishes a half-built pass; the pipelines are made on first use
}

void rtpbr_forward_pass_finish(rtpbr_context *ctx)
{
    rtpbr_forward_pass *pass = &ctx->forward;
    rtpbr_pass_objects_destroy(ctx, pass->pipelines, 2 * RTPBR_LIGHTING_VARIANT_COUNT, pass->layout, pass->set_layout);
    *pass = (rtpbr_forward_pass){0};
}

rtpbr_result rtpbr_forward_pipeline_get(rtpbr_context *ctx, rtpbr_ndf ndf, rtpbr_multiscatter ms, bool spheres,
                                        VkPipeline *out)
{
    static const rtpbr_spirv frag[2 * RTPBR_LIGHTING_VARIANT_COUNT] = {
        RTPBR_SPIRV(rtpbr_spirv_forward_ggx_ms0),
        RTPBR_SPIRV(rtpbr_spirv_forward_ggx_ms1),
        RTPBR_SPIRV(rtpbr_spirv_forward_beckmann_ms0),
        RTPBR_SPIRV(rtpbr_spirv_forward_beckmann_ms1),
        RTPBR_SPIRV(rtpbr_spirv_forward_ggx_ms0_spheres),
        RTPBR_SPIRV(rtpbr_spirv_forward_ggx_ms1_spheres),
        RTPBR_SPIRV(rtpbr_spirv_forward_beckmann_ms0_spheres),
        RTPBR_SPIRV(rtpbr_spirv_forward_beckmann_ms1_spheres),
    };
    rtpbr_forward_pass *pass = &ctx->forward;
    uint32_t v = rtpbr_lighting_variant(ndf, ms) + (spheres ? RTPBR_LIGHTING_VARIANT_COUNT : 0);
    rtpbr_result result = RTPBR_SUCCESS;
    VkShaderModule vert = VK_NULL_HANDLE, fragment = VK_NULL_HANDLE;
    if (!pass->pipelines[v]) {
        RTPBR_TRY(rtpbr_gbuffer_vertex_module(ctx, &vert)); // gbuffer.vert
        RTPBR_TRY(rtpbr_shader_module(ctx, frag[v], &fragment));
        const VkFormat format = RTPBR_RADIANCE_FORMAT;
        rtpbr_graphics_desc d = {
            .vert = vert,
            .frag = fragment,
            .layout = pass->layout,
            .color_formats = &format,
            .color_count = 1,
            .depth_format = RTPBR_DEPTH_FORMAT,
            .vertex_input = &rtpbr_scene_vertex_input,
            .dynamic_cull = true,
            .blend_premultiplied = true,
            .depth_read_only = true,
        };
        RTPBR_TRY(rtpbr_graphics_pipeline_create(ctx, &d, &pass->pipelines[v]));
    }
    *out = pass->pipelines[v];
cleanup:
    vkDestroyShaderModule(ctx->device, vert, NULL);
    vkDestroyShaderModule(ctx->device, fragment, NULL);
    return result;
}

rtpbr_result rtpbr_forward_renderer_init(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_descriptor_set_create(ctx, RTPBR_BINDINGS(bindings), ctx->forward.set_layout, &r->forward_set));
    const rtpbr_bindings table = RTPBR_BINDINGS(bindings);
    rtpbr_descriptor_write_buffer(ctx, table, r->forward_set.set, RTPBR_BINDING_LIGHT_FRAME, r->frame.buffer,
                                  sizeof(rtpbr_shader_frame));
    for (uint32_t i = 0; i < RTPBR_LUT_COUNT; ++i)
        rtpbr_descriptor_write_image(ctx, table, r->forward_set.set, RTPBR_BINDING_LUT_LTC_GGX_1 + i, ctx->lut_sampler,
                                     ctx->luts[i].image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
cleanup:
    return result;
}

void rtpbr_forward_renderer_finish(rtpbr_renderer *r)
{
    rtpbr_descriptor_set_destroy(r->context, &r->forward_set);
}

void rtpbr_forward_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene)
{
    const rtpbr_buffer_write writes[] = {
        {RTPBR_BINDING_LIGHT_LIGHTS, scene->lights.buffer},
        {RTPBR_BINDING_LIGHT_MATERIALS, scene->materials.buffer},
        {RTPBR_BINDING_GBUFFER_TEXTURE_TRANSFORMS, scene->texture_transforms.buffer},
    };
    rtpbr_descriptor_write_buffers(r->context, RTPBR_BINDINGS(bindings), r->forward_set.set, writes,
                                   sizeof writes / sizeof writes[0]);
    rtpbr_descriptor_write_image(r->context, RTPBR_BINDINGS(bindings), r->forward_set.set, RTPBR_BINDING_LIGHT_TEXTURES,
                                 r->context->light_texture_sampler, rtpbr_gpu_scene_light_texture_view(scene),
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

static int farther_first(const void *a, const void *b)
{
    const rtpbr_draw_depth *x = a, *y = b;
    return x->distance2 > y->distance2 ? -1 : x->distance2 < y->distance2 ? 1 : (x->draw > y->draw) - (x->draw < y->draw);
}

// The BLEND draws into scene->blend_order, farthest first; returns how many.
static uint32_t sort_blend_draws(const rtpbr_renderer *r, const rtpbr_gpu_scene *scene)
{
    const rtpbr_shader_material *materials = scene->materials.mapped;
    const float *eye = ((const rtpbr_shader_frame *)r->frame.mapped)->camera_position;
    uint32_t n = 0;
    for (uint32_t i = 0; i < scene->draw_count; ++i) {
        const rtpbr_draw *d = &scene->draws[i];
        if (!(materials[d->push.material].flags & RTPBR_MATERIAL_FLAG_ALPHA_BLEND)) continue;
        const float *m = d->push.world_from_object, *c = d->center;
        float distance2 = 0.0f;
        for (int k = 0; k < 3; ++k) {
            float w = m[k] * c[0] + m[4 + k] * c[1] + m[8 + k] * c[2] + m[12 + k] - eye[k];
            distance2 += w * w;
        }
        scene->blend_order[n++] = (rtpbr_draw_depth){distance2, i};
    }
    qsort(scene->blend_order, n, sizeof *scene->blend_order, farther_first);
    return n;
}

void rtpbr_forward_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, VkPipeline pipeline, VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    uint32_t count = sort_blend_draws(r, scene);
    if (count == 0) return;
    VkImage target = r->supersample > 1 ? r->radiance_ss.image : r->radiance.image;
    VkImageView target_view = r->supersample > 1 ? r->radiance_ss.view : r->radiance.view;
    // After the lighting pass's writes; the image stays in GENERAL (its storage binding's layout).
    rtpbr_image_barrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    // The G-buffer's depth, read by the shadow and lighting passes, now tested against; the
    // next frame's G-buffer pass starts it from UNDEFINED.
    rtpbr_image_barrier(cmd, r->depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                        VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
    VkRenderingAttachmentInfo color = rtpbr_attachment(target_view, VK_IMAGE_LAYOUT_GENERAL, VK_ATTACHMENT_LOAD_OP_LOAD,
                                                       VK_ATTACHMENT_STORE_OP_STORE);
    VkRenderingAttachmentInfo depth = rtpbr_attachment(r->depth.view, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL,
                                                       VK_ATTACHMENT_LOAD_OP_LOAD, VK_ATTACHMENT_STORE_OP_NONE);
    rtpbr_begin_rendering(cmd, r->shade_width, r->shade_height, &color, 1, &depth);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ctx->forward.layout, 0, 1, &r->forward_set.set, 0,
                            NULL);
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &scene->vertices.buffer, &offset);
    vkCmdBindIndexBuffer(cmd, scene->indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    for (uint32_t k = 0; k < count; ++k) // sidedness as in the G-buffer pass
        rtpbr_draw_mesh(cmd, ctx->forward.layout, scene, &scene->draws[scene->blend_order[k].draw]);
    vkCmdEndRendering(cmd);
    // Before the resolve, the tone mapping and the readback (rtpbr_lighting_end's barrier
    // covers the compute writes only).
    rtpbr_image_barrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                            VK_PIPELINE_STAGE_TRANSFER_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}
