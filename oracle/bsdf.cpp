// rtpbr oracle: the material BSDF (see bsdf.h).
#include "bsdf.h"

#include <luts/rtpbr_kc_tables.h>
#include <luts/rtpbr_sheen_tables.h>
#include <rtpbr/material.h>
#include <rtpbr/microfacet.h>
#include <rtpbr/sampling.h>
#include <rtpbr/sheen.h>

#include <algorithm>

namespace rtpbr_oracle {

namespace {

float luminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
constexpr float kClearcoatF0 = rtpbr::RTPBR_MATERIAL_COAT_F0; // KHR_materials_clearcoat: ior 1.5
constexpr float kInvPi = 0.31830988618379067f;

float muOfNode(int i, int n) {
    float x = float(i) / float(n - 1);
    return i == 0 ? 1e-4f : x * x;
}

// An albedo table E[r][x] of n x n nodes (x = sqrt(mu), r at i / (n - 1)), bilinear at (mu, r).
template <int n>
float albedoBilinear(const float (&E)[n][n], float mu, float r) {
    float fx = std::sqrt(glm::clamp(mu, 0.0f, 1.0f)) * float(n - 1), fr = glm::clamp(r, 0.0f, 1.0f) * float(n - 1);
    int x0 = std::min(n - 2, int(fx)), r0 = std::min(n - 2, int(fr));
    float ax = fx - float(x0), ar = fr - float(r0);
    return (1.0f - ar) * ((1.0f - ax) * E[r0][x0] + ax * E[r0][x0 + 1]) +
           ar * ((1.0f - ax) * E[r0 + 1][x0] + ax * E[r0 + 1][x0 + 1]);
}

// Single-scattering albedo E(mu, r) of GGX with F = 1 (the Kulla-Conty table, height-correlated
// Smith), bilinear on the table's nodes. Used only to shape MIS weights.
float singleScatterAlbedo(float mu, float r) {
    return albedoBilinear<RTPBR_KC_SIZE>(rtpbr_kc_E[RTPBR_KC_VARIANT_ggx_hc], mu, r);
}

// E_sheen(mu, r) of the charlie lobe (V_Charlie, sheen.h's default), bilinear on the nodes of
// the committed table.
float sheenAlbedo(float mu, float r) {
    return albedoBilinear<RTPBR_SHEEN_SIZE>(rtpbr_sheen_E[RTPBR_SHEEN_VARIANT_charlie], mu, r);
}

} // namespace

// ---- LayerAlbedo ------------------------------------------------------------------------------

LayerAlbedo::LayerAlbedo(float eta, int walksPerNode) : eta_(eta) {
    const int n = kNodes;
    ConductorFresnel F;
    F.kind = ConductorFresnel::Kind::Dielectric;
    F.eta = vec3(eta);
    for (int s = 0; s < 2; s++) {
        e_[s].assign(size_t(n) * n, 0.0f);
        eavg_[s].assign(size_t(n), 0.0f);
    }
    for (int ir = 0; ir < n; ir++) {
        float r = float(ir) / float(n - 1);
        float alpha = r * r;
        MicrosurfaceGGX ms(alpha, alpha);
        for (int ix = 0; ix < n; ix++) {
            float mu = muOfNode(ix, n);
            vec3 wi(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
            Rng rng(uint64_t(ir * n + ix), 0x6c61796572ull);
            double sum = 0.0, sumSingle = 0.0;
            for (int k = 0; k < walksPerNode; k++) {
                vec3 wo, weight;
                int order = 0;
                if (conductorSample(ms, F, wi, rng, &wo, &weight, &order)) {
                    sum += weight.x;
                    if (order == 1)
                        sumSingle += weight.x;
                }
            }
            e_[0][size_t(ir * n + ix)] = float(sum / walksPerNode);
            e_[1][size_t(ir * n + ix)] = float(sumSingle / walksPerNode);
        }
        // Es_avg = 2 int E mu dmu = 4 int E(x^2) x^3 dx (trapezoid on the x nodes).
        for (int s = 0; s < 2; s++) {
            double acc = 0.0;
            for (int ix = 0; ix + 1 < n; ix++) {
                double x0 = double(ix) / (n - 1), x1 = double(ix + 1) / (n - 1);
                double f0 = e_[s][size_t(ir * n + ix)] * x0 * x0 * x0;
                double f1 = e_[s][size_t(ir * n + ix + 1)] * x1 * x1 * x1;
                acc += 0.5 * (f0 + f1) * (x1 - x0);
            }
            eavg_[s][size_t(ir)] = float(4.0 * acc);
        }
    }
}

float LayerAlbedo::E(float mu, float r, bool single) const {
    const int n = kNodes;
    float fx = std::sqrt(glm::clamp(mu, 0.0f, 1.0f)) * float(n - 1);
    float fr = glm::clamp(r, 0.0f, 1.0f) * float(n - 1);
    int x0 = std::min(n - 2, int(fx)), r0 = std::min(n - 2, int(fr));
    float ax = fx - float(x0), ar = fr - float(r0);
    const std::vector<float> &e = e_[single ? 1 : 0];
    auto at = [&](int ri, int xi) { return e[size_t(ri * n + xi)]; };
    return (1.0f - ar) * ((1.0f - ax) * at(r0, x0) + ax * at(r0, x0 + 1)) +
           ar * ((1.0f - ax) * at(r0 + 1, x0) + ax * at(r0 + 1, x0 + 1));
}

float LayerAlbedo::Eavg(float r, bool single) const {
    const int n = kNodes;
    float fr = glm::clamp(r, 0.0f, 1.0f) * float(n - 1);
    int r0 = std::min(n - 2, int(fr));
    float ar = fr - float(r0);
    const std::vector<float> &e = eavg_[single ? 1 : 0];
    return (1.0f - ar) * e[size_t(r0)] + ar * e[size_t(r0 + 1)];
}

// ---- Bsdf -------------------------------------------------------------------------------------

Bsdf::Bsdf(const SurfaceMaterial &m, bool singleScatter, vec3 wo)
    : m_(m), single_(singleScatter), wo_(wo), ms_(m.alphaX, m.alphaY), msClear_(m.coatAlpha, m.coatAlpha) {
    if (!m_.layer)
        m_.specularWeight = 0.0f;
    metalF_.f0 = m.baseColor;
    metalF_.f90 = 1.0f;
    coatF_.kind = ConductorFresnel::Kind::Dielectric;
    coatF_.eta = vec3(m_.layer ? m_.layer->eta() : 1.5f);
    clearF_.f0 = vec3(kClearcoatF0);
    clearF_.f90 = 1.0f;
    if (!(wo.z > 0.0f))
        return;
    essMain_ = singleScatterAlbedo(wo.z, std::sqrt(std::sqrt(ms_.alphaX() * ms_.alphaY())));
    essClear_ = singleScatterAlbedo(wo.z, std::sqrt(msClear_.alphaX()));
    if (m_.disney) {
        initDisney();
        return;
    }
    float fc = rtpbr::F_Schlick1(kClearcoatF0, 1.0f, wo.z);
    baseScale_ = 1.0f - m_.coat * fc;
    m_.sheenColor = rtpbr::Sheen_SanitizeColor(m_.sheenColor);
    sheenMax_ = rtpbr::Sheen_Max3(m_.sheenColor);
    sheen_ = sheenMax_ > 0.0f;
    float sheenScaleO = 1.0f; // the base layer's share at wo (for the lobe probabilities)
    if (sheen_) {
        sheenAlpha_ = rtpbr::Sheen_Alpha(m_.sheenRoughness);
        sheenEo_ = sheenAlbedo(wo.z, glm::clamp(m_.sheenRoughness, 0.0f, 1.0f));
        sheenScaleO = rtpbr::Sheen_AlbedoScalingView(m_.sheenColor, sheenEo_);
        probSheen_ = baseScale_ * std::max(sheenMax_ * std::min(sheenEo_, 1.0f), 0.02f);
    }
    float eo = layerE(wo.z);
    float eavg = m_.layer ? m_.specularWeight * m_.layer->Eavg(m_.tableRoughness, single_) : 0.0f;
    baseFactorO_ = eavg < 0.999f ? std::max(0.0f, 1.0f - eo) / (1.0f - eavg) : 0.0f;
    // Lobe selection by each lobe's albedo at wo (rough for the metal).
    probMetal_ = sheenScaleO * baseScale_ * m_.metallic * std::max(luminance(m_.baseColor), 0.02f);
    probCoat_ = sheenScaleO * baseScale_ * (1.0f - m_.metallic) * std::max(eo, 0.02f);
    probDiffuse_ = sheenScaleO * baseScale_ * (1.0f - m_.metallic) * luminance(m_.baseColor) * std::max(0.0f, 1.0f - eo);
    probClear_ = m_.coat * std::max(fc, 0.02f);
    if (m_.metallic <= 0.0f)
        probMetal_ = 0.0f;
    if (m_.specularWeight <= 0.0f)
        probCoat_ = 0.0f;
    if (m_.coat <= 0.0f)
        probClear_ = 0.0f;
    probSum_ = probMetal_ + probCoat_ + probDiffuse_ + probClear_ + probSheen_;
    if (probSum_ > 0.0f) {
        probMetal_ /= probSum_;
        probCoat_ /= probSum_;
        probDiffuse_ /= probSum_;
        probClear_ /= probSum_;
        probSheen_ /= probSum_;
    }
}

float Bsdf::layerE(float mu) const {
    if (!m_.layer || m_.specularWeight <= 0.0f)
        return 0.0f;
    return m_.specularWeight * m_.layer->E(mu, m_.tableRoughness, single_);
}

float Bsdf::sheenScaling(vec3 wi) const {
    if (!sheen_)
        return 1.0f;
    float ei = sheenAlbedo(wi.z, glm::clamp(m_.sheenRoughness, 0.0f, 1.0f));
    return rtpbr::Sheen_AlbedoScaling(m_.sheenColor, sheenEo_, ei);
}

vec3 Bsdf::sheenEval(vec3 wi) const {
    if (!sheen_)
        return vec3(0.0f);
    return rtpbr::BRDF_SheenLocal(m_.sheenColor, m_.sheenRoughness, wo_, wi) * wi.z;
}

float Bsdf::baseWeight(vec3 wi) const { return baseFactorO_ * std::max(0.0f, 1.0f - layerE(wi.z)); }

vec3 Bsdf::specularEvalOn(const MicrosurfaceGGX &ms, const ConductorFresnel &F, vec3 wi, Rng &rng) const {
    // Single scattering in closed form: the walk's first order is exactly this BRDF (Heitz
    // 2016, sec. 4.3; tests/oracle/test_microsurface.cpp checks it), so only the orders >= 2
    // are estimated by the walk, which removes the first order's estimation noise.
    // BRDF_SpecularLocal with F = 1 (Schlick F0 = 1) is D G2 / (4 NoV NoL); F applied here.
    rtpbr::FresnelParams p = rtpbr::Fresnel_FromF0(vec3(1.0f));
    vec3 hs = wo_ + wi;
    float hl = glm::length(hs);
    if (!(hl > 0.0f))
        return vec3(0.0f);
    vec3 f = rtpbr::BRDF_SpecularLocal(wo_, wi, ms.alphaX(), ms.alphaY(), p) * F.eval(glm::dot(wo_, hs / hl)) * wi.z;
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

// ---- Disney -----------------------------------------------------------------------------------

void Bsdf::initDisney() {
    const rtpbr::DisneyMaterial &d = m_.disneyParams;
    metalF_.f0 = rtpbr::Disney_SpecularF0(rtpbr::Disney_SanitizeMaterial(d));
    metalF_.f90 = 1.0f;
    disneyClearAlpha_ = std::max(rtpbr::Disney_ClearcoatAlpha(rtpbr::Disney_SanitizeMaterial(d)), 0.02f);
    // Lobes: specular walk (probMetal_), diffuse + sheen (probDiffuse_), clearcoat (probClear_).
    float fo = luminance(rtpbr::F_Schlick(metalF_.f0, 1.0f, wo_.z));
    probMetal_ = std::max(fo, 0.02f);
    probDiffuse_ = (1.0f - glm::clamp(d.metallic, 0.0f, 1.0f)) *
                   (luminance(d.baseColor) + glm::clamp(d.sheen, 0.0f, 1.0f) * 0.1f);
    probClear_ = 0.25f * glm::clamp(d.clearcoat, 0.0f, 1.0f) * rtpbr::F_Schlick1(0.04f, 1.0f, wo_.z);
    probSum_ = probMetal_ + probDiffuse_ + probClear_;
    probMetal_ /= probSum_;
    probDiffuse_ /= probSum_;
    probClear_ /= probSum_;
}

vec3 Bsdf::evalDisney(vec3 wi, Rng &rng) const {
    const rtpbr::DisneyMaterial &d = m_.disneyParams;
    vec3 f = (rtpbr::BRDF_DisneyDiffuse(d, wo_, wi) + rtpbr::BRDF_DisneySheen(d, wo_, wi) +
              vec3(rtpbr::BRDF_DisneyClearcoat(d, wo_, wi))) * wi.z;
    if (single_)
        return f + rtpbr::BRDF_DisneySpecular(d, wo_, wi) * wi.z;
    // The walk's first order is Disney's specular lobe (GGX, Smith per RTPBR_SMITH, Schlick).
    return f + rtpbr::BRDF_DisneySpecular(d, wo_, wi) * wi.z + conductorEval(ms_, metalF_, wo_, wi, rng, -2);
}

float Bsdf::pdfMisDisney(vec3 wi) const {
    return probDiffuse_ * wi.z * kInvPi + probMetal_ * specularPdfMis(ms_, essMain_, wi) +
           probClear_ * rtpbr::PDF_GGX_Reflection(wo_, wi, disneyClearAlpha_, disneyClearAlpha_);
}

bool Bsdf::sampleDisney(Rng &rng, BsdfSample *s) const {
    const rtpbr::DisneyMaterial &d = m_.disneyParams;
    float u = rng.uniform();
    if (u < probMetal_) {
        vec3 weight;
        if (!specularSampleOn(ms_, metalF_, rng, &s->wi, &weight))
            return false;
        s->weight = weight / probMetal_;
    } else {
        float u1 = rng.uniform(), u2 = rng.uniform();
        float pdf;
        vec3 f;
        if (u < probMetal_ + probDiffuse_) {
            s->wi = rtpbr::Sample_CosineHemisphere(rtpbr::float2(u1, u2));
            pdf = s->wi.z * kInvPi;
            f = rtpbr::BRDF_DisneyDiffuse(d, wo_, s->wi) + rtpbr::BRDF_DisneySheen(d, wo_, s->wi);
            pdf *= probDiffuse_;
        } else {
            // GTR1 sampled by GGX visible normals of a comparable alpha (any density with the
            // right support works: the weight is f cos / pdf).
            vec3 wm = rtpbr::Sample_GGX_VNDF(wo_, disneyClearAlpha_, disneyClearAlpha_, rtpbr::float2(u1, u2));
            s->wi = rtpbr::Reflect_About(wo_, wm);
            pdf = probClear_ * rtpbr::PDF_GGX_Reflection(wo_, s->wi, disneyClearAlpha_, disneyClearAlpha_);
            f = vec3(rtpbr::BRDF_DisneyClearcoat(d, wo_, s->wi));
        }
        if (!(s->wi.z > 0.0f) || !(pdf > 0.0f))
            return false;
        s->weight = f * (s->wi.z / pdf);
    }
    s->pdfMis = pdfMisDisney(s->wi);
    return true;
}

// ---- evaluation and sampling ------------------------------------------------------------------

vec3 Bsdf::eval(vec3 wi, Rng &rng) const {
    if (!(wi.z > 0.0f) || !(wo_.z > 0.0f))
        return vec3(0.0f);
    if (m_.disney)
        return evalDisney(wi, rng);
    vec3 f(0.0f);
    if (m_.metallic > 0.0f)
        f += m_.metallic * specularEvalOn(ms_, metalF_, wi, rng);
    if (m_.metallic < 1.0f) {
        if (m_.specularWeight > 0.0f)
            f += (1.0f - m_.metallic) * m_.specularWeight * specularEvalOn(ms_, coatF_, wi, rng);
        f += (1.0f - m_.metallic) * baseWeight(wi) * m_.baseColor * (wi.z * kInvPi);
    }
    if (sheen_)
        f = f * sheenScaling(wi) + sheenEval(wi);
    f *= baseScale_;
    if (m_.coat > 0.0f)
        f += m_.coat * specularEvalOn(msClear_, clearF_, wi, rng);
    return f;
}

float Bsdf::specularPdfMis(const MicrosurfaceGGX &ms, float E, vec3 wi) const {
    float p = rtpbr::PDF_GGX_Reflection(wo_, wi, ms.alphaX(), ms.alphaY());
    if (single_)
        return p;
    // The walk leaves after one bounce with probability ~ E(mu_o) (F = 1), after more bounces
    // in a broad, roughly cosine-shaped lobe.
    return E * p + (1.0f - E) * wi.z * kInvPi;
}

float Bsdf::pdfMis(vec3 wi) const {
    if (!(wi.z > 0.0f) || probSum_ <= 0.0f)
        return 0.0f;
    if (m_.disney)
        return pdfMisDisney(wi);
    float p = probDiffuse_ * wi.z * kInvPi;
    if (probMetal_ + probCoat_ > 0.0f)
        p += (probMetal_ + probCoat_) * specularPdfMis(ms_, essMain_, wi);
    if (probClear_ > 0.0f)
        p += probClear_ * specularPdfMis(msClear_, essClear_, wi);
    if (probSheen_ > 0.0f)
        p += probSheen_ * rtpbr::PDF_SheenLobe(wo_, wi, sheenAlpha_);
    return p;
}

bool Bsdf::sample(Rng &rng, BsdfSample *s) const {
    if (probSum_ <= 0.0f)
        return false;
    if (m_.disney)
        return sampleDisney(rng, s);
    float u = rng.uniform();
    vec3 weight;
    if (u < probClear_) {
        if (!specularSampleOn(msClear_, clearF_, rng, &s->wi, &weight))
            return false;
        s->weight = weight * (m_.coat / probClear_);
    } else if (u < probClear_ + probMetal_) {
        if (!specularSampleOn(ms_, metalF_, rng, &s->wi, &weight))
            return false;
        s->weight = weight * (baseScale_ * m_.metallic * sheenScaling(s->wi) / probMetal_);
    } else if (u < probClear_ + probMetal_ + probCoat_) {
        if (!specularSampleOn(ms_, coatF_, rng, &s->wi, &weight))
            return false;
        s->weight = weight * (baseScale_ * (1.0f - m_.metallic) * m_.specularWeight * sheenScaling(s->wi) / probCoat_);
    } else if (u < probClear_ + probMetal_ + probCoat_ + probSheen_) {
        // The sheen lobe by Sample_SheenLobe (half Charlie normals, half uniform): weight f cos / pdf.
        float u1 = rng.uniform();
        float u2 = rng.uniform();
        s->wi = rtpbr::Sample_SheenLobe(wo_, rtpbr::float2(u1, u2), sheenAlpha_);
        float pdf = rtpbr::PDF_SheenLobe(wo_, s->wi, sheenAlpha_);
        if (!(s->wi.z > 0.0f) || !(pdf > 0.0f))
            return false;
        s->weight = sheenEval(s->wi) * (baseScale_ / (probSheen_ * pdf));
    } else {
        if (!(probDiffuse_ > 0.0f))
            return false;
        float u1 = rng.uniform();
        float u2 = rng.uniform();
        s->wi = rtpbr::Sample_CosineHemisphere(rtpbr::float2(u1, u2));
        if (!(s->wi.z > 0.0f))
            return false;
        s->weight = m_.baseColor * (baseScale_ * (1.0f - m_.metallic) * baseWeight(s->wi) * sheenScaling(s->wi) / probDiffuse_);
    }
    s->pdfMis = pdfMis(s->wi);
    return true;
}

} // namespace rtpbr_oracle
