// White furnace through the whole renderer: a rough conductor with F = 1 (metallic, base
// colour 1: Schlick F0 = 1) inside an enclosure emitting radiance 1 everywhere reflects
// radiance 1 with the multiple-scattering walk, and E(mu) (its single-scattering albedo:
// 1 - the energy loss Kulla-Conty compensate) with --single-scatter, E(mu) taken both from
// the Kulla-Conty table (shaderlib/luts, GGX height-correlated) and from a quadrature here.
#include "test_common.h"

#include "oracle.h"
#include "scene_builder.h"

#include <luts/rtpbr_kc_tables.h>
#include <rtpbr/microfacet.h>

using namespace rtpbr_oracle;

namespace {

constexpr uint32_t kW = 12, kH = 12;

// Single-scattering albedo with F = 1, E(wo) = integral of D G2 / (4 wo.z wi.z) wi.z dwi, by a
// midpoint grid over the GGX NDF's own parametrisation (h from (u, phi) with density
// D(h) cos(theta_h)), independent of the oracle's VNDF sampling:
// E = mean over the grid of G2(wo, wi) (wo.h) / (wo.z cos(theta_h)), wi = reflect(wo, h).
double singleScatterAlbedo(glm::vec3 wo, float alpha) {
    const int n = 160;
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        double u = (i + 0.5) / n;
        double tanT = alpha * std::sqrt(u / (1.0 - u)); // GGX: tan^2 = a^2 u / (1 - u)
        double cosT = 1.0 / std::sqrt(1.0 + tanT * tanT), sinT = tanT * cosT;
        for (int j = 0; j < n; j++) {
            double phi = (j + 0.5) / n * 2.0 * 3.14159265358979323846;
            glm::vec3 h(float(sinT * std::cos(phi)), float(sinT * std::sin(phi)), float(cosT));
            float oh = glm::dot(wo, h);
            if (oh <= 0.0f)
                continue;
            glm::vec3 wi = 2.0f * oh * h - wo;
            if (wi.z <= 0.0f)
                continue;
            double G2 = rtpbr::G2_Microfacet(wo, wi, alpha, alpha);
            sum += G2 * oh / (wo.z * cosT);
        }
    }
    return sum / (double(n) * n);
}

// E(mu, r) from the Kulla-Conty table by bilinear interpolation on its node grid
// (sqrt(mu) and perceptual roughness r at i / (N - 1); see rtpbr_kc_tables.h).
double tableAlbedo(double mu, double r) {
    const int n = RTPBR_KC_SIZE;
    const auto &E = rtpbr_kc_E[RTPBR_KC_VARIANT_ggx_hc];
    double fx = std::sqrt(std::max(mu, 0.0)) * (n - 1), fr = r * (n - 1);
    int x0 = std::min(n - 2, int(fx)), r0 = std::min(n - 2, int(fr));
    double ax = fx - x0, ar = fr - r0;
    return (1 - ar) * ((1 - ax) * E[r0][x0] + ax * E[r0][x0 + 1]) + ar * ((1 - ax) * E[r0 + 1][x0] + ax * E[r0 + 1][x0 + 1]);
}

struct Furnace {
    SceneBuilder b;
    // anisotropy > 0: KHR_materials_anisotropy strength, with tangents along +x rotated by
    // 30 degrees (anisotropy_rotation).
    explicit Furnace(float alpha, float anisotropy = 0.0f) {
        uint32_t metal = b.material(glm::vec3(1.0f), 1.0f, std::sqrt(alpha));
        b.materials[metal].anisotropy.anisotropy_strength = anisotropy;
        b.materials[metal].anisotropy.anisotropy_rotation = 0.5236f;
        b.polygon({{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}}, metal);
        if (anisotropy > 0.0f) {
            std::vector<float> &t = b.floatArrays[b.floatArrays.size() - 1];
            for (size_t v = 0; v < 4; v++) {
                t[4 * v] = 1.0f;
                t[4 * v + 3] = 1.0f;
            }
            b.primitives.back().has_tangents = true;
        }
        const float s = 10.0f;
        glm::vec3 c[8] = {{-s, -s, -s}, {s, -s, -s}, {s, s, -s}, {-s, s, -s},
                          {-s, -s, s},  {s, -s, s},  {s, s, s},  {-s, s, s}};
        int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}};
        for (auto &f : faces)
            b.light({c[f[0]], c[f[1]], c[f[2]], c[f[3]]}, glm::vec3(1.0f), true);
        // Looking down at 60 degrees from the normal, a narrow field of view on the plate.
        b.camera(glm::vec3(0.0f, 1.5f * std::cos(1.047f), 1.5f * std::sin(1.047f)), glm::vec3(0.0f), 0.3f);
        b.build();
    }
};

void run(float alpha, bool single, float anisotropy = 0.0f) {
    Furnace f(alpha, anisotropy);
    RenderSettings s;
    s.width = kW;
    s.height = kH;
    s.spp = 1024;
    s.threads = 2;
    s.singleScatter = single;
    Accumulator acc;
    std::string err;
    Result r = render(f.b.scene, s, &acc, &err, nullptr);
    if (r != Result::Success)
        fail_msg("render: %s", err.c_str());
    std::vector<float> rgb, se;
    resolve(acc, &rgb, &se);
    MeanEstimator image;
    double ref = 0.0, refTable = 0.0;
    for (uint32_t y = 0; y < kH; y++)
        for (uint32_t x = 0; x < kW; x++) {
            image.add(rgb[3 * (y * kW + x) + 1]);
            if (single) {
                glm::vec3 d = cameraRay(f.b.cameras[0], x + 0.5f, y + 0.5f, kW, kH);
                glm::vec3 wo(-d.x, -d.z, -d.y); // local frame of the plate: n = +y
                ref += singleScatterAlbedo(wo, alpha);
                refTable += tableAlbedo(wo.z, std::sqrt(alpha));
            }
        }
    ref = single ? ref / (kW * kH) : 1.0;
    refTable = single ? refTable / (kW * kH) : 1.0;
    if (single) {
        std::printf("alpha %.1f: E(mu) by quadrature %.5f, from the Kulla-Conty table %.5f\n", alpha, ref, refTable);
        if (!(std::fabs(image.mean() - refTable) <= 0.01 * refTable))
            fail_msg("alpha %.2f: radiance %.5f, Kulla-Conty E(mu) %.5f, not within 1%%", alpha, image.mean(),
                     refTable);
    }
    std::printf("alpha %.1f %s: mean radiance %.5f (se %.5f), expected %.5f\n", alpha,
                single ? "single-scatter" : "multi-bounce", image.mean(), image.stderror(), ref);
    if (!(std::fabs(image.mean() - ref) <= 0.01 * ref))
        fail_msg("alpha %.2f: radiance %.5f, expected %.5f within 1%%", alpha, image.mean(), ref);
    if (single && alpha >= 0.5f && !(ref < 0.97))
        fail_msg("alpha %.2f: E(mu) = %.4f shows no single-scattering energy loss", alpha, ref);
}

void test_furnace_multi_01(void **) { run(0.1f, false); }
void test_furnace_multi_05(void **) { run(0.5f, false); }
void test_furnace_multi_10(void **) { run(1.0f, false); }
// Anisotropic (alpha_t = mix(0.3, 1, 0.8^2) = 0.75, alpha_b = 0.3), rotated tangent frame.
void test_furnace_multi_anisotropic(void **) { run(0.3f, false, 0.8f); }
void test_furnace_single_01(void **) { run(0.1f, true); }
void test_furnace_single_05(void **) { run(0.5f, true); }
void test_furnace_single_10(void **) { run(1.0f, true); }

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_furnace_multi_01),
                cmocka_unit_test(test_furnace_multi_05),
                cmocka_unit_test(test_furnace_multi_10),
                cmocka_unit_test(test_furnace_multi_anisotropic),
                cmocka_unit_test(test_furnace_single_01),
                cmocka_unit_test(test_furnace_single_05),
                cmocka_unit_test(test_furnace_single_10))
