/* rtpbr GPU test: the shader library compiled as GLSL and as HLSL (glslang -> SPIR-V),
 * evaluated by a compute shader on lavapipe with the validation layers on, against the C++
 * build of the same kernel (kernel.h).
 *
 * Inputs: RTPBR_TEST_INPUTS tuples of eight numbers in [0, 1] from a fixed-seed PRNG; about
 * 3% of the numbers are exactly 0, 3% exactly 1, 6% near 0 and 6% near 1 (log-uniform
 * distance in [1e-6, 1e-2]), so every clamp, horizon test and grazing case is reached.
 *
 * Match criterion, per value (c = C++, g = GPU):
 *   - both finite (no public function is documented to return NaN or Inf: a non-finite value
 *     on either side is a failure, even NaN on both);
 *   - |c| > 1e-6:  |g - c| <= tol |c|, tol = 1e-4 (RTPBR_TEST_REL_TOL);
 *   - |c| <= 1e-6: |g - c| <= 1e-10 (RTPBR_TEST_ABS_TOL, the relative bound at the
 *     threshold, so the criterion is continuous).
 * One exception, the Beckmann sampler's CDF inversion, gets a backward-error test instead
 * (see is_cdf_inverting_sampler() for the reason and the bound).
 *
 * Any Vulkan validation message fails the test (each test checks the count, and the last one
 * destroys the context and checks the object tracker's report). The negative control compares
 * a C++ build with other model flags against the GPU's default build and requires mismatches
 * exactly where the flags matter.
 *
 * Exit code 77 (meson: skipped) only when there is no Vulkan driver / device at all.
 */
#define _POSIX_C_SOURCE 200809L /* dlopen */

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "kernel_cpu.h"
#include "rtpbr_common/rng.h"
#include "vk_compute.h"
#include "vk_host.h"

#include "eval_glsl_ggx_hc_schlick.spv.h"
#include "eval_hlsl_ggx_hc_schlick.spv.h"
#include "eval_glsl_beckmann_sep_conductor.spv.h"
#include "eval_hlsl_beckmann_sep_conductor.spv.h"
#include "eval_glsl_gtr_fast_dielectric.spv.h"
#include "eval_hlsl_gtr_fast_dielectric.spv.h"

#define RTPBR_TEST_INPUTS 16384u /* >= 10^4, a multiple of the workgroup size */
#define RTPBR_TEST_GROUP_SIZE 64u /* local_size_x of eval.comp / numthreads of eval.hlsl */
#define RTPBR_TEST_REL_TOL 1e-4
#define RTPBR_TEST_ABS_TOL 1e-10
#define RTPBR_TEST_REL_THRESHOLD 1e-6
#define RTPBR_TEST_SEED 0x7274706272u /* "rtpbr" */

typedef struct gpu_variant {
    const char *name;
    const rtpbr_test_cpu_kernel *(*cpu)(void);
    const uint32_t *spirv[2]; /* GLSL, HLSL */
    size_t spirv_size[2];
} gpu_variant;

enum { LANG_GLSL, LANG_HLSL, LANG_COUNT };
static const char *const lang_names[LANG_COUNT] = {"GLSL", "HLSL"};

#define VARIANT(v)                                                                             \
    {#v, rtpbr_test_cpu_##v, {rtpbr_test_spv_glsl_##v, rtpbr_test_spv_hlsl_##v},               \
     {sizeof(rtpbr_test_spv_glsl_##v), sizeof(rtpbr_test_spv_hlsl_##v)}}
static const gpu_variant variants[] = {
    VARIANT(ggx_hc_schlick),
    VARIANT(beckmann_sep_conductor),
    VARIANT(gtr_fast_dielectric),
};
#undef VARIANT
#define VARIANT_COUNT (sizeof(variants) / sizeof(variants[0]))

typedef struct test_state {
    vkc_context *vk;
    float *inputs;                               /* 8 per tuple */
    float *gpu[VARIANT_COUNT][LANG_COUNT];       /* outputs, j-major; NULL until run */
} test_state;

/* ---- inputs ------------------------------------------------------------------------------ */


static float input_number(uint64_t *s) {
    uint32_t kind = (uint32_t)(rtpbr_tools_splitmix64_next(s) % 64u);
    if (kind < 2)
        return 0.0f;
    if (kind < 4)
        return 1.0f;
    if (kind < 12) {
        float d = powf(10.0f, -6.0f + 4.0f * rtpbr_tools_splitmix64_float(s)); /* [1e-6, 1e-2] */
        return kind < 8 ? d : 1.0f - d;
    }
    return rtpbr_tools_splitmix64_float(s);
}

/* ---- comparison ------------------------------------------------------------------------ */

/* The Beckmann visible-normal sampler inverts its CDF by Newton iteration (sampling.h,
 * Beckmann_SampleSlopeX). Where the CDF is flat (u.x near 1, the slope's tail) the inverse is
 * ill-conditioned: |dx/du| reaches 1e5 at u = 1 - 1e-6, so a residual differing by one ulp
 * between the GPU's and the CPU's exp/erfc moves the slope by ~5e-3 while the GPU's sample is
 * the exact sample of a u' within 3e-8 (half an ulp of u) of u. For these outputs, and only
 * these, a value that fails the forward test passes a backward test:
 *     |g - c| <= 1e-4 |c| + 1e-10 + RTPBR_TEST_SAMPLE_DU (|ds/du.x| + |ds/du.y|),
 * i.e. g is the C++ sample of a u' within RTPBR_TEST_SAMPLE_DU = 2^-20 (~9.5e-7, 16 ulps of
 * numbers just below 1, and below the sampler's own resolution of 1e-6) of u, to first order.
 * Why that much: at the tail the residual of the Newton iteration is a difference of terms of
 * size ~norm that cancel to ~1e-6 norm, so each side's float rounding (the C++ side's too:
 * against a double-precision inversion it is off by up to ~4 ulps of u there) and the GPU's
 * exp and fused multiply-adds move the root by a few ulps of u; and ds/du is estimated by the
 * C++ sampler's largest one-sided difference quotient over a step of RTPBR_TEST_SAMPLE_PROBE =
 * 2e-6 (twice the clamp margin, so that u = 1, clamped to 1 - 1e-6, is probed at a distinct
 * u'), which underestimates |ds/du| at the clamp by up to ~2x (the inverse CDF has a
 * square-root singularity where the slope reaches mu). The table's "max du" column prints the
 * largest equivalent |g - c| / |ds/du| that was needed. The GGX spherical-cap sampler is
 * ill-conditioned the same way where u.y -> 1: the cap point c tends to -wo_std, so
 * h = c + wo_std is a difference of nearly equal unit vectors that normalisation amplifies
 * (measured: 7 of 16384 x 3 components off by 1e-4..2e-4 relative, each within a u' a few ulps
 * away, or components below 2e-3 of a unit vector off by < 1e-8 absolute); it gets the same
 * backward test. The cosine sampler meets the forward test and gets no allowance. */
#define RTPBR_TEST_SAMPLE_DU 0x1p-20
#define RTPBR_TEST_SAMPLE_PROBE 2e-6f

static int is_cdf_inverting_sampler(const char *name) {
    return strncmp(name, "Sample_Beckmann_VNDF", 20) == 0 || strcmp(name, "Beckmann_SampleSlopeX") == 0 ||
           strncmp(name, "Sample_GGX_VNDF", 15) == 0;
}

typedef struct output_stats {
    double max_rel;      /* over |c| > threshold */
    double max_abs;      /* over |c| <= threshold */
    uint32_t mismatches;
    uint32_t backward;   /* accepted by the backward test only */
    double max_du;       /* largest |g - c| / |ds/du| among those */
} output_stats;

static int value_matches(float c, float g, double *rel, double *abs_err) {
    *rel = 0.0;
    *abs_err = 0.0;
    if (!isfinite(c) || !isfinite(g)) {
        *rel = INFINITY;
        return 0;
    }
    double d = fabs((double)g - (double)c);
    if (fabs((double)c) > RTPBR_TEST_REL_THRESHOLD) {
        *rel = d / fabs((double)c);
        return *rel <= RTPBR_TEST_REL_TOL;
    }
    *abs_err = d;
    return d <= RTPBR_TEST_ABS_TOL;
}

/* Per output value, the estimate of |ds/du.x| + |ds/du.y| of the C++ kernel, where (u.x, u.y)
 * is the input pair (b.x, b.y). */
typedef struct sample_slope {
    float *sum;
} sample_slope;

static float *cpu_outputs(const rtpbr_test_cpu_kernel *k, const float *inputs);

static sample_slope sample_slope_make(const rtpbr_test_cpu_kernel *k, const float *inputs, const float *cpu) {
    size_t n = (size_t)k->outputs * RTPBR_TEST_INPUTS;
    sample_slope r = {calloc(n, sizeof(float))};
    float *moved = malloc((size_t)RTPBR_TEST_INPUTS * 8 * sizeof(float));
    float *comp_slope = malloc(n * sizeof(float));
    assert_true(r.sum && moved && comp_slope);
    for (int comp = 4; comp < 6; comp++) { /* b.x, b.y: the kernel's u */
        memset(comp_slope, 0, n * sizeof(float));
        for (int sign = -1; sign <= 1; sign += 2) {
            memcpy(moved, inputs, (size_t)RTPBR_TEST_INPUTS * 8 * sizeof(float));
            for (size_t i = 0; i < RTPBR_TEST_INPUTS; i++) {
                float *x = &moved[8 * i + (size_t)comp];
                *x = fminf(fmaxf(*x + (float)sign * RTPBR_TEST_SAMPLE_PROBE, 0.0f), 1.0f);
            }
            float *out = cpu_outputs(k, moved);
            for (size_t m = 0; m < n; m++) {
                size_t i = m % RTPBR_TEST_INPUTS;
                float du = fabsf(moved[8 * i + (size_t)comp] - inputs[8 * i + (size_t)comp]);
                float q = du > 0.0f ? fabsf(out[m] - cpu[m]) / du : 0.0f;
                comp_slope[m] = fmaxf(comp_slope[m], q);
            }
            free(out);
        }
        for (size_t m = 0; m < n; m++)
            r.sum[m] += comp_slope[m];
    }
    free(comp_slope);
    free(moved);
    return r;
}

/* Compares two output arrays (j-major, `count` inputs); prints a table; returns the number of
 * mismatching values and fills per-output statistics when `stats` is not NULL. `slope` (may
 * be NULL) enables the backward test for the CDF-inverting samplers. */
static uint32_t compare(const char *title, const rtpbr_test_cpu_kernel *k, const float *inputs,
                        const float *cpu, const float *gpu, uint32_t count, const sample_slope *slope,
                        output_stats *stats) {
    uint32_t total = 0;
    printf("\n%s (%u inputs x %u outputs)\n", title, count, k->outputs);
    printf("  %-28s %12s %12s %10s %9s %9s\n", "output", "max rel err", "max abs err", "mismatches",
           slope ? "backward" : "", slope ? "max du" : "");
    for (uint32_t j = 0; j < k->outputs; j++) {
        output_stats s = {0, 0, 0, 0, 0};
        int backward = slope && is_cdf_inverting_sampler(k->names[j]);
        for (uint32_t i = 0; i < count; i++) {
            double rel, abs_err;
            size_t m = (size_t)j * count + i;
            float c = cpu[m];
            float g = gpu[m];
            if (!value_matches(c, g, &rel, &abs_err)) {
                double allowed = RTPBR_TEST_REL_TOL * fabs((double)c) + RTPBR_TEST_ABS_TOL +
                                 (backward ? RTPBR_TEST_SAMPLE_DU * slope->sum[m] : 0.0);
                if (backward && isfinite(c) && isfinite(g) && fabs((double)g - (double)c) <= allowed) {
                    s.backward++;
                    double du = fabs((double)g - (double)c) / slope->sum[m];
                    if (du > s.max_du)
                        s.max_du = du;
                } else {
                    if (s.mismatches < 3) {
                        const float *in = inputs + 8 * (size_t)i;
                        printf("    mismatch %s[%u]: cpu %.9g gpu %.9g  in (%.9g %.9g %.9g %.9g | %.9g %.9g %.9g %.9g)\n",
                               k->names[j], i, c, g, in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7]);
                    }
                    s.mismatches++;
                }
            }
            if (rel > s.max_rel)
                s.max_rel = rel;
            if (abs_err > s.max_abs)
                s.max_abs = abs_err;
        }
        if (backward)
            printf("  %-28s %12.3g %12.3g %10u %9u %9.2g\n", k->names[j], s.max_rel, s.max_abs, s.mismatches,
                   s.backward, s.max_du);
        else
            printf("  %-28s %12.3g %12.3g %10u\n", k->names[j], s.max_rel, s.max_abs, s.mismatches);
        total += s.mismatches;
        if (stats)
            stats[j] = s;
    }
    printf("  total mismatches: %u\n", total);
    fflush(stdout);
    return total;
}

/* ---- running ----------------------------------------------------------------------------- */

static const float *gpu_outputs(test_state *st, size_t v, int lang) {
    if (st->gpu[v][lang])
        return st->gpu[v][lang];
    const rtpbr_test_cpu_kernel *k = variants[v].cpu();
    size_t n = (size_t)k->outputs * RTPBR_TEST_INPUTS;
    float *out = malloc(n * sizeof(float));
    assert_non_null(out);
    vkc_dispatch_desc desc = {
        .spirv = variants[v].spirv[lang],
        .spirv_size = variants[v].spirv_size[lang],
        .input = st->inputs,
        .input_size = (size_t)RTPBR_TEST_INPUTS * 8 * sizeof(float),
        .output = out,
        .output_size = n * sizeof(float),
        .push_constant = RTPBR_TEST_INPUTS,
        .groups = {RTPBR_TEST_INPUTS / RTPBR_TEST_GROUP_SIZE, k->outputs, 1},
    };
    vkc_result r = vkc_dispatch(st->vk, &desc);
    if (r != VKC_OK) {
        fprintf(stderr, "%s %s dispatch failed: %s: %s\n", lang_names[lang], variants[v].name,
                vkc_result_string(r), vkc_last_error(st->vk));
        free(out);
        fail();
    }
    st->gpu[v][lang] = out;
    assert_int_equal(vkc_message_count(st->vk), 0);
    return out;
}

static float *cpu_outputs(const rtpbr_test_cpu_kernel *k, const float *inputs) {
    float *out = malloc((size_t)k->outputs * RTPBR_TEST_INPUTS * sizeof(float));
    assert_non_null(out);
    k->eval(inputs, RTPBR_TEST_INPUTS, out);
    return out;
}

/* With RTPBR_TEST_GPU_DUMP=dir, writes the raw float32 arrays (inputs, C++ and GPU outputs,
 * j-major) there for offline analysis. */
static void dump(const char *what, const float *data, size_t n) {
    const char *dir = getenv("RTPBR_TEST_GPU_DUMP");
    if (!dir)
        return;
    char path[1024];
    snprintf(path, sizeof(path), "%s/%s.f32", dir, what);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, sizeof(float), n, f) != n)
        fprintf(stderr, "cannot write %s\n", path);
    if (f)
        fclose(f);
}

static void check_variant(test_state *st, size_t v, int lang) {
    const rtpbr_test_cpu_kernel *k = variants[v].cpu();
    const float *gpu = gpu_outputs(st, v, lang);
    float *cpu = cpu_outputs(k, st->inputs);
    char what[128];
    size_t n = (size_t)k->outputs * RTPBR_TEST_INPUTS;
    snprintf(what, sizeof(what), "%s_%s", lang_names[lang], variants[v].name);
    dump(what, gpu, n);
    snprintf(what, sizeof(what), "cpu_%s", variants[v].name);
    dump(what, cpu, n);
    dump("inputs", st->inputs, (size_t)RTPBR_TEST_INPUTS * 8);
    if (getenv("RTPBR_TEST_GPU_DUMP")) {
        char path[1024];
        snprintf(path, sizeof(path), "%s/names.txt", getenv("RTPBR_TEST_GPU_DUMP"));
        FILE *f = fopen(path, "w");
        for (uint32_t j = 0; f && j < k->outputs; j++)
            fprintf(f, "%s\n", k->names[j]);
        if (f)
            fclose(f);
    }
    char title[128];
    snprintf(title, sizeof(title), "%s vs C++, variant %s", lang_names[lang], variants[v].name);
    sample_slope slope = sample_slope_make(k, st->inputs, cpu);
    uint32_t mismatches = compare(title, k, st->inputs, cpu, gpu, RTPBR_TEST_INPUTS, &slope, NULL);
    free(slope.sum);
    free(cpu);
    assert_int_equal(mismatches, 0);
}

#define VARIANT_TEST(v, lang)                                                                  \
    static void test_##lang##_##v(void **state) { check_variant(*state, v, LANG_##lang); }
VARIANT_TEST(0, GLSL)
VARIANT_TEST(0, HLSL)
VARIANT_TEST(1, GLSL)
VARIANT_TEST(1, HLSL)
VARIANT_TEST(2, GLSL)
VARIANT_TEST(2, HLSL)
#undef VARIANT_TEST

static uint32_t output_index(const rtpbr_test_cpu_kernel *k, const char *name) {
    for (uint32_t j = 0; j < k->outputs; j++) {
        if (strcmp(k->names[j], name) == 0)
            return j;
    }
    fail_msg("no output named %s", name);
    return 0;
}

/* Negative control (forward test only, so the ill-conditioned samplers are not in the
 * flag-independent list): the C++ build with Beckmann / separable Smith / conductor Fresnel against
 * the GPU's GGX / height-correlated / Schlick build. The comparison must find mismatches in
 * the outputs that depend on the flags and none in those that do not. */
static void test_negative_control(void **state) {
    test_state *st = *state;
    const rtpbr_test_cpu_kernel *ggx = variants[0].cpu();
    const rtpbr_test_cpu_kernel *beckmann = variants[1].cpu();
    assert_int_equal(ggx->outputs, beckmann->outputs);
    const float *gpu = gpu_outputs(st, 0, LANG_GLSL);
    float *cpu = cpu_outputs(beckmann, st->inputs);
    output_stats *stats = calloc(beckmann->outputs, sizeof(*stats));
    assert_non_null(stats);
    uint32_t mismatches = compare("negative control: C++ beckmann_sep_conductor vs GLSL ggx_hc_schlick",
                                  beckmann, st->inputs, cpu, gpu, RTPBR_TEST_INPUTS, NULL, stats);
    assert_true(mismatches > 0);
    static const char *const flag_dependent[] = {
        "D_Microfacet", "V_Microfacet", "G2_Microfacet", "Lambda_Microfacet",
        "F_Microfacet_x", "BRDF_Specular_x", "BRDF_SpecularLocal_x",
    };
    for (size_t i = 0; i < sizeof(flag_dependent) / sizeof(flag_dependent[0]); i++)
        assert_true(stats[output_index(beckmann, flag_dependent[i])].mismatches > 0);
    static const char *const flag_independent[] = {
        "D_GGX", "D_Beckmann", "V_SmithGGXCorrelated", "F_Conductor_x", "Sample_CosineHemisphere_x",
    };
    for (size_t i = 0; i < sizeof(flag_independent) / sizeof(flag_independent[0]); i++)
        assert_int_equal(stats[output_index(beckmann, flag_independent[i])].mismatches, 0);
    free(stats);
    free(cpu);
}

/* Destroys the Vulkan context: the object tracker reports anything left alive. */
static void test_validation_clean(void **state) {
    test_state *st = *state;
    uint32_t messages = 0;
    vkc_destroy(st->vk, &messages);
    st->vk = NULL;
    assert_int_equal(messages, 0);
}

static void state_free(test_state *st) {
    vkc_destroy(st->vk, NULL);
    for (size_t v = 0; v < VARIANT_COUNT; v++) {
        for (int l = 0; l < LANG_COUNT; l++)
            free(st->gpu[v][l]);
    }
    free(st->inputs);
    free(st);
}

int main(void) {
    vk_host_keep_driver_libraries_loaded();
    test_state *st = calloc(1, sizeof(*st));
    if (!st) {
        fprintf(stderr, "test_gpu: out of memory\n");
        return 1;
    }
    char err[512] = "";
    vkc_result r = vkc_create(&st->vk, err, sizeof(err));
    if (r == VKC_NO_DRIVER) {
        fprintf(stderr, "test_gpu: SKIP: %s\n", err);
        free(st);
        return 77;
    }
    if (r != VKC_OK) {
        fprintf(stderr, "test_gpu: cannot set up Vulkan: %s: %s\n", vkc_result_string(r), err);
        free(st);
        return 1;
    }
    printf("device: %s\n", vkc_device_name(st->vk));

    st->inputs = malloc((size_t)RTPBR_TEST_INPUTS * 8 * sizeof(float));
    if (!st->inputs) {
        state_free(st);
        return 1;
    }
    uint64_t seed = RTPBR_TEST_SEED;
    for (size_t i = 0; i < (size_t)RTPBR_TEST_INPUTS * 8; i++)
        st->inputs[i] = input_number(&seed);

    const struct CMUnitTest tests[] = {
        cmocka_unit_test_prestate(test_GLSL_0, st),
        cmocka_unit_test_prestate(test_HLSL_0, st),
        cmocka_unit_test_prestate(test_GLSL_1, st),
        cmocka_unit_test_prestate(test_HLSL_1, st),
        cmocka_unit_test_prestate(test_GLSL_2, st),
        cmocka_unit_test_prestate(test_HLSL_2, st),
        cmocka_unit_test_prestate(test_negative_control, st),
        cmocka_unit_test_prestate(test_validation_clean, st), /* last: destroys the context */
    };
    int failed = cmocka_run_group_tests_name("gpu", tests, NULL, NULL);
    state_free(st);
    return failed == 0 ? 0 : 1;
}
