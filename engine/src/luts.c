// The lookup tables of the lighting passes, uploaded from the shader library's generated C
// arrays (shaderlib/luts/).
#include "internal.h"

#include "luts/rtpbr_ltc_tables.h"
// The generated tables initialise multi-dimensional arrays with flat lists (valid C).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-braces"
#include "luts/rtpbr_sheen_tables.h"
#include "luts/rtpbr_kc_tables.h"
#pragma GCC diagnostic pop
#include "luts/rtpbr_ltc_sheen_tables.h"

// In binding order (rtpbr_shared.h: RTPBR_BINDING_LUT_LTC_GGX_1 + index).
enum {
    LUT_LTC_GGX_1, LUT_LTC_GGX_2, LUT_LTC_BECKMANN_1, LUT_LTC_BECKMANN_2, LUT_KC_E, LUT_KC_EAVG, LUT_KC_EF,
    LUT_KC_EFAVG, LUT_LTC_DISNEY_1, LUT_LTC_DISNEY_2, LUT_SHEEN_E, LUT_LTC_SHEEN_1, LUT_LTC_SHEEN_2, LUT_COUNT
};
_Static_assert(LUT_COUNT == RTPBR_LUT_COUNT, "LUT slots");
_Static_assert(RTPBR_BINDING_LUT_LTC_DISNEY_2 == RTPBR_BINDING_LUT_LTC_GGX_1 + LUT_LTC_DISNEY_2, "LUT bindings");
_Static_assert(RTPBR_BINDING_LUT_LTC_SHEEN_2 == RTPBR_BINDING_LUT_LTC_GGX_1 + LUT_LTC_SHEEN_2, "LUT bindings");

// Kulla-Conty tables of the two NDFs the engine compiles, one per channel: r = GGX, g =
// Beckmann (both with height-correlated Smith, the shader library's default).
static rtpbr_result create_kc_luts(rtpbr_context *ctx)
{
    const int ggx = RTPBR_KC_VARIANT_ggx_hc, beckmann = RTPBR_KC_VARIANT_beckmann_hc;
    rtpbr_result result = RTPBR_SUCCESS;
    float *e = NULL, *eavg = NULL, *ef = NULL, *efavg = NULL;
    RTPBR_ALLOC(&ctx->host, e, RTPBR_KC_SIZE * RTPBR_KC_SIZE * 4 * sizeof(float));
    RTPBR_ALLOC(&ctx->host, eavg, RTPBR_KC_SIZE * 4 * sizeof(float));
    // E_F(mu, r, eta) and E(mu, r) together in one 3D table (u = mu, v = r, w = eta): rgba =
    // (E_F GGX, E_F Beckmann, E GGX, E Beckmann), E repeated in every eta slice, so that one
    // trilinear fetch gives a direction's E and E_F (the lighting passes' per-light lookup);
    // E_F_avg: u = r, v = eta.
    RTPBR_ALLOC(&ctx->host, ef, (size_t)RTPBR_KC_SIZE * RTPBR_KC_SIZE * RTPBR_KC_SIZE_ETA * 4 * sizeof(float));
    RTPBR_ALLOC(&ctx->host, efavg, (size_t)RTPBR_KC_SIZE * RTPBR_KC_SIZE_ETA * 4 * sizeof(float));
    // rtpbr_kc_E[variant][r][mu]: texel x = mu axis, y = roughness (KC_TableCoord).
    for (int r = 0; r < RTPBR_KC_SIZE; ++r)
        for (int mu = 0; mu < RTPBR_KC_SIZE; ++mu) {
            float *t = e + 4 * (r * RTPBR_KC_SIZE + mu);
            t[0] = rtpbr_kc_E[ggx][r][mu];
            t[1] = rtpbr_kc_E[beckmann][r][mu];
        }
    for (int r = 0; r < RTPBR_KC_SIZE; ++r) {
        eavg[4 * r + 0] = rtpbr_kc_Eavg[ggx][r];
        eavg[4 * r + 1] = rtpbr_kc_Eavg[beckmann][r];
    }
    for (int eta = 0; eta < RTPBR_KC_SIZE_ETA; ++eta) {
        for (int r = 0; r < RTPBR_KC_SIZE; ++r) {
            for (int mu = 0; mu < RTPBR_KC_SIZE; ++mu) {
                float *t = ef + 4 * ((eta * RTPBR_KC_SIZE + r) * RTPBR_KC_SIZE + mu);
                t[0] = rtpbr_kc_EF[ggx][eta][r][mu];
                t[1] = rtpbr_kc_EF[beckmann][eta][r][mu];
                t[2] = rtpbr_kc_E[ggx][r][mu];
                t[3] = rtpbr_kc_E[beckmann][r][mu];
            }
            float *a = efavg + 4 * (eta * RTPBR_KC_SIZE + r);
            a[0] = rtpbr_kc_EFavg[ggx][eta][r];
            a[1] = rtpbr_kc_EFavg[beckmann][eta][r];
            a[2] = a[3] = 0.0f;
        }
    }
    RTPBR_TRY(rtpbr_lut_create(ctx, RTPBR_KC_SIZE, RTPBR_KC_SIZE, 1, e, &ctx->luts[LUT_KC_E]));
    RTPBR_TRY(rtpbr_lut_create(ctx, RTPBR_KC_SIZE, 1, 1, eavg, &ctx->luts[LUT_KC_EAVG]));
    RTPBR_TRY(rtpbr_lut_create(ctx, RTPBR_KC_SIZE, RTPBR_KC_SIZE, RTPBR_KC_SIZE_ETA, ef, &ctx->luts[LUT_KC_EF]));
    RTPBR_TRY(rtpbr_lut_create(ctx, RTPBR_KC_SIZE, RTPBR_KC_SIZE_ETA, 1, efavg, &ctx->luts[LUT_KC_EFAVG]));
cleanup:
    rtpbr_free(&ctx->host, e);
    rtpbr_free(&ctx->host, eavg);
    rtpbr_free(&ctx->host, ef);
    rtpbr_free(&ctx->host, efavg);
    return result;
}

// KHR sheen: the albedo of the Charlie lobe (r channel).
static rtpbr_result create_sheen_lut(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    float *e = NULL;
    RTPBR_ALLOC(&ctx->host, e, RTPBR_SHEEN_SIZE * RTPBR_SHEEN_SIZE * 4 * sizeof(float));
    for (int r = 0; r < RTPBR_SHEEN_SIZE; ++r)
        for (int mu = 0; mu < RTPBR_SHEEN_SIZE; ++mu)
            e[4 * (r * RTPBR_SHEEN_SIZE + mu)] = rtpbr_sheen_E[RTPBR_SHEEN_VARIANT_charlie][r][mu];
    RTPBR_TRY(rtpbr_lut_create(ctx, RTPBR_SHEEN_SIZE, RTPBR_SHEEN_SIZE, 1, e, &ctx->luts[LUT_SHEEN_E]));
cleanup:
    rtpbr_free(&ctx->host, e);
    return result;
}

rtpbr_result rtpbr_luts_create(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    // The LTC fits, used as the generator wrote them (RTPBR_LTC_SIZE^2 RGBA texels each).
    static const struct {
        int slot;
        const float *table;
    } ltc[] = {
        {LUT_LTC_GGX_1, rtpbr_ltc_ggx_1},
        {LUT_LTC_GGX_2, rtpbr_ltc_ggx_2},
        {LUT_LTC_BECKMANN_1, rtpbr_ltc_beckmann_1},
        {LUT_LTC_BECKMANN_2, rtpbr_ltc_beckmann_2},
        {LUT_LTC_DISNEY_1, rtpbr_ltc_disney_diffuse_1},
        {LUT_LTC_DISNEY_2, rtpbr_ltc_disney_diffuse_2},
        {LUT_LTC_SHEEN_1, rtpbr_ltc_sheen_1},
        {LUT_LTC_SHEEN_2, rtpbr_ltc_sheen_2},
    };
    for (size_t i = 0; i < sizeof ltc / sizeof ltc[0]; ++i)
        RTPBR_TRY(rtpbr_lut_create(ctx, RTPBR_LTC_SIZE, RTPBR_LTC_SIZE, 1, ltc[i].table, &ctx->luts[ltc[i].slot]));
    RTPBR_TRY(create_kc_luts(ctx));
    RTPBR_TRY(create_sheen_lut(ctx));
cleanup:
    return result; // the caller destroys what was made (rtpbr_luts_destroy)
}

void rtpbr_luts_destroy(rtpbr_context *ctx)
{
    for (size_t i = 0; i < sizeof ctx->luts / sizeof ctx->luts[0]; ++i) rtpbr_lut_destroy(ctx, &ctx->luts[i]);
}
