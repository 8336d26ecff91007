// KHR_lights_punctual lights in the oracle (issue 30), rendered on hand-built scenes and held
// per pixel to closed forms written here from the extension's text (not oracle/lights.cpp's):
//   - a Lambert plane under a directional light: every pixel a/pi E cos(theta), exactly;
//   - under a point light: a/pi I cos / d^2, averaged over each pixel's footprint;
//   - a spot: exactly 0 outside the outer cone, the point's value inside the inner one, the
//     falloff between; the range window: exactly 0 beyond the range;
//   - shadows: exactly 0 in an occluder's umbra (a directional light's shadow ray goes to
//     infinity), the unshadowed value with noShadows;
//   - a rough GGX conductor (single scattering): D G2 F / (4 NoL NoV) NoL E, with the shader
//     library's BRDF_SpecularLocal only as a cross-check of the formula written here;
//   - multi-bounce: a floor in the shadow of a shade is exactly 0 with direct lighting and,
//     with two scattering events, the integral of the lit wall's radiance over the wall.
//   - the sun's disk (a directional light's angular_diameter > 0): a Lambert plane a/pi E cos
//     theta while the disk is wholly above its horizon, the quadrature of the part above it
//     where it straddles the horizon, exactly 0 below; GGX (roughness 0.05, 0.3) against the
//     quadrature of f cos L over the disk, f the shader library's BRDF_SpecularLocal.
//   - a point light's sphere (radius > 0): on a Lambert plane the point light's I cos / d^2
//     while it is wholly above the horizon (also with a range window, and seen through it: it
//     occludes nothing), the horizon-clipped cap's closed form (Snyder 1996, checked against
//     quadrature) where it straddles the horizon, a L inside it, exactly 0 in its umbra; GGX
//     (roughness 0.05, 0.3) against the quadrature of f cos L over its cone.
// The oracle's pixel is the mean of spp evaluations at points jittered uniformly in the pixel,
// so its expectation is the closed form averaged over the pixel's footprint, and its error is
// the jitter's (and the paths'), which its standard error measures.
#include "test_common.h"

#include "oracle.h"
#include "scene_builder.h"

#include <rtpbr/fresnel.h>
#include <rtpbr/ltc_shapes.h>
#include <rtpbr/microfacet.h>

#include <algorithm>
#include <cstdlib>
#include <functional>

using namespace rtpbr_oracle;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kAlbedo = 0.8f;
// float arithmetic along a path: relative error allowed on top of the standard errors.
constexpr double kRounding = 2e-5;

// ---- the closed forms: KHR_lights_punctual, "Light Types", "Range Property", "Inner and Outer
// Cone Angles" -----------------------------------------------------------------------------------

struct Light {
    rtpbr_gltf_punctual_type type;
    glm::dvec3 position, direction; // direction: the way the light travels, unit
    double intensity;               // candela (point, spot) or lux (directional), grey
    double range = 0.0;             // 0: infinite
    double inner = 0.0, outer = kPi / 4.0;
    double radius = 0.0;            // point: a sphere's (0: a true point)
};

// Irradiance at p on a surface of normal n from the unoccluded light; *wi: towards the light.
double irradiance(const Light &L, glm::dvec3 p, glm::dvec3 n, glm::dvec3 *wi) {
    if (L.type == RTPBR_GLTF_PUNCTUAL_DIRECTIONAL) {
        *wi = -L.direction;
        return L.intensity * std::max(0.0, glm::dot(n, *wi));
    }
    glm::dvec3 toLight = L.position - p;
    double d = glm::length(toLight);
    *wi = toLight / d;
    // The spec's sample code: max(min(1.0 - pow(d / range, 4), 1), 0) / pow(d, 2).
    double attenuation = 1.0 / std::pow(d, 2.0);
    if (L.range > 0.0)
        attenuation *= std::max(std::min(1.0 - std::pow(d / L.range, 4.0), 1.0), 0.0);
    if (L.type == RTPBR_GLTF_PUNCTUAL_SPOT) {
        // The spec's lightAngleScale / lightAngleOffset, squared.
        double scale = 1.0 / std::max(0.001, std::cos(L.inner) - std::cos(L.outer));
        double offset = -std::cos(L.outer) * scale;
        double cd = glm::dot(L.direction, -*wi);
        double a = std::min(std::max(cd * scale + offset, 0.0), 1.0);
        attenuation *= a * a;
    }
    return L.intensity * attenuation * std::max(0.0, glm::dot(n, *wi));
}

// Reflected radiance of a Lambert surface of albedo a.
double lambert(const Light &L, glm::dvec3 p, glm::dvec3 n, double a) {
    glm::dvec3 wi;
    return a / kPi * irradiance(L, p, n, &wi);
}

// GGX (Trowbridge-Reitz) with the height-correlated Smith G2 and Schlick's Fresnel (F90 = 1):
// the single-scattering BRDF times NoL, one channel of F0.
double ggxReflectance(glm::dvec3 n, glm::dvec3 wo, glm::dvec3 wi, double alpha, double f0) {
    double NoL = glm::dot(n, wi), NoV = glm::dot(n, wo);
    if (!(NoL > 0.0) || !(NoV > 0.0))
        return 0.0;
    glm::dvec3 h = glm::normalize(wo + wi);
    double a2 = alpha * alpha, NoH = glm::dot(n, h);
    double D = a2 / (kPi * std::pow(NoH * NoH * (a2 - 1.0) + 1.0, 2.0));
    auto lambda = [a2](double c) { return 0.5 * (-1.0 + std::sqrt(1.0 + a2 * (1.0 - c * c) / (c * c))); };
    double G2 = 1.0 / (1.0 + lambda(NoV) + lambda(NoL));
    double F = f0 + (1.0 - f0) * std::pow(1.0 - glm::dot(wo, h), 5.0);
    return D * G2 * F / (4.0 * NoL * NoV) * NoL;
}

// ---- scenes and images ---------------------------------------------------------------------

const glm::dvec3 kUp(0.0, 1.0, 0.0);

// A black, double-sided square at height y, centre (cx, cz), half-size r: an occluder.
void occluder(SceneBuilder &b, double y, double cx, double cz, double r) {
    uint32_t black = lambertMaterial(b, 0.0f);
    b.materials[black].double_sided = true;
    float fy = float(y), x0 = float(cx - r), x1 = float(cx + r), z0 = float(cz - r), z1 = float(cz + r);
    b.polygon({{x0, fy, z0}, {x0, fy, z1}, {x1, fy, z1}, {x1, fy, z0}}, black);
}

void addLight(SceneBuilder &b, const Light &L) {
    b.punctual(L.type, glm::vec3(L.position), glm::vec3(L.direction), glm::vec3(float(L.intensity)), float(L.range),
               float(L.inner), float(L.outer));
    b.punctualLights.back().radius = float(L.radius);
}

struct Image {
    uint32_t w = 0, h = 0;
    std::vector<float> rgb, se;
    double v(uint32_t x, uint32_t y, int c = 0) const { return rgb[3 * (size_t(y) * w + x) + c]; }
    double e(uint32_t x, uint32_t y, int c = 0) const { return se[3 * (size_t(y) * w + x) + c]; }
};

Image renderOnly(const SceneBuilder &b, RenderSettings s, uint32_t w, uint32_t h) {
    s.width = w;
    s.height = h;
    s.threads = 2;
    Accumulator acc;
    std::string err;
    if (render(b.scene, s, &acc, &err, nullptr) != Result::Success)
        fail_msg("render: %s", err.c_str());
    Image img;
    img.w = w;
    img.h = h;
    resolve(acc, &img.rgb, &img.se);
    return img;
}

// The scene rendered at w x h. With RTPBR_TEST_IMAGES=DIR set, also at 256 pixels wide (the
// whole image) as DIR/name.png, for looking at:
//   RTPBR_TEST_IMAGES=/tmp build/tests/oracle/test_oracle_punctual_light
Image renderImage(SceneBuilder &b, const RenderSettings &s, uint32_t w, uint32_t h, const char *name) {
    b.build();
    if (const char *dir = std::getenv("RTPBR_TEST_IMAGES")) {
        RenderSettings big = s;
        big.region = Region{};
        Image view = renderOnly(b, big, 256, 256 * h / w);
        std::string err;
        if (writeImage(std::string(dir) + "/" + name + ".png", view.w, view.h, view.rgb, 1.0f, &err) != Result::Success)
            fail_msg("%s", err.c_str());
    }
    return renderOnly(b, s, w, h);
}

// f(p, wo) at q x q points of pixel (x, y)'s footprint on the floor y = 0 (wo: towards the
// camera): their mean and standard deviation (centres of a q x q grid), their minimum and
// maximum over a grid that includes the pixel's edges and corners.
struct Footprint {
    double mean, min, max, sd;
    // The standard error of the mean of n uniform samples of the footprint: what the jitter
    // alone gives the oracle's pixel (also where its own estimate is 0 because no sample met
    // a sliver of light).
    double se(uint32_t n) const { return sd / std::sqrt(double(n)); }
};
Footprint footprint(const rtpbr_gltf_camera &c, uint32_t x, uint32_t y, uint32_t W, uint32_t H, int q,
                    const std::function<double(glm::dvec3, glm::dvec3)> &f) {
    glm::dvec3 o(c.position[0], c.position[1], c.position[2]);
    Footprint fp{0.0, 1e300, -1e300, 0.0};
    double sq = 0.0;
    for (int edges = 0; edges < 2; edges++)
        for (int i = 0; i < q; i++)
            for (int j = 0; j < q; j++) {
                float sx = edges ? float(i) / float(q - 1) : (float(i) + 0.5f) / float(q);
                float sy = edges ? float(j) / float(q - 1) : (float(j) + 0.5f) / float(q);
                glm::dvec3 d(cameraRay(c, float(x) + sx, float(y) + sy, W, H));
                if (!(d.y < 0.0))
                    fail_msg("pixel (%u, %u) sees above the horizon: choose another camera", x, y);
                glm::dvec3 p = o - (o.y / d.y) * d;
                double v = f(p, -d);
                if (edges) {
                    fp.min = std::min(fp.min, v);
                    fp.max = std::max(fp.max, v);
                } else {
                    fp.mean += v / double(q * q);
                    sq += v * v / double(q * q);
                }
            }
    fp.sd = std::sqrt(std::max(0.0, sq - fp.mean * fp.mean));
    return fp;
}

// The largest |pixel - reference| / (its standard error) that expectPixel met since the last
// report, printed by the tests.
double gWorstZ = 0.0;
double worstZ() {
    double z = gWorstZ;
    gWorstZ = 0.0;
    return z;
}

// Pixel (x, y), channel c, against its footprint's mean: within 5 standard errors (the
// oracle's, or the jitter's predicted one where larger) plus rounding.
void expectPixel(const Image &img, uint32_t x, uint32_t y, int c, double ref, double predictedSe, const char *what) {
    double v = img.v(x, y, c), e = std::max(img.e(x, y, c), predictedSe);
    if (e > 0.0)
        gWorstZ = std::max(gWorstZ, std::fabs(v - ref) / e);
    if (!(std::fabs(v - ref) <= 5.0 * e + kRounding * std::fabs(ref) + 1e-12))
        fail_msg("%s: pixel (%u, %u) channel %d: %.7g vs closed form %.7g (standard error %.3g)", what, x, y, c, v, ref,
                 e);
}

// ---- directional ---------------------------------------------------------------------------

// Every pixel shows a/pi E cos(theta): the same for every point, so exact (the jitter moves
// the point, not the value), with and without bounces and shadows.
void test_directional_lambert(void **) {
    const Light L{RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, glm::dvec3(0.0), glm::normalize(glm::dvec3(0.4, -1.0, -0.3)), 3.0};
    const double expected = kAlbedo / kPi * L.intensity * glm::dot(kUp, -L.direction);
    for (int mode = 0; mode < 3; mode++) {
        SceneBuilder b;
        floorPlane(b, lambertMaterial(b, kAlbedo));
        addLight(b, L);
        b.camera(glm::vec3(0.3f, 1.5f, 2.0f), glm::vec3(0.0f), 0.8f);
        RenderSettings s;
        s.spp = 4;
        s.directOnly = mode == 0;
        s.noShadows = mode == 2;
        const char *names[3] = {"directional-direct", "directional-multi", "directional-noshadows"};
        Image img = renderImage(b, s, 12, 12, names[mode]);
        for (uint32_t y = 0; y < img.h; y++)
            for (uint32_t x = 0; x < img.w; x++)
                for (int c = 0; c < 3; c++)
                    if (!(std::fabs(img.v(x, y, c) - expected) <= 1e-6 * expected))
                        fail_msg("mode %d: pixel (%u, %u): %.8g, a/pi E cos = %.8g", mode, x, y, img.v(x, y, c),
                                 expected);
    }
    std::printf("directional: every pixel a/pi E cos = %.6f\n", expected);
    // Light from below the floor (which faces up): nothing.
    SceneBuilder b;
    floorPlane(b, lambertMaterial(b, kAlbedo));
    const glm::dvec3 up = glm::normalize(glm::dvec3(0.2, 1.0, 0.1));
    addLight(b, Light{RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, glm::dvec3(0.0), up, 3.0});
    b.camera(glm::vec3(0.3f, 1.5f, 2.0f), glm::vec3(0.0f), 0.8f);
    RenderSettings s;
    s.spp = 2;
    Image img = renderImage(b, s, 8, 8, "directional-from-below");
    for (float v : img.rgb)
        assert_true(v == 0.0f);
}

// ---- point, range, spot --------------------------------------------------------------------

constexpr uint32_t kN = 16; // image size of the point and spot scenes

// A Lambert floor under the lights, seen from a camera above: each pixel against its
// footprint's mean of the lights' sum (closed forms of true points: a sphere wholly above the
// floor's horizon is one, below). Returns the number of pixels whose footprint gets no light
// at all (each of them exactly 0).
int checkLambertFloor(const std::vector<Light> &lights, RenderSettings s, glm::vec3 camPos, glm::vec3 camTarget,
                      float yfov, glm::vec3 upHint, const char *what, const char *name) {
    SceneBuilder b;
    floorPlane(b, lambertMaterial(b, kAlbedo));
    for (const Light &L : lights)
        addLight(b, L);
    b.camera(camPos, camTarget, yfov, upHint);
    Image img = renderImage(b, s, kN, kN, name);
    auto f = [&lights](glm::dvec3 p, glm::dvec3) {
        double sum = 0.0;
        for (const Light &L : lights)
            sum += lambert(L, p, kUp, kAlbedo);
        return sum;
    };
    int dark = 0;
    double lo = 1e300, hi = 0.0, sum = 0.0, ref = 0.0, var = 0.0; // over the lit pixels, channel 0
    for (uint32_t y = 0; y < kN; y++)
        for (uint32_t x = 0; x < kN; x++) {
            Footprint fp = footprint(b.cameras[0], x, y, kN, kN, 16, f);
            if (fp.max == 0.0) { // the whole footprint unlit: exactly nothing, not merely little
                dark++;
                for (int c = 0; c < 3; c++)
                    if (img.v(x, y, c) != 0.0)
                        fail_msg("%s: pixel (%u, %u) lies wholly outside the light and shows %.3g", what, x, y,
                                 img.v(x, y, c));
                continue;
            }
            lo = std::min(lo, fp.mean);
            hi = std::max(hi, fp.mean);
            for (int c = 0; c < 3; c++)
                expectPixel(img, x, y, c, fp.mean, fp.se(s.spp), what);
            sum += img.v(x, y);
            ref += fp.mean;
            var += img.e(x, y) * img.e(x, y);
        }
    std::printf("%s: %d pixels exactly 0, the others from %.4g to %.4g, largest |z| %.2f; their sum %+.2e "
                "relative, %.2f se\n", what, dark, lo, hi, worstZ(), sum / ref - 1.0, (sum - ref) / std::sqrt(var));
    // The sum finds a bias too small for any one pixel (a sphere's BSDF-ray share of 10%
    // without its range window: 2% of each pixel, 6 standard errors of the sum).
    EXPECT_AGREE(sum, std::sqrt(var), ref, 0.0, 4.0, kRounding * ref);
    return dark;
}

void test_point_lambert(void **) {
    const Light L{RTPBR_GLTF_PUNCTUAL_POINT, glm::dvec3(0.2, 0.7, -0.1), glm::dvec3(0, 0, -1), 2.0};
    for (int mode = 0; mode < 2; mode++) {
        RenderSettings s;
        s.spp = 64;
        s.directOnly = mode == 0;
        int dark = checkLambertFloor({L}, s, glm::vec3(0.0f, 1.6f, 1.8f), glm::vec3(0.0f), 0.9f, glm::vec3(0, 1, 0),
                                     mode == 0 ? "point, direct only" : "point, multi-bounce",
                                     mode == 0 ? "point-direct" : "point-multi");
        assert_int_equal(dark, 0);
    }
}

// The window clamp(1 - (d / range)^4, 0, 1): exactly 0 beyond the range.
void test_point_range(void **) {
    Light L{RTPBR_GLTF_PUNCTUAL_POINT, glm::dvec3(0.1, 0.5, 0.0), glm::dvec3(0, 0, -1), 2.0};
    L.range = 1.0; // reaches the floor out to a radius of 0.87
    RenderSettings s;
    s.spp = 64;
    s.directOnly = true;
    int dark = checkLambertFloor({L}, s, glm::vec3(0.0f, 2.0f, 0.3f), glm::vec3(0.0f), 1.0f, glm::vec3(0, 1, 0),
                                 "point with range 1", "point-range");
    assert_true(dark >= 40);
}

void test_spot(void **) {
    // Straight down from 1 above the floor: lit out to a radius of tan(0.45) = 0.48, at full
    // strength within tan(0.25) = 0.26.
    Light L{RTPBR_GLTF_PUNCTUAL_SPOT, glm::dvec3(0.03, 1.0, -0.02), glm::dvec3(0, -1, 0), 3.0};
    L.inner = 0.25;
    L.outer = 0.45;
    RenderSettings s;
    s.spp = 64;
    s.directOnly = true;
    const glm::vec3 camPos(0.0f, 2.0f, 0.0f), camTarget(0.0f), up(0, 0, -1);
    const float yfov = 0.75f;
    int dark = checkLambertFloor({L}, s, camPos, camTarget, yfov, up, "spot", "spot");
    assert_true(dark >= 40);
    // The three zones counted, and inside the inner cone the spot is the point light.
    SceneBuilder b;
    floorPlane(b, lambertMaterial(b, kAlbedo));
    b.camera(camPos, camTarget, yfov, up);
    Light P = L;
    P.type = RTPBR_GLTF_PUNCTUAL_POINT;
    addLight(b, L);
    Image img = renderImage(b, s, kN, kN, "spot-zones");
    auto angle = [&L](glm::dvec3 p, glm::dvec3) {
        return std::acos(glm::clamp(glm::dot(L.direction, glm::normalize(p - L.position)), -1.0, 1.0));
    };
    auto point = [&P](glm::dvec3 p, glm::dvec3) { return lambert(P, p, kUp, kAlbedo); };
    int inner = 0, between = 0;
    for (uint32_t y = 0; y < kN; y++)
        for (uint32_t x = 0; x < kN; x++) {
            Footprint a = footprint(b.cameras[0], x, y, kN, kN, 16, angle);
            if (a.max < L.inner) {
                inner++;
                Footprint fp = footprint(b.cameras[0], x, y, kN, kN, 16, point);
                expectPixel(img, x, y, 0, fp.mean, fp.se(s.spp), "spot's inner cone");
            } else if (a.min > L.inner && a.max < L.outer) {
                between++;
                // Strictly dimmer than the point light there (the falloff is < 1).
                double pt = footprint(b.cameras[0], x, y, kN, kN, 16, point).mean;
                if (!(img.v(x, y) < pt - 5.0 * img.e(x, y)))
                    fail_msg("pixel (%u, %u) between the cones: %.5g, not below the point light's %.5g", x, y,
                             img.v(x, y), pt);
            }
        }
    std::printf("spot: %d pixels inside the inner cone (largest |z| against the point light %.2f), %d wholly between "
                "the cones\n", inner, worstZ(), between);
    assert_true(inner >= 9);
    assert_true(between >= 9);
    // Turned away from the floor (up): nothing behind the spot's cone, however wide.
    SceneBuilder away;
    floorPlane(away, lambertMaterial(away, kAlbedo));
    away.camera(camPos, camTarget, yfov, up);
    away.punctual(RTPBR_GLTF_PUNCTUAL_SPOT, glm::vec3(L.position), glm::vec3(0, 1, 0), glm::vec3(3.0f), 0.0f, 1.2f,
                  1.5707963f);
    for (float v : renderImage(away, s, 8, 8, "spot-away").rgb)
        assert_true(v == 0.0f);
}

// ---- shadows -------------------------------------------------------------------------------

// The camera of the shadow scenes: below the occluder at 0.5, looking down at the floor.
void shadowCamera(SceneBuilder &b) { b.camera(glm::vec3(0.0f, 0.45f, 0.9f), glm::vec3(0.0f), 0.6f); }

void test_point_shadow(void **) {
    // A point light 1 above the floor over a 0.4 x 0.4 occluder at height 0.5: the umbra is
    // the square |x|, |z| < 0.4 on the floor (no penumbra: the light has no size).
    const Light L{RTPBR_GLTF_PUNCTUAL_POINT, glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0, 0, -1), 1.5};
    auto unshadowed = [&L](glm::dvec3 p, glm::dvec3) { return lambert(L, p, kUp, kAlbedo); };
    auto umbra = [](glm::dvec3 p, glm::dvec3) { return std::max(std::fabs(p.x), std::fabs(p.z)) - 0.4; };
    for (int noShadows = 0; noShadows < 2; noShadows++) {
        SceneBuilder b;
        floorPlane(b, lambertMaterial(b, kAlbedo));
        occluder(b, 0.5, 0.0, 0.0, 0.2);
        addLight(b, L);
        shadowCamera(b);
        RenderSettings s;
        s.spp = 32;
        s.directOnly = true;
        s.noShadows = noShadows == 1;
        Image img = renderImage(b, s, kN, kN, noShadows ? "point-shadow-off" : "point-shadow");
        int inside = 0, outside = 0;
        for (uint32_t y = 0; y < kN; y++)
            for (uint32_t x = 0; x < kN; x++) {
                Footprint u = footprint(b.cameras[0], x, y, kN, kN, 8, umbra);
                Footprint fp = footprint(b.cameras[0], x, y, kN, kN, 16, unshadowed);
                const double ref = fp.mean;
                if (u.max < 0.0) {
                    inside++;
                    if (noShadows)
                        expectPixel(img, x, y, 0, ref, fp.se(s.spp), "in the umbra without shadows");
                    else if (img.v(x, y) != 0.0)
                        fail_msg("pixel (%u, %u) in the umbra: %.4g (unshadowed %.4g)", x, y, img.v(x, y), ref);
                } else if (u.min > 0.0) {
                    outside++;
                    expectPixel(img, x, y, 0, ref, fp.se(s.spp), "outside the umbra");
                }
            }
        std::printf("point shadow%s: %d pixels in the umbra, %d outside, largest |z| %.2f\n",
                    noShadows ? " (no shadows)" : "", inside, outside, worstZ());
        assert_true(inside >= 20);
        assert_true(outside >= 20);
    }
}

void test_directional_shadow(void **) {
    // An occluder 10^4 up the light's direction, 10^4 wide: its shadow covers the floor in view,
    // reached only by a shadow ray that goes (far enough) towards infinity.
    const Light L{RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, glm::dvec3(0.0), glm::normalize(glm::dvec3(0.2, -1.0, 0.1)), 2.0};
    const double t = 1e4 / -L.direction.y;
    const glm::dvec3 c = -t * L.direction; // above the origin along the light's way
    const double expected = kAlbedo / kPi * L.intensity * glm::dot(kUp, -L.direction);
    for (int noShadows = 0; noShadows < 2; noShadows++) {
        SceneBuilder b;
        floorPlane(b, lambertMaterial(b, kAlbedo));
        occluder(b, c.y, c.x, c.z, 5e3);
        addLight(b, L);
        shadowCamera(b);
        RenderSettings s;
        s.spp = 4;
        s.noShadows = noShadows == 1;
        Image img = renderImage(b, s, 8, 8, noShadows ? "directional-shadow-off" : "directional-shadow");
        for (uint32_t y = 0; y < img.h; y++)
            for (uint32_t x = 0; x < img.w; x++) {
                double want = noShadows ? expected : 0.0;
                if (!(std::fabs(img.v(x, y) - want) <= 1e-6 * expected))
                    fail_msg("directional%s: pixel (%u, %u) %.7g, expected %.7g", noShadows ? " without shadows" : "",
                             x, y, img.v(x, y), want);
            }
    }
}

// ---- GGX -----------------------------------------------------------------------------------

void test_ggx_directional(void **) {
    const double roughness = 0.6, alpha = roughness * roughness;
    const glm::dvec3 f0(0.95, 0.64, 0.54);
    // The formula written above against the shader library's (a cross-check of the test itself).
    for (glm::dvec3 wi : {glm::dvec3(0.3, 0.2, 0.93), glm::dvec3(-0.6, 0.1, 0.79), glm::dvec3(0.1, -0.7, 0.7)})
        for (glm::dvec3 wo : {glm::dvec3(-0.2, 0.1, 0.97), glm::dvec3(0.5, -0.4, 0.77)}) {
            wi = glm::normalize(wi);
            wo = glm::normalize(wo);
            rtpbr::FresnelParams F = rtpbr::Fresnel_FromF0(glm::vec3(f0));
            glm::vec3 lib = rtpbr::BRDF_SpecularLocal(glm::vec3(wo), glm::vec3(wi), float(alpha), float(alpha), F) *
                            float(wi.z);
            for (int c = 0; c < 3; c++) {
                double mine = ggxReflectance(glm::dvec3(0, 0, 1), wo, wi, alpha, f0[c]);
                if (!(std::fabs(mine - lib[c]) <= 1e-4 * mine))
                    fail_msg("GGX closed form %.7g vs BRDF_SpecularLocal %.7g", mine, double(lib[c]));
            }
        }
    const Light L{RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, glm::dvec3(0.0), glm::normalize(glm::dvec3(-0.3, -1.0, 0.4)), 2.0};
    double mean[2] = {0.0, 0.0};
    for (int walk = 0; walk < 2; walk++) {
        SceneBuilder b;
        floorPlane(b, b.material(glm::vec3(f0), 1.0f, float(roughness)));
        addLight(b, L);
        b.camera(glm::vec3(0.0f, 1.0f, 1.5f), glm::vec3(0.0f, 0.0f, 0.2f), 0.7f);
        RenderSettings s;
        s.spp = 64;
        s.directOnly = true;
        s.singleScatter = walk == 0;
        const uint32_t n = 12;
        Image img = renderImage(b, s, n, n, walk ? "ggx-walk" : "ggx-single");
        double lo = 1e300, hi = 0.0;
        for (uint32_t y = 0; y < n; y++)
            for (uint32_t x = 0; x < n; x++) {
                mean[walk] += img.v(x, y) / double(n * n);
                if (walk)
                    continue;
                for (int c = 0; c < 3; c++) {
                    auto f = [&](glm::dvec3, glm::dvec3 wo) {
                        return L.intensity * ggxReflectance(kUp, wo, -L.direction, alpha, f0[c]);
                    };
                    Footprint fp = footprint(b.cameras[0], x, y, n, n, 16, f);
                    lo = std::min(lo, fp.mean);
                    hi = std::max(hi, fp.mean);
                    expectPixel(img, x, y, c, fp.mean, fp.se(s.spp), "GGX, single scattering");
                }
            }
        if (!walk)
            std::printf("GGX (alpha %.2f) single scattering: pixels from %.4g to %.4g, largest |z| %.2f\n", alpha, lo,
                        hi, worstZ());
    }
    // The walk adds the orders >= 2 (a cross-check, not a reference).
    std::printf("GGX image mean, red: single scattering %.5f, random walk %.5f\n", mean[0], mean[1]);
    assert_true(mean[1] > mean[0]);
}

// ---- multi-bounce --------------------------------------------------------------------------

// A white floor and a white wall z = -2 (facing +z, 8 wide, 4 high) under a point light
// 1 above the origin, with a black shade 0.8 x 0.8 just under the light at height 0.8: the
// floor |x|, |z| < 2 lies in the shade's shadow, the wall is lit in full.
struct Room {
    SceneBuilder b;
    static constexpr double kWhite = 0.9, kShadeY = 0.8, kShadeR = 0.4, kWallZ = -2.0;
    Light light{RTPBR_GLTF_PUNCTUAL_POINT, glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0, 0, -1), 4.0};

    Room() {
        uint32_t white = lambertMaterial(b, float(kWhite));
        b.polygon({{-4, 0, 4}, {4, 0, 4}, {4, 0, -2}, {-4, 0, -2}}, white);
        b.polygon({{-4, 0, -2}, {4, 0, -2}, {4, 4, -2}, {-4, 4, -2}}, white);
        occluder(b, kShadeY, 0.0, 0.0, kShadeR);
        addLight(b, light);
        b.camera(glm::vec3(0.0f, 0.5f, 3.0f), glm::vec3(0.0f, 0.0f, 0.0f), 0.4f);
    }

    // Does the segment a -> b cross the shade?
    static bool shaded(glm::dvec3 a, glm::dvec3 b) {
        if ((a.y - kShadeY) * (b.y - kShadeY) >= 0.0)
            return false;
        glm::dvec3 p = a + (kShadeY - a.y) / (b.y - a.y) * (b - a);
        return std::fabs(p.x) < kShadeR && std::fabs(p.z) < kShadeR;
    }

    // Radiance of floor point p after exactly two scattering events: the wall's direct
    // radiance integrated over the wall (midpoint rule, n x n/2 cells).
    double twoBounce(glm::dvec3 p, int n) const {
        const glm::dvec3 nWall(0, 0, 1);
        double sum = 0.0, cell = (8.0 / n) * (4.0 / (n / 2));
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n / 2; j++) {
                glm::dvec3 q(-4.0 + 8.0 * (i + 0.5) / n, 4.0 * (j + 0.5) / (n / 2), kWallZ);
                if (shaded(q, light.position) || shaded(p, q))
                    continue;
                glm::dvec3 d = q - p;
                double r2 = glm::dot(d, d);
                glm::dvec3 w = d / std::sqrt(r2);
                double g = std::max(0.0, glm::dot(kUp, w)) * std::max(0.0, -glm::dot(nWall, w)) / r2;
                sum += lambert(light, q, nWall, kWhite) * g * cell;
            }
        return kWhite / kPi * sum;
    }
};

void test_multibounce_point(void **) {
    Room room;
    const uint32_t n = 16, x0 = 6, y0 = 6, x1 = 10, y1 = 10; // the middle pixels see the floor in shadow
    double unlitCheck = 0.0;
    for (uint32_t y = y0; y < y1; y++)
        for (uint32_t x = x0; x < x1; x++) {
            auto inShadow = [&room](glm::dvec3 p, glm::dvec3) {
                return Room::shaded(p, room.light.position) ? 0.0 : 1.0;
            };
            unlitCheck += footprint(room.b.cameras[0], x, y, n, n, 6, inShadow).max;
        }
    assert_true(unlitCheck == 0.0);
    Image img[3];
    const uint32_t depths[3] = {1, 2, 16};
    for (int k = 0; k < 3; k++) {
        RenderSettings s;
        s.spp = k == 0 ? 16 : 1024;
        s.maxDepth = depths[k];
        s.region = {x0, y0, x1, y1};
        const char *names[3] = {"room-depth1", "room-depth2", "room-depth16"};
        img[k] = renderImage(room.b, s, n, n, names[k]);
    }
    double sumImg = 0.0, sumRef = 0.0, sumVar = 0.0, sumDeep = 0.0, varDeep = 0.0;
    for (uint32_t y = y0; y < y1; y++)
        for (uint32_t x = x0; x < x1; x++) {
            if (img[0].v(x, y) != 0.0)
                fail_msg("pixel (%u, %u): the floor in the shade's shadow shows %.4g with direct light only", x, y,
                         img[0].v(x, y));
            auto f = [&room](glm::dvec3 p, glm::dvec3) { return room.twoBounce(p, 160); };
            double ref = footprint(room.b.cameras[0], x, y, n, n, 3, f).mean;
            expectPixel(img[1], x, y, 0, ref, 0.0, "two scattering events");
            sumImg += img[1].v(x, y);
            sumVar += img[1].e(x, y) * img[1].e(x, y);
            sumRef += ref;
            sumDeep += img[2].v(x, y);
            varDeep += img[2].e(x, y) * img[2].e(x, y);
        }
    const double m = (x1 - x0) * (y1 - y0);
    std::printf("multi-bounce, floor in shadow: direct 0, two events %.5f (se %.2g) vs the wall integral %.5f "
                "(per pixel: largest |z| %.2f), 16 events %.5f (se %.2g)\n",
                sumImg / m, std::sqrt(sumVar) / m, sumRef / m, worstZ(), sumDeep / m, std::sqrt(varDeep) / m);
    EXPECT_AGREE(sumImg / m, std::sqrt(sumVar) / m, sumRef / m, 0.0, 3.0, 1e-3 * sumRef / m);
    assert_true(sumRef / m > 1e-3);
    // More bounces only add light (floor -> wall -> floor ...).
    assert_true(sumDeep / m > sumImg / m + 3.0 * std::sqrt(sumVar + varDeep) / m);
}

// ---- the sun's disk (a directional light's angular_diameter) --------------------------------

// A directional light of angular diameter d: the cap of half-angle d / 2 around towardLight,
// radiance E / (pi sin^2(d / 2)) (rtpbr_gltf_punctual_light.angular_diameter).
void addSun(SceneBuilder &b, glm::dvec3 towardLight, double E, double diameter) {
    b.punctual(RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, glm::vec3(0.0f), -glm::vec3(towardLight), glm::vec3(float(E)));
    b.punctualLights.back().angular_diameter = float(diameter);
}

double sunRadiance(double E, double diameter) {
    const double s = std::sin(0.5 * diameter);
    return E / (kPi * s * s);
}

// The integral of g(w) over the cap of half-angle a around the unit vector c, in double, by
// the midpoint rule on rings x sectors cells of equal solid angle (1 - cos theta and phi
// uniform).
template <class G>
auto capIntegral(glm::dvec3 c, double a, int rings, int sectors, const G &g) -> decltype(g(c)) {
    glm::dvec3 t = glm::normalize(glm::cross(std::fabs(c.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), c));
    glm::dvec3 b = glm::cross(c, t);
    const double sh = std::sin(0.5 * a), oneMinusCosA = 2.0 * sh * sh;
    const double cell = 2.0 * kPi * oneMinusCosA / (double(rings) * sectors);
    decltype(g(c)) sum(0.0);
    for (int i = 0; i < rings; i++) {
        const double u = (i + 0.5) / rings * oneMinusCosA; // 1 - cos theta
        const double cosT = 1.0 - u, sinT = std::sqrt(u * (2.0 - u));
        for (int j = 0; j < sectors; j++) {
            const double phi = 2.0 * kPi * (j + 0.5) / sectors;
            sum += g(cosT * c + sinT * (std::cos(phi) * t + std::sin(phi) * b));
        }
    }
    return sum * cell;
}

// Every pixel of img (channels 0..2, spp samples each) against one value, on a scene where
// every pixel's samples have one distribution (grey light and surfaces: the channels are one
// estimate, counted once): each pixel within 5 pooled standard errors (the pixels' mean
// variance) and the image mean within 3 of its own. A pixel's own standard error is no
// measure here: by the balance heuristic a BSDF ray that finds the disk adds about one light
// sample's worth (f cos L / (pdf_bsdf + pdf_disk) ~ f cos E), a rare event for a small disk
// (probability ~ sin^2 a cos theta per sample: 2e-5 for the sun), which a pixel's samples
// rarely show; so both bounds also allow two such events (2 ref / samples).
void expectUniformImage(const Image &img, double ref, uint32_t spp, const char *what) {
    double sum = 0.0, var = 0.0;
    for (uint32_t y = 0; y < img.h; y++)
        for (uint32_t x = 0; x < img.w; x++)
            var += img.e(x, y) * img.e(x, y);
    const double n = double(img.w) * img.h, pooled = std::sqrt(var / n);
    for (uint32_t y = 0; y < img.h; y++)
        for (uint32_t x = 0; x < img.w; x++) {
            for (int c = 0; c < 3; c++) {
                const double v = img.v(x, y, c);
                if (!(std::fabs(v - ref) <= 5.0 * pooled + (2.0 / spp + kRounding) * ref))
                    fail_msg("%s: pixel (%u, %u) channel %d: %.7g vs %.7g (pooled standard error %.3g)", what, x, y,
                             c, v, ref, pooled);
            }
            sum += img.v(x, y);
        }
    const double mean = sum / n, se = std::sqrt(var) / n;
    std::printf("%s: mean %.7g vs %.7g (relative error %+.2e, %.2f se)\n", what, mean, ref, mean / ref - 1.0,
                se > 0.0 ? (mean - ref) / se : 0.0);
    EXPECT_AGREE(mean, se, ref, 0.0, 3.0, (2.0 / (n * spp) + kRounding) * ref);
}

// A Lambert floor under a sun wholly above its horizon: a/pi E cos(theta), as under a delta
// light (a uniform cap's irradiance is pi L sin^2 a cos theta = E cos theta), for the sun's
// 0.53 degrees and wide disks; angular diameter 0 is the delta light (exact); 1e-6 and 1e-30
// (a = 5e-31, sin^2 a = 2.5e-61: the disk's constants fit only a double) stay finite, a delta
// light in all but name. Direct lighting (the cap sampled, MIS against the BSDF rays that
// escape into it), all bounces and noShadows (the BSDF rays' disk found without a shadow ray).
void test_sun_lambert(void **) {
    struct Case {
        double theta, azimuth, diameter;
    };
    const Case cases[] = {{0.0, 0.0, 0.3},  {0.7, 0.4, 0.00925}, {0.7, 0.4, 0.0},
                          {1.2, 2.0, 0.4}, {0.45, -1.0, 1e-6}, {0.3, 2.5, 1e-30}};
    const double E = 3.0;
    for (const Case &k : cases) {
        const glm::dvec3 toward(std::sin(k.theta) * std::cos(k.azimuth), std::cos(k.theta),
                                std::sin(k.theta) * std::sin(k.azimuth));
        const double expected = kAlbedo / kPi * E * std::cos(k.theta);
        for (int mode = 0; mode < 3; mode++) {
            SceneBuilder b;
            floorPlane(b, lambertMaterial(b, kAlbedo));
            addSun(b, toward, E, k.diameter);
            b.camera(glm::vec3(0.3f, 1.5f, 2.0f), glm::vec3(0.0f), 0.8f);
            RenderSettings s;
            s.spp = 128;
            s.directOnly = mode == 0;
            s.noShadows = mode == 2;
            Image img = renderImage(b, s, 12, 12, "sun-lambert");
            char what[160];
            std::snprintf(what, sizeof what, "sun %.3g rad at %.2f rad from the zenith, %s", k.diameter, k.theta,
                          mode == 0 ? "direct" : mode == 1 ? "multi-bounce" : "no shadows");
            if (k.diameter == 0.0) { // the delta light, exactly
                for (float v : img.rgb)
                    if (!(std::fabs(v - expected) <= 1e-6 * expected))
                        fail_msg("%s: pixel %.8g, a/pi E cos = %.8g", what, double(v), expected);
                std::printf("%s: every pixel %.7g (exact)\n", what, expected);
                continue;
            }
            expectUniformImage(img, expected, s.spp, what);
        }
    }
}

// A sun straddling the floor's horizon (half-angle 0.1 rad, its centre between 0.06 below
// and 0.07 above it): only the part above lights the floor, against a/pi L times the
// quadrature of max(0, cos) over the cap; wholly below: exactly 0.
void test_sun_horizon(void **) {
    const double E = 2.0, diameter = 0.2, a = 0.5 * diameter, L = sunRadiance(E, diameter);
    auto cosUp = [](glm::dvec3 w) { return std::max(0.0, w.y); };
    // The quadrature against the closed form where the cap is wholly above the horizon.
    const glm::dvec3 high = glm::normalize(glm::dvec3(0.6, 0.5, 0.2));
    const double qHigh = L * capIntegral(high, a, 400, 800, cosUp);
    std::printf("quadrature check, cap above the horizon: %.9g vs E cos = %.9g\n", qHigh, E * high.y);
    assert_true(std::fabs(qHigh - E * high.y) <= 1e-6 * E * high.y);
    for (double elevation : {-0.06, 0.0, 0.07, -0.12}) {
        const glm::dvec3 toward(std::cos(elevation) * 0.8, std::sin(elevation), std::cos(elevation) * -0.6);
        const double irr = L * capIntegral(toward, a, 400, 800, cosUp);
        const double expected = kAlbedo / kPi * irr;
        for (int mode = 0; mode < 2; mode++) {
            SceneBuilder b;
            floorPlane(b, lambertMaterial(b, kAlbedo));
            addSun(b, toward, E, diameter);
            b.camera(glm::vec3(0.3f, 1.5f, 2.0f), glm::vec3(0.0f), 0.8f);
            RenderSettings s;
            s.spp = 1024;
            s.directOnly = mode == 0;
            Image img = renderImage(b, s, 12, 12, "sun-horizon");
            char what[160];
            std::snprintf(what, sizeof what, "sun's centre %.2f rad above the horizon (half-angle %.2f), %s",
                          elevation, a, mode == 0 ? "direct" : "multi-bounce");
            if (elevation < -a) {
                for (float v : img.rgb)
                    assert_true(v == 0.0f);
                std::printf("%s: every pixel 0\n", what);
                continue;
            }
            std::printf("  irradiance %.6g of E = %.6g\n", irr, E);
            expectUniformImage(img, expected, s.spp, what);
        }
    }
}

// What a light with a size is, seen from a point: the cone (cap) of half-angle halfAngle
// around axis, of uniform radiance.
struct SeenCone {
    glm::dvec3 axis;
    double halfAngle, radiance;
};

// A GGX conductor floor (single scattering, direct light) seeing a light's reflection: the
// camera, 2 from the origin, sees at its image's centre the mirror image of the direction
// `toward` (0, sin 0.6, -cos 0.6). Each pixel against the footprint mean (4 x 4 points) of L
// times the quadrature over the light's cone seen from the floor point (cone(p)) of f cos, f
// the shader library's BRDF_SpecularLocal; the image mean of each channel within 3 standard
// errors; the highlight in view.
const glm::dvec3 kGgxToward(0.0, std::sin(0.6), -std::cos(0.6));
void checkGgxFloor(double roughness, float yfov, const std::function<void(SceneBuilder &)> &addLights,
                   const std::function<SeenCone(glm::dvec3)> &cone, const char *name, const char *what) {
    const glm::dvec3 f0(0.95, 0.64, 0.54);
    const rtpbr::FresnelParams F = rtpbr::Fresnel_FromF0(glm::vec3(f0));
    const float alpha = float(roughness * roughness);
    SceneBuilder b;
    floorPlane(b, b.material(glm::vec3(f0), 1.0f, float(roughness)));
    addLights(b);
    const glm::vec3 camPos = 2.0f * glm::vec3(0.0f, float(kGgxToward.y), float(-kGgxToward.z));
    b.camera(camPos, glm::vec3(0.0f), yfov);
    RenderSettings s;
    s.spp = 1024;
    s.directOnly = true;
    s.singleScatter = true;
    const uint32_t n = 12;
    Image img = renderImage(b, s, n, n, name);
    // Reflected radiance at p towards wo (world; the floor's local frame: z = +y).
    auto local = [](glm::dvec3 w) { return glm::vec3(float(w.x), float(-w.z), float(w.y)); };
    auto reflected = [&](glm::dvec3 p, glm::dvec3 wo) {
        const glm::vec3 woL = local(wo);
        const SeenCone c = cone(p);
        return c.radiance * capIntegral(c.axis, c.halfAngle, 48, 96, [&](glm::dvec3 wi) {
                   const glm::vec3 wiL = local(wi);
                   return glm::dvec3(rtpbr::BRDF_SpecularLocal(woL, wiL, alpha, alpha, F) * wiL.z);
               });
    };
    // Per channel: sums of pixels and of the references, the pixels' variance.
    glm::dvec3 sum(0.0), ref(0.0), var(0.0);
    double hi = 0.0;
    for (uint32_t y = 0; y < n; y++)
        for (uint32_t x = 0; x < n; x++) {
            // The footprint mean of each channel (4 x 4 points), and the jitter's spread.
            const int q = 4;
            glm::dvec3 mean(0.0), sq(0.0);
            const glm::dvec3 o(camPos);
            for (int i = 0; i < q; i++)
                for (int j = 0; j < q; j++) {
                    const float sx = float(x) + (i + 0.5f) / q, sy = float(y) + (j + 0.5f) / q;
                    const glm::dvec3 d(cameraRay(b.cameras[0], sx, sy, n, n));
                    const glm::dvec3 p = o - (o.y / d.y) * d;
                    const glm::dvec3 v = reflected(p, glm::normalize(o - p));
                    mean += v / double(q * q);
                    sq += v * v / double(q * q);
                }
            for (int c = 0; c < 3; c++) {
                const double sd = std::sqrt(std::max(0.0, sq[c] - mean[c] * mean[c]));
                expectPixel(img, x, y, c, mean[c], sd / std::sqrt(double(s.spp)), what);
                sum[c] += img.v(x, y, c);
                var[c] += img.e(x, y, c) * img.e(x, y, c);
                ref[c] += mean[c];
                hi = std::max(hi, mean[c]);
            }
        }
    const double m = double(n) * n, L = cone(glm::dvec3(0.0)).radiance;
    std::printf("%s, roughness %.2f (L %.5g): pixels up to %.5g (F0 L = %.5g); largest |z| %.2f\n", what, roughness, L,
                hi, f0.x * L, worstZ());
    for (int c = 0; c < 3; c++) {
        std::printf("  channel %d: image mean %.6g vs quadrature %.6g (relative %+.2e, %.2f se)\n", c, sum[c] / m,
                    ref[c] / m, sum[c] / ref[c] - 1.0, (sum[c] - ref[c]) / std::sqrt(var[c]));
        EXPECT_AGREE(sum[c] / m, std::sqrt(var[c]) / m, ref[c] / m, 0.0, 3.0, 1e-3 * ref[c] / m);
    }
    assert_true(hi > 5.0 * ref.x / m); // the highlight is in view
}

// The sun's reflection in GGX: roughness 0.05 (alpha 0.0025) under the sun's 0.53 degrees: the
// highlight is the sun's blurred image, found as often by BSDF sampling as by sampling the
// disk (MIS); roughness 0.3 under a 0.1 rad disk.
void test_sun_ggx(void **) {
    struct Case {
        double roughness, diameter;
        float yfov;
    };
    const Case cases[] = {{0.05, 0.00925, 0.05f}, {0.3, 0.1, 0.6f}};
    const double E = 2.0;
    for (const Case &k : cases) {
        const SeenCone sun{kGgxToward, 0.5 * k.diameter, sunRadiance(E, k.diameter)};
        char what[80];
        std::snprintf(what, sizeof what, "GGX under the sun of %.3g rad", k.diameter);
        checkGgxFloor(
            k.roughness, k.yfov, [&](SceneBuilder &b) { addSun(b, kGgxToward, E, k.diameter); },
            [&](glm::dvec3) { return sun; }, k.roughness < 0.1 ? "sun-ggx-005" : "sun-ggx-03", what);
    }
}

// ---- a point light's sphere (rtpbr_gltf_punctual_light.radius) --------------------------------

// The sphere's radiance I / (pi r^2).
double sphereRadiance(const Light &L) { return L.intensity / (kPi * L.radius * L.radius); }

// A sphere wholly above a Lambert floor's horizon (its centre higher than its radius) is, on
// the floor, the point light of its intensity: the cone of half-angle s, sin s = r / d, gives
// the irradiance pi L sin^2 s cos(theta) = I cos(theta) / d^2 (its exact form factor), times
// W(d). Three spheres (one almost touching the floor), direct lighting (the cone sampled, MIS
// against the BSDF rays that meet the sphere), all bounces and noShadows; tiny radii (1e-6,
// and 1e-30, whose radiance and cone density fit only a double) stay finite, the point light
// in all but name. A sphere occludes nothing: a point light above one lights the floor
// through it. (Radius 0, the delta light, exact: test_point_lambert.) 256 samples a pixel: a
// BSDF ray meets the sphere with probability ~ its cone's projected solid angle / pi (~0.1
// here), an event a pixel must see often enough for its standard error to mean something
// (at 64 samples one pixel in a few hundred is 5 of its standard errors off).
void test_sphere_lambert(void **) {
    struct Case {
        glm::dvec3 centre;
        double radius;
    };
    const Case cases[] = {{{0.2, 0.7, -0.1}, 0.3}, {{-0.3, 0.5, 0.2}, 0.45}, {{0.1, 0.6, 0.0}, 1e-6},
                          {{0.0, 0.8, 0.1}, 1e-30}};
    for (const Case &k : cases) {
        Light L{RTPBR_GLTF_PUNCTUAL_POINT, k.centre, glm::dvec3(0, 0, -1), 2.0};
        L.radius = k.radius;
        const int modes = k.radius > 1e-3 ? 3 : 1;
        for (int mode = 0; mode < modes; mode++) {
            RenderSettings s;
            s.spp = 256;
            s.directOnly = mode == 0;
            s.noShadows = mode == 2;
            char what[160];
            std::snprintf(what, sizeof what, "sphere of radius %.3g at height %.2f, %s", k.radius, k.centre.y,
                          mode == 0 ? "direct" : mode == 1 ? "multi-bounce" : "no shadows");
            assert_int_equal(checkLambertFloor({L}, s, glm::vec3(0.0f, 1.6f, 1.8f), glm::vec3(0.0f), 0.9f,
                                               glm::vec3(0, 1, 0), what, "sphere-lambert"),
                             0);
        }
    }
    Light sphere{RTPBR_GLTF_PUNCTUAL_POINT, glm::dvec3(0.0, 0.5, 0.0), glm::dvec3(0, 0, -1), 1.5};
    sphere.radius = 0.3;
    const Light above{RTPBR_GLTF_PUNCTUAL_POINT, glm::dvec3(0.05, 1.2, 0.0), glm::dvec3(0, 0, -1), 1.0};
    RenderSettings s;
    s.spp = 256;
    s.directOnly = true;
    checkLambertFloor({sphere, above}, s, glm::vec3(0.0f, 0.9f, 1.0f), glm::vec3(0.0f), 0.9f, glm::vec3(0, 1, 0),
                      "a point light above a sphere, through it", "sphere-transparent");
}

// The form factor of the cone of half-angle s (sin^2 s = s2) around the unit vector axis on a
// surface of normal +y, clipped by its horizon: the shader library's exact closed form (Snyder
// 1996), checked against quadrature below.
double capFormFactor(glm::dvec3 axis, double s2) {
    const glm::dvec3 F = axis * s2;
    return double(rtpbr::LTC_SphereCapFormFactor(glm::vec3(float(F.x), float(F.z), float(F.y))));
}

// A sphere straddling the floor's horizon (radius 0.4, its centre 0.15 above the floor, then
// 0.1 below it): a floor point outside it sees the part of its cone above the horizon, a/pi pi
// L FF with FF the horizon-clipped cap's form factor; a point inside it sees it in every
// direction: a L. Pixels whose footprint straddles the sphere's edge are left out.
void test_sphere_horizon(void **) {
    const double r = 0.4, I = 2.0;
    // The closed form against quadrature at points outside, the cap straddling the horizon.
    for (glm::dvec3 toCentre : {glm::dvec3(0.6, 0.1, 0.2), glm::dvec3(-0.3, -0.15, 0.5), glm::dvec3(0.0, 0.3, 0.45)}) {
        const double d = glm::length(toCentre), sinS = r / d;
        const glm::dvec3 axis = toCentre / d;
        const double q = capIntegral(axis, std::asin(sinS), 400, 800, [](glm::dvec3 w) { return std::max(0.0, w.y); });
        const double ff = kPi * capFormFactor(axis, sinS * sinS);
        std::printf("horizon-clipped cap (sin s %.3f, axis %.2f above the horizon): closed form %.8f, quadrature "
                    "%.8f\n", sinS, axis.y, ff, q);
        assert_true(std::fabs(ff - q) <= 1e-5 * q);
    }
    for (double height : {0.15, -0.1}) {
        Light L{RTPBR_GLTF_PUNCTUAL_POINT, glm::dvec3(0.1, height, -0.05), glm::dvec3(0, 0, -1), I};
        L.radius = r;
        const double Le = sphereRadiance(L);
        auto edge = [&L](glm::dvec3 p, glm::dvec3) { return glm::length(L.position - p) - L.radius; };
        auto reflected = [&L, Le](glm::dvec3 p, glm::dvec3) {
            const glm::dvec3 toCentre = L.position - p;
            const double d = glm::length(toCentre);
            if (d <= L.radius)
                return kAlbedo * Le;
            return kAlbedo * Le * capFormFactor(toCentre / d, (L.radius / d) * (L.radius / d));
        };
        for (int mode = 0; mode < 2; mode++) {
            SceneBuilder b;
            floorPlane(b, lambertMaterial(b, kAlbedo));
            addLight(b, L);
            b.camera(glm::vec3(0.0f, 1.2f, 1.3f), glm::vec3(0.0f), 1.0f);
            RenderSettings s;
            s.spp = 256;
            s.directOnly = mode == 0;
            Image img = renderImage(b, s, kN, kN, height > 0.0 ? "sphere-horizon-above" : "sphere-horizon-below");
            char what[160];
            std::snprintf(what, sizeof what, "sphere's centre %.2f above the floor (radius %.1f), %s", height, r,
                          mode == 0 ? "direct" : "multi-bounce");
            int inside = 0, outside = 0;
            double sum = 0.0, ref = 0.0, var = 0.0; // the pixels outside, channel 0
            for (uint32_t y = 0; y < kN; y++)
                for (uint32_t x = 0; x < kN; x++) {
                    const Footprint e = footprint(b.cameras[0], x, y, kN, kN, 8, edge);
                    if (e.max < 0.0) {
                        inside++;
                        // Every BSDF ray sees the sphere: a L, exactly.
                        for (int c = 0; c < 3; c++)
                            if (!(std::fabs(img.v(x, y, c) - kAlbedo * Le) <= 1e-5 * kAlbedo * Le))
                                fail_msg("%s: pixel (%u, %u) inside the sphere: %.7g, a L = %.7g", what, x, y,
                                         img.v(x, y, c), kAlbedo * Le);
                    } else if (e.min > 0.0) {
                        outside++;
                        const Footprint fp = footprint(b.cameras[0], x, y, kN, kN, 16, reflected);
                        for (int c = 0; c < 3; c++)
                            expectPixel(img, x, y, c, fp.mean, fp.se(s.spp), what);
                        sum += img.v(x, y);
                        ref += fp.mean;
                        var += img.e(x, y) * img.e(x, y);
                    }
                }
            std::printf("%s: %d pixels inside (a L = %.5g exactly), %d outside: largest |z| %.2f, their sum %+.2e "
                        "relative, %.2f se\n", what, inside, kAlbedo * Le, outside, worstZ(), sum / ref - 1.0,
                        (sum - ref) / std::sqrt(var));
            assert_true(inside >= 4);
            assert_true(outside >= 100);
        }
    }
}

// A sphere's reflection in GGX (checkGgxFloor; the sphere 2 from the origin in the direction
// the camera sees mirrored): roughness 0.05 (alpha 0.0025) under a sphere of angular radius
// 0.01 (found as often by BSDF sampling as by sampling the cone: MIS), roughness 0.3 under one
// of 0.1.
void test_sphere_ggx(void **) {
    struct Case {
        double roughness, radius;
        float yfov;
    };
    const Case cases[] = {{0.05, 0.02, 0.05f}, {0.3, 0.2, 0.6f}};
    for (const Case &k : cases) {
        Light L{RTPBR_GLTF_PUNCTUAL_POINT, 2.0 * kGgxToward, glm::dvec3(0, 0, -1), 3.0};
        L.radius = k.radius;
        auto cone = [&L](glm::dvec3 p) {
            const glm::dvec3 toCentre = L.position - p;
            const double d = glm::length(toCentre);
            return SeenCone{toCentre / d, std::asin(L.radius / d), sphereRadiance(L)};
        };
        char what[80];
        std::snprintf(what, sizeof what, "GGX under a sphere of radius %.2f at 2", k.radius);
        checkGgxFloor(
            k.roughness, k.yfov, [&L](SceneBuilder &b) { addLight(b, L); }, cone,
            k.roughness < 0.1 ? "sphere-ggx-005" : "sphere-ggx-03", what);
    }
}

// A sphere's shadow (radius 0.1, 1 above the floor, over the shade of test_point_shadow): a
// floor point whose every line to the sphere crosses the shade (its cone's edge, 64
// directions, crosses the shade's plane inside it, 0.01 from its edges: the cone's section and
// the square are convex) is exactly 0: no light sample passes the shade and no BSDF ray meets
// the sphere before it. With noShadows the same pixels show the unshadowed sphere, the point
// light's closed form, within the standard error of the rare event that a pixel's own samples
// may not show: a BSDF ray meets this small sphere with probability at most sin^2 s (~0.01),
// each time adding about the pixel's value (by the balance heuristic, as a light sample does).
void test_sphere_shadow(void **) {
    Light L{RTPBR_GLTF_PUNCTUAL_POINT, glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0, 0, -1), 1.5};
    L.radius = 0.1;
    const double shadeY = 0.5, shadeR = 0.2;
    auto umbra = [&](glm::dvec3 p, glm::dvec3) {
        const glm::dvec3 toCentre = L.position - p;
        const double d = glm::length(toCentre), sinS = L.radius / d, cosS = std::sqrt(1.0 - sinS * sinS);
        const glm::dvec3 axis = toCentre / d;
        const glm::dvec3 t = glm::normalize(glm::cross(axis, glm::dvec3(1, 0, 0))), b = glm::cross(axis, t);
        double worst = -1e300; // the largest max-norm of an edge direction's crossing, minus the shade's
        for (int k = 0; k < 64; k++) {
            const double phi = 2.0 * kPi * k / 64.0;
            const glm::dvec3 w = cosS * axis + sinS * (std::cos(phi) * t + std::sin(phi) * b);
            const glm::dvec3 q = p + (shadeY / w.y) * w;
            worst = std::max(worst, std::max(std::fabs(q.x), std::fabs(q.z)) - (shadeR - 0.01));
        }
        return worst;
    };
    auto unshadowed = [&L](glm::dvec3 p, glm::dvec3) { return lambert(L, p, kUp, kAlbedo); };
    for (int noShadows = 0; noShadows < 2; noShadows++) {
        SceneBuilder b;
        floorPlane(b, lambertMaterial(b, kAlbedo));
        occluder(b, shadeY, 0.0, 0.0, shadeR);
        addLight(b, L);
        shadowCamera(b);
        RenderSettings s;
        s.spp = 256;
        s.directOnly = true;
        s.noShadows = noShadows == 1;
        Image img = renderImage(b, s, kN, kN, noShadows ? "sphere-shadow-off" : "sphere-shadow");
        int inside = 0;
        for (uint32_t y = 0; y < kN; y++)
            for (uint32_t x = 0; x < kN; x++) {
                if (!(footprint(b.cameras[0], x, y, kN, kN, 8, umbra).max < 0.0))
                    continue;
                inside++;
                Footprint fp = footprint(b.cameras[0], x, y, kN, kN, 16, unshadowed);
                const double sin2 = L.radius * L.radius; // sin^2 s = r^2 / d^2, d >= 1 on the floor
                if (noShadows)
                    expectPixel(img, x, y, 0, fp.mean, std::max(fp.se(s.spp), fp.mean * std::sqrt(sin2 / s.spp)),
                                "in the sphere's umbra without shadows");
                else if (img.v(x, y) != 0.0)
                    fail_msg("pixel (%u, %u) in the sphere's umbra: %.4g (unshadowed %.4g)", x, y, img.v(x, y),
                             fp.mean);
            }
        std::printf("sphere shadow%s: %d pixels in the umbra, largest |z| %.2f\n", noShadows ? " (no shadows)" : "",
                    inside, worstZ());
        assert_true(inside >= 12);
    }
}

// The range window W(d), d from the shading point to the sphere's centre, scales the sphere's
// radiance: wholly above the horizon the floor gets I W(d) cos / d^2, the point light's, and
// exactly 0 beyond the range (0.87 from the centre's foot).
void test_sphere_range(void **) {
    Light L{RTPBR_GLTF_PUNCTUAL_POINT, glm::dvec3(0.1, 0.5, 0.0), glm::dvec3(0, 0, -1), 2.0};
    L.range = 1.0;
    L.radius = 0.2;
    for (int mode = 0; mode < 2; mode++) {
        RenderSettings s;
        s.spp = 256;
        s.directOnly = mode == 0;
        int dark = checkLambertFloor({L}, s, glm::vec3(0.0f, 2.0f, 0.3f), glm::vec3(0.0f), 1.0f, glm::vec3(0, 1, 0),
                                     mode == 0 ? "sphere of radius 0.2 with range 1, direct"
                                               : "sphere of radius 0.2 with range 1, multi-bounce",
                                     "sphere-range");
        assert_true(dark >= 40);
    }
}

// ---- validation ----------------------------------------------------------------------------

void expectRejected(const std::function<void(rtpbr_gltf_punctual_light &)> &spoil, Result want, const char *words) {
    SceneBuilder b;
    floorPlane(b, lambertMaterial(b, kAlbedo));
    b.punctual(RTPBR_GLTF_PUNCTUAL_SPOT, glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1.0f), 0.0f, 0.2f, 0.5f);
    b.camera(glm::vec3(0, 1, 2), glm::vec3(0.0f), 0.8f);
    spoil(b.punctualLights[0]);
    b.build();
    RenderSettings s;
    std::string err;
    Result r = validateScene(b.scene, s, &err);
    std::printf("  %s: %s\n", resultString(r), err.c_str());
    if (r != want || err.find(words) == std::string::npos)
        fail_msg("expected %s with \"%s\", got %s: %s", resultString(want), words, resultString(r), err.c_str());
}

void test_validation(void **) {
    using P = rtpbr_gltf_punctual_light;
    const float nan = std::nanf("");
    expectRejected([](P &) {}, Result::Success, "");
    expectRejected([nan](P &p) { p.position[1] = nan; }, Result::InvalidScene, "punctual light 0 (spot): position");
    expectRejected([](P &p) { p.position[0] = 1e16f; }, Result::InvalidScene, "scene extent");
    expectRejected([](P &p) { p.direction[1] = -0.5f; }, Result::InvalidScene, "direction");
    expectRejected([nan](P &p) { p.direction[0] = nan; }, Result::InvalidScene, "direction");
    expectRejected([](P &p) { p.intensity[2] = -1.0f; }, Result::InvalidScene, "intensity");
    expectRejected([](P &p) { p.intensity[0] = INFINITY; }, Result::InvalidScene, "intensity");
    expectRejected([](P &p) { p.range = -1.0f; }, Result::InvalidScene, "range");
    expectRejected([](P &p) { p.inner_cone_angle = 0.6f; }, Result::InvalidScene, "cone angles");
    // Equal angles: the file's doubles may round to one float; the falloff stays finite.
    expectRejected([](P &p) { p.inner_cone_angle = 0.5f; }, Result::Success, "");
    expectRejected([](P &p) { p.outer_cone_angle = 1.6f; }, Result::InvalidScene, "cone angles");
    expectRejected([](P &p) { p.inner_cone_angle = -0.1f; }, Result::InvalidScene, "cone angles");
    expectRejected([](P &p) { p.type = rtpbr_gltf_punctual_type(7); }, Result::InvalidScene, "unknown type 7");
    // A point light's direction and a directional light's position and range are not used.
    expectRejected([](P &p) { p.type = RTPBR_GLTF_PUNCTUAL_POINT, p.direction[1] = 0.0f; }, Result::Success, "");
    expectRejected([nan](P &p) { p.type = RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, p.position[0] = nan, p.range = -1.0f; },
                   Result::Success, "");
    // The sun's disk: a directional light's angular diameter in [0, pi/2); none on the others.
    auto directional = [](P &p, float d) { p.type = RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, p.angular_diameter = d; };
    expectRejected([&](P &p) { directional(p, 0.00925f); }, Result::Success, "");
    expectRejected([&](P &p) { directional(p, 1e-30f); }, Result::Success, "");
    expectRejected([&](P &p) { directional(p, 1.5707963f); }, Result::Success, "");
    expectRejected([&](P &p) { directional(p, 1.5707964f); }, Result::InvalidScene, "angular diameter");
    expectRejected([&](P &p) { directional(p, -0.01f); }, Result::InvalidScene, "angular diameter");
    expectRejected([&](P &p) { directional(p, nan); }, Result::InvalidScene, "angular diameter");
    expectRejected([&](P &p) { directional(p, INFINITY); }, Result::InvalidScene, "angular diameter");
    expectRejected([](P &p) { p.angular_diameter = 0.01f; }, Result::InvalidScene,
                   "punctual light 0 (spot): angular diameter");
    expectRejected([](P &p) { p.type = RTPBR_GLTF_PUNCTUAL_POINT, p.angular_diameter = 0.01f; }, Result::InvalidScene,
                   "punctual light 0 (point): angular diameter");
    // A point light's sphere: radius >= 0 and finite; none on the others.
    auto point = [](P &p, float r) { p.type = RTPBR_GLTF_PUNCTUAL_POINT, p.radius = r; };
    expectRejected([&](P &p) { point(p, 0.3f); }, Result::Success, "");
    expectRejected([&](P &p) { point(p, 1e-30f); }, Result::Success, "");
    expectRejected([&](P &p) { point(p, -0.1f); }, Result::InvalidScene, "punctual light 0 (point): radius -0.1");
    expectRejected([&](P &p) { point(p, nan); }, Result::InvalidScene, "punctual light 0 (point): radius nan");
    expectRejected([&](P &p) { point(p, INFINITY); }, Result::InvalidScene, "radius inf is negative or not finite");
    expectRejected([](P &p) { p.radius = 0.2f; }, Result::InvalidScene,
                   "punctual light 0 (spot): radius 0.2: only a point light has one");
    expectRejected([nan](P &p) { p.radius = nan; }, Result::InvalidScene, "punctual light 0 (spot): radius nan");
    expectRejected([](P &p) { p.type = RTPBR_GLTF_PUNCTUAL_DIRECTIONAL, p.radius = 1.0f; }, Result::InvalidScene,
                   "punctual light 0 (directional): radius 1");
    // A point light's capsule (test_capsule_light.cpp): length >= 0 and finite, only with a
    // radius > 0, a unit axis, both ends within the scene extent.
    auto capsule = [](P &p, float length) {
        p.type = RTPBR_GLTF_PUNCTUAL_POINT, p.radius = 0.15f, p.length = length;
        p.axis[0] = 1.0f, p.axis[1] = p.axis[2] = 0.0f;
    };
    expectRejected([&](P &p) { capsule(p, 0.8f); }, Result::Success, "");
    expectRejected([&](P &p) { capsule(p, -0.5f); }, Result::InvalidScene, "punctual light 0 (point): length -0.5");
    expectRejected([&](P &p) { capsule(p, nan); }, Result::InvalidScene, "length nan");
    expectRejected([&](P &p) { capsule(p, INFINITY); }, Result::InvalidScene, "length inf");
    expectRejected([&](P &p) { capsule(p, 0.8f), p.radius = 0.0f; }, Result::InvalidScene,
                   "(point): length 0.8: only a point light with a radius > 0");
    expectRejected([&](P &p) { capsule(p, 0.8f), p.radius = 0.0f, p.type = RTPBR_GLTF_PUNCTUAL_SPOT; },
                   Result::InvalidScene, "(spot): length 0.8: only a point light with a radius > 0");
    expectRejected([&](P &p) { capsule(p, 0.8f), p.axis[0] = 0.5f; }, Result::InvalidScene, "capsule axis (0.5, 0, 0)");
    expectRejected([&](P &p) { capsule(p, 0.8f), p.axis[1] = nan; }, Result::InvalidScene, "capsule axis");
    expectRejected([&](P &p) { capsule(p, 3e15f); }, Result::InvalidScene, "beyond the oracle's scene extent");
    // No length: the axis is not used (a hand-built light may leave it 0).
    expectRejected([&](P &p) { capsule(p, 0.0f), p.axis[0] = 0.0f; }, Result::Success, "");
    // Only black lights: nothing to render.
    expectRejected([](P &p) { p.intensity[0] = p.intensity[1] = p.intensity[2] = 0.0f; }, Result::NoLights,
                   "KHR_lights_punctual");
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_directional_lambert), cmocka_unit_test(test_point_lambert),
                cmocka_unit_test(test_point_range), cmocka_unit_test(test_spot), cmocka_unit_test(test_point_shadow),
                cmocka_unit_test(test_directional_shadow), cmocka_unit_test(test_ggx_directional),
                cmocka_unit_test(test_multibounce_point), cmocka_unit_test(test_sun_lambert),
                cmocka_unit_test(test_sun_horizon), cmocka_unit_test(test_sun_ggx),
                cmocka_unit_test(test_sphere_lambert), cmocka_unit_test(test_sphere_horizon),
                cmocka_unit_test(test_sphere_ggx), cmocka_unit_test(test_sphere_shadow),
                cmocka_unit_test(test_sphere_range),
                cmocka_unit_test(test_validation))
