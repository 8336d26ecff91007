// KHR_materials_sheen in the oracle's BSDF (oracle/bsdf.h): a white-furnace-style energy check
// (sheen over a black base: the albedo is E_sheen, the committed table, at its nodes; over a
// white Lambertian base the KHR albedo scaling keeps the albedo at or below 1), and sampling
// agreeing with evaluation for sheen combined with every other lobe.
#include "bsdf_fixtures.h"

#include <luts/rtpbr_sheen_tables.h>
#include <rtpbr/sampling.h>
#include <rtpbr/sheen.h>

using namespace rtpbr_oracle;

namespace {

SurfaceMaterial sheenOnly(float r, vec3 base) {
    SurfaceMaterial m;
    m.baseColor = base;
    m.metallic = 0.0f;
    m.alphaX = m.alphaY = 0.25f;
    m.tableRoughness = 0.5f;
    m.specularWeight = 0.0f;
    m.layer = nullptr; // no dielectric specular: the base is Lambertian (black or white)
    m.sheenColor = vec3(1.0f);
    m.sheenRoughness = r;
    return m;
}

vec3 nodeDirection(int imu) {
    float x = float(imu) / float(RTPBR_SHEEN_SIZE - 1);
    float mu = imu == 0 ? 1e-4f : x * x;
    return vec3(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
}

// Over a black base the only light leaving is the sheen lobe's: its albedo is E_sheen(mu, r)
// (the table's value at a node, no interpolation), by sampling (mean weight) and by evaluation
// (integral of eval over the uniform hemisphere).
void test_black_base_albedo_is_table(void **) {
    uint64_t seed = 1;
    double worst = 0.0;
    for (int ir : {6, 12, 20, 31})
        for (int imu : {8, 16, 25, 31}) {
            float r = float(ir) / float(RTPBR_SHEEN_SIZE - 1);
            vec3 wo = nodeDirection(imu);
            Bsdf bsdf(sheenOnly(r, vec3(0.0f)), false, wo);
            Rng rng(seed++, 3);
            MeanEstimator bySampling, byEval;
            for (int i = 0; i < 60000; i++) {
                BsdfSample s;
                bySampling.add(bsdf.sample(rng, &s) ? double(s.weight.y) : 0.0);
                float z = rng.uniform(), phi = 6.2831853f * rng.uniform(), sr = std::sqrt(std::max(0.0f, 1.0f - z * z));
                vec3 wi(sr * std::cos(phi), sr * std::sin(phi), z);
                byEval.add(double(bsdf.eval(wi, rng).y) * 6.2831853);
            }
            double E = rtpbr_sheen_E[RTPBR_SHEEN_VARIANT_charlie][ir][imu];
            // The table's own standard error (at most RTPBR_SHEEN_MAX_STDERR, ~1e-4 at these nodes).
            EXPECT_AGREE(bySampling.mean(), bySampling.stderror(), E, 1e-3 * E, 4.0, 1e-4);
            EXPECT_AGREE(byEval.mean(), byEval.stderror(), E, 1e-3 * E, 4.0, 1e-4);
            worst = std::max(worst, std::fabs(bySampling.mean() - E) / E);
        }
    std::printf("oracle sheen over black: largest relative difference of the sampled albedo from E_sheen %.2e\n", worst);
}

// Over a white Lambertian base: albedo = E(mu_o) + int min(1 - E(mu_o), 1 - E(mu_i)) cos / pi
// <= 1, and at least E(mu_o) (roughness where E <= 1).
void test_white_base_conserves_energy(void **) {
    uint64_t seed = 100;
    for (float r : {0.4f, 0.7f, 1.0f})
        for (float mu : {0.1f, 0.5f, 0.95f}) {
            vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
            Bsdf bsdf(sheenOnly(r, vec3(1.0f)), false, wo);
            Rng rng(seed++, 5);
            MeanEstimator albedo;
            for (int i = 0; i < 60000; i++) {
                BsdfSample s;
                albedo.add(bsdf.sample(rng, &s) ? double(s.weight.x) : 0.0);
            }
            if (!(albedo.mean() <= 1.0 + 4.0 * albedo.stderror()))
                fail_msg("r %.2f mu %.2f: albedo %.4f (se %.4f) > 1", r, mu, albedo.mean(), albedo.stderror());
            // The base must still show through (albedo scaling, not replacement).
            assert_true(albedo.mean() > 0.5);
        }
}

void test_sampling_matches_evaluation(void **) {
    struct Case {
        vec3 base;
        float metallic, alpha, clearcoat;
        vec3 sheen;
        float sheenRoughness;
    };
    const Case cases[] = {
        {vec3(0.2f, 0.5f, 0.8f), 0.0f, 0.5f, 0.0f, vec3(1.0f, 0.8f, 0.6f), 0.5f}, // dielectric over diffuse + sheen
        {vec3(0.9f, 0.6f, 0.3f), 1.0f, 0.3f, 0.0f, vec3(0.3f, 0.3f, 0.9f), 0.3f}, // metal + sheen
        {vec3(0.7f, 0.2f, 0.2f), 0.0f, 0.7f, 1.0f, vec3(0.9f), 0.8f},             // coat over sheen over plastic
    };
    const vec3 wos[] = {vec3(0.0f, 0.0f, 1.0f), glm::normalize(vec3(0.8f, 0.1f, 0.4f)),
                        glm::normalize(vec3(-0.2f, 0.9f, 0.15f))};
    uint64_t seed = 200;
    for (const Case &c : cases)
        for (vec3 wo : wos)
            for (bool single : {false, true}) {
                SurfaceMaterial m;
                m.baseColor = c.base;
                m.metallic = c.metallic;
                m.alphaX = m.alphaY = c.alpha;
                m.tableRoughness = std::sqrt(c.alpha);
                m.specularWeight = 1.0f;
                m.layer = &layer15();
                m.coat = c.clearcoat;
                m.coatAlpha = 0.05f;
                m.sheenColor = c.sheen;
                m.sheenRoughness = c.sheenRoughness;
                checkAlbedo(m, single, wo, seed++, true);
            }
}

// The sheen lobe adds to the material: with sheen the albedo at grazing view is larger than
// without (the same seed), and sheenColor 0 leaves the BSDF exactly as before.
void test_zero_sheen_is_unchanged(void **) {
    SurfaceMaterial m;
    m.baseColor = vec3(0.5f);
    m.metallic = 0.0f;
    m.alphaX = m.alphaY = 0.3f;
    m.tableRoughness = std::sqrt(0.3f);
    m.specularWeight = 1.0f;
    m.layer = &layer15();
    vec3 wo = glm::normalize(vec3(0.6f, 0.0f, 0.8f)), wi = glm::normalize(vec3(-0.3f, 0.2f, 0.9f));
    Bsdf a(m, true, wo);
    m.sheenColor = vec3(0.0f);
    m.sheenRoughness = 0.7f;
    Bsdf b(m, true, wo);
    Rng r1(1, 1), r2(1, 1);
    vec3 fa = a.eval(wi, r1), fb = b.eval(wi, r2);
    assert_true(fa == fb);
    assert_true(a.pdfMis(wi) == b.pdfMis(wi));
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_black_base_albedo_is_table),
                cmocka_unit_test(test_white_base_conserves_energy),
                cmocka_unit_test(test_sampling_matches_evaluation),
                cmocka_unit_test(test_zero_sheen_is_unchanged))
