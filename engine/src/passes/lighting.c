// Lighting pass: the tile cull (cull.comp) writes each tile's light mask and queues the tile
// for its class; then one indirect dispatch per class runs that class's LTC variant
// (lighting.comp) over its queue, turning the G-buffer into linear radiance; with
// supersampling, the resolve (resolve.c) box-filters it down to the output.
#include <stddef.h>

#include "passes.h"

#include "../internal.h"
#include "pipeline.h"
#include "rtpbr_spirv_cull_comp.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_basic.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_full.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_basic_spheres.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_full_spheres.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_basic.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_full.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_basic_spheres.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_full_spheres.h"
#include "rtpbr_spirv_lighting_empty.h"
#include "rtpbr_spirv_lighting_ggx_ms0_basic.h"
#include "rtpbr_spirv_lighting_ggx_ms0_full.h"
#include "rtpbr_spirv_lighting_ggx_ms0_basic_spheres.h"
#include "rtpbr_spirv_lighting_ggx_ms0_full_spheres.h"
#include "rtpbr_spirv_lighting_ggx_ms1_basic.h"
#include "rtpbr_spirv_lighting_ggx_ms1_full.h"
#include "rtpbr_spirv_lighting_ggx_ms1_basic_spheres.h"
#include "rtpbr_spirv_lighting_ggx_ms1_full_spheres.h"
#include "rtpbr_spirv_lighting_ggx_ms0_basic_textured.h"
#include "rtpbr_spirv_lighting_ggx_ms0_full_textured.h"
#include "rtpbr_spirv_lighting_ggx_ms1_basic_textured.h"
#include "rtpbr_spirv_lighting_ggx_ms1_full_textured.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_basic_textured.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_full_textured.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_basic_textured.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_full_textured.h"
#include "rtpbr_spirv_lighting_ggx_ms0_basic_tubes.h"
#include "rtpbr_spirv_lighting_ggx_ms0_full_tubes.h"
#include "rtpbr_spirv_lighting_ggx_ms1_basic_tubes.h"
#include "rtpbr_spirv_lighting_ggx_ms1_full_tubes.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_basic_tubes.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_full_tubes.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_basic_tubes.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_full_tubes.h"
#include "rtpbr_spirv_lighting_ggx_ms0_basic_tubes_cpu.h"
#include "rtpbr_spirv_lighting_ggx_ms0_full_tubes_cpu.h"
#include "rtpbr_spirv_lighting_ggx_ms1_basic_tubes_cpu.h"
#include "rtpbr_spirv_lighting_ggx_ms1_full_tubes_cpu.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_basic_tubes_cpu.h"
#include "rtpbr_spirv_lighting_beckmann_ms0_full_tubes_cpu.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_basic_tubes_cpu.h"
#include "rtpbr_spirv_lighting_beckmann_ms1_full_tubes_cpu.h"

// The set of the cull, LTC and Monte Carlo passes (rtpbr_shared.h: RTPBR_BINDING_LIGHT_*).
#define COMPUTE(binding, type) {binding, VK_DESCRIPTOR_TYPE_##type, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL}
static const VkDescriptorSetLayoutBinding bindings[] = {
    COMPUTE(RTPBR_BINDING_LIGHT_FRAME, UNIFORM_BUFFER),
    COMPUTE(RTPBR_BINDING_LIGHT_LIGHTS, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_LIGHT_GBUFFER0, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_GBUFFER1, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_GBUFFER2, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_GBUFFER3, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_DEPTH, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_RADIANCE, STORAGE_IMAGE),
    COMPUTE(RTPBR_BINDING_LUT_LTC_GGX_1, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_LTC_GGX_2, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_LTC_BECKMANN_1, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_LTC_BECKMANN_2, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_KC_E, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_KC_EAVG, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_KC_EF, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_KC_EFAVG, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_LTC_DISNEY_1, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_LTC_DISNEY_2, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_SHEEN_E, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_LTC_SHEEN_1, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LUT_LTC_SHEEN_2, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_MATERIALS, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_LIGHT_TILE_MASKS, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_LIGHT_TILE_LISTS, STORAGE_BUFFER),
    COMPUTE(RTPBR_BINDING_LIGHT_SHADOW_RATIO, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_GBUFFER4, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_GBUFFER5, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_GBUFFER6, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_TEXTURES, COMBINED_IMAGE_SAMPLER),
    COMPUTE(RTPBR_BINDING_LIGHT_LIGHTS_UNIFORM, UNIFORM_BUFFER),
};
// The binding of each G-buffer image (renderer.gbuffer[i]).
static const uint32_t gbuffer_bindings[RTPBR_GBUFFER_COUNT] = {
    RTPBR_BINDING_LIGHT_GBUFFER0, RTPBR_BINDING_LIGHT_GBUFFER1, RTPBR_BINDING_LIGHT_GBUFFER2,
    RTPBR_BINDING_LIGHT_GBUFFER3, RTPBR_BINDING_LIGHT_GBUFFER4, RTPBR_BINDING_LIGHT_GBUFFER5,
    RTPBR_BINDING_LIGHT_GBUFFER6};
#undef COMPUTE
_Static_assert(sizeof bindings / sizeof bindings[0] == RTPBR_LIGHTING_BINDING_COUNT, "every lighting binding");
_Static_assert(RTPBR_BINDING_LUT_LTC_SHEEN_2 + 1 == RTPBR_BINDING_LUT_LTC_GGX_1 + RTPBR_LUT_COUNT, "LUT bindings");

uint32_t rtpbr_lighting_gbuffer_binding(uint32_t i)
{
    return gbuffer_bindings[i];
}

uint32_t rtpbr_lighting_variant(rtpbr_ndf ndf, rtpbr_multiscatter ms)
{
    uint32_t n = ndf == RTPBR_NDF_BECKMANN_MODEL ? 1 : 0;
    uint32_t m = ms == RTPBR_MULTISCATTER_OFF ? 0 : 1;
    return n * 2 + m;
}

rtpbr_result rtpbr_lighting_pass_init(rtpbr_context *ctx)
{
    rtpbr_lighting_pass *pass = &ctx->lighting;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_pass_layouts_create(ctx, RTPBR_BINDINGS(bindings), 0, 0, &pass->set_layout, &pass->layout));
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(ctx->physical_device, &props);
    pass->cpu_device = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    pass->uniform_lights = pass->cpu_device && props.limits.maxUniformBufferRange >= RTPBR_UNIFORM_LIGHTS_BYTES;
    // (the binding is written on every device, read only where uniform_lights: within the range)
    pass->uniform_lights_range = props.limits.maxUniformBufferRange < RTPBR_UNIFORM_LIGHTS_BYTES
                                     ? props.limits.maxUniformBufferRange
                                     : RTPBR_UNIFORM_LIGHTS_BYTES;
    RTPBR_TRY(rtpbr_compute_pipeline_create(ctx, RTPBR_SPIRV(rtpbr_spirv_cull_comp), pass->layout, &pass->cull));
    // The empty tiles' variant with and without the G-buffer's emission (RTPBR_SPEC_LIGHTING_EMISSION).
    for (uint32_t e = 0; e < 2; ++e) {
        const VkBool32 emission = e;
        const VkSpecializationMapEntry entry = {RTPBR_SPEC_LIGHTING_EMISSION, 0, sizeof emission};
        const VkSpecializationInfo specialization = {1, &entry, sizeof emission, &emission};
        RTPBR_TRY(rtpbr_compute_pipeline_create_specialized(ctx, RTPBR_SPIRV(rtpbr_spirv_lighting_empty), pass->layout,
                                                            &specialization, &pass->empty[e]));
    }
    // The default variant (GGX, multiple scattering on) for polygons of up to 4 vertices now, so
    // that a bad driver fails early; the others on first use (rtpbr_lighting_pipelines_get):
    // each costs shader compilations.
    VkPipeline unused[RTPBR_TILE_CLASS_COUNT];
    const rtpbr_lighting_needs quads = {.shapes = 0, .max_vertices = 4, .punctual = false, .material_features = 0};
    RTPBR_TRY(rtpbr_lighting_pipelines_get(ctx, RTPBR_NDF_GGX_MODEL, RTPBR_MULTISCATTER_ON, &quads, unused));
cleanup:
    return result; // the caller finishes a half-built pass
}

void rtpbr_lighting_pass_finish(rtpbr_context *ctx)
{
    rtpbr_lighting_pass *pass = &ctx->lighting;
    for (uint32_t v = 0; v < RTPBR_LIGHTING_VARIANT_COUNT; ++v)
        for (uint32_t c = 0; c < RTPBR_LIT_CLASS_COUNT; ++c)
            for (uint32_t s = 0; s < RTPBR_LIGHTING_SPEC_COUNT; ++s) vkDestroyPipeline(ctx->device, pass->ltc[v][c][s], NULL);
    const VkPipeline fixed[3] = {pass->empty[0], pass->empty[1], pass->cull};
    rtpbr_pass_objects_destroy(ctx, fixed, 3, pass->layout, pass->set_layout);
    // (the Monte Carlo pipelines and layout are lighting_mc.c's)
    for (uint32_t v = 0; v < RTPBR_LIGHTING_VARIANT_COUNT; ++v)
        for (uint32_t c = 0; c < RTPBR_LIT_CLASS_COUNT; ++c)
            for (uint32_t s = 0; s < RTPBR_LIGHTING_SPEC_COUNT; ++s) pass->ltc[v][c][s] = VK_NULL_HANDLE;
    pass->empty[0] = pass->empty[1] = pass->cull = VK_NULL_HANDLE;
    pass->layout = VK_NULL_HANDLE;
    pass->set_layout = VK_NULL_HANDLE;
}

// The LTC pipelines' specialization constants (shade_lights.glsl, shading.glsl:
// RTPBR_SPEC_LIGHTING_*).
typedef struct lighting_constants {
    uint32_t max_vertices;
    VkBool32 punctual;
    uint32_t material_features;
    VkBool32 cpu; // (the context's device: the same for all its pipelines)
    VkBool32 uniform_lights;
    VkBool32 streak; // (false only in RTPBR_TILE_CLASS_BASIC_NO_STREAK's pipeline)
    VkBool32 shadows;
} lighting_constants;

rtpbr_result rtpbr_lighting_pipelines_get(rtpbr_context *ctx, rtpbr_ndf ndf, rtpbr_multiscatter ms,
                                          const rtpbr_lighting_needs *needs, VkPipeline out[RTPBR_TILE_CLASS_COUNT])
{
#define LTC_CLASSES(ndf, ms)                                                                      \
    {RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_basic), RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_full), \
     RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_basic_spheres),                                     \
     RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_full_spheres),                                      \
     RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_basic_textured),                                    \
     RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_full_textured),                                     \
     RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_basic_tubes),                                       \
     RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_full_tubes)}
    static const rtpbr_spirv ltc[RTPBR_LIGHTING_VARIANT_COUNT][RTPBR_LIT_CLASS_COUNT] = {
        LTC_CLASSES(ggx, ms0), LTC_CLASSES(ggx, ms1), LTC_CLASSES(beckmann, ms0), LTC_CLASSES(beckmann, ms1)};
#undef LTC_CLASSES
    // The tube classes on a CPU device: a tube's parts unrolled (engine/shaders/meson.build)
#define TUBES_CPU(ndf, ms)                                                                        \
    {RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_basic_tubes_cpu),                            \
     RTPBR_SPIRV(rtpbr_spirv_lighting_##ndf##_##ms##_full_tubes_cpu)}
    static const rtpbr_spirv tubes_cpu[RTPBR_LIGHTING_VARIANT_COUNT][2] = {
        TUBES_CPU(ggx, ms0), TUBES_CPU(ggx, ms1), TUBES_CPU(beckmann, ms0), TUBES_CPU(beckmann, ms1)};
#undef TUBES_CPU
    _Static_assert(RTPBR_TILE_CLASS_EMPTY == 0 && RTPBR_TILE_CLASS_BASIC == 1 && RTPBR_TILE_CLASS_FULL == 2 &&
                       RTPBR_TILE_CLASS_BASIC_SPHERES == 3 && RTPBR_TILE_CLASS_FULL_SPHERES == 4 &&
                       RTPBR_TILE_CLASS_BASIC_TEXTURED == 5 && RTPBR_TILE_CLASS_FULL_TEXTURED == 6 &&
                       RTPBR_TILE_CLASS_BASIC_TUBES == 7 && RTPBR_TILE_CLASS_FULL_TUBES == 8 &&
                       RTPBR_TILE_CLASS_BASIC_NO_STREAK == 9 && RTPBR_TILE_CLASS_COUNT == 10,
                   "lit classes follow the empty one, the spheres' after the others, the textured, the tubes, "
                   "then the basic class without the streak estimate");
    rtpbr_lighting_pass *pass = &ctx->lighting;
    uint32_t v = rtpbr_lighting_variant(ndf, ms);
    rtpbr_result result = RTPBR_SUCCESS;
    // The specialization: polygons of up to 3, 4 or 8 vertices, punctual lights or none, in
    // the full classes the materials' features (the basic ones compile them out anyway: one
    // pipeline for all, with the default), and on a CPU device the lights read from the uniform
    // buffer where they fit (RTPBR_UNIFORM_LIGHTS_MAX), and the shadow ratios read or not
    // (RTPBR_SPEC_LIGHTING_SHADOWS); a pipeline per combination, compiled on first use.
    _Static_assert(RTPBR_MATERIAL_FLAGS_FULL == 0x3cu, "the full variant's features: bits 2 to 5");
    lighting_constants constants = {
        .max_vertices = needs->max_vertices <= 3 ? 3u : needs->max_vertices <= 4 ? 4u : RTPBR_SHADER_MAX_POLYGON_VERTICES,
        .punctual = needs->punctual ? VK_TRUE : VK_FALSE,
        .cpu = pass->cpu_device ? VK_TRUE : VK_FALSE,
        .uniform_lights = pass->uniform_lights && needs->light_count <= RTPBR_UNIFORM_LIGHTS_MAX ? VK_TRUE : VK_FALSE,
        .streak = VK_TRUE,
        .shadows = needs->shadows ? VK_TRUE : VK_FALSE,
    };
    const VkSpecializationMapEntry entries[7] = {
        {RTPBR_SPEC_LIGHTING_MAX_VERTICES, offsetof(lighting_constants, max_vertices), sizeof(uint32_t)},
        {RTPBR_SPEC_LIGHTING_PUNCTUAL, offsetof(lighting_constants, punctual), sizeof(VkBool32)},
        {RTPBR_SPEC_LIGHTING_MATERIALS, offsetof(lighting_constants, material_features), sizeof(uint32_t)},
        {RTPBR_SPEC_LIGHTING_CPU, offsetof(lighting_constants, cpu), sizeof(VkBool32)},
        {RTPBR_SPEC_LIGHTING_UNIFORM_LIGHTS, offsetof(lighting_constants, uniform_lights), sizeof(VkBool32)},
        {RTPBR_SPEC_LIGHTING_STREAK, offsetof(lighting_constants, streak), sizeof(VkBool32)},
        {RTPBR_SPEC_LIGHTING_SHADOWS, offsetof(lighting_constants, shadows), sizeof(VkBool32)},
    };
    const VkSpecializationInfo specialization = {7, entries, sizeof constants, &constants};
    out[RTPBR_TILE_CLASS_EMPTY] = pass->empty[needs->emission ? 1 : 0];
    for (uint32_t c = 0; c < RTPBR_LIT_CLASS_COUNT; ++c) {
        // the spheres' classes only for a frame with a sphere or a disk, the textured ones only
        // for a frame with a textured quad, the tubes' for one with a tube (shapes: rtpbr_lights_shapes; no tile is queued for
        // the others: their slots get a class's pipeline that is compiled, never dispatched);
        // the basic class without the streak estimate (lit class 8, its own cache slot k) is
        // the basic class's code (k = 0) with the estimate specialized out (on Beckmann, which
        // has no estimate, the same code again: it reads its class's own queue, lighting.comp)
        bool noStreak = c == RTPBR_TILE_CLASS_BASIC_NO_STREAK - RTPBR_TILE_CLASS_BASIC;
        uint32_t k = noStreak || c < 2u * (needs->shapes + 1u) ? c : c % 2u + 2u * needs->shapes;
        bool full = !noStreak && k % 2u == 1u; // (RTPBR_TILE_CLASS_FULL, _FULL_SPHERES, ...: lit class 1, 3, 5, 7)
        constants.streak = noStreak ? VK_FALSE : VK_TRUE;
        constants.material_features = full ? needs->material_features & RTPBR_MATERIAL_FLAGS_FULL : RTPBR_MATERIAL_FLAGS_FULL;
        uint32_t s = (constants.max_vertices == 3 ? 0u : constants.max_vertices == 4 ? 1u : 2u) +
                     3u * constants.punctual + 6u * (constants.material_features >> 2) + 96u * constants.uniform_lights +
                     192u * constants.shadows;
        const rtpbr_spirv *code = noStreak ? &ltc[v][0]
                                  : pass->cpu_device && k >= RTPBR_TILE_CLASS_BASIC_TUBES - 1u
                                      ? &tubes_cpu[v][k - (RTPBR_TILE_CLASS_BASIC_TUBES - 1u)]
                                      : &ltc[v][k];
        if (!pass->ltc[v][k][s])
            RTPBR_TRY(rtpbr_compute_pipeline_create_specialized(ctx, *code, pass->layout, &specialization,
                                                                &pass->ltc[v][k][s]));
        out[RTPBR_TILE_CLASS_BASIC + c] = pass->ltc[v][k][s];
    }
cleanup:
    return result;
}

rtpbr_result rtpbr_lighting_tile_buffers_create(rtpbr_context *ctx, uint32_t tiles_x, uint32_t tiles_y,
                                                rtpbr_buffer *masks, rtpbr_buffer *lists)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkDeviceSize tiles = (VkDeviceSize)tiles_x * tiles_y;
    RTPBR_TRY(rtpbr_buffer_create_device(ctx, tiles * RTPBR_TILE_MASK_STRIDE * sizeof(uint32_t),
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, masks));
    RTPBR_TRY(rtpbr_buffer_create_device(ctx, (RTPBR_TILE_QUEUE_SLOTS * 4 + RTPBR_TILE_CLASS_COUNT * tiles) * sizeof(uint32_t),
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                             VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                         lists));
cleanup:
    return result; // the caller destroys both (rtpbr_buffer_destroy accepts a zeroed buffer)
}

// Everything but the scene's buffers is fixed for the renderer's lifetime.
rtpbr_result rtpbr_lighting_renderer_init(rtpbr_renderer *r)
{
    rtpbr_context *ctx = r->context;
    rtpbr_result result = RTPBR_SUCCESS;
    RTPBR_TRY(rtpbr_descriptor_set_create(ctx, RTPBR_BINDINGS(bindings), ctx->lighting.set_layout, &r->lighting_set));
    VkDescriptorSet set = r->lighting_set.set;
    const rtpbr_bindings table = RTPBR_BINDINGS(bindings);
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    rtpbr_descriptor_write_buffer(ctx, table, set, RTPBR_BINDING_LIGHT_FRAME, r->frame.buffer, sizeof(rtpbr_shader_frame));
    rtpbr_descriptor_write_buffer(ctx, table, set, RTPBR_BINDING_LIGHT_TILE_MASKS, r->tile_masks.buffer, VK_WHOLE_SIZE);
    rtpbr_descriptor_write_buffer(ctx, table, set, RTPBR_BINDING_LIGHT_TILE_LISTS, r->tile_lists.buffer, VK_WHOLE_SIZE);
    for (uint32_t i = 0; i < RTPBR_GBUFFER_COUNT; ++i)
        rtpbr_descriptor_write_image(ctx, table, set, gbuffer_bindings[i], ctx->gbuffer_sampler,
                                     r->gbuffer[i].view, read);
    rtpbr_descriptor_write_image(ctx, table, set, RTPBR_BINDING_LIGHT_DEPTH, ctx->gbuffer_sampler, r->depth.view, read);
    const rtpbr_image *shaded = r->supersample > 1 ? &r->radiance_ss : &r->radiance;
    rtpbr_descriptor_write_image(ctx, table, set, RTPBR_BINDING_LIGHT_RADIANCE, VK_NULL_HANDLE, shaded->view,
                                 VK_IMAGE_LAYOUT_GENERAL);
    for (uint32_t i = 0; i < RTPBR_LUT_COUNT; ++i)
        rtpbr_descriptor_write_image(ctx, table, set, RTPBR_BINDING_LUT_LTC_GGX_1 + i, ctx->lut_sampler,
                                     ctx->luts[i].image.view, read);
    // The shadow ratios stay in GENERAL layout (shadow.c), read with texelFetch.
    rtpbr_descriptor_write_image(ctx, table, set, RTPBR_BINDING_LIGHT_SHADOW_RATIO, ctx->gbuffer_sampler,
                                 r->shadow_ratio.view, VK_IMAGE_LAYOUT_GENERAL);
cleanup:
    return result;
}

rtpbr_result rtpbr_lighting_sets_create(rtpbr_context *ctx, uint32_t count, VkDescriptorPool *pool,
                                        VkDescriptorSet *sets)
{
    rtpbr_result result = RTPBR_SUCCESS;
    VkDescriptorSetLayout layouts[RTPBR_MAX_FRAMES_IN_FLIGHT];
    for (uint32_t i = 0; i < count; ++i) layouts[i] = ctx->lighting.set_layout;
    RTPBR_TRY(rtpbr_descriptor_pool_create(ctx, RTPBR_BINDINGS(bindings), count, pool));
    VkDescriptorSetAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = *pool,
        .descriptorSetCount = count,
        .pSetLayouts = layouts,
    };
    RTPBR_VK(&ctx->host, vkAllocateDescriptorSets(ctx->device, &alloc, sets));
cleanup:
    return result;
}

void rtpbr_lighting_write_buffer(rtpbr_context *ctx, VkDescriptorSet set, uint32_t binding, VkBuffer buffer,
                                 VkDeviceSize offset, VkDeviceSize range)
{
    rtpbr_descriptor_write_buffer_range(ctx, RTPBR_BINDINGS(bindings), set, binding, buffer, offset, range);
}

void rtpbr_lighting_write_image(rtpbr_context *ctx, VkDescriptorSet set, uint32_t binding, VkImageView view,
                                VkImageLayout layout)
{
    VkSampler sampler = binding == RTPBR_BINDING_LIGHT_RADIANCE ? VK_NULL_HANDLE : ctx->gbuffer_sampler;
    rtpbr_descriptor_write_image(ctx, RTPBR_BINDINGS(bindings), set, binding, sampler, view, layout);
}

void rtpbr_lighting_write_luts(rtpbr_context *ctx, VkDescriptorSet set)
{
    // (and the light textures' stand-in: a light set has no textured lights)
    rtpbr_descriptor_write_image(ctx, RTPBR_BINDINGS(bindings), set, RTPBR_BINDING_LIGHT_TEXTURES,
                                 ctx->light_texture_sampler, ctx->light_texture_stand_in.view,
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    for (uint32_t i = 0; i < RTPBR_LUT_COUNT; ++i)
        rtpbr_descriptor_write_image(ctx, RTPBR_BINDINGS(bindings), set, RTPBR_BINDING_LUT_LTC_GGX_1 + i,
                                     ctx->lut_sampler, ctx->luts[i].image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

void rtpbr_lighting_renderer_finish(rtpbr_renderer *r)
{
    rtpbr_descriptor_set_destroy(r->context, &r->lighting_set);
}

void rtpbr_lighting_bind_scene(rtpbr_renderer *r, const rtpbr_gpu_scene *scene)
{
    const rtpbr_buffer_write writes[] = {
        {RTPBR_BINDING_LIGHT_MATERIALS, scene->materials.buffer},
        {RTPBR_BINDING_LIGHT_LIGHTS, scene->lights.buffer},
    };
    rtpbr_descriptor_write_buffers(r->context, RTPBR_BINDINGS(bindings), r->lighting_set.set, writes, 2);
    // (the scene's buffer holds RTPBR_MAX_LIGHTS records: the uniform binding its first ones)
    _Static_assert(RTPBR_MAX_LIGHTS * sizeof(rtpbr_shader_light) >= RTPBR_UNIFORM_LIGHTS_BYTES, "uniform range");
    rtpbr_descriptor_write_buffer_range(r->context, RTPBR_BINDINGS(bindings), r->lighting_set.set,
                                        RTPBR_BINDING_LIGHT_LIGHTS_UNIFORM, scene->lights.buffer, 0,
                                        r->context->lighting.uniform_lights_range);
    rtpbr_descriptor_write_image(r->context, RTPBR_BINDINGS(bindings), r->lighting_set.set, RTPBR_BINDING_LIGHT_TEXTURES,
                                 r->context->light_texture_sampler, rtpbr_gpu_scene_light_texture_view(scene),
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

// The image the lighting pass writes: the output, or its supersampled version.
static VkImage shade_target(const rtpbr_renderer *r)
{
    return r->supersample > 1 ? r->radiance_ss.image : r->radiance.image;
}

// The barrier before a lighting pass writes its target (its previous readers: tone mapping,
// readback, resolve, or the host's), then the binds.
static void begin_target(const rtpbr_lighting_target *t, VkPipeline pipeline, VkPipelineLayout layout,
                         VkCommandBuffer cmd)
{
    rtpbr_image_barrier(cmd, t->output, VK_IMAGE_ASPECT_COLOR_BIT, t->output_old_layout, VK_IMAGE_LAYOUT_GENERAL,
                        t->output_src_stages, t->output_src_access, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                        VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &t->set, 0, NULL);
}

// The renderer's lighting target: its own set, tile buffers and shading image.
static rtpbr_lighting_target renderer_target(const rtpbr_renderer *r)
{
    return (rtpbr_lighting_target){
        .set = r->lighting_set.set,
        .tile_lists = r->tile_lists.buffer,
        .tiles_x = r->tiles_x,
        .tiles_y = r->tiles_y,
        .output = shade_target(r),
        // The previous frame's tone mapping, readback or resolve read the image.
        .output_old_layout = VK_IMAGE_LAYOUT_UNDEFINED,
        .output_src_stages = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
        .output_src_access = 0,
    };
}

void rtpbr_lighting_begin(rtpbr_renderer *r, VkPipeline pipeline, VkPipelineLayout layout, VkCommandBuffer cmd)
{
    rtpbr_lighting_target t = renderer_target(r);
    begin_target(&t, pipeline, layout, cmd);
}

void rtpbr_lighting_end(rtpbr_renderer *r, VkCommandBuffer cmd)
{
    if (r->supersample > 1) rtpbr_resolve_record(r, cmd);
    rtpbr_image_barrier(cmd, r->radiance.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                        VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

// The LTC pass: the culling pass (cull.comp) writes each tile's light mask and queues the tile
// for its class; then one indirect dispatch per class runs that class's lighting variant over
// its queue (no barrier inside either kernel).
void rtpbr_lighting_record_target(const rtpbr_context *ctx, const rtpbr_lighting_target *t,
                                  const VkPipeline pipelines[RTPBR_TILE_CLASS_COUNT], VkCommandBuffer cmd)
{
    // Empty queues: VkDispatchIndirectCommand (0, 1, 1) per class (the previous frame's lighting
    // read them as indirect arguments and as storage).
    uint32_t empty[RTPBR_TILE_QUEUE_SLOTS][4]; // (the slots past the classes' unused)
    for (uint32_t c = 0; c < RTPBR_TILE_QUEUE_SLOTS; ++c) {
        empty[c][0] = 0;
        empty[c][1] = empty[c][2] = 1;
        empty[c][3] = 0;
    }
    VkBufferMemoryBarrier before = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT,
        .dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = t->tile_lists,
        .size = VK_WHOLE_SIZE,
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, NULL, 1, &before, 0, NULL);
    vkCmdUpdateBuffer(cmd, t->tile_lists, 0, sizeof empty, empty);
    VkBufferMemoryBarrier cleared = before;
    cleared.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    cleared.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, NULL, 1,
                         &cleared, 0, NULL);

    begin_target(t, ctx->lighting.cull, ctx->lighting.layout, cmd);
    vkCmdDispatch(cmd, (t->tiles_x + RTPBR_CULL_GROUP - 1) / RTPBR_CULL_GROUP,
                  (t->tiles_y + RTPBR_CULL_GROUP - 1) / RTPBR_CULL_GROUP, 1);
    VkMemoryBarrier culled = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT,
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1, &culled, 0,
                         NULL, 0, NULL);
    for (uint32_t c = 0; c < RTPBR_TILE_CLASS_COUNT; ++c) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[c]);
        vkCmdDispatchIndirect(cmd, t->tile_lists, c * 4 * sizeof(uint32_t));
    }
}

void rtpbr_lighting_ltc_record(rtpbr_renderer *r, const VkPipeline pipelines[RTPBR_TILE_CLASS_COUNT], VkCommandBuffer cmd)
{
    rtpbr_lighting_target t = renderer_target(r);
    rtpbr_lighting_record_target(r->context, &t, pipelines, cmd);
}
