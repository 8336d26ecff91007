// The fitting itself: BRDF moments, LTC error, Nelder-Mead, continuation over the table.
#include "ltc_fit.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <thread>

#include "rtpbr/disney.h"
#include "rtpbr/microfacet.h"
#include "rtpbr/sampling.h"
#include "rtpbr/sheen.h"

namespace ltcfit {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The least mass above the horizon an LTC may keep where the lobe reaches the horizon (fit_at):
// more than twice the 1 / 48 that the fit's 24 x 24 cosine grid cannot see.
constexpr double kMinVisibleMass = 0.05;

// ---- the BRDF, from the shaderlib -----------------------------------------------------------

// f(V, L) NoL with F = 1 and the density of L under the shaderlib's visible-normal sampler.
struct BrdfSample {
    double value; // f NoL
    double pdf;
};

// Burley's diffuse lobe as fitted: white, dielectric, no subsurface, perceptual roughness r.
rtpbr::DisneyMaterial diffuse_material(float r) {
    rtpbr::DisneyMaterial m = rtpbr::Disney_DefaultMaterial();
    m.baseColor = glm::vec3(1.0f);
    m.metallic = 0.0f;
    m.subsurface = 0.0f;
    m.roughness = r;
    return m;
}

// The terms of a microfacet evaluation that depend only on the view (issue 19: a Beckmann
// evaluation took Lambda(V) twice, in G1 and in V_SmithBeckmann, each an exp and an erfc, and
// the fit evaluates the same view hundreds of thousands of times per cell).
struct ViewTerms {
    float G1 = 0.0f;      // G1(V)
    float lambdaV = 0.0f; // Beckmann: Lambda(min(NoV, 1))
    float FV = 0.0f;      // Burley's diffuse: Disney_SchlickWeight(NoV)
    float ggxV = 0.0f;    // GGX: V_SmithGGXCorrelated's sqrt(NoV^2 (1 - a^2) + a^2)
};

ViewTerms view_terms(Lobe lobe, glm::vec3 V, float alpha) {
    ViewTerms t;
    if (lobe == Lobe::GGX) {
        t.G1 = rtpbr::G1_GGX(V.z, alpha);
        const float v = std::min(V.z, 1.0f), a2 = rtpbr::rtpbr_sq(rtpbr::Alpha_Clamp(alpha));
        t.ggxV = std::sqrt(v * v * (1.0f - a2) + a2);
    } else if (lobe == Lobe::Beckmann) {
        t.G1 = rtpbr::G1_Beckmann(V.z, alpha);
        t.lambdaV = rtpbr::Lambda_Beckmann(std::min(V.z, 1.0f), alpha);
    } else if (lobe == Lobe::DisneyDiffuse)
        t.FV = rtpbr::Disney_SchlickWeight(V.z);
    return t;
}

// V_SmithGGXCorrelated(NoV, NoL, alpha) with its view's square root given (issue 19, second
// round): the library's operations on the same values.
float vis_ggx(float NoV, float NoL, float alpha, float ggxV) {
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return 0.0f;
    const float v = std::min(NoV, 1.0f), l = std::min(NoL, 1.0f);
    const float a2 = rtpbr::rtpbr_sq(rtpbr::Alpha_Clamp(alpha));
    return 0.5f / (l * ggxV + v * std::sqrt(l * l * (1.0f - a2) + a2));
}

// BRDF_DisneyDiffuse(diffuse_material(r), V, L).x for V, L above the horizon and finite, with
// Disney_SchlickWeight(NoV) given (issue 19, second round: the library function takes the whole
// material, sanitises each of its parameters and computes three channels, per sample). The
// library's operations on the same values; what it adds for this material changes no bit: the
// subsurface blend is lerp(Fd, ss, 0) = Fd (ss finite), and metallic 0 and the white base colour
// multiply by 1 (checked against the library on each grid's first row, see error_samples).
float disney_diffuse(glm::vec3 V, glm::vec3 L, float r, float FV) {
    const float roughness = r > 0.0f ? std::min(r, 1.0f) : 0.0f; // Disney_SanitizeMaterial's clamp
    const glm::vec3 sum = V + L;
    const glm::vec3 h = sum * rtpbr::rtpbr_rsqrt(std::max(glm::dot(sum, sum), 1e-30f)); // Disney_HalfVector
    const float LoH = glm::dot(L, h);
    const float FL = rtpbr::Disney_SchlickWeight(L.z);
    const float LoH2 = LoH * LoH;
    const float Fd90 = 0.5f + 2.0f * roughness * LoH2;
    const float Fd = rtpbr::rtpbr_lerp(1.0f, Fd90, FL) * rtpbr::rtpbr_lerp(1.0f, Fd90, FV);
    return rtpbr::Disney_Clamp(1.0f * rtpbr::RTPBR_INV_PI * Fd, rtpbr::RTPBR_FLT_MAX);
}

// V_SmithBeckmann(NoV, NoL, alpha) with Lambda(NoV) given: the same operations on the same
// values, so the same float (a mismatch aborts the fit, see check_view_terms). The library's
// default Smith (height-correlated, exact Lambda) only; other choices take V_SmithBeckmann.
float vis_beckmann(float NoV, float NoL, float alpha, float lambdaV) {
#if !RTPBR_SMITH_FAST && RTPBR_SMITH != RTPBR_SMITH_SEPARABLE
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return 0.0f;
    float v = std::min(NoV, 1.0f);
    float l = std::min(NoL, 1.0f);
    float G = rtpbr::G2_HeightCorrelated(lambdaV, rtpbr::Lambda_Beckmann(l, alpha));
    return G / (4.0f * v * l);
#else
    (void)lambdaV;
    return rtpbr::V_SmithBeckmann(NoV, NoL, alpha);
#endif
}

// alpha: the microfacet lobes' alpha; for Lobe::DisneyDiffuse the perceptual roughness.
// vt: view_terms(lobe, V, alpha), or null to compute them here.
// Inlined (issue 19, second round): with the lobe a constant (ltc_error_for), the lobe's branch
// and the terms of alpha alone are resolved once per loop; the same operations on each sample.
[[gnu::always_inline]] inline BrdfSample brdf_eval(Lobe lobe, glm::vec3 V, glm::vec3 L, float alpha,
                                                   const ViewTerms *vt = nullptr) {
    if (lobe == Lobe::Sheen) { // sampled by Sample_SheenLobe (its density counts below the horizon too)
        double pdf = double(rtpbr::PDF_SheenLobe(V, L, alpha));
        if (!(V.z > 0.0f) || !(L.z > 0.0f))
            return {0.0, pdf};
        glm::vec3 H = glm::normalize(V + L);
        double f = double(rtpbr::D_Charlie(H.z, alpha)) * double(rtpbr::V_Charlie(V.z, L.z, alpha));
        return {f * double(L.z), pdf};
    }
    if (lobe == Lobe::DisneyDiffuse) { // sampled by the cosine: pdf = NoL / pi
        if (!(V.z > 0.0f) || !(L.z > 0.0f))
            return {0.0, 0.0};
        const bool finite = glm::dot(V, V) < 1e30f && glm::dot(L, L) < 1e30f; // Disney_ValidPair
        double f = vt && finite ? double(disney_diffuse(V, L, alpha, vt->FV))
                                : double(rtpbr::BRDF_DisneyDiffuse(diffuse_material(alpha), V, L).x);
        return {f * double(L.z), double(L.z) / kPi};
    }
    glm::vec3 hs = V + L;
    if (!(V.z > 0.0f) || !(glm::dot(hs, hs) > 1e-12f))
        return {0.0, 0.0};
    glm::vec3 H = glm::normalize(hs);
    if (!(H.z > 0.0f))
        return {0.0, 0.0};
    float D, Vis, G1;
    if (lobe == Lobe::GGX) {
        D = rtpbr::D_GGX(H.z, alpha);
        Vis = vt ? vis_ggx(V.z, L.z, alpha, vt->ggxV) : rtpbr::V_SmithGGXCorrelated(V.z, L.z, alpha);
        G1 = vt ? vt->G1 : rtpbr::G1_GGX(V.z, alpha);
    } else {
        D = rtpbr::D_Beckmann(H.z, alpha);
        // Where D is 0 (far from a sharp lobe's peak: D_Beckmann returns 0 for tan^2 / alpha^2
        // > 80) the value below is 0 x Vis = +0 for any finite Vis, and Vis = G2 / (4 NoV NoL)
        // with G2 in (0, 1] is finite once NoV NoL >= 1e-20: Lambda(L) (an exp and an erfc)
        // is skipped there (issue 19; the same value and pdf bits).
        if (vt && D == 0.0f && V.z * L.z >= 1e-20f)
            Vis = 0.0f;
        else
            Vis = vt ? vis_beckmann(V.z, L.z, alpha, vt->lambdaV) : rtpbr::V_SmithBeckmann(V.z, L.z, alpha);
        G1 = vt ? vt->G1 : rtpbr::G1_Beckmann(V.z, alpha);
    }
    // The density of the visible-normal sampler's reflected direction, D_V(h) / (4 VoH) =
    // G1(V) D(h) / (4 NoV) (Heitz & d'Eon 2014), written with the same D value as f: near the
    // peak of a sharp lobe D varies faster than float directions resolve, and a second
    // evaluation (PDF_*_Reflection recomputes h) would not cancel.
    // The sampler also produces directions below the horizon (where f = 0): their density
    // counts too, for the two-strategy estimator to stay unbiased there.
    double pdf = double(G1) * double(D) / (4.0 * double(V.z));
    double value = L.z > 0.0f ? double(D) * double(Vis) * double(L.z) : 0.0;
    return {value, pdf};
}

glm::vec3 brdf_sample(Lobe lobe, glm::vec3 V, float alpha, glm::vec2 u) {
    if (lobe == Lobe::Sheen)
        return rtpbr::Sample_SheenLobe(V, u, alpha);
    if (lobe == Lobe::DisneyDiffuse)
        return rtpbr::Sample_CosineHemisphere(u);
    glm::vec3 wm = lobe == Lobe::GGX ? rtpbr::Sample_GGX_VNDF(V, alpha, alpha, u)
                                     : rtpbr::Sample_Beckmann_VNDF(V, alpha, alpha, u);
    return rtpbr::Reflect_About(V, wm);
}

// ---- the LTC ----------------------------------------------------------------------------

struct Ltc {
    glm::dvec3 X{1, 0, 0}, Y{0, 1, 0}, Z{0, 0, 1};
    double m11 = 1, m22 = 1, m13 = 0;
    glm::dmat3 M{1.0}, invM{1.0};
    double detInvM = 1;

    void update() {
        glm::dmat3 shape(1.0);
        shape[0][0] = m11; // glm: [column][row]
        shape[1][1] = m22;
        shape[2][0] = m13;
        M = glm::dmat3(X, Y, Z) * shape;
        invM = glm::inverse(M);
        detInvM = std::fabs(glm::determinant(invM));
    }
    // The fraction of the LTC above the horizon: the clamped cosine over the hemisphere
    // with normal normalize(M^T z), which is (1 + cos of its angle to z) / 2 (the sky view
    // factor of a tilted plane).
    double mass_above_horizon() const {
        glm::dvec3 m(M[0][2], M[1][2], M[2][2]); // row 2 of M = M^T z
        return 0.5 * (1.0 + m.z / glm::length(m));
    }
    // The normalised LTC density at direction L (unit).
    double eval(glm::dvec3 L) const {
        glm::dvec3 lo = invM * L;
        double l = glm::length(lo);
        double cosTheta = lo.z / l;
        if (!(cosTheta > 0.0))
            return 0.0;
        return cosTheta / kPi * detInvM / (l * l * l);
    }
};

// Sample points of a side x side grid, centred in their cells: deterministic, and every
// fit sees the same points (the error is a smooth function of the parameters).
glm::vec2 grid_point(int i, int side) {
    return glm::vec2((float(i % side) + 0.5f) / float(side), (float(i / side) + 0.5f) / float(side));
}

// The BRDF's sample directions at the points of a side x side grid, in grid order: the same
// directions as brdf_sample(grid_point(i, side)). For Beckmann, Sample_Beckmann_VNDF's costly
// slope inversion (Beckmann_SampleSlopeX: Newton on erfc) depends only on the view (through
// mu) and on u.x, which takes `side` values on the grid: it is computed once per column and
// composed as Sample_Beckmann_VNDF does (same operations, so the same bits; checked against
// Sample_Beckmann_VNDF on the first row of every grid).
// For GGX likewise (issue 19, second round): Sample_GGX_VNDF's cos and sin of phi depend only
// on u.x (once per column), its sinTheta and hStd.z only on u.y (once per row); composed with
// Sample_GGX_VNDF's operations (checked on the first row and the first column of every grid).
std::vector<glm::vec3> ggx_grid_samples(glm::vec3 V, float alpha, int side) {
    std::vector<glm::vec3> out(size_t(side) * size_t(side));
    const float ax = rtpbr::Alpha_Clamp(alpha), ay = rtpbr::Alpha_Clamp(alpha);
    const glm::vec3 wStd = glm::normalize(glm::vec3(V.x * ax, V.y * ay, V.z));
    const float onePlusW = 1.0f + wStd.z;
    const float oneMinusW = (wStd.x * wStd.x + wStd.y * wStd.y) / onePlusW;
    std::vector<float> cosPhi(static_cast<size_t>(side)), sinPhi(static_cast<size_t>(side));
    std::vector<float> sinTheta(static_cast<size_t>(side)), hz(static_cast<size_t>(side));
    for (int k = 0; k < side; k++) {
        const glm::vec2 u = grid_point(k * side + k, side); // column k, row k
        const float phi = rtpbr::RTPBR_TWO_PI * u.x;
        cosPhi[size_t(k)] = glm::cos(phi);
        sinPhi[size_t(k)] = glm::sin(phi);
        sinTheta[size_t(k)] = rtpbr::rtpbr_safe_sqrt(u.y * onePlusW * (oneMinusW + (1.0f - u.y) * onePlusW));
        hz[size_t(k)] = (1.0f - u.y) * (1.0f + wStd.z);
    }
    for (int i = 0; i < side * side; i++) {
        const size_t col = size_t(i % side), row = size_t(i / side);
        const glm::vec3 hStd(sinTheta[row] * cosPhi[col] + wStd.x, sinTheta[row] * sinPhi[col] + wStd.y, hz[row]);
        const glm::vec3 h(hStd.x * ax, hStd.y * ay, std::max(hStd.z, 0.0f));
        const float l2 = glm::dot(h, h);
        const glm::vec3 wm = l2 > 1e-20f ? h * rtpbr::rtpbr_rsqrt(l2) : glm::vec3(0.0f, 0.0f, 1.0f);
        out[size_t(i)] = rtpbr::Reflect_About(V, wm);
    }
    for (int i = 0; i < side; i++) // the composition above must stay Sample_GGX_VNDF's
        if (out[size_t(i)] != brdf_sample(Lobe::GGX, V, alpha, grid_point(i, side)) ||
            out[size_t(i) * size_t(side)] != brdf_sample(Lobe::GGX, V, alpha, grid_point(i * side, side))) {
            fprintf(stderr, "ltcfit: internal error: the GGX grid sampler differs from Sample_GGX_VNDF\n");
            std::abort();
        }
    return out;
}

std::vector<glm::vec3> brdf_grid_samples(Lobe lobe, glm::vec3 V, float alpha, int side) {
    if (lobe == Lobe::GGX && V.z > 0.0f)
        return ggx_grid_samples(V, alpha, side);
    std::vector<glm::vec3> out(size_t(side) * size_t(side));
    if (lobe != Lobe::Beckmann || !(V.z > 0.0f)) {
        for (int i = 0; i < side * side; i++)
            out[size_t(i)] = brdf_sample(lobe, V, alpha, grid_point(i, side));
        return out;
    }
    const float a = rtpbr::Alpha_Clamp(alpha);
    const glm::vec3 wStd = glm::normalize(glm::vec3(V.x * a, V.y * a, V.z));
    const float sinTheta = std::sqrt(wStd.x * wStd.x + wStd.y * wStd.y);
    const float mu = sinTheta > 1e-6f ? wStd.z / sinTheta : 1e6f;
    float cosPhi = 1.0f, sinPhi = 0.0f;
    if (sinTheta > 0.0f) {
        cosPhi = wStd.x / sinTheta;
        sinPhi = wStd.y / sinTheta;
    }
    std::vector<float> sx(static_cast<size_t>(side)), sy(static_cast<size_t>(side));
    for (int k = 0; k < side; k++) {
        glm::vec2 u = grid_point(k * side + k, side); // column k, row k
        sx[size_t(k)] = rtpbr::Beckmann_SampleSlopeX(mu, u.x);
        sy[size_t(k)] = rtpbr::rtpbr_erfinv(2.0f * glm::clamp(u.y, 1e-6f, 1.0f - 1e-6f) - 1.0f);
    }
    for (int i = 0; i < side * side; i++) {
        const float x = (cosPhi * sx[size_t(i % side)] - sinPhi * sy[size_t(i / side)]) * a;
        const float y = (sinPhi * sx[size_t(i % side)] + cosPhi * sy[size_t(i / side)]) * a;
        out[size_t(i)] = rtpbr::Reflect_About(V, glm::normalize(glm::vec3(-x, -y, 1.0f)));
    }
    for (int i = 0; i < side; i++) // the composition above must stay Sample_Beckmann_VNDF's
        if (out[size_t(i)] != brdf_sample(lobe, V, alpha, grid_point(i, side))) {
            fprintf(stderr, "ltcfit: internal error: the Beckmann grid sampler differs from Sample_Beckmann_VNDF\n");
            std::abort();
        }
    return out;
}

struct WeightedDir {
    glm::dvec3 L;
    double w; // f NoL / pdf
};

struct Moments {
    double norm = 0, fresnel = 0, f82 = 0;
    glm::dvec3 avgDir{0, 0, 1};
    std::vector<WeightedDir> samples; // the samples with w > 0, if kept (polygon refinement)
    int sampleCount = 0;
};

// Integrals of f NoL by visible-normal sampling (the weights f NoL / pdf are bounded).
Moments brdf_moments(Lobe lobe, glm::vec3 V, float alpha, int side, bool keep) {
    Moments m;
    m.sampleCount = side * side;
    glm::dvec3 dir(0.0);
    int n = side * side;
    const std::vector<glm::vec3> dirs = brdf_grid_samples(lobe, V, alpha, side);
    const ViewTerms vt = view_terms(lobe, V, alpha);
    for (int i = 0; i < n; i++) {
        glm::vec3 L = dirs[size_t(i)];
        BrdfSample b = brdf_eval(lobe, V, L, alpha, &vt);
        if (!(b.pdf > 0.0))
            continue;
        double w = b.value / b.pdf;
        if (keep && w > 0.0)
            m.samples.push_back({glm::dvec3(L), w});
        double VoH = glm::clamp(double(glm::dot(V, glm::normalize(V + L))), 0.0, 1.0);
        double s = 1.0 - VoH;
        double s5 = s * s * s * s * s;
        m.norm += w;
        m.fresnel += w * s5;
        m.f82 += w * VoH * s5 * s;
        dir += w * glm::dvec3(L);
    }
    m.norm /= n;
    // The diffuse lobe's Fresnel is part of its shape (Fd): no Schlick split, columns 0.
    // The sheen lobe has no Fresnel (KHR_materials_sheen: F = 1): columns 0 as well.
    const bool noFresnel = lobe == Lobe::DisneyDiffuse || lobe == Lobe::Sheen;
    m.fresnel = noFresnel ? 0.0 : m.fresnel / n;
    m.f82 = noFresnel ? 0.0 : m.f82 / n;
    dir.y = 0.0; // isotropic lobes are symmetric about the plane of incidence
    m.avgDir = glm::length(dir) > 0.0 ? glm::normalize(dir) : glm::dvec3(0, 0, 1);
    return m;
}

// The sample points of both strategies for one cell. The BRDF's samples (and their values
// and densities) do not depend on the LTC, so they are drawn once per cell; the LTC's are
// kept as cosine-distributed directions and transformed by each candidate M.
struct ErrorSamples {
    std::vector<glm::dvec3> cosine;
    std::vector<glm::vec3> brdfL;
    std::vector<BrdfSample> brdf;
};

ErrorSamples error_samples(Lobe lobe, glm::vec3 V, float alpha, int side) {
    ErrorSamples es;
    int n = side * side;
    const std::vector<glm::vec3> dirs = brdf_grid_samples(lobe, V, alpha, side);
    const ViewTerms vt = view_terms(lobe, V, alpha);
    for (int i = 0; i < n; i++) {
        glm::vec2 u = grid_point(i, side);
        es.cosine.push_back(glm::dvec3(rtpbr::Sample_CosineHemisphere(u)));
        glm::vec3 L = dirs[size_t(i)];
        es.brdfL.push_back(L);
        es.brdf.push_back(brdf_eval(lobe, V, L, alpha, &vt));
        // the per-view terms must give the library's values (see vis_beckmann), checked on the
        // grid's first row
        if (i < side) {
            const BrdfSample ref = brdf_eval(lobe, V, L, alpha);
            if (ref.value != es.brdf.back().value || ref.pdf != es.brdf.back().pdf) {
                fprintf(stderr, "ltcfit: internal error: the per-view BRDF terms differ from the library's\n");
                std::abort();
            }
        }
    }
    return es;
}

// Multiple-importance estimate of  integral |f NoL - norm D_ltc|^p  (p = 3 for the fit,
// p = 1 for the reported error): each strategy's samples weighted by 1 / (pdf_ltc + pdf_brdf)
// (the balance heuristic with one sample of each per grid point).
// horizon: compare only above the horizon, with the LTC scaled by norm / (its mass above the
// horizon) (the evaluation clips there, so mass below it is neither light nor error).
template <Lobe lobe>
double ltc_error_for(const Ltc &ltc, const ErrorSamples &es, glm::vec3 V, float alpha, double norm, int p, bool horizon) {
    double sum = 0.0;
    const size_t n = es.cosine.size();
    const double scale = horizon ? norm / ltc.mass_above_horizon() : norm;
    auto accumulate = [&](double value, double pdfBrdf, double d, double z) {
        double pdfSum = d + pdfBrdf;
        if (!(pdfSum > 0.0) || (horizon && !(z > 0.0)))
            return;
        double diff = std::fabs(value - scale * d);
        sum += (p == 3 ? diff * diff * diff : p == 2 ? diff * diff : diff) / pdfSum;
    };
    const ViewTerms vt = view_terms(lobe, V, alpha);
    for (size_t i = 0; i < n; i++) {
        // Above the horizon only: a direction under it adds nothing, so skip evaluating it.
        glm::dvec3 L = glm::normalize(ltc.M * es.cosine[i]);
        if (!horizon || L.z > 0.0) {
            BrdfSample b = brdf_eval(lobe, V, glm::vec3(L), alpha, &vt);
            accumulate(b.value, b.pdf, ltc.eval(L), L.z);
        }
        if (!horizon || es.brdfL[i].z > 0.0f)
            accumulate(es.brdf[i].value, es.brdf[i].pdf, ltc.eval(glm::dvec3(es.brdfL[i])), double(es.brdfL[i].z));
    }
    return sum / double(n);
}

double ltc_error(const Ltc &ltc, const ErrorSamples &es, Lobe lobe, glm::vec3 V, float alpha, double norm, int p,
                 bool horizon) {
    switch (lobe) {
    case Lobe::GGX:
        return ltc_error_for<Lobe::GGX>(ltc, es, V, alpha, norm, p, horizon);
    case Lobe::Beckmann:
        return ltc_error_for<Lobe::Beckmann>(ltc, es, V, alpha, norm, p, horizon);
    case Lobe::DisneyDiffuse:
        return ltc_error_for<Lobe::DisneyDiffuse>(ltc, es, V, alpha, norm, p, horizon);
    case Lobe::Sheen:
        break;
    }
    return ltc_error_for<Lobe::Sheen>(ltc, es, V, alpha, norm, p, horizon);
}

// ---- polygon refinement ---------------------------------------------------------------------
//
// What a renderer integrates is the lobe over a polygon, and what is measured (rtpbr-ltc-validate,
// the engine against the oracle) is the relative error of that integral. The L3 distance of
// the distributions is dominated by the lobe's peak: at grazing views (65-80 degrees, r 0.3-0.7)
// it accepts an LTC that puts 2-6x too much light on the viewer's side of the lobe (lights
// between the eye and a far floor) and too little on its flanks. The refinement minimises
// instead the mean squared relative error of the integrals over a fixed set of square lights
// covering the hemisphere, plus squares centred on the lobe (weighted peakWeight):
//   e_k = |norm / mass * I_ltc(k) - I_brdf(k)| / (I_brdf(k) + floor * albedo).

// A square light: centre c at distance 1 from the shading point, its plane's normal d
// pointing away from the shading point (the light faces the point), axes e1, e2, half-size.
// ring >= 0: a floor square (see test_squares), whose error is relative to its ring.
struct TestSquare {
    glm::dvec3 c, d, e1, e2;
    double half = 0, weight = 0;
    int ring = -1;
    double cosCone = 1;     // cos of the largest angle between c and a direction in the square
    glm::dvec3 clipped[8];  // the square clipped to the horizon (constant per cell)
    int clippedCount = 0;
};

// Sutherland-Hodgman against the half-space dot(n, p) >= 0 (convex polygon, at most 8 vertices in,
// at most 10 out).
// (issue 19, second round: each vertex's distance once, not once per edge: the same values.)
int clip_half_space(const glm::dvec3 *in, int n, glm::dvec3 nrm, glm::dvec3 *out) {
    double dist[10];
    for (int i = 0; i < n; i++)
        dist[i] = glm::dot(nrm, in[i]);
    int m = 0;
    for (int i = 0; i < n; i++) {
        glm::dvec3 a = in[i], b = in[(i + 1) % n];
        double da = dist[i], db = dist[(i + 1) % n];
        if (da >= 0.0)
            out[m++] = a;
        if ((da >= 0.0) != (db >= 0.0))
            out[m++] = a + (b - a) * (da / (da - db));
    }
    return m;
}

TestSquare finish_square(TestSquare s) {
    glm::dvec3 p[4] = {s.c - s.half * s.e1 - s.half * s.e2, s.c + s.half * s.e1 - s.half * s.e2,
                       s.c + s.half * s.e1 + s.half * s.e2, s.c - s.half * s.e1 + s.half * s.e2};
    s.cosCone = 1.0;
    for (const glm::dvec3 &q : p) // the farthest direction of a convex polygon is a corner's
        s.cosCone = std::min(s.cosCone, glm::dot(glm::normalize(q), s.c));
    s.cosCone -= 1e-12;
    s.clippedCount = clip_half_space(p, 4, glm::dvec3(0, 0, 1), s.clipped);
    return s;
}

// Facing the shading point.
TestSquare make_square(glm::dvec3 c, double half, double weight) {
    TestSquare s;
    s.c = glm::normalize(c);
    s.d = s.c;
    s.e1 = glm::normalize(std::fabs(s.c.z) < 0.9 ? glm::cross(glm::dvec3(0, 0, 1), s.c) : glm::cross(glm::dvec3(1, 0, 0), s.c));
    s.e2 = glm::cross(s.c, s.e1);
    s.half = half;
    s.weight = weight;
    return finish_square(s);
}

// Horizontal, facing down (a ceiling panel seen from the floor).
TestSquare make_ceiling_square(glm::dvec3 c, double half, double weight, int ring) {
    TestSquare s;
    s.c = glm::normalize(c);
    s.d = glm::dvec3(0, 0, 1);
    s.e1 = glm::dvec3(1, 0, 0);
    s.e2 = glm::dvec3(0, 1, 0);
    s.half = half;
    s.weight = weight;
    s.ring = ring;
    return finish_square(s);
}

glm::dvec3 square_dir(double el, double az) {
    const double deg = kPi / 180.0;
    return glm::dvec3(std::cos(el * deg) * std::cos(az * deg), std::cos(el * deg) * std::sin(az * deg),
                      std::sin(el * deg));
}

// The squares all over the hemisphere, the same for every cell (test_squares' first ones).
// The lobe is symmetric about the plane of incidence (y = 0): azimuths 0 (the viewer's side)
// to 180 degrees (the mirror side) suffice.
std::vector<TestSquare> hemisphere_squares() {
    std::vector<TestSquare> v;
    for (double el : {8.0, 20.0, 35.0, 50.0, 65.0, 80.0, 90.0})
        for (double az = 0.0; az <= 180.0 && (el < 90.0 || az == 0.0); az += 30.0)
            for (double h : {0.15, 0.4, 1.0})
                v.push_back(make_square(square_dir(el, az), h, 1.0));
    return v;
}

// hemisphere_squares(), then the squares of this cell's lobe (and the floor squares).
std::vector<TestSquare> test_squares(glm::dvec3 V, glm::dvec3 avgDir, double alpha, const FitSettings &s) {
    std::vector<TestSquare> v = hemisphere_squares();
    auto dir = square_dir;
    glm::dvec3 mirror(-V.x, 0.0, std::max(V.z, 0.1)); // not under the horizon
    // Sharp lobes (alpha below ~0.02) fit inside the smallest of these: squares of the lobe's
    // own width (alpha, 3 alpha) keep its shape measured.
    for (glm::dvec3 c : {mirror, avgDir})
        for (double h : {alpha, 3.0 * alpha, 0.05, 0.1, 0.2, 0.4})
            if (h >= 0.05 || 3.0 * alpha < 0.05)
                v.push_back(make_square(c, h, s.peakWeight));
    // Floors (issue 19): ceiling panels near the floor's horizon, all around: a ring of
    // azimuths per elevation. What a floor image shows is relative to its brightest part,
    // so each square's error is relative to its own integral + horizonFloor x the brightest
    // integral of its ring (see polygon_refs).
    if (s.horizonWeight > 0.0) {
        int ring = 0;
        for (double el : {3.0, 7.0, 12.0, 17.0, 25.0, 35.0}) {
            for (double az : {0.0, 45.0, 90.0, 135.0, 180.0})
                for (double h : {0.1, 0.3})
                    v.push_back(make_ceiling_square(dir(el, az), h, s.horizonWeight * (az == 0.0 || az == 180.0 ? 1.0 : 2.0), ring));
            ring++;
        }
    }
    return v;
}

// Whether direction L (unit) passes through the square.
bool in_square(const TestSquare &s, glm::dvec3 L) {
    if (glm::dot(L, s.c) < s.cosCone)
        return false;
    double den = glm::dot(L, s.d);
    if (!(den > 0.0))
        return false;
    // facing squares (d = c, the plane dot(c, x) = 1): L / den, as before issue 19 (same bits)
    glm::dvec3 q = s.ring < 0 ? L / den - s.c : L * (glm::dot(s.c, s.d) / den) - s.c;
    return std::fabs(glm::dot(q, s.e1)) <= s.half && std::fabs(glm::dot(q, s.e2)) <= s.half;
}

// The LTC's integral over the square's part above the horizon (as ltc.h computes it, in
// double): clipped to z >= 0 (once per cell) and to the LTC's support, transformed by M^-1,
// Lambert's formula.
double ltc_square_integral(const Ltc &l, const TestSquare &s) {
    if (s.clippedCount < 3)
        return 0.0;
    glm::dvec3 b[10];
    const glm::dvec3 support(l.invM[0][2], l.invM[1][2], l.invM[2][2]); // row 2 of M^-1
    int n = clip_half_space(s.clipped, s.clippedCount, support, b);
    if (n < 3)
        return 0.0;
    for (int i = 0; i < n; i++)
        b[i] = glm::normalize(l.invM * b[i]);
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        glm::dvec3 cr = glm::cross(b[i], b[(i + 1) % n]);
        double sn = glm::length(cr);
        double theta = std::atan2(sn, glm::dot(b[i], b[(i + 1) % n]));
        sum += (sn > 1e-300 ? theta / sn : 1.0) * cr.z;
    }
    return std::fabs(sum) / (2.0 * kPi);
}

// Calls hit(k) for every square k that direction L passes through, testing each.
template <class F> void for_each_square_hit(const std::vector<TestSquare> &squares, glm::dvec3 L, F &&hit) {
    for (size_t k = 0; k < squares.size(); k++)
        if (in_square(squares[k], L))
            hit(k);
}

// The bin of a direction's (x, y) on a side x side grid over [-1, 1]^2 (row-major).
size_t direction_bin(glm::dvec3 L, int side) {
    const int bx = std::clamp(int((L.x + 1.0) * 0.5 * side), 0, side - 1);
    const int by = std::clamp(int((L.y + 1.0) * 0.5 * side), 0, side - 1);
    return size_t(by) * size_t(side) + size_t(bx);
}

// The squares a direction hits, for the references' 256^2 samples per cell (issue 19: testing
// every sample against every square was 37% of the fit's CPU, then the exact tests of the
// squares left 27%).
//  - Squares that share their plane and axes (test_squares makes them consecutively: one
//    position, several half-sizes) form a group: the direction's point in that plane is
//    computed once per group, then compared with each half-size.
//  - Directions above the horizon are binned by their (x, y); a bin keeps the groups whose
//    widest cone can reach some direction of the bin: the largest dot(L, c) over the bin's box
//    in (x, y, z) is at least the cone's cosine (with a margin for float directions that are
//    not exactly unit).
// Each square's test is in_square's, in its order (cone, facing, bounds), and each integral
// still sums its samples in their order: the integrals are the same bits.
class SquareHits {
  public:
    explicit SquareHits(const std::vector<TestSquare> &squares) : squares_(squares), bins_(size_t(kSide) * kSide) {
        for (size_t k = 0; k < squares.size(); k++) {
            const TestSquare &q = squares[k];
            const bool same = !groups_.empty() && (q.ring < 0) == (squares[groups_.back().first].ring < 0) &&
                              q.c == squares[groups_.back().first].c && q.d == squares[groups_.back().first].d &&
                              q.e1 == squares[groups_.back().first].e1 && q.e2 == squares[groups_.back().first].e2;
            if (same) {
                groups_.back().count++;
                groups_.back().cosCone = std::min(groups_.back().cosCone, q.cosCone);
            } else {
                groups_.push_back({k, 1, q.cosCone});
            }
        }
        for (int by = 0; by < kSide; by++)
            for (int bx = 0; bx < kSide; bx++) {
                const double x0 = -1.0 + 2.0 * bx / kSide, x1 = -1.0 + 2.0 * (bx + 1) / kSide;
                const double y0 = -1.0 + 2.0 * by / kSide, y1 = -1.0 + 2.0 * (by + 1) / kSide;
                auto minSq = [](double lo, double hi) { return lo <= 0.0 && hi >= 0.0 ? 0.0 : std::min(lo * lo, hi * hi); };
                const double r2min = minSq(x0, x1) + minSq(y0, y1);
                const double r2max = std::max(x0 * x0, x1 * x1) + std::max(y0 * y0, y1 * y1);
                if (r2min > 1.0 + 1e-3)
                    continue; // outside the unit disk: no direction lands here
                const double z0 = std::sqrt(std::max(0.0, 1.0 - r2max)), z1 = std::sqrt(std::max(0.0, 1.0 - r2min));
                for (size_t g = 0; g < groups_.size(); g++) {
                    const glm::dvec3 &c = squares[groups_[g].first].c;
                    const double reach = std::max(c.x * x0, c.x * x1) + std::max(c.y * y0, c.y * y1) +
                                         std::max(c.z * z0, c.z * z1);
                    if (reach >= groups_[g].cosCone - 1e-3)
                        bins_[size_t(by) * kSide + bx].push_back(uint16_t(g));
                }
            }
    }
    // Calls hit(k) for every square k that direction L passes through (in_square).
    template <class F> void for_each_hit(glm::dvec3 L, F &&hit) const {
        if (!(L.z > 0.0)) // not binned: every square
            return for_each_square_hit(squares_, L, hit);
        for (uint16_t g : bins_[direction_bin(L, kSide)]) {
            const Group &gr = groups_[g];
            const TestSquare &first = squares_[gr.first];
            const double cosL = glm::dot(L, first.c);
            if (cosL < gr.cosCone)
                continue;
            const double den = glm::dot(L, first.d);
            if (!(den > 0.0))
                continue;
            // as in_square
            const glm::dvec3 q = first.ring < 0 ? L / den - first.c : L * (glm::dot(first.c, first.d) / den) - first.c;
            const double u = std::fabs(glm::dot(q, first.e1)), v = std::fabs(glm::dot(q, first.e2));
            for (size_t k = gr.first; k < gr.first + gr.count; k++)
                if (!(cosL < squares_[k].cosCone) && u <= squares_[k].half && v <= squares_[k].half)
                    hit(k);
        }
    }

  private:
    struct Group {
        size_t first, count;
        double cosCone; // the widest member's
    };
    static constexpr int kSide = 32;
    const std::vector<TestSquare> &squares_;
    std::vector<Group> groups_;
    std::vector<std::vector<uint16_t>> bins_;
};

// The squares of hemisphere_squares() (the same for every cell) that a direction hits, for the
// references' 256^2 samples per cell (issue 19, second round: SquareHits over them was still 29%
// of the fit's CPU). Directions above the horizon and of length 1 +- 1e-5 are binned by their
// (x, y) on a fine grid, built once: per bin, the squares that every such direction of the bin
// provably hits (no test) or may hit (in_square). A square is left out of a bin only if every
// such direction provably misses it. "Provably": in_square's quantities dot(L, c) and
// dot(L / dot(L, c) - c, e_i) are linear in L, or ratios of linear functions, so their bounds
// over the box around the bin's directions are at its corners; a margin of 1e-9 covers the
// rounding of in_square's few double operations (~1e-15). Every other direction (below the
// horizon, or not unit) takes in_square for every square. Each integral still sums its samples
// in their order: the integrals are the same bits.
class HemisphereHits {
  public:
    HemisphereHits() : squares_(hemisphere_squares()), first_(size_t(kSide) * kSide + 1, 0), partial_(first_.size(), 0) {
        const double pad = 1e-9, margin = 1e-9;
        for (int by = 0; by < kSide; by++)
            for (int bx = 0; bx < kSide; bx++) {
                const size_t bin = size_t(by) * kSide + size_t(bx);
                first_[bin] = partial_[bin] = uint32_t(entries_.size());
                std::vector<uint16_t> partial;
                const double x0 = -1.0 + 2.0 * bx / kSide - pad, x1 = -1.0 + 2.0 * (bx + 1) / kSide + pad;
                const double y0 = -1.0 + 2.0 * by / kSide - pad, y1 = -1.0 + 2.0 * (by + 1) / kSide + pad;
                auto minSq = [](double lo, double hi) { return lo <= 0.0 && hi >= 0.0 ? 0.0 : std::min(lo * lo, hi * hi); };
                const double r2min = minSq(x0, x1) + minSq(y0, y1);
                const double r2max = std::max(x0 * x0, x1 * x1) + std::max(y0 * y0, y1 * y1);
                if (r2min > 1.0 + kLengthTolerance)
                    continue; // no direction of length ~1 lands here
                const double z0 = std::sqrt(std::max(0.0, 1.0 - kLengthTolerance - r2max));
                const double z1 = std::sqrt(1.0 + kLengthTolerance - r2min);
                glm::dvec3 corner[8];
                for (int i = 0; i < 8; i++)
                    corner[i] = glm::dvec3(i & 1 ? x1 : x0, i & 2 ? y1 : y0, i & 4 ? z1 : z0);
                for (size_t k = 0; k < squares_.size(); k++) {
                    const TestSquare &q = squares_[k];
                    bool coneIn = true, coneOut = true, facing = true;
                    bool in1 = true, in2 = true, outLo1 = true, outHi1 = true, outLo2 = true, outHi2 = true;
                    for (const glm::dvec3 &p : corner) {
                        const double a = glm::dot(p, q.c), b1 = glm::dot(p, q.e1), b2 = glm::dot(p, q.e2);
                        coneIn = coneIn && a >= q.cosCone + margin;
                        coneOut = coneOut && a <= q.cosCone - margin;
                        facing = facing && a >= margin;
                        in1 = in1 && std::fabs(b1) <= (q.half - margin) * a;
                        in2 = in2 && std::fabs(b2) <= (q.half - margin) * a;
                        outHi1 = outHi1 && b1 >= (q.half + margin) * a;
                        outLo1 = outLo1 && -b1 >= (q.half + margin) * a;
                        outHi2 = outHi2 && b2 >= (q.half + margin) * a;
                        outLo2 = outLo2 && -b2 >= (q.half + margin) * a;
                    }
                    if (coneOut || (facing && (outHi1 || outLo1 || outHi2 || outLo2)))
                        continue; // missed by every direction of the bin
                    const bool all = coneIn && facing && in1 && in2;
                    (all ? entries_ : partial).push_back(uint16_t(k));
                }
                partial_[bin] = uint32_t(entries_.size());
                entries_.insert(entries_.end(), partial.begin(), partial.end());
            }
        first_.back() = uint32_t(entries_.size());
    }
    size_t size() const { return squares_.size(); }
    const std::vector<TestSquare> &squares() const { return squares_; }
    // Calls hit(k) for every square k that direction L passes through (in_square).
    template <class F> void for_each_hit(glm::dvec3 L, F &&hit) const {
        const double len2 = glm::dot(L, L);
        // not binned: below the horizon, not of length ~1, or outside the bins' square (|x| or
        // |y| > 1 would be clamped into an edge bin whose box does not hold it)
        if (!(L.z > 0.0) || !(std::fabs(len2 - 1.0) <= 0.5 * kLengthTolerance) || !(std::fabs(L.x) <= 1.0) ||
            !(std::fabs(L.y) <= 1.0))
            return for_each_square_hit(squares_, L, hit);
        const size_t bin = direction_bin(L, kSide);
        for (uint32_t e = first_[bin]; e < partial_[bin]; e++)
            hit(size_t(entries_[e]));
        for (uint32_t e = partial_[bin]; e < first_[bin + 1]; e++)
            if (in_square(squares_[entries_[e]], L))
                hit(size_t(entries_[e]));
    }
    static const HemisphereHits &get() {
        static const HemisphereHits h; // built once (thread-safe), shared by every cell
        return h;
    }

  private:
    static constexpr int kSide = 128;
    static constexpr double kLengthTolerance = 2e-5; // |L|^2 in [1 - t/2, 1 + t/2] is binned
    std::vector<TestSquare> squares_;
    std::vector<uint32_t> first_;   // per bin, its first entry (and the end): the squares that
    std::vector<uint32_t> partial_; // every direction of the bin hits, then from partial_[bin]
    std::vector<uint16_t> entries_; // those that some may hit (square indices)
};

struct PolygonRefs {
    std::vector<TestSquare> squares;
    std::vector<double> integral; // of f NoL over each square
    std::vector<double> denom;    // of each square's relative error
    double albedo = 0.0;
};

// The BRDF's integrals over the squares by the visible-normal sampler on a fixed grid
// (weights f NoL / pdf are bounded by 1): their own polygonSamples^2 points, or (--fast) the
// moments' samples.
PolygonRefs polygon_refs(Lobe lobe, const Moments &mom, glm::vec3 V, float alpha, const FitSettings &s) {
    PolygonRefs r;
    r.squares = test_squares(glm::dvec3(V), mom.avgDir, double(alpha), s);
    r.integral.assign(r.squares.size(), 0.0);
    // test_squares: the hemisphere's squares first (binned once for all cells), then this cell's
    const HemisphereHits &hemisphere = HemisphereHits::get();
    const size_t nh = hemisphere.size();
    for (size_t k = 0; k < nh; k++) // the same squares (a difference would be a programming error)
        if (r.squares[k].c != hemisphere.squares()[k].c || r.squares[k].half != hemisphere.squares()[k].half ||
            r.squares[k].ring >= 0 || r.squares[k].d != r.squares[k].c) {
            fprintf(stderr, "ltcfit: internal error: test_squares does not start with hemisphere_squares\n");
            std::abort();
        }
    const std::vector<TestSquare> cellSquares(r.squares.begin() + long(nh), r.squares.end());
    const SquareHits hits(cellSquares);
    auto add = [&](glm::dvec3 L, double w) {
        hemisphere.for_each_hit(L, [&](size_t k) { r.integral[k] += w; });
        hits.for_each_hit(L, [&](size_t k) { r.integral[nh + k] += w; });
    };
    if (s.fast) {
        for (const WeightedDir &wd : mom.samples)
            add(wd.L, wd.w);
        r.albedo = mom.norm;
        for (double &x : r.integral)
            x /= double(mom.sampleCount);
    } else {
        const int n = s.polygonSamples * s.polygonSamples;
        const std::vector<glm::vec3> dirs = brdf_grid_samples(lobe, V, alpha, s.polygonSamples);
        const ViewTerms vt = view_terms(lobe, V, alpha);
        for (int i = 0; i < n; i++) {
            const glm::vec3 L = dirs[size_t(i)];
            BrdfSample b = brdf_eval(lobe, V, L, alpha, &vt);
            if (!(b.pdf > 0.0) || !(b.value > 0.0))
                continue;
            double w = b.value / b.pdf;
            r.albedo += w;
            add(glm::dvec3(L), w);
        }
        for (double &x : r.integral)
            x /= n;
        r.albedo /= n;
    }
    double ringMax[16] = {0};
    for (size_t k = 0; k < r.squares.size(); k++)
        if (r.squares[k].ring >= 0)
            ringMax[r.squares[k].ring] = std::max(ringMax[r.squares[k].ring], r.integral[k]);
    for (size_t k = 0; k < r.squares.size(); k++) {
        const TestSquare &q = r.squares[k];
        double floor = q.ring >= 0 && !s.horizonAlbedoFloor ? s.horizonFloor * ringMax[q.ring]
                       : q.ring >= 0                        ? s.horizonFloor * r.albedo
                                                            : s.polygonFloor * r.albedo;
        r.denom.push_back(r.integral[k] + std::max(floor, 1e-30));
    }
    return r;
}

// Weighted mean of the squared relative errors of the integrals (norm = the albedo).
double polygon_error(const Ltc &l, const PolygonRefs &r, double norm) {
    const double scale = norm / l.mass_above_horizon();
    double sum = 0.0, wsum = 0.0;
    for (size_t k = 0; k < r.squares.size(); k++) {
        double e = (scale * ltc_square_integral(l, r.squares[k]) - r.integral[k]) / r.denom[k];
        sum += r.squares[k].weight * e * e;
        wsum += r.squares[k].weight;
    }
    return sum / wsum;
}

using Params = std::array<double, 4>;

// Nelder & Mead 1965, "A Simplex Method for Function Minimization" (standard coefficients:
// reflection 1, expansion 2, contraction 1/2, shrink 1/2). Minimises f over R^dim, dim <= 4.
// startValue: f(start) if known (not evaluated again); bestValue: receives f(result).
template <class F>
Params nelder_mead(F &&f, Params start, Params step, int dim, int maxIterations, double tolerance,
                   double *bestValue = nullptr, const double *startValue = nullptr) {
    std::array<Params, 5> x;
    std::array<double, 5> fx{};
    for (int i = 0; i <= dim; i++) {
        x[i] = start;
        if (i > 0)
            x[i][i - 1] += step[i - 1];
        fx[i] = i == 0 && startValue ? *startValue : f(x[i]);
    }
    for (int it = 0; it < maxIterations; it++) {
        // order: x[0] best ... x[dim] worst
        for (int i = 1; i <= dim; i++)
            for (int j = i; j > 0 && fx[j] < fx[j - 1]; j--) {
                std::swap(fx[j], fx[j - 1]);
                std::swap(x[j], x[j - 1]);
            }
        if (std::fabs(fx[dim] - fx[0]) <= tolerance * (std::fabs(fx[0]) + 1e-300))
            break;
        Params c{0, 0, 0, 0};
        for (int i = 0; i < dim; i++)
            for (int k = 0; k < dim; k++)
                c[k] += x[i][k] / dim;
        auto along = [&](double t) { // c + t (x_worst - c)
            Params r = c;
            for (int k = 0; k < dim; k++)
                r[k] = c[k] + t * (x[dim][k] - c[k]);
            return r;
        };
        Params xr = along(-1.0);
        double fr = f(xr);
        if (fr < fx[0]) {
            Params xe = along(-2.0);
            double fe = f(xe);
            if (fe < fr) {
                x[dim] = xe;
                fx[dim] = fe;
            } else {
                x[dim] = xr;
                fx[dim] = fr;
            }
        } else if (fr < fx[dim - 1]) {
            x[dim] = xr;
            fx[dim] = fr;
        } else {
            bool outside = fr < fx[dim];
            Params xc = along(outside ? -0.5 : 0.5);
            double fc = f(xc);
            if (fc < (outside ? fr : fx[dim])) {
                x[dim] = xc;
                fx[dim] = fc;
            } else {
                for (int i = 1; i <= dim; i++) {
                    for (int k = 0; k < dim; k++)
                        x[i][k] = x[0][k] + 0.5 * (x[i][k] - x[0][k]);
                    fx[i] = f(x[i]);
                }
            }
        }
    }
    int best = 0;
    for (int i = 1; i <= dim; i++)
        if (fx[i] < fx[best])
            best = i;
    if (bestValue)
        *bestValue = fx[best];
    return x[best];
}

// Fits one cell, starting from the shape of `start` (m11, m22, m13, rotation).
Cell fit_at(Lobe lobe, float r, double nov, const FitSettings &s, const Cell *start) {
    // The diffuse lobe's parameter is the perceptual roughness itself (see brdf_eval).
    const float alpha = lobe == Lobe::DisneyDiffuse ? r
                        : lobe == Lobe::Sheen       ? rtpbr::Sheen_Alpha(r)
                                                    : rtpbr::Alpha_FromPerceptual(r);
    const glm::vec3 V(float(std::sqrt(1.0 - nov * nov)), 0.0f, float(nov));

    const bool refine = s.polygonSamples > 0 && lobe != Lobe::DisneyDiffuse && r >= s.polygonMinRoughness;
    Moments mom = brdf_moments(lobe, V, alpha, s.momentSamples, refine && s.fast);

    Ltc ltc;
    const bool isotropic = nov >= 1.0; // V = N: the lobe is symmetric about the normal
    // The frame's Z starts at the lobe's average direction (Heitz et al.); with
    // s.freeRotation its angle in the plane of incidence is a fourth parameter.
    const double baseAngle = isotropic ? 0.0 : std::atan2(mom.avgDir.x, mom.avgDir.z);
    double rotation = 0.0;
    if (start) {
        // Sharp lobes scale with alpha: start from the neighbour's shape scaled by the ratio
        // of the alphas (about 1 for rough lobes).
        // The diffuse lobe does not sharpen with roughness, the sheen lobe moves towards the
        // horizon rather than narrowing around a direction: no scaling for either.
        double ratio = lobe == Lobe::DisneyDiffuse || lobe == Lobe::Sheen
                           ? 1.0
                           : double(alpha) / double(rtpbr::Alpha_FromPerceptual(float(start->roughness)));
        ltc.m11 = start->m11 * ratio;
        ltc.m22 = start->m22 * ratio;
        ltc.m13 = isotropic ? 0.0 : start->m13 * ratio;
        rotation = isotropic || !s.freeRotation ? 0.0 : start->rotation;
    }
    auto apply = [&](const Params &p, Ltc &l) {
        l.m11 = std::exp(glm::clamp(p[0], -30.0, 10.0));
        l.m22 = isotropic ? l.m11 : std::exp(glm::clamp(p[1], -30.0, 10.0));
        l.m13 = isotropic ? 0.0 : p[2];
        double angle = baseAngle + (isotropic ? 0.0 : glm::clamp(p[3], -1.5, 1.5));
        l.Z = glm::dvec3(std::sin(angle), 0.0, std::cos(angle));
        l.X = glm::dvec3(l.Z.z, 0.0, -l.Z.x);
        l.update();
    };
    // --fast: where the polygon refinement follows, the L3 fit is only its start (and
    // fallback), and a coarser one is taken.
    const bool coarseL3 = refine && s.fast;
    const int l3Iterations = coarseL3 ? s.refinedL3Iterations : s.maxIterations;
    const ErrorSamples fitSamples = error_samples(lobe, V, alpha, coarseL3 ? s.refinedL3Samples : s.fitSamples);
    auto cost = [&](const Params &p) {
        Ltc l = ltc;
        apply(p, l);
        return ltc_error(l, fitSamples, lobe, V, alpha, mom.norm, s.errorPower, s.horizonNormalised);
    };
    Params step{0.1, 0.1, 0.05 * std::max(ltc.m11, 1e-3), 0.05};
    // The sheen lobe of small alpha at steep views is empty (albedo down to 1e-30): nothing to
    // fit (the optimiser may push the LTC under the horizon, mass 0, norm infinite); such a
    // cell keeps its rougher neighbour's shape.
    const bool emptyLobe = lobe == Lobe::Sheen && !(mom.norm >= 1e-6);
    // Heitz et al.'s 3 parameters (Z at the average direction) ...
    // (issue 19: the costs the optimiser returns and the L1 errors of the candidates are kept,
    // not evaluated again: the same values.)
    double bestFit = HUGE_VAL;
    Params best = emptyLobe ? Params{std::log(ltc.m11), std::log(ltc.m22), ltc.m13, rotation}
                            : nelder_mead(cost, Params{std::log(ltc.m11), std::log(ltc.m22), ltc.m13, 0.0}, step,
                                          isotropic ? 1 : 3, l3Iterations, 1e-5, &bestFit);
    // Candidates: Heitz et al.'s fit, the 4-parameter fit from the neighbour's rotation, and
    // the neighbour's shape itself. The lowest L3 cost wins among those that overlap the lobe
    // (relative L1 error < 1); if none does, the lowest L1 error. The L3 cost, dominated by
    // the peak values of sharp lobes, can prefer a wide LTC disjoint from the lobe to a
    // slightly misaligned narrow one (it happens for alpha ~ 1e-3 at grazing views, where
    // float directions barely resolve the lobe).
    std::vector<std::pair<Params, double>> l1Known;
    auto l1 = [&](const Params &p) {
        for (const auto &k : l1Known)
            if (k.first == p)
                return k.second;
        Ltc l = ltc;
        apply(p, l);
        const double e = ltc_error(l, fitSamples, lobe, V, alpha, mom.norm, 1, s.horizonNormalised) / mom.norm;
        l1Known.emplace_back(p, e);
        return e;
    };
    // The horizon-normalised error sees the LTC's part above the horizon through two sets of
    // samples: the LTC's own (cosine directions transformed by M, kept if above the horizon) and
    // the BRDF's. The cosine grid's outermost ring is at cos theta = sqrt(1 / (2 side)) (side =
    // 24: the band under it holds 1 / 48 = 0.0208 of the cosine's mass), so an LTC with less than
    // that above the horizon has none of its own samples there, and is seen only through the
    // BRDF's samples, which miss part of it (at the last row, NoV = 1e-3, 21-38% of its light,
    // scaled by norm / mass): the error estimate misses it too. The optimiser slides into that
    // blind spot: at the last row below roughness 8/63 it drove the mass to 1e-15 (log m22
    // towards its bound -30: M^-1's third row 1e-13 of its first). Where
    // the lobe reaches the horizon (the mirror direction within 2 alpha of it) an LTC must
    // keep kMinVisibleMass above it.
    const bool guardMass = s.horizonNormalised && (lobe == Lobe::GGX || lobe == Lobe::Beckmann) && nov < 2.0 * double(alpha);
    auto visible = [&](const Params &p) {
        Ltc l = ltc;
        apply(p, l);
        return l.mass_above_horizon() >= kMinVisibleMass;
    };
    std::vector<Params> candidates{best};
    std::vector<double> candidateCosts{emptyLobe ? cost(best) : bestFit};
    if (s.freeRotation && !isotropic && !emptyLobe) {
        candidates.push_back(nelder_mead(cost, Params{std::log(ltc.m11), std::log(ltc.m22), ltc.m13, rotation}, step,
                                         4, l3Iterations, 1e-5, &bestFit));
        candidateCosts.push_back(bestFit);
    }
    if (start && !emptyLobe) {
        candidates.push_back(Params{std::log(ltc.m11), std::log(ltc.m22), ltc.m13, rotation});
        candidateCosts.push_back(cost(candidates.back()));
    }
    // Where the lobe reaches the horizon, an LTC must keep enough of itself above the horizon
    // for the error's own LTC samples to see it (see kMinVisibleMass): the others are not
    // candidates. If none is left, the L3 fit again, with that as a constraint.
    if (guardMass && !emptyLobe) {
        bool any = false;
        for (const Params &c : candidates)
            any = any || visible(c);
        if (!any) {
            const Params starts[2] = {Params{std::log(ltc.m11), std::log(ltc.m22), ltc.m13, rotation},
                                      Params{std::log(ltc.m11), std::log(ltc.m22), 0.0, 0.0}};
            for (const Params &from : starts)
                if (visible(from)) {
                    auto constrained = [&](const Params &p) { return visible(p) ? cost(p) : HUGE_VAL; };
                    candidates.push_back(nelder_mead(constrained, from, step, isotropic ? 1 : 4, l3Iterations, 1e-5, &bestFit));
                    candidateCosts.push_back(bestFit);
                    break;
                }
        }
    }
    double bestCost = HUGE_VAL, bestL1 = HUGE_VAL;
    bool overlapping = false;
    for (size_t ci = 0; ci < candidates.size(); ci++) {
        const Params &c = candidates[ci];
        if (guardMass && !emptyLobe && !visible(c))
            continue;
        double e1 = l1(c), e3 = candidateCosts[ci];
        bool ok = e1 < 1.0;
        if ((ok && (!overlapping || e3 < bestCost)) || (!ok && !overlapping && e1 < bestL1)) {
            best = c;
            bestCost = e3;
            bestL1 = e1;
            overlapping = ok;
        }
    }
    // Second stage: the error of the integrals over square lights, from the best of the L3
    // fit and the neighbour's shape; the L3 fit stays if nothing improves on it.
    double polyErr = 0.0;
    if (refine) {
        const PolygonRefs refs = polygon_refs(lobe, mom, V, alpha, s);

        auto pcost = [&](const Params &p) {
            Ltc l = ltc;
            apply(p, l);
            return polygon_error(l, refs, mom.norm);
        };
        Params from = best;
        double fromCost = pcost(best);
        if (start) {
            Params neighbour{std::log(ltc.m11), std::log(ltc.m22), ltc.m13, rotation};
            double nc = pcost(neighbour);
            if (nc < fromCost && (l1(neighbour) < 1.0 || l1(neighbour) <= l1(best)) && (!guardMass || visible(neighbour))) {
                from = neighbour;
                fromCost = nc;
            }
        }
        const int dim = isotropic ? 1 : 4;
        Params refined = from;
        double refinedCost = fromCost;
        for (int pass = 0; pass < 2; pass++) { // a restart: Nelder-Mead's simplex can collapse
            const double startCost = refinedCost;
            refined = nelder_mead(pcost, refined, Params{0.1, 0.1, 0.05 * std::max(std::exp(refined[0]), 1e-3), 0.05}, dim,
                                  s.maxIterations, 1e-6, &refinedCost, &startCost);
        }
        // Where the lobe reaches the horizon, the refinement keeps the L3 fit's constraint too:
        // if it left it, it runs again from `from` (which keeps it) with the constraint. At the
        // last row, r = 0.111, it had gone to mass 4e-5 (RMS 1.7% over the squares against 15%
        // for its regular neighbours, but a relative L1 distance of 1.02 to the lobe, against
        // 0.74, and the L1 estimate blind there).
        if (guardMass && !visible(refined) && visible(from)) {
            auto constrained = [&](const Params &p) { return visible(p) ? pcost(p) : HUGE_VAL; };
            refined = from;
            refinedCost = fromCost;
            for (int pass = 0; pass < 2; pass++) {
                const double startCost = refinedCost;
                refined = nelder_mead(constrained, refined, Params{0.1, 0.1, 0.05 * std::max(std::exp(refined[0]), 1e-3), 0.05},
                                      dim, s.maxIterations, 1e-6, &refinedCost, &startCost);
            }
        }
        // Never trade an LTC that overlaps the lobe for one that hardly does (relative L1
        // distance >= 1, as in the candidates' choice above): the squares cannot see every
        // shape error of a sharp lobe.
        const double l1Before = l1(from), l1After = l1(refined);
        if (refinedCost < fromCost && (l1After < 1.0 || l1After <= l1Before)) {
            from = refined;
            fromCost = refinedCost;
        }
        best = from;
        polyErr = std::sqrt(fromCost);
    }
    apply(best, ltc);

    Cell c;
    c.polygonError = polyErr;
    c.roughness = r;
    c.m11 = ltc.m11;
    c.m22 = ltc.m22;
    c.m13 = ltc.m13;
    c.rotation = isotropic ? 0.0 : best[3];
    c.avgDir = ltc.Z;
    c.invM = ltc.invM / ltc.invM[1][1];
    // The stored integrals are the BRDF's own (norm = the directional albedo): ltc.h divides
    // the clipped LTC integral by the mass above the horizon of the LTC it evaluates (the
    // bilinearly interpolated one, LTC_HorizonMass), so that norm x that fraction never exceeds
    // the interpolated albedo. Dividing the table by each cell's own mass instead (before the
    // energy-bound fix) made norm / mass pairs that interpolation does not keep together:
    // cells of mass 1e-15 beside cells of mass 1 gave up to 1e8 x the albedo.
    c.albedo = mom.norm;
    c.norm = mom.norm;
    c.fresnel = mom.fresnel;
    c.f82 = mom.f82;
    const ErrorSamples reportSamples = error_samples(lobe, V, alpha, s.errorSamples);
    c.error = mom.norm > 0.0 ? ltc_error(ltc, reportSamples, lobe, V, alpha, mom.norm, 1, s.horizonNormalised) / mom.norm
                             : 0.0;
    return c;
}

Cell fit_cell(Lobe lobe, int col, int row, const FitSettings &s, const Cell *start) {
    return fit_at(lobe, float(cell_roughness(col, s.size)), cell_nov(row, s.size), s, start);
}

} // namespace

Cell fit_exact(Lobe lobe, double r, double nov, const FitSettings &s) {
    // As a row of the table, at this view: from the roughest end (a start of M = I) down to r
    // in the table's steps, each fit starting from the previous one.
    const double step = 1.0 / double(s.size - 1);
    int steps = int(std::floor((1.0 - r) / step + 1e-9));
    Cell c = fit_at(lobe, float(r + steps * step), nov, s, nullptr);
    for (int k = steps - 1; k >= 0; k--)
        c = fit_at(lobe, float(r + k * step), nov, s, &c);
    return c;
}

double cell_roughness(int col, int size) { return double(col) / double(size - 1); }

double cell_nov(int row, int size) {
    double x = double(row) / double(size - 1);
    return std::max(1.0 - x * x, kMinNoV);
}

namespace {

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

} // namespace

std::vector<Table> fit_tables(const std::vector<Lobe> &lobes, const FitSettings &s,
                              const std::function<void(int, int)> &progress) {
    const auto t0 = std::chrono::steady_clock::now();
    const int nLobes = int(lobes.size()), last = s.size - 1;
    const int firstRow = std::clamp(s.firstRow, 0, s.size);
    const int rowsPerLobe = s.size - firstRow, totalRows = nLobes * rowsPerLobe;
    std::vector<Table> tables(lobes.size());
    for (int l = 0; l < nLobes; l++) {
        tables[size_t(l)].lobe = lobes[size_t(l)];
        tables[size_t(l)].size = s.size;
        tables[size_t(l)].cells.resize(size_t(s.size) * size_t(s.size));
    }
    // Tasks, taken in this order from one counter by every thread:
    //  1. per lobe, its roughest column down the view angles (each cell starts from the previous
    //     one, the first from the clamped cosine itself, m11 = m22 = 1);
    //  2. per lobe, each row from rough to smooth, each cell starting from its rougher
    //     neighbour. A row needs only its own cell of the first column: it waits for that cell,
    //     not for the whole column, so the serial columns overlap each other and the rows.
    // Every cell starts from the same neighbour whatever thread fits it: the tables do not
    // depend on the thread count. No deadlock: every column task is taken before any row task,
    // and column tasks never wait.
    std::atomic<int> nextTask{0}, doneRows{0};
    std::vector<int> columnDone(lobes.size(), 0);       // cells of the first column fitted
    std::vector<double> cpu(lobes.size(), 0.0), end(lobes.size(), 0.0);
    std::vector<int> rowsLeft(lobes.size(), rowsPerLobe);
    std::mutex mutex;
    std::condition_variable columnAdvanced;
    auto worker = [&]() {
        for (int task = nextTask++; task < nLobes + totalRows; task = nextTask++) {
            const double c0 = thread_cpu_seconds();
            const int l = task < nLobes ? task : (task - nLobes) / rowsPerLobe;
            Table &t = tables[size_t(l)];
            if (task < nLobes) {
                for (int row = 0; row < s.size; row++) {
                    t.cells[size_t(row) * s.size + last] =
                        fit_cell(t.lobe, last, row, s, row > 0 ? &t.cells[size_t(row - 1) * s.size + last] : nullptr);
                    std::lock_guard<std::mutex> lock(mutex);
                    columnDone[size_t(l)] = row + 1;
                    columnAdvanced.notify_all();
                }
                std::lock_guard<std::mutex> lock(mutex);
                cpu[size_t(l)] += thread_cpu_seconds() - c0;
                continue;
            }
            const int row = firstRow + (task - nLobes) % rowsPerLobe;
            {
                std::unique_lock<std::mutex> lock(mutex);
                columnAdvanced.wait(lock, [&] { return columnDone[size_t(l)] > row; });
            }
            for (int col = last - 1; col >= 0; col--)
                t.cells[size_t(row) * s.size + col] = fit_cell(t.lobe, col, row, s, &t.cells[size_t(row) * s.size + col + 1]);
            std::lock_guard<std::mutex> lock(mutex);
            cpu[size_t(l)] += thread_cpu_seconds() - c0;
            if (--rowsLeft[size_t(l)] == 0)
                end[size_t(l)] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            progress(++doneRows, totalRows);
        }
    };
    std::vector<std::thread> pool;
    for (int i = 0; i < std::max(1, s.threads); i++)
        pool.emplace_back(worker);
    for (std::thread &th : pool)
        th.join();
    for (int l = 0; l < nLobes; l++) {
        tables[size_t(l)].seconds = rowsPerLobe > 0 ? end[size_t(l)]
                                                    : std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        tables[size_t(l)].cpuSeconds = cpu[size_t(l)];
    }
    return tables;
}

Table fit_table(Lobe lobe, const FitSettings &s, const std::function<void(int, int)> &progress) {
    return std::move(fit_tables({lobe}, s, progress)[0]);
}

double clipped_cap_form_factor(double omega, double sigma) {
    // integral over the cap (polar angle rho from its centre, azimuth phi) of max(cos, 0),
    // cos = A + B cos(phi) with A = cos(omega) cos(rho), B = sin(omega) sin(rho) >= 0; the
    // phi integral is closed-form, the rho integral the midpoint rule (the integrand is C^1).
    const int steps = 4096;
    double sum = 0.0;
    for (int i = 0; i < steps; i++) {
        double rho = sigma * (i + 0.5) / steps;
        double A = std::cos(omega) * std::cos(rho), B = std::sin(omega) * std::sin(rho);
        double inner;
        if (A >= B)
            inner = 2.0 * kPi * A;
        else if (A <= -B)
            inner = 0.0;
        else {
            double phi0 = std::acos(-A / B);
            inner = 2.0 * (A * phi0 + B * std::sin(phi0));
        }
        sum += inner * std::sin(rho);
    }
    return sum * (sigma / steps) / kPi;
}

std::vector<float> sphere_table(int size) {
    std::vector<float> tab(size_t(size) * size);
    for (int row = 0; row < size; row++)
        for (int col = 0; col < size; col++) {
            double z = 2.0 * col / (size - 1) - 1.0;
            double len = double(row) / (size - 1);
            double v;
            if (len <= 0.0)
                v = std::max(z, 0.0);
            else
                v = clipped_cap_form_factor(std::acos(z), std::asin(std::sqrt(len))) / len;
            tab[size_t(row) * size + col] = float(v);
        }
    return tab;
}

std::vector<float> pack_ltc1(const Table &t) {
    std::vector<float> out(t.cells.size() * 4);
    for (size_t i = 0; i < t.cells.size(); i++) {
        const glm::dmat3 &m = t.cells[i].invM; // glm [column][row]
        out[4 * i + 0] = float(m[0][0]);         // row 0, column 0
        out[4 * i + 1] = float(m[2][0]);         // row 0, column 2
        out[4 * i + 2] = float(m[0][2]);         // row 2, column 0
        out[4 * i + 3] = float(m[2][2]);         // row 2, column 2
    }
    return out;
}

std::vector<float> pack_ltc2(const Table &t, const std::vector<float> &sphere) {
    std::vector<float> out(t.cells.size() * 4);
    for (size_t i = 0; i < t.cells.size(); i++) {
        out[4 * i + 0] = float(t.cells[i].norm);
        out[4 * i + 1] = float(t.cells[i].fresnel);
        out[4 * i + 2] = float(t.cells[i].f82);
        out[4 * i + 3] = sphere[i];
    }
    return out;
}

PackedTables pack_tables(const Table &ggx, const Table &beckmann, const Table &diffuse,
                         const std::vector<float> &sphere) {
    return {pack_ltc1(ggx), pack_ltc2(ggx, sphere), pack_ltc1(beckmann), pack_ltc2(beckmann, sphere),
            pack_ltc1(diffuse), pack_ltc2(diffuse, sphere)};
}

} // namespace ltcfit
