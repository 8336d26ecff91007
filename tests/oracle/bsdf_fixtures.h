// Shared fixtures of the oracle's BSDF tests (test_bsdf.cpp, test_sheen.cpp): an independent
// density to integrate a BSDF's eval with, the check that sampling and evaluation give one
// albedo, and the layered-dielectric albedo table at ior 1.5.
#ifndef RTPBR_TESTS_ORACLE_BSDF_FIXTURES_H
#define RTPBR_TESTS_ORACLE_BSDF_FIXTURES_H

#include "test_common.h"

#include "bsdf.h"
#include "rng.h"

#include <rtpbr/microfacet.h>
#include <rtpbr/sampling.h>

// Half uniform hemisphere, half GGX VNDF reflection of the given alpha: covers sharp and
// broad lobes.
struct Mixture {
    float alpha;
    rtpbr_oracle::vec3 wo;
    rtpbr_oracle::vec3 sample(rtpbr_oracle::Rng &rng) const {
        float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        if (u0 < 0.5f)
            return rtpbr::Reflect_About(wo, rtpbr::Sample_GGX_VNDF(wo, alpha, alpha, rtpbr::float2(u1, u2)));
        float z = u1, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 6.2831853f * u2;
        return rtpbr_oracle::vec3(r * std::cos(phi), r * std::sin(phi), z);
    }
    float pdf(rtpbr_oracle::vec3 wi) const {
        return 0.5f * rtpbr::PDF_GGX_Reflection(wo, wi, alpha, alpha) + (wi.z > 0.0f ? 0.5f / 6.2831853f : 0.0f);
    }
};

// The BSDF's albedo seen from wo, two ways that must agree (4 standard errors + 2e-3 per
// channel): the mean weight of 100000 of its own samples, and the mean of eval / pdf over
// 100000 directions of a Mixture of the material's sharpest lobe's alpha (at least 0.05).
// With checkPdfMis every sampling step also draws one more sample, whose MIS density must be
// positive and finite.
inline void checkAlbedo(const rtpbr_oracle::SurfaceMaterial &m, bool single, rtpbr_oracle::vec3 wo, uint64_t seed,
                        bool checkPdfMis = false) {
    using rtpbr_oracle::vec3;
    rtpbr_oracle::Bsdf bsdf(m, single, wo);
    rtpbr_oracle::Rng rng(seed, 1);
    MeanEstimator bySampling[3], byEval[3];
    for (int i = 0; i < 100000; i++) {
        rtpbr_oracle::BsdfSample s;
        vec3 w = bsdf.sample(rng, &s) ? s.weight : vec3(0.0f);
        for (int c = 0; c < 3; c++)
            bySampling[c].add(w[c]);
        if (checkPdfMis && bsdf.sample(rng, &s))
            assert_true(s.pdfMis > 0.0f && std::isfinite(s.pdfMis));
    }
    float lobeAlpha = m.coat > 0.0f ? m.coatAlpha : m.alphaX;
    Mixture mix{std::max(lobeAlpha, 0.05f), wo};
    for (int i = 0; i < 100000; i++) {
        vec3 wi = mix.sample(rng);
        float p = mix.pdf(wi);
        vec3 f = p > 0.0f ? bsdf.eval(wi, rng) / p : vec3(0.0f);
        for (int c = 0; c < 3; c++)
            byEval[c].add(f[c]);
    }
    for (int c = 0; c < 3; c++)
        EXPECT_AGREE(bySampling[c].mean(), bySampling[c].stderror(), byEval[c].mean(), byEval[c].stderror(), 4.0,
                     2e-3);
}

inline const rtpbr_oracle::LayerAlbedo &layer15() {
    static const rtpbr_oracle::LayerAlbedo table(1.5f, 256);
    return table;
}

#endif
