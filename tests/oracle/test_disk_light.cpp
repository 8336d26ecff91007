// EXT_lights_area disks in the oracle (issue 30): a disk light (RTPBR_GLTF_LIGHT_DISK) is the
// true disk, not the equal-area octagon the loader also gives. Held to references written here:
//   - on the axis of a disk (radius r, height h, radiance L) facing a Lambert plane (albedo a):
//     the closed form a L r^2 / (h^2 + r^2) (irradiance pi L r^2 / (h^2 + r^2)), with direct
//     lighting, all bounces and noShadows;
//   - off the axis, under the rim and beyond it: the closed form of a plane element parallel to
//     a disk; a tilted disk, and one half below the plane's horizon: a Gauss-Legendre quadrature
//     of its form factor, over the half above the horizon (no light leaks from the half below,
//     none is missing from the half above); the quadrature also reproduces the closed forms;
//   - the octagon (rendered as the polygon light it is) against Lambert's polygon formula: the
//     disk's radiance differs from the octagon's by the two references' difference, and the
//     disk matches its closed form better than the octagon does;
//   - seen by the camera: each pixel L times the part of it the disk covers (the octagon's
//     image fails that);
//   - as an occluder of a point light: a floor point whose line to the light passes inside the
//     disk but outside the octagon is exactly 0, one outside the disk but inside the octagon is
//     lit (and the octagon the other way round);
//   - GGX (single scattering) against the quadrature of f cos over the disk: MIS with the BSDF
//     rays that meet it;
//   - loaded from glTF (EXT_lights_area "disk"): the loader's centre, normal and radius, lit
//     from the front, black from behind;
//   - bad disks refused.
// A point's radiance is rendered as a 1 x 1 image whose camera looks at the point from close by
// with a field of view of 1e-3 rad: the jitter moves the point by < 1e-4 m, which changes no
// reference here by more than about 1e-7 of itself. The oracle samples the lights and the BSDF
// from the point moved off its surface by 1e-4 (1 + |p|_inf) (oracle/README.md), where the
// irradiance differs from the point's by up to 1.3e-3 of it here (more than the standard
// errors): the references are taken there (leaving()).
#include "test_common.h"

#include "oracle.h"
#include "quadrature.hpp" // gauss_legendre
#include "scene_builder.h"

#include <rtpbr/fresnel.h>
#include <rtpbr/microfacet.h>

#include <functional>

using namespace rtpbr_oracle;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kAlbedo = 0.8f;
const glm::dvec3 kUp(0.0, 1.0, 0.0);

// ---- the references ------------------------------------------------------------------------

struct Disk {
    glm::dvec3 centre, n; // n: the emitting side
    double r, L;
};

// The integral over the part of disk D at angles [phi0, phi1] (about its centre, from
// SceneBuilder::diskTangent towards n x tangent) of g(wi) cos(theta_l) / d^2 dA, seen from x
// (wi, d: the direction and distance to the disk's point; theta_l: between -wi and n; the
// disk's back gives nothing): Gauss-Legendre in the radius and the angle.
double diskIntegral(const Disk &D, glm::dvec3 x, int rings, int sectors, double phi0, double phi1,
                    const std::function<double(glm::dvec3)> &g) {
    std::vector<double> rx, rw, px, pw;
    gauss_legendre(rings, rx, rw);
    gauss_legendre(sectors, px, pw);
    const glm::dvec3 t = SceneBuilder::diskTangent(glm::vec3(D.n)), b = glm::cross(D.n, t);
    double sum = 0.0;
    for (int i = 0; i < rings; i++) {
        const double rho = D.r * rx[i];
        for (int j = 0; j < sectors; j++) {
            const double phi = phi0 + (phi1 - phi0) * px[j];
            const glm::dvec3 toQ = D.centre + rho * (std::cos(phi) * t + std::sin(phi) * b) - x;
            const double d2 = glm::dot(toQ, toQ);
            const glm::dvec3 wi = toQ / std::sqrt(d2);
            const double cosL = -glm::dot(wi, D.n);
            if (cosL > 0.0)
                sum += rw[i] * pw[j] * g(wi) * cosL / d2 * rho;
        }
    }
    return sum * D.r * (phi1 - phi0);
}

// diskIntegral at 96 x 192 and 192 x 384 nodes, which must agree to `converged` (relative).
double quadrature(const Disk &D, glm::dvec3 x, double phi0, double phi1, double converged,
                  const std::function<double(glm::dvec3)> &g) {
    const double coarse = diskIntegral(D, x, 96, 192, phi0, phi1, g), fine = diskIntegral(D, x, 192, 384, phi0, phi1, g);
    if (!(std::fabs(coarse - fine) <= converged * std::fabs(fine)))
        fail_msg("the quadrature has not converged at (%g, %g, %g): %.12g vs %.12g", x.x, x.y, x.z, coarse, fine);
    return fine;
}

// A Lambert floor's (albedo kAlbedo, normal +y) radiance at x from the part of D at angles
// [phi0, phi1] above its horizon.
double lambertQuadrature(const Disk &D, glm::dvec3 x, double phi0 = 0.0, double phi1 = 2.0 * kPi,
                         double converged = 1e-9) {
    return quadrature(D, x, phi0, phi1, converged,
                      [&D](glm::dvec3 wi) { return kAlbedo / kPi * D.L * std::max(0.0, wi.y); });
}

// The same from a disk facing the floor, parallel to it, at height h, its axis rho from x: the
// configuration factor of a plane element parallel to a disk (Howell, "A Catalog of Radiation
// Heat Transfer Configuration Factors"), F = (1 - (h^2 + rho^2 - r^2) / sqrt((h^2 + rho^2 +
// r^2)^2 - 4 r^2 rho^2)) / 2; radiance a L F. On the axis: a L r^2 / (h^2 + r^2).
double lambertParallel(const Disk &D, glm::dvec3 x) {
    const double h = D.centre.y - x.y, r = D.r;
    const glm::dvec3 off = D.centre - x;
    const double rho2 = off.x * off.x + off.z * off.z;
    const double F = 0.5 * (1.0 - (h * h + rho2 - r * r) / std::sqrt(std::pow(h * h + rho2 + r * r, 2.0) - 4.0 * r * r * rho2));
    return kAlbedo * D.L * F;
}

// The equal-area octagon's: Lambert's polygon formula.
double lambertOctagon(const Disk &D, glm::dvec3 x) {
    const std::vector<glm::vec3> oct = SceneBuilder::diskOctagon(glm::vec3(D.centre), glm::vec3(D.n), float(D.r));
    return kAlbedo / kPi * polygonIrradiance(x, kUp, oct, D.L);
}

// ---- scenes and renders --------------------------------------------------------------------

// D as a disk light (EXT_lights_area, one-sided unless twoSided), or as its octagon: a polygon
// light of the same vertices.
void addDisk(SceneBuilder &b, const Disk &D, bool asOctagon = false, bool twoSided = false) {
    const glm::vec3 radiance(float(D.L));
    if (asOctagon)
        b.light(SceneBuilder::diskOctagon(glm::vec3(D.centre), glm::vec3(D.n), float(D.r)), radiance, twoSided);
    else
        b.disk(glm::vec3(D.centre), glm::vec3(D.n), float(D.r), radiance, twoSided);
}

// The scene (built) rendered at n x n pixels on `threads` threads: each pixel's radiance and its
// standard error (RGB).
void renderImage(const SceneBuilder &b, RenderSettings s, uint32_t n, uint32_t threads, std::vector<float> *rgb,
                 std::vector<float> *se) {
    s.width = s.height = n;
    s.threads = threads;
    Accumulator acc;
    std::string err;
    if (render(b.scene, s, &acc, &err, nullptr) != Result::Success)
        fail_msg("render: %s", err.c_str());
    resolve(acc, rgb, se);
}

// The oracle's estimate of the radiance leaving p towards a camera at p + dist toCamera (unit),
// channel 0, and its standard error.
struct Estimate {
    double v, se;
};
Estimate renderPoint(SceneBuilder &b, glm::dvec3 p, glm::dvec3 toCamera, double dist, const RenderSettings &s) {
    b.cameras.clear();
    const glm::vec3 upHint = std::fabs(toCamera.y) > 0.9 ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    b.camera(glm::vec3(p + dist * toCamera), glm::vec3(p), 1e-3f, upHint);
    b.build();
    std::vector<float> rgb, se;
    renderImage(b, s, 1, 1, &rgb, &se);
    return {rgb[0], se[0]};
}

// |estimate - reference| within 4.5 standard errors plus `rounding` of the reference (a seeded
// render: the bound is met or not, the same way every run); returns the difference in
// standard errors.
double expectWithin(const Estimate &e, double ref, const char *what, double rounding = 0.0) {
    const double z = e.se > 0.0 ? (e.v - ref) / e.se : 0.0;
    std::printf("  %s: %.7f vs %.7f (se %.2e, relative %+.2e, %+.2f se)\n", what, e.v, ref, e.se, e.v / ref - 1.0, z);
    if (!(std::fabs(e.v - ref) <= 4.5 * e.se + rounding * std::fabs(ref)))
        fail_msg("%s: %.7f vs reference %.7f: %.2f standard errors (se %.3g)", what, e.v, ref, z, e.se);
    return z;
}

// ---- a disk facing a Lambert floor, parallel to it -------------------------------------------

// The centre of the floor under a disk facing it, h = r: the closed form, with direct light,
// all bounces (the floor's light goes to the disk's black back: nothing more) and noShadows.
// There the octagon's value is -5.6e-4 of it off (the most over h / r); 2^22 samples (0.42 of
// the value a sample) bring the disk's standard error to 2e-4 of it, and the disk, rendered,
// is nearer its closed form than the octagon, rendered, is.
void test_disk_on_axis(void **) {
    const Disk D{glm::dvec3(0.0, 0.5, 0.0), -kUp, 0.5, 2.0};
    const glm::dvec3 p(0.0), toCamera = glm::normalize(glm::dvec3(0.0, 0.3, 1.0));
    assert_true(std::fabs(lambertParallel(D, p) - kAlbedo * D.L * 0.5) <= 1e-12); // a L r^2 / (h^2 + r^2)
    const glm::dvec3 x = leaving(p);
    const double closed = lambertParallel(D, x), q = lambertQuadrature(D, x), oct = lambertOctagon(D, x);
    std::printf("on the axis (h = r = 0.5, L = 2; 1.1e-4 above the floor): closed form %.10f, quadrature %.10f, "
                "octagon %.10f (%+.2e)\n", closed, q, oct, oct / closed - 1.0);
    assert_true(std::fabs(q - closed) <= 1e-10 * closed);
    RenderSettings s;
    s.spp = 1u << 22;
    s.directOnly = true;
    Estimate disk{0.0, 0.0}, octagon{0.0, 0.0};
    for (int asOctagon = 0; asOctagon < 2; asOctagon++) {
        SceneBuilder b;
        floorPlane(b, lambertMaterial(b, kAlbedo));
        addDisk(b, D, asOctagon != 0);
        const Estimate e = renderPoint(b, p, toCamera, 0.2, s);
        expectWithin(e, asOctagon ? oct : closed, asOctagon ? "octagon, direct" : "disk, direct");
        (asOctagon ? octagon : disk) = e;
    }
    std::printf("  from the closed form: the disk %+.2e (%+.2f se), the octagon %+.2e (%+.2f se)\n", disk.v - closed,
                (disk.v - closed) / disk.se, octagon.v - closed, (octagon.v - closed) / octagon.se);
    assert_true(std::fabs(disk.v - closed) < std::fabs(octagon.v - closed));
    s.spp = 1u << 16;
    for (int mode = 1; mode < 3; mode++) {
        s.directOnly = mode == 2;
        s.noShadows = mode == 2;
        SceneBuilder b;
        floorPlane(b, lambertMaterial(b, kAlbedo));
        addDisk(b, D);
        expectWithin(renderPoint(b, p, toCamera, 0.2, s), closed, mode == 1 ? "disk, all bounces" : "disk, no shadows");
    }
}

// Off the axis of the same kind of disk (h = 0.2, r = 0.5): the closed form (checked against
// the quadrature) inside, beyond the rim, and under it where the octagon's vertex stands out
// (+1.7 %) and where its edge cuts in (-1.7 %). The octagon, rendered, against Lambert's
// polygon formula; under the rim the disk's radiance is many standard errors from the
// octagon's and matches its closed form better.
void test_disk_parallel_offset(void **) {
    const Disk D{glm::dvec3(0.0, 0.2, 0.0), -kUp, 0.5, 2.0};
    const glm::dvec3 t = SceneBuilder::diskTangent(glm::vec3(D.n)), b = glm::cross(D.n, t);
    const double edge = kPi / 8.0; // the octagon's edge midpoint; its vertices at multiples of pi / 4
    struct Point {
        double rho, angle;
        bool rim;
    };
    const Point points[] = {{0.3, 1.0, false}, {0.5, 0.0, true}, {0.5, edge, true}, {0.8, 2.0, false}};
    RenderSettings s;
    s.spp = 1u << 18;
    s.directOnly = true;
    for (const Point &pt : points) {
        const glm::dvec3 p = pt.rho * (std::cos(pt.angle) * t + std::sin(pt.angle) * b);
        const glm::dvec3 toCamera = glm::normalize(glm::dvec3(0.3, 1.0, 0.6));
        const glm::dvec3 x = leaving(p);
        const double closed = lambertParallel(D, x), q = lambertQuadrature(D, x), oct = lambertOctagon(D, x);
        std::printf("%.1f from the axis at %.3f rad: closed form %.10f, quadrature %.10f, octagon %.10f (%+.2e)\n", pt.rho,
                    pt.angle, closed, q, oct, oct / closed - 1.0);
        assert_true(std::fabs(q - closed) <= 1e-9 * closed);
        SceneBuilder bd, bo;
        floorPlane(bd, lambertMaterial(bd, kAlbedo));
        addDisk(bd, D);
        floorPlane(bo, lambertMaterial(bo, kAlbedo));
        addDisk(bo, D, true);
        const Estimate disk = renderPoint(bd, p, toCamera, 0.1, s), octagon = renderPoint(bo, p, toCamera, 0.1, s);
        expectWithin(disk, closed, "disk");
        expectWithin(octagon, oct, "octagon (a polygon light)");
        if (pt.rim) {
            const double apart = std::fabs(disk.v - octagon.v) / std::hypot(disk.se, octagon.se);
            std::printf("  disk - octagon %+.3e (the references' %+.3e), %.1f se; |disk - closed| %.2e, |octagon - "
                        "closed| %.2e\n", disk.v - octagon.v, closed - oct, apart, std::fabs(disk.v - closed),
                        std::fabs(octagon.v - closed));
            assert_true(apart > 6.0);
            assert_true(std::fabs(disk.v - closed) < std::fabs(octagon.v - closed));
            EXPECT_AGREE(disk.v - octagon.v, std::hypot(disk.se, octagon.se), closed - oct, 0.0, 4.5, 0.0);
        }
    }
}

// One-sided: a disk facing away from the floor gives it exactly nothing (and its back is black
// to the camera's rays that meet it); two-sided, the closed form either way up.
void test_disk_sides(void **) {
    const glm::dvec3 p(0.1, 0.0, -0.05), toCamera = glm::normalize(glm::dvec3(-0.2, 0.25, 1.0));
    RenderSettings s;
    s.spp = 1u << 15;
    s.directOnly = true;
    for (int twoSided = 0; twoSided < 2; twoSided++)
        for (double up : {-1.0, 1.0}) {
            const Disk D{glm::dvec3(0.0, 0.4, 0.0), up * kUp, 0.3, 1.5};
            SceneBuilder b;
            floorPlane(b, lambertMaterial(b, kAlbedo));
            addDisk(b, D, false, twoSided != 0);
            const Estimate e = renderPoint(b, p, toCamera, 0.3, s);
            char what[80];
            std::snprintf(what, sizeof what, "%s disk facing %s", twoSided ? "two-sided" : "one-sided",
                          up < 0.0 ? "the floor" : "away");
            if (!twoSided && up > 0.0) {
                std::printf("  %s: %g\n", what, e.v);
                assert_true(e.v == 0.0);
            } else {
                expectWithin(e, lambertParallel(D, leaving(p)), what);
            }
        }
}

// ---- a tilted disk half below the floor's horizon ----------------------------------------------

// A disk whose centre lies in the floor's plane, beyond the floor's edge (x = 1), tilted towards
// it: from a floor point its half above the horizon shines, the other half is below it. The
// quadrature over the half above (its angles: a half-turn; the integrand smooth) is the
// reference; the half below would add `leak` if the horizon were ignored (|cos| over it), and a
// sampler that dropped the half above's samples near the horizon would miss light: both many
// standard errors. Also a point that sees the whole disk above its horizon (the disk raised).
void test_disk_horizon(void **) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(-1.0, 0.6, 0.3));
    const Disk tilted{glm::dvec3(1.6, 0.0, 0.0), n, 0.5, 2.0}, raised{glm::dvec3(1.6, 0.7, 0.0), n, 0.5, 2.0};
    // The angles of the half above: y(phi) = rho (cos(phi) t.y + sin(phi) b.y) >= 0.
    const glm::dvec3 t = SceneBuilder::diskTangent(glm::vec3(n)), b = glm::cross(n, t);
    const double mid = std::atan2(b.y, t.y);
    RenderSettings s;
    s.spp = 1u << 17;
    s.directOnly = true;
    for (const glm::dvec3 p : {glm::dvec3(0.2, 0.0, 0.3), glm::dvec3(-0.5, 0.0, -0.8)}) {
        const glm::dvec3 toCamera = glm::normalize(glm::dvec3(-0.3, 1.0, 0.2));
        const glm::dvec3 x = leaving(p);
        // The half above the floor's plane: the sliver of it below x's horizon (1.2e-4 higher)
        // is a kink in the integrand, where it is ~0: converged to 1e-7.
        const double above = lambertQuadrature(tilted, x, mid - kPi / 2.0, mid + kPi / 2.0, 1e-7);
        const double leak = quadrature(tilted, x, mid + kPi / 2.0, mid + 1.5 * kPi, 1e-9,
                                       [&tilted](glm::dvec3 wi) { return kAlbedo / kPi * tilted.L * std::fabs(wi.y); });
        std::printf("floor point (%.1f, %.1f): the half above %.8f, the half below would leak %.8f\n", p.x, p.z, above,
                    leak);
        SceneBuilder bt;
        floorPlane(bt, lambertMaterial(bt, kAlbedo), -3.0f, 1.0f, -3.0f, 3.0f);
        addDisk(bt, tilted);
        const Estimate e = renderPoint(bt, p, toCamera, 0.5, s);
        expectWithin(e, above, "tilted disk, half below the horizon");
        assert_true(std::fabs(e.v - (above + leak)) > 10.0 * e.se);
        SceneBuilder br;
        floorPlane(br, lambertMaterial(br, kAlbedo), -3.0f, 1.0f, -3.0f, 3.0f);
        addDisk(br, raised);
        expectWithin(renderPoint(br, p, toCamera, 0.5, s), lambertQuadrature(raised, x), "the same disk raised above it");
    }
}

// ---- seen by the camera, and as an occluder --------------------------------------------------

// The camera 1 below a disk facing it (radius 0.5, 16 x 16 pixels, yfov 1.2): each pixel is L
// times the part of it whose rays meet the disk (a 256 x 256 grid of rays through the pixel
// for the pixels its edge crosses; cameraRay: the oracle's camera): exactly L inside, exactly 0 outside, within 5 standard
// errors (and 2e-3 L for the grid) on the edge. The octagon's image fails that.
void test_disk_seen(void **) {
    const Disk D{glm::dvec3(0.0), -kUp, 0.5, 1.5};
    const uint32_t n = 16;
    RenderSettings s;
    s.spp = 1024;
    int worseOctagon = 0, edgePixels = 0;
    for (int asOctagon = 0; asOctagon < 2; asOctagon++) {
        SceneBuilder b;
        addDisk(b, D, asOctagon != 0);
        b.camera(glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(0.0f), 1.2f, glm::vec3(0, 0, 1));
        b.build();
        std::vector<float> rgb, se;
        renderImage(b, s, n, 2, &rgb, &se);
        double worstZ = 0.0;
        for (uint32_t y = 0; y < n; y++)
            for (uint32_t x = 0; x < n; x++) {
                // Where the pixel's rays meet the plane y = 0 (t = 1 / dir.y): a square (the camera
                // looks along the disk's axis), wholly inside the disk, wholly outside, or neither.
                auto at = [&](float sx, float sy) {
                    const glm::dvec3 d(cameraRay(b.cameras[0], float(x) + sx, float(y) + sy, n, n));
                    return glm::dvec2(d.x / d.y, d.z / d.y);
                };
                const glm::dvec2 c0 = at(0, 0), c1 = at(1, 1), lo = glm::min(c0, c1), hi = glm::max(c0, c1);
                const double nearest = glm::length(glm::clamp(glm::dvec2(0.0), lo, hi));
                const double farthest = glm::length(glm::max(glm::abs(lo), glm::abs(hi)));
                const bool a = farthest < D.r, allSame = a || nearest > D.r;
                auto inside = [&](float sx, float sy) { return glm::length(at(sx, sy)) <= D.r; };
                double cover = a ? 1.0 : 0.0;
                if (!allSame) {
                    const int g = 256;
                    int hits = 0;
                    for (int i = 0; i < g; i++)
                        for (int j = 0; j < g; j++)
                            hits += inside((i + 0.5f) / g, (j + 0.5f) / g);
                    cover = double(hits) / (g * g);
                }
                const size_t k = 3 * (size_t(y) * n + x);
                const double v = rgb[k], e = se[k], ref = D.L * cover;
                if (allSame) { // wholly inside or outside the disk: exact
                    if (!asOctagon && !(std::fabs(v - ref) <= 1e-6 * D.L))
                        fail_msg("pixel (%u, %u) %s the disk: %.7g, expected %.7g", x, y, a ? "inside" : "outside", v,
                                 ref);
                    continue;
                }
                const double z = e > 0.0 ? std::fabs(v - ref) / e : 0.0; // e = 0: every sample met, or missed
                worstZ = std::max(worstZ, z);
                if (asOctagon) {
                    worseOctagon += std::fabs(v - ref) > 5.0 * e + 2e-3 * D.L;
                    continue;
                }
                edgePixels++;
                if (!(std::fabs(v - ref) <= 5.0 * e + 2e-3 * D.L))
                    fail_msg("pixel (%u, %u) on the disk's edge: %.5f, L x its cover %.5f (se %.3g)", x, y, v, ref, e);
            }
        std::printf("%s seen by the camera: the pixels on the disk's edge up to %.1f standard errors off\n",
                    asOctagon ? "the octagon" : "the disk", worstZ);
    }
    std::printf("%d pixels on the disk's edge; the octagon's image fails at %d of them\n", edgePixels, worseOctagon);
    assert_true(edgePixels >= 20);
    assert_true(worseOctagon >= 4);
}

// A point light 2 above the floor, a disk light 1 above it facing up (it lights nothing below:
// one-sided) casting its shadow, twice its size, on the floor. A floor point whose line to the
// light crosses the disk's plane at 0.99 r where the octagon's edge cuts in (its apothem is
// 0.9746 r) is in the disk's shadow: exactly 0; one whose line crosses at 1.02 r where the
// octagon's vertex stands out (to 1.0549 r) is lit: a/pi I cos / d^2. The octagon the other
// way round; well inside and beyond, both alike.
void test_disk_shadow(void **) {
    const Disk D{glm::dvec3(0.0, 1.0, 0.0), kUp, 0.5, 1.0};
    const glm::dvec3 light(0.0, 2.0, 0.0);
    const double I = 3.0;
    const glm::dvec3 t = SceneBuilder::diskTangent(glm::vec3(D.n)), b = glm::cross(D.n, t);
    struct Point {
        double rho, angle; // where the line to the light crosses the disk's plane
        bool diskShadow, octagonShadow;
    };
    const Point points[] = {{0.99, kPi / 8.0, true, false}, {1.02, 0.0, false, true}, {0.5, 1.0, true, true},
                            {1.2, 2.0, false, false}};
    RenderSettings s;
    s.spp = 64;
    s.directOnly = true;
    for (const Point &pt : points)
        for (int asOctagon = 0; asOctagon < 2; asOctagon++) {
            // The floor point: the crossing's horizontal offset, doubled.
            const glm::dvec3 p = 2.0 * pt.rho * D.r * (std::cos(pt.angle) * t + std::sin(pt.angle) * b);
            SceneBuilder sb;
            floorPlane(sb, lambertMaterial(sb, kAlbedo));
            addDisk(sb, D, asOctagon != 0);
            sb.punctual(RTPBR_GLTF_PUNCTUAL_POINT, glm::vec3(light), glm::vec3(0, -1, 0), glm::vec3(float(I)));
            const Estimate e = renderPoint(sb, p, glm::normalize(glm::dvec3(0.2, 1.0, 0.3)), 0.3, s);
            const bool shadow = asOctagon ? pt.octagonShadow : pt.diskShadow;
            const glm::dvec3 toLight = light - p;
            const double d2 = glm::dot(toLight, toLight), lit = kAlbedo / kPi * I * toLight.y / std::sqrt(d2) / d2;
            char what[120];
            std::snprintf(what, sizeof what, "%s, the line to the light at %.2f r, %s", asOctagon ? "octagon" : "disk",
                          pt.rho, shadow ? "in shadow" : "lit");
            if (shadow) {
                std::printf("  %s: %g\n", what, e.v);
                assert_true(e.v == 0.0);
            } else {
                expectWithin(e, lit, what, 2e-5);
            }
        }
}

// ---- glossy: MIS with the BSDF rays that meet the disk -------------------------------------

// A GGX conductor floor (F0 0.9, single scattering, direct light) under a disk facing it, seen
// where it mirrors the disk: roughness 0.2 (the BSDF's samples find the disk far more often than
// the disk's own hit the narrow lobe: MIS weighs them) and 0.5, against the quadrature of f cos
// over the disk (f the shader library's BRDF_SpecularLocal, the oracle's single-scattering BRDF,
// tested on its own elsewhere; under test here are the disk's samples, the BSDF rays that meet
// it, and their weights).
void test_disk_ggx(void **) {
    const Disk D{glm::dvec3(0.0, 0.6, 0.0), -kUp, 0.4, 2.0};
    const glm::dvec3 p(0.25, 0.0, 0.1), wo = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));
    const rtpbr::FresnelParams F = rtpbr::Fresnel_FromF0(glm::vec3(0.9f));
    auto local = [](glm::dvec3 w) { return glm::vec3(float(w.x), float(-w.z), float(w.y)); };
    RenderSettings s;
    s.spp = 1u << 16;
    s.directOnly = true;
    s.singleScatter = true;
    for (double roughness : {0.2, 0.5}) {
        const float alpha = float(roughness * roughness);
        const glm::vec3 woL = local(wo);
        const double ref = quadrature(D, leaving(p), 0.0, 2.0 * kPi, 1e-6, [&](glm::dvec3 wi) {
            const glm::vec3 wiL = local(wi);
            return D.L * double(rtpbr::BRDF_SpecularLocal(woL, wiL, alpha, alpha, F).x) * double(wiL.z);
        });
        SceneBuilder b;
        floorPlane(b, b.material(glm::vec3(0.9f), 1.0f, float(roughness)));
        addDisk(b, D);
        char what[80];
        std::snprintf(what, sizeof what, "GGX roughness %.1f", roughness);
        expectWithin(renderPoint(b, p, wo, 0.3, s), ref, what);
    }
}

// ---- from glTF, and bad disks ------------------------------------------------------------------

// An ellipse (half-axes 0.6 along (1, 0, 1) / sqrt 2 and 0.25 across it, 0.4 above a Lambert
// floor, facing it, L = 2): under its centre the closed form a L r1 r2 / sqrt((r1^2 + h^2)
// (r2^2 + h^2)) (the disk's r^2 / (r^2 + h^2) when r1 = r2); half-way to its tip along the long
// axis, a midpoint quadrature over the ellipse (there the circle of the same area is 7.8 % low,
// the ellipse with its axes swapped 29 % low).
void test_ellipse(void **) {
    const glm::dvec3 c(0.0, 0.4, 0.0), n = -kUp, axis = glm::normalize(glm::dvec3(1.0, 0.0, 1.0));
    const double r1 = 0.6, r2 = 0.25, L = 2.0, h = 0.4;
    const glm::dvec3 across = glm::cross(n, axis);
    auto quadrature = [&](glm::dvec3 x) { // the floor's radiance at x: a / pi int L cos_x cos_l / d^2 dA
        const int m = 600;
        double sum = 0.0;
        for (int i = 0; i < m; i++)
            for (int j = 0; j < m; j++) {
                const double s = std::sqrt((i + 0.5) / m), phi = 2.0 * kPi * (j + 0.5) / m;
                const glm::dvec3 q = c + s * (r1 * std::cos(phi) * axis + r2 * std::sin(phi) * across) - x;
                const double d2 = glm::dot(q, q), cosX = q.y / std::sqrt(d2), cosL = -glm::dot(q, n) / std::sqrt(d2);
                if (cosX > 0.0 && cosL > 0.0)
                    sum += cosX * cosL / d2;
            }
        return kAlbedo / kPi * L * sum * kPi * r1 * r2 / (double(m) * m);
    };
    const glm::dvec3 p0(0.0), p1 = 0.5 * r1 * axis, toCamera = glm::normalize(glm::dvec3(0.0, 0.3, 1.0));
    const double he = h - leaving(p0).y; // (the references are taken just above the floor)
    const double closed = kAlbedo * L * r1 * r2 / std::sqrt((r1 * r1 + he * he) * (r2 * r2 + he * he));
    const double q0 = quadrature(leaving(p0)), q1 = quadrature(leaving(p1));
    std::printf("ellipse: under its centre closed form %.8f, quadrature %.8f; half-way to its tip quadrature %.8f\n",
                closed, q0, q1);
    assert_true(std::fabs(q0 - closed) <= 1e-5 * closed);
    RenderSettings s;
    s.spp = 1u << 20;
    s.directOnly = true;
    for (int k = 0; k < 2; k++) {
        SceneBuilder b;
        floorPlane(b, lambertMaterial(b, kAlbedo));
        b.ellipse(glm::vec3(c), glm::vec3(n), glm::vec3(axis), float(r1), float(r2), glm::vec3(float(L)), false);
        expectWithin(renderPoint(b, k ? p1 : p0, toCamera, 0.2, s), k ? q1 : closed,
                     k ? "ellipse, half-way to its tip" : "ellipse, under its centre", 1e-6);
    }
}

// An EXT_lights_area disk (size 1: radius 0.5; radiance 3; at the origin, emitting towards -z)
// through the loader, a 1 x 1 camera 1 from its plane looking along its axis at a point
// (x, y) of it: in front, L inside the disk and 0 outside, where the octagon would say the
// opposite (just beyond the disk at its vertex, local +x; just inside it at its edge's
// midpoint, 22.5 degrees on); behind, 0 (the loader's disks are one-sided and black).
void test_disk_from_gltf(void **) {
    struct View {
        double x, y;
        bool front;
        double expected;
    };
    const double c = std::cos(kPi / 8.0), sn = std::sin(kPi / 8.0);
    const View views[] = {{0.0, 0.0, true, 3.0}, {0.49, 0.0, true, 3.0}, {0.51, 0.0, true, 0.0},
                          {0.495 * c, 0.495 * sn, true, 3.0}, {0.2, -0.1, false, 0.0}};
    for (const View &v : views) {
        // glTF cameras look along -z: turned half a turn about y to look along +z from the front.
        char json[1024];
        std::snprintf(json, sizeof json,
                      "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"EXT_lights_area\"],"
                      "\"extensions\":{\"EXT_lights_area\":{\"lights\":[{\"type\":\"disk\",\"size\":1,"
                      "\"intensity\":3}]}},\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],"
                      "\"nodes\":[{\"extensions\":{\"EXT_lights_area\":{\"light\":0}}},"
                      "{\"camera\":0,\"translation\":[%.17g,%.17g,%d]%s}],"
                      "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.001,\"znear\":0.01}}]}",
                      v.x, v.y, v.front ? -1 : 1, v.front ? ",\"rotation\":[0,1,0,0]" : "");
        rtpbr_gltf_scene *scene = nullptr;
        rtpbr_gltf_load_desc desc{};
        if (rtpbr_gltf_load_memory(json, std::strlen(json), &desc, &scene) != RTPBR_GLTF_SUCCESS)
            fail_msg("the loader refused the disk scene");
        assert_int_equal(scene->light_count, 1);
        assert_int_equal(scene->lights[0].shape, RTPBR_GLTF_LIGHT_DISK);
        RenderSettings s;
        s.width = s.height = 1;
        s.spp = 64;
        s.directOnly = true;
        Accumulator acc;
        std::string err;
        const Result r = render(*scene, s, &acc, &err, nullptr);
        rtpbr_gltf_destroy(scene);
        if (r != Result::Success)
            fail_msg("render: %s", err.c_str());
        std::vector<float> rgb;
        resolve(acc, &rgb, nullptr);
        std::printf("  looking at (%.3f, %.3f) from the %s: %g\n", v.x, v.y, v.front ? "front" : "back", rgb[0]);
        assert_true(std::fabs(rgb[0] - v.expected) <= 1e-6 * 3.0);
    }
}

void expectRejected(const std::function<void(rtpbr_gltf_light &)> &spoil, Result want, const char *words) {
    SceneBuilder b;
    floorPlane(b, lambertMaterial(b, kAlbedo));
    addDisk(b, Disk{glm::dvec3(0.0, 1.0, 0.0), -kUp, 0.5, 1.0});
    b.camera(glm::vec3(0, 0.5f, 2), glm::vec3(0.0f), 0.8f);
    spoil(b.lights[0]);
    b.build();
    RenderSettings s;
    std::string err;
    Result r = validateScene(b.scene, s, &err);
    std::printf("  %s: %s\n", resultString(r), err.c_str());
    if (r != want || err.find(words) == std::string::npos)
        fail_msg("expected %s with \"%s\", got %s: %s", resultString(want), words, resultString(r), err.c_str());
}

void test_disk_validation(void **) {
    using L = rtpbr_gltf_light;
    const float nan = std::nanf("");
    expectRejected([](L &) {}, Result::Success, "");
    expectRejected([](L &l) { l.radius = 0.0f; }, Result::InvalidScene, "light 0 (disk): radius 0");
    expectRejected([](L &l) { l.radius = -0.5f; }, Result::InvalidScene, "light 0 (disk): radius -0.5");
    expectRejected([nan](L &l) { l.radius = nan; }, Result::InvalidScene, "light 0 (disk): radius nan");
    expectRejected([](L &l) { l.radius = INFINITY; }, Result::InvalidScene, "light 0 (disk): radius inf");
    expectRejected([nan](L &l) { l.facts.center[1] = nan; }, Result::InvalidScene, "centre (0, nan");
    expectRejected([](L &l) { l.facts.center[0] = 1e16f; }, Result::InvalidScene, "scene extent");
    expectRejected([](L &l) { l.radius = 2e15f; }, Result::InvalidScene, "the disk within the oracle's scene extent");
    expectRejected([](L &l) { l.facts.normal[1] = 0.0f; }, Result::InvalidScene, "a unit normal");
    expectRejected([](L &l) { l.facts.normal[1] = -0.9f; }, Result::InvalidScene, "a unit normal");
    expectRejected([](L &l) { l.shape = rtpbr_gltf_light_shape(7); }, Result::InvalidScene, "unknown shape 7");
    // A polygon's radius is not used.
    expectRejected([](L &l) { l.shape = RTPBR_GLTF_LIGHT_POLYGON, l.radius = -1.0f; }, Result::Success, "");
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_disk_on_axis), cmocka_unit_test(test_disk_parallel_offset),
                cmocka_unit_test(test_disk_sides), cmocka_unit_test(test_disk_horizon), cmocka_unit_test(test_disk_seen),
                cmocka_unit_test(test_disk_shadow), cmocka_unit_test(test_disk_ggx),
                cmocka_unit_test(test_disk_from_gltf), cmocka_unit_test(test_disk_validation),
                cmocka_unit_test(test_ellipse))
