// A Lambertian plane under a polygonal light: the rendered radiance is albedo / pi times the
// irradiance from Lambert's closed-form polygon formula (polygonIrradiance, scene_builder.h),
// per pixel within the oracle's own standard error, for both light sampling strategies;
// --no-shadows ignores an occluder.
#include "test_common.h"

#include "oracle.h"
#include "scene_builder.h"

using namespace rtpbr_oracle;

namespace {

constexpr uint32_t kW = 10, kH = 10;
constexpr float kAlbedo = 0.8f;
constexpr float kRadiance = 5.0f;
const std::vector<glm::vec3> kLight = {
    // A convex pentagon in the plane y = 1.2, counter-clockwise seen from below: emits down.
    {-0.5f, 1.2f, -0.4f}, {0.6f, 1.2f, -0.5f}, {0.8f, 1.2f, 0.3f}, {0.1f, 1.2f, 0.7f}, {-0.6f, 1.2f, 0.4f}};

struct Scene {
    SceneBuilder b;
    explicit Scene(bool occluder) {
        uint32_t white = b.material(glm::vec3(kAlbedo), 0.0f, 1.0f);
        b.materials[white].specular.specular_factor = 0.0f; // no specular layer: pure Lambert
        b.polygon({{-40, 0, 40}, {40, 0, 40}, {40, 0, -40}, {-40, 0, -40}}, white);
        b.light(kLight, glm::vec3(kRadiance), false);
        assert_true(b.lights.back().facts.normal[1] < -0.99f);
        if (occluder) {
            uint32_t black = b.material(glm::vec3(0.0f), 0.0f, 1.0f);
            b.materials[black].specular.specular_factor = 0.0f;
            // Double-sided: its front faces the light, and a single-sided surface lets rays
            // from behind through (glTF doubleSided false).
            b.materials[black].double_sided = true;
            // Between the light and the plane, above the camera (which looks down): invisible.
            b.polygon({{-1, 1.0f, -1}, {-1, 1.0f, 1}, {1, 1.0f, 1}, {1, 1.0f, -1}}, black);
        }
        b.camera(glm::vec3(0.3f, 0.8f, 2.0f), glm::vec3(0.0f, 0.0f, 0.2f), 0.6f);
        b.build();
    }
};

// Reference radiance of pixel (x, y): the closed form averaged over the pixel footprint.
double referencePixel(const rtpbr_gltf_camera &cam, uint32_t x, uint32_t y) {
    const int q = 6;
    double sum = 0.0;
    glm::dvec3 o(cam.position[0], cam.position[1], cam.position[2]);
    for (int i = 0; i < q; i++)
        for (int j = 0; j < q; j++) {
            glm::dvec3 d(cameraRay(cam, x + (i + 0.5f) / q, y + (j + 0.5f) / q, kW, kH));
            double t = -o.y / d.y;
            glm::dvec3 p = o + t * d;
            sum += kAlbedo / 3.14159265358979323846 * polygonIrradiance(p, glm::dvec3(0, 1, 0), kLight, kRadiance);
        }
    return sum / (q * q);
}

void check(bool occluder, RenderSettings s, double *meanStderr) {
    Scene scene(occluder);
    s.width = kW;
    s.height = kH;
    s.threads = 2;
    Accumulator acc;
    std::string err;
    if (render(scene.b.scene, s, &acc, &err, nullptr) != Result::Success)
        fail_msg("render: %s", err.c_str());
    std::vector<float> rgb, se;
    resolve(acc, &rgb, &se);
    double chi2 = 0.0, sumImg = 0.0, sumRef = 0.0, sumVar = 0.0, sumSe = 0.0;
    for (uint32_t y = 0; y < kH; y++)
        for (uint32_t x = 0; x < kW; x++) {
            size_t i = 3 * (y * kW + x);
            double ref = referencePixel(scene.b.cameras[0], x, y);
            double v = rgb[i], e = se[i];
            if (!(e > 0.0))
                fail_msg("pixel (%u, %u): value %g, standard error %g, reference %g", x, y, v, e, ref);
            double z = (v - ref) / e;
            if (std::fabs(z) > 5.0)
                fail_msg("pixel (%u, %u): %.5f vs closed form %.5f, %.1f standard errors", x, y, v, ref, z);
            chi2 += z * z;
            sumImg += v;
            sumRef += ref;
            sumVar += e * e;
            sumSe += e / std::max(ref, 1e-6);
        }
    int n = kW * kH;
    // Image mean within three standard errors; per-pixel errors distributed as they should.
    EXPECT_AGREE(sumImg / n, std::sqrt(sumVar) / n, sumRef / n, 0.0, 3.0, 0.0);
    if (!(chi2 < n + 5.0 * std::sqrt(2.0 * n)))
        fail_msg("sum of squared z-scores %.1f over %d pixels", chi2, n);
    if (meanStderr)
        *meanStderr = sumSe / n;
}

void test_polygon_light_solid_angle_sampling(void **) {
    RenderSettings s;
    s.spp = 256;
    double relSe = 0.0;
    check(false, s, &relSe);
    RenderSettings a = s;
    a.lightSampling = LightSampling::Area;
    double relSeArea = 0.0;
    check(false, a, &relSeArea);
    std::printf("mean relative standard error at %u spp: solid-angle sampling %.4f, area sampling %.4f\n", s.spp,
                relSe, relSeArea);
}

void test_polygon_light_direct_only(void **) {
    RenderSettings s;
    s.spp = 128;
    s.directOnly = true;
    check(false, s, nullptr);
}

void test_polygon_light_no_shadows_ignores_occluder(void **) {
    RenderSettings s;
    s.spp = 128;
    s.directOnly = true;
    s.noShadows = true;
    check(true, s, nullptr);
}

// Sanity of the previous test: with shadows the occluder does darken the plane.
void test_polygon_light_occluder_casts_shadow(void **) {
    Scene scene(true);
    RenderSettings s;
    s.width = kW;
    s.height = kH;
    s.spp = 16;
    Accumulator acc;
    std::string err;
    assert_true(render(scene.b.scene, s, &acc, &err, nullptr) == Result::Success);
    std::vector<float> rgb;
    resolve(acc, &rgb, nullptr);
    // The pixels looking at the plane under the occluder's centre lie in the umbra.
    double ref = referencePixel(scene.b.cameras[0], kW / 2, kH / 2);
    assert_true(ref > 0.1);
    assert_true(rgb[3 * (kH / 2 * kW + kW / 2)] < 0.2 * ref);
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_polygon_light_solid_angle_sampling),
                cmocka_unit_test(test_polygon_light_direct_only),
                cmocka_unit_test(test_polygon_light_no_shadows_ignores_occluder),
                cmocka_unit_test(test_polygon_light_occluder_casts_shadow))
