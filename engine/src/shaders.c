// Shader modules (SPIR-V embedded at build time) and the pipelines of the three passes.
#include <string.h>

#include "internal.h"

#include "rtpbr_spirv_gbuffer_frag.h"
#include "rtpbr_spirv_gbuffer_vert.h"
#include "rtpbr_spirv_cull_comp.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_basic.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_full.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_basic.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_full.h"
#include "rtpbr_spirv_lighting_empty.h"
#include "rtpbr_spirv_lighting_ggx_ms0_basic.h"
#include "rtpbr_spirv_lighting_ggx_ms0_full.h"
#include "rtpbr_spirv_lighting_ggx_ms1_basic.h"
#include "rtpbr_spirv_lighting_ggx_ms1_full.h"
#include "rtpbr_spirv_lighting_mc_beckmann_ms0.h"
#include "rtpbr_spirv_lighting_mc_beckmann_ms1.h"
#include "rtpbr_spirv_lighting_mc_ggx_ms0.h"
#include "rtpbr_spirv_lighting_mc_ggx_ms1.h"
#include "rtpbr_spirv_resolve_comp.h"
#include "rtpbr_spirv_tonemap_frag.h"
#include "rtpbr_spirv_tonemap_vert.h"

#define SPIRV(name) ((rtpbr_spirv){name, sizeof name})

const VkFormat rtpbr_gbuffer_formats[RTPBR_GBUFFER_COUNT] = {
    VK_FORMAT_R8G8B8A8_UNORM,      // base colour, metallic
    VK_FORMAT_R16G16B16A16_SFLOAT, // normal, roughness
    VK_FORMAT_R32G32B32A32_SFLOAT, // emission, material index (exact as a float up to 2^24)
    VK_FORMAT_R16G16B16A16_SFLOAT, // anisotropy direction
};

// Index of a lighting variant: ndf * 2 + multiscatter.
static uint32_t lighting_variant(rtpbr_ndf ndf, rtpbr_multiscatter ms)
{
    uint32_t n = ndf == RTPBR_NDF_BECKMANN_MODEL ? 1 : 0;
    uint32_t m = ms == RTPBR_MULTISCATTER_OFF ? 0 : 1;
    return n * 2 + m;
}

rtpbr_result rtpbr_shader_module(rtpbr_context *ctx, rtpbr_spirv spirv, VkShaderModule *out)
{
    VkShaderModuleCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = spirv.size,
        .pCode = spirv.code,
    };
    VkResult vr = vkCreateShaderModule(ctx->device, &info, NULL, out);
    return vr == VK_SUCCESS ? RTPBR_SUCCESS : rtpbr_vk_fail(ctx, vr, "vkCreateShaderModule");
}

static rtpbr_result create_set_layout(rtpbr_context *ctx, const VkDescriptorSetLayoutBinding *bindings,
                                      uint32_t count, VkDescriptorSetLayout *out)
{
    VkDescriptorSetLayoutCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = count,
        .pBindings = bindings,
    };
    VkResult vr = vkCreateDescriptorSetLayout(ctx->device, &info, NULL, out);
    return vr == VK_SUCCESS ? RTPBR_SUCCESS : rtpbr_vk_fail(ctx, vr, "vkCreateDescriptorSetLayout");
}

static rtpbr_result create_pipeline_layout(rtpbr_context *ctx, VkDescriptorSetLayout set,
                                           VkShaderStageFlags push_stages, uint32_t push_size,
                                           VkPipelineLayout *out)
{
    VkPushConstantRange push = {push_stages, 0, push_size};
    VkPipelineLayoutCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &set,
        .pushConstantRangeCount = push_size ? 1 : 0,
        .pPushConstantRanges = &push,
    };
    VkResult vr = vkCreatePipelineLayout(ctx->device, &info, NULL, out);
    return vr == VK_SUCCESS ? RTPBR_SUCCESS : rtpbr_vk_fail(ctx, vr, "vkCreatePipelineLayout");
}

// Graphics pipeline with dynamic rendering, dynamic viewport and scissor, no blending.
typedef struct graphics_desc {
    VkShaderModule vert, frag;
    VkPipelineLayout layout;
    const VkFormat *color_formats;
    uint32_t color_count;
    VkFormat depth_format;      // VK_FORMAT_UNDEFINED: no depth
    bool vertex_input;          // position, normal, uv, tangent (RTPBR_VERTEX_FLOATS)
} graphics_desc;

static rtpbr_result create_graphics(rtpbr_context *ctx, const graphics_desc *d, VkPipeline *out)
{
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = d->vert, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = d->frag, .pName = "main"},
    };
    VkVertexInputBindingDescription binding = {0, RTPBR_VERTEX_FLOATS * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attributes[4] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 3 * sizeof(float)},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, 6 * sizeof(float)},
        {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 8 * sizeof(float)},
    };
    VkPipelineVertexInputStateCreateInfo vertex_input = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        .vertexBindingDescriptionCount = d->vertex_input ? 1 : 0,
        .pVertexBindingDescriptions = &binding,
        .vertexAttributeDescriptionCount = d->vertex_input ? 4 : 0,
        .pVertexAttributeDescriptions = attributes,
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
        .depthWriteEnable = d->depth_format != VK_FORMAT_UNDEFINED,
        .depthCompareOp = VK_COMPARE_OP_LESS,
    };
    VkPipelineColorBlendAttachmentState blend[RTPBR_GBUFFER_COUNT];
    for (uint32_t i = 0; i < RTPBR_GBUFFER_COUNT; ++i)
        blend[i] = (VkPipelineColorBlendAttachmentState){
            .colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                              VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT,
        };
    VkPipelineColorBlendStateCreateInfo blending = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        .attachmentCount = d->color_count,
        .pAttachments = blend,
    };
    VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
        .dynamicStateCount = 2,
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
        .pVertexInputState = &vertex_input,
        .pInputAssemblyState = &assembly,
        .pViewportState = &viewport,
        .pRasterizationState = &raster,
        .pMultisampleState = &multisample,
        .pDepthStencilState = &depth,
        .pColorBlendState = &blending,
        .pDynamicState = &dynamic,
        .layout = d->layout,
    };
    VkResult vr = vkCreateGraphicsPipelines(ctx->device, VK_NULL_HANDLE, 1, &info, NULL, out);
    return vr == VK_SUCCESS ? RTPBR_SUCCESS : rtpbr_vk_fail(ctx, vr, "vkCreateGraphicsPipelines");
}

static rtpbr_result create_gbuffer(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    VkDescriptorSetLayoutBinding bindings[] = {
        {RTPBR_BINDING_GBUFFER_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
         VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, NULL},
        {RTPBR_BINDING_GBUFFER_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, NULL},
    };
    RTPBR_TRY(create_set_layout(ctx, bindings, 2, &ctx->gbuffer_set_layout));
    VkDescriptorSetLayoutBinding textures[RTPBR_MATERIAL_TEXTURE_COUNT];
    for (uint32_t i = 0; i < RTPBR_MATERIAL_TEXTURE_COUNT; ++i)
        textures[i] = (VkDescriptorSetLayoutBinding){i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                                     VK_SHADER_STAGE_FRAGMENT_BIT, NULL};
    RTPBR_TRY(create_set_layout(ctx, textures, RTPBR_MATERIAL_TEXTURE_COUNT, &ctx->material_set_layout));
    VkDescriptorSetLayout sets[2] = {ctx->gbuffer_set_layout, ctx->material_set_layout};
    VkPushConstantRange push = {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(rtpbr_shader_draw)};
    VkPipelineLayoutCreateInfo layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 2,
        .pSetLayouts = sets,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push,
    };
    RTPBR_VK(ctx, vkCreatePipelineLayout(ctx->device, &layout_info, NULL, &ctx->gbuffer_layout));
    RTPBR_TRY(rtpbr_shader_module(ctx, SPIRV(rtpbr_spirv_gbuffer_vert), &vert));
    RTPBR_TRY(rtpbr_shader_module(ctx, SPIRV(rtpbr_spirv_gbuffer_frag), &frag));
    graphics_desc d = {
        .vert = vert,
        .frag = frag,
        .layout = ctx->gbuffer_layout,
        .color_formats = rtpbr_gbuffer_formats,
        .color_count = RTPBR_GBUFFER_COUNT,
        .depth_format = RTPBR_DEPTH_FORMAT,
        .vertex_input = true,
    };
    RTPBR_TRY(create_graphics(ctx, &d, &ctx->gbuffer_pipeline));
cleanup:
    vkDestroyShaderModule(ctx->device, vert, NULL);
    vkDestroyShaderModule(ctx->device, frag, NULL);
    return result;
}

static rtpbr_result create_compute(rtpbr_context *ctx, rtpbr_spirv spirv, VkPipelineLayout layout, VkPipeline *out)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkShaderModule module = VK_NULL_HANDLE;
    RTPBR_TRY(rtpbr_shader_module(ctx, spirv, &module));
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = module, .pName = "main"},
        .layout = layout,
    };
    RTPBR_VK(ctx, vkCreateComputePipelines(ctx->device, VK_NULL_HANDLE, 1, &info, NULL, out));
cleanup:
    vkDestroyShaderModule(ctx->device, module, NULL);
    return result;
}

// The culling pass and the LTC lighting pass share one set layout (rtpbr_shared.h's
// RTPBR_BINDING_LIGHT_*).
static rtpbr_result create_lighting(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkDescriptorSetLayoutBinding bindings[RTPBR_LIGHTING_BINDING_COUNT];
    for (uint32_t i = 0; i < RTPBR_LIGHTING_BINDING_COUNT; ++i)
        bindings[i] = (VkDescriptorSetLayoutBinding){i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                                     VK_SHADER_STAGE_COMPUTE_BIT, NULL};
    bindings[RTPBR_BINDING_LIGHT_FRAME].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    bindings[RTPBR_BINDING_LIGHT_LIGHTS].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[RTPBR_BINDING_LIGHT_MATERIALS].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[RTPBR_BINDING_LIGHT_TILE_MASKS].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[RTPBR_BINDING_LIGHT_TILE_LISTS].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[RTPBR_BINDING_LIGHT_RADIANCE].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    RTPBR_TRY(create_set_layout(ctx, bindings, RTPBR_LIGHTING_BINDING_COUNT, &ctx->lighting_set_layout));
    RTPBR_TRY(create_pipeline_layout(ctx, ctx->lighting_set_layout, 0, 0, &ctx->lighting_layout));
    RTPBR_TRY(create_compute(ctx, SPIRV(rtpbr_spirv_cull_comp), ctx->lighting_layout, &ctx->cull_pipeline));
    RTPBR_TRY(create_compute(ctx, SPIRV(rtpbr_spirv_lighting_empty), ctx->lighting_layout,
                             &ctx->lighting_empty_pipeline));

    // The default variant (GGX, multiple scattering on) now, so that a bad driver fails early;
    // the others on first use (rtpbr_lighting_pipelines_get): each costs shader compilations.
    VkPipeline unused[RTPBR_TILE_CLASS_COUNT];
    RTPBR_TRY(rtpbr_lighting_pipelines_get(ctx, false, RTPBR_NDF_GGX_MODEL, RTPBR_MULTISCATTER_ON, unused));
cleanup:
    return result;
}

// The Monte Carlo lighting pass: the lighting pass's set layout (created first), its own
// pipeline layout with the push constants rtpbr_shader_mc.
static rtpbr_result create_lighting_mc(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkShaderModule module = VK_NULL_HANDLE;
    RTPBR_TRY(create_pipeline_layout(ctx, ctx->lighting_set_layout, VK_SHADER_STAGE_COMPUTE_BIT,
                                     sizeof(rtpbr_shader_mc), &ctx->lighting_mc_layout));
    // Its pipelines are made on first use (rtpbr_lighting_pipelines_get).
cleanup:
    vkDestroyShaderModule(ctx->device, module, NULL);
    return result;
}

// The supersampling resolve: two storage images, push constants rtpbr_shader_resolve.
static rtpbr_result create_resolve(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkShaderModule module = VK_NULL_HANDLE;
    VkDescriptorSetLayoutBinding bindings[2] = {
        {RTPBR_BINDING_RESOLVE_SOURCE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL},
        {RTPBR_BINDING_RESOLVE_TARGET, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL},
    };
    RTPBR_TRY(create_set_layout(ctx, bindings, 2, &ctx->resolve_set_layout));
    RTPBR_TRY(create_pipeline_layout(ctx, ctx->resolve_set_layout, VK_SHADER_STAGE_COMPUTE_BIT,
                                     sizeof(rtpbr_shader_resolve), &ctx->resolve_layout));
    RTPBR_TRY(rtpbr_shader_module(ctx, SPIRV(rtpbr_spirv_resolve_comp), &module));
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = module, .pName = "main"},
        .layout = ctx->resolve_layout,
    };
    RTPBR_VK(ctx, vkCreateComputePipelines(ctx->device, VK_NULL_HANDLE, 1, &info, NULL, &ctx->resolve_pipeline));
cleanup:
    vkDestroyShaderModule(ctx->device, module, NULL);
    return result;
}

static rtpbr_result create_tonemap(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkDescriptorSetLayoutBinding binding = {RTPBR_BINDING_TONEMAP_RADIANCE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1,
                                            VK_SHADER_STAGE_FRAGMENT_BIT, NULL};
    RTPBR_TRY(create_set_layout(ctx, &binding, 1, &ctx->tonemap_set_layout));
    RTPBR_TRY(create_pipeline_layout(ctx, ctx->tonemap_set_layout, VK_SHADER_STAGE_FRAGMENT_BIT,
                                     sizeof(rtpbr_shader_tonemap), &ctx->tonemap_layout));
    RTPBR_TRY(rtpbr_shader_module(ctx, SPIRV(rtpbr_spirv_tonemap_vert), &ctx->tonemap_vert));
    RTPBR_TRY(rtpbr_shader_module(ctx, SPIRV(rtpbr_spirv_tonemap_frag), &ctx->tonemap_frag));
cleanup:
    return result;
}

rtpbr_result rtpbr_pipelines_create(rtpbr_context *ctx)
{
    rtpbr_result result = create_gbuffer(ctx);
    if (result == RTPBR_SUCCESS) result = create_lighting(ctx);
    if (result == RTPBR_SUCCESS) result = create_lighting_mc(ctx);
    if (result == RTPBR_SUCCESS) result = create_resolve(ctx);
    if (result == RTPBR_SUCCESS) result = create_tonemap(ctx);
    if (result == RTPBR_SUCCESS) result = rtpbr_shadow_layouts_create(ctx);
    if (result == RTPBR_SUCCESS) {
        // The renderer's own display target: created now so that a bad driver fails early.
        VkPipeline unused;
        result = rtpbr_tonemap_pipeline_get(ctx, RTPBR_DISPLAY_FORMAT, &unused);
    }
    return result; // the caller destroys a half-built set through rtpbr_pipelines_destroy
}

void rtpbr_pipelines_destroy(rtpbr_context *ctx)
{
    VkDevice dev = ctx->device;
    rtpbr_shadow_pipelines_destroy(ctx);
    for (uint32_t i = 0; i < RTPBR_TONEMAP_PIPELINE_CACHE; ++i)
        vkDestroyPipeline(dev, ctx->tonemap_pipelines[i].pipeline, NULL);
    vkDestroyShaderModule(dev, ctx->tonemap_vert, NULL);
    vkDestroyShaderModule(dev, ctx->tonemap_frag, NULL);
    vkDestroyPipelineLayout(dev, ctx->tonemap_layout, NULL);
    vkDestroyDescriptorSetLayout(dev, ctx->tonemap_set_layout, NULL);
    vkDestroyPipeline(dev, ctx->resolve_pipeline, NULL);
    vkDestroyPipelineLayout(dev, ctx->resolve_layout, NULL);
    vkDestroyDescriptorSetLayout(dev, ctx->resolve_set_layout, NULL);
    for (uint32_t i = 0; i < RTPBR_LIGHTING_VARIANT_COUNT; ++i)
        for (uint32_t c = 0; c < RTPBR_LIT_CLASS_COUNT; ++c) vkDestroyPipeline(dev, ctx->lighting_pipelines[i][c], NULL);
    vkDestroyPipeline(dev, ctx->lighting_empty_pipeline, NULL);
    vkDestroyPipeline(dev, ctx->cull_pipeline, NULL);
    vkDestroyPipelineLayout(dev, ctx->lighting_layout, NULL);
    for (uint32_t i = 0; i < RTPBR_LIGHTING_VARIANT_COUNT; ++i)
        vkDestroyPipeline(dev, ctx->lighting_mc_pipelines[i], NULL);
    vkDestroyPipelineLayout(dev, ctx->lighting_mc_layout, NULL);
    vkDestroyDescriptorSetLayout(dev, ctx->lighting_set_layout, NULL);
    vkDestroyPipeline(dev, ctx->gbuffer_pipeline, NULL);
    vkDestroyPipelineLayout(dev, ctx->gbuffer_layout, NULL);
    vkDestroyDescriptorSetLayout(dev, ctx->gbuffer_set_layout, NULL);
    vkDestroyDescriptorSetLayout(dev, ctx->material_set_layout, NULL);
}

rtpbr_result rtpbr_lighting_pipelines_get(rtpbr_context *ctx, bool monte_carlo, rtpbr_ndf ndf, rtpbr_multiscatter ms,
                                          VkPipeline out[RTPBR_TILE_CLASS_COUNT])
{
    static const rtpbr_spirv ltc[RTPBR_LIGHTING_VARIANT_COUNT][RTPBR_LIT_CLASS_COUNT] = {
        {SPIRV(rtpbr_spirv_lighting_ggx_ms0_basic), SPIRV(rtpbr_spirv_lighting_ggx_ms0_full)},
        {SPIRV(rtpbr_spirv_lighting_ggx_ms1_basic), SPIRV(rtpbr_spirv_lighting_ggx_ms1_full)},
        {SPIRV(rtpbr_spirv_lighting_beckmann_ms0_basic), SPIRV(rtpbr_spirv_lighting_beckmann_ms0_full)},
        {SPIRV(rtpbr_spirv_lighting_beckmann_ms1_basic), SPIRV(rtpbr_spirv_lighting_beckmann_ms1_full)},
    };
    static const rtpbr_spirv mc[RTPBR_LIGHTING_VARIANT_COUNT] = {
        SPIRV(rtpbr_spirv_lighting_mc_ggx_ms0), SPIRV(rtpbr_spirv_lighting_mc_ggx_ms1),
        SPIRV(rtpbr_spirv_lighting_mc_beckmann_ms0), SPIRV(rtpbr_spirv_lighting_mc_beckmann_ms1),
    };
    _Static_assert(RTPBR_TILE_CLASS_EMPTY == 0 && RTPBR_TILE_CLASS_BASIC == 1 && RTPBR_TILE_CLASS_FULL == 2,
                   "lit classes follow the empty one");
    uint32_t v = lighting_variant(ndf, ms);
    rtpbr_result result = RTPBR_SUCCESS;
    if (monte_carlo) {
        if (!ctx->lighting_mc_pipelines[v])
            RTPBR_TRY(create_compute(ctx, mc[v], ctx->lighting_mc_layout, &ctx->lighting_mc_pipelines[v]));
        out[0] = ctx->lighting_mc_pipelines[v];
        return RTPBR_SUCCESS;
    }
    out[RTPBR_TILE_CLASS_EMPTY] = ctx->lighting_empty_pipeline;
    for (uint32_t c = 0; c < RTPBR_LIT_CLASS_COUNT; ++c) {
        if (!ctx->lighting_pipelines[v][c])
            RTPBR_TRY(create_compute(ctx, ltc[v][c], ctx->lighting_layout, &ctx->lighting_pipelines[v][c]));
        out[RTPBR_TILE_CLASS_BASIC + c] = ctx->lighting_pipelines[v][c];
    }
cleanup:
    return result;
}

rtpbr_result rtpbr_tonemap_pipeline_get(rtpbr_context *ctx, VkFormat format, VkPipeline *out)
{
    uint32_t slot = RTPBR_TONEMAP_PIPELINE_CACHE;
    for (uint32_t i = 0; i < RTPBR_TONEMAP_PIPELINE_CACHE; ++i) {
        if (ctx->tonemap_pipelines[i].pipeline && ctx->tonemap_pipelines[i].format == format) {
            *out = ctx->tonemap_pipelines[i].pipeline;
            return RTPBR_SUCCESS;
        }
        if (!ctx->tonemap_pipelines[i].pipeline && slot == RTPBR_TONEMAP_PIPELINE_CACHE) slot = i;
    }
    if (slot == RTPBR_TONEMAP_PIPELINE_CACHE) {
        rtpbr_log(ctx, RTPBR_LOG_ERROR, "more than %u different target formats used with rtpbr_record",
                  RTPBR_TONEMAP_PIPELINE_CACHE);
        return RTPBR_ERROR_LIMIT_EXCEEDED;
    }
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx->physical_device, format, &props);
    if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT)) {
        rtpbr_log(ctx, RTPBR_LOG_ERROR, "target format %d does not support colour attachments", (int)format);
        return RTPBR_ERROR_MISSING_FEATURE;
    }
    graphics_desc d = {
        .vert = ctx->tonemap_vert,
        .frag = ctx->tonemap_frag,
        .layout = ctx->tonemap_layout,
        .color_formats = &format,
        .color_count = 1,
        .depth_format = VK_FORMAT_UNDEFINED,
    };
    rtpbr_result result = create_graphics(ctx, &d, &ctx->tonemap_pipelines[slot].pipeline);
    if (result != RTPBR_SUCCESS) return result;
    ctx->tonemap_pipelines[slot].format = format;
    *out = ctx->tonemap_pipelines[slot].pipeline;
    return RTPBR_SUCCESS;
}
