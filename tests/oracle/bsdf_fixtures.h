// Shared fixtures of the oracle's BSDF tests (test_bsdf.cpp, test_sheen.cpp): an independent
// density to integrate a BSDF's eval with, and the layered-dielectric albedo table at ior 1.5.
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

inline const rtpbr_oracle::LayerAlbedo &layer15() {
    static const rtpbr_oracle::LayerAlbedo table(1.5f, 256);
    return table;
}

#endif
