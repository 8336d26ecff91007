// rtpbr oracle: the material BSDF (see bsdf.h).
#include "bsdf.h"

#include <rtpbr/microfacet.h>
#include <rtpbr/sampling.h>

#include <algorithm>

namespace rtpbr_oracle {

namespace {

float max3(vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }
float luminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

} // namespace

namespace {
constexpr float kClearcoatF0 = 0.04f; // KHR_materials_clearcoat: ior 1.5
}

Bsdf::Bsdf(const SurfaceMaterial &m, bool singleScatter, vec3 wo)
    : m_(m), single_(singleScatter), wo_(wo), ms_(m.alphaX, m.alphaY), msClear_(m.clearcoatAlpha, m.clearcoatAlpha) {
    metalF_.f0 = m.baseColor;
    metalF_.f90 = 1.0f;
    coatF_.f0 = m.dielectricF0;
    coatF_.f90 = 1.0f;
    clearF_.f0 = vec3(kClearcoatF0);
    clearF_.f90 = 1.0f;
    if (!(wo.z > 0.0f))
        return;
    float fc = rtpbr::F_Schlick1(kClearcoatF0, 1.0f, wo.z);
    baseScale_ = 1.0f - m.clearcoat * fc;
    // Lobe selection by a rough estimate of each lobe's albedo at wo.
    float fo = max3(rtpbr::F_Schlick(m.dielectricF0, 1.0f, wo.z));
    probMetal_ = baseScale_ * m.metallic * std::max(luminance(m.baseColor), 0.02f);
    probCoat_ = baseScale_ * (1.0f - m.metallic) * m.specularWeight * std::max(fo, 0.02f);
    probDiffuse_ = baseScale_ * (1.0f - m.metallic) * luminance(m.baseColor) * (1.0f - m.specularWeight * fo);
    probClear_ = m.clearcoat * std::max(fc, 0.02f);
    if (m.metallic <= 0.0f)
        probMetal_ = 0.0f;
    if (m.specularWeight <= 0.0f)
        probCoat_ = 0.0f;
    if (m.clearcoat <= 0.0f)
        probClear_ = 0.0f;
    probDiffuse_ = std::max(probDiffuse_, 0.0f);
    probSum_ = probMetal_ + probCoat_ + probDiffuse_ + probClear_;
    if (probSum_ > 0.0f) {
        probMetal_ /= probSum_;
        probCoat_ /= probSum_;
        probDiffuse_ /= probSum_;
        probClear_ /= probSum_;
    }
}

float Bsdf::diffuseWeight(vec3 wi) const {
    vec3 h = glm::normalize(wo_ + wi);
    float c = std::fabs(glm::dot(wo_, h));
    return 1.0f - m_.specularWeight * max3(rtpbr::F_Schlick(m_.dielectricF0, 1.0f, c));
}

vec3 Bsdf::specularEvalOn(const MicrosurfaceGGX &ms, const ConductorFresnel &F, vec3 wi, Rng &rng) const {
    // Single scattering in closed form: the walk's first order is exactly this BRDF (Heitz
    // 2016, sec. 4.3; tests/oracle/test_microsurface.cpp checks it), so only the orders >= 2
    // are estimated by the walk, which removes the first order's estimation noise.
    rtpbr::FresnelParams p;
    p.f0 = F.f0;
    p.f90 = F.f90;
    p.eta = vec3(1.5f);
    p.k = vec3(0.0f);
    vec3 f = rtpbr::BRDF_SpecularLocal(wo_, wi, ms.alphaX(), ms.alphaY(), p) * wi.z;
    if (single_)
        return f;
    // The walk starts from the viewer side: Heitz's eval(wi = wo_, wo = wi) is f |wi.z|.
    return f + conductorEval(ms, F, wo_, wi, rng, -2);
}

bool Bsdf::specularSampleOn(const MicrosurfaceGGX &ms, const ConductorFresnel &F, Rng &rng, vec3 *wi,
                            vec3 *weight) const {
    if (single_) {
        float u1 = rng.uniform();
        float u2 = rng.uniform();
        vec3 wm = rtpbr::Sample_GGX_VNDF(wo_, ms.alphaX(), ms.alphaY(), rtpbr::float2(u1, u2));
        *wi = rtpbr::Reflect_About(wo_, wm);
        if (!(wi->z > 0.0f))
            return false;
        // f |wi.z| / pdf = F G2 / G1(wo) for VNDF sampling (Heitz 2018, eq. 19).
        float G1o = rtpbr::G1_FromLambda(ms.lambda(wo_));
        float G2 = rtpbr::G2_Microfacet(wo_, *wi, ms.alphaX(), ms.alphaY());
        *weight = F.eval(glm::dot(wo_, wm)) * (G2 / G1o);
        return true;
    }
    return conductorSample(ms, F, wo_, rng, wi, weight);
}

vec3 Bsdf::eval(vec3 wi, Rng &rng) const {
    if (!(wi.z > 0.0f) || !(wo_.z > 0.0f))
        return vec3(0.0f);
    vec3 f(0.0f);
    if (m_.metallic > 0.0f)
        f += m_.metallic * specularEvalOn(ms_, metalF_, wi, rng);
    if (m_.metallic < 1.0f) {
        if (m_.specularWeight > 0.0f)
            f += (1.0f - m_.metallic) * m_.specularWeight * specularEvalOn(ms_, coatF_, wi, rng);
        f += (1.0f - m_.metallic) * diffuseWeight(wi) * m_.baseColor * (wi.z * 0.31830988618379067f);
    }
    f *= baseScale_;
    if (m_.clearcoat > 0.0f)
        f += m_.clearcoat * specularEvalOn(msClear_, clearF_, wi, rng);
    return f;
}

float Bsdf::pdfMis(vec3 wi) const {
    if (!(wi.z > 0.0f) || probSum_ <= 0.0f)
        return 0.0f;
    float p = probDiffuse_ * wi.z * 0.31830988618379067f;
    if (probMetal_ + probCoat_ > 0.0f)
        p += (probMetal_ + probCoat_) * rtpbr::PDF_GGX_Reflection(wo_, wi, ms_.alphaX(), ms_.alphaY());
    if (probClear_ > 0.0f)
        p += probClear_ * rtpbr::PDF_GGX_Reflection(wo_, wi, msClear_.alphaX(), msClear_.alphaY());
    return p;
}

bool Bsdf::sample(Rng &rng, BsdfSample *s) const {
    if (probSum_ <= 0.0f)
        return false;
    float u = rng.uniform();
    vec3 weight;
    if (u < probClear_) {
        if (!specularSampleOn(msClear_, clearF_, rng, &s->wi, &weight))
            return false;
        s->weight = weight * (m_.clearcoat / probClear_);
    } else if (u < probClear_ + probMetal_) {
        if (!specularSampleOn(ms_, metalF_, rng, &s->wi, &weight))
            return false;
        s->weight = weight * (baseScale_ * m_.metallic / probMetal_);
    } else if (u < probClear_ + probMetal_ + probCoat_) {
        if (!specularSampleOn(ms_, coatF_, rng, &s->wi, &weight))
            return false;
        s->weight = weight * (baseScale_ * (1.0f - m_.metallic) * m_.specularWeight / probCoat_);
    } else {
        if (!(probDiffuse_ > 0.0f))
            return false;
        float u1 = rng.uniform();
        float u2 = rng.uniform();
        s->wi = rtpbr::Sample_CosineHemisphere(rtpbr::float2(u1, u2));
        if (!(s->wi.z > 0.0f))
            return false;
        s->weight = m_.baseColor * (baseScale_ * (1.0f - m_.metallic) * diffuseWeight(s->wi) / probDiffuse_);
    }
    s->pdfMis = pdfMis(s->wi);
    return true;
}

} // namespace rtpbr_oracle
