// The lookup tables of the lighting passes, uploaded from the shader library's generated C
// arrays (shaderlib/luts/).
#include <stdlib.h>

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
    float *e = rtpbr_alloc(ctx, RTPBR_KC_SIZE * RTPBR_KC_SIZE * 4 * sizeof(float));
    float *eavg = rtpbr_alloc(ctx, RTPBR_KC_SIZE * 4 * sizeof(float));
    // E_F(mu, r, eta) and E(mu, r) together in one 3D table (u = mu, v = r, w = eta): rgba =
    // (E_F GGX, E_F Beckmann, E GGX, E Beckmann), E repeated in every eta slice, so that one
    // trilinear fetch gives a direction's E and E_F (the lighting passes' per-light lookup);
    // E_F_avg: u = r, v = eta.
    float *ef = rtpbr_alloc(ctx, (size_t)RTPBR_KC_SIZE * RTPBR_KC_SIZE * RTPBR_KC_SIZE_ETA * 4 * sizeof(float));
    float *efavg = rtpbr_alloc(ctx, (size_t)RTPBR_KC_SIZE * RTPBR_KC_SIZE_ETA * 4 * sizeof(float));
    rtpbr_result result = RTPBR_ERROR_OUT_OF_HOST_MEMORY;
    if (e && eavg && ef && efavg) {
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
        result = rtpbr_lut_create(ctx, RTPBR_KC_SIZE, RTPBR_KC_SIZE, 1, e, &ctx->luts[LUT_KC_E]);
        if (result == RTPBR_SUCCESS) result = rtpbr_lut_create(ctx, RTPBR_KC_SIZE, 1, 1, eavg, &ctx->luts[LUT_KC_EAVG]);
        if (result == RTPBR_SUCCESS)
            result = rtpbr_lut_create(ctx, RTPBR_KC_SIZE, RTPBR_KC_SIZE, RTPBR_KC_SIZE_ETA, ef, &ctx->luts[LUT_KC_EF]);
        if (result == RTPBR_SUCCESS)
            result = rtpbr_lut_create(ctx, RTPBR_KC_SIZE, RTPBR_KC_SIZE_ETA, 1, efavg, &ctx->luts[LUT_KC_EFAVG]);
    }
    rtpbr_free(ctx, e);
    rtpbr_free(ctx, eavg);
    rtpbr_free(ctx, ef);
    rtpbr_free(ctx, efavg);
    return result;
}

rtpbr_result rtpbr_luts_create(rtpbr_context *ctx)
{
    rtpbr_result result = RTPBR_SUCCESS;
    const float *ltc[4] = {rtpbr_ltc_ggx_1, rtpbr_ltc_ggx_2, rtpbr_ltc_beckmann_1, rtpbr_ltc_beckmann_2};
    for (int i = 0; i < 4 && result == RTPBR_SUCCESS; ++i)
        result = rtpbr_lut_create(ctx, RTPBR_LTC_SIZE, RTPBR_LTC_SIZE, 1, ltc[i], &ctx->luts[LUT_LTC_GGX_1 + i]);
    const float *disney[2] = {rtpbr_ltc_disney_diffuse_1, rtpbr_ltc_disney_diffuse_2};
    for (int i = 0; i < 2 && result == RTPBR_SUCCESS; ++i)
        result = rtpbr_lut_create(ctx, RTPBR_LTC_SIZE, RTPBR_LTC_SIZE, 1, disney[i], &ctx->luts[LUT_LTC_DISNEY_1 + i]);
    if (result == RTPBR_SUCCESS) result = create_kc_luts(ctx);
    // KHR sheen: the albedo of the Charlie lobe (r channel) and its LTC fit.
    if (result == RTPBR_SUCCESS) {
        float *e = rtpbr_alloc(ctx, RTPBR_SHEEN_SIZE * RTPBR_SHEEN_SIZE * 4 * sizeof(float));
        if (!e) return RTPBR_ERROR_OUT_OF_HOST_MEMORY;
        for (int r = 0; r < RTPBR_SHEEN_SIZE; ++r)
            for (int mu = 0; mu < RTPBR_SHEEN_SIZE; ++mu)
                e[4 * (r * RTPBR_SHEEN_SIZE + mu)] = rtpbr_sheen_E[RTPBR_SHEEN_VARIANT_charlie][r][mu];
        result = rtpbr_lut_create(ctx, RTPBR_SHEEN_SIZE, RTPBR_SHEEN_SIZE, 1, e, &ctx->luts[LUT_SHEEN_E]);
        rtpbr_free(ctx, e);
    }
    const float *sheen[2] = {rtpbr_ltc_sheen_1, rtpbr_ltc_sheen_2};
    for (int i = 0; i < 2 && result == RTPBR_SUCCESS; ++i)
        result = rtpbr_lut_create(ctx, RTPBR_LTC_SIZE, RTPBR_LTC_SIZE, 1, sheen[i], &ctx->luts[LUT_LTC_SHEEN_1 + i]);
    return result; // the caller destroys what was made (rtpbr_luts_destroy)
}

void rtpbr_luts_destroy(rtpbr_context *ctx)
{
    for (size_t i = 0; i < sizeof ctx->luts / sizeof ctx->luts[0]; ++i) rtpbr_lut_destroy(ctx, &ctx->luts[i]);
}
