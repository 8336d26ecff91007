// Tests of shaderlib/rtpbr/sheen.h and shaderlib/luts/rtpbr_sheen_tables.h (suite 'sheen').
// References are independent of the code under test: the Charlie normalisation by 1D
// quadrature, the fitted Lambda re-typed from Estevez & Kulla 2017's table 1 in double, the
// albedo table against a fresh deterministic 2D quadrature (not the generator's Monte Carlo).
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
extern "C" {
#include "test_main.h"
}

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <cstdio>
#include <limits>

#include <luts/rtpbr_sheen_tables.h>
#include <rtpbr/sheen.h>

#include "sheen_reference.hpp"

using namespace sheenref;

// sheen_neubelt.cpp: the same header compiled with RTPBR_SHEEN_VISIBILITY = NEUBELT.
float sheen_neubelt_V_Sheen(float NoV, float NoL, float alpha);
float sheen_neubelt_BRDF(float NoV, float NoL, float NoH, float roughness);

namespace {

bool finiteNonNeg(float x) { return std::isfinite(x) && x >= 0.0f; }
bool finiteNonNeg(glm::vec3 v) { return finiteNonNeg(v.x) && finiteNonNeg(v.y) && finiteNonNeg(v.z); }

// ---- tests -----------------------------------------------------------------------------------

// int D_Charlie cos_h dw_h = 1 (2 pi int D(cos t) cos t sin t dt, midpoint rule).
void test_d_normalisation(void **) {
    double worst = 0.0;
    for (float r : {0.0f, 0.1f, 0.3f, 0.5f, 0.7f, 1.0f}) {
        float alpha = rtpbr::Sheen_Alpha(r);
        const int n = 200000;
        double sum = 0.0;
        for (int i = 0; i < n; i++) {
            double t = (i + 0.5) / n * 0.5 * kPi;
            sum += double(rtpbr::D_Charlie(float(std::cos(t)), alpha)) * std::cos(t) * std::sin(t);
        }
        double I = sum * 2.0 * kPi * (0.5 * kPi / n);
        worst = std::max(worst, std::fabs(I - 1.0));
    }
    std::printf("D_Charlie normalisation: largest |int D cos - 1| = %.2e\n", worst);
    assert_true(worst < 1e-4);
}

// The sampler draws h with density D cos_h: the fraction of samples with cos_h < c0 matches
// the closed-form CDF 1 - (1 - ... ) = 1 - (1 - c0^2)^((2 + 1/alpha) / 2).
void test_sample_charlie_cdf(void **) {
    for (float r : {0.2f, 0.6f, 1.0f}) {
        float alpha = rtpbr::Sheen_Alpha(r);
        const int n = 256;
        for (float c0 : {0.1f, 0.3f, 0.6f}) {
            int below = 0;
            for (int i = 0; i < n * n; i++) {
                glm::vec3 h = rtpbr::Sample_Charlie(glm::vec2((i % n + 0.5f) / n, (i / n + 0.5f) / n), alpha);
                below += h.z < c0;
                assert_true(std::fabs(glm::length(h) - 1.0f) < 1e-5f);
            }
            // P(cos_h < c0) = P(sin_h > s0) = 1 - s0^(2 + 1/alpha)
            double s0 = std::sqrt(1.0 - double(c0) * c0);
            double expect = 1.0 - std::pow(s0, 2.0 + 1.0 / double(alpha));
            assert_true(std::fabs(double(below) / (n * n) - expect) < 2.0 / n);
        }
    }
}

// Lambda_Charlie / V_Charlie against the formula re-typed in double; V_Neubelt by hand.
void test_visibility_formulas(void **) {
    double worst = 0.0;
    for (float r : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        float alpha = rtpbr::Sheen_Alpha(r);
        for (int i = 0; i <= 40; i++) {
            float c = std::max(1e-3f, float(i) / 40.0f);
            double ref = refLambda(c, alpha);
            worst = std::max(worst, std::fabs(double(rtpbr::Lambda_Charlie(c, alpha)) / ref - 1.0));
            for (float l : {0.05f, 0.5f, 0.95f}) {
                double v = refV(0, c, l, alpha);
                worst = std::max(worst, std::fabs(double(rtpbr::V_Charlie(c, l, alpha)) / v - 1.0));
            }
        }
        // Continuity of the mirrored fit at cos = 0.5.
        double below = rtpbr::Lambda_Charlie(0.4999f, alpha), above = rtpbr::Lambda_Charlie(0.5001f, alpha);
        assert_true(std::fabs(below / above - 1.0) < 1e-3);
    }
    std::printf("Lambda_Charlie / V_Charlie vs the double-precision formula: largest relative error %.2e\n", worst);
    assert_true(worst < 2e-5);
    // Hand values: 1 / (4 (0.5 + 0.5 - 0.25)) = 1/3; 1 / (4 (1 + 0.2 - 0.2)) = 1/4.
    assert_true(std::fabs(rtpbr::V_Neubelt(0.5f, 0.5f) - 1.0f / 3.0f) < 1e-6f);
    assert_true(std::fabs(rtpbr::V_Neubelt(1.0f, 0.2f) - 0.25f) < 1e-6f);
    // The softened Lambda equals Lambda at normal incidence and exceeds it towards the horizon.
    assert_true(std::fabs(rtpbr::Lambda_CharlieSoftened(1.0f, 0.25f) / rtpbr::Lambda_Charlie(1.0f, 0.25f) - 1.0f) < 1e-5f);
    assert_true(rtpbr::Lambda_CharlieSoftened(0.1f, 0.25f) > rtpbr::Lambda_Charlie(0.1f, 0.25f));
}

// RTPBR_SHEEN_VISIBILITY picks the visibility of V_Sheen and BRDF_Sheen (default Charlie).
void test_visibility_flag(void **) {
    for (float v : {0.1f, 0.5f, 0.9f})
        for (float l : {0.2f, 0.7f}) {
            float a = rtpbr::Sheen_Alpha(0.6f);
            assert_true(rtpbr::V_Sheen(v, l, a) == rtpbr::V_Charlie(v, l, a));
            assert_true(sheen_neubelt_V_Sheen(v, l, a) == rtpbr::V_Neubelt(v, l));
            float nh = 0.4f;
            float ref = rtpbr::D_Charlie(nh, a) * rtpbr::V_Neubelt(v, l);
            assert_true(std::fabs(sheen_neubelt_BRDF(v, l, nh, 0.6f) - ref) <= 1e-6f * ref);
            assert_true(rtpbr::V_Charlie(v, l, a) != rtpbr::V_Neubelt(v, l));
        }
}

void test_reciprocity(void **) {
    uint64_t s = 12345;
    auto uni = [&]() {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return float(s >> 40) / 16777216.0f;
    };
    auto dir = [&]() {
        float z = 0.01f + 0.99f * uni(), p = 6.2831853f * uni(), r = std::sqrt(1.0f - z * z);
        return glm::vec3(r * std::cos(p), r * std::sin(p), z);
    };
    double worst = 0.0;
    for (int i = 0; i < 2000; i++) {
        glm::vec3 a = dir(), b = dir();
        float rough = uni();
        glm::vec3 c(1.0f, 0.5f, 0.25f);
        glm::vec3 f1 = rtpbr::BRDF_SheenLocal(c, rough, a, b), f2 = rtpbr::BRDF_SheenLocal(c, rough, b, a);
        double d = std::fabs(double(f1.x) - double(f2.x)) / std::max(1e-30, double(std::max(f1.x, f2.x)));
        worst = std::max(worst, d);
        // The colour scales the lobe: f = sheenColor D V.
        assert_true(std::fabs(f1.y - 0.5f * f1.x) <= 1e-6f * f1.x + 1e-30f);
    }
    std::printf("reciprocity: largest relative difference %.2e\n", worst);
    assert_true(worst < 1e-5);
}

void test_edge_inputs(void **) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const float values[] = {nan, -inf, -1.0f, 0.0f, 1e-38f, 1e-7f, 0.5f, 1.0f, 2.0f, inf};
    const glm::vec3 dirs[] = {glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0.9999f, 0, 0.0141f),
                              glm::vec3(1, 0, 1e-30f), glm::vec3(0, 0, -1), glm::vec3(nan, 0, 1),
                              glm::vec3(inf, 0, 1), glm::vec3(-1, 0, 1e-6f)};
    for (float v : values) {
        glm::vec3 c(v, 0.5f, v);
        for (float r : values) {
            for (glm::vec3 wo : dirs)
                for (glm::vec3 wi : dirs) {
                    assert_true(finiteNonNeg(rtpbr::BRDF_SheenLocal(c, r, wo, wi)));
                    float a = rtpbr::Sheen_Alpha(r);
                    assert_true(finiteNonNeg(rtpbr::PDF_SheenLobe(wo, wi, a)));
                }
            for (float x : values) {
                float a = rtpbr::Sheen_Alpha(r);
                assert_true(finiteNonNeg(rtpbr::BRDF_Sheen(c, r, x, v, x)));
                assert_true(finiteNonNeg(rtpbr::D_Charlie(x, a)));
                assert_true(finiteNonNeg(rtpbr::D_Charlie(x, r)));
                assert_true(finiteNonNeg(rtpbr::V_Charlie(x, v, a)));
                assert_true(finiteNonNeg(rtpbr::V_Charlie(x, v, r)));
                assert_true(finiteNonNeg(rtpbr::V_Neubelt(x, v)));
                assert_true(finiteNonNeg(rtpbr::Lambda_Charlie(x, a)));
                assert_true(finiteNonNeg(rtpbr::Lambda_CharlieSoftened(x, a)));
                float s = rtpbr::Sheen_AlbedoScaling(c, x, r);
                assert_true(s >= 0.0f && s <= 1.0f);
                s = rtpbr::Sheen_AlbedoScalingView(c, x);
                assert_true(s >= 0.0f && s <= 1.0f);
                glm::vec2 uv = rtpbr::Sheen_TableCoord(x, r);
                assert_true(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f);
                assert_true(finiteNonNeg(rtpbr::Sheen_LtcScale(glm::vec4(x, 0, 0, 0), c)));
            }
            glm::vec3 h = rtpbr::Sample_Charlie(glm::vec2(v, 0.3f), rtpbr::Sheen_Alpha(r));
            assert_true(std::isfinite(h.x) && std::isfinite(h.z));
        }
    }
    // Hand value of the layering: sheenColor (0.8, 0.4, 0.2), E(NoV) 0.25, E(NoL) 0.5:
    // min(1 - 0.8 * 0.25, 1 - 0.8 * 0.5) = 0.6.
    assert_true(std::fabs(rtpbr::Sheen_AlbedoScaling(glm::vec3(0.8f, 0.4f, 0.2f), 0.25f, 0.5f) - 0.6f) < 1e-6f);
    assert_true(std::fabs(rtpbr::Sheen_AlbedoScalingView(glm::vec3(0.8f, 0.4f, 0.2f), 0.25f) - 0.8f) < 1e-6f);
    // Black sheen colour: no lobe.
    glm::vec3 f = rtpbr::BRDF_SheenLocal(glm::vec3(0.0f), 0.5f, glm::vec3(0.6f, 0, 0.8f), glm::vec3(-0.6f, 0, 0.8f));
    assert_true(f.x == 0.0f && f.y == 0.0f && f.z == 0.0f);
}

// The density of Sample_SheenLobe: its integral over the upper hemisphere (quadrature of
// PDF_SheenLobe) equals the fraction of samples above the horizon.
void test_sampling_density(void **) {
    for (float r : {0.15f, 0.5f, 1.0f})
        for (float mu : {0.1f, 0.6f, 1.0f}) {
            float alpha = rtpbr::Sheen_Alpha(r);
            glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
            const int n = 400;
            double integral = 0.0;
            for (int i = 0; i < n; i++)
                for (int j = 0; j < 2 * n; j++) {
                    double u = (i + 0.5) / n, cl = u * u, sl = std::sqrt(1.0 - cl * cl), ph = (j + 0.5) / (2 * n) * 2.0 * kPi;
                    glm::vec3 wi(float(sl * std::cos(ph)), float(sl * std::sin(ph)), float(cl));
                    integral += double(rtpbr::PDF_SheenLobe(wo, wi, alpha)) * (2.0 * u / n) * (kPi / n);
                }
            const int m = 512;
            int above = 0;
            for (int k = 0; k < m * m; k++) {
                glm::vec3 wi = rtpbr::Sample_SheenLobe(wo, glm::vec2((k % m + 0.5f) / m, (k / m + 0.5f) / m), alpha);
                above += wi.z > 0.0f;
            }
            double frac = double(above) / (m * m);
            assert_true(std::fabs(integral - frac) < 5e-3);
        }
}

// The committed E_sheen table against a fresh deterministic quadrature (double precision,
// independent formulas), on a subset of nodes of both variants.
void test_albedo_table(void **) {
    double worst = 0.0, worstRel = 0.0;
    for (int v = 0; v < RTPBR_SHEEN_VARIANTS; v++)
        for (int ir : {0, 3, 8, 15, 23, 31})
            for (int imu : {0, 2, 5, 11, 20, 31}) {
                double x = double(imu) / (RTPBR_SHEEN_SIZE - 1);
                double mu = imu == 0 ? 1e-4 : x * x;
                double r = double(ir) / (RTPBR_SHEEN_SIZE - 1);
                double alpha = std::max(r * r, 1e-3);
                double ref = quadratureAlbedo(v, mu, alpha, 1200, 600);
                double tab = rtpbr_sheen_E[v][ir][imu];
                double d = std::fabs(tab - ref);
                worst = std::max(worst, d);
                worstRel = std::max(worstRel, d / std::max(ref, 1e-2));
                // 4 x the largest relative standard error of a cell (0.5%, at the sharpest lobes)
                if (d > 0.02 * ref + 1e-4)
                    std::printf("E mismatch variant %d r %.3f mu %.4g: table %.5f quadrature %.5f\n", v, r, mu, tab, ref);
                assert_true(d <= 0.02 * ref + 1e-4);
            }
    std::printf("E_sheen table vs quadrature: largest |difference| %.2e, largest relative %.2e\n", worst, worstRel);
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_d_normalisation),
                cmocka_unit_test(test_sample_charlie_cdf),
                cmocka_unit_test(test_visibility_formulas),
                cmocka_unit_test(test_visibility_flag),
                cmocka_unit_test(test_reciprocity),
                cmocka_unit_test(test_edge_inputs),
                cmocka_unit_test(test_sampling_density),
                cmocka_unit_test(test_albedo_table))
