// The shader library's per-light evaluation (shaderlib/rtpbr/area_light.h) in its C++ build,
// through a host bridge of its own: a white Lambertian surface (KHR specular 0, so the
// specular lobe's scale is 0 whatever the tables hold) under a square light must give the
// square's form factor in closed form (Howell's catalogue, C-10: a parallel rectangle on the
// normal), and nothing where the light cannot reach. The same surface under punctual lights
// (RTPBR_AREA_LIGHT_PUNCTUAL 1: AreaLight_Add dispatching on Host_LightShape) gives their
// closed forms from KHR_lights_punctual's text: I cos / (pi d^2) x window x cone falloff.
#include "rtpbr/lang.h"
#include "rtpbr/config.h"

#include <cmath>

using rtpbr::float2;
using rtpbr::float3;
using rtpbr::float4;
using rtpbr::uint;

namespace {
// The light: a square of half-size h at height d above the origin, facing down (or up).
float g_half = 1.0f, g_height = 2.0f;
bool g_faceDown = true, g_twoSided = false;
// A punctual light instead (shape != 0): its position (w = 1 / range^2), direction and cone.
uint g_shape = 0u;
float4 g_position(0.0f);
float3 g_direction(0.0f, 0.0f, -1.0f);
float2 g_cone(-2.0f, 1.0f);
} // namespace

uint Host_LightShape(uint) { return g_shape; }
float4 Host_LightPosition(uint) { return g_position; }
float3 Host_LightDirection(uint) { return g_direction; }
float2 Host_LightSpotCone(uint) { return g_cone; }

uint Host_LightVertexCount(uint) { return 4u; }
float3 Host_LightVertex(uint, uint k) {
    const float sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    // counter-clockwise seen from below when the light faces down
    float y = g_faceDown ? -sy[k] : sy[k];
    return float3(sx[k] * g_half, y * g_half, g_height);
}
float4 Host_LightPlane(uint) { return g_faceDown ? float4(0, 0, -1, g_height) : float4(0, 0, 1, -g_height); }
// (a sphere light's: the sphere itself, g_sphere, when its radius is set)
float4 g_sphere(0.0f);
float4 Host_LightSphere(uint) { return g_sphere.w > 0.0f ? g_sphere : float4(0, 0, g_height, g_half * std::sqrt(2.0f)); }
bool Host_LightTwoSided(uint) { return g_twoSided; }
float3 Host_LightRadiance(uint) { return float3(1.0f); }
float3 Host_LightVisibility(uint) { return float3(1.0f); }
float4 Host_TableLtc1(int, float2) { return float4(1, 0, 0, 1); }
float4 Host_TableLtc2(int, float2) { return float4(1, 0, 0, 0); }
float2 Host_TableE_EF(float, float, float) { return float2(1.0f); }
float Host_TableE(float, float) { return 1.0f; }
float Host_TableEavg(float) { return 1.0f; }
float Host_TableEFavg(float, float) { return 1.0f; }
float Host_TableSheenE(float, float) { return 0.0f; }

#define RTPBR_AREA_LIGHT_PUNCTUAL 1
#define RTPBR_AREA_LIGHT_SPHERES 1
#include "rtpbr/area_light.h"

#include <cstdarg>
#include <cstddef>
#include <csetjmp>
extern "C" {
#include "test_main.h"
}

namespace {
float lambert_radiance(bool sphere = false) {
    rtpbr::MaterialInputs m{};
    m.model = rtpbr::RTPBR_MATERIAL_MODEL_METALLIC_ROUGHNESS;
    m.baseColor = float3(1.0f);
    m.roughness = 0.5f;
    m.ior = 1.5f;
    m.specularFactor = 0.0f;
    m.specularColor = float3(1.0f);
    m.disney = rtpbr::Disney_DefaultMaterial();
    float3 N(0, 0, 1), V = glm::normalize(float3(0.3f, 0.0f, 1.0f));
    rtpbr::ShadingSurface s = rtpbr::Surface_Resolve(rtpbr::Material_Resolve(m), glm::dot(N, V), float3(0.0f));
    float3 L;
    if (sphere) { // AreaLight_AddSphere, as a host's loop over its spheres calls it
        rtpbr::AreaLightPixel px = rtpbr::AreaLight_Begin(s, N, V);
        rtpbr::AreaLightSum acc = rtpbr::AreaLight_SumBegin();
        rtpbr::AreaLight_AddSphere(px, acc, s, float3(0.0f), N, 0u);
        L = rtpbr::AreaLight_End(px, acc, s, float3(0.0f));
    } else {
        L = rtpbr::AreaLight_Evaluate(s, float3(0.0f), N, V, 0u);
    }
    assert_true(L.x == L.y && L.y == L.z);
    return L.x;
}

// The form factor from a point to a parallel square of half-size h at distance d centred on
// its normal: (2 / pi) * 2 X / sqrt(1 + X^2) atan(X / sqrt(1 + X^2)), X = h / d.
double square_form_factor(double h, double d) {
    double X = h / d, s = std::sqrt(1.0 + X * X);
    return 4.0 / M_PI * X / s * std::atan(X / s);
}

void test_lambert_closed_form(void **) {
    g_faceDown = true;
    g_twoSided = false;
    const float cases[][2] = {{1.0f, 2.0f}, {1.0f, 0.25f}, {0.05f, 3.0f}, {4.0f, 1.0f}};
    for (const auto &c : cases) {
        g_half = c[0];
        g_height = c[1];
        double expect = square_form_factor(c[0], c[1]), got = lambert_radiance();
        print_message("half %g height %g: %.7f (closed form %.7f)\n", c[0], c[1], got, expect);
        assert_true(std::fabs(got - expect) <= 2e-5 * expect);
    }
}

void test_no_light_where_it_cannot_reach(void **) {
    g_half = 1.0f;
    g_height = 2.0f;
    g_faceDown = false; // one-sided, facing away from the point
    g_twoSided = false;
    assert_true(lambert_radiance() == 0.0f);
    g_twoSided = true; // both faces emit: the same as facing the point
    double expect = square_form_factor(1.0, 2.0);
    assert_true(std::fabs(lambert_radiance() - expect) <= 2e-5 * expect);
    g_height = -2.0f; // below the horizon
    g_faceDown = false;
    assert_true(lambert_radiance() == 0.0f);
}

// The white Lambertian surface at the origin under punctual lights against the closed forms.
void test_punctual_closed_form(void **) {
    const double pi = 3.14159265358979323846;
    // point light at (0.3, -0.2, 2): cos / (pi d^2)
    g_shape = RTPBR_PUNCTUAL_POINT;
    g_position = float4(0.3f, -0.2f, 2.0f, 0.0f);
    g_cone = float2(-2.0f, 1.0f);
    double d2 = 0.09 + 0.04 + 4.0, expect = 2.0 / std::sqrt(d2) / (pi * d2);
    double got = lambert_radiance();
    print_message("point: %.7f (closed form %.7f)\n", got, expect);
    assert_true(std::fabs(got - expect) <= 1e-5 * expect);
    // its range: the window 1 - (d / range)^4 at range 2.5; beyond the range, nothing
    g_position.w = 1.0f / (2.5f * 2.5f);
    double q = d2 / 6.25, windowed = expect * (1.0 - q * q);
    got = lambert_radiance();
    print_message("point, range 2.5: %.7f (closed form %.7f)\n", got, windowed);
    assert_true(std::fabs(got - windowed) <= 1e-5 * windowed);
    g_position.w = 1.0f / (2.0f * 2.0f);
    assert_true(lambert_radiance() == 0.0f);
    g_position.w = 0.0f;
    // below the horizon: nothing
    g_position = float4(0.3f, -0.2f, -2.0f, 0.0f);
    assert_true(lambert_radiance() == 0.0f);
    // a spot straight above, pointing down, cones 0.1 and 0.3: the point's value inside the
    // inner cone, nothing outside the outer one, the falloff t^2 between
    g_shape = RTPBR_PUNCTUAL_SPOT;
    g_position = float4(0.0f, 0.0f, 2.0f, 0.0f);
    const double inner = 0.1, outer = 0.3;
    g_cone = rtpbr::Punctual_SpotCone(float(inner), float(outer));
    const float tilts[] = {0.0f, 0.15f, 0.25f, 0.35f}; // the spot's axis turned away from the point
    for (float tilt : tilts) {
        g_direction = float3(std::sin(tilt), 0.0f, -std::cos(tilt));
        double t = (std::cos(double(tilt)) - std::cos(outer)) / (std::cos(inner) - std::cos(outer));
        t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
        double spot = 1.0 / (pi * 4.0) * t * t;
        got = lambert_radiance();
        print_message("spot tilted %.2f: %.7f (closed form %.7f)\n", tilt, got, spot);
        assert_true(std::fabs(got - spot) <= 1e-5 * spot + 1e-9);
    }
    // a directional light of illuminance 1 at 60 degrees: cos 60 / pi
    g_shape = RTPBR_PUNCTUAL_DIRECTIONAL;
    g_direction = float3(-std::sin(1.0471976f), 0.0f, -std::cos(1.0471976f));
    expect = 0.5 / pi;
    got = lambert_radiance();
    print_message("directional: %.7f (closed form %.7f)\n", got, expect);
    assert_true(std::fabs(got - expect) <= 1e-5 * expect);
    g_shape = 0u;
}

// The white Lambertian surface at the origin under a sphere light of radiance 1 (RTPBR_AREA_
// LIGHT_SPHERES: AreaLight_AddSphere): its form factor (r / d)^2 cos(theta) wholly above the
// horizon; the horizon-clipped cap's where the horizon cuts it, against a midpoint quadrature
// in double here; 1 inside it; nothing below the horizon; its range window.
double cap_quadrature(double cx, double cy, double cz, double r) {
    double d = std::sqrt(cx * cx + cy * cy + cz * cz), a = std::asin(r / d);
    double c[3] = {cx / d, cy / d, cz / d}, t1[3] = {1, 0, 0};
    if (std::fabs(c[0]) > 0.9) t1[0] = 0, t1[1] = 1;
    double dt = t1[0] * c[0] + t1[1] * c[1] + t1[2] * c[2];
    for (int k = 0; k < 3; ++k) t1[k] -= dt * c[k];
    double tl = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (int k = 0; k < 3; ++k) t1[k] /= tl;
    double t2[3] = {c[1] * t1[2] - c[2] * t1[1], c[2] * t1[0] - c[0] * t1[2], c[0] * t1[1] - c[1] * t1[0]};
    const int n = 800;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        double t = (i + 0.5) * a / n;
        for (int j = 0; j < n; ++j) {
            double phi = (j + 0.5) * 2.0 * M_PI / n;
            double z = std::cos(t) * c[2] + std::sin(t) * (std::cos(phi) * t1[2] + std::sin(phi) * t2[2]);
            if (z > 0.0) sum += z * std::sin(t);
        }
    }
    return sum * (a / n) * (2.0 * M_PI / n) / M_PI;
}

void test_sphere_closed_form(void **) {
    g_shape = 0u;
    g_position = float4(0.0f); // no range
    struct {
        float x, y, z, r;
    } cases[] = {{0.3f, -0.2f, 2.0f, 0.5f}, {1.5f, 0.0f, 0.8f, 0.3f}, {0.0f, 0.0f, 10.0f, 0.01f},
                 {0.6f, 0.1f, 0.2f, 0.4f},  {1.0f, 0.0f, -0.1f, 0.4f}};
    for (const auto &c : cases) {
        g_sphere = float4(c.x, c.y, c.z, c.r);
        double d2 = double(c.x) * c.x + double(c.y) * c.y + double(c.z) * c.z, d = std::sqrt(d2);
        double expect = c.z / d > c.r / d ? double(c.r) * c.r / d2 * (c.z / d) : cap_quadrature(c.x, c.y, c.z, c.r);
        double got = lambert_radiance(true);
        print_message("sphere (%g, %g, %g) r %g: %.7f (expected %.7f)\n", c.x, c.y, c.z, c.r, got, expect);
        assert_true(std::fabs(got - expect) <= 2e-5 * expect + 1e-9);
    }
    g_sphere = float4(0.2f, 0.1f, 0.3f, 1.0f); // the point inside: every direction is the light
    assert_true(std::fabs(lambert_radiance(true) - 1.0) <= 1e-6);
    g_sphere = float4(0.2f, 0.1f, -1.0f, 0.5f); // wholly below the horizon
    assert_true(lambert_radiance(true) == 0.0f);
    g_sphere = float4(0.3f, -0.2f, 2.0f, 0.5f); // a range of 2.5 from its centre: the window
    g_position.w = 1.0f / (2.5f * 2.5f);
    double d2 = 0.09 + 0.04 + 4.0, q = d2 / 6.25;
    double expect = 0.25 / d2 * (2.0 / std::sqrt(d2)) * (1.0 - q * q), got = lambert_radiance(true);
    print_message("sphere, range 2.5: %.7f (expected %.7f)\n", got, expect);
    assert_true(std::fabs(got - expect) <= 2e-5 * expect);
    g_position.w = 0.0f;
    g_sphere = float4(0.0f);
}
} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_lambert_closed_form),
                cmocka_unit_test(test_no_light_where_it_cannot_reach),
                cmocka_unit_test(test_punctual_closed_form),
                cmocka_unit_test(test_sphere_closed_form))
