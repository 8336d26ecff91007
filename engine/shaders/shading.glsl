// What shading a surface point needs, shared by the LTC lighting pass (lighting.comp, through
// lighting_common.glsl), the Monte Carlo pass (lighting_mc.comp) and the forward pass of BLEND
// surfaces (forward.frag): the lights, the materials, the Kulla-Conty and sheen table accessors
// and the per-point material terms (surface_terms), so that every pass shades exactly the same
// model (docs/materials.md, "What each renderer shades"). Bindings of the lighting set's
// numbering (rtpbr_shared.h: RTPBR_BINDING_LIGHT_*, RTPBR_BINDING_LUT_*), which the forward
// pass's set follows.
// Include after rtpbr_shared.h, the shader-library headers (fresnel.h, kulla_conty.h,
// disney.h, sheen.h, material.h), material.glsl and frame.glsl.

#include "light.glsl"
layout(set = 0, binding = RTPBR_BINDING_LIGHT_LIGHTS, std430) readonly buffer Lights {
    Light lights[];
};
layout(set = 0, binding = RTPBR_BINDING_LIGHT_MATERIALS, std430) readonly buffer Materials {
    Material materials[];
};
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_E) uniform sampler2D lut_kc_e;
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_EAVG) uniform sampler2D lut_kc_eavg;
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_EF) uniform sampler3D lut_kc_ef;
layout(set = 0, binding = RTPBR_BINDING_LUT_KC_EFAVG) uniform sampler2D lut_kc_efavg;
layout(set = 0, binding = RTPBR_BINDING_LUT_SHEEN_E) uniform sampler2D lut_sheen_e;

// The Kulla-Conty tables of the NDF this variant is built for (engine/src/luts.c: E and E_avg
// r = GGX, g = Beckmann; the 3D table rgba = E_F GGX, E_F Beckmann, E GGX, E Beckmann).
#if RTPBR_NDF == RTPBR_NDF_BECKMANN
#define KC_CHANNEL g
#define KC_E_EF_CHANNELS ag
#else
#define KC_CHANNEL r
#define KC_E_EF_CHANNELS br
#endif

float kc_E(float mu, float r) { return textureLod(lut_kc_e, KC_TableCoord(mu, r), 0.0f).KC_CHANNEL; }
float kc_Eavg(float r) { return textureLod(lut_kc_eavg, vec2(KC_TableCoordAvg(r), 0.5f), 0.0f).KC_CHANNEL; }
// E(mu, r) and E_F(mu, r, eta) in one trilinear fetch (E is repeated along eta).
vec2 kc_E_EF(float mu, float r, float eta)
{
    return textureLod(lut_kc_ef, KC_TableCoord3D(mu, r, eta), 0.0f).KC_E_EF_CHANNELS;
}
float kc_EFavg(float r, float eta) { return textureLod(lut_kc_efavg, KC_TableCoordAvg2D(r, eta), 0.0f).KC_CHANNEL; }
// KHR sheen's directional albedo (Charlie lobe; shaderlib/luts/sheen.md).
float sheen_E(float mu, float r) { return textureLod(lut_sheen_e, Sheen_TableCoord(mu, r), 0.0f).r; }

// A surface point's material: the G-buffer's per-pixel values and its material record,
// resolved into the terms both passes use. The model (oracle/bsdf.h):
//   metallic-roughness: f = (1 - c Fc(NoV)) [metallic f_metal + (1 - metallic) f_dielectric]
//                           + c f_coat,
//     f_metal = GGX, Schlick(F0 = baseColor, 1) + its Kulla-Conty lobe,
//     f_dielectric = w GGX Schlick(F0(ior) specularColor, 1) + w F_ms f_ms
//                    + baseColor (1 - Es(mu_o)) (1 - Es(mu_i)) / (pi (1 - Es_avg)),
//     Es = w (E_F + F_ms (1 - E)) (KC_SpecularAlbedoDielectric; E_F with exact Fresnel),
//     f_coat = GGX(clearcoat roughness), Schlick(0.04, 1) + its Kulla-Conty lobe;
//     with KHR sheen, the bracket is f_sheen + A [...], f_sheen = sheenColor D_Charlie V
//     (sheen.h), A = min(1 - max(sheenColor) E_sheen(mu_o), 1 - max(sheenColor) E_sheen(mu_i));
//   Disney (Burley 2012, disney.h): specular GGX Schlick(Disney_SpecularF0, 1) + its
//     Kulla-Conty lobe, Burley diffuse + subsurface + sheen, GTR1 clearcoat 0.25 c.
// Anisotropic lobes (alpha_t along the G-buffer's anisotropy direction, alpha_b across it):
// the tables are looked up at sqrt(alpha_t alpha_b); the LTC pass stretches that isotropic
// lobe by k = sqrt(alpha_t / alpha_b) along the direction (LTC_AnisotropicInverseMatrix).
struct Surface {
    bool disney;
    DisneyMaterial dm;    // sanitised (Disney materials only); the material fields up to
                          // baseAttenuation come from material.h's Material_Resolve (NoV and
                          // the anisotropy direction from the G-buffer)
    vec3 baseColor;
    float metallic;
    float roughness;      // perceptual, the G-buffer's
    float NoV;
    float specR;          // perceptual roughness of the specular lobe's tables, sqrt(sqrt(at ab))
    vec3 anisoDir;        // anisotropy direction (world, unit) or 0
    float anisoK;         // sqrt(alpha_t / alpha_b) >= 1; 1: isotropic
    vec2 alphas;          // (alpha_t, alpha_b) of the specular lobe (isotropic: both sqrt(at ab))
    float w;              // dielectric specular weight (KHR specularFactor)
    float eta;            // dielectric IOR
    vec3 f0;              // Schlick F0 and F90 of the specular lobe (metal and dielectric mixed)
    float f90;
    vec3 diffuseColor;    // (1 - metallic) baseColor
    float coat;           // coat weight (Disney: 0.25 clearcoat), 0: none
    float coatR;          // its perceptual roughness (Disney: sqrt of the GTR1 alpha)
    float baseAttenuation; // 1 - c Fc(NoV) for KHR clearcoat; 1 for Disney's
    // Kulla-Conty terms (zero without RTPBR_MULTISCATTER)
    float Eo, Eavg;       // E(NoV), E_avg of the specular lobe
    float FmsDielectric;  // F_ms of the dielectric layer
    vec3 msColor;         // colour of the specular lobe's f_ms
    float EFavg;          // E_F_avg of the dielectric layer
    float Eso, EsAvg;     // the layer's albedo at NoV and on average (w included)
    float Eoc, Eavgc;     // E(NoV), E_avg of the coat
    vec3 msCoat;          // colour of the coat's f_ms (coat weight included)
    bool sheen;           // KHR sheen layer present
    vec3 sheenColor;
    float sheenR;         // its perceptual roughness
    float EsheenO;        // E_sheen(NoV)
};

// A point's extension-texture values: multipliers of the material record's KHR factors (the
// G-buffer's for the lighting passes, lighting_common.glsl; the textures' own in the forward
// pass), 1 where the material has no such texture.
struct ExtensionTexels {
    vec4 specular; // specular colour rgb, specular a
    vec4 sheen;    // sheen colour rgb, sheen roughness a
    vec2 coat;     // clearcoat, clearcoat roughness
};

ExtensionTexels extension_texels_none()
{
    ExtensionTexels e;
    e.specular = vec4(1.0f);
    e.sheen = vec4(1.0f);
    e.coat = vec2(1.0f);
    return e;
}

// RTPBR_LIGHTING_FULL 0 (the basic lighting variant) resolves only what
// material_tile_class calls basic: the Disney, clear-coat, sheen and anisotropy terms become
// compile-time constants and drop out of the shader.
#ifndef RTPBR_LIGHTING_FULL
#define RTPBR_LIGHTING_FULL 1
#endif
// The material record and the G-buffer's per-pixel values as the inputs of the shader
// library's material resolve (material.h), the KHR factors times the point's extension
// textures. The basic variant's inputs have no coat, sheen,
// anisotropy or Disney model.
MaterialInputs material_inputs(vec4 g0, float roughness, Material m, ExtensionTexels e)
{
    MaterialInputs in_;
    in_.model = (m.flags & RTPBR_MATERIAL_FLAG_DISNEY) != 0u ? RTPBR_MATERIAL_MODEL_DISNEY
                                                             : RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    in_.baseColor = g0.rgb;
    in_.metallic = g0.a;
    in_.roughness = roughness;
    in_.ior = m.ior;
    in_.specularFactor = m.specular_factor * e.specular.a;
    in_.specularColor = m.specular_color * e.specular.rgb;
    in_.clearcoat = m.clearcoat * e.coat.x;
    in_.clearcoatRoughness = m.clearcoat_roughness * e.coat.y;
    in_.sheenColor = m.sheen_color * e.sheen.rgb;
    in_.sheenRoughness = m.sheen_roughness * e.sheen.a;
    in_.anisotropyStrength = m.anisotropy_strength;
    in_.disney.baseColor = g0.rgb;
    in_.disney.metallic = g0.a;
    in_.disney.roughness = roughness;
    in_.disney.subsurface = m.disney_subsurface;
    in_.disney.specular = m.disney_specular;
    in_.disney.specularTint = m.disney_specular_tint;
    in_.disney.anisotropic = m.disney_anisotropic;
    in_.disney.sheen = m.disney_sheen;
    in_.disney.sheenTint = m.disney_sheen_tint;
    in_.disney.clearcoat = m.disney_clearcoat;
    in_.disney.clearcoatGloss = m.disney_clearcoat_gloss;
#if !RTPBR_LIGHTING_FULL
    in_.model = RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    in_.clearcoat = 0.0f;
    in_.sheenColor = vec3(0.0f);
    in_.anisotropyStrength = 0.0f;
#endif
    return in_;
}

Surface surface_terms(vec4 g0, float roughness, Material m, ExtensionTexels e, float NoV, vec3 anisoDir)
{
#if !RTPBR_LIGHTING_FULL
    anisoDir = vec3(0.0f);
#endif
    MaterialParams p = Material_Resolve(material_inputs(g0, roughness, m, e));
    Surface s;
    s.disney = p.disney;
    s.dm = p.dm;
    s.baseColor = p.baseColor;
    s.metallic = p.metallic;
    s.roughness = p.roughness;
    s.NoV = NoV;
    s.specR = p.tableRoughness;
    // Anisotropic lobes: alpha_t along the G-buffer's direction; without one, isotropic.
    bool hasDirection = dot(anisoDir, anisoDir) > 0.25f;
    s.anisoDir = hasDirection ? normalize(anisoDir) : vec3(0.0f);
    s.anisoK = hasDirection && p.alphas.y > 0.0f ? sqrt(max(p.alphas.x / p.alphas.y, 1.0f)) : 1.0f;
    float isotropicAlpha = Alpha_FromPerceptual(s.specR);
    s.alphas = s.anisoK > 1.0f ? clamp(p.alphas, RTPBR_F2(RTPBR_MIN_ALPHA), RTPBR_F2(1.0f))
                               : vec2(isotropicAlpha, isotropicAlpha);
    s.w = p.specularWeight;
    s.eta = p.eta;
    s.f0 = p.f0;
    s.f90 = p.f90;
    s.diffuseColor = p.diffuseColor;
    s.coat = p.coat;
    s.coatR = p.coatRoughness;
    s.baseAttenuation = Material_BaseAttenuation(p, NoV);

    vec2 eo = kc_E_EF(NoV, s.specR, s.eta);
    s.Eo = eo.x;
    s.Eavg = kc_Eavg(s.specR);
#if RTPBR_MULTISCATTER
    s.FmsDielectric = KC_FmsColor(RTPBR_F3(F_Avg_Dielectric(s.eta)), s.Eavg).x;
    s.msColor = s.disney ? KC_FmsColor(F_Avg_Schlick(s.f0, 1.0f), s.Eavg)
                         : s.metallic * KC_FmsColor(F_Avg_Schlick(s.baseColor, 1.0f), s.Eavg) +
                               RTPBR_F3((1.0f - s.metallic) * s.w * s.FmsDielectric);
#else
    s.FmsDielectric = 0.0f;
    s.msColor = RTPBR_F3(0.0f);
#endif
    // The layered base (metallic-roughness): the specular layer's albedo at mu_o and on average.
    bool layered = !s.disney && s.w > 0.0f;
    s.EFavg = layered ? kc_EFavg(s.specR, s.eta) : 0.0f;
    s.Eso = layered ? s.w * KC_SpecularAlbedoDielectric(eo.y, s.Eo, s.FmsDielectric) : 0.0f;
    s.EsAvg = layered ? s.w * KC_SpecularAlbedoDielectric(s.EFavg, s.Eavg, s.FmsDielectric) : 0.0f;
    bool coated = s.coat > 0.0f;
    s.Eoc = coated ? kc_E(NoV, s.coatR) : 1.0f;
    s.Eavgc = coated ? kc_Eavg(s.coatR) : 1.0f;
#if RTPBR_MULTISCATTER
    s.msCoat = s.coat * KC_FmsColor(F_Avg_Schlick(RTPBR_F3(RTPBR_MATERIAL_COAT_F0), 1.0f), s.Eavgc);
#else
    s.msCoat = RTPBR_F3(0.0f);
#endif
    s.sheenColor = p.sheenColor;
    s.sheenR = p.sheenRoughness;
    s.sheen = max(s.sheenColor.r, max(s.sheenColor.g, s.sheenColor.b)) > 0.0f;
    s.EsheenO = s.sheen ? sheen_E(NoV, s.sheenR) : 0.0f;
    return s;
}

