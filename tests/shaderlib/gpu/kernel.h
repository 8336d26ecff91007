// rtpbr GPU test kernel: one source that says what the GPU (GLSL and HLSL builds) and the
// CPU (C++ build) both evaluate.
//
//   float rtpbr_test_eval(rtpbr_float4 a, rtpbr_float4 b, uint j)
//
// maps one input tuple (a, b: eight uniforms in [0, 1], made on the host by a fixed-seed PRNG
// with a share of exact 0 / 1 / near-0 / near-1 values, see test_gpu.c) and an output index
// j in [0, RTPBR_TEST_OUTPUTS) to one value: output j is one public shaderlib function (or one
// component of a vector result) evaluated at arguments derived from (a, b).
//
// The outputs are listed in kernel_cases.h, one section per shaderlib header
// (cases/<header>.inc), as RTPBR_TEST_CASE(name, expression) lines. This file includes that
// list several times with different meanings of RTPBR_TEST_CASE: the evaluation chain here,
// and for C++ only the output count and the output names. Adding a header: see kernel_cases.h.
//
// Arguments are derived with + - * / and sqrt only (no transcendentals, no normalize), so
// that both sides see the same inputs up to rounding: the test compares the library, not the
// argument mapping. `precise` keeps GPU compilers from contracting the derivations into FMAs.
#ifndef RTPBR_TEST_KERNEL_H
#define RTPBR_TEST_KERNEL_H

#include "rtpbr/microfacet.h"
#include "rtpbr/sampling.h"
#include "rtpbr/ltc.h"
#include "rtpbr/ltc_anisotropy.h"
#include "rtpbr/ltc_corrections.h"
#include "rtpbr/material.h"
#include "rtpbr/kulla_conty.h"

#if defined(RTPBR_CPP)
#define RTPBR_TEST_PRECISE
#else
#define RTPBR_TEST_PRECISE precise
#endif

RTPBR_NAMESPACE_BEGIN

// The largest float below 1.
RTPBR_CONST float RTPBR_TEST_BELOW_ONE = 0.99999994f;

// The arguments every case draws from. Domains are those of the library's documentation.
struct RtpbrTestArgs {
    float c0, c1, c2, c3; // cosines in [0, 1] (a.x, a.y, b.x, b.y), exact 0 and 1 included
    float sc;             // signed cosine in [-1, 1] (2 a.x - 1)
    float x;              // real argument in [-4, 4] (erf, erfc)
    float p;              // open interval (-1, 1) (erfinv)
    float perceptual;     // perceptual roughness in [0, 1] (a.z)
    float alpha;          // [RTPBR_MIN_ALPHA, 1], denser near the minimum (a.z^2)
    float alphaX, alphaY; // anisotropic pair (a.z, a.w)
    float aniso;          // anisotropy in [0, 1] (a.w)
    float gamma;          // GTR exponent: [0.5, 4], 10% of tuples within 5e-5 of 1 (series path)
    float eta;            // dielectric relative IOR in [1.01, 3]
    rtpbr_float3 etaC;          // conductor IOR per channel in [0.1, 3]
    rtpbr_float3 kC;            // conductor extinction per channel in [0, 8]
    float f0, f90;        // Schlick parameters in [0, 1]
    rtpbr_float3 f0C;           // coloured f0 in [0, 1]
    float lambdaO, lambdaI; // Smith Lambda values in [0, 1e3]
    float beckA;          // Beckmann a = cot(theta) / alpha in [0, 10]
    float mu;             // cot(theta) of a direction, [0, 1e6]
    rtpbr_float3 wo, wi, wm;    // local directions (n = +z), z = c0, c1, a.w; azimuths from b.z, b.w, b.x
    rtpbr_float2 u;             // a sample pair (b.x, b.y) in [0, 1) (the samplers' domain)
};

// A direction with cosine c to +z and an azimuth picked by t in [0, 1] through the rational
// parametrisation of the circle by q = tan(phi / 2) (two half circles, t < 0.5 and t >= 0.5).
RTPBR_FN rtpbr_float3 rtpbr_test_dir(float c, float t) {
    RTPBR_TEST_PRECISE float v = 4.0f * t;
    RTPBR_TEST_PRECISE float sgn = v < 2.0f ? 1.0f : -1.0f;
    RTPBR_TEST_PRECISE float q = v < 2.0f ? v - 1.0f : v - 3.0f;
    RTPBR_TEST_PRECISE float d = 1.0f + q * q;
    RTPBR_TEST_PRECISE float cosPhi = sgn * (1.0f - q * q) / d;
    RTPBR_TEST_PRECISE float sinPhi = sgn * (2.0f * q) / d;
    RTPBR_TEST_PRECISE float s = sqrt(max(1.0f - c * c, 0.0f));
    return rtpbr_float3(s * cosPhi, s * sinPhi, c);
}

RTPBR_FN float rtpbr_test_lerp(float lo, float hi, float t) {
    RTPBR_TEST_PRECISE float r = lo + (hi - lo) * t;
    return r;
}

RTPBR_FN RtpbrTestArgs rtpbr_test_args(rtpbr_float4 a, rtpbr_float4 b) {
    RtpbrTestArgs t;
    t.c0 = a.x;
    t.c1 = a.y;
    t.c2 = b.x;
    t.c3 = b.y;
    t.sc = rtpbr_test_lerp(-1.0f, 1.0f, a.x);
    t.x = rtpbr_test_lerp(-4.0f, 4.0f, a.x);
    t.p = rtpbr_test_lerp(-0.999f, 0.999f, a.y);
    t.perceptual = a.z;
    t.alpha = rtpbr_test_lerp(RTPBR_MIN_ALPHA, 1.0f, a.z * a.z);
    t.alphaX = t.alpha;
    t.alphaY = rtpbr_test_lerp(RTPBR_MIN_ALPHA, 1.0f, a.w * a.w);
    t.aniso = a.w;
    if (b.w < 0.1f)
        t.gamma = rtpbr_test_lerp(1.0f - 5e-5f, 1.0f + 5e-5f, b.w * 10.0f);
    else
        t.gamma = rtpbr_test_lerp(0.5f, 4.0f, b.w);
    t.eta = rtpbr_test_lerp(1.01f, 3.0f, b.z);
    t.etaC = rtpbr_float3(rtpbr_test_lerp(0.1f, 3.0f, b.z), rtpbr_test_lerp(0.1f, 3.0f, b.w),
                    rtpbr_test_lerp(0.1f, 3.0f, a.w));
    t.kC = rtpbr_float3(8.0f * b.x, 8.0f * b.y, 8.0f * a.z);
    t.f0 = b.z;
    t.f90 = b.w;
    t.f0C = rtpbr_float3(b.z, b.w, a.w);
    t.lambdaO = 1e3f * a.x * a.x;
    t.lambdaI = 1e3f * a.y * a.y;
    t.beckA = 10.0f * a.x;
    RTPBR_TEST_PRECISE float s0 = sqrt(max(1.0f - a.x * a.x, 0.0f));
    t.mu = s0 > 1e-6f ? a.x / s0 : 1e6f;
    t.wo = rtpbr_test_dir(a.x, b.z);
    t.wi = rtpbr_test_dir(a.y, b.w);
    t.wm = rtpbr_test_dir(a.w, b.x);
    t.u = rtpbr_float2(min(b.x, RTPBR_TEST_BELOW_ONE), min(b.y, RTPBR_TEST_BELOW_ONE));
    return t;
}

// ltc.h's streamed integration of a planar convex quad around the shading point that the
// horizon may cut (vertex heights h + gx x + gy y over the unit square's corners rotated by 45
// degrees, all derived from the arguments), through the horizon clip and one LTC lobe of
// M^-1 rows (m00, 0, m02), (0, 1, 0), (m20, 0, m22), stretched (LTC_AnisotropicInverseMatrix,
// about +z along +x by k) when `stretch`. Returns the lobe's form factor (which = 0), or the
// component `which` - 1 of the clipped quad's vector form factor (1-3); the lobe's own vector
// (LTC_LobeEndVector, 4-6); the point correction's direction (LTC_LobePoint, 7-9), density
// (10) and factor (LTC_PointFactor with fCos = t.c2 x density x 2, the lobe's form factor and
// a width ratio of 0.8 + t.aniso, 11); the tail estimate's weight (LTC_PointTailWeight of the
// lobe's vector, the lobe's form factor and 2 t.c3 F.z, 12) and the combination (LTC_PointCombine of the corrected form factor, a tail
// LTC_PointTail(t.lambdaO, F.z, 0.2 + t.c3) and that weight, 13).
RTPBR_FN float rtpbr_test_ltc_quad(RtpbrTestArgs t, bool stretch, int which) {
    RTPBR_TEST_PRECISE float h = 0.5f * t.sc;
    RTPBR_TEST_PRECISE float gx = t.c1 - 0.5f;
    RTPBR_TEST_PRECISE float gy = t.c2 - 0.5f;
    rtpbr_float3 v0 = rtpbr_float3(1.0f, 0.0f, h + gx);
    rtpbr_float3 v1 = rtpbr_float3(0.0f, 1.0f, h + gy);
    rtpbr_float3 v2 = rtpbr_float3(-1.0f, 0.0f, h - gx);
    rtpbr_float3 v3 = rtpbr_float3(0.0f, -1.0f, h - gy);
    RTPBR_TEST_PRECISE float m02 = 0.5f * t.sc;
    RTPBR_TEST_PRECISE float m20 = t.c3 - 0.5f;
    RTPBR_TEST_PRECISE float m22 = 0.5f + t.c0;
    RTPBR_TEST_PRECISE float k = 1.0f + 3.0f * t.aniso;
    rtpbr_float4 ltc1 = rtpbr_float4(0.2f + t.perceptual, m02, m20, m22);
    rtpbr_float3x3 minv = stretch ? LTC_AnisotropicInverseMatrix(ltc1, rtpbr_float3(0.0f, 0.0f, 1.0f), rtpbr_float3(1.0f, 0.0f, 0.0f), k)
                            : LTC_InverseMatrix(ltc1);
    LtcClipper horizon = LTC_ClipperBegin();
    LtcLobe lobe = LTC_LobeBegin(minv);
    rtpbr_float3 F = RTPBR_F3(0.0f);
    for (int e = 0; e < 5; e++) {
        rtpbr_float3 a = e == 0 ? v0 : (e == 1 ? v1 : (e == 2 ? v2 : v3));
        rtpbr_float3 b = e == 0 ? v1 : (e == 1 ? v2 : (e == 2 ? v3 : v0));
        LtcSegment seg = e < 4 ? LTC_ClipEdge(horizon, a, b) : LTC_ClipClose(horizon);
        if (seg.valid) {
            F += LTC_EdgeIntegral(LTC_SafeNormalize(seg.a), LTC_SafeNormalize(seg.b));
            LTC_LobeEdge(lobe, seg.a, seg.b);
        }
    }
    if (which <= 3)
        return which == 0 ? LTC_LobeEnd(lobe) : (which == 1 ? F.x : (which == 2 ? F.y : F.z));
    rtpbr_float3 Fl = LTC_LobeEndVector(lobe);
    if (which <= 6)
        return which == 4 ? Fl.x : (which == 5 ? Fl.y : Fl.z);
    LtcPoint pt = LTC_LobePoint(Fl, ltc1);
    if (which <= 9)
        return which == 7 ? pt.dir.x : (which == 8 ? pt.dir.y : pt.dir.z);
    if (which == 10)
        return pt.density;
    float corrected = LTC_LobeEnd(lobe) * LTC_PointFactor(2.0f * t.c2 * pt.density, pt.density, LTC_LobeEnd(lobe), 0.8f + t.aniso);
    if (which == 11)
        return corrected / max(LTC_LobeEnd(lobe), 1e-30f);
    float weight = LTC_PointTailWeight(Fl, LTC_LobeEnd(lobe), 2.0f * t.c3 * F.z);
    if (which == 12)
        return weight;
    return LTC_PointCombine(corrected, LTC_PointTail(t.lambdaO, F.z, 0.2f + t.c3), weight);
}

// The streak estimate (ltc_corrections.h) streamed as the engine does (two passes over a
// horizon-clipped quad): a horizontal panel facing down at height h, on the mirror side of
// V at a low view angle, seen edge-on. which: 0 the estimate, 1 its trust, 2 its weight.
RTPBR_FN float rtpbr_test_ltc_streak(RtpbrTestArgs t, int which) {
    RTPBR_TEST_PRECISE float nov = 0.05f + 0.4f * t.c0;
    RTPBR_TEST_PRECISE float h = 0.02f + 0.2f * t.c1;
    RTPBR_TEST_PRECISE float w = 0.15f + 0.3f * t.c2;
    RTPBR_TEST_PRECISE float cx = -1.0f - 0.5f * t.c3;
    RTPBR_TEST_PRECISE float cy = 0.8f * t.sc; // |cy| > w: off the plane of incidence (the second cut)
    rtpbr_float3 vLocal = rtpbr_float3(sqrt(1.0f - nov * nov), 0.0f, nov);
    rtpbr_float3 v0 = rtpbr_float3(cx - w, cy - w, h);
    rtpbr_float3 v1 = rtpbr_float3(cx + w, cy - w, h);
    rtpbr_float3 v2 = rtpbr_float3(cx + w, cy + w, h);
    rtpbr_float3 v3 = rtpbr_float3(cx - w, cy + w, h);
    rtpbr_float3 F = RTPBR_F3(0.0f);
    LtcStreak st = LTC_StreakBegin();
    for (int pass = 0; pass < 2; pass++) {
        LtcClipper horizon = LTC_ClipperBegin();
        for (int e = 0; e < 5; e++) {
            rtpbr_float3 a = e == 0 ? v0 : (e == 1 ? v1 : (e == 2 ? v2 : v3));
            rtpbr_float3 b = e == 0 ? v1 : (e == 1 ? v2 : (e == 2 ? v3 : v0));
            LtcSegment seg = e < 4 ? LTC_ClipEdge(horizon, a, b) : LTC_ClipClose(horizon);
            if (seg.valid) {
                if (pass == 0) {
                    F += LTC_EdgeIntegral(LTC_SafeNormalize(seg.a), LTC_SafeNormalize(seg.b));
                    LTC_StreakEdge(st, seg.a, seg.b);
                } else {
                    LTC_StreakChordEdge(st, seg.a, seg.b);
                }
            }
        }
        if (pass == 0)
            LTC_StreakNodes(st, F);
    }
    if (which == 2)
        return LTC_StreakWeight(vLocal, F);
    rtpbr_float2 r = LTC_StreakEnd(st, vLocal, 0.05f + 0.5f * t.perceptual);
    return which == 0 ? r.x : r.y;
}

// LTC_StreakLateral over [s1, s1 + w] with every argument rounded once (no contraction: a
// narrow range's width would otherwise differ between compilers by an ulp of s1).
RTPBR_FN float rtpbr_test_streak_lateral(RtpbrTestArgs t) {
    RTPBR_TEST_PRECISE float s1 = 4.0f * t.c1 - 2.0f;
    RTPBR_TEST_PRECISE float w = 3.0f * t.c2;
    RTPBR_TEST_PRECISE float s2 = s1 + w;
    RTPBR_TEST_PRECISE float a2 = 0.01f + t.c3;
    RTPBR_TEST_PRECISE float m = 1.0f - t.alpha * t.alpha;
    return LTC_StreakLateral(s1, s2, a2, m);
}

// A scalar argument in the regimes of rtpbr_test_material, picked by b.w: x (b.w < 0.4), then
// 0 (< 0.6), negative, huge (1e30), NaN, +infinity. NaN and infinity come from an overflow of
// run-time values (no division by zero), so that no compiler folds them.
RTPBR_FN float rtpbr_test_hostile(float x, rtpbr_float4 a, rtpbr_float4 b) {
    RTPBR_TEST_PRECISE float big = 1e30f * (1.0f + a.x);
    RTPBR_TEST_PRECISE float inf = big * big;
    RTPBR_TEST_PRECISE float nan = inf - inf;
    return b.w < 0.4f ? x : (b.w < 0.6f ? 0.0f : (b.w < 0.7f ? -0.5f - a.x : (b.w < 0.8f ? big : (b.w < 0.9f ? nan : inf))));
}

// material.h's inputs from (a, b) in one of seven regimes picked by b.w: ordinary values
// (b.w < 0.4), ordinary with ior 0 (KHR's F = 1 mode; < 0.5), then every scalar of the
// material (colours included) set to the same hostile value of rtpbr_test_hostile: 0
// (roughness 0, ior 0, ...), negative, huge, NaN, +infinity.
RTPBR_FN MaterialInputs rtpbr_test_material(rtpbr_float4 a, rtpbr_float4 b, int model) {
    MaterialInputs m;
    m.model = model;
    m.baseColor = rtpbr_float3(a.x, a.y, b.x);
    m.metallic = b.y;
    m.roughness = a.z;
    m.ior = b.w < 0.4f ? rtpbr_test_lerp(1.0f, 3.0f, b.z) : 0.0f;
    m.specularFactor = a.w;
    m.specularColor = rtpbr_float3(2.0f * b.z, b.x, a.y);
    m.clearcoatFactor = a.x;
    m.clearcoatRoughness = a.w;
    m.sheenColorFactor = rtpbr_float3(b.y, a.z, a.x);
    m.sheenRoughness = b.x;
    m.anisotropyStrength = a.w;
    m.disney.baseColor = RTPBR_F3(0.0f); // ignored by the resolve: the fields above are used
    m.disney.metallic = 0.0f;
    m.disney.roughness = 0.0f;
    m.disney.subsurface = a.y;
    m.disney.specular = 12.5f * b.z * b.z;
    m.disney.specularTint = b.x;
    m.disney.anisotropic = a.w;
    m.disney.sheen = b.y;
    m.disney.sheenTint = a.x;
    m.disney.clearcoat = b.z;
    m.disney.clearcoatGloss = a.z;
    float h = rtpbr_test_hostile(0.0f, a, b);
    if (b.w >= 0.5f) {
        rtpbr_float3 h3 = rtpbr_float3(h, h, h);
        m.baseColor = h3;
        m.metallic = h;
        m.roughness = h;
        m.ior = h;
        m.specularFactor = h;
        m.specularColor = h3;
        m.clearcoatFactor = h;
        m.clearcoatRoughness = h;
        m.sheenColorFactor = h3;
        m.sheenRoughness = h;
        m.anisotropyStrength = h;
        m.disney.subsurface = h;
        m.disney.specular = h;
        m.disney.specularTint = h;
        m.disney.anisotropic = h;
        m.disney.sheen = h;
        m.disney.sheenTint = h;
        m.disney.clearcoat = h;
        m.disney.clearcoatGloss = h;
    }
    return m;
}

// Each case assigns instead of returning early: lavapipe (Mesa 22.3, gallivm) miscompiled the
// early-return form of this chain (outputs past ~75 came out wrong, the same SPIR-V with fewer
// cases was right); returns are lowered to nested ifs and gallivm's control-flow nesting is
// limited (LP_MAX_TGSI_NESTING = 80), the likely cause. Keep the chain flat.
RTPBR_FN float rtpbr_test_eval(rtpbr_float4 a, rtpbr_float4 b, uint j) {
    RtpbrTestArgs t = rtpbr_test_args(a, b);
    uint n = 0u;
    float r = 0.0f;
#define RTPBR_TEST_CASE(name, expr) \
    if (j == n)                     \
        r = (expr);                 \
    n++;
#include "kernel_cases.h"
#undef RTPBR_TEST_CASE
    return r;
}

RTPBR_NAMESPACE_END

#if defined(RTPBR_CPP)
// The number of outputs and their names (for the host's report), from the same list.
#define RTPBR_TEST_CASE(name, expr) +1
RTPBR_CONST unsigned RTPBR_TEST_OUTPUTS = 0u
#include "kernel_cases.h"
    ;
#undef RTPBR_TEST_CASE
#define RTPBR_TEST_CASE(name, expr) #name,
static const char *const rtpbr_test_output_names[RTPBR_TEST_OUTPUTS] = {
#include "kernel_cases.h"
};
#undef RTPBR_TEST_CASE
#endif

#endif // RTPBR_TEST_KERNEL_H
