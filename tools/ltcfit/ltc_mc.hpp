// LTC against Monte Carlo: the integral of the true BRDF x cosine over a polygon light,
// estimated by multiple importance sampling, compared with the LTC evaluation from the
// committed tables (fetched with GPU-like bilinear filtering). Shared by the test
// (tests/shaderlib/ltc/test_ltc_mc.cpp, reduced grid, bounds) and rtpbr-ltc-validate (full grid, table
// and plot for shaderlib/luts/ltc.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "rtpbr/disney.h"
#include "rtpbr/ltc.h"
#include "rtpbr/ltc_anisotropy.h"
#include "rtpbr/ltc_clipless.h"
#include "rtpbr/ltc_corrections.h"
#include "rtpbr/microfacet.h"
#include "rtpbr/sampling.h"
#include "rtpbr/sheen.h"
#include "luts/rtpbr_ltc_tables.h"
#include "luts/rtpbr_ltc_sheen_tables.h"
#include "rtpbr_common/rng.h"

#include "error_stats.hpp"

namespace ltcmc {

using rtpbr::float2;
using rtpbr::float3;
using rtpbr::float4;

// DisneyDiffuse: BRDF_DisneyDiffuse (white, metallic 0, subsurface 0), the table fitted by
// tools/ltcfit into rtpbr_ltc_disney_diffuse_*. Sheen: the KHR_materials_sheen lobe
// (sheen.h, D_Charlie V_Charlie, sheenColor 1), table rtpbr_ltc_sheen_* (own header).
enum class Lobe { GGX, Beckmann, DisneyDiffuse, Sheen };
inline const char *lobe_name(Lobe l) {
    return l == Lobe::GGX ? "GGX" : l == Lobe::Beckmann ? "Beckmann" : l == Lobe::Sheen ? "Sheen" : "Disney diffuse";
}

// Bilinear fetch with clamp-to-edge at texture coordinate uv, as a GPU sampler does.
inline float4 fetch(const float *tab, float2 uv) {
    const int n = RTPBR_LTC_SIZE;
    float x = std::clamp(uv.x * n - 0.5f, 0.0f, float(n - 1));
    float y = std::clamp(uv.y * n - 0.5f, 0.0f, float(n - 1));
    int x0 = std::min(int(x), n - 2), y0 = std::min(int(y), n - 2);
    float fx = x - float(x0), fy = y - float(y0);
    auto at = [&](int i, int j) {
        const float *p = tab + (size_t(j) * n + size_t(i)) * 4;
        return float4(p[0], p[1], p[2], p[3]);
    };
    float4 a = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * fx;
    float4 b = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * fx;
    return a + (b - a) * fy;
}

// Deterministic uniform floats in [0, 1): SplitMix64 (common/).
struct Rng : rtpbr_tools::SplitMix64 {
    using SplitMix64::SplitMix64;
    float uniform() { return uniform_float(); }
};

// A square light of half-size `half` at distance 1 in direction `dir`, facing the shading
// point at the origin (front face toward it), turned by 20 degrees about dir.
struct Square {
    float3 c, d, e1, e2;
    float half;
    rtpbr::LtcPolygon poly() const {
        return rtpbr::LTC_Quad(c - half * e1 - half * e2, c - half * e1 + half * e2, c + half * e1 + half * e2,
                               c + half * e1 - half * e2);
    }
};

inline Square make_square(float3 dir, float half) {
    Square s;
    s.d = glm::normalize(dir);
    s.c = s.d;
    float3 t = std::fabs(s.d.z) < 0.9f ? glm::normalize(glm::cross(float3(0, 0, 1), s.d))
                                       : glm::normalize(glm::cross(float3(1, 0, 0), s.d));
    float3 b = glm::cross(s.d, t);
    float c20 = std::cos(0.349f), s20 = std::sin(0.349f);
    s.e1 = c20 * t + s20 * b;
    s.e2 = glm::cross(s.d, s.e1);
    s.half = half;
    return s;
}

// The BRDF under test: f (F = 1) and its sampling density (visible normals; the cosine for
// the diffuse lobe).
struct Brdf {
    Lobe lobe;
    float alpha; // microfacet alpha; for Lobe::DisneyDiffuse the perceptual roughness
    static Brdf make(Lobe lobe, float roughness) {
        if (lobe == Lobe::Sheen)
            return {lobe, rtpbr::Sheen_Alpha(roughness)};
        return {lobe, lobe == Lobe::DisneyDiffuse ? roughness : rtpbr::Alpha_FromPerceptual(roughness)};
    }
    float value_cos(float3 V, float3 L, float &pdf) const {
        if (lobe == Lobe::Sheen) { // Sample_SheenLobe's density (half Charlie, half uniform)
            pdf = rtpbr::PDF_SheenLobe(V, L, alpha);
            if (!(L.z > 0.0f))
                return 0.0f;
            float3 H = glm::normalize(V + L);
            return rtpbr::D_Charlie(H.z, alpha) * rtpbr::V_Charlie(V.z, L.z, alpha) * L.z;
        }
        if (lobe == Lobe::DisneyDiffuse) {
            pdf = L.z > 0.0f ? L.z * rtpbr::RTPBR_INV_PI : 0.0f;
            rtpbr::DisneyMaterial m = rtpbr::Disney_DefaultMaterial();
            m.baseColor = float3(1.0f);
            m.metallic = 0.0f;
            m.subsurface = 0.0f;
            m.roughness = alpha;
            return L.z > 0.0f ? rtpbr::BRDF_DisneyDiffuse(m, V, L).x * L.z : 0.0f;
        }
        float3 hs = V + L;
        pdf = 0.0f;
        if (!(glm::dot(hs, hs) > 1e-12f))
            return 0.0f;
        float3 H = glm::normalize(hs);
        if (!(H.z > 0.0f))
            return 0.0f;
        float D = lobe == Lobe::GGX ? rtpbr::D_GGX(H.z, alpha) : rtpbr::D_Beckmann(H.z, alpha);
        float G1 = lobe == Lobe::GGX ? rtpbr::G1_GGX(V.z, alpha) : rtpbr::G1_Beckmann(V.z, alpha);
        pdf = G1 * D / (4.0f * V.z);
        if (!(L.z > 0.0f))
            return 0.0f;
        float Vis = lobe == Lobe::GGX ? rtpbr::V_SmithGGXCorrelated(V.z, L.z, alpha)
                                      : rtpbr::V_SmithBeckmann(V.z, L.z, alpha);
        return D * Vis * L.z;
    }
    float3 sample(float3 V, float2 u) const {
        if (lobe == Lobe::Sheen)
            return rtpbr::Sample_SheenLobe(V, u, alpha);
        if (lobe == Lobe::DisneyDiffuse)
            return rtpbr::Sample_CosineHemisphere(u);
        float3 wm = lobe == Lobe::GGX ? rtpbr::Sample_GGX_VNDF(V, alpha, alpha, u)
                                      : rtpbr::Sample_Beckmann_VNDF(V, alpha, alpha, u);
        return rtpbr::Reflect_About(V, wm);
    }
};

// Fresnel weight used by the reference: 0 = none (F = 1), 1 = Schlick f0 = 0.04,
// 2 = exact conductor (gold: eta, k at R, G, B; only the green channel is compared).
struct FresnelChoice {
    int kind = 0;
    float weight(float VoH) const {
        if (kind == 1)
            return rtpbr::F_Schlick1(0.04f, 1.0f, VoH);
        if (kind == 2)
            return rtpbr::F_Conductor(VoH, float3(0.143f, 0.374f, 1.442f), float3(3.983f, 2.385f, 1.603f)).y;
        return 1.0f;
    }
};

// Lights receiving less than this fraction of the lobe's energy (albedo) are the lobe's far
// tail: their error is reported relative to the albedo instead of to their own value.
constexpr double kSignificant = 0.01;

struct McResult {
    double mean, relStdErr;
    long samples;
};

// Multiple importance sampling (Veach 1997, balance heuristic, one sample of each strategy
// per sample point): light samples uniform on the square's area, BRDF samples by visible
// normals; both stratified (one jittered sample per cell of a 64 x 64 grid per batch). The
// standard error comes from the spread of the batch means (independent batches); batches
// are added until it is below targetRelErr of max(mean, floor), or maxPairs (floor: the
// scale below which relative precision is not needed).
inline McResult reference(const Brdf &brdf, float3 V, const Square &sq, FresnelChoice fr, uint64_t seed,
                          double targetRelErr, long maxPairs, double floor = 0.0) {
    Rng rng(seed);
    const int side = 64, perBatch = side * side;
    const double area = 4.0 * double(sq.half) * double(sq.half);
    double sumB = 0.0, sum2B = 0.0;
    long batches = 0;
    auto light_pdf = [&](float3 L, float dist2) {
        float cosL = glm::dot(L, sq.d);
        return cosL > 0.0f ? double(dist2) / (area * double(cosL)) : 0.0;
    };
    auto stratum = [&](int i) {
        return float2((float(i % side) + rng.uniform()) / float(side), (float(i / side) + rng.uniform()) / float(side));
    };
    double mean = 0.0, stdErr = 0.0;
    while (long(batches) * perBatch < maxPairs) {
        double batch = 0.0;
        for (int i = 0; i < perBatch; i++) {
            { // light sample
                float2 u = stratum(i);
                float3 q = sq.c + ((2.0f * u.x - 1.0f) * sq.half) * sq.e1 + ((2.0f * u.y - 1.0f) * sq.half) * sq.e2;
                float dist2 = glm::dot(q, q);
                float3 L = q / std::sqrt(dist2);
                double pl = light_pdf(L, dist2);
                float pb;
                float f = brdf.value_cos(V, L, pb);
                if (f > 0.0f && pl > 0.0)
                    batch += double(f) * fr.weight(glm::dot(V, glm::normalize(V + L))) / (pl + double(pb));
            }
            { // BRDF sample
                float3 L = brdf.sample(V, stratum(i));
                float denom = glm::dot(L, sq.d);
                if (L.z > 0.0f && denom > 0.0f) {
                    float t = glm::dot(sq.c, sq.d) / denom;
                    float3 q = t * L - sq.c;
                    if (std::fabs(glm::dot(q, sq.e1)) <= sq.half && std::fabs(glm::dot(q, sq.e2)) <= sq.half) {
                        float pb;
                        float f = brdf.value_cos(V, L, pb);
                        double pl = light_pdf(L, t * t);
                        if (f > 0.0f && pb > 0.0f)
                            batch += double(f) * fr.weight(glm::dot(V, glm::normalize(V + L))) / (pl + double(pb));
                    }
                }
            }
        }
        batch /= perBatch;
        sumB += batch;
        sum2B += batch * batch;
        batches++;
        mean = sumB / double(batches);
        double var = std::max(sum2B / double(batches) - mean * mean, 0.0) * double(batches) / double(batches - 1 > 0 ? batches - 1 : 1);
        stdErr = std::sqrt(var / double(batches));
        if (batches >= 8 && std::max(mean, floor) > 0.0 && stdErr <= targetRelErr * std::max(mean, floor))
            break;
    }
    return {mean, mean > 0.0 ? stdErr / mean : 0.0, long(batches) * perBatch};
}

// The directional albedo (integral of f cos, F = 1) by stratified visible-normal sampling:
// the scale that separates lights that matter from lights in the lobe's far tail.
inline double albedo(const Brdf &brdf, float3 V) {
    const int side = 128;
    double sum = 0.0;
    for (int i = 0; i < side * side; i++) {
        float3 L = brdf.sample(V, float2((float(i % side) + 0.5f) / side, (float(i / side) + 0.5f) / side));
        float pb;
        float f = brdf.value_cos(V, L, pb);
        if (f > 0.0f && pb > 0.0f)
            sum += double(f) / double(pb);
    }
    return sum / (side * side);
}

// The solid-angle centroid direction (Arvo's vector form factor, normalised) of the part of a
// local polygon (already above the horizon) that lies in z >= 0 after the linear map minv;
// zero if none does. Double precision, written apart from ltc.h's streamed float path
// (LTC_LobeEndVector): rtpbr-ltc-floor --point-ff uses it, and test_ltc_mc checks
// ltc_corrections.h's point correction against it.
inline glm::dvec3 clipped_centroid(const rtpbr::LtcLocalPolygon &local, const glm::dmat3 &minv) {
    std::vector<glm::dvec3> in, out;
    for (int i = 0; i < local.count; i++)
        in.push_back(minv * glm::dvec3(local.v[i]));
    for (size_t i = 0; i < in.size(); i++) { // Sutherland-Hodgman against z >= 0
        const glm::dvec3 a = in[i], b = in[(i + 1) % in.size()];
        if (a.z >= 0.0)
            out.push_back(a);
        if ((a.z >= 0.0) != (b.z >= 0.0))
            out.push_back(a + (b - a) * (a.z / (a.z - b.z)));
    }
    glm::dvec3 F(0.0);
    for (size_t i = 0; i < out.size(); i++) {
        const glm::dvec3 a = glm::normalize(out[i]), b = glm::normalize(out[(i + 1) % out.size()]);
        const glm::dvec3 c = glm::cross(a, b);
        const double l = glm::length(c);
        if (l > 1e-300)
            F += std::atan2(l, glm::dot(a, b)) * c / l;
    }
    if (F.z < 0.0)
        F = -F;
    return F;
}

// The engine's point correction (ltc_corrections.h, LTC_PointFactor; issue 19, fourth round) of the LTC
// result for a local polygon: the true f NoL at the centre of the part the LTC sees over the
// LTC's value there (norm x density), above 1 only where the lobe is not much narrower than the
// light, faded by the LTC's form factor. `raw`: the ratio alone, without the fade and the
// width gate (the first experiment of that round).
inline double point_ratio(const Brdf &brdf, float3 V, const rtpbr::LtcLocalPolygon &local, float4 l1, float norm,
                          bool raw = false) {
    const float3 Fl = rtpbr::LTC_IntegrateLocalVector(local, l1);
    const rtpbr::LtcPoint pt = rtpbr::LTC_LobePoint(Fl, l1);
    if (!(pt.density > 0.0f))
        return 1.0;
    float pdf;
    const float fCos = brdf.value_cos(V, pt.dir, pdf);
    if (raw)
        return double(fCos) / (double(norm) * double(pt.density));
    // the light's horizon-clipped vector form factor (the local polygon is clipped already)
    const float lenF = glm::length(rtpbr::LTC_FormFactorVector(local, rtpbr::LTC_Identity()));
    const float vPlusW = glm::length(V + pt.dir);
    return double(rtpbr::LTC_PointFactor(fCos, norm * pt.density, rtpbr::LTC_IntegrateLocal(local, l1),
                                         rtpbr::LTC_PointWidthRatio(brdf.alpha, vPlusW, lenF)));
}

// The engine's whole correction of the specular LTC (lighting.comp): the point-corrected LTC
// or, for a light in the LTC's tail, the tail estimate (ltc_corrections.h, LTC_PointTail; fifth round),
// whichever is larger. ltc = norm x the LTC integral (F = 1); V in the LTC's frame (the local
// polygon's). tail = false: the point correction alone (the fourth round's engine).
// parts (optional): the point-corrected LTC and the weighted tail estimate, in the same units;
// the streak estimate (-1: none) and its weight (LTC_StreakWeight x its trust).
// streak (with tail): the streak estimate mixed in (ltc_corrections.h, LTC_StreakEnd; GGX; the sixth
// round's engine); false: the fifth round's engine.
inline double point_value(const Brdf &brdf, float3 V, const rtpbr::LtcLocalPolygon &local, float4 l1, float norm,
                          double ltc, bool tail = true, double parts[4] = nullptr, bool streak = true) {
    const double corrected = ltc > 0.0 ? ltc * point_ratio(brdf, V, local, l1, norm) : 0.0;
    if (parts)
        parts[0] = corrected, parts[1] = 0.0, parts[2] = -1.0, parts[3] = 0.0;
    if (!tail || !(norm > 0.0f))
        return corrected;
    const float3 F = rtpbr::LTC_FormFactorVector(local, rtpbr::LTC_Identity());
    const float lf = glm::length(F);
    if (!(lf > 0.0f))
        return corrected;
    float pdf;
    const float3 c = F / lf;
    // f without the cosine (value_cos is f NoL)
    const float f = c.z > 0.0f ? brdf.value_cos(V, c, pdf) / c.z : 0.0f;
    const float weight = rtpbr::LTC_PointTailWeight(rtpbr::LTC_IntegrateLocalVector(local, l1), float(ltc / double(norm)), F.z);
    const float tailValue = rtpbr::LTC_PointTail(f, F.z, norm);
    if (parts)
        parts[1] = double(norm) * double(tailValue) * double(weight);
    double value = double(norm) * double(rtpbr::LTC_PointCombine(float(corrected / double(norm)), tailValue, weight));
    // the streak estimate (ltc_corrections.h, LTC_StreakEnd; sixth round): GGX, mixed in by its weight
    const float w = streak && brdf.lobe == Lobe::GGX ? rtpbr::LTC_StreakWeight(V, F) : 0.0f;
    if (w > 0.0f) {
        const float2 S = rtpbr::LTC_StreakLocal(local, F, V, brdf.alpha);
        if (parts)
            parts[2] = double(S.x), parts[3] = double(w * S.y);
        if (S.x >= 0.0f)
            value += (double(S.x) - value) * double(w * S.y);
    }
    return value;
}

struct LtcEval {
    double exact, clipless, clipless_table;
    double pointOnly = 0.0, tail = 0.0; // point's parts: exact x the point correction; the weighted tail estimate
    double point = 0.0; // the engine's value: the larger of pointOnly and tail (point_value), the streak estimate mixed in
    double streak = -1.0, streakWeight = 0.0; // the streak estimate (-1: none), its weight
};

// The LTC answer with F = 1 (norm x form factor), as a renderer computes it.
inline LtcEval ltc_eval(Lobe lobe, float roughness, float3 V, const Square &sq, FresnelChoice fr) {
    const float *t1 = lobe == Lobe::GGX        ? rtpbr_ltc_ggx_1
                      : lobe == Lobe::Beckmann ? rtpbr_ltc_beckmann_1
                                               : rtpbr_ltc_disney_diffuse_1;
    const float *t2 = lobe == Lobe::GGX        ? rtpbr_ltc_ggx_2
                      : lobe == Lobe::Beckmann ? rtpbr_ltc_beckmann_2
                                               : rtpbr_ltc_disney_diffuse_2;
    if (lobe == Lobe::Sheen) {
        t1 = rtpbr_ltc_sheen_1;
        t2 = rtpbr_ltc_sheen_2;
    }
    float3 N(0, 0, 1);
    float2 uv = rtpbr::LTC_LutCoord(glm::dot(N, V), roughness);
    float4 l1 = fetch(t1, uv), l2 = fetch(t2, uv);
    float scale;
    if (fr.kind == 1)
        scale = rtpbr::LTC_FresnelScale(l2, float3(0.04f), 1.0f).y;
    else if (fr.kind == 2)
        scale = rtpbr::LTC_FresnelScaleConductor(l2, float3(0.143f, 0.374f, 1.442f), float3(3.983f, 2.385f, 1.603f)).y;
    else
        scale = l2.x;
    rtpbr::float3x3 frame = rtpbr::LTC_Frame(N, V);
    rtpbr::LtcPolygon poly = sq.poly();
    float exact = rtpbr::LTC_IntegrateLocal(rtpbr::LTC_PolygonToLocal(frame, float3(0), poly, false), l1);
    float3 F = rtpbr::LTC_FormFactorVector(rtpbr::LTC_PolygonToLocalUnclipped(frame, float3(0), poly, false), l1);
    float approx = rtpbr::LTC_SphereFormFactorApprox(F);
    float tableValue = fetch(t2, rtpbr::LTC_SphereLutCoord(F)).w;
    float tabled = rtpbr::LTC_SphereFormFactor(F, tableValue);
    LtcEval e{double(scale) * exact, double(scale) * approx, double(scale) * tabled};
    // the engine corrects the microfacet lobes only (lighting.comp)
    double parts[4] = {0.0, 0.0, -1.0, 0.0};
    e.point = lobe == Lobe::GGX || lobe == Lobe::Beckmann
                  ? point_value(Brdf::make(lobe, roughness), V, rtpbr::LTC_PolygonToLocal(frame, float3(0), poly, false),
                                l1, l2.x, double(l2.x) * double(exact), true, parts) * double(scale) / double(l2.x)
                  : e.exact;
    e.pointOnly = lobe == Lobe::GGX || lobe == Lobe::Beckmann ? parts[0] * double(scale) / double(l2.x) : e.exact;
    e.tail = parts[1] * double(scale) / double(l2.x);
    e.streak = parts[2] >= 0.0 ? parts[2] * double(scale) / double(l2.x) : -1.0;
    e.streakWeight = parts[3];
    return e;
}

// One configuration of the grid.
struct Config {
    Lobe lobe;
    float roughness, viewDeg, half;
    int position; // 0 mirror direction, 1 normal, 2 side (azimuth 90, elevation 45), 3 low (elevation 10, azimuth 180),
                  // 4 back (elevation 25 on the viewer's side, azimuth 0: a light between the eye and a far floor)
};
inline const char *position_name(int p) {
    static const char *names[] = {"mirror", "normal", "side", "low", "back"};
    return names[p];
}

struct Outcome {
    Config cfg;
    double albedo;   // integral of f cos over the hemisphere
    bool significant; // the light receives at least kSignificant of the lobe's energy
    McResult ref;
    LtcEval ltc;
    double relExact, relClipless, relClipTable, relPoint;
};

inline float3 position_dir(int p, float3 V) {
    switch (p) {
    case 0: return float3(-V.x, -V.y, V.z);
    case 1: return float3(0, 0, 1);
    case 2: return float3(0.0f, 0.70710678f, 0.70710678f);
    case 3: return float3(-0.98480775f, 0.0f, 0.17364818f);
    default: return float3(0.90630779f, 0.0f, 0.42261826f);
    }
}

inline Outcome run_config(const Config &c, FresnelChoice fr, double targetRelErr, long maxPairs, uint64_t seed) {
    float th = c.viewDeg * 3.14159265f / 180.0f;
    float3 V(std::sin(th), 0.0f, std::cos(th));
    Square sq = make_square(position_dir(c.position, V), c.half);
    Brdf brdf = Brdf::make(c.lobe, c.roughness);
    Outcome o;
    o.cfg = c;
    o.albedo = albedo(brdf, V);
    o.ref = reference(brdf, V, sq, fr, seed, targetRelErr, maxPairs, kSignificant * o.albedo);
    o.significant = o.ref.mean >= kSignificant * o.albedo;
    o.ltc = ltc_eval(c.lobe, c.roughness, V, sq, fr);
    // Relative to the reference where the light matters; relative to the albedo (the whole
    // lobe's energy) in the far tail, where a relative error says nothing visible.
    double r = o.significant ? o.ref.mean : o.albedo;
    o.relExact = r > 0 ? std::fabs(o.ltc.exact - o.ref.mean) / r : 0.0;
    o.relClipless = r > 0 ? std::fabs(o.ltc.clipless - o.ref.mean) / r : 0.0;
    o.relClipTable = r > 0 ? std::fabs(o.ltc.clipless_table - o.ref.mean) / r : 0.0;
    o.relPoint = r > 0 ? std::fabs(o.ltc.point - o.ref.mean) / r : 0.0;
    return o;
}

struct Summary {
    double mean, p95, max;
    int count;
};

inline Summary summarize(std::vector<double> v) {
    const int count = int(v.size());
    const ltcfit::ErrorStats s = ltcfit::error_stats(std::move(v));
    return {s.mean, s.p95, s.max, count};
}

// The grid: roughness between table cells on purpose (bilinear filtering is part of what
// is measured), view angles, square half-sizes (at distance 1) and positions.
inline std::vector<float> grid_roughness(bool reduced) {
    return reduced ? std::vector<float>{0.2f, 0.5f, 0.8f} : std::vector<float>{0.15f, 0.3f, 0.5f, 0.7f, 0.9f};
}
inline std::vector<float> grid_views(bool reduced) {
    return reduced ? std::vector<float>{0.0f, 40.0f, 70.0f} : std::vector<float>{0.0f, 25.0f, 50.0f, 65.0f, 80.0f};
}
inline std::vector<float> grid_halves(bool reduced) {
    return reduced ? std::vector<float>{0.1f, 0.5f} : std::vector<float>{0.1f, 0.3f, 1.0f};
}

// positions: the default grid has the first four; rtpbr-ltc-validate --back measures position 4 alone.
inline std::vector<Config> grid(bool reduced, std::vector<Lobe> lobes = {Lobe::GGX, Lobe::Beckmann},
                                std::vector<int> positions = {0, 1, 2, 3}) {
    std::vector<Config> g;
    for (Lobe l : lobes)
        for (float r : grid_roughness(reduced))
            for (float v : grid_views(reduced))
                for (float h : grid_halves(reduced))
                    for (int p : positions) {
                        if (v == 0.0f && p == 0) // the mirror direction is the normal
                            continue;
                        g.push_back({l, r, v, h, p});
                    }
    return g;
}

} // namespace ltcmc
