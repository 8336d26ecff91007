// The brute-force Monte Carlo lighting pass (lighting_mc.comp; rtpbr_render_desc.mc_samples):
// the LTC pass's descriptor set, dispatch and barriers (lighting.c), with the sample count and
// seed as push constants, one workgroup per tile and no culling.
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

void rtpbr_lighting_mc_record(rtpbr_renderer *r, VkPipeline pipeline, const rtpbr_render_desc *desc,
                              VkCommandBuffer cmd)
{
    const rtpbr_context *ctx = r->context;
    rtpbr_shader_mc params = {.samples = desc->mc_samples, .seed = desc->mc_seed};
    rtpbr_lighting_begin(r, pipeline, ctx->lighting.mc_layout, cmd);
    vkCmdPushConstants(cmd, ctx->lighting.mc_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
    vkCmdDispatch(cmd, r->tiles_x, r->tiles_y, 1);
    rtpbr_lighting_end(r, cmd);
}
