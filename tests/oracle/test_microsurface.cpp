// The random walk on the Smith microsurface (oracle/microsurface.h): its first order is the
// shaderlib's single-scattering BRDF, it conserves energy (conductor with F = 1, lossless
// dielectric), it is reciprocal, and what it samples agrees with what it evaluates.
#include "test_common.h"

#include "microsurface.h"
#include "rng.h"

#include <rtpbr/microfacet.h>
#include <rtpbr/sampling.h>

#include <vector>

using namespace rtpbr_oracle;

namespace {

constexpr double kPi = 3.14159265358979323846;

vec3 dirFromAngles(float thetaDeg, float phiDeg) {
    float t = thetaDeg * float(kPi) / 180.0f, p = phiDeg * float(kPi) / 180.0f;
    return vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}

// Density of the mixture used to integrate eval over the upper hemisphere:
// half single-scattering VNDF reflection, half cosine.
struct HemisphereMixture {
    float ax, ay;
    vec3 wi;
    vec3 sample(Rng &rng) const {
        float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        if (u0 < 0.5f) {
            vec3 wm = rtpbr::Sample_GGX_VNDF(wi, ax, ay, rtpbr::float2(u1, u2));
            return rtpbr::Reflect_About(wi, wm);
        }
        return rtpbr::Sample_CosineHemisphere(rtpbr::float2(u1, u2));
    }
    float pdf(vec3 wo) const {
        return 0.5f * rtpbr::PDF_GGX_Reflection(wi, wo, ax, ay) + 0.5f * rtpbr::PDF_CosineHemisphere(wo);
    }
};

// Order 1 of the walk is the microfacet BRDF with height-correlated Smith masking-shadowing
// (Heitz 2016, sec. 4.3): the shaderlib's BRDF_SpecularLocal.
void test_first_order_is_single_scattering(void **) {
    struct Case {
        float ax, ay, ti, pi, to, po;
    } cases[] = {{0.3f, 0.3f, 30, 0, 50, 160}, {0.8f, 0.8f, 70, 10, 20, 200}, {0.2f, 0.6f, 45, 30, 60, 250},
                 {0.5f, 0.5f, 80, 0, 80, 180}};
    ConductorFresnel F;
    F.f0 = vec3(0.7f, 0.5f, 0.3f);
    Rng rng(1, 2);
    for (const Case &c : cases) {
        MicrosurfaceGGX ms(c.ax, c.ay);
        vec3 wi = dirFromAngles(c.ti, c.pi), wo = dirFromAngles(c.to, c.po);
        MeanEstimator est;
        for (int i = 0; i < 200000; i++)
            est.add(conductorEval(ms, F, wi, wo, rng, 1).y);
        rtpbr::FresnelParams p = rtpbr::Fresnel_FromF0(F.f0);
        double ref = rtpbr::BRDF_SpecularLocal(wi, wo, c.ax, c.ay, p).y * wo.z;
        EXPECT_AGREE(est.mean(), est.stderror(), ref, 0.0, 4.0, 1e-4 * ref);
        // The closed-form first order plus the walk's orders >= 2 is the whole walk.
        MeanEstimator all, split;
        for (int i = 0; i < 100000; i++) {
            all.add(conductorEval(ms, F, wi, wo, rng, 0).y);
            split.add(ref + conductorEval(ms, F, wi, wo, rng, -2).y);
        }
        EXPECT_AGREE(all.mean(), all.stderror(), split.mean(), split.stderror(), 4.0, 1e-5);
        std::printf("walk se %.3g, closed-form first order + walk se %.3g\n", all.stderror(), split.stderror());
    }
}

// A conductor with F = 1 loses no energy: every sampled walk leaves upwards with weight 1,
// and the evaluated BSDF integrates to 1 over the hemisphere.
void test_conductor_white_furnace(void **) {
    ConductorFresnel F; // Schlick with F0 = 1: F = 1
    Rng rng(3, 4);
    for (float alpha : {0.1f, 0.5f, 1.0f})
        for (float theta : {0.0f, 45.0f, 80.0f}) {
            MicrosurfaceGGX ms(alpha, alpha);
            vec3 wi = dirFromAngles(theta, 20.0f);
            int lost = 0;
            for (int i = 0; i < 20000; i++) {
                vec3 wo, w;
                if (!conductorSample(ms, F, wi, rng, &wo, &w) || !(wo.z > 0.0f) || w != vec3(1.0f))
                    lost++;
            }
            assert_int_equal(lost, 0);
            HemisphereMixture mix{alpha, alpha, wi};
            MeanEstimator est;
            for (int i = 0; i < 100000; i++) {
                vec3 wo = mix.sample(rng);
                float p = mix.pdf(wo);
                est.add(p > 0.0f ? conductorEval(ms, F, wi, wo, rng).x / p : 0.0);
            }
            EXPECT_AGREE(est.mean(), est.stderror(), 1.0, 0.0, 4.0, 2e-3);
        }
}

// Sampling and evaluation describe the same BSDF: with a coloured Fresnel the mean sample
// weight (the albedo by sampling) equals the integral of the evaluation.
void test_conductor_sampling_matches_evaluation_albedo(void **) {
    ConductorFresnel F;
    F.f0 = vec3(0.9f, 0.5f, 0.2f);
    Rng rng(5, 6);
    for (float alpha : {0.3f, 0.9f}) {
        MicrosurfaceGGX ms(alpha, 0.7f * alpha);
        vec3 wi = dirFromAngles(60.0f, 45.0f);
        MeanEstimator bySampling, byEval;
        for (int i = 0; i < 100000; i++) {
            vec3 wo, w;
            bySampling.add(conductorSample(ms, F, wi, rng, &wo, &w) ? w.z : 0.0);
        }
        HemisphereMixture mix{alpha, 0.7f * alpha, wi};
        for (int i = 0; i < 100000; i++) {
            vec3 wo = mix.sample(rng);
            float p = mix.pdf(wo);
            byEval.add(p > 0.0f ? conductorEval(ms, F, wi, wo, rng).z / p : 0.0);
        }
        EXPECT_AGREE(bySampling.mean(), bySampling.stderror(), byEval.mean(), byEval.stderror(), 4.0, 1e-3);
    }
}

// Chi-square of the sampled directions (F = 1: their density is eval itself) against bin
// integrals of eval, in 8 equal-area rings x 16 azimuths.
void test_conductor_sampling_histogram(void **) {
    const int nz = 8, nphi = 16, N = 200000, M = 400;
    MicrosurfaceGGX ms(0.4f, 0.8f);
    ConductorFresnel F;
    vec3 wi = dirFromAngles(60.0f, 30.0f);
    Rng rng(7, 8);
    std::vector<double> counts(nz * nphi, 0.0);
    for (int i = 0; i < N; i++) {
        vec3 wo, w;
        if (!conductorSample(ms, F, wi, rng, &wo, &w))
            continue;
        int iz = std::min(nz - 1, int(wo.z * nz));
        double phi = std::atan2(wo.y, wo.x);
        if (phi < 0.0)
            phi += 2.0 * kPi;
        int ip = std::min(nphi - 1, int(phi / (2.0 * kPi) * nphi));
        counts[iz * nphi + ip] += 1.0;
    }
    double chi2 = 0.0;
    int dof = 0;
    for (int iz = 0; iz < nz; iz++)
        for (int ip = 0; ip < nphi; ip++) {
            double binArea = (1.0 / nz) * (2.0 * kPi / nphi);
            MeanEstimator e;
            for (int k = 0; k < M; k++) {
                double z = (iz + rng.uniform()) / nz;
                double phi = (ip + rng.uniform()) * 2.0 * kPi / nphi;
                double s = std::sqrt(std::max(0.0, 1.0 - z * z));
                vec3 wo(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
                e.add(conductorEval(ms, F, wi, wo, rng).x * binArea);
            }
            double p = e.mean(), varP = e.variance() * binArea * 0.0 + e.variance() / M;
            double expected = N * p;
            double var = N * p * (1.0 - p) + double(N) * N * varP;
            if (expected < 5.0)
                continue;
            double d = counts[iz * nphi + ip] - expected;
            chi2 += d * d / var;
            dof++;
        }
    double limit = dof + 5.0 * std::sqrt(2.0 * dof);
    if (!(chi2 < limit))
        fail_msg("chi2 = %.1f with %d bins (limit %.1f)", chi2, dof, limit);
}

// Reciprocity f(a, b) = f(b, a) of the whole walk and of its second order alone.
void test_conductor_reciprocity(void **) {
    ConductorFresnel F;
    F.f0 = vec3(0.6f, 0.8f, 0.95f);
    Rng rng(9, 10);
    struct Pair {
        float ax, ay;
        vec3 a, b;
    } pairs[] = {{0.5f, 0.5f, dirFromAngles(20, 0), dirFromAngles(75, 120)},
                 {0.9f, 0.3f, dirFromAngles(60, 10), dirFromAngles(40, 250)},
                 {1.0f, 1.0f, dirFromAngles(85, 0), dirFromAngles(30, 90)}};
    for (const Pair &p : pairs) {
        MicrosurfaceGGX ms(p.ax, p.ay);
        for (int order : {0, 2}) {
            MeanEstimator ab, ba;
            for (int i = 0; i < 200000; i++) {
                ab.add(conductorEval(ms, F, p.a, p.b, rng, order).y / p.b.z);
                ba.add(conductorEval(ms, F, p.b, p.a, rng, order).y / p.a.z);
            }
            EXPECT_AGREE(ab.mean(), ab.stderror(), ba.mean(), ba.stderror(), 4.0, 1e-5);
        }
    }
}

// Visible normals seen from below the macro surface (the walk needs them; the shaderlib
// sampler covers upward directions only): chi-square against bin integrals of Dvis.
void test_visible_normals_from_below(void **) {
    const int nz = 8, nphi = 16, N = 200000, Q = 12;
    MicrosurfaceGGX ms(0.6f, 0.3f);
    vec3 w = glm::normalize(vec3(0.6f, 0.2f, -0.5f));
    Rng rng(11, 12);
    std::vector<double> counts(nz * nphi, 0.0);
    for (int i = 0; i < N; i++) {
        vec3 wm = ms.sampleVisibleNormal(w, rng.uniform(), rng.uniform());
        int iz = std::min(nz - 1, std::max(0, int(wm.z * nz)));
        double phi = std::atan2(wm.y, wm.x);
        if (phi < 0.0)
            phi += 2.0 * kPi;
        counts[iz * nphi + std::min(nphi - 1, int(phi / (2.0 * kPi) * nphi))] += 1.0;
    }
    double chi2 = 0.0, total = 0.0;
    int dof = 0;
    for (int iz = 0; iz < nz; iz++)
        for (int ip = 0; ip < nphi; ip++) {
            // Midpoint quadrature of Dvis over the bin (uniform in z is uniform in area).
            double p = 0.0, dA = (1.0 / nz) * (2.0 * kPi / nphi) / (Q * Q);
            for (int a = 0; a < Q; a++)
                for (int b = 0; b < Q; b++) {
                    double z = (iz + (a + 0.5) / Q) / nz;
                    double phi = (ip + (b + 0.5) / Q) * 2.0 * kPi / nphi;
                    double s = std::sqrt(1.0 - z * z);
                    p += ms.Dvis(w, vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z))) * dA;
                }
            total += p;
            double expected = N * p;
            if (expected < 20.0)
                continue;
            double d = counts[iz * nphi + ip] - expected;
            chi2 += d * d / expected;
            dof++;
        }
    // Dvis is normalised (quadrature error aside) and the histogram follows it.
    assert_true(std::fabs(total - 1.0) < 0.02);
    double limit = dof + 5.0 * std::sqrt(2.0 * dof);
    if (!(chi2 < limit))
        fail_msg("chi2 = %.1f with %d bins (limit %.1f)", chi2, dof, limit);
}

// A rough dielectric interface is lossless: eval integrates to 1 over the sphere, from
// outside and from inside; the reflected fraction agrees between sampling and evaluation.
void test_dielectric_energy_and_sampling(void **) {
    const float eta = 1.5f;
    Rng rng(13, 14);
    for (float alpha : {0.3f, 0.7f})
        for (vec3 wi : {dirFromAngles(30, 0), dirFromAngles(70, 40), -dirFromAngles(20, 0), -dirFromAngles(60, 0)}) {
            MicrosurfaceGGX ms(alpha, alpha);
            MeanEstimator total, upper;
            for (int i = 0; i < 200000; i++) {
                float z = 1.0f - 2.0f * rng.uniform();
                float phi = 2.0f * float(kPi) * rng.uniform();
                float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
                vec3 wo(s * std::cos(phi), s * std::sin(phi), z);
                double v = dielectricEval(ms, eta, wi, wo, rng) * 4.0 * kPi;
                total.add(v);
                upper.add(wo.z > 0.0f ? v : 0.0);
            }
            EXPECT_AGREE(total.mean(), total.stderror(), 1.0, 0.0, 4.0, 5e-3);
            MeanEstimator sampledUpper;
            for (int i = 0; i < 100000; i++) {
                vec3 wo;
                sampledUpper.add(dielectricSample(ms, eta, wi, rng, &wo) && wo.z > 0.0f ? 1.0 : 0.0);
            }
            EXPECT_AGREE(sampledUpper.mean(), sampledUpper.stderror(), upper.mean(), upper.stderror(), 4.0, 5e-3);
        }
}

// Reflection is reciprocal; transmission obeys f(a, b) / eta_b^2 = f(b, a) / eta_a^2.
void test_dielectric_reciprocity(void **) {
    const float eta = 1.5f;
    MicrosurfaceGGX ms(0.6f, 0.6f);
    Rng rng(15, 16);
    struct Pair {
        vec3 a, b;
    } pairs[] = {{dirFromAngles(30, 0), dirFromAngles(70, 150)},     // reflection outside
                 {-dirFromAngles(20, 0), -dirFromAngles(50, 100)},   // reflection inside
                 {dirFromAngles(40, 0), -dirFromAngles(25, 160)},    // transmission
                 {dirFromAngles(75, 30), -dirFromAngles(35, 200)}};  // transmission, grazing
    for (const Pair &p : pairs) {
        auto n2 = [eta](vec3 w) { return w.z > 0.0f ? 1.0 : double(eta) * eta; };
        MeanEstimator ab, ba;
        for (int i = 0; i < 200000; i++) {
            ab.add(dielectricEval(ms, eta, p.a, p.b, rng) / std::fabs(p.b.z) / n2(p.b));
            ba.add(dielectricEval(ms, eta, p.b, p.a, rng) / std::fabs(p.a.z) / n2(p.a));
        }
        EXPECT_AGREE(ab.mean(), ab.stderror(), ba.mean(), ba.stderror(), 4.0, 1e-5);
    }
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_first_order_is_single_scattering),
                cmocka_unit_test(test_conductor_white_furnace),
                cmocka_unit_test(test_conductor_sampling_matches_evaluation_albedo),
                cmocka_unit_test(test_conductor_sampling_histogram),
                cmocka_unit_test(test_conductor_reciprocity),
                cmocka_unit_test(test_visible_normals_from_below),
                cmocka_unit_test(test_dielectric_energy_and_sampling),
                cmocka_unit_test(test_dielectric_reciprocity))
