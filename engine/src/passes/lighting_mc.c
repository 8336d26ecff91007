// The brute-force Monte Carlo lighting pass (lighting_mc.comp; rtpbr_render_desc.mc_samples):
// the LTC pass's descriptor set, dispatch and barriers (lighting.c), with the sample count and
// seed as push constants, one workgroup per tile and no culling, in as many dispatches as
// lavapipe's loop budget asks for (below).
#include "passes.h"

#include "../internal.h"
#include "pipeline.h"
#include "rtpbr_spirv_lighting_mc_beckmann_ms0.h"
#include "rtpbr_spirv_lighting_mc_beckmann_ms1.h"
#include "rtpbr_spirv_lighting_mc_ggx_ms0.h"
#include "rtpbr_spirv_lighting_mc_ggx_ms1.h"

rtpbr_result rtpbr_lighting_mc_pass_init(rtpbr_context *ctx)
{
    // Its pipelines are made on first use (rtpbr_lighting_mc_pipeline_get).
    return rtpbr_pipeline_layout_create(ctx, &ctx->lighting.set_layout, 1, VK_SHADER_STAGE_COMPUTE_BIT,
                                        sizeof(rtpbr_shader_mc), &ctx->lighting.mc_layout);
}

void rtpbr_lighting_mc_pass_finish(rtpbr_context *ctx)
{
    rtpbr_lighting_pass *pass = &ctx->lighting;
    for (uint32_t v = 0; v < RTPBR_LIGHTING_VARIANT_COUNT; ++v) {
        vkDestroyPipeline(ctx->device, pass->mc[v], NULL);
        pass->mc[v] = VK_NULL_HANDLE;
    }
    vkDestroyPipelineLayout(ctx->device, pass->mc_layout, NULL);
    pass->mc_layout = VK_NULL_HANDLE;
}

rtpbr_result rtpbr_lighting_mc_pipeline_get(rtpbr_context *ctx, rtpbr_ndf ndf, rtpbr_multiscatter ms, VkPipeline *out)
{
    static const rtpbr_spirv spirv[RTPBR_LIGHTING_VARIANT_COUNT] = {
        RTPBR_SPIRV(rtpbr_spirv_lighting_mc_ggx_ms0), RTPBR_SPIRV(rtpbr_spirv_lighting_mc_ggx_ms1),
        RTPBR_SPIRV(rtpbr_spirv_lighting_mc_beckmann_ms0), RTPBR_SPIRV(rtpbr_spirv_lighting_mc_beckmann_ms1),
    };
    rtpbr_lighting_pass *pass = &ctx->lighting;
    uint32_t v = rtpbr_lighting_variant(ndf, ms);
    rtpbr_result result = RTPBR_SUCCESS;
    if (!pass->mc[v]) RTPBR_TRY(rtpbr_compute_pipeline_create(ctx, spirv[v], pass->mc_layout, &pass->mc[v]));
    *out = pass->mc[v];
cleanup:
    return result;
}

// lavapipe (llvmpipe) ends every loop of a shader run once its loops have taken 65535
// iterations in all (LP_MAX_TGSI_LOOP_ITERATIONS) and skips what follows, silently: one
// dispatch summing every sample of every light cut the sums short (quad_light at 65536
// samples came out a third as bright). The pass is therefore split into dispatches over a
// range of lights and a range of samples whose loop iterations per invocation stay within
// RTPBR_MC_LOOP_BUDGET, a quarter of that limit. Counted per light of a polygon of c vertices
// (a SIMD batch runs both sides of a divergent branch): the light loop, 1; per sample, the
// sample loop, the fan-triangle pick (c - 3) and the ray-polygon test (c), 2 c - 2. The split
// below counts c - 1 and 2 c - 1, the loops before the light record carried the fan's areas
// (a fan-area loop per light, one more pick step): an upper bound, kept so that the dispatches,
// and so the rounding of the sums, stay as they were.
enum { RTPBR_MC_LOOP_BUDGET = 16384 };

// The LCG step of mc_next (mc_sampling.glsl) taken n times: state * *mul + *add (Brown 1994,
// "Random Number Generation with Arbitrary Strides": square the step, keep the bits' steps).
static void lcg_skip(uint32_t n, uint32_t *mul, uint32_t *add)
{
    uint32_t acc_mul = 1u, acc_add = 0u, cur_mul = 747796405u, cur_add = 2891336453u;
    for (; n; n >>= 1) {
        if (n & 1u) {
            acc_mul *= cur_mul;
            acc_add = acc_add * cur_mul + cur_add;
        }
        cur_add *= cur_mul + 1u;
        cur_mul *= cur_mul;
    }
    *mul = acc_mul;
    *add = acc_add;
}

void rtpbr_lighting_mc_record(rtpbr_renderer *r, const rtpbr_gpu_scene *scene, VkPipeline pipeline,
                              const rtpbr_render_desc *desc, VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    const uint32_t samples = desc->mc_samples, lights = scene->light_count;
    // The split, from the scene's largest polygon.
    uint32_t c = 3;
    const rtpbr_shader_light *gpu = scene->lights.mapped;
    for (uint32_t i = 0; i < lights; ++i)
        if (gpu[i].vertex_count > c) c = gpu[i].vertex_count;
    if (c > RTPBR_SHADER_MAX_POLYGON_VERTICES) c = RTPBR_SHADER_MAX_POLYGON_VERTICES;
    const uint32_t per_light = c - 1, per_sample = 2 * c - 1;
    uint32_t sample_step = samples, light_step;
    if (per_light + samples * per_sample <= RTPBR_MC_LOOP_BUDGET) {
        light_step = RTPBR_MC_LOOP_BUDGET / (per_light + samples * per_sample);
    } else {
        light_step = 1;
        sample_step = (RTPBR_MC_LOOP_BUDGET - per_light) / per_sample;
    }

    rtpbr_lighting_begin(r, pipeline, ctx->lighting.mc_layout, cmd);
    const VkMemoryBarrier added = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
    };
    rtpbr_shader_mc params = {.samples = samples, .seed = desc->mc_seed};
    for (uint32_t first_sample = 0; first_sample < samples; first_sample += sample_step) {
        params.first_sample = first_sample;
        params.sample_count = samples - first_sample < sample_step ? samples - first_sample : sample_step;
        lcg_skip(4 * first_sample, &params.skip_mul, &params.skip_add); // 4 numbers per sample
        // One dispatch at least: the first writes every pixel (background, emission) even
        // without lights.
        for (uint32_t first_light = 0; first_light == 0 || first_light < lights; first_light += light_step) {
            if (first_sample || first_light)
                vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                     0, 1, &added, 0, NULL, 0, NULL);
            params.first_light = first_light;
            params.light_count = light_step;
            vkCmdPushConstants(cmd, ctx->lighting.mc_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
            vkCmdDispatch(cmd, r->tiles_x, r->tiles_y, 1);
        }
    }
}
