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

// The surface terms (ShadingSurface, Surface_Resolve) are the shader library's
// (shaderlib/rtpbr/surface.h), which reads its tables through these (its host bridge).
vec2 Host_TableE_EF(float mu, float r, float eta) { return kc_E_EF(mu, r, eta); }
float Host_TableE(float mu, float r) { return kc_E(mu, r); }
float Host_TableEavg(float r) { return kc_Eavg(r); }
float Host_TableEFavg(float r, float eta) { return kc_EFavg(r, eta); }
float Host_TableSheenE(float mu, float r) { return sheen_E(mu, r); }
#include "rtpbr/surface.h"
#include "rtpbr/gbuffer.h" // the G-buffer contract: GBufferSurface

// RTPBR_LIGHTING_FULL 0 (the basic lighting variant) resolves only what
// material_tile_class calls basic: the Disney, clear-coat, sheen and anisotropy terms become
// compile-time constants and drop out of the shader.
#ifndef RTPBR_LIGHTING_FULL
#define RTPBR_LIGHTING_FULL 1
#endif
// The material record and a point's values (the G-buffer's, gbuffer.h's GBufferSurface; the
// forward pass's own) as the inputs of the shader library's material resolve (material.h), the
// KHR factors times the point's extension texels. The basic variant's inputs have no coat,
// sheen, anisotropy or Disney model.
// The full variant's material features as its pipeline was specialized for
// (RTPBR_SPEC_LIGHTING_MATERIALS: the RTPBR_MATERIAL_FLAGS_FULL bits that some material of the
// frame has, all of them by default): a feature no material has is a compile-time zero, and its
// lobe's walk drops out (on lavapipe it costs every pixel whether any has the feature or not).
layout(constant_id = RTPBR_SPEC_LIGHTING_MATERIALS) const uint shade_material_features = RTPBR_MATERIAL_FLAGS_FULL;
MaterialInputs material_inputs(GBufferSurface g, Material m)
{
    MaterialInputs in_;
    in_.model = (m.flags & RTPBR_MATERIAL_FLAG_DISNEY) != 0u ? RTPBR_MATERIAL_MODEL_DISNEY
                                                             : RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    in_.baseColor = g.baseColor;
    in_.metallic = g.metallic;
    in_.roughness = g.roughness;
    in_.ior = m.ior;
    in_.specularFactor = m.specular_factor * g.specular.a;
    in_.specularColor = m.specular_color * g.specular.rgb;
    in_.clearcoatFactor = m.clearcoat_factor * g.coat.x;
    in_.clearcoatRoughness = m.clearcoat_roughness_factor * g.coat.y;
    in_.sheenColorFactor = m.sheen_color_factor * g.sheen.rgb;
    in_.sheenRoughness = m.sheen_roughness_factor * g.sheen.a;
    in_.anisotropyStrength = m.anisotropy_strength;
    in_.disney.baseColor = g.baseColor;
    in_.disney.metallic = g.metallic;
    in_.disney.roughness = g.roughness;
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
    in_.clearcoatFactor = 0.0f;
    in_.sheenColorFactor = vec3(0.0f);
    in_.anisotropyStrength = 0.0f;
#else
    if ((shade_material_features & RTPBR_MATERIAL_FLAG_DISNEY) == 0u) in_.model = RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    if ((shade_material_features & RTPBR_MATERIAL_FLAG_CLEARCOAT) == 0u) in_.clearcoatFactor = 0.0f;
    if ((shade_material_features & RTPBR_MATERIAL_FLAG_SHEEN) == 0u) in_.sheenColorFactor = vec3(0.0f);
    if ((shade_material_features & RTPBR_MATERIAL_FLAG_ANISOTROPY) == 0u) in_.anisotropyStrength = 0.0f;
#endif
    return in_;
}

// The point's surface terms (surface.h): the material record and the point's values resolved
// (material.h), seen at NoV.
ShadingSurface surface_terms(GBufferSurface g, Material m, float NoV)
{
#if !RTPBR_LIGHTING_FULL
    g.anisotropyDirection = vec3(0.0f);
#endif
    return Surface_Resolve(Material_Resolve(material_inputs(g, m)), NoV, g.anisotropyDirection);
}
