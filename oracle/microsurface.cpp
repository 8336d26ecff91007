// rtpbr oracle: random walk on the Smith microsurface (see microsurface.h).
#include "microsurface.h"

#include <rtpbr/fresnel.h>
#include <rtpbr/ndf.h>
#include <rtpbr/sampling.h>
#include <rtpbr/smith.h>

#include <cmath>
#include <limits>

namespace rtpbr_oracle {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Uniform height distribution on [-1, 1] (Heitz 2016, sec. 4.1): its CDF C1 and inverse.
float C1(float h) { return glm::clamp(0.5f * (h + 1.0f), 0.0f, 1.0f); }
float invC1(float u) { return glm::clamp(2.0f * u - 1.0f, -1.0f, 1.0f); }

// The walk starts above the microsurface, where C1 = 1.
constexpr float kStartHeight = 2.0f;

bool finite3(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

vec3 reflectAbout(vec3 w, vec3 wm) { return 2.0f * glm::dot(w, wm) * wm - w; }

// Refraction of w (pointing away from the facet, on the side wm points to) through a facet
// with relative IOR eta = n_t / n_i; false on total internal reflection.
bool refractAbout(vec3 w, vec3 wm, float eta, vec3 *out) {
    float cosI = glm::dot(w, wm);
    float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f)
        return false;
    float cosT = std::sqrt(1.0f - sin2T);
    *out = glm::normalize(-w / eta + (cosI / eta - cosT) * wm);
    return true;
}

} // namespace

vec3 ConductorFresnel::eval(float cosTheta) const {
    switch (kind) {
    case Kind::Conductor: return rtpbr::F_Conductor(cosTheta, eta, k);
    case Kind::Dielectric: return vec3(rtpbr::F_Dielectric(cosTheta, eta.x));
    case Kind::Schlick: break;
    }
    return rtpbr::F_Schlick(f0, f90, cosTheta);
}

MicrosurfaceGGX::MicrosurfaceGGX(float alphaX, float alphaY)
    : ax_(rtpbr::Alpha_Clamp(alphaX)), ay_(rtpbr::Alpha_Clamp(alphaY)) {}

float MicrosurfaceGGX::lambda(vec3 w) const {
    if (w.z > 0.9999f)
        return 0.0f;
    if (w.z < -0.9999f)
        return -1.0f;
    if (w.z >= 0.0f)
        return rtpbr::Lambda_GGX_Aniso(w, ax_, ay_);
    return -1.0f - rtpbr::Lambda_GGX_Aniso(-w, ax_, ay_);
}

float MicrosurfaceGGX::projectedArea(vec3 w) const {
    // For GGX, (1 + Lambda(w)) w.z = (w.z + sqrt(w.z^2 + ax^2 wx^2 + ay^2 wy^2)) / 2 for
    // both signs of w.z (Heitz 2014, eq. 86 with Lambda(-w) = -1 - Lambda(w)); this form has
    // no division and stays exact at grazing angles, where the Lambda form is 0 * Inf.
    float A = (ax_ * w.x) * (ax_ * w.x) + (ay_ * w.y) * (ay_ * w.y);
    return 0.5f * (w.z + std::sqrt(w.z * w.z + A));
}

float MicrosurfaceGGX::G1(vec3 w, float h) const {
    if (w.z > 0.9999f)
        return 1.0f;
    if (!(w.z > 0.0f))
        return 0.0f;
    return std::pow(C1(h), lambda(w));
}

float MicrosurfaceGGX::D(vec3 wm) const { return rtpbr::D_GGX_Aniso(wm.z, wm.x, wm.y, ax_, ay_); }

float MicrosurfaceGGX::Dvis(vec3 w, vec3 wm) const {
    float c = glm::dot(w, wm);
    if (!(c > 0.0f))
        return 0.0f;
    float a = projectedArea(w);
    if (!(a > 0.0f))
        return 0.0f;
    return c * D(wm) / a;
}

vec3 MicrosurfaceGGX::sampleVisibleNormal(vec3 w, float u1, float u2) const {
    if (w.z > 0.0f)
        return rtpbr::Sample_GGX_VNDF(w, ax_, ay_, rtpbr::float2(u1, u2));
    // Downward w: the shaderlib sampler covers w.z > 0 only. Dupuy & Benyoub 2023, "Sampling
    // Visible GGX Normals with Spherical Caps": in the stretched (alpha = 1) configuration
    // the reflected directions of the visible normals are uniform on the cap z > -w.z, which
    // holds for any w; unstretch the half vector.
    vec3 wStd = glm::normalize(vec3(w.x * ax_, w.y * ay_, w.z));
    float phi = 6.28318530717958647692f * u1;
    float z = (1.0f - u2) * (1.0f + wStd.z) - wStd.z;
    float sinTheta = std::sqrt(glm::max(0.0f, 1.0f - z * z));
    vec3 hStd = vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), z) + wStd;
    vec3 h = vec3(hStd.x * ax_, hStd.y * ay_, glm::max(hStd.z, 0.0f));
    float l2 = glm::dot(h, h);
    if (!(l2 > 1e-20f))
        return vec3(0.0f, 0.0f, 1.0f);
    return h / std::sqrt(l2);
}

float MicrosurfaceGGX::sampleHeight(vec3 wr, float h, float u) const {
    if (wr.z > 0.9999f)
        return kInf;
    if (wr.z < -0.9999f)
        return invC1(u * C1(h));
    if (std::fabs(wr.z) < 1e-4f)
        return h;
    float g1 = G1(wr, h);
    if (u > 1.0f - g1)
        return kInf;
    float lam = lambda(wr);
    return invC1(C1(h) / std::pow(1.0f - u, 1.0f / lam));
}

// ---- conductor --------------------------------------------------------------------------------

namespace {

// One step of the conductor's random walk at height hr: reflect the ray *wr off a visible
// microfacet (Heitz et al. 2016, sec. 5) and weight *energy by its Fresnel term; false once
// the walk is no longer finite.
bool conductorBounce(const MicrosurfaceGGX &ms, const ConductorFresnel &F, Rng &rng, float hr, vec3 *wr,
                     vec3 *energy) {
    float u1 = rng.uniform();
    float u2 = rng.uniform();
    vec3 wm = ms.sampleVisibleNormal(-*wr, u1, u2);
    *energy *= F.eval(glm::dot(-*wr, wm));
    *wr = reflectAbout(-*wr, wm);
    return finite3(*wr) && std::isfinite(hr);
}

} // namespace

vec3 conductorEval(const MicrosurfaceGGX &ms, const ConductorFresnel &F, vec3 wi, vec3 wo, Rng &rng,
                   int order) {
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f))
        return vec3(0.0f);
    vec3 wr = -wi;
    float hr = kStartHeight;
    vec3 energy(1.0f);
    vec3 sum(0.0f);
    for (int k = 1; k <= kMaxScatteringOrder; k++) {
        hr = ms.sampleHeight(wr, hr, rng.uniform());
        if (hr == kInf)
            break;
        // Next-event estimation towards wo: phase function x Fresnel x masking of wo.
        if (order == 0 || order == k || (order < 0 && k >= -order)) {
            vec3 hs = -wr + wo;
            float l2 = glm::dot(hs, hs);
            if (l2 > 1e-20f) {
                vec3 wh = hs / std::sqrt(l2);
                float c = glm::dot(-wr, wh);
                if (c > 0.0f) {
                    float phase = 0.25f * ms.Dvis(-wr, wh) / c;
                    vec3 I = energy * F.eval(c) * (phase * ms.G1(wo, hr));
                    if (finite3(I))
                        sum += I;
                }
            }
            if (order == k)
                break;
        }
        // Continue the walk: reflect off a visible microfacet.
        if (!conductorBounce(ms, F, rng, hr, &wr, &energy))
            return vec3(0.0f);
    }
    return sum;
}

bool conductorSample(const MicrosurfaceGGX &ms, const ConductorFresnel &F, vec3 wi, Rng &rng, vec3 *wo,
                     vec3 *weight, int *orderOut) {
    if (!(wi.z > 0.0f))
        return false;
    vec3 wr = -wi;
    float hr = kStartHeight;
    vec3 energy(1.0f);
    for (int k = 0; k <= kMaxScatteringOrder; k++) {
        hr = ms.sampleHeight(wr, hr, rng.uniform());
        if (hr == kInf) {
            if (orderOut)
                *orderOut = k;
            *wo = wr;
            *weight = energy;
            return wr.z > 0.0f;
        }
        if (!conductorBounce(ms, F, rng, hr, &wr, &energy))
            return false;
    }
    return false;
}

// ---- dielectric -------------------------------------------------------------------------------

namespace {

// The microsurface seen from inside is the same microsurface mirrored in z: a walk on the
// inside uses mirrored directions and heights (Heitz 2016, sec. 5.3).
struct DielectricWalk {
    const MicrosurfaceGGX &ms;
    float eta; // n_inside / n_outside

    // Samples the facet hit from direction w (pointing away from the facet, on the current
    // side) and scatters: returns the new direction and updates *outside.
    vec3 samplePhase(vec3 w, bool *outside, Rng &rng) const {
        float u1 = rng.uniform();
        float u2 = rng.uniform();
        float etaRel = *outside ? eta : 1.0f / eta;
        vec3 wm = *outside ? ms.sampleVisibleNormal(w, u1, u2) : -ms.sampleVisibleNormal(-w, u1, u2);
        float Fr = rtpbr::F_Dielectric(glm::dot(w, wm), etaRel);
        vec3 t;
        if (rng.uniform() < Fr || !refractAbout(w, wm, etaRel, &t))
            return reflectAbout(w, wm);
        *outside = !*outside;
        return t;
    }

    // Density of leaving along wo after one facet interaction entered from w.
    float evalPhase(vec3 w, vec3 wo, bool wOutside, bool woOutside) const {
        float etaRel = wOutside ? eta : 1.0f / eta;
        // Work in the frame where the current side is up.
        vec3 a = wOutside ? w : -w;
        vec3 b = wOutside ? wo : -wo;
        if (wOutside == woOutside) {
            vec3 hs = a + b;
            float l2 = glm::dot(hs, hs);
            if (!(l2 > 1e-20f))
                return 0.0f;
            vec3 wh = hs / std::sqrt(l2);
            float c = glm::dot(a, wh);
            if (!(c > 0.0f))
                return 0.0f;
            return 0.25f * ms.Dvis(a, wh) / c * rtpbr::F_Dielectric(c, etaRel);
        }
        // Transmission (Walter et al. 2007, eq. 16-17, as a density of wo):
        // eta^2 (1 - F) Dvis(a, wh) |b.wh| / (a.wh + eta b.wh)^2, wh = -normalize(a + eta b).
        vec3 hs = a + etaRel * b;
        float l2 = glm::dot(hs, hs);
        if (!(l2 > 1e-20f))
            return 0.0f;
        vec3 wh = -hs / std::sqrt(l2);
        if (wh.z < 0.0f)
            wh = -wh;
        float ca = glm::dot(a, wh);
        float cb = glm::dot(b, wh);
        if (!(ca > 0.0f) || !(cb < 0.0f))
            return 0.0f;
        float denom = ca + etaRel * cb;
        return etaRel * etaRel * (1.0f - rtpbr::F_Dielectric(ca, etaRel)) * ms.Dvis(a, wh) * (-cb) /
               (denom * denom);
    }

    float height(vec3 wr, float hr, bool outside, float u) const {
        if (outside)
            return ms.sampleHeight(wr, hr, u);
        return -ms.sampleHeight(-wr, -hr, u);
    }

    float masking(vec3 wo, float hr) const { return wo.z > 0.0f ? ms.G1(wo, hr) : ms.G1(-wo, -hr); }
};

} // namespace

float dielectricEval(const MicrosurfaceGGX &ms, float eta, vec3 wi, vec3 wo, Rng &rng, int order) {
    if (wi.z < 0.0f) // from inside: the mirrored configuration with the inverse IOR
        return dielectricEval(ms, 1.0f / eta, -wi, -wo, rng, order);
    if (!(wi.z > 0.0f) || wo.z == 0.0f)
        return 0.0f;
    DielectricWalk walk{ms, eta};
    vec3 wr = -wi;
    float hr = kStartHeight;
    bool outside = true;
    float sum = 0.0f;
    for (int k = 1; k <= kMaxScatteringOrder; k++) {
        hr = walk.height(wr, hr, outside, rng.uniform());
        if (std::isinf(hr))
            break;
        if (order == 0 || order == k) {
            float I = walk.evalPhase(-wr, wo, outside, wo.z > 0.0f) * walk.masking(wo, hr);
            if (std::isfinite(I))
                sum += I;
            if (order == k)
                break;
        }
        wr = walk.samplePhase(-wr, &outside, rng);
        if (!finite3(wr) || !std::isfinite(hr))
            return 0.0f;
    }
    return sum;
}

bool dielectricSample(const MicrosurfaceGGX &ms, float eta, vec3 wi, Rng &rng, vec3 *wo, int *orderOut) {
    if (wi.z < 0.0f) {
        bool ok = dielectricSample(ms, 1.0f / eta, -wi, rng, wo, orderOut);
        *wo = -*wo;
        return ok;
    }
    if (!(wi.z > 0.0f))
        return false;
    DielectricWalk walk{ms, eta};
    vec3 wr = -wi;
    float hr = kStartHeight;
    bool outside = true;
    for (int k = 0; k <= kMaxScatteringOrder; k++) {
        hr = walk.height(wr, hr, outside, rng.uniform());
        if (std::isinf(hr)) {
            if (orderOut)
                *orderOut = k;
            *wo = wr;
            return wr.z != 0.0f;
        }
        wr = walk.samplePhase(-wr, &outside, rng);
        if (!finite3(wr) || !std::isfinite(hr))
            return false;
    }
    return false;
}

} // namespace rtpbr_oracle
