// Unit checks of shaderlib/rtpbr/material.h's rules (suite 'unit') against values computed
// here independently: Fresnel's normal-incidence reflectance, the KHR_materials_specular and
// _anisotropy formulas, Burley 2012's Disney mappings, the roughness floor and ior 0.
// (tests/shaderlib/gpu checks that the GLSL and HLSL builds of the resolve agree with this C++
// build on ordinary and hostile inputs.)
#include <cstdarg>
#include <cstddef>
#include <csetjmp>
#include <cstdint>

extern "C" {
#include "test_main.h"
}

#include <rtpbr/material.h>

#if defined(RTPBR_TEST_HAVE_ENGINE_HEADER)
#include <rtpbr/rtpbr.h>
// The public constant mirrors the one the resolve applies.
static_assert(RTPBR_MIN_ROUGHNESS == rtpbr::RTPBR_MATERIAL_MIN_ROUGHNESS,
              "rtpbr.h's RTPBR_MIN_ROUGHNESS is material.h's floor");
#endif

#include <cmath>
#include <initializer_list>
#include <limits>

using namespace rtpbr;

namespace {

void near(double got, double want, double tol, const char *what) {
    if (!(std::fabs(got - want) <= tol)) {
        fail_msg("%s: got %.9g, want %.9g (tolerance %g)", what, got, want, tol);
    }
}

MaterialInputs plastic() {
    MaterialInputs m;
    m.model = RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    m.baseColor = float3(0.8f, 0.4f, 0.2f);
    m.metallic = 0.0f;
    m.roughness = 0.5f;
    m.ior = 1.5f;
    m.specularFactor = 1.0f;
    m.specularColor = float3(1.0f);
    m.clearcoatFactor = 0.0f;
    m.clearcoatRoughness = 0.0f;
    m.sheenColorFactor = float3(0.0f);
    m.sheenRoughness = 0.0f;
    m.anisotropyStrength = 0.0f;
    m.disney = Disney_DefaultMaterial();
    return m;
}

// Normal-incidence reflectance of a dielectric from Fresnel's equations (Born & Wolf 1.5.2):
// r_s = r_p = (1 - n) / (1 + n) at theta = 0, R = r^2, in double precision.
double fresnel_normal(double n) {
    double r = (1.0 - n) / (1.0 + n);
    return r * r;
}

void test_f0_from_ior(void **) {
    const float iors[] = {1.0f, 1.33f, 1.5f, 1.76f, 2.42f, 3.0f};
    for (float ior : iors) {
        MaterialInputs m = plastic();
        m.ior = ior;
        MaterialParams p = Material_Resolve(m);
        near(p.f0.x, fresnel_normal(ior), 1e-6, "f0 of a dielectric");
        near(p.f0.z, fresnel_normal(ior), 1e-6, "f0 of a dielectric (blue)");
        near(p.f90, 1.0, 1e-7, "f90 of a dielectric");
        near(p.eta, ior, 1e-7, "eta");
    }
    near(Material_Resolve(plastic()).f0.y, 0.04, 1e-7, "ior 1.5: F0 = 0.04 (glTF 2.0)");
}

// KHR_materials_ior, "Specular-Glossiness Backwards Compatibility Mode": ior 0 means an
// infinite IOR, Fresnel 1 at every angle.
void test_ior_zero(void **) {
    MaterialInputs m = plastic();
    m.ior = 0.0f;
    MaterialParams p = Material_Resolve(m);
    near(p.f0.x, 1.0, 1e-7, "ior 0: F0 = 1");
    near(p.f90, 1.0, 1e-7, "ior 0: F90 = 1");
    for (float c : {0.0f, 0.3f, 1.0f})
        near(F_Schlick(p.f0, p.f90, c).y, 1.0, 1e-7, "ior 0: Schlick Fresnel = 1");
    if (!(p.eta >= 1e5f)) fail_msg("ior 0: eta %g is not effectively infinite", double(p.eta));
    // Exact-Fresnel consumers (the oracle): F_Dielectric clamps eta to 1e3, F0 = 0.996; it dips
    // to 0.96 at grazing cosine 0.05.
    for (float c : {0.5f, 1.0f})
        near(F_Dielectric(c, p.eta), 1.0, 5e-3, "ior 0: exact dielectric Fresnel ~ 1");
    // Invalid values read as glTF's default 1.5.
    for (float ior : {-2.0f, 0.5f, std::numeric_limits<float>::quiet_NaN()}) {
        m.ior = ior;
        near(Material_Resolve(m).eta, 1.5, 1e-7, "invalid ior: 1.5");
    }
}

// KHR_materials_specular: dielectric_f0 = min(F0(ior) specularColor, 1) specularFactor,
// dielectric_f90 = specularFactor; fresnel_mix with metallic: f0 = mix(dielectric_f0, base,
// metallic), f90 = mix(specularFactor, 1, metallic).
void test_khr_specular(void **) {
    MaterialInputs m = plastic();
    m.specularFactor = 0.5f;
    m.specularColor = float3(2.0f, 1.0f, 40.0f);
    MaterialParams p = Material_Resolve(m);
    near(p.f0.x, 0.04 * 2.0 * 0.5, 1e-7, "f0 red");
    near(p.f0.y, 0.04 * 0.5, 1e-7, "f0 green");
    near(p.f0.z, 1.0 * 0.5, 1e-7, "f0 blue clamped to 1 before the factor");
    near(p.f90, 0.5, 1e-7, "f90 = specularFactor");
    near(p.specularWeight, 0.5, 1e-7, "specular weight");
    m.metallic = 0.25f;
    p = Material_Resolve(m);
    near(p.f0.x, 0.75 * 0.04 + 0.25 * 0.8, 1e-7, "f0 mixed by metallic");
    near(p.f90, 0.75 * 0.5 + 0.25, 1e-7, "f90 mixed by metallic");
    near(p.diffuseColor.x, 0.75 * 0.8, 1e-7, "diffuse colour (1 - metallic) base");
}

void test_roughness_floor(void **) {
    near(RTPBR_MATERIAL_MIN_ROUGHNESS, 0.045, 1e-8, "Filament's floor");
    const float zero = 0.0f, nan = std::numeric_limits<float>::quiet_NaN();
    near(Material_PerceptualRoughness(zero), 0.045, 1e-8, "roughness 0");
    near(Material_PerceptualRoughness(-1.0f), 0.045, 1e-8, "negative roughness");
    near(Material_PerceptualRoughness(nan), 0.045, 1e-8, "NaN roughness");
    near(Material_PerceptualRoughness(7.0f), 1.0, 1e-7, "roughness above 1");
    near(Material_PerceptualRoughness(0.3f), 0.3, 1e-7, "roughness kept");
    MaterialInputs m = plastic();
    m.roughness = 0.0f;
    m.clearcoatFactor = 1.0f;
    m.clearcoatRoughness = 0.0f;
    MaterialParams p = Material_Resolve(m);
    near(p.alphas.x, 0.045 * 0.045, 1e-8, "alpha at the floor");
    near(p.coatAlpha, 0.045 * 0.045, 1e-8, "coat alpha at the same floor");
    near(p.tableRoughness, 0.045, 1e-7, "table roughness at the floor");
    m.model = RTPBR_MATERIAL_MODEL_DISNEY;
    m.disney.anisotropic = 0.0f;
    p = Material_Resolve(m);
    near(p.dm.roughness, 0.045, 1e-8, "Disney roughness at the same floor");
}

// KHR_materials_anisotropy: alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha.
void test_khr_anisotropy(void **) {
    MaterialInputs m = plastic();
    m.anisotropyStrength = 0.5f;
    MaterialParams p = Material_Resolve(m);
    near(p.alphas.x, 0.25 + 0.75 * 0.25, 1e-7, "alpha_t");
    near(p.alphas.y, 0.25, 1e-7, "alpha_b");
    near(p.tableRoughness, std::pow(0.4375 * 0.25, 0.25), 1e-6, "table roughness sqrt(sqrt(at ab))");
}

// KHR_materials_clearcoat: perceptual clearcoatRoughness, alpha = r^2; the base is attenuated
// by 1 - c Schlick(0.04, 1, NoV).
void test_khr_clearcoat(void **) {
    MaterialInputs m = plastic();
    m.clearcoatFactor = 0.6f;
    m.clearcoatRoughness = 0.3f;
    MaterialParams p = Material_Resolve(m);
    near(p.coat, 0.6, 1e-7, "coat weight");
    near(p.coatRoughness, 0.3, 1e-7, "coat roughness as stored");
    near(p.coatAlpha, 0.09, 1e-8, "coat alpha = r^2");
    near(Material_BaseAttenuation(p, 1.0f), 1.0 - 0.6 * 0.04, 1e-7, "attenuation at normal incidence");
    near(Material_BaseAttenuation(p, 0.0f), 1.0 - 0.6, 1e-7, "attenuation at grazing incidence");
    near(Material_BaseAttenuation(p, 0.5f), 1.0 - 0.6 * (0.04 + 0.96 * std::pow(0.5, 5.0)), 1e-7,
         "attenuation at NoV 0.5");
}

// KHR_materials_sheen: colour and roughness clamped to [0, 1].
void test_khr_sheen(void **) {
    MaterialInputs m = plastic();
    m.sheenColorFactor = float3(0.5f, 2.0f, -1.0f);
    m.sheenRoughness = 0.7f;
    MaterialParams p = Material_Resolve(m);
    near(p.sheenColor.x, 0.5, 1e-7, "sheen colour");
    near(p.sheenColor.y, 1.0, 1e-7, "sheen colour clamped");
    near(p.sheenColor.z, 0.0, 1e-7, "sheen colour clamped at 0");
    near(p.sheenRoughness, 0.7, 1e-7, "sheen roughness");
}

// Burley 2012, sec. 5.2-5.4 and the BRDF Explorer's disney.brdf: aspect = sqrt(1 - 0.9
// anisotropic), alpha_x = r^2 / aspect, alpha_y = r^2 aspect; clearcoat GTR1 alpha =
// mix(0.1, 0.001, gloss), weight 0.25 clearcoat, no attenuation of the base; dielectric
// F0 = 0.08 specular mix(1, tint colour, specularTint), metals the base colour.
void test_disney(void **) {
    MaterialInputs m = plastic();
    m.model = RTPBR_MATERIAL_MODEL_DISNEY;
    m.disney.anisotropic = 0.8f;
    m.disney.clearcoat = 0.4f;
    m.disney.clearcoatGloss = 0.3f;
    m.disney.specular = 0.5f;
    m.disney.specularTint = 0.0f;
    MaterialParams p = Material_Resolve(m);
    double aspect = std::sqrt(1.0 - 0.9 * 0.8);
    if (!p.disney) fail_msg("Disney model not resolved as Disney");
    near(p.alphas.x, 0.25 / aspect, 1e-6, "Disney alpha_x");
    near(p.alphas.y, 0.25 * aspect, 1e-6, "Disney alpha_y");
    near(p.coat, 0.25 * 0.4, 1e-7, "Disney coat weight");
    near(p.coatAlpha, 0.1 * 0.7 + 0.001 * 0.3, 1e-7, "Disney GTR1 alpha");
    near(p.coatRoughness, std::sqrt(0.1 * 0.7 + 0.001 * 0.3), 1e-6, "Disney coat table roughness");
    near(Material_BaseAttenuation(p, 0.2f), 1.0, 1e-7, "Disney's coat does not attenuate");
    near(p.f0.x, 0.04, 1e-7, "Disney F0 = 0.08 specular");
    near(p.sheenColor.x + p.sheenColor.y + p.sheenColor.z, 0.0, 1e-7, "no KHR sheen for Disney");
    m.metallic = 1.0f;
    p = Material_Resolve(m);
    near(p.f0.y, 0.4, 1e-7, "Disney metal F0 = base colour");
    // KHR fields are ignored by the Disney model and vice versa.
    m.clearcoatFactor = 1.0f;
    m.sheenColorFactor = float3(1.0f);
    near(Material_Resolve(m).coat, 0.1, 1e-7, "KHR clearcoat ignored by Disney");
    MaterialInputs k = plastic();
    k.disney.clearcoat = 1.0f;
    near(Material_Resolve(k).coat, 0.0, 1e-7, "Disney clearcoat ignored by metallic-roughness");
}

// Hostile inputs: every output finite, the ranges kept.
void test_hostile(void **) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    for (int model = 0; model < 2; ++model)
        for (float h : {0.0f, -3.0f, 1e30f, nan, inf, -inf}) {
            MaterialInputs m;
            m.model = model;
            m.baseColor = float3(h);
            m.metallic = m.roughness = m.ior = m.specularFactor = m.clearcoatFactor = m.clearcoatRoughness = h;
            m.sheenRoughness = m.anisotropyStrength = h;
            m.specularColor = m.sheenColorFactor = float3(h);
            m.disney = Disney_DefaultMaterial();
            m.disney.subsurface = m.disney.specular = m.disney.specularTint = m.disney.anisotropic = h;
            m.disney.sheen = m.disney.sheenTint = m.disney.clearcoat = m.disney.clearcoatGloss = h;
            MaterialParams p = Material_Resolve(m);
            const float out[] = {p.alphas.x, p.alphas.y, p.tableRoughness, p.roughness, p.specularWeight, p.eta,
                                 p.f0.x, p.f90, p.diffuseColor.x, p.coat, p.coatAlpha, p.coatRoughness,
                                 p.sheenColor.x, p.sheenRoughness, Material_BaseAttenuation(p, 0.5f)};
            for (float v : out)
                if (!std::isfinite(v) || v < 0.0f)
                    fail_msg("model %d, input %g: an output is %g", model, double(h), double(v));
            if (!(p.roughness >= 0.045f && p.roughness <= 1.0f)) fail_msg("roughness %g", double(p.roughness));
            if (!(p.f0.x <= 1.0f && p.f90 <= 1.0f && p.eta >= 1.0f)) fail_msg("Fresnel out of range");
        }
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_f0_from_ior),
                cmocka_unit_test(test_ior_zero),
                cmocka_unit_test(test_khr_specular),
                cmocka_unit_test(test_roughness_floor),
                cmocka_unit_test(test_khr_anisotropy),
                cmocka_unit_test(test_khr_clearcoat),
                cmocka_unit_test(test_khr_sheen),
                cmocka_unit_test(test_disney),
                cmocka_unit_test(test_hostile))
