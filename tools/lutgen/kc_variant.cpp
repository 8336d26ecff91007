// One NDF / Smith variant of the Kulla-Conty cell estimator. Compiled once per variant with
// RTPBR_NDF / RTPBR_SMITH / RTPBR_SMITH_FAST, its own RTPBR_CPP_VARIANT namespace and
// KC_SUFFIX (the exported symbol suffix); see kc_compute.hpp.
#include "kc_compute.hpp"

#include <rtpbr/microfacet.h>
#include <rtpbr/sampling.h>

#include "rtpbr_common/rng.h"

#include <cmath>

#define KC_CAT2(a, b) a##_##b
#define KC_CAT(a, b) KC_CAT2(a, b)
#define KC_NAME(fn) KC_CAT(fn, KC_SUFFIX)

namespace kc {

namespace {

std::uint64_t cell_stream(float mu, float r, std::uint64_t replica) {
    std::uint64_t a = static_cast<std::uint64_t>(std::llround(mu * 1e7));
    std::uint64_t b = static_cast<std::uint64_t>(std::llround(r * 1e7));
    return (a * 0x9E3779B97F4A7C15ull) ^ (b * 0xC2B2AE3D27D4EB4Full) ^ (replica * 0x165667B19E3779F9ull);
}

rtpbr::float3 sample_vndf(rtpbr::float3 wo, float alpha, rtpbr::float2 u) {
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
    return rtpbr::Sample_Beckmann_VNDF(wo, alpha, alpha, u);
#else
    return rtpbr::Sample_GGX_VNDF(wo, alpha, alpha, u);
#endif
}

float pdf_reflection(rtpbr::float3 wo, rtpbr::float3 wi, float alpha) {
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
    return rtpbr::PDF_Beckmann_Reflection(wo, wi, alpha, alpha);
#else
    return rtpbr::PDF_GGX_Reflection(wo, wi, alpha, alpha);
#endif
}

} // namespace

void KC_NAME(kc_cell)(float mu, float perceptualRoughness, const float *etas, int nEta,
                      const SampleSpec &spec, CellResult *out) {
    const float alpha = rtpbr::Alpha_FromPerceptual(perceptualRoughness);
    const float NoV = std::fmin(std::fmax(mu, 1e-6f), 1.0f);
    const rtpbr::float3 wo(std::sqrt(1.0f - NoV * NoV), 0.0f, NoV);
    const int n = spec.strata;
    const int nE = nEta < kMaxEta ? nEta : kMaxEta;
    double sumE = 0.0, sumE2 = 0.0;
    double sumF[kMaxEta] = {}, sumF2[kMaxEta] = {};
    for (int rep = 0; rep < spec.replicas; rep++) {
        // PCG32, one stream per cell and replica: the tables do not depend on threading.
        rtpbr_tools::Pcg32 rng(spec.seed, cell_stream(mu, perceptualRoughness, static_cast<std::uint64_t>(rep)));
        double accE = 0.0;
        double accF[kMaxEta] = {};
        for (int a = 0; a < n; a++) {
            for (int b = 0; b < n; b++) {
                rtpbr::float2 u((a + rng.uniform_float()) / n, (b + rng.uniform_float()) / n);
                rtpbr::float3 wm = sample_vndf(wo, alpha, u);
                rtpbr::float3 wi = rtpbr::Reflect_About(wo, wm);
                if (!(wi.z > 0.0f))
                    continue;
                float pdf = pdf_reflection(wo, wi, alpha);
                if (!(pdf > 0.0f))
                    continue;
                float VoH = rtpbr::dot(wo, wm);
                // f_ss with F = 1, as BRDF_Specular computes it (D_Microfacet V_Microfacet), but D
                // from the components of wm: from NoH alone, D_GGX loses its float precision at
                // alpha ~ 1e-3 (1 - NoH ~ 1e-7), which turned into table noise.
                float f = rtpbr::D_Microfacet_Aniso(wm.z, wm.x, wm.y, alpha, alpha) *
                          rtpbr::V_Microfacet(NoV, wi.z, alpha);
                double w = static_cast<double>(f) * wi.z / pdf;
                accE += w;
                for (int k = 0; k < nE; k++)
                    accF[k] += w * rtpbr::F_Dielectric(VoH, etas[k]);
            }
        }
        double m = accE / (n * n);
        sumE += m;
        sumE2 += m * m;
        for (int k = 0; k < nE; k++) {
            double mf = accF[k] / (n * n);
            sumF[k] += mf;
            sumF2[k] += mf * mf;
        }
    }
    const double R = spec.replicas;
    auto stderr_of = [R](double s, double s2) {
        double mean = s / R;
        double var = (s2 / R - mean * mean) * R / (R - 1.0);
        return std::sqrt(var > 0.0 ? var / R : 0.0);
    };
    out->E = sumE / R;
    out->E_err = stderr_of(sumE, sumE2);
    for (int k = 0; k < nE; k++) {
        out->EF[k] = sumF[k] / R;
        out->EF_err[k] = stderr_of(sumF[k], sumF2[k]);
    }
}

float KC_NAME(kc_brdf)(float NoV, float NoL, float NoH, float VoH, float alpha) {
    return rtpbr::BRDF_Specular(NoV, NoL, NoH, VoH, alpha, rtpbr::Fresnel_FromF0(rtpbr::float3(1.0f))).x;
}

} // namespace kc
