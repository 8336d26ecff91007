// rtpbr shader library: the KHR_materials_sheen lobe.
//
// Estevez & Kulla 2017, "Production Friendly Microfacet Sheen BRDF" (SIGGRAPH course) [EK17]:
// the "Charlie" fibre distribution and its fitted Smith Lambda, as the glTF extension
// KHR_materials_sheen uses them (its implementation notes, cited as [KHR]).
//
//   f_sheen = sheenColor D_Charlie(NoH, alpha) V_Sheen(NoV, NoL, alpha)      (no Fresnel [KHR])
//   f       = f_sheen + Sheen_AlbedoScaling(sheenColor, E(NoV), E(NoL)) f_base
//   with a KHR clearcoat on top: f = f_coat + (1 - c Fc(NoV)) (f_sheen + scaling f_base).
//
// Conventions
//   - sheenRoughness is perceptual in [0, 1], alpha = sheenRoughness^2 (Sheen_Alpha; the
//     ratified [KHR] text and Filament square it), clamped below at RTPBR_MIN_ALPHA.
//   - V = G / (4 NoV NoL) like every V_ term of the library; nothing here includes the cosine
//     NoL. Local-frame functions take wo (viewer) and wi (light) with n = +z.
//   - Every public function is finite and non-negative for any input (NaN colours and
//     roughnesses are clamped like Disney_SanitizeMaterial: NaN -> the lower end).
//
// Model selection
//   RTPBR_SHEEN_VISIBILITY  RTPBR_SHEEN_VISIBILITY_CHARLIE (default): [EK17]'s fitted Lambda,
//                           the visibility [KHR] gives first; the albedo-scaling layering is
//                           energy conserving with it (the E tables are of this lobe).
//                           RTPBR_SHEEN_VISIBILITY_NEUBELT: Neubelt & Pettineo 2013's cheap
//                           1 / (4 (NoL + NoV - NoL NoV)) (Filament's cloth model, [KHR]'s
//                           alternative; not energy conserving with albedo scaling, its own
//                           E table is variant 1).
//
// Tables (shaderlib/luts/rtpbr_sheen_tables.h, sheen.md): E_sheen(mu, r), the directional
// albedo of f_sheen with sheenColor = 1, 32 x 32, the Kulla-Conty axis conventions (fetch at
// Sheen_TableCoord); the LTC fit of f_sheen NoL (rtpbr_ltc_sheen_tables.h; see Sheen_LtcScale).
#ifndef RTPBR_SHEEN_H
#define RTPBR_SHEEN_H

#include "lang.h"
#include "config.h"
#include "ndf.h"
#include "kulla_conty.h"

#define RTPBR_SHEEN_VISIBILITY_CHARLIE 1
#define RTPBR_SHEEN_VISIBILITY_NEUBELT 2
#ifndef RTPBR_SHEEN_VISIBILITY
#define RTPBR_SHEEN_VISIBILITY RTPBR_SHEEN_VISIBILITY_CHARLIE
#endif

RTPBR_NAMESPACE_BEGIN

// ---- parameters ------------------------------------------------------------------------------

// NaN-safe clamp to [0, 1] (NaN and negatives give 0).
RTPBR_FN float Sheen_Clamp01(float x) { return x > 0.0f ? min(x, 1.0f) : 0.0f; }

RTPBR_FN rtpbr_float3 Sheen_SanitizeColor(rtpbr_float3 c) {
    return rtpbr_float3(Sheen_Clamp01(c.x), Sheen_Clamp01(c.y), Sheen_Clamp01(c.z));
}

// [KHR] sheen layering: max3(sheenColor), the layer's weight in the albedo scaling.
RTPBR_FN float Sheen_Max3(rtpbr_float3 c) { return max(max(c.x, c.y), c.z); }

// alpha = sheenRoughness^2 ([KHR], Filament), clamped to [RTPBR_MIN_ALPHA, 1].
RTPBR_FN float Sheen_Alpha(float sheenRoughness) {
    float r = Sheen_Clamp01(sheenRoughness);
    return max(r * r, RTPBR_MIN_ALPHA);
}

// ---- distribution ----------------------------------------------------------------------------

// Estevez & Kulla 2017, "Production Friendly Microfacet Sheen BRDF", eq. 2:
// D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi); int D cos_h dw_h = 1.
RTPBR_FN float D_Charlie(float NoH, float alpha) {
    float a = max(alpha > 0.0f ? alpha : RTPBR_MIN_ALPHA, RTPBR_MIN_ALPHA);
    float invAlpha = 1.0f / a;
    float c = NoH > 0.0f ? min(NoH, 1.0f) : 0.0f; // NaN -> 0 (the peak, finite)
    float sin2h = rtpbr_pos(1.0f - c * c);
    return (2.0f + invAlpha) * pow(sin2h, 0.5f * invAlpha) * (0.5f * RTPBR_INV_PI);
}

// Samples h with density D_Charlie(h) cos(theta_h) (the CDF sin(theta_h)^(2 + 1/alpha) = u.x
// inverts in closed form; [EK17] sec. 2).
RTPBR_FN rtpbr_float3 Sample_Charlie(rtpbr_float2 u, float alpha) {
    float a = max(alpha > 0.0f ? alpha : RTPBR_MIN_ALPHA, RTPBR_MIN_ALPHA);
    float sinTheta = pow(Sheen_Clamp01(u.x), a / (2.0f * a + 1.0f));
    float cosTheta = rtpbr_safe_sqrt(1.0f - sinTheta * sinTheta);
    float phi = RTPBR_TWO_PI * Sheen_Clamp01(u.y);
    return rtpbr_float3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// ---- visibility ------------------------------------------------------------------------------

// Estevez & Kulla 2017, eq. 3 and table 1: the fitted curve
// L(x) = a / (1 + b x^c) + d x + e, coefficients interpolated between the fits at r = 0 and
// r = 1 with t = (1 - r)^2 (r = alpha, as [KHR]'s reference).
RTPBR_FN float Sheen_CharlieL(float x, float alpha) {
    float t = rtpbr_sq(1.0f - rtpbr_saturate(alpha));
    float a = rtpbr_lerp(21.5473f, 25.3245f, t);
    float b = rtpbr_lerp(3.82987f, 3.32435f, t);
    float c = rtpbr_lerp(0.19823f, 0.16801f, t);
    float d = rtpbr_lerp(-1.97760f, -1.27393f, t);
    float e = rtpbr_lerp(-4.32054f, -4.85967f, t);
    return a / (1.0f + b * pow(rtpbr_pos(x), c)) + d * x + e;
}

// Estevez & Kulla 2017, eq. 3: Lambda(cos) = exp(L(cos)) for cos < 0.5, else
// exp(2 L(0.5) - L(1 - cos)) (the fit mirrored about 0.5 keeps Lambda smooth at normal
// incidence); cos clamped to [0, 1] (Lambda(0) = exp(a + e) ~ 8e8, finite).
RTPBR_FN float Lambda_Charlie(float cosTheta, float alpha) {
    float c = cosTheta > 0.0f ? min(cosTheta, 1.0f) : 0.0f;
    if (c < 0.5f)
        return exp(Sheen_CharlieL(c, alpha));
    return exp(2.0f * Sheen_CharlieL(0.5f, alpha) - Sheen_CharlieL(1.0f - c, alpha));
}

// Estevez & Kulla 2017, sec. 3 "terminator softening": Lambda'(cos) = Lambda(cos)^(1 + 2 (1 -
// cos)^8), for the light direction only. NOT used by V_Charlie ([KHR] omits it; it breaks
// reciprocity); provided for renderers that want the paper's softer shadow terminator.
RTPBR_FN float Lambda_CharlieSoftened(float cosTheta, float alpha) {
    float c = cosTheta > 0.0f ? min(cosTheta, 1.0f) : 0.0f;
    float s = 1.0f - c;
    float s2 = s * s;
    float s4 = s2 * s2;
    return pow(Lambda_Charlie(c, alpha), 1.0f + 2.0f * s4 * s4);
}

// Estevez & Kulla 2017 with the height-correlated form [KHR] uses:
// V = 1 / ((1 + Lambda(NoV) + Lambda(NoL)) 4 NoV NoL); 0 below the horizon, capped at FLT_MAX.
RTPBR_FN float V_Charlie(float NoV, float NoL, float alpha) {
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return 0.0f;
    float denom = (1.0f + Lambda_Charlie(NoV, alpha) + Lambda_Charlie(NoL, alpha)) * (4.0f * NoV * NoL);
    return denom > 1.0f / RTPBR_FLT_MAX ? 1.0f / denom : RTPBR_FLT_MAX;
}

// Neubelt & Pettineo 2013, "Crafting a Next-Gen Material Pipeline for The Order: 1886":
// V = 1 / (4 (NoL + NoV - NoL NoV)) (Filament's cloth visibility; [KHR]'s cheap alternative).
RTPBR_FN float V_Neubelt(float NoV, float NoL) {
    if (!(NoV > 0.0f) || !(NoL > 0.0f))
        return 0.0f;
    float v = min(NoV, 1.0f), l = min(NoL, 1.0f);
    return 1.0f / (4.0f * (l + v - l * v));
}

// The visibility RTPBR_SHEEN_VISIBILITY selects.
RTPBR_FN float V_Sheen(float NoV, float NoL, float alpha) {
#if RTPBR_SHEEN_VISIBILITY == RTPBR_SHEEN_VISIBILITY_NEUBELT
#if defined(RTPBR_CPP)
    (void)alpha;
#endif
    return V_Neubelt(NoV, NoL);
#else
    return V_Charlie(NoV, NoL, alpha);
#endif
}

// ---- the lobe --------------------------------------------------------------------------------

// [KHR] f_sheen = sheenColor D V (F = 1), without the cosine. 0 unless NoV, NoL > 0.
RTPBR_FN rtpbr_float3 BRDF_Sheen(rtpbr_float3 sheenColor, float sheenRoughness, float NoV, float NoL, float NoH) {
    float alpha = Sheen_Alpha(sheenRoughness);
    float v = V_Sheen(NoV, NoL, alpha);
    float dv = min(D_Charlie(NoH, alpha) * v, RTPBR_FLT_MAX);
    return Sheen_SanitizeColor(sheenColor) * dv;
}

// BRDF_Sheen in the local frame (n = +z): the half vector from wo and wi.
RTPBR_FN rtpbr_float3 BRDF_SheenLocal(rtpbr_float3 sheenColor, float sheenRoughness, rtpbr_float3 wo, rtpbr_float3 wi) {
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f) || !(dot(wo, wo) < 1e30f) || !(dot(wi, wi) < 1e30f))
        return RTPBR_F3(0.0f);
    rtpbr_float3 hs = wo + wi;
    float hl = dot(hs, hs);
    if (!(hl > 0.0f))
        return RTPBR_F3(0.0f);
    return BRDF_Sheen(sheenColor, sheenRoughness, wo.z, wi.z, hs.z * rtpbr_rsqrt(hl));
}

// ---- layering --------------------------------------------------------------------------------

// [KHR] "Albedo-scaling technique" (Conty & Kulla 2017): the factor of the base layer,
// min(1 - max3(sheenColor) E(NoV), 1 - max3(sheenColor) E(NoL)), E = E_sheen fetched at
// Sheen_TableCoord(NoV or NoL, sheenRoughness). In [0, 1].
RTPBR_FN float Sheen_AlbedoScaling(rtpbr_float3 sheenColor, float E_NoV, float E_NoL) {
    float m = Sheen_Max3(Sheen_SanitizeColor(sheenColor));
    return rtpbr_saturate(min(1.0f - m * Sheen_Clamp01(E_NoV), 1.0f - m * Sheen_Clamp01(E_NoL)));
}

// [KHR] the view-only form 1 - max3(sheenColor) E(NoV): one lookup, usable for the
// environment (irradiance and specular) and for lights alike.
RTPBR_FN float Sheen_AlbedoScalingView(rtpbr_float3 sheenColor, float E_NoV) {
    float m = Sheen_Max3(Sheen_SanitizeColor(sheenColor));
    return rtpbr_saturate(1.0f - m * Sheen_Clamp01(E_NoV));
}

// uv at which to fetch the E_sheen table (rtpbr_sheen_E, 32 x 32): u = sqrt(NoV) axis, v =
// sheen perceptual roughness, node i at i / 31 on texel centres (the Kulla-Conty layout).
RTPBR_FN rtpbr_float2 Sheen_TableCoord(float NoV, float sheenRoughness) {
    return KC_TableCoord(NoV, Sheen_Clamp01(sheenRoughness));
}

// For polygon lights with the sheen LTC table (rtpbr_ltc_sheen_1/_2, fetched at
// LTC_LutCoord(NoV, sheenRoughness)): Lo = Le * Sheen_LtcScale(ltc2, sheenColor) *
// LTC_IntegrateLocal(local, ltc1). ltc2.x = norm (norm x the LTC's mass above the horizon =
// the lobe's albedo); the lobe has no Fresnel columns.
RTPBR_FN rtpbr_float3 Sheen_LtcScale(rtpbr_float4 ltc2, rtpbr_float3 sheenColor) {
    float norm = ltc2.x > 0.0f ? min(ltc2.x, RTPBR_FLT_MAX) : 0.0f; // NaN -> 0
    return Sheen_SanitizeColor(sheenColor) * norm;
}

// ---- sampling (oracle, table generation) -----------------------------------------------------

// A one-sample mixture for the sheen lobe: u.x < 0.5 reflects wo about h ~ D_Charlie cos_h,
// otherwise the uniform hemisphere (the lobe of small alpha is a ring near the horizon, which
// the D sampling alone misses at normal view; the uniform half bounds the weights). u.x is
// rescaled in each half, so stratified u stay stratified. The result may be below the horizon.
RTPBR_FN rtpbr_float3 Sample_SheenLobe(rtpbr_float3 wo, rtpbr_float2 u, float alpha) {
    if (u.x < 0.5f) {
        rtpbr_float3 h = Sample_Charlie(rtpbr_float2(2.0f * u.x, u.y), alpha);
        return 2.0f * dot(wo, h) * h - wo;
    }
    float z = rtpbr_saturate(2.0f * u.x - 1.0f);
    float r = rtpbr_safe_sqrt(1.0f - z * z);
    float phi = RTPBR_TWO_PI * u.y;
    return rtpbr_float3(r * cos(phi), r * sin(phi), z);
}

// The density of Sample_SheenLobe (solid angle): 0.5 D(h) NoH / (4 VoH) + 0.5 / (2 pi).
RTPBR_FN float PDF_SheenLobe(rtpbr_float3 wo, rtpbr_float3 wi, float alpha) {
    float p = wi.z > 0.0f ? 0.25f * RTPBR_INV_PI : 0.0f;
    rtpbr_float3 hs = wo + wi;
    float hl = dot(hs, hs);
    if (hl > 0.0f) {
        rtpbr_float3 h = hs * rtpbr_rsqrt(hl);
        float VoH = dot(wo, h);
        if (h.z > 0.0f && VoH > 0.0f)
            p += 0.5f * D_Charlie(h.z, alpha) * h.z / (4.0f * VoH);
    }
    return min(p, RTPBR_FLT_MAX);
}

RTPBR_NAMESPACE_END

#endif // RTPBR_SHEEN_H
