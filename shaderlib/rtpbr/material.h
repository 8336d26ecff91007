// rtpbr shader library: the material resolve. One function turns a material's inputs (glTF
// metallic-roughness with KHR_materials_ior, _specular, _clearcoat, _sheen and _anisotropy, or
// Burley's Disney parameters) into what the lobes of the other headers take: alphas, F0, F90,
// the dielectric IOR, the coat and sheen layers and the diffuse colour. Every renderer that
// shades these materials (the engine's G-buffer and lighting passes, the oracle) calls it, so
// that they read a material the same way; the rules live here and nowhere else.
//
// The rules (each one, once):
//   roughness   perceptual roughness r is clamped to [RTPBR_MATERIAL_MIN_ROUGHNESS, 1] (NaN:
//               the floor), alpha = r^2, for the base lobe and the KHR coat alike: once, here
//               (the roughnesses derived from alphas, tableRoughness and Disney's coat, are
//               floored once where derived); surface.h and area_light.h square them as they
//               are. docs/materials.md lists the clamps hop by hop. The floor is
//               Filament's (0.045, alpha ~0.002: alpha^2 stays a normal float, and the LTC and
//               Kulla-Conty tables start there). RTPBR_MIN_ALPHA (config.h) is the NDFs' own
//               numerical guard below it, not a material rule.
//   ior         KHR_materials_ior: ior >= 1 is the dielectric's IOR; ior = 0 is the spec's
//               specular-glossiness mode, "the effective IOR becomes positive infinity and the
//               Fresnel term MUST evaluate to 1.0": F0 = 1 exactly (the spec's own
//               ((ior - 1) / (ior + 1))^2 at 0) and eta = RTPBR_MATERIAL_ETA_INFINITE for
//               exact-Fresnel consumers. Anything else (negative, (0, 1), NaN) is invalid and
//               reads as the glTF default 1.5.
//   specular    KHR_materials_specular: dielectric F0 = min(F0(ior) specularColor, 1)
//               specularFactor, F90 = specularFactor; metals F0 = baseColor, F90 = 1, mixed
//               by metallic (glTF 2.0 appendix B, fresnel_mix).
//   clearcoat   KHR_materials_clearcoat: clearcoatRoughness is perceptual roughness (glTF's
//               convention, the one every rtpbr struct stores); F0 0.04, F90 1 (ior 1.5); the
//               coat attenuates what lies below by 1 - c Fc(NoV) (Material_BaseAttenuation).
//               Disney's clearcoatGloss is turned into a coat here only: GTR1 alpha
//               mix(0.1, 0.001, gloss), weight 0.25 clearcoat, no attenuation (Burley 2012).
//   anisotropy  KHR_materials_anisotropy: alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha;
//               Disney: Burley's aspect sqrt(1 - 0.9 anisotropic) (Disney_SpecularAlphas).
//   sheen       KHR_materials_sheen: colour clamped to [0, 1], perceptual roughness to [0, 1]
//               (sheen.h squares it); Disney's sheen stays in its DisneyMaterial.
// Every output is finite for any input (NaN and infinities are clamped like
// Disney_SanitizeMaterial: NaN -> the lower end).
#ifndef RTPBR_MATERIAL_H
#define RTPBR_MATERIAL_H

#include "lang.h"
#include "config.h"
#include "fresnel.h"
#include "ndf.h"
#include "disney.h"

RTPBR_NAMESPACE_BEGIN

// Filament (google/filament, shading_parameters: MIN_PERCEPTUAL_ROUGHNESS): the lower clamp of
// perceptual roughness.
RTPBR_CONST float RTPBR_MATERIAL_MIN_ROUGHNESS = 0.045f;
// KHR_materials_ior: the IOR of the ior = 0 mode ("positive infinity, subject to numerical
// precision"): F0 = 1 - 4e-6; F_Dielectric clamps it further to 1e3 (F0 0.996).
RTPBR_CONST float RTPBR_MATERIAL_ETA_INFINITE = 1e6f;
// glTF 2.0: the dielectric default IOR (F0 = 0.04).
RTPBR_CONST float RTPBR_MATERIAL_DEFAULT_IOR = 1.5f;
// KHR_materials_clearcoat: the coat's F0 (ior 1.5) and F90.
RTPBR_CONST float RTPBR_MATERIAL_COAT_F0 = 0.04f;

// The material models (values of MaterialInputs.model).
RTPBR_CONST int RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS = 0;
RTPBR_CONST int RTPBR_MATERIAL_MODEL_DISNEY = 1;

// A material's parameters at a surface point, textures applied (factor x texel).
struct MaterialInputs {
    int model;                  // RTPBR_MATERIAL_MODEL_*
    rtpbr_float3 baseColor;     // linear RGB
    float metallic;
    float roughness;            // perceptual
    float ior;                  // KHR_materials_ior (0: F = 1 everywhere)
    float specularFactor;       // KHR_materials_specular
    rtpbr_float3 specularColor; // KHR_materials_specular (may exceed 1)
    float clearcoatFactor;      // KHR_materials_clearcoat clearcoatFactor
    float clearcoatRoughness;   // KHR_materials_clearcoat clearcoatRoughnessFactor (perceptual)
    rtpbr_float3 sheenColorFactor; // KHR_materials_sheen sheenColorFactor
    float sheenRoughness;       // KHR_materials_sheen sheenRoughnessFactor (perceptual)
    float anisotropyStrength;   // KHR_materials_anisotropy
    // Disney (model RTPBR_MATERIAL_MODEL_DISNEY): its baseColor, metallic and roughness are
    // ignored (the fields above are used); the KHR fields above are ignored.
    DisneyMaterial disney;
};

// What the lobes need, resolved once per shading point.
struct MaterialParams {
    bool disney;                // Burley's model: dm holds it (sanitised, roughness floored)
    DisneyMaterial dm;
    rtpbr_float3 baseColor;     // [0, 1]
    float metallic;             // [0, 1]
    float roughness;            // perceptual, [RTPBR_MATERIAL_MIN_ROUGHNESS, 1]
    rtpbr_float2 alphas;        // (alpha_t along the anisotropy direction, alpha_b across it)
    float tableRoughness;       // sqrt(sqrt(alpha_t alpha_b)), floored again (rounding; Disney's
                                //   alpha split): isotropic table lookups, alpha = its square
    float specularWeight;       // KHR specularFactor in [0, 1] (Disney: 1)
    float eta;                  // dielectric IOR >= 1 (exact Fresnel, the E_F tables)
    rtpbr_float3 f0;            // Schlick F0 and F90 of the specular lobe (metal and dielectric
    float f90;                  //   mixed by metallic; Disney: Disney_SpecularF0, 1)
    rtpbr_float3 diffuseColor;  // (1 - metallic) baseColor
    float coat;                 // coat weight (KHR: clearcoat; Disney: 0.25 clearcoat); 0: none
    float coatAlpha;            // KHR: the coat's GGX alpha; Disney: the GTR1 alpha
    float coatRoughness;        // perceptual roughness of the coat's isotropic tables
    bool coatAttenuates;        // KHR: the coat attenuates the base by 1 - c Fc(NoV); Disney: no
    rtpbr_float3 sheenColor;    // KHR sheen, [0, 1]; 0: no sheen layer
    float sheenRoughness;       // perceptual, [0, 1]
};

// NaN-safe clamp to [lo, hi]: NaN gives lo.
RTPBR_FN float Material_Clamp(float x, float lo, float hi) { return x > lo ? min(x, hi) : lo; }

RTPBR_FN rtpbr_float3 Material_Clamp3(rtpbr_float3 v, float lo, float hi) {
    return rtpbr_float3(Material_Clamp(v.x, lo, hi), Material_Clamp(v.y, lo, hi), Material_Clamp(v.z, lo, hi));
}

// The one roughness floor: perceptual roughness clamped to [RTPBR_MATERIAL_MIN_ROUGHNESS, 1].
RTPBR_FN float Material_PerceptualRoughness(float roughness) {
    return Material_Clamp(roughness, RTPBR_MATERIAL_MIN_ROUGHNESS, 1.0f);
}

// KHR_materials_ior: the dielectric's IOR for exact-Fresnel consumers (header comment).
RTPBR_FN float Material_DielectricEta(float ior) {
    if (ior == 0.0f)
        return RTPBR_MATERIAL_ETA_INFINITE;
    return ior >= 1.0f ? min(ior, RTPBR_MATERIAL_ETA_INFINITE) : RTPBR_MATERIAL_DEFAULT_IOR;
}

// KHR_materials_ior: f0 = ((ior - 1) / (ior + 1))^2, exactly 1 for ior = 0.
RTPBR_FN float Material_DielectricF0(float ior) {
    return ior == 0.0f ? 1.0f : F0_FromIor(Material_DielectricEta(ior));
}

// Burley 2012 (disney.h): the inputs' Disney parameters with the shared base colour, metallic
// and roughness (floored), sanitised. Any input; Material_Resolve builds the same from its
// already clamped base colour, metallic and roughness (each clamped once there).
RTPBR_FN DisneyMaterial Material_DisneyParams(MaterialInputs m) {
    DisneyMaterial d = m.disney;
    d.baseColor = m.baseColor;
    d.metallic = m.metallic;
    d.roughness = Material_PerceptualRoughness(m.roughness);
    return Disney_SanitizeMaterial(d);
}

RTPBR_FN MaterialParams Material_Resolve(MaterialInputs m) {
    MaterialParams p;
    p.disney = m.model == RTPBR_MATERIAL_MODEL_DISNEY;
    // The library's one roughness clamp (and base colour's, metallic's) on the way in.
    p.baseColor = Material_Clamp3(m.baseColor, 0.0f, 1.0f);
    p.metallic = Material_Clamp(m.metallic, 0.0f, 1.0f);
    p.roughness = Material_PerceptualRoughness(m.roughness);
    // Material_DisneyParams without clamping the shared three again: Burley's own parameters
    // sanitised (Disney_SanitizeMaterial's clamps of the three are overwritten, so dropped).
    p.dm = Disney_SanitizeMaterial(m.disney);
    p.dm.baseColor = p.baseColor;
    p.dm.metallic = p.metallic;
    p.dm.roughness = p.roughness;
    float alpha = p.roughness * p.roughness;

    // KHR_materials_anisotropy: alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha.
    float strength = Material_Clamp(m.anisotropyStrength, 0.0f, 1.0f);
    rtpbr_float2 khrAlphas = rtpbr_float2(rtpbr_lerp(alpha, 1.0f, strength * strength), alpha);
    p.alphas = p.disney ? Disney_SpecularAlphas(p.dm) : khrAlphas;
    p.tableRoughness = Material_PerceptualRoughness(sqrt(sqrt(p.alphas.x * p.alphas.y)));

    // KHR_materials_ior and KHR_materials_specular (glTF 2.0 appendix B, fresnel_mix).
    p.specularWeight = p.disney ? 1.0f : Material_Clamp(m.specularFactor, 0.0f, 1.0f);
    p.eta = Material_DielectricEta(m.ior);
    rtpbr_float3 specularColor = Material_Clamp3(m.specularColor, 0.0f, RTPBR_FLT_MAX);
    rtpbr_float3 f0Dielectric = min(Material_DielectricF0(m.ior) * specularColor, RTPBR_F3(1.0f));
    // The metallic blends as sums of non-negative terms (no cancellation: every language's
    // build rounds alike).
    rtpbr_float3 f0 = ((1.0f - p.metallic) * p.specularWeight) * f0Dielectric + p.metallic * p.baseColor;
    p.f0 = p.disney ? Disney_SpecularF0(p.dm) : f0;
    p.f90 = p.disney ? 1.0f : (1.0f - p.metallic) * p.specularWeight + p.metallic;
    p.diffuseColor = (1.0f - p.metallic) * p.baseColor;

    // The coat: KHR_materials_clearcoat, or Disney's GTR1 coat (Burley 2012, sec. 5.4).
    float khrCoatRoughness = Material_PerceptualRoughness(m.clearcoatRoughness);
    float disneyCoatAlpha = Disney_ClearcoatAlpha(p.dm);
    p.coat = p.disney ? RTPBR_DISNEY_CLEARCOAT_SCALE * p.dm.clearcoat : Material_Clamp(m.clearcoatFactor, 0.0f, 1.0f);
    p.coatAlpha = p.disney ? disneyCoatAlpha : khrCoatRoughness * khrCoatRoughness;
    p.coatRoughness = p.disney ? Material_PerceptualRoughness(sqrt(disneyCoatAlpha)) : khrCoatRoughness;
    p.coatAttenuates = !p.disney;

    // KHR_materials_sheen (Disney's sheen is part of dm).
    p.sheenColor = p.disney ? RTPBR_F3(0.0f) : Material_Clamp3(m.sheenColorFactor, 0.0f, 1.0f);
    p.sheenRoughness = Material_Clamp(m.sheenRoughness, 0.0f, 1.0f);
    return p;
}

// KHR_materials_clearcoat: the factor 1 - c Fc(NoV) of everything below the coat (Fc Schlick
// with F0 0.04, F90 1); 1 without a coat and for Disney's coat, which does not attenuate.
// Written without cancellation where it nears 0 (c = 1, grazing): with x = 1 - NoV,
// 1 - c Fc = (1 - c) + c (1 - F0) (1 - x^5) and 1 - x^5 = NoV (1 + x + x^2 + x^3 + x^4).
RTPBR_FN float Material_BaseAttenuation(MaterialParams p, float NoV) {
    float mu = rtpbr_saturate(NoV);
    float x = 1.0f - mu;
    float oneMinusX5 = mu * (1.0f + x * (1.0f + x * (1.0f + x * (1.0f + x))));
    float attenuation = (1.0f - p.coat) + p.coat * (1.0f - RTPBR_MATERIAL_COAT_F0) * oneMinusX5;
    return p.coatAttenuates ? attenuation : 1.0f;
}

RTPBR_NAMESPACE_END

#endif // RTPBR_MATERIAL_H
