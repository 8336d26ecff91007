/* Edge values: every public function over a sweep of edge inputs (cosines 0, 1, tiny,
 * grazing, negative; alpha 0, at and below RTPBR_MIN_ALPHA, 1, above 1; eta near 1 and
 * extreme; NaN and Inf). For finite inputs every function must return a finite value
 * (the issue: no NaN or Inf at grazing angles, at the minimum alpha, at normal incidence or
 * below the horizon, where the result is 0). For NaN inputs the table printed says which
 * functions still return a finite value (documented behaviour, not asserted). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include "test_main.h"
#include "test_common.h"

static const float kCos[] = {0.0f, 1.0f, 1e-7f, 1e-4f, 0.5f, 0.9999999f, -1e-7f, -0.5f, -1.0f};
static const float kAlpha[] = {0.0f, 1e-8f, 1e-3f, 0.01f, 0.5f, 1.0f, 2.0f, -0.5f};
#define N_COS (int)(sizeof kCos / sizeof *kCos)
#define N_ALPHA (int)(sizeof kAlpha / sizeof *kAlpha)

typedef float (*fn_ca)(float c, float a);
typedef struct { const char *name; fn_ca fn; } named_ca;

static int finite3(rtpbr_v3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

static void test_scalar_functions_finite(void **state) {
    (void)state;
    const named_ca fns[] = {
        {"D_GGX", rtpbr_D_GGX}, {"D_Beckmann", rtpbr_D_Beckmann}, {"Lambda_GGX", rtpbr_Lambda_GGX},
        {"G1_GGX", rtpbr_G1_GGX}, {"Lambda_Beckmann", rtpbr_Lambda_Beckmann}, {"G1_Beckmann", rtpbr_G1_Beckmann},
        {"G1_Beckmann_Fast", rtpbr_G1_Beckmann_Fast},
    };
    for (size_t f = 0; f < sizeof fns / sizeof *fns; f++)
        for (int i = 0; i < N_COS; i++)
            for (int j = 0; j < N_ALPHA; j++) {
                float r = fns[f].fn(kCos[i], kAlpha[j]);
                if (!isfinite(r)) print_error("%s(%g, %g) = %g\n", fns[f].name, kCos[i], kAlpha[j], r);
                assert_true(isfinite(r));
                if (kCos[i] <= 0.0f && fns[f].name[0] == 'D') assert_true(r == 0.0f);
                if (kCos[i] <= 0.0f && fns[f].name[0] == 'G') assert_true(r == 0.0f);
            }
    for (int i = 0; i < N_COS; i++)
        for (int j = 0; j < N_ALPHA; j++)
            for (int k = 0; k < N_COS; k++) {
                float v1 = rtpbr_V_SmithGGXCorrelated(kCos[i], kCos[k], kAlpha[j]);
                float v2 = rtpbr_V_SmithGGXCorrelated_Fast(kCos[i], kCos[k], kAlpha[j]);
                float v3s = rtpbr_V_SmithGGXSeparable(kCos[i], kCos[k], kAlpha[j]);
                assert_true(isfinite(v1) && isfinite(v2) && isfinite(v3s));
                assert_true(rtpbr_D_GTR(kCos[i], kAlpha[j], 1.0f + 0.5f * (float)k) >= 0.0f);
                assert_true(isfinite(rtpbr_D_GTR(kCos[i], kAlpha[j], 0.5f + 0.5f * (float)k)));
                assert_true(isfinite(rtpbr_F_Dielectric(kCos[i], 1e-9f + 0.5f * (float)k)));
                assert_true(isfinite(rtpbr_F_Schlick1(0.04f, 1.0f, kCos[i])));
                if (kCos[i] <= 0.0f || kCos[k] <= 0.0f) assert_true(v1 == 0.0f && v2 == 0.0f && v3s == 0.0f);
            }
}

static void test_vector_functions_finite(void **state) {
    (void)state;
    for (int i = 0; i < N_COS; i++)
        for (int k = 0; k < N_COS; k++)
            for (int j = 0; j < N_ALPHA; j++) {
                float so = sqrtf(fmaxf(0.0f, 1.0f - kCos[i] * kCos[i]));
                float si = sqrtf(fmaxf(0.0f, 1.0f - kCos[k] * kCos[k]));
                rtpbr_v3 wo = v3(so, 0.0f, kCos[i]);
                rtpbr_v3 wis[3] = {v3(-si, 0.0f, kCos[k]), v3(si, 0.0f, kCos[k]), v3(0.0f, si, kCos[k])};
                for (int w = 0; w < 3; w++) {
                    rtpbr_v3 wi = wis[w];
                    for (int v = 0; v < RTPBR_SHIM_VARIANT_COUNT; v++) {
                        rtpbr_fresnel_params fr = rtpbr_Fresnel_FromF0(v3(0.04f, 0.5f, 1.0f));
                        rtpbr_v3 f = rtpbr_BRDF_SpecularLocal((rtpbr_shim_variant)v, wo, wi, kAlpha[j], kAlpha[(j + 3) % N_ALPHA], fr);
                        if (!finite3(f))
                            print_error("BRDF_SpecularLocal[%s] wo=(%g,%g) wi=(%g,%g,%g) a=%g: %g\n",
                                        rtpbr_shim_variant_name((rtpbr_shim_variant)v), wo.x, wo.z, wi.x, wi.y, wi.z, kAlpha[j], f.x);
                        assert_true(finite3(f));
                        assert_true(f.x >= 0.0f && f.y >= 0.0f && f.z >= 0.0f);
                        if (wo.z <= 0.0f || wi.z <= 0.0f) assert_true(f.x == 0.0f);
                        float ndoth = (kCos[i] + kCos[k]) * 0.5f;
                        rtpbr_v3 g = rtpbr_BRDF_Specular((rtpbr_shim_variant)v, kCos[i], kCos[k], ndoth, kCos[i], kAlpha[j], fr);
                        assert_true(finite3(g));
                    }
                    assert_true(isfinite(rtpbr_PDF_GGX_Reflection(wo, wi, kAlpha[j], kAlpha[j])));
                    assert_true(isfinite(rtpbr_PDF_Beckmann_Reflection(wo, wi, kAlpha[j], kAlpha[j])));
                    assert_true(isfinite(rtpbr_Lambda_Beckmann_Aniso(wi, kAlpha[j], 0.3f)));
                    assert_true(isfinite(rtpbr_G1_GGX_Aniso(wi, kAlpha[j], 0.3f)));
                }
                const float us[] = {0.0f, 0.5f, 0.99999994f};
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++) {
                        rtpbr_v3 m1 = rtpbr_Sample_GGX_VNDF(wo, kAlpha[j], kAlpha[j], us[a], us[b]);
                        rtpbr_v3 m2 = rtpbr_Sample_Beckmann_VNDF(wo, kAlpha[j], kAlpha[j], us[a], us[b]);
                        rtpbr_v3 m3 = rtpbr_Sample_CosineHemisphere(us[a], us[b]);
                        assert_true(finite3(m1) && finite3(m2) && finite3(m3));
                        assert_true(m1.z >= 0.0f && m2.z >= 0.0f && m3.z >= 0.0f);
                        assert_true(isfinite(rtpbr_PDF_GGX_VNDF(wo, m1, kAlpha[j], kAlpha[j])));
                        assert_true(isfinite(rtpbr_PDF_Beckmann_VNDF(wo, m2, kAlpha[j], kAlpha[j])));
                    }
            }
    const float etas[] = {0.0f, 1e-6f, 1.0f, 1.5f, 1e6f};
    for (int i = 0; i < N_COS; i++)
        for (int e = 0; e < 5; e++) {
            rtpbr_v3 f = rtpbr_F_Conductor(kCos[i], v3(etas[e], etas[e], etas[e]), v3(etas[(e + 2) % 5], 0.0f, 1e6f));
            assert_true(finite3(f));
            assert_true(f.x >= 0.0f && f.x <= 1.0f);
            float d = rtpbr_F_Dielectric(kCos[i], etas[e]);
            assert_true(isfinite(d) && d >= 0.0f && d <= 1.0f);
        }
}

/* NaN inputs: print which functions absorb a NaN into a finite result. */
static void test_nan_report(void **state) {
    (void)state;
    const float nan = NAN;
    rtpbr_fresnel_params fr = rtpbr_Fresnel_FromF0(v3(0.04f, 0.04f, 0.04f));
    struct { const char *name; float value; } rows[] = {
        {"D_GGX(NaN, 0.5)", rtpbr_D_GGX(nan, 0.5f)},
        {"D_GGX(0.5, NaN alpha)", rtpbr_D_GGX(0.5f, nan)},
        {"D_Beckmann(NaN, 0.5)", rtpbr_D_Beckmann(nan, 0.5f)},
        {"D_Beckmann(0.5, NaN alpha)", rtpbr_D_Beckmann(0.5f, nan)},
        {"D_GTR(0.5, 0.5, NaN gamma)", rtpbr_D_GTR(0.5f, 0.5f, nan)},
        {"G1_GGX(NaN, 0.5)", rtpbr_G1_GGX(nan, 0.5f)},
        {"G1_GGX(0.5, NaN alpha)", rtpbr_G1_GGX(0.5f, nan)},
        {"Lambda_Beckmann(0.5, NaN alpha)", rtpbr_Lambda_Beckmann(0.5f, nan)},
        {"V_SmithGGXCorrelated(NaN, 0.5, 0.5)", rtpbr_V_SmithGGXCorrelated(nan, 0.5f, 0.5f)},
        {"V_SmithGGXCorrelated(0.5, 0.5, NaN)", rtpbr_V_SmithGGXCorrelated(0.5f, 0.5f, nan)},
        {"F_Dielectric(NaN, 1.5)", rtpbr_F_Dielectric(nan, 1.5f)},
        {"F_Dielectric(0.5, NaN eta)", rtpbr_F_Dielectric(0.5f, nan)},
        {"F_Schlick1(0.04, 1, NaN)", rtpbr_F_Schlick1(0.04f, 1.0f, nan)},
        {"BRDF_Specular(NaN NoV)", rtpbr_BRDF_Specular(RTPBR_SHIM_GGX_HEIGHT_CORRELATED, nan, 0.5f, 0.9f, 0.9f, 0.5f, fr).x},
        {"BRDF_Specular(NaN alpha)", rtpbr_BRDF_Specular(RTPBR_SHIM_GGX_HEIGHT_CORRELATED, 0.5f, 0.5f, 0.9f, 0.9f, nan, fr).x},
        {"BRDF_SpecularLocal(NaN wo)", rtpbr_BRDF_SpecularLocal(RTPBR_SHIM_GGX_HEIGHT_CORRELATED, v3(nan, 0, nan), v3(0, 0, 1), 0.5f, 0.5f, fr).x},
        {"Sample_GGX_VNDF(NaN wo)", rtpbr_Sample_GGX_VNDF(v3(nan, 0, nan), 0.5f, 0.5f, 0.3f, 0.3f).z},
        {"Sample_GGX_VNDF(NaN u)", rtpbr_Sample_GGX_VNDF(v3(0, 0, 1), 0.5f, 0.5f, nan, nan).z},
        {"Sample_Beckmann_VNDF(NaN alpha)", rtpbr_Sample_Beckmann_VNDF(v3(0.6f, 0, 0.8f), nan, nan, 0.3f, 0.3f).z},
    };
    int finite_count = 0, n = (int)(sizeof rows / sizeof *rows);
    print_message("%-40s %s\n", "function (NaN input)", "result");
    for (int i = 0; i < n; i++) {
        print_message("%-40s %g%s\n", rows[i].name, rows[i].value, isfinite(rows[i].value) ? "" : "   (not finite)");
        finite_count += isfinite(rows[i].value) ? 1 : 0;
    }
    print_message("%d of %d NaN cases return a finite value\n", finite_count, n);
    /* the entry points guard their cosine and alpha arguments: these must hold */
    assert_true(rtpbr_D_GGX(nan, 0.5f) == 0.0f);
    assert_true(isfinite(rtpbr_D_GGX(0.5f, nan)));
    assert_true(rtpbr_BRDF_Specular(RTPBR_SHIM_GGX_HEIGHT_CORRELATED, nan, 0.5f, 0.9f, 0.9f, 0.5f, fr).x == 0.0f);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_scalar_functions_finite),
                cmocka_unit_test(test_vector_functions_finite),
                cmocka_unit_test(test_nan_report))
