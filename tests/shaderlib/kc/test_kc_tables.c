// tests/shaderlib/kc: the committed Kulla-Conty tables compile as C11 and hold physically required
// values: albedos in [0, 1], E_F <= E, a mirror (r = 0) reflects everything with F = 1 and
// exactly the Fresnel average with the dielectric Fresnel, and roughness only loses energy.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include "test_main.h"

#include <luts/rtpbr_kc_tables.h>

#define KC_N RTPBR_KC_SIZE
#define KC_NE RTPBR_KC_SIZE_ETA
#define KC_TOL (4.0 * RTPBR_KC_MAX_STDERR)

// Unpolarised Fresnel reflectance of a dielectric interface (Born & Wolf sec. 1.5.2), written
// here independently of the shader library.
static double fresnel_dielectric(double c, double eta) {
    double s2 = (1.0 - c * c) / (eta * eta);
    if (s2 >= 1.0)
        return 1.0;
    double ct = sqrt(1.0 - s2);
    double rs = (c - eta * ct) / (c + eta * ct);
    double rp = (eta * c - ct) / (eta * c + ct);
    return 0.5 * (rs * rs + rp * rp);
}

static void test_ranges(void **state) {
    (void)state;
    for (int v = 0; v < RTPBR_KC_VARIANTS; v++) {
        for (int r = 0; r < KC_N; r++) {
            assert_true(isfinite(rtpbr_kc_Eavg[v][r]) && rtpbr_kc_Eavg[v][r] >= 0.0f &&
                        rtpbr_kc_Eavg[v][r] <= 1.0 + KC_TOL);
            for (int m = 0; m < KC_N; m++) {
                float e = rtpbr_kc_E[v][r][m];
                assert_true(isfinite(e) && e >= 0.0f && e <= 1.0 + KC_TOL);
                for (int k = 0; k < KC_NE; k++) {
                    float ef = rtpbr_kc_EF[v][k][r][m];
                    assert_true(isfinite(ef) && ef >= 0.0f && ef <= e + 1e-6f); // same samples, F <= 1
                }
                // eta = 1: no interface. Node 0 (mu = 1e-4) is excluded: F_Dielectric(c, 1)
                // returns 1 for c < ~3e-4 (1 - c^2 rounds to 1 in float, cos_t to 0).
                if (m > 0)
                    assert_true(rtpbr_kc_EF[v][0][r][m] < 1e-4f);
            }
        }
    }
}

static void test_mirror_limit(void **state) {
    (void)state;
    for (int v = 0; v < RTPBR_KC_VARIANTS; v++) {
        // r = 0 (alpha = 1e-3): nothing is masked away from grazing angles, E = 1. The fast
        // visibility approximations are not exact there: Hammon's loses ~1% at mu = 0.1.
        const int fast = v == RTPBR_KC_VARIANT_ggx_fast || v == RTPBR_KC_VARIANT_beckmann_fast;
        for (int m = 6; m < KC_N; m++) // mu >= (6/31)^2 = 0.037
            assert_true(fabs(rtpbr_kc_E[v][0][m] - 1.0) < (fast ? 3e-2 : 2e-3));
        // ... and with the dielectric Fresnel, E_F_avg = F_avg = 2 int F(mu) mu dmu.
        for (int k = 1; k < KC_NE; k++) {
            double s = 0.5 * k / (KC_NE - 1.0), eta = (1.0 + s) / (1.0 - s), favg = 0.0;
            const int n = 20000;
            for (int i = 0; i < n; i++) {
                double mu = (i + 0.5) / n;
                favg += 2.0 * mu * fresnel_dielectric(mu, eta) / n;
            }
            assert_true(fabs(rtpbr_kc_EFavg[v][k][0] - favg) < 2e-3);
        }
    }
}

static void test_roughness_loses_energy(void **state) {
    (void)state;
    for (int v = 0; v < RTPBR_KC_VARIANTS; v++) {
        assert_true(fabs(rtpbr_kc_Eavg[v][0] - 1.0) < 1e-3);
        for (int r = 1; r < KC_N; r++)
            assert_true(rtpbr_kc_Eavg[v][r] <= rtpbr_kc_Eavg[v][r - 1] + KC_TOL);
    }
    // GGX height-correlated, alpha = 1: about 0.4 (the "roughly 0.4").
    assert_true(rtpbr_kc_Eavg[RTPBR_KC_VARIANT_ggx_hc][KC_N - 1] > 0.35f &&
                rtpbr_kc_Eavg[RTPBR_KC_VARIANT_ggx_hc][KC_N - 1] < 0.45f);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_ranges),
                cmocka_unit_test(test_mirror_limit),
                cmocka_unit_test(test_roughness_loses_energy))
