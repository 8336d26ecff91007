/* Fresnel against known values and an independent complex-arithmetic reference.
 * References: Born & Wolf, Principles of Optics, sec. 1.5.2 (dielectric) and 14.2
 * (absorbing media): r_s = (cos_i - n cos_t) / (cos_i + n cos_t),
 * r_p = (n cos_i - cos_t) / (n cos_i + cos_t), cos_t = sqrt(1 - sin_i^2 / n^2), with complex n
 * for conductors, evaluated here in double complex (C99), independent of the library's
 * real-arithmetic form. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <complex.h>
#include "test_main.h"
#include "test_common.h"

static double ref_fresnel(double cos_i, double complex n) {
    double sin2 = 1.0 - cos_i * cos_i;
    double complex cos_t = csqrt(1.0 - sin2 / (n * n));
    double complex rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    double complex rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    return 0.5 * (creal(rs * conj(rs)) + creal(rp * conj(rp)));
}

static void test_dielectric_known_values(void **state) {
    (void)state;
    /* eta = 1.5 at normal incidence: ((1.5 - 1) / (1.5 + 1))^2 = 0.04 */
    assert_float_equal(rtpbr_F_Dielectric(1.0f, 1.5f), 0.04f, 1e-6f);
    assert_float_equal(rtpbr_F0_FromIor(1.5f), 0.04f, 1e-7f);
    /* grazing incidence reflects everything */
    assert_float_equal(rtpbr_F_Dielectric(0.0f, 1.5f), 1.0f, 1e-6f);
    /* Brewster's angle tan(theta_B) = eta: r_p = 0, so F = r_s^2 / 2 */
    double tb = atan(1.5), ci = cos(tb), ct = sqrt(1.0 - sin(tb) * sin(tb) / 2.25);
    double rs = (ci - 1.5 * ct) / (ci + 1.5 * ct);
    assert_float_equal(rtpbr_F_Dielectric((float)ci, 1.5f), (float)(0.5 * rs * rs), 1e-6f);
    /* total internal reflection: from inside glass (cos < 0 flips the interface) past the
     * critical angle asin(1 / 1.5) = 41.8 deg */
    for (int i = 0; i < 100; i++) {
        double theta = asin(1.0 / 1.5) + 1e-4 + (M_PI / 2 - asin(1.0 / 1.5) - 1e-4) * i / 99.0;
        assert_float_equal(rtpbr_F_Dielectric(-(float)cos(theta), 1.5f), 1.0f, 0.0f);
        assert_float_equal(rtpbr_F_Dielectric((float)cos(theta), 1.0f / 1.5f), 1.0f, 0.0f);
    }
    /* against the complex reference at every angle, both sides, several eta */
    const double etas[] = {1.0001, 1.33, 1.5, 2.4, 0.75};
    for (int e = 0; e < 5; e++)
        for (int i = 0; i <= 200; i++) {
            double c = (double)(float)(i / 200.0);
            /* the reference sees the same float-rounded eta as the library */
            double eta = (double)(float)etas[e];
            double ref = ref_fresnel(c, eta);
            assert_true(fabs(rtpbr_F_Dielectric((float)c, (float)etas[e]) - ref) <= 2e-6);
            double ref_in = ref_fresnel(c, (double)(1.0f / (float)etas[e]));
            /* Near the critical angle F has an infinite slope in cos: float rounding of the
             * (e - 1)(e + 1) + c^2 cancellation costs up to ~6e-6 there (measured), so the
             * bound is 1e-5 within 0.01 of the critical cosine and 2e-6 elsewhere. */
            double ein = (double)(1.0f / (float)etas[e]);
            double crit = ein < 1.0 ? sqrt(1.0 - ein * ein) : -1.0;
            double tol = fabs(c - crit) < 0.01 ? 1e-5 : 2e-6;
            assert_true(fabs(rtpbr_F_Dielectric(-(float)c, (float)etas[e]) - ref_in) <= tol);
        }
}

static void test_conductor(void **state) {
    (void)state;
    /* gold-like, copper-like, aluminium-like and a k = 0 "conductor" (a dielectric) */
    const float etas[][3] = {{0.143f, 0.374f, 1.442f}, {0.200f, 0.924f, 1.102f}, {1.66f, 0.88f, 0.52f}, {1.5f, 1.5f, 1.5f}};
    const float ks[][3] = {{3.983f, 2.385f, 1.603f}, {3.912f, 2.452f, 2.142f}, {9.22f, 6.27f, 4.84f}, {0.0f, 0.0f, 0.0f}};
    for (int m = 0; m < 4; m++) {
        rtpbr_v3 eta = v3(etas[m][0], etas[m][1], etas[m][2]);
        rtpbr_v3 k = v3(ks[m][0], ks[m][1], ks[m][2]);
        rtpbr_v3 f0 = rtpbr_F_Conductor(1.0f, eta, k);
        const float *fv = &f0.x;
        for (int ch = 0; ch < 3; ch++) {
            double n = etas[m][ch], kk = ks[m][ch];
            double closed = ((n - 1) * (n - 1) + kk * kk) / ((n + 1) * (n + 1) + kk * kk);
            assert_true(fabs(fv[ch] - closed) <= 1e-6);
        }
        for (int i = 0; i <= 200; i++) {
            double c = i / 200.0;
            rtpbr_v3 f = rtpbr_F_Conductor((float)c, eta, k);
            const float *fp = &f.x;
            for (int ch = 0; ch < 3; ch++) {
                double ref = ref_fresnel(c, etas[m][ch] + I * ks[m][ch]);
                if (fabs(fp[ch] - ref) > 1e-5) print_error("conductor m=%d c=%g ch=%d %g vs %g\n", m, c, ch, fp[ch], ref);
                assert_true(fabs(fp[ch] - ref) <= 1e-5);
            }
        }
    }
}

/* Schlick against the exact dielectric: the maximum absolute error over angles, measured
 * here (and printed) for eta in [1.1, 2.5]. Measured: 0.0357 at eta = 1.5 (worst near
 * cos = 0.09), 0.0192 at eta = 1.5 for cos >= 0.5, 0.0824 at eta = 2.5, 0.21 at eta = 1.1
 * (Schlick's curve rises too early when F0 is tiny). Bounds: those values + 5%. */
static void test_schlick_error(void **state) {
    (void)state;
    double worst_glass = 0.0, worst_glass_steep = 0.0, worst_all = 0.0;
    for (int e = 0; e <= 140; e++) {
        double eta = (double)(float)(1.1 + 0.01 * e);
        float f0 = rtpbr_F0_FromIor((float)eta);
        for (int i = 0; i <= 1000; i++) {
            double c = i / 1000.0;
            double err = fabs(rtpbr_F_Schlick1(f0, 1.0f, (float)c) - ref_fresnel(c, eta));
            if (e == 40) {
                worst_glass = fmax(worst_glass, err);
                if (c >= 0.5) worst_glass_steep = fmax(worst_glass_steep, err);
            }
            worst_all = fmax(worst_all, err);
        }
    }
    print_message("Schlick vs exact dielectric, max abs error: eta 1.5: %.4f (cos >= 0.5: %.4f); eta 1.1..2.5: %.4f\n",
                  worst_glass, worst_glass_steep, worst_all);
    assert_true(worst_glass <= 0.0375);
    assert_true(worst_glass_steep <= 0.0202);
    assert_true(worst_all <= 0.221);
    /* and the RGB form is the scalar form per channel */
    rtpbr_v3 s = rtpbr_F_Schlick(v3(0.04f, 0.5f, 0.9f), 1.0f, 0.3f);
    assert_float_equal(s.y, rtpbr_F_Schlick1(0.5f, 1.0f, 0.3f), 0.0f);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_dielectric_known_values),
                cmocka_unit_test(test_conductor),
                cmocka_unit_test(test_schlick_error))
