// rtpbr oracle: the material model as a BSDF (see README.md, "Material model").
//
// glTF metallic-roughness, as the glTF 2.0 specification (appendix B) and
// KHR_materials_specular / KHR_materials_ior define it, with every specular term replaced by
// the multiple-scattering random walk of Heitz et al. 2016 (or, with singleScatter, by the
// shaderlib's single-scattering microfacet BRDF):
//   f = metallic * f_metal + (1 - metallic) * f_dielectric
//   f_metal      = walk(GGX alpha, Fresnel = Schlick(F0 = baseColor, F90 = 1))
//   f_dielectric = w * walk(GGX alpha, Fresnel = Schlick(F0 = f0d, F90 = 1))
//                  + (1 - w * max3(Schlick(f0d, 1, |wo.h|))) * baseColor / pi
//   f0d = min(((ior - 1) / (ior + 1))^2 * specularColor, 1), w = specularFactor,
//   h = normalize(wo + wi), alpha = roughness^2 (clamped by the shaderlib's Alpha_Clamp).
// KHR_materials_clearcoat (weight c, coat alpha ac) on top, as its fresnel_coat:
//   f_coated = (1 - c Fc(wo.z)) f + c * walk(GGX ac, Fresnel = Schlick(0.04, 1)),
//   Fc = Schlick(0.04, 1, .); the coat shares the shading normal.
// The Fresnel term is applied at every microfacet of the walk. Directions are in the local
// shading frame (n = +z, tangent = +x); wo points to the viewer, wi to the light.
#ifndef RTPBR_ORACLE_BSDF_H
#define RTPBR_ORACLE_BSDF_H

#include "microsurface.h"
#include "rng.h"

namespace rtpbr_oracle {

// A material with its parameters resolved at a surface point.
struct SurfaceMaterial {
    vec3 baseColor = vec3(1.0f);
    float metallic = 0.0f;
    float alphaX = 0.25f, alphaY = 0.25f;
    vec3 dielectricF0 = vec3(0.04f); // f0d
    float specularWeight = 1.0f;     // w
    float clearcoat = 0.0f;          // c
    float clearcoatAlpha = 0.001f;   // ac
};

struct BsdfSample {
    vec3 wi;
    vec3 weight;  // estimate of f |wi.z| / pdf
    float pdfMis; // the density used in MIS weights (see Bsdf::pdfMis)
};

class Bsdf {
public:
    Bsdf(const SurfaceMaterial &m, bool singleScatter, vec3 wo);

    // Unbiased estimate of f(wo, wi) |wi.z| (exact in single-scatter mode).
    vec3 eval(vec3 wi, Rng &rng) const;
    bool sample(Rng &rng, BsdfSample *s) const;
    // The multi-bounce walk has no closed-form density: MIS weights use the density of the
    // single-scattering lobes (lobe probabilities x VNDF reflection pdf, cosine for the
    // diffuse lobe). Weights built from any fixed density that sum to one over the two
    // strategies keep the estimator unbiased; only the variance depends on the choice.
    float pdfMis(vec3 wi) const;
    bool isBlack() const { return probSum_ <= 0.0f; }

private:
    float diffuseWeight(vec3 wi) const;

    SurfaceMaterial m_;
    bool single_;
    vec3 wo_;
    vec3 specularEvalOn(const MicrosurfaceGGX &ms, const ConductorFresnel &F, vec3 wi, Rng &rng) const;
    bool specularSampleOn(const MicrosurfaceGGX &ms, const ConductorFresnel &F, Rng &rng, vec3 *wi,
                          vec3 *weight) const;

    MicrosurfaceGGX ms_, msClear_;
    ConductorFresnel metalF_, coatF_, clearF_;
    float baseScale_ = 1.0f; // 1 - c Fc(wo.z)
    float probMetal_ = 0.0f, probCoat_ = 0.0f, probDiffuse_ = 0.0f, probClear_ = 0.0f, probSum_ = 0.0f;
};

} // namespace rtpbr_oracle

#endif
