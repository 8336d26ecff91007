// rtpbr shader library: a surface point's material, resolved for shading.
//
// Surface_Resolve turns a material's resolved parameters (material.h, Material_Resolve) and the
// view into every term the per-light evaluation (area_light.h) and a Monte Carlo estimator need:
// the lobes' table roughness, Fresnel, anisotropy, layers, and the Kulla-Conty albedos at the
// view direction. The model (oracle/bsdf.h is the path tracer's statement of it):
//   metallic-roughness: f = (1 - c Fc(NoV)) [metallic f_metal + (1 - metallic) f_dielectric]
//                           + c f_coat,
//     f_metal = GGX, Schlick(F0 = baseColor, 1) + its Kulla-Conty lobe,
//     f_dielectric = w GGX Schlick(F0(ior) specularColor, 1) + w F_ms f_ms (w: specularWeight)
//                    + baseColor (1 - Es(mu_o)) (1 - Es(mu_i)) / (pi (1 - Es_avg)),
//     Es = w (E_F + F_ms (1 - E)) (KC_SpecularAlbedoDielectric; E_F with exact Fresnel),
//     f_coat = GGX(clearcoat roughness), Schlick(0.04, 1) + its Kulla-Conty lobe;
//     with KHR sheen, the bracket is f_sheen + A [...], f_sheen = sheenColor D_Charlie V
//     (sheen.h), A = min(1 - max(sheenColor) E_sheen(mu_o), 1 - max(sheenColor) E_sheen(mu_i));
//   Disney (Burley 2012, disney.h): specular GGX Schlick(Disney_SpecularF0, 1) + its
//     Kulla-Conty lobe, Burley diffuse + subsurface + sheen, GTR1 clearcoat 0.25 c.
// Anisotropic lobes (alpha_t along the anisotropy direction, alpha_b across it): the tables
// are looked up at sqrt(alpha_t alpha_b); the LTC evaluation stretches that isotropic lobe by
// k = sqrt(alpha_t / alpha_b) along the direction (LTC_AnisotropicInverseMatrix).
//
// The library never samples textures: the host defines, before including this header, the
// table reads it needs (the host bridge; bilinear, clamp to edge, tables of the NDF in use):
//   rtpbr_float2 Host_TableE_EF(float mu, float r, float eta)  Kulla-Conty E(mu, r) and
//                                     E_F(mu, r, eta) (rtpbr_kc_tables.h; KC_TableCoord3D)
//   float Host_TableE(float mu, float r)       E(mu, r)   (KC_TableCoord)
//   float Host_TableEavg(float r)              E_avg(r)   (KC_TableCoordAvg)
//   float Host_TableEFavg(float r, float eta)  E_F_avg    (KC_TableCoordAvg2D)
//   float Host_TableSheenE(float mu, float r)  E_sheen    (rtpbr_sheen_tables.h; Sheen_TableCoord)
// A host without multiple scattering may return 0 from the E_F and E_F_avg reads and build
// with RTPBR_MULTISCATTER 0. Values that the model does not need (no coat, no sheen) are never
// read.
#ifndef RTPBR_SURFACE_H
#define RTPBR_SURFACE_H

#include "lang.h"
#include "config.h"
#include "fresnel.h"
#include "ndf.h"
#include "microfacet.h"
#include "kulla_conty.h"
#include "disney.h"
#include "sheen.h"
#include "material.h"

RTPBR_NAMESPACE_BEGIN

struct ShadingSurface {
    bool disney;
    DisneyMaterial dm;    // sanitised (Disney materials only)
    rtpbr_float3 baseColor;
    float metallic;
    float roughness;      // perceptual
    float NoV;
    float tableRoughness; // MaterialParams.tableRoughness: the specular lobe's tables' axis
    rtpbr_float3 anisoDir; // anisotropy direction (world, unit) or 0
    float anisoK;         // sqrt(alpha_t / alpha_b) >= 1; 1: isotropic
    rtpbr_float2 alphas;  // (alpha_t, alpha_b) of the specular lobe (isotropic: both sqrt(at ab))
    float specularWeight; // dielectric specular weight (KHR specularFactor)
    float eta;            // dielectric IOR
    rtpbr_float3 f0;      // Schlick F0 and F90 of the specular lobe (metal and dielectric mixed)
    float f90;
    rtpbr_float3 diffuseColor; // (1 - metallic) baseColor
    float coat;           // coat weight (Disney: 0.25 clearcoat), 0: none
    float coatRoughness;  // its perceptual roughness (Disney: sqrt of the GTR1 alpha)
    float baseAttenuation; // 1 - c Fc(NoV) for KHR clearcoat; 1 for Disney's
    // Kulla-Conty terms (zero without RTPBR_MULTISCATTER)
    float Eo, Eavg;       // E(NoV), E_avg of the specular lobe
    float FmsDielectric;  // F_ms of the dielectric layer
    rtpbr_float3 msColor; // colour of the specular lobe's f_ms
    float EFavg;          // E_F_avg of the dielectric layer
    float Eso, EsAvg;     // the layer's albedo at NoV and on average (specularWeight included)
    float Eoc, Eavgc;     // E(NoV), E_avg of the coat
    rtpbr_float3 msCoat;  // colour of the coat's f_ms (coat weight included)
    bool sheen;           // KHR sheen layer present
    rtpbr_float3 sheenColor;
    float sheenRoughness; // its perceptual roughness
    float EsheenO;        // E_sheen(NoV)
};

// The shading terms of a material p (Material_Resolve) seen at NoV = saturate(N.V), with the
// anisotropy direction anisoDir (world space; 0 for none: the lobe is then isotropic at
// sqrt(alpha_t alpha_b)).
RTPBR_FN ShadingSurface Surface_Resolve(MaterialParams p, float NoV, rtpbr_float3 anisoDir) {
    ShadingSurface s;
    s.disney = p.disney;
    s.dm = p.dm;
    s.baseColor = p.baseColor;
    s.metallic = p.metallic;
    s.roughness = p.roughness;
    s.NoV = NoV;
    s.tableRoughness = p.tableRoughness;
    // Anisotropic lobes: alpha_t along the given direction; without one, isotropic.
    bool hasDirection = dot(anisoDir, anisoDir) > 0.25f;
    s.anisoDir = hasDirection ? normalize(anisoDir) : RTPBR_F3(0.0f);
    s.anisoK = hasDirection && p.alphas.y > 0.0f ? sqrt(max(p.alphas.x / p.alphas.y, 1.0f)) : 1.0f;
    // In [RTPBR_MATERIAL_MIN_ROUGHNESS, 1] (Material_Resolve): alpha = r^2 without a second clamp.
    float isotropicAlpha = s.tableRoughness * s.tableRoughness;
    s.alphas = s.anisoK > 1.0f ? clamp(p.alphas, RTPBR_F2(RTPBR_MIN_ALPHA), RTPBR_F2(1.0f))
                               : rtpbr_float2(isotropicAlpha, isotropicAlpha);
    s.specularWeight = p.specularWeight;
    s.eta = p.eta;
    s.f0 = p.f0;
    s.f90 = p.f90;
    s.diffuseColor = p.diffuseColor;
    s.coat = p.coat;
    s.coatRoughness = p.coatRoughness;
    s.baseAttenuation = Material_BaseAttenuation(p, NoV);

    rtpbr_float2 eo = Host_TableE_EF(NoV, s.tableRoughness, s.eta);
    s.Eo = eo.x;
    s.Eavg = Host_TableEavg(s.tableRoughness);
#if RTPBR_MULTISCATTER
    s.FmsDielectric = KC_FmsColor(RTPBR_F3(F_Avg_Dielectric(s.eta)), s.Eavg).x;
    s.msColor = s.disney ? KC_FmsColor(F_Avg_Schlick(s.f0, 1.0f), s.Eavg)
                         : s.metallic * KC_FmsColor(F_Avg_Schlick(s.baseColor, 1.0f), s.Eavg) +
                               RTPBR_F3((1.0f - s.metallic) * s.specularWeight * s.FmsDielectric);
#else
    s.FmsDielectric = 0.0f;
    s.msColor = RTPBR_F3(0.0f);
#endif
    // The layered base (metallic-roughness): the specular layer's albedo at mu_o and on average.
    bool layered = !s.disney && s.specularWeight > 0.0f;
    s.EFavg = layered ? Host_TableEFavg(s.tableRoughness, s.eta) : 0.0f;
    s.Eso = layered ? s.specularWeight * KC_SpecularAlbedoDielectric(eo.y, s.Eo, s.FmsDielectric) : 0.0f;
    s.EsAvg = layered ? s.specularWeight * KC_SpecularAlbedoDielectric(s.EFavg, s.Eavg, s.FmsDielectric) : 0.0f;
    bool coated = s.coat > 0.0f;
    s.Eoc = coated ? Host_TableE(NoV, s.coatRoughness) : 1.0f;
    s.Eavgc = coated ? Host_TableEavg(s.coatRoughness) : 1.0f;
#if RTPBR_MULTISCATTER
    s.msCoat = s.coat * KC_FmsColor(F_Avg_Schlick(RTPBR_F3(RTPBR_MATERIAL_COAT_F0), 1.0f), s.Eavgc);
#else
    s.msCoat = RTPBR_F3(0.0f);
#endif
    s.sheenColor = p.sheenColor;
    s.sheenRoughness = p.sheenRoughness;
    s.sheen = max(s.sheenColor.x, max(s.sheenColor.y, s.sheenColor.z)) > 0.0f;
    s.EsheenO = s.sheen ? Host_TableSheenE(NoV, s.sheenRoughness) : 0.0f;
    return s;
}

// The largest channel.
RTPBR_FN float Surface_Max3(rtpbr_float3 v) {
    return max(v.x, max(v.y, v.z));
}

// The BRDF of surface s for one pair of directions (the model above, every lobe), wo and wi
// unit vectors in a local frame: z = the shading normal, x along the anisotropy direction
// (alpha_t) when the lobe is anisotropic (s.anisoK > 1; any tangent otherwise), wo.z = s.NoV.
// What a punctual light (area_light.h) and a Monte Carlo estimator evaluate per direction: the
// multiple-scattering and layered lobes with E and E_F at wi (Host_TableE_EF), the coat's E
// (Host_TableE) and E_sheen (Host_TableSheenE) read where the material needs them. Zero below
// the horizon is the caller's (f is returned as the lobes give it; callers weigh by max(wi.z, 0)).
// full = false: the metallic-roughness lobes alone (no Disney, sheen, coat; the lobes of
// area_light.h's RTPBR_AREA_LIGHT_FULL 0), for surfaces known to have none of them.
RTPBR_FN rtpbr_float3 Surface_EvaluateLobes(ShadingSurface s, rtpbr_float3 wo, rtpbr_float3 wi, bool full) {
    FresnelParams fresnel;
    fresnel.f0 = s.f0;
    fresnel.f90 = s.f90;
    fresnel.eta = RTPBR_F3(s.eta);
    fresnel.k = RTPBR_F3(0.0f);
    bool layered = !(full && s.disney) && s.specularWeight > 0.0f && Surface_Max3(s.diffuseColor) > 0.0f;
    bool needEi = layered || Surface_Max3(s.msColor) > 0.0f;
    float NoL = wi.z;
    rtpbr_float3 h = normalize(wo + wi);
    float NoH = h.z;
    float VoH = dot(wo, h);
    float mu = max(NoL, 0.0f);
    rtpbr_float2 ei = needEi ? Host_TableE_EF(mu, s.tableRoughness, s.eta) : rtpbr_float2(1.0f, 0.0f);
    float Ei = ei.x;
#if RTPBR_KC_SHAPE
    // the shaped multiple-scattering lobe (kulla_conty.h), its single-scattering part from the
    // isotropic lobe at the tables' roughness (as BRDF_SpecularMS); resolved roughness
    // (Material_Resolve): no second clamp
    float alphaIso = s.tableRoughness * s.tableRoughness;
    float fss1 = NoL > 0.0f ? D_Microfacet(NoH, alphaIso) * V_Microfacet(s.NoV, NoL, alphaIso) : 0.0f;
    rtpbr_float3 f = BRDF_SpecularLocal(wo, wi, s.alphas.x, s.alphas.y, fresnel) +
                     s.msColor * KC_LobeShaped(s.Eo, Ei, s.Eavg, fss1, KC_ShapeWeight(s.tableRoughness, s.NoV));
#else
    rtpbr_float3 f = BRDF_SpecularLocal(wo, wi, s.alphas.x, s.alphas.y, fresnel) + s.msColor * KC_Lobe(s.Eo, Ei, s.Eavg);
#endif
    if (full && s.disney) {
        f += BRDF_DisneyDiffuse(s.dm, wo, wi) + BRDF_DisneySheen(s.dm, wo, wi);
    } else {
        float Esi = layered ? s.specularWeight * KC_SpecularAlbedoDielectric(ei.y, Ei, s.FmsDielectric) : 0.0f;
        f += s.diffuseColor * KC_Lobe(s.Eso, Esi, s.EsAvg);
    }
    if (full && s.sheen)
        f = f * Sheen_AlbedoScaling(s.sheenColor, s.EsheenO, Host_TableSheenE(mu, s.sheenRoughness)) +
            BRDF_Sheen(s.sheenColor, s.sheenRoughness, s.NoV, NoL, NoH);
    if (!full) return f;
    f *= s.baseAttenuation;
    if (s.coat > 0.0f) {
        // KHR clearcoat: GGX with Schlick(0.04, 1); Disney's: its GTR1 lobe
        FresnelParams coatFresnel;
        coatFresnel.f0 = RTPBR_F3(RTPBR_MATERIAL_COAT_F0);
        coatFresnel.f90 = 1.0f;
        coatFresnel.eta = RTPBR_F3(1.5f);
        coatFresnel.k = RTPBR_F3(0.0f);
        float coatAlpha = s.coatRoughness * s.coatRoughness; // resolved: no second clamp
        float coatLobe = s.disney ? BRDF_DisneyClearcoat(s.dm, wo, wi)
                                  : s.coat * BRDF_Specular(s.NoV, NoL, NoH, VoH, coatAlpha, coatFresnel).x;
        f += RTPBR_F3(coatLobe) + s.msCoat * KC_Lobe(s.Eoc, Host_TableE(mu, s.coatRoughness), s.Eavgc);
    }
    return f;
}

// Every lobe (Surface_EvaluateLobes with full = true).
RTPBR_FN rtpbr_float3 Surface_Evaluate(ShadingSurface s, rtpbr_float3 wo, rtpbr_float3 wi) {
    return Surface_EvaluateLobes(s, wo, wi, true);
}

RTPBR_NAMESPACE_END

#endif // RTPBR_SURFACE_H
