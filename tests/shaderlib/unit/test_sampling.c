/* Importance sampling: chi-square tests of each sampler against its pdf (the method of
 * pbrt-v4's and Mitsuba 3's BSDF tests: histogram over (theta, phi), expected counts from a
 * numerical integral of the pdf over each cell, cells with expected < 5 pooled), each pdf
 * integrating to 1, and the reflection pdf's Jacobian checked against the fraction of
 * reflected samples above the horizon. theta bins are warped by s = atan(tan(theta) / scale)
 * so that narrow lobes (alpha = 0.01) still spread over many bins. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include "test_main.h"
#include "test_common.h"

enum { THETA_BINS = 16, PHI_BINS = 32, SAMPLES = 200000, SUB = 4 };
enum { SAMPLER_GGX, SAMPLER_BECKMANN, SAMPLER_COSINE };

typedef struct sampler_case {
    int kind;
    float ax, ay;
    rtpbr_v3 wo;
} sampler_case;

static double pdf_of(const sampler_case *c, rtpbr_v3 wm) {
    switch (c->kind) {
    case SAMPLER_GGX: return rtpbr_PDF_GGX_VNDF(c->wo, wm, c->ax, c->ay);
    case SAMPLER_BECKMANN: return rtpbr_PDF_Beckmann_VNDF(c->wo, wm, c->ax, c->ay);
    default: return rtpbr_PDF_CosineHemisphere(wm);
    }
}

static rtpbr_v3 sample_of(const sampler_case *c, float u0, float u1) {
    switch (c->kind) {
    case SAMPLER_GGX: return rtpbr_Sample_GGX_VNDF(c->wo, c->ax, c->ay, u0, u1);
    case SAMPLER_BECKMANN: return rtpbr_Sample_Beckmann_VNDF(c->wo, c->ax, c->ay, u0, u1);
    default: return rtpbr_Sample_CosineHemisphere(u0, u1);
    }
}

static double scale_of(const sampler_case *c) { return c->kind == SAMPLER_COSINE ? 1.0 : sqrt((double)c->ax * c->ay); }

/* theta from the warped coordinate s in [0, 1] and d theta / d s */
static double theta_of(double s, double scale, double *dtheta) {
    double x = 0.5 * M_PI * s, cx = cos(x), sx = sin(x);
    *dtheta = scale * 0.5 * M_PI / (cx * cx + scale * scale * sx * sx);
    return atan2(scale * sx, cx);
}

static int bin_of(rtpbr_v3 w, double scale) {
    /* atan2 of (sin, cos) keeps theta's precision near the pole, where acos(z) of a float z
     * would quantise theta to a few values at alpha = 0.01 */
    double theta = atan2(sqrt((double)w.x * w.x + (double)w.y * w.y), (double)w.z);
    double s = atan(tan(theta) / scale) / (0.5 * M_PI);
    double phi = atan2((double)w.y, (double)w.x);
    if (phi < 0) phi += 2.0 * M_PI;
    int ti = (int)(s * THETA_BINS), pi = (int)(phi / (2.0 * M_PI) * PHI_BINS);
    if (ti >= THETA_BINS) ti = THETA_BINS - 1;
    if (pi >= PHI_BINS) pi = PHI_BINS - 1;
    if (ti < 0) ti = 0;
    return ti * PHI_BINS + pi;
}

/* integral of the pdf over each cell: SUB x SUB sub-cells, 5x5 Gauss-Legendre each */
static double expected_counts(const sampler_case *c, double *expct) {
    double scale = scale_of(c), total = 0.0;
    for (int ti = 0; ti < THETA_BINS; ti++)
        for (int pi = 0; pi < PHI_BINS; pi++) {
            double sum = 0.0;
            double ds = 1.0 / (THETA_BINS * SUB), dp = 2.0 * M_PI / (PHI_BINS * SUB);
            for (int a = 0; a < SUB; a++)
                for (int b = 0; b < SUB; b++)
                    for (int ga = 0; ga < 5; ga++)
                        for (int gb = 0; gb < 5; gb++) {
                            double s = (ti * SUB + a + 0.5 + 0.5 * kGL5x[ga]) * ds;
                            double phi = (pi * SUB + b + 0.5 + 0.5 * kGL5x[gb]) * dp;
                            double dth, th = theta_of(s, scale, &dth);
                            double w = 0.25 * kGL5w[ga] * kGL5w[gb] * ds * dp * dth * sin(th);
                            sum += w * pdf_of(c, v3_spherical(th, phi));
                        }
            expct[ti * PHI_BINS + pi] = sum;
            total += sum;
        }
    return total;
}

static void run_chi2(const sampler_case *c, const char *name, uint64_t seed) {
    double *obs = calloc(THETA_BINS * PHI_BINS, sizeof(double));
    double *expct = calloc(THETA_BINS * PHI_BINS, sizeof(double));
    assert_non_null(obs);
    assert_non_null(expct);
    double integral = expected_counts(c, expct);
    if (fabs(integral - 1.0) > 1e-3) print_error("%s: pdf integrates to %.6f\n", name, integral);
    assert_true(fabs(integral - 1.0) <= 1e-3);
    for (int i = 0; i < THETA_BINS * PHI_BINS; i++) expct[i] *= SAMPLES;
    test_rng rng = test_rng_make(seed);
    double scale = scale_of(c);
    for (int i = 0; i < SAMPLES; i++) {
        rtpbr_v3 w = sample_of(c, test_rng_float(&rng), test_rng_float(&rng));
        assert_true(isfinite(w.x) && isfinite(w.y) && isfinite(w.z) && w.z >= 0.0f);
        assert_true(fabs(w.x * w.x + w.y * w.y + w.z * w.z - 1.0) < 1e-4);
        obs[bin_of(w, scale)] += 1.0;
    }
    int dof = 0;
    double p = test_chi2_pvalue(obs, expct, THETA_BINS * PHI_BINS, &dof);
    /* Bonferroni: 1% significance over all the tests of this program */
    double alpha = 0.01 / 30.0;
    print_message("%-34s dof %4d  p = %.4f\n", name, dof, p);
    assert_true(p > alpha);
    free(obs);
    free(expct);
}

/* One visible-normal sampler over alpha 0.01..1 x three view angles, plus an anisotropic case. */
static void run_vndf_grid(int kind, const char *label, uint64_t seed) {
    const float alphas[] = {0.01f, 0.1f, 0.4f, 1.0f};
    const double thetas[] = {0.0, 0.8, 1.45};
    char name[96];
    for (int a = 0; a < 4; a++)
        for (int t = 0; t < 3; t++) {
            sampler_case c = {kind, alphas[a], alphas[a], v3_spherical(thetas[t], 0.3)};
            snprintf(name, sizeof name, "%s a=%.2f theta_o=%.2f", label, alphas[a], thetas[t]);
            run_chi2(&c, name, seed + a * 3 + t);
        }
    sampler_case c = {kind, 0.1f, 0.5f, v3_spherical(1.0, 0.6)};
    snprintf(name, sizeof name, "%s a=(0.1,0.5) theta_o=1.0", label);
    run_chi2(&c, name, seed + 100);
}

static void test_ggx_vndf(void **state) {
    (void)state;
    run_vndf_grid(SAMPLER_GGX, "GGX", 100);
}

static void test_beckmann_vndf(void **state) {
    (void)state;
    run_vndf_grid(SAMPLER_BECKMANN, "Beckmann", 300);
}

static void test_cosine(void **state) {
    (void)state;
    sampler_case c = {SAMPLER_COSINE, 1.0f, 1.0f, v3(0, 0, 1)};
    run_chi2(&c, "cosine hemisphere", 500);
}

/* The reflection pdf: integral over the upper hemisphere of PDF_*_Reflection equals the
 * probability that wi = reflect(wo, wm) lands above the horizon, estimated by sampling
 * (binomial standard error; 4 sigma + quadrature error). */
static double refl_integrand(double theta, double phi, void *user) {
    sampler_case *c = user;
    rtpbr_v3 wi = v3_spherical(theta, phi);
    return c->kind == SAMPLER_GGX ? rtpbr_PDF_GGX_Reflection(c->wo, wi, c->ax, c->ay)
                                  : rtpbr_PDF_Beckmann_Reflection(c->wo, wi, c->ax, c->ay);
}

static void test_reflection_pdf(void **state) {
    (void)state;
    const float alphas[] = {0.05f, 0.3f, 0.8f};
    for (int k = 0; k < 2; k++)
        for (int a = 0; a < 3; a++) {
            sampler_case c = {k == 0 ? SAMPLER_GGX : SAMPLER_BECKMANN, alphas[a], alphas[a], v3_spherical(1.2, 0.0)};
            /* the reflected lobe is centred off the normal: integrate without warping */
            double integral = test_integrate_hemisphere(refl_integrand, &c, 1.0, 600, 720);
            test_rng rng = test_rng_make(900 + k * 3 + a);
            int above = 0, n = 400000;
            for (int i = 0; i < n; i++) {
                rtpbr_v3 wm = sample_of(&c, test_rng_float(&rng), test_rng_float(&rng));
                double d = c.wo.x * wm.x + c.wo.y * wm.y + c.wo.z * wm.z;
                if (2.0 * d * wm.z - c.wo.z > 0.0) above++;
            }
            double frac = (double)above / n;
            double sigma = sqrt(frac * (1.0 - frac) / n);
            print_message("%s a=%.2f: integral of reflection pdf %.5f, sampled fraction above horizon %.5f\n",
                          k == 0 ? "GGX" : "Beckmann", alphas[a], integral, frac);
            assert_true(fabs(integral - frac) <= 4.0 * sigma + 2e-3);
        }
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_ggx_vndf),
                cmocka_unit_test(test_beckmann_vndf),
                cmocka_unit_test(test_cosine),
                cmocka_unit_test(test_reflection_pdf))
