// A point light's capsule in the oracle (issue 30, tube lights): a KHR_lights_punctual point
// light of radius r > 0 and length L > 0 (rtpbr_gltf_punctual_light.radius, .length, .axis) is
// the segment position +- axis L / 2 swept by the ball of radius r, of uniform radiance
// L_e W(d), L_e = 2 I / (pi r (2 r + L)), W at the distance d to its centre. Held to
// references written here:
//   - the shape itself (CapsuleShape): area samples lie on the surface with their normals, the
//     cylinder's share is its area's; a sample faces a point outside iff the ray from the point
//     meets the capsule first there (the facing test the oracle uses is the exact visibility of
//     a convex body: no front-facing point is hidden by another part of it);
//   - a Lambert floor under a horizontal capsule: each point against a double-precision
//     quadrature of L_e cos_receiver cos_light / d^2 over the capsule's surface points visible
//     from it (n.(x_receiver - x) > 0), with direct light, all bounces, noShadows and a range;
//   - L -> 0: the sphere's closed form, I cos / d^2 on the floor (the sphere wholly above it),
//     for L = 0 (the sphere's own sampling), 1e-6 and 1e-3;
//   - capsules straddling the floor's horizon (horizontal and tilted): the quadrature of the
//     part above it (no leak from the part below, nothing missing from the part above); wholly
//     below: exactly 0; a floor point inside a capsule: a L_e exactly (every BSDF ray sees it);
//   - from glTF: the loader's capsule (axis the node's +X) rendered as the quadrature says.
// (Bad capsules refused by validateScene: test_punctual_light.cpp, test_validation.)
// A point's radiance is a 1 x 1 image whose camera looks at it from close by with a field of
// view of 1e-3 rad, as in test_disk_light.cpp; the references are taken where the oracle's rays
// leave the floor, 1e-4 (1 + |p|_inf) above the point.
#include "test_common.h"

#include "oracle.h"
#include "quadrature.hpp" // gauss_legendre
#include "scene_builder.h"

#include <functional>
#include <random>

using namespace rtpbr_oracle;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kAlbedo = 0.8f;

struct Capsule {
    glm::dvec3 centre, axis; // axis unit
    double r, length, I;     // I: intensity (grey)
    double range = 0.0;
};

// L_e = 2 I / (pi r (2 r + L)) (power 4 pi I over the area 2 pi r (2 r + L)).
double capsuleRadiance(const Capsule &C) { return 2.0 * C.I / (kPi * C.r * (2.0 * C.r + C.length)); }

// KHR_lights_punctual's recommended window clamp(1 - (d / range)^4, 0, 1).
double window(double d, double range) {
    if (!(range > 0.0))
        return 1.0;
    const double q = d / range;
    return std::min(1.0, std::max(0.0, 1.0 - q * q * q * q));
}

// The integral over C's surface points y visible from x (a convex body: n.(x - y) > 0) of
// g(wi) cos_light / d^2 dA (wi, d: direction and distance from x to y): Gauss-Legendre over the
// cylinder (along the axis x around it, dA = r dz dphi) and over each hemispherical cap (polar
// angle from the cap's axis x azimuth, dA = r^2 sin(theta) dtheta dphi).
double capsuleIntegral(const Capsule &C, glm::dvec3 x, int n1, int n2, const std::function<double(glm::dvec3)> &g) {
    std::vector<double> ax, aw, px, pw;
    gauss_legendre(n1, ax, aw);
    gauss_legendre(n2, px, pw);
    const glm::dvec3 u = C.axis;
    const glm::dvec3 t = glm::normalize(glm::cross(std::fabs(u.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), u));
    const glm::dvec3 b = glm::cross(u, t);
    const double h = 0.5 * C.length;
    auto at = [&](glm::dvec3 y, glm::dvec3 n) {
        const glm::dvec3 toY = y - x;
        const double d2 = glm::dot(toY, toY), d = std::sqrt(d2);
        const double cosL = -glm::dot(n, toY) / d;
        return cosL > 0.0 ? g(toY / d) * cosL / d2 : 0.0;
    };
    double sum = 0.0;
    for (int i = 0; i < n1 && h > 0.0; i++) {
        const double z = h * (2.0 * ax[i] - 1.0);
        for (int j = 0; j < n2; j++) {
            const double phi = 2.0 * kPi * px[j];
            const glm::dvec3 n = std::cos(phi) * t + std::sin(phi) * b;
            sum += aw[i] * pw[j] * at(C.centre + z * u + C.r * n, n) * C.r * (2.0 * h) * (2.0 * kPi);
        }
    }
    for (double side : {1.0, -1.0}) {
        const glm::dvec3 e = C.centre + side * h * u;
        for (int i = 0; i < n1; i++) {
            const double theta = 0.5 * kPi * ax[i];
            for (int j = 0; j < n2; j++) {
                const double phi = 2.0 * kPi * px[j];
                const glm::dvec3 n = std::sin(theta) * (std::cos(phi) * t + std::sin(phi) * b) + side * std::cos(theta) * u;
                sum += aw[i] * pw[j] * at(e + C.r * n, n) * C.r * C.r * std::sin(theta) * (0.5 * kPi) * (2.0 * kPi);
            }
        }
    }
    return sum;
}

// A Lambert floor's (albedo kAlbedo, normal +y) radiance at x from C's visible part above its
// horizon: a / pi L_e W max(wi.y, 0) over the surface, at 192 x 384 and 384 x 768 nodes, which
// must agree to `converged` (the terminator and the horizon are kinks: algebraic convergence).
double lambertQuadrature(const Capsule &C, glm::dvec3 x, double converged = 2e-4) {
    const double Le = capsuleRadiance(C) * window(glm::length(C.centre - x), C.range);
    auto g = [Le](glm::dvec3 wi) { return kAlbedo / kPi * Le * std::max(0.0, wi.y); };
    const double coarse = capsuleIntegral(C, x, 192, 384, g), fine = capsuleIntegral(C, x, 384, 768, g);
    if (!(std::fabs(coarse - fine) <= converged * std::fabs(fine) + 1e-300))
        fail_msg("the quadrature has not converged at (%g, %g, %g): %.12g vs %.12g", x.x, x.y, x.z, coarse, fine);
    std::printf("    quadrature %.9f (coarse %+.1e)\n", fine, coarse / fine - 1.0);
    return fine;
}

// The sphere's closed form (L = 0, wholly above the floor): the point light's a / pi I cos / d^2 W.
double lambertSphere(const Capsule &C, glm::dvec3 x) {
    const glm::dvec3 toC = C.centre - x;
    const double d = glm::length(toC);
    return kAlbedo / kPi * C.I * (toC.y / d) / (d * d) * window(d, C.range);
}

// ---- scenes and renders --------------------------------------------------------------------

// C as the loader gives it: a point light with radius, length and axis.
void addCapsule(SceneBuilder &b, const Capsule &C) {
    b.punctual(RTPBR_GLTF_PUNCTUAL_POINT, glm::vec3(C.centre), glm::vec3(0, 0, -1), glm::vec3(float(C.I)),
               float(C.range));
    rtpbr_gltf_punctual_light &P = b.punctualLights.back();
    P.radius = float(C.r);
    P.length = float(C.length);
    for (int k = 0; k < 3; k++)
        P.axis[k] = float(C.axis[k]);
}

struct Estimate {
    double v, se;
};

// The oracle's radiance leaving floor point p towards a camera 0.2 away (channel 0) and its
// standard error, with s (1 x 1 pixels, one thread).
Estimate renderPoint(SceneBuilder &b, glm::dvec3 p, const RenderSettings &settings) {
    const glm::dvec3 toCamera = glm::normalize(glm::dvec3(0.0, 0.3, 1.0));
    b.cameras.clear();
    b.camera(glm::vec3(p + 0.2 * toCamera), glm::vec3(p), 1e-3f);
    b.build();
    RenderSettings s = settings;
    s.width = s.height = 1;
    s.threads = 1;
    Accumulator acc;
    std::string err;
    if (render(b.scene, s, &acc, &err, nullptr) != Result::Success)
        fail_msg("render: %s", err.c_str());
    std::vector<float> rgb, se;
    resolve(acc, &rgb, &se);
    return {rgb[0], se[0]};
}

Estimate renderCapsule(const Capsule &C, glm::dvec3 p, const RenderSettings &s) {
    SceneBuilder b;
    floorPlane(b, lambertMaterial(b, kAlbedo));
    addCapsule(b, C);
    return renderPoint(b, p, s);
}

// |estimate - reference| within 4.5 standard errors (a seeded render: met or not, the same way
// every run); returns the difference in standard errors.
double expectWithin(const Estimate &e, double ref, const char *what) {
    const double z = e.se > 0.0 ? (e.v - ref) / e.se : 0.0;
    std::printf("  %s: %.7f vs %.7f (se %.2e, relative %+.2e, %+.2f se)\n", what, e.v, ref, e.se, e.v / ref - 1.0, z);
    if (!(std::fabs(e.v - ref) <= 4.5 * e.se))
        fail_msg("%s: %.7f vs reference %.7f: %.2f standard errors (se %.3g)", what, e.v, ref, z, e.se);
    return z;
}

// ---- the shape -----------------------------------------------------------------------------

CapsuleShape shapeOf(const Capsule &C) {
    rtpbr_gltf_punctual_light P{};
    P.type = RTPBR_GLTF_PUNCTUAL_POINT;
    for (int k = 0; k < 3; k++) {
        P.position[k] = float(C.centre[k]);
        P.axis[k] = float(C.axis[k]);
    }
    P.radius = float(C.r);
    P.length = float(C.length);
    return CapsuleShape::of(P);
}

// Area samples lie on the surface (distance r from the segment) with the outward normal there,
// the cylinder taking its share of the area (within 4 se over 2^16 samples); a sample faces a
// point p outside (n.(p - x) > 0) iff the ray from p towards it meets the capsule first at it
// (intersect, |s - dist| <= 1e-9 dist), away from grazing (|cos| < 1e-6 left out); from inside
// every ray leaves through a point whose normal faces along it.
void test_capsule_shape(void **) {
    const Capsule C{glm::dvec3(0.3, 0.5, -0.2), glm::normalize(glm::dvec3(1.0, 0.4, -0.7)), 0.25, 1.3, 1.0};
    const CapsuleShape S = shapeOf(C);
    assert_true(std::fabs(S.area() - 2.0 * kPi * C.r * (2.0 * C.r + C.length)) <= 1e-6 * S.area());
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const int n = 1 << 16;
    int onCylinder = 0, facing = 0, hidden = 0, mismatches = 0;
    for (int i = 0; i < n; i++) {
        glm::dvec3 normal;
        const glm::dvec3 x = S.sample(U(rng), U(rng), &normal);
        const double z = glm::dot(x - S.centre, S.axis);
        const glm::dvec3 nearest = S.centre + glm::clamp(z, -S.half, S.half) * S.axis;
        if (!(std::fabs(glm::length(x - nearest) - C.r) <= 1e-9) ||
            !(glm::length(normal - (x - nearest) / C.r) <= 1e-6))
            fail_msg("sample %d: (%g, %g, %g) not on the surface with its normal", i, x.x, x.y, x.z);
        onCylinder += std::fabs(z) < S.half;
        // A point outside, up to 2 m from the centre.
        glm::dvec3 p;
        do
            p = S.centre + 4.0 * glm::dvec3(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5);
        while (S.contains(p));
        const glm::dvec3 toX = x - p;
        const double dist = glm::length(toX), cosL = glm::dot(normal, p - x) / dist;
        if (std::fabs(cosL) < 1e-6)
            continue;
        double s;
        glm::dvec3 nHit;
        const bool first = S.intersect(p, toX / dist, HUGE_VAL, &s, &nHit) && std::fabs(s - dist) <= 1e-9 * dist;
        (cosL > 0.0 ? facing : hidden)++;
        mismatches += first != (cosL > 0.0);
    }
    // Rays that pass farther from the centre than half + r miss it, however far they go.
    for (int i = 0; i < 1000; i++) {
        const glm::dvec3 p = S.centre + 4.0 * glm::dvec3(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5);
        const glm::dvec3 w = glm::normalize(glm::dvec3(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5));
        const glm::dvec3 toC = S.centre - p;
        const double along = std::max(0.0, glm::dot(toC, w));
        double s;
        glm::dvec3 nHit;
        if (glm::length(toC - along * w) > S.half + C.r)
            assert_false(S.intersect(p, w, HUGE_VAL, &s, &nHit));
    }
    const double share = S.cylinderArea() / S.area(), se = std::sqrt(share * (1.0 - share) / n);
    std::printf("cylinder share %.5f vs %.5f (%+.2f se); %d facing, %d hidden, %d disagree with the ray\n",
                double(onCylinder) / n, share, (double(onCylinder) / n - share) / se, facing, hidden, mismatches);
    assert_true(std::fabs(double(onCylinder) / n - share) <= 4.0 * se);
    assert_int_equal(mismatches, 0);
    for (int i = 0; i < 1000; i++) {
        const glm::dvec3 p = S.centre + S.axis * (S.half * (2.0 * U(rng) - 1.0)) + 0.2 * C.r * (U(rng) - 0.5) * S.t;
        const glm::dvec3 w = glm::normalize(glm::dvec3(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5));
        double s;
        glm::dvec3 nHit;
        assert_true(S.contains(p) && S.intersect(p, w, HUGE_VAL, &s, &nHit));
        assert_true(!S.intersect(p, w, 0.5 * s, &s, &nHit)); // nothing before it
        const glm::dvec3 x = p + s * w;
        const glm::dvec3 nearest = S.centre + glm::clamp(glm::dot(x - S.centre, S.axis), -S.half, S.half) * S.axis;
        assert_true(glm::dot(nHit, w) > 0.0 && std::fabs(glm::length(x - nearest) - C.r) <= 1e-9);
    }
}

// ---- a horizontal capsule above a Lambert floor ----------------------------------------------

// Length 0.8, radius 0.15, 0.6 above the floor along x: under its middle, under a cap, beyond an
// end, off to the side, and (radius 0.2, 0.3 above) close under it where a BSDF ray meets it
// often (MIS weights tested). Direct light at 2^20 samples; at one point also all bounces and
// noShadows (the floor's light goes nowhere: the same value), and a range of 1.5.
void test_capsule_lambert(void **) {
    const Capsule high{glm::dvec3(0.0, 0.6, 0.0), glm::dvec3(1, 0, 0), 0.15, 0.8, 2.0};
    const Capsule low{glm::dvec3(0.0, 0.3, 0.0), glm::dvec3(1, 0, 0), 0.2, 0.8, 2.0};
    struct Point {
        const Capsule *C;
        glm::dvec3 p;
        const char *what;
    };
    const Point points[] = {{&high, {0.0, 0.0, 0.0}, "under its middle"},
                            {&high, {0.45, 0.0, 0.1}, "under a cap"},
                            {&high, {1.2, 0.0, -0.3}, "beyond an end"},
                            {&high, {0.1, 0.0, 0.9}, "off to the side"},
                            {&low, {0.2, 0.0, 0.05}, "close under a low one"}};
    RenderSettings s;
    s.spp = 1u << 20;
    s.directOnly = true;
    double worst = 0.0;
    for (const Point &k : points) {
        const double ref = lambertQuadrature(*k.C, leaving(k.p));
        worst = std::max(worst, std::fabs(expectWithin(renderCapsule(*k.C, k.p, s), ref, k.what)));
    }
    s.spp = 1u << 18;
    for (int mode = 1; mode < 3; mode++) {
        s.directOnly = mode == 2;
        s.noShadows = mode == 2;
        const glm::dvec3 p(0.45, 0.0, 0.1);
        expectWithin(renderCapsule(high, p, s), lambertQuadrature(high, leaving(p)),
                     mode == 1 ? "under a cap, all bounces" : "under a cap, no shadows");
    }
    Capsule ranged = high;
    ranged.range = 1.5;
    s.directOnly = true;
    s.noShadows = false;
    const glm::dvec3 p(1.2, 0.0, -0.3);
    const double ref = lambertQuadrature(ranged, leaving(p));
    std::printf("  range 1.5: W = %.4f\n", window(glm::length(ranged.centre - leaving(p)), 1.5));
    expectWithin(renderCapsule(ranged, p, s), ref, "beyond an end, range 1.5");
    std::printf("largest |z| at 2^20 samples: %.2f\n", worst);
}

// ---- the sphere's limit ----------------------------------------------------------------------

// Radius 0.3, 0.7 above the floor: at length 0 (the sphere: its cone sampling), 1e-6 and 1e-3
// the floor's radiance is the sphere's closed form a / pi I cos / d^2 (the quadrature of the
// capsule agrees with it to 1e-5 at length 0 and differs by its own O(L / r) at 1e-3, less than
// the standard error). The quadrature itself reproduces the closed form at length 0.
void test_capsule_sphere_limit(void **) {
    const glm::dvec3 points[] = {{0.0, 0.0, 0.0}, {0.9, 0.0, 0.4}};
    RenderSettings s;
    s.spp = 1u << 20;
    s.directOnly = true;
    for (const glm::dvec3 &p : points) {
        const Capsule sphere{glm::dvec3(0.1, 0.7, 0.0), glm::dvec3(0, 0, 1), 0.3, 0.0, 2.0};
        const glm::dvec3 x = leaving(p);
        const double closed = lambertSphere(sphere, x), q = lambertQuadrature(sphere, x);
        std::printf("at (%g, 0, %g): closed form %.9f, quadrature at length 0 %+.2e\n", p.x, p.z, closed, q / closed - 1.0);
        assert_true(std::fabs(q - closed) <= 1e-5 * closed);
        for (double length : {0.0, 1e-6, 1e-3}) {
            Capsule C = sphere;
            C.length = length;
            char what[96];
            std::snprintf(what, sizeof what, "length %g, against the sphere's closed form", length);
            expectWithin(renderCapsule(C, p, s), closed, what);
        }
    }
}

// ---- the horizon ---------------------------------------------------------------------------

// Capsules cut by the floor: horizontal (radius 0.2, centre 0.05 above, length 0.8) and tilted
// (radius 0.15, length 1, its axis 31 degrees below the horizontal, centre 0.1 above): the
// quadrature of the part above the floor's horizon at points beside them (the part below would
// add light if it leaked). Wholly below (centre 0.3 below): exactly 0. A floor point inside the
// horizontal one sees it everywhere: a L_e, exactly (BSDF rays alone, weight 1).
void test_capsule_horizon(void **) {
    const Capsule flat{glm::dvec3(0.0, 0.05, 0.0), glm::dvec3(1, 0, 0), 0.2, 0.8, 2.0};
    const Capsule tilted{glm::dvec3(0.0, 0.1, 0.0), glm::normalize(glm::dvec3(1.0, -0.6, 0.3)), 0.15, 1.0, 2.0};
    struct Point {
        const Capsule *C;
        glm::dvec3 p;
        const char *what;
    };
    const Point points[] = {{&flat, {0.0, 0.0, 0.5}, "beside a horizontal one"},
                            {&flat, {0.9, 0.0, 0.3}, "beyond its end"},
                            {&tilted, {0.2, 0.0, 0.6}, "beside a tilted one"},
                            {&tilted, {-0.8, 0.0, 0.1}, "beyond its raised end"},
                            {&tilted, {0.7, 0.0, -0.2}, "by its sunken end"}};
    RenderSettings s;
    s.spp = 1u << 20;
    s.directOnly = true;
    for (const Point &k : points) {
        const glm::dvec3 x = leaving(k.p);
        // The whole capsule, horizon ignored: what a leak would tend to.
        const double Le = capsuleRadiance(*k.C);
        const double whole = capsuleIntegral(*k.C, x, 384, 768, [Le](glm::dvec3 wi) { return kAlbedo / kPi * Le * std::fabs(wi.y); });
        const double ref = lambertQuadrature(*k.C, x);
        std::printf("%s: above the horizon %.6f, with the part below %.6f\n", k.what, ref, whole);
        expectWithin(renderCapsule(*k.C, k.p, s), ref, k.what);
    }
    s.spp = 1u << 12;
    Capsule below = flat;
    below.centre.y = -0.3;
    const Estimate none = renderCapsule(below, glm::dvec3(0.5, 0.0, 0.2), s);
    std::printf("wholly below: %g\n", none.v);
    assert_true(none.v == 0.0);
    const Estimate inside = renderCapsule(flat, glm::dvec3(0.1, 0.0, 0.05), s);
    const double aLe = kAlbedo * capsuleRadiance(flat);
    std::printf("inside: %.7f vs a L_e %.7f (%+.1e)\n", inside.v, aLe, inside.v / aLe - 1.0);
    assert_true(std::fabs(inside.v - aLe) <= 1e-5 * aLe);
}

// ---- from glTF -------------------------------------------------------------------------------

// A capsule from glTF (KHR_lights_punctual point light, "extras": {"radius": 0.1, "length": 1},
// its node 0.5 up and turned 90 degrees about +y: its +X, the axis, becomes -z): the loader's
// light, put over a Lambert floor, against the quadrature of the capsule along z at a point
// under its end (along x it would give 0.65 of it there, 100 standard errors off).
void test_capsule_from_gltf(void **) {
    const char *json = "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_lights_punctual\"],"
                       "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\",\"intensity\":2,"
                       "\"extras\":{\"radius\":0.1,\"length\":1}}]}},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
                       "\"nodes\":[{\"translation\":[0,0.5,0],\"rotation\":[0,0.70710678118654752,0,0.70710678118654752],"
                       "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}]}";
    rtpbr_gltf_scene *scene = nullptr;
    rtpbr_gltf_load_desc desc{};
    if (rtpbr_gltf_load_memory(json, std::strlen(json), &desc, &scene) != RTPBR_GLTF_SUCCESS)
        fail_msg("the loader refused the capsule scene");
    assert_int_equal(scene->punctual_light_count, 1);
    const rtpbr_gltf_punctual_light P = scene->punctual_lights[0];
    rtpbr_gltf_destroy(scene);
    std::printf("loaded: radius %g, length %g, axis (%g, %g, %g)\n", double(P.radius), double(P.length),
                double(P.axis[0]), double(P.axis[1]), double(P.axis[2]));
    assert_true(std::fabs(P.axis[2] + 1.0f) <= 1e-6f && P.length == 1.0f && P.radius == 0.1f);
    SceneBuilder b;
    floorPlane(b, lambertMaterial(b, kAlbedo));
    b.punctualLights.push_back(P);
    const glm::dvec3 p(0.05, 0.0, 0.6);
    const Capsule alongZ{glm::dvec3(0.0, 0.5, 0.0), glm::dvec3(0, 0, 1), 0.1, 1.0, 2.0};
    const Capsule alongX{glm::dvec3(0.0, 0.5, 0.0), glm::dvec3(1, 0, 0), 0.1, 1.0, 2.0};
    std::printf("  along x it would be %.6f\n", lambertQuadrature(alongX, leaving(p)));
    RenderSettings s;
    s.spp = 1u << 18;
    s.directOnly = true;
    expectWithin(renderPoint(b, p, s), lambertQuadrature(alongZ, leaving(p)), "under the end of a loaded capsule");
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_capsule_shape), cmocka_unit_test(test_capsule_lambert),
                cmocka_unit_test(test_capsule_sphere_limit), cmocka_unit_test(test_capsule_horizon),
                cmocka_unit_test(test_capsule_from_gltf))
