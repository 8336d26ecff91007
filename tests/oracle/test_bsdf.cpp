// The material BSDF (oracle/bsdf.h): for every lobe combination, sampling (mean sample weight)
// and evaluation (integral of eval by an independent mixture density) give the same albedo,
// in multi-bounce and single-scatter mode; the single-scatter mode is the closed form.
#include "bsdf_fixtures.h"

#include <rtpbr/microfacet.h>
#include <rtpbr/sampling.h>

using namespace rtpbr_oracle;

namespace {

SurfaceMaterial mat(vec3 base, float metallic, float alpha, float coat, float coatAlpha) {
    SurfaceMaterial m;
    m.baseColor = base;
    m.metallic = metallic;
    m.alphaX = m.alphaY = alpha;
    m.tableRoughness = std::sqrt(alpha);
    m.specularWeight = 1.0f;
    m.layer = &layer15();
    m.coat = coat;
    m.coatAlpha = coatAlpha;
    return m;
}

void test_sampling_matches_evaluation(void **) {
    const SurfaceMaterial mats[] = {
        mat(vec3(0.9f, 0.6f, 0.3f), 1.0f, 0.3f, 0.0f, 0.01f),  // metal
        mat(vec3(0.2f, 0.5f, 0.8f), 0.0f, 0.5f, 0.0f, 0.01f),  // dielectric over diffuse
        mat(vec3(0.7f, 0.7f, 0.2f), 0.4f, 0.8f, 0.0f, 0.01f),  // blend
        mat(vec3(0.8f, 0.1f, 0.1f), 0.0f, 0.6f, 1.0f, 0.05f),  // clear-coated plastic
        mat(vec3(0.9f, 0.9f, 0.9f), 1.0f, 0.4f, 0.5f, 0.2f),   // clear-coated metal
    };
    const vec3 wos[] = {vec3(0.0f, 0.0f, 1.0f), glm::normalize(vec3(0.8f, 0.1f, 0.4f)),
                        glm::normalize(vec3(-0.2f, 0.9f, 0.15f))};
    uint64_t seed = 1;
    for (const SurfaceMaterial &m : mats)
        for (vec3 wo : wos)
            for (bool single : {false, true})
                checkAlbedo(m, single, wo, seed++);
}

// Single-scatter metal: eval is exactly BRDF_SpecularLocal x cos (deterministic), and the
// multi-bounce evaluation is at least as large on average (it adds orders >= 2).
void test_single_scatter_is_closed_form(void **) {
    SurfaceMaterial m = mat(vec3(0.9f, 0.6f, 0.3f), 1.0f, 0.5f, 0.0f, 0.01f);
    vec3 wo = glm::normalize(vec3(0.5f, 0.2f, 0.6f)), wi = glm::normalize(vec3(-0.3f, 0.1f, 0.8f));
    Rng rng(9, 9);
    Bsdf single(m, true, wo), multi(m, false, wo);
    rtpbr::FresnelParams p = rtpbr::Fresnel_FromF0(m.baseColor);
    vec3 ref = rtpbr::BRDF_SpecularLocal(wo, wi, 0.5f, 0.5f, p) * wi.z;
    vec3 f = single.eval(wi, rng);
    for (int c = 0; c < 3; c++)
        assert_true(std::fabs(f[c] - ref[c]) <= 1e-6f * ref[c]);
    MeanEstimator extra;
    for (int i = 0; i < 20000; i++)
        extra.add(multi.eval(wi, rng).x - ref.x);
    assert_true(extra.mean() > 0.0);
}

// The dielectric-over-diffuse layering conserves energy: with a white base the albedo is 1
// (Es(mu_o) from the coat + 1 - Es(mu_o) from the base), by sampling and by evaluation,
// multi-bounce and single-scatter (each with its own layer albedo).
void test_white_dielectric_over_diffuse_furnace(void **) {
    for (float alpha : {0.05f, 0.3f, 0.8f})
        for (bool single : {false, true})
            for (float mu : {0.95f, 0.5f, 0.15f}) {
                SurfaceMaterial m = mat(vec3(1.0f), 0.0f, alpha, 0.0f, 0.01f);
                vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
                Bsdf bsdf(m, single, wo);
                Rng rng(uint64_t(alpha * 100) + (single ? 7 : 0), uint64_t(mu * 100));
                MeanEstimator albedo;
                for (int i = 0; i < 40000; i++) {
                    BsdfSample s;
                    albedo.add(bsdf.sample(rng, &s) ? s.weight.x : 0.0);
                }
                // Table interpolation and its Monte Carlo error: 1 %.
                if (!(std::fabs(albedo.mean() - 1.0) < 0.01 + 4.0 * albedo.stderror()))
                    fail_msg("alpha %.2f mu %.2f %s: albedo %.4f (se %.4f)", alpha, mu, single ? "single" : "multi",
                             albedo.mean(), albedo.stderror());
            }
}

SurfaceMaterial disney(vec3 base, float metallic, float roughness, float sheen, float clearcoat, float aniso) {
    SurfaceMaterial m;
    m.disney = true;
    rtpbr::DisneyMaterial &d = m.disneyParams;
    d = rtpbr::Disney_DefaultMaterial();
    d.baseColor = base;
    d.metallic = metallic;
    d.roughness = roughness;
    d.sheen = sheen;
    d.clearcoat = clearcoat;
    d.clearcoatGloss = 0.7f;
    d.subsurface = 0.3f;
    d.anisotropic = aniso;
    glm::vec2 a = rtpbr::Disney_SpecularAlphas(d);
    m.alphaX = a.x;
    m.alphaY = a.y;
    m.baseColor = base;
    m.metallic = metallic;
    return m;
}

// Disney materials: sampling agrees with evaluation; single-scatter evaluation is BRDF_Disney.
void test_disney(void **) {
    const SurfaceMaterial mats[] = {disney(vec3(0.8f, 0.5f, 0.2f), 0.0f, 0.5f, 0.5f, 0.0f, 0.0f),
                                    disney(vec3(0.9f, 0.8f, 0.6f), 1.0f, 0.3f, 0.0f, 0.0f, 0.6f),
                                    disney(vec3(0.2f, 0.3f, 0.7f), 0.3f, 0.7f, 0.0f, 1.0f, 0.0f)};
    const vec3 wos[] = {vec3(0.0f, 0.0f, 1.0f), glm::normalize(vec3(0.7f, 0.3f, 0.3f))};
    uint64_t seed = 100;
    for (const SurfaceMaterial &m : mats)
        for (vec3 wo : wos) {
            for (bool single : {false, true})
                checkAlbedo(m, single, wo, seed++);
            Bsdf b(m, true, wo);
            Rng rng(1, 1);
            vec3 wi = glm::normalize(vec3(-0.2f, 0.4f, 0.7f));
            vec3 ref = rtpbr::BRDF_Disney(m.disneyParams, wo, wi) * wi.z;
            vec3 f = b.eval(wi, rng);
            for (int c = 0; c < 3; c++)
                assert_true(std::fabs(f[c] - ref[c]) <= 1e-5f * ref[c] + 1e-7f);
        }
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_sampling_matches_evaluation),
                cmocka_unit_test(test_single_scatter_is_closed_form),
                cmocka_unit_test(test_white_dielectric_over_diffuse_furnace),
                cmocka_unit_test(test_disney))
