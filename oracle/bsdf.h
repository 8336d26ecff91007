// rtpbr oracle: the material model as a BSDF (see README.md, "Material model").
//
// glTF metallic-roughness with the dielectric-over-diffuse layering of the shaderlib's
// BRDF_DielectricOverDiffuse (kulla_conty.h; Kulla & Conty 2017), every specular term being
// the multiple-scattering random walk of Heitz et al. 2016 (or, with singleScatter, the
// single-scattering microfacet BRDF) instead of a compensated approximation:
//   f = metallic * f_metal + (1 - metallic) * f_dielectric
//   f_metal      = S(Fresnel = Schlick(F0 = baseColor, F90 = 1))
//   f_dielectric = w * S(Fresnel = F_Dielectric(., ior))
//                  + baseColor (1 - Es(mu_o)) (1 - Es(mu_i)) / (pi (1 - Es_avg))
//   Es(mu) = albedo of w * S at mu (its own walk albedo, tabulated by LayerAlbedo),
//   Es_avg = 2 int Es mu dmu, w = specularFactor, alpha = roughness^2 (GGX).
// KHR_materials_clearcoat (weight c, coat alpha ac) on top, as its fresnel_coat:
//   f_coated = (1 - c Fc(wo.z)) f + c * S(GGX ac, Fresnel = Schlick(0.04, 1)),
//   Fc = Schlick(0.04, 1, .); the coat shares the shading normal.
// KHR_materials_sheen (sheenColor s != 0), between the clearcoat and the base (KHR order):
//   f_coated = (1 - c Fc(wo.z)) (f_sheen + A(wo, wi) f) + c * S(...),
//   f_sheen = s D_Charlie V_Charlie (shaderlib sheen.h, sheenRoughness r_s, alpha = r_s^2),
//   A = Sheen_AlbedoScaling(s, E(mu_o), E(mu_i)), E = the committed E_sheen table (charlie,
//   bilinear): KHR's albedo scaling is part of the model, so the oracle uses it as well.
// Disney materials (disney != null): Burley 2012's principled BRDF (shaderlib disney.h:
// diffuse + subsurface, sheen, GTR1 clearcoat in closed form) with its specular lobe
// (anisotropic GGX, Schlick F0 = Disney_SpecularF0) simulated by the walk.
// The Fresnel term is applied at every microfacet of the walk. Directions are in the local
// shading frame (n = +z, tangent = +x); wo points to the viewer, wi to the light.
#ifndef RTPBR_ORACLE_BSDF_H
#define RTPBR_ORACLE_BSDF_H

#include "microsurface.h"
#include "rng.h"

#include <rtpbr/disney.h>

#include <vector>

namespace rtpbr_oracle {

// Directional albedo Es(mu, r) of the dielectric specular layer (F = F_Dielectric(., eta),
// GGX, alpha = r^2) and its cosine-weighted average, for the walk (multi) and for its first
// order (single), by Monte Carlo over the walk itself (deterministic seed). Nodes: x = sqrt(mu)
// and r at i / (n - 1), mu node 0 at 1e-4 (as shaderlib/luts); bilinear lookups.
class LayerAlbedo {
public:
    static constexpr int kNodes = 24;
    LayerAlbedo(float eta, int walksPerNode);
    float eta() const { return eta_; }
    float E(float mu, float r, bool single) const;
    float Eavg(float r, bool single) const;

private:
    float eta_;
    std::vector<float> e_[2];    // [single][r * kNodes + x]
    std::vector<float> eavg_[2]; // [single][r]
};

// A material with its parameters resolved at a surface point.
struct SurfaceMaterial {
    vec3 baseColor = vec3(1.0f);
    float metallic = 0.0f;
    float alphaX = 0.25f, alphaY = 0.25f;
    float tableRoughness = 0.5f;      // MaterialParams.tableRoughness, sqrt(sqrt(alphaX alphaY)): the LayerAlbedo axis
    float specularWeight = 1.0f;      // w: MaterialParams.specularWeight
    const LayerAlbedo *layer = nullptr; // dielectric layer albedo (its eta is the IOR); null = w 0
    float coat = 0.0f;                // c: MaterialParams.coat (KHR clearcoat weight)
    float coatAlpha = 0.001f;         // ac: MaterialParams.coatAlpha
    vec3 sheenColor = vec3(0.0f);     // KHR sheenColor (0: no sheen layer)
    float sheenRoughness = 0.0f;      // KHR sheenRoughness (perceptual)
    bool disney = false;              // Burley's model with disneyParams (alphas from it)
    rtpbr::DisneyMaterial disneyParams{};
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
    vec3 specularEvalOn(const MicrosurfaceGGX &ms, const ConductorFresnel &F, vec3 wi, Rng &rng) const;
    bool specularSampleOn(const MicrosurfaceGGX &ms, const ConductorFresnel &F, Rng &rng, vec3 *wi,
                          vec3 *weight) const;
    // Base lobe per unit base colour, without the 1/pi cos: (1 - Es(mu_i)) (1 - Es(mu_o)) / (1 - Es_avg).
    float specularPdfMis(const MicrosurfaceGGX &ms, float E, vec3 wi) const;
    float baseWeight(vec3 wi) const;
    float layerE(float mu) const;
    void initDisney();
    vec3 evalDisney(vec3 wi, Rng &rng) const;
    bool sampleDisney(Rng &rng, BsdfSample *s) const;
    float pdfMisDisney(vec3 wi) const;
    // KHR sheen: the base layer's factor Sheen_AlbedoScaling at wi (1 without sheen).
    float sheenScaling(vec3 wi) const;
    vec3 sheenEval(vec3 wi) const; // f_sheen |wi.z|

    SurfaceMaterial m_;
    bool single_;
    vec3 wo_;
    MicrosurfaceGGX ms_, msClear_;
    ConductorFresnel metalF_, coatF_, clearF_;
    float baseScale_ = 1.0f;  // 1 - c Fc(wo.z)
    float baseFactorO_ = 1.0f; // (1 - Es(mu_o)) / (1 - Es_avg)
    float probMetal_ = 0.0f, probCoat_ = 0.0f, probDiffuse_ = 0.0f, probClear_ = 0.0f, probSheen_ = 0.0f,
          probSum_ = 0.0f;
    bool sheen_ = false;
    float sheenAlpha_ = 1.0f, sheenMax_ = 0.0f, sheenEo_ = 0.0f; // alpha, max3(sheenColor), E(mu_o)
    float disneyClearAlpha_ = 0.1f; // GGX alpha used to sample the GTR1 clearcoat
    float essMain_ = 1.0f, essClear_ = 1.0f; // single-scattering albedo at wo (MIS shaping)
};

} // namespace rtpbr_oracle

#endif
