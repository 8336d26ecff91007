// rtpbr shader library: the Disney principled BRDF.
//
// Burley 2012, "Physically-Based Shading at Disney" (SIGGRAPH course notes, revised Aug 31
// 2012, and its BRDF Explorer reference shader disney.brdf, cited as [B12] and [B12-brdf]).
// One colour and ten scalar parameters, each 0..1 over its plausible range (DisneyMaterial).
//
// Conventions
//   - Local shading frame: n = +z, tangent (the anisotropy's "rougher" axis) = +x, bitangent
//     = +y. wo (towards the viewer) and wi (towards the light) are unit vectors in that frame;
//     build them with rtpbr_mul(rtpbr_mat3_rows(t, b, n), w). Directions at or below the
//     horizon give 0. Nothing here includes the cosine factor NoL.
//   - baseColor is LINEAR (the BRDF Explorer gamma-decodes its colour picker first).
//   - Roughness is perceptual; alpha = roughness^2 (Alpha_FromPerceptual, [B12] sec. 5.4).
//   - Every public function first clamps the material to the documented ranges
//     (Disney_SanitizeMaterial; NaN becomes the lower end of the range), so the result is
//     finite and non-negative for any input.
//   - The Smith G of both specular lobes follows RTPBR_SMITH (height-correlated by default).
//     Burley's reference shader uses the separable product G1(l) G1(v); compile with
//     RTPBR_SMITH = RTPBR_SMITH_SEPARABLE to reproduce it exactly. The specular lobe is GGX
//     with Schlick's Fresnel whatever RTPBR_NDF / RTPBR_FRESNEL say: that is the model.
//   - [B12-brdf] has no upper clamp on the anisotropic alphas; the core's Alpha_Anisotropic
//     clamps them to 1 (a difference only at roughness > ~0.56 with anisotropy).
//
// Model selection
//   RTPBR_DISNEY_ENERGY_CONSERVING  0 (default): Burley's model, BRDF_Disney.
//                                   1: the energy-conserving variant,
//                                   BRDF_DisneyEnergyConserving (below, and docs/disney.md).
//   BRDF_DisneyModel / Disney_Sample / Disney_PDF follow the flag; the named functions of
//   both variants are always compiled.
#ifndef RTPBR_DISNEY_H
#define RTPBR_DISNEY_H

#include "lang.h"
#include "config.h"
#include "fresnel.h"
#include "ndf.h"
#include "smith.h"
#include "sampling.h"
#include "kulla_conty.h"

#ifndef RTPBR_DISNEY_ENERGY_CONSERVING
#define RTPBR_DISNEY_ENERGY_CONSERVING 0
#endif

// Marks a parameter a flag setting leaves unused (C++ warns; GLSL and HLSL have no cast to void).
#if defined(RTPBR_CPP)
#define RTPBR_DISNEY_UNUSED(x) (void)(x)
#else
#define RTPBR_DISNEY_UNUSED(x)
#endif

RTPBR_NAMESPACE_BEGIN

// The parameters of [B12] sec. 5.2; defaults of [B12-brdf]. Ranges: all [0, 1] except
// specular in [0, 12.5] ([B12] principle 4, "pushed beyond the plausible range where it makes
// sense": specular = 1 is F0 = 0.08, IOR ~1.8; 12.5 is F0 = 1). Out-of-range values and NaN
// are clamped by Disney_SanitizeMaterial.
struct DisneyMaterial {
    rtpbr_float3 baseColor;     // linear RGB in [0, 1]; default (0.82, 0.67, 0.16) [B12-brdf]
    float metallic;       // 0 dielectric .. 1 metal (linear blend); default 0
    float subsurface;     // blend of Burley diffuse towards the subsurface shape; default 0
    float specular;       // F0 = 0.08 specular for dielectrics; default 0.5 (F0 = 0.04)
    float specularTint;   // tints dielectric F0 towards the base hue; default 0
    float roughness;      // perceptual roughness (diffuse and specular); default 0.5
    float anisotropic;    // 0 isotropic .. 1 aspect 10:1 along the tangent; default 0
    float sheen;          // grazing retro-reflective lobe for cloth; default 0
    float sheenTint;      // tints sheen towards the base hue; default 0.5
    float clearcoat;      // strength of the second specular lobe; default 0
    float clearcoatGloss; // 0 "satin" (alpha 0.1) .. 1 "gloss" (alpha 0.001); default 1
};

// The values of the BRDF Explorer's disney.brdf parameter block.
RTPBR_FN DisneyMaterial Disney_DefaultMaterial() {
    DisneyMaterial m;
    m.baseColor = rtpbr_float3(0.82f, 0.67f, 0.16f);
    m.metallic = 0.0f;
    m.subsurface = 0.0f;
    m.specular = 0.5f;
    m.specularTint = 0.0f;
    m.roughness = 0.5f;
    m.anisotropic = 0.0f;
    m.sheen = 0.0f;
    m.sheenTint = 0.5f;
    m.clearcoat = 0.0f;
    m.clearcoatGloss = 1.0f;
    return m;
}

RTPBR_CONST float RTPBR_DISNEY_SPECULAR_MAX = 12.5f;

// NaN-safe clamp to [0, hi]: NaN and negatives give 0.
RTPBR_FN float Disney_Clamp(float x, float hi) { return x > 0.0f ? min(x, hi) : 0.0f; }

RTPBR_FN DisneyMaterial Disney_SanitizeMaterial(DisneyMaterial m) {
    DisneyMaterial s;
    s.baseColor = rtpbr_float3(Disney_Clamp(m.baseColor.x, 1.0f), Disney_Clamp(m.baseColor.y, 1.0f),
                         Disney_Clamp(m.baseColor.z, 1.0f));
    s.metallic = Disney_Clamp(m.metallic, 1.0f);
    s.subsurface = Disney_Clamp(m.subsurface, 1.0f);
    s.specular = Disney_Clamp(m.specular, RTPBR_DISNEY_SPECULAR_MAX);
    s.specularTint = Disney_Clamp(m.specularTint, 1.0f);
    s.roughness = Disney_Clamp(m.roughness, 1.0f);
    s.anisotropic = Disney_Clamp(m.anisotropic, 1.0f);
    s.sheen = Disney_Clamp(m.sheen, 1.0f);
    s.sheenTint = Disney_Clamp(m.sheenTint, 1.0f);
    s.clearcoat = Disney_Clamp(m.clearcoat, 1.0f);
    s.clearcoatGloss = Disney_Clamp(m.clearcoatGloss, 1.0f);
    return s;
}

// Replaces NaN and negative components by 0 and caps at the largest float.
RTPBR_FN rtpbr_float3 Disney_FiniteNonNegative(rtpbr_float3 v) {
    return rtpbr_float3(Disney_Clamp(v.x, RTPBR_FLT_MAX), Disney_Clamp(v.y, RTPBR_FLT_MAX),
                  Disney_Clamp(v.z, RTPBR_FLT_MAX));
}

// True when both directions are finite and strictly above the horizon.
RTPBR_FN bool Disney_ValidPair(rtpbr_float3 wo, rtpbr_float3 wi) {
    return wo.z > 0.0f && wi.z > 0.0f && dot(wo, wo) < 1e30f && dot(wi, wi) < 1e30f;
}

// [B12-brdf] SchlickFresnel: the Schlick weight (1 - u)^5, u clamped to [0, 1] (NaN -> 1).
RTPBR_FN float Disney_SchlickWeight(float u) {
    float m = 1.0f - (u > 0.0f ? min(u, 1.0f) : 0.0f);
    float m2 = m * m;
    return m2 * m2 * m;
}

// [B12-brdf] luminance approximation 0.3 R + 0.6 G + 0.1 B.
RTPBR_FN float Disney_Luminance(rtpbr_float3 c) { return 0.3f * c.x + 0.6f * c.y + 0.1f * c.z; }

// [B12-brdf] Ctint: the base colour normalised by its luminance (hue and saturation only);
// white for a black base colour.
RTPBR_FN rtpbr_float3 Disney_TintColor(rtpbr_float3 baseColor) {
    float lum = Disney_Luminance(baseColor);
    if (lum > 0.0f)
        return baseColor / lum;
    return RTPBR_F3(1.0f);
}

// [B12] sec. 5.5 and [B12-brdf]: F0 = rtpbr_lerp(0.08 specular rtpbr_lerp(1, Ctint, specularTint),
// baseColor, metallic), clamped to [0, 1] (0.08 = the F0 of IOR ~1.8: the top of the
// "plausible" dielectric range). Expects a sanitized material.
// The blends are written as sums of non-negative terms: no cancellation, so that the GLSL,
// HLSL and C++ builds round alike even where the result is tiny.
RTPBR_FN rtpbr_float3 Disney_SpecularF0(DisneyMaterial m) {
    rtpbr_float3 tint = Disney_TintColor(m.baseColor);
    rtpbr_float3 dielectric = (0.08f * m.specular) * (RTPBR_F3(1.0f - m.specularTint) + m.specularTint * tint);
    return rtpbr_saturate((1.0f - m.metallic) * dielectric + m.metallic * m.baseColor);
}

// [B12-brdf] Csheen = rtpbr_lerp(1, Ctint, sheenTint).
RTPBR_FN rtpbr_float3 Disney_SheenColor(DisneyMaterial m) {
    return rtpbr_lerp(RTPBR_F3(1.0f), Disney_TintColor(m.baseColor), m.sheenTint);
}

// [B12] addenda / [B12-brdf]: aspect = sqrt(1 - 0.9 anisotropic), alphaX = alpha / aspect,
// alphaY = alpha aspect (the core's Alpha_Anisotropic), alpha = roughness^2; as in [B12-brdf]
// the lower clamp (RTPBR_MIN_ALPHA = 0.001) applies after the aspect split. Sanitized material.
RTPBR_FN rtpbr_float2 Disney_SpecularAlphas(DisneyMaterial m) {
    return Alpha_Anisotropic(m.roughness * m.roughness, m.anisotropic);
}

// The isotropic alpha at which a caller looks up isotropic tables (split-sum DFG, Kulla-Conty
// E and E_avg) for this material: sqrt(alphaX alphaY), = roughness^2 unless clamped.
RTPBR_FN float Disney_SpecularTableAlpha(DisneyMaterial m) {
    DisneyMaterial s = Disney_SanitizeMaterial(m);
    rtpbr_float2 a = Disney_SpecularAlphas(s);
    return sqrt(a.x * a.y);
}

// [B12] sec. 5.4 and [B12-brdf]: clearcoat GTR1 alpha = rtpbr_lerp(0.1, 0.001, clearcoatGloss).
RTPBR_FN float Disney_ClearcoatAlpha(DisneyMaterial m) {
    return rtpbr_lerp(0.1f, 0.001f, m.clearcoatGloss);
}

// [B12-brdf]: the clearcoat's Smith G uses the fixed GGX alpha 0.25.
RTPBR_CONST float RTPBR_DISNEY_CLEARCOAT_G_ALPHA = 0.25f;
// [B12] sec. 5.4: the clearcoat layer has a fixed IOR of 1.5, F0 = 0.04.
RTPBR_CONST float RTPBR_DISNEY_CLEARCOAT_F0 = 0.04f;
// [B12] sec. 5.4: "the normalized parameter range corresponds to an overall scale of [0, 0.25]".
RTPBR_CONST float RTPBR_DISNEY_CLEARCOAT_SCALE = 0.25f;

RTPBR_FN float Disney_CombineSmith(float lambdaO, float lambdaI) {
#if RTPBR_SMITH == RTPBR_SMITH_SEPARABLE
    return G2_Separable(lambdaO, lambdaI);
#else
    return G2_HeightCorrelated(lambdaO, lambdaI);
#endif
}

// ---- the lobes of Burley's model (sanitized material, valid directions) ----------------------

// [B12] sec. 5.3: Burley diffuse, Fd = (1 + (FD90 - 1)(1 - NoL)^5)(1 + (FD90 - 1)(1 - NoV)^5),
// FD90 = 0.5 + 2 roughness cos^2(theta_d); [B12-brdf]: the subsurface shape after
// Hanrahan & Krueger 1993 ("Reflection from Layered Surfaces due to Subsurface Scattering"):
// Fss90 = roughness cos^2(theta_d), ss = 1.25 (Fss (1 / (NoL + NoV) - 0.5) + 0.5), the 1.25
// "roughly preserving albedo". Result: (1 - metallic) baseColor / pi rtpbr_lerp(Fd, ss, subsurface).
RTPBR_FN rtpbr_float3 Disney_DiffuseLobe(DisneyMaterial m, float NoV, float NoL, float LoH) {
    float FL = Disney_SchlickWeight(NoL);
    float FV = Disney_SchlickWeight(NoV);
    float LoH2 = LoH * LoH;
    float Fd90 = 0.5f + 2.0f * m.roughness * LoH2;
    float Fd = rtpbr_lerp(1.0f, Fd90, FL) * rtpbr_lerp(1.0f, Fd90, FV);
    float Fss90 = m.roughness * LoH2;
    float Fss = rtpbr_lerp(1.0f, Fss90, FL) * rtpbr_lerp(1.0f, Fss90, FV);
    // NoL + NoV > 0 here; the floor keeps 1/x finite for denormal cosines.
    float ss = 1.25f * (Fss * (1.0f / max(NoL + NoV, 1e-7f) - 0.5f) + 0.5f);
    float shape = rtpbr_lerp(Fd, ss, m.subsurface);
    return ((1.0f - m.metallic) * RTPBR_INV_PI * shape) * m.baseColor;
}

// [B12] sec. 5.3: sheen, a Schlick-shaped grazing term sheen Csheen (1 - LoH)^5, scaled by
// (1 - metallic) like the diffuse ([B12-brdf]).
RTPBR_FN rtpbr_float3 Disney_SheenLobe(DisneyMaterial m, float LoH) {
    return ((1.0f - m.metallic) * m.sheen * Disney_SchlickWeight(LoH)) * Disney_SheenColor(m);
}

// [B12] appendix B.2 / [B12-brdf]: anisotropic GGX (GTR2_aniso) with Smith G and Schlick
// Fresnel (f90 = 1): D G F / (4 NoL NoV).
RTPBR_FN rtpbr_float3 Disney_SpecularLobe(DisneyMaterial m, rtpbr_float3 wo, rtpbr_float3 wi, rtpbr_float3 h) {
    rtpbr_float2 a = Disney_SpecularAlphas(m);
    float D = D_GGX_Aniso(h.z, h.x, h.y, a.x, a.y);
    float G = Disney_CombineSmith(Lambda_GGX_Aniso(wo, a.x, a.y), Lambda_GGX_Aniso(wi, a.x, a.y));
    rtpbr_float3 F = F_Schlick(Disney_SpecularF0(m), 1.0f, dot(wo, h));
    return (D * G / max(4.0f * wo.z * wi.z, 1e-30f)) * F;
}

// Burley 2012, appendix B.2, eq. 4: GTR1, D = (a^2 - 1) / (pi ln(a^2) (1 + (a^2 - 1) cos^2 theta_h)),
// the core's D_GTR at gamma = 1, but with the denominator written a^2 cos^2 + sin^2 and sin^2
// from h's tangent components: at gloss 1 (alpha = 0.001) 1 - cos^2 near the peak cancels
// catastrophically in float (D_GTR errs by ~1% there). h is a unit vector in the local frame.
RTPBR_FN float D_GTR1_Local(rtpbr_float3 h, float alpha) {
    if (!(h.z > 0.0f))
        return 0.0f;
    float a2 = rtpbr_sq(Alpha_Clamp(alpha));
    if (!(a2 < 0.9999f)) // alpha = 1: the uniform distribution of normals
        return RTPBR_INV_PI;
    float sin2 = h.x * h.x + h.y * h.y;
    return (a2 - 1.0f) / (RTPBR_PI * log(a2) * (a2 * h.z * h.z + sin2));
}

// [B12] sec. 5.4 and [B12-brdf]: clearcoat, 0.25 clearcoat GTR1(alpha_c) G(0.25) F(0.04) /
// (4 NoL NoV).
RTPBR_FN float Disney_ClearcoatLobe(DisneyMaterial m, rtpbr_float3 wo, rtpbr_float3 wi, rtpbr_float3 h) {
    if (!(m.clearcoat > 0.0f))
        return 0.0f;
    float D = D_GTR1_Local(h, Disney_ClearcoatAlpha(m));
    float G = Disney_CombineSmith(Lambda_GGX(wo.z, RTPBR_DISNEY_CLEARCOAT_G_ALPHA),
                                  Lambda_GGX(wi.z, RTPBR_DISNEY_CLEARCOAT_G_ALPHA));
    float F = F_Schlick1(RTPBR_DISNEY_CLEARCOAT_F0, 1.0f, dot(wo, h));
    return RTPBR_DISNEY_CLEARCOAT_SCALE * m.clearcoat * D * G * F / max(4.0f * wo.z * wi.z, 1e-30f);
}

// Half vector of a valid pair (wo + wi cannot vanish when both are above the horizon).
RTPBR_FN rtpbr_float3 Disney_HalfVector(rtpbr_float3 wo, rtpbr_float3 wi) {
    rtpbr_float3 s = wo + wi;
    return s * rtpbr_rsqrt(max(dot(s, s), 1e-30f));
}

// ---- public lobe evaluation (any material, any directions) -----------------------------------

// Diffuse + subsurface lobe of BRDF_Disney.
RTPBR_FN rtpbr_float3 BRDF_DisneyDiffuse(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi) {
    if (!Disney_ValidPair(wo, wi))
        return RTPBR_F3(0.0f);
    DisneyMaterial m = Disney_SanitizeMaterial(material);
    rtpbr_float3 h = Disney_HalfVector(wo, wi);
    return Disney_FiniteNonNegative(Disney_DiffuseLobe(m, wo.z, wi.z, dot(wi, h)));
}

// Sheen lobe of BRDF_Disney.
RTPBR_FN rtpbr_float3 BRDF_DisneySheen(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi) {
    if (!Disney_ValidPair(wo, wi))
        return RTPBR_F3(0.0f);
    DisneyMaterial m = Disney_SanitizeMaterial(material);
    rtpbr_float3 h = Disney_HalfVector(wo, wi);
    return Disney_FiniteNonNegative(Disney_SheenLobe(m, dot(wi, h)));
}

// Specular (anisotropic GGX) lobe of BRDF_Disney.
RTPBR_FN rtpbr_float3 BRDF_DisneySpecular(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi) {
    if (!Disney_ValidPair(wo, wi))
        return RTPBR_F3(0.0f);
    DisneyMaterial m = Disney_SanitizeMaterial(material);
    return Disney_FiniteNonNegative(Disney_SpecularLobe(m, wo, wi, Disney_HalfVector(wo, wi)));
}

// Clearcoat (GTR1) lobe of BRDF_Disney (achromatic).
RTPBR_FN float BRDF_DisneyClearcoat(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi) {
    if (!Disney_ValidPair(wo, wi))
        return 0.0f;
    DisneyMaterial m = Disney_SanitizeMaterial(material);
    return Disney_Clamp(Disney_ClearcoatLobe(m, wo, wi, Disney_HalfVector(wo, wi)), RTPBR_FLT_MAX);
}

// Burley's principled BRDF ([B12-brdf] BRDF()): diffuse + sheen + specular + clearcoat.
RTPBR_FN rtpbr_float3 BRDF_Disney(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi) {
    if (!Disney_ValidPair(wo, wi))
        return RTPBR_F3(0.0f);
    DisneyMaterial m = Disney_SanitizeMaterial(material);
    rtpbr_float3 h = Disney_HalfVector(wo, wi);
    float LoH = dot(wi, h);
    rtpbr_float3 f = Disney_DiffuseLobe(m, wo.z, wi.z, LoH) + Disney_SheenLobe(m, LoH);
    f = f + Disney_SpecularLobe(m, wo, wi, h);
    f = f + RTPBR_F3(Disney_ClearcoatLobe(m, wo, wi, h));
    return Disney_FiniteNonNegative(f);
}

// ---- the energy-conserving variant ----------------------------------------------------------
//
//   f_ec(o, i) = f_cc(o, i) + Tcc(o) Tcc(i) [ f_spec(o, i) + f_ms(o, i) + tb(o) tb(i) f_base(o, i) ]
//
//   f_cc, f_spec   Burley's clearcoat and specular lobes, unchanged.
//   f_ms           Kulla & Conty 2017 ("Revisiting Physically Based Shading at Imageworks"),
//                  the terms of kulla_conty.h: KC_FmsColor(F_Avg_Schlick(F0, 1), E_avg)
//                  KC_Lobe(E(o), E(i), E_avg), i.e. Fms (1 - E(o)) (1 - E(i)) / (pi (1 - E_avg)),
//                  Fms = Favg^2 E_avg / (1 - Favg (1 - E_avg)), Favg = F0 + (1 - F0) / 21: the
//                  energy the single-scattering specular loses, coloured by multiple bounces.
//   f_base         Burley's diffuse + subsurface + sheen, (1 - metallic) included.
//   Tcc(mu)        = 1 - clearcoat Ucc(mu): Ucc bounds the clearcoat lobe's albedo (at
//                  clearcoat = 1) from above, over all clearcoatGloss.
//   tb(mu)         = (1 - Espec(mu)) / max(1, Bbase(mu)) per channel: Espec(mu) = F0 A(mu) + B(mu)
//                  + Fms (1 - E(mu)) is the albedo of f_spec + f_ms, Bbase(mu) >= the albedo of
//                  f_base / (1 - metallic) (closed form, Disney_BaseAlbedoBound).
// Every factor is symmetric in (o, i), so the variant is reciprocal, and the albedo is at most
//   Ucc(o) + Tcc(o) [Espec(o) + tb(o) Bbase(o)] <= Ucc(o) + Tcc(o) = 1
// provided the table values are the albedos of this specular lobe (see DisneyEnergyTerms).
// Unlike Burley's model it cannot gain energy; unlike it, the base loses the energy that the
// layers above reflect, and Burley's retro-reflective diffuse gain (albedo up to ~1.56 at
// roughness 1, grazing) is normalised away.

// The table values the energy-conserving variant needs, fetched by the caller (the library
// takes already-fetched values). For the specular lobe at perceptual roughness
// Disney_SpecularTableRoughness (the Kulla-Conty tables' axis; alpha = its square):
//   dfgO, dfgI  (A, B) at mu = wo.z and mu = wi.z: the lobe's directional albedo with Schlick's
//               Fresnel is F0 A + B, with F = 1 it is Kulla-Conty's E = A + B; B is the
//               (1 - VoH)^5-weighted part (the split-sum terms of Karis 2013, "Real Shading in
//               Unreal Engine 4"). Exact (A, B) from a DFG table, or, from the Kulla-Conty
//               E(mu) alone, the conservative Disney_EnergyTermsFromKullaConty.
//   Eavg        Kulla-Conty E_avg = 2 integral E(mu) mu dmu.
// The tables must belong to the Smith G of this header (RTPBR_SMITH: the kulla_conty tables'
// ggx_hc variant by default, ggx_sep for RTPBR_SMITH_SEPARABLE). With anisotropy the isotropic
// tables are an approximation (exact per-direction albedos keep the bound exact).
struct DisneyEnergyTerms {
    rtpbr_float2 dfgO;
    rtpbr_float2 dfgI;
    float Eavg;
};

// Perceptual roughness at which to fetch the isotropic Kulla-Conty / DFG tables:
// sqrt(sqrt(alphaX alphaY)), = roughness unless clamped (the Kulla-Conty tables' r axis).
RTPBR_FN float Disney_SpecularTableRoughness(DisneyMaterial material) {
    return sqrt(Disney_SpecularTableAlpha(material));
}

// Texture coordinates of E(mu, r) for the direction with cosine NoV, and of E_avg(r)
// (kulla_conty.h conventions).
RTPBR_FN rtpbr_float2 Disney_KullaContyCoord(DisneyMaterial material, float NoV) {
    return KC_TableCoord(NoV, Disney_SpecularTableRoughness(material));
}
RTPBR_FN float Disney_KullaContyCoordAvg(DisneyMaterial material) {
    return KC_TableCoordAvg(Disney_SpecularTableRoughness(material));
}

// (A, B) from the Kulla-Conty E(mu) alone, with B replaced by an upper bound: every reflected
// direction above the horizon has VoH >= mu / 2 (wi.z = 2 VoH h.z - mu >= 0), so
// B <= E (1 - mu / 2)^5. Overestimating B only overestimates the specular albedo, which darkens
// the base: the bound of the variant still holds (at mu = 0.5 a smooth dielectric's base loses
// ~20 % more than with exact split-sum terms; nothing at normal or grazing incidence).
RTPBR_FN rtpbr_float2 Disney_DfgFromKullaConty(float E, float mu) {
    float e = Disney_Clamp(E, 1.0f);
    float B = e * Disney_SchlickWeight(0.5f * Disney_Clamp(mu, 1.0f));
    return rtpbr_float2(e - B, B);
}

// DisneyEnergyTerms from fetched Kulla-Conty values E(NoV), E(NoL), E_avg.
RTPBR_FN DisneyEnergyTerms Disney_EnergyTermsFromKullaConty(float Eo, float Ei, float Eavg, float NoV,
                                                            float NoL) {
    DisneyEnergyTerms t;
    t.dfgO = Disney_DfgFromKullaConty(Eo, NoV);
    t.dfgI = Disney_DfgFromKullaConty(Ei, NoL);
    t.Eavg = Eavg;
    return t;
}

// The Fresnel colour of f_ms (Kulla & Conty 2017) for Disney's Schlick Fresnel with f90 = 1.
RTPBR_FN rtpbr_float3 Disney_MultiscatterFresnel(rtpbr_float3 F0, float Eavg) {
    return KC_FmsColor(F_Avg_Schlick(F0, 1.0f), Eavg);
}

// Albedo of Burley's diffuse shape Fd / pi (baseColor = 1, subsurface = 0, no sheen) for a
// direction with cosine mu, in closed form. With k = FD90 - 1 = (r - 1/2) + r (o.i) and
// cos^2(theta_d) = (1 + o.i) / 2, averaging over the azimuth of i leaves polynomials in mu_i
// whose moments against (1 - mu_i)^5 are Beta integrals (1/21, 1/84, 1/252; derivation in
// docs/disney.md). Exact, not a bound.
RTPBR_FN float Disney_DiffuseAlbedo(float mu, float roughness) {
    float y = rtpbr_saturate(mu > 0.0f ? mu : 0.0f);
    float V = Disney_SchlickWeight(y);
    float a = roughness - 0.5f;
    float b = roughness;
    return 1.0f + a * (1.0f / 21.0f + V) + b * y * (1.0f / 84.0f + (2.0f / 3.0f) * V) +
           V * (a * a / 21.0f + a * b * y / 42.0f +
                b * b * (y * y / 252.0f + (11.0f / 504.0f) * (1.0f - y * y)));
}

// Upper bound of the albedo of the subsurface shape ss / pi: Fss <= 1 - (1 - r)(1 - mu_o)^5
// (each factor lies in [Fss90, 1] and Fss90 <= r), 1/(mu_o + mu_i) - 1/2 >= 0, and
// 2 integral mu_i / (mu_o + mu_i) dmu_i = 2 (1 - mu_o ln(1 + 1/mu_o)).
RTPBR_FN float Disney_SubsurfaceAlbedoBound(float mu, float roughness) {
    float y = max(rtpbr_saturate(mu > 0.0f ? mu : 0.0f), 1e-6f);
    float V = Disney_SchlickWeight(y);
    float inv = 2.0f * (1.0f - y * log(1.0f + 1.0f / y)) - 0.5f;
    return 1.25f * ((1.0f - (1.0f - roughness) * V) * inv + 0.5f);
}

// Upper bound of the albedo of the sheen shape (1 - LoH)^5 (no 1/pi in [B12-brdf]):
// 0.0006 + 0.09 (1 - mu)^2, a fit above the numerically integrated albedo (0.0884 at grazing,
// 0.00026 at normal incidence; checked by tests/shaderlib/disney).
RTPBR_FN float Disney_SheenAlbedoBound(float mu) {
    float y = rtpbr_saturate(mu > 0.0f ? mu : 0.0f);
    return 0.0006f + 0.09f * rtpbr_sq(1.0f - y);
}

// Upper bound Ucc of the albedo of the clearcoat lobe at clearcoat = 1, over every
// clearcoatGloss: 0.01 + 0.055 (1 - mu)^1.5, a fit above the numerically integrated albedo with
// the height-correlated G (0.059 at grazing, 0.0094 at normal incidence; checked by
// tests/shaderlib/disney); the separable G2 is smaller, so the bound holds for both RTPBR_SMITH forms.
RTPBR_FN float Disney_ClearcoatAlbedoBound(float mu) {
    float x = 1.0f - rtpbr_saturate(mu > 0.0f ? mu : 0.0f);
    return 0.01f + 0.055f * x * sqrt(x);
}

// Per channel upper bound of the albedo of f_base / (1 - metallic) for a sanitized material.
RTPBR_FN rtpbr_float3 Disney_BaseAlbedoBound(DisneyMaterial m, float mu) {
    float shape = rtpbr_lerp(Disney_DiffuseAlbedo(mu, m.roughness),
                       Disney_SubsurfaceAlbedoBound(mu, m.roughness), m.subsurface);
    return shape * m.baseColor + (m.sheen * Disney_SheenAlbedoBound(mu)) * Disney_SheenColor(m);
}

// Sanitized copy of the caller's table values: A, B, E = A + B and E_avg in [0, 1].
RTPBR_FN DisneyEnergyTerms Disney_SanitizeTerms(DisneyEnergyTerms t) {
    DisneyEnergyTerms s;
    s.dfgO = rtpbr_float2(Disney_Clamp(t.dfgO.x, 1.0f), Disney_Clamp(t.dfgO.y, 1.0f));
    s.dfgI = rtpbr_float2(Disney_Clamp(t.dfgI.x, 1.0f), Disney_Clamp(t.dfgI.y, 1.0f));
    s.dfgO.x = min(s.dfgO.x, 1.0f - s.dfgO.y);
    s.dfgI.x = min(s.dfgI.x, 1.0f - s.dfgI.y);
    s.Eavg = Disney_Clamp(t.Eavg, 1.0f);
    return s;
}

// Albedo of f_spec + f_ms at a direction with table values dfg = (A, B).
RTPBR_FN rtpbr_float3 Disney_SpecularAlbedo(rtpbr_float3 F0, rtpbr_float2 dfg, rtpbr_float3 Fms) {
    float E = dfg.x + dfg.y;
    return F0 * dfg.x + RTPBR_F3(dfg.y) + Fms * (1.0f - E);
}

// The scale tb(mu) of the base layer, per channel.
RTPBR_FN rtpbr_float3 Disney_BaseScale(DisneyMaterial m, float mu, rtpbr_float3 F0, rtpbr_float2 dfg, rtpbr_float3 Fms) {
    rtpbr_float3 room = rtpbr_saturate(RTPBR_F3(1.0f) - Disney_SpecularAlbedo(F0, dfg, Fms));
    return room / max(Disney_BaseAlbedoBound(m, mu), RTPBR_F3(1.0f));
}

// Kulla-Conty multiple-scattering lobe f_ms (with its Fresnel), for sanitized terms.
RTPBR_FN rtpbr_float3 Disney_MultiscatterLobe(rtpbr_float3 Fms, DisneyEnergyTerms t) {
    return Fms * KC_Lobe(t.dfgO.x + t.dfgO.y, t.dfgI.x + t.dfgI.y, t.Eavg);
}

// Tcc(o) Tcc(i): the transmission through the clearcoat, for a sanitized material.
RTPBR_FN float Disney_ClearcoatTransmission(DisneyMaterial m, float NoV, float NoL) {
    return (1.0f - m.clearcoat * Disney_ClearcoatAlbedoBound(NoV)) *
           (1.0f - m.clearcoat * Disney_ClearcoatAlbedoBound(NoL));
}

// The glossy part of f_ec: Tcc(o) Tcc(i) f_spec. Needs no table values.
RTPBR_FN rtpbr_float3 BRDF_DisneyEnergyConservingSpecular(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi) {
    if (!Disney_ValidPair(wo, wi))
        return RTPBR_F3(0.0f);
    DisneyMaterial m = Disney_SanitizeMaterial(material);
    rtpbr_float3 f = Disney_SpecularLobe(m, wo, wi, Disney_HalfVector(wo, wi));
    return Disney_FiniteNonNegative(Disney_ClearcoatTransmission(m, wo.z, wi.z) * f);
}

// The broad part of f_ec: Tcc(o) Tcc(i) [f_ms + tb(o) tb(i) f_base] (multiple scattering, diffuse,
// subsurface, sheen).
RTPBR_FN rtpbr_float3 BRDF_DisneyEnergyConservingDiffuse(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi,
                                                   DisneyEnergyTerms terms) {
    if (!Disney_ValidPair(wo, wi))
        return RTPBR_F3(0.0f);
    DisneyMaterial m = Disney_SanitizeMaterial(material);
    DisneyEnergyTerms t = Disney_SanitizeTerms(terms);
    rtpbr_float3 h = Disney_HalfVector(wo, wi);
    float LoH = dot(wi, h);
    rtpbr_float3 F0 = Disney_SpecularF0(m);
    rtpbr_float3 Fms = Disney_MultiscatterFresnel(F0, t.Eavg);
    rtpbr_float3 base = Disney_DiffuseLobe(m, wo.z, wi.z, LoH) + Disney_SheenLobe(m, LoH);
    rtpbr_float3 tb = Disney_BaseScale(m, wo.z, F0, t.dfgO, Fms) * Disney_BaseScale(m, wi.z, F0, t.dfgI, Fms);
    rtpbr_float3 f = Disney_MultiscatterLobe(Fms, t) + tb * base;
    return Disney_FiniteNonNegative(Disney_ClearcoatTransmission(m, wo.z, wi.z) * f);
}

// The energy-conserving variant f_ec (see above): the sum of its diffuse, specular and clearcoat
// parts.
RTPBR_FN rtpbr_float3 BRDF_DisneyEnergyConserving(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi,
                                            DisneyEnergyTerms terms) {
    rtpbr_float3 f = BRDF_DisneyEnergyConservingDiffuse(material, wo, wi, terms) +
               BRDF_DisneyEnergyConservingSpecular(material, wo, wi);
    return Disney_FiniteNonNegative(f + RTPBR_F3(BRDF_DisneyClearcoat(material, wo, wi)));
}

// The model selected by RTPBR_DISNEY_ENERGY_CONSERVING (terms are ignored by Burley's model).
RTPBR_FN rtpbr_float3 BRDF_DisneyModel(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi, DisneyEnergyTerms terms) {
#if RTPBR_DISNEY_ENERGY_CONSERVING
    return BRDF_DisneyEnergyConserving(material, wo, wi, terms);
#else
    RTPBR_DISNEY_UNUSED(terms);
    return BRDF_Disney(material, wo, wi);
#endif
}

// ---- sampling -------------------------------------------------------------------------------
//
// One-sample mixture: a lobe is picked with probability proportional to its weight, then
// importance-sampled: cosine-weighted hemisphere for diffuse + subsurface + sheen (and the
// multiple-scattering lobe), the core's GGX visible normals for the specular, GTR1 inversion
// for the clearcoat. Disney_PDF returns the mixture density sum_k p_k pdf_k(wi), the density of
// Disney_Sample; the caller evaluates the BRDF at the returned direction (the energy-conserving
// variant needs the table values at wi first).

RTPBR_CONST int RTPBR_DISNEY_LOBE_DIFFUSE = 1;
RTPBR_CONST int RTPBR_DISNEY_LOBE_SPECULAR = 2;
RTPBR_CONST int RTPBR_DISNEY_LOBE_CLEARCOAT = 4;

struct DisneySample {
    rtpbr_float3 wi;  // sampled direction (local frame); below the horizon when pdf = 0
    float pdf;  // Disney_PDF(wo, wi), per solid angle; 0 for an invalid sample
    int lobe;   // the RTPBR_DISNEY_LOBE_* that produced wi
};

// Burley 2012, appendix B.2, eq. 2: GTR1 half vectors, cos^2 theta_h = (1 - a^(2(1 - u))) / (1 - a^2),
// density D_GTR1(h) cos theta_h.
RTPBR_FN rtpbr_float3 Sample_GTR1(float alpha, rtpbr_float2 u) {
    float a2 = rtpbr_sq(Alpha_Clamp(alpha));
    float cos2 = (1.0f - pow(a2, 1.0f - u.x)) / (1.0f - a2);
    if (!(a2 < 0.9999f)) // alpha -> 1: the limit of the formula, cos^2 theta_h = 1 - u
        cos2 = 1.0f - u.x;
    float cosTheta = rtpbr_safe_sqrt(min(cos2, 1.0f));
    float sinTheta = rtpbr_safe_sqrt(1.0f - cosTheta * cosTheta);
    float phi = RTPBR_TWO_PI * u.y;
    return rtpbr_float3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// Density of the reflected direction when h ~ D_GTR1(h) cos theta_h: pdf_h / (4 wo.h).
RTPBR_FN float PDF_GTR1_Reflection(rtpbr_float3 wo, rtpbr_float3 wi, float alpha) {
    if (!Disney_ValidPair(wo, wi))
        return 0.0f;
    rtpbr_float3 h = Disney_HalfVector(wo, wi);
    float woDotH = dot(wo, h);
    if (!(woDotH > 0.0f))
        return 0.0f;
    return D_GTR1_Local(h, alpha) * h.z / (4.0f * woDotH);
}

// Lobe probabilities (diffuse, specular, clearcoat), summing to 1, for a sanitized material:
// diffuse (1 - metallic)(lum(baseColor) + sheen lum(Csheen)) + multiscatter,
// specular lum(F_Schlick(F0, NoV)) (at least 0.02: the lobe is never 0),
// clearcoat 0.25 clearcoat F_Schlick(0.04, NoV). multiscatter > 0 adds a cosine-lobe weight for
// the energy-conserving variant's f_ms.
RTPBR_FN rtpbr_float3 Disney_LobeProbabilities(DisneyMaterial m, float NoV, float multiscatter) {
    rtpbr_float3 F0 = Disney_SpecularF0(m);
    float wd = (1.0f - m.metallic) *
               (Disney_Luminance(m.baseColor) + m.sheen * Disney_Luminance(Disney_SheenColor(m))) +
               multiscatter;
    float ws = max(Disney_Luminance(F_Schlick(F0, 1.0f, NoV)), 0.02f);
    float wc = RTPBR_DISNEY_CLEARCOAT_SCALE * m.clearcoat * F_Schlick1(RTPBR_DISNEY_CLEARCOAT_F0, 1.0f, NoV);
    float total = wd + ws + wc;
    return rtpbr_float3(wd, ws, wc) / total;
}

// The weight of the multiple-scattering lobe in the lobe choice: alpha lum(Favg), roughly the
// energy f_ms carries (0 unless energyConserving).
RTPBR_FN float Disney_MultiscatterWeight(DisneyMaterial m, bool energyConserving) {
    if (!energyConserving)
        return 0.0f;
    rtpbr_float2 a = Disney_SpecularAlphas(m);
    return sqrt(a.x * a.y) * Disney_Luminance(F_Avg_Schlick(Disney_SpecularF0(m), 1.0f));
}

RTPBR_FN float Disney_PDFEx(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi, bool energyConserving) {
    if (!Disney_ValidPair(wo, wi))
        return 0.0f;
    DisneyMaterial m = Disney_SanitizeMaterial(material);
    rtpbr_float3 p = Disney_LobeProbabilities(m, wo.z, Disney_MultiscatterWeight(m, energyConserving));
    rtpbr_float2 a = Disney_SpecularAlphas(m);
    float pdf = p.x * PDF_CosineHemisphere(wi) + p.y * PDF_GGX_Reflection(wo, wi, a.x, a.y);
    if (p.z > 0.0f)
        pdf += p.z * PDF_GTR1_Reflection(wo, wi, Disney_ClearcoatAlpha(m));
    return Disney_Clamp(pdf, RTPBR_FLT_MAX);
}

// u: three uniform numbers in [0, 1): u.x picks the lobe, (u.y, u.z) sample it.
RTPBR_FN DisneySample Disney_SampleEx(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 u, bool energyConserving) {
    DisneySample s;
    s.wi = rtpbr_float3(0.0f, 0.0f, -1.0f);
    s.pdf = 0.0f;
    s.lobe = 0;
    if (!(wo.z > 0.0f) || !(dot(wo, wo) < 1e30f))
        return s;
    DisneyMaterial m = Disney_SanitizeMaterial(material);
    rtpbr_float3 p = Disney_LobeProbabilities(m, wo.z, Disney_MultiscatterWeight(m, energyConserving));
    rtpbr_float2 uv = rtpbr_float2(Disney_Clamp(u.y, 0.99999994f), Disney_Clamp(u.z, 0.99999994f));
    float choice = Disney_Clamp(u.x, 0.99999994f);
    if (choice < p.x) {
        s.wi = Sample_CosineHemisphere(uv);
        s.lobe = RTPBR_DISNEY_LOBE_DIFFUSE;
    } else if (choice < p.x + p.y || !(p.z > 0.0f)) {
        rtpbr_float2 a = Disney_SpecularAlphas(m);
        s.wi = Reflect_About(wo, Sample_GGX_VNDF(wo, a.x, a.y, uv));
        s.lobe = RTPBR_DISNEY_LOBE_SPECULAR;
    } else {
        s.wi = Reflect_About(wo, Sample_GTR1(Disney_ClearcoatAlpha(m), uv));
        s.lobe = RTPBR_DISNEY_LOBE_CLEARCOAT;
    }
    s.pdf = Disney_PDFEx(m, wo, s.wi, energyConserving);
    return s;
}

// Mixture density and sampler of the model selected by RTPBR_DISNEY_ENERGY_CONSERVING.
RTPBR_FN float Disney_PDF(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 wi) {
    return Disney_PDFEx(material, wo, wi, RTPBR_DISNEY_ENERGY_CONSERVING != 0);
}

RTPBR_FN DisneySample Disney_Sample(DisneyMaterial material, rtpbr_float3 wo, rtpbr_float3 u) {
    return Disney_SampleEx(material, wo, u, RTPBR_DISNEY_ENERGY_CONSERVING != 0);
}

RTPBR_NAMESPACE_END

#endif // RTPBR_DISNEY_H
