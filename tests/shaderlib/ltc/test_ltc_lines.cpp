// Line and tube lights (shaderlib/rtpbr/ltc_lines.h) in the C++ build, against noise-free
// double-precision quadrature of the LTC distribution itself, D(w) = D_o(M^-1 w / |M^-1 w|)
// |det M^-1| / |M^-1 w|^3 with D_o = max(z, 0) / pi, over the light above the horizon (z > 0),
// divided by the lobe's mass above the horizon (what the functions return: ltc.h's
// conventions), for the Lambert lobe (M = identity) and lobes of the committed GGX table.
//   - A line of width W: W int D(p / |p|) n / |p|^3 dt along the segment (the facing strip's
//     solid angle, n the line's distance from the point), Gauss-Legendre panels over the part
//     above the horizon; and a real quad of small width by a 2-D rule, which the line must
//     match to O((W / n)^2).
//   - A tube: the capsule's surface (the cylinder and both outer hemispheres), where a convex
//     body is seen exactly through its front-facing points: D(w) max(0, -n.w) / |x|^2 dA.
//   - The limits: length 0 is LTC_EvaluateSphere's value, radius -> 0 the line's.
#include "rtpbr/ltc_lines.h"
#include "luts/rtpbr_ltc_tables.h"

extern "C" {
#include "test_main.h"
}

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "capsule_quadrature.hpp" // capsule_integral, integrate (gauss_legendre)

using rtpbr::float3;
using rtpbr::float4;

namespace {

struct D3 {
    double x, y, z;
};
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double len(D3 a) { return std::sqrt(dot(a, a)); }
D3 unit(D3 a) { return a * (1.0 / len(a)); }
float3 f3(D3 v) { return float3(float(v.x), float(v.y), float(v.z)); }

// The LTC distribution for ltc1 = (m00, m02, m20, m22) of M^-1 (ltc.h's layout), local frame.
struct Lobe {
    const char *name;
    double m00, m02, m20, m22;
    // D over every direction (below the horizon too: what a lobe that is not clipped sees)
    double D(D3 w) const {
        D3 t = {m00 * w.x + m02 * w.z, w.y, m20 * w.x + m22 * w.z};
        double l = len(t);
        double det = std::fabs(m00 * m22 - m02 * m20);
        return std::max(t.z / l, 0.0) / M_PI * det / (l * l * l);
    }
    // The clamped cosine's share on the side n of a plane through the origin is (1 + n.z) / 2
    // (a tilted plane's sky view factor); the horizon's image under M^-1 has the normal
    // (M^-1 x) x (M^-1 y) = (-m20, 0, m00), turned toward M^-1 z.
    double mass() const {
        double s = m00 * m22 - m02 * m20 < 0.0 ? -1.0 : 1.0;
        D3 n = D3{-m20, 0.0, m00} * s;
        return 0.5 * (1.0 + n.z / len(n));
    }
    float4 ltc1() const { return float4(float(m00), float(m02), float(m20), float(m22)); }
};

// Texel (i, j) of the GGX table: perceptual roughness i / 63, sqrt(1 - NoV) = j / 63.
Lobe ggx(const char *name, int i, int j) {
    const float *t = rtpbr_ltc_ggx_1 + (size_t(j) * RTPBR_LTC_SIZE + size_t(i)) * 4;
    return {name, t[0], t[1], t[2], t[3]};
}

const Lobe kLambert = {"Lambert", 1, 0, 0, 1};

// The shading point at the origin, N = z, V in the xz-plane: LTC_Frame is the identity.
const float3 kN(0, 0, 1), kV(0.6f, 0.0f, 0.8f), kP(0, 0, 0);

// The line a -> b of width W: W int D(p / |p|) n / |p|^3 dt over the part with z > 0, over the
// lobe's mass above the horizon. aboveOnly = false: D's integral over the whole segment, below
// the horizon too (a clip in the cosine's space alone sees that).
double line_reference(const Lobe &lobe, D3 a, D3 b, double W, bool aboveOnly = true) {
    D3 T = unit(b - a);
    double t1 = dot(a, T), t2 = dot(b, T);
    D3 foot = a - T * t1;
    double n = len(foot);
    if (aboveOnly) { // keep t where foot.z + t T.z > 0
        if (T.z != 0.0) {
            double t0 = -foot.z / T.z;
            if (T.z > 0.0) t1 = std::max(t1, t0);
            else t2 = std::min(t2, t0);
        } else if (foot.z <= 0.0) {
            return 0.0;
        }
        if (!(t2 > t1)) return 0.0;
    }
    double sum = integrate(t1, t2, 400, 16, [&](double t) {
        D3 p = foot + T * t;
        double r = len(p);
        return lobe.D(p * (1.0 / r)) * n / (r * r * r);
    });
    return W * sum / lobe.mass();
}

// A real quad of width W along a -> b, its width along cross(a, b) (facing the point), by a
// 2-D rule over its area: D(w) |cos| / r^2 dA, above the horizon.
double quad_reference(const Lobe &lobe, D3 a, D3 b, double W) {
    D3 o = unit(cross(a, b)), nq = unit(cross(b - a, o));
    double L = len(b - a);
    D3 T = (b - a) * (1.0 / L);
    double sum = integrate(0.0, L, 400, 16, [&](double t) {
        return integrate(-0.5 * W, 0.5 * W, 1, 8, [&](double s) {
            D3 p = a + T * t + o * s;
            if (p.z <= 0.0) return 0.0;
            double r = len(p);
            D3 w = p * (1.0 / r);
            return lobe.D(w) * std::fabs(dot(nq, w)) / (r * r);
        });
    });
    return sum / lobe.mass();
}

float line_ff(const Lobe &lobe, D3 a, D3 b, double W) {
    return rtpbr::LTC_EvaluateLine(kN, kV, kP, f3(a), f3(b), float(W), lobe.ltc1());
}

// The capsule of radius r around a -> b (relative to the point): its front-facing surface
// (capsule_quadrature.hpp), over the lobe's mass above the horizon.
double capsule_reference(const Lobe &lobe, D3 a, D3 b, double r, int scale = 1) {
    const double A[3] = {a.x, a.y, a.z}, B[3] = {b.x, b.y, b.z};
    return capsule_integral(A, B, r, [&](double x, double y, double z) { return lobe.D({x, y, z}); }, scale) / lobe.mass();
}

float tube_ff(const Lobe &lobe, D3 a, D3 b, double r) {
    return rtpbr::LTC_EvaluateTube(kN, kV, kP, f3(a), f3(b), float(r), lobe.ltc1());
}

std::vector<Lobe> lobes() {
    // GGX at NoV 0.69 (j = 35) and roughness 0.25, 0.5, 0.75; and a grazing view (NoV 0.09)
    return {kLambert, ggx("GGX 0.25", 16, 35), ggx("GGX 0.5", 32, 35), ggx("GGX 0.75", 47, 35),
            ggx("GGX 0.5 grazing", 32, 60)};
}

struct LineCase {
    const char *name;
    D3 a, b;
};

// Measured largest relative errors per lobe (Lambert, GGX 0.25, 0.5, 0.75, 0.5 grazing):
// 2.2e-7, 1.3e-6, 4.4e-7, 7.5e-7, 1.2e-5 (the last on a segment mostly below the horizon, a
// value of 9e-7); float rounding. Held at the bounds below.
void test_line_against_quadrature(void **) {
    const double bound[5] = {5e-7, 2e-6, 1e-6, 1e-6, 1.5e-5};
    const LineCase cases[] = {
        {"oblique, above", {-1.0, -0.8, 1.0}, {0.5, 0.9, 1.6}},
        {"toward the reflection", {-2.0, -0.5, 1.5}, {-1.0, 0.5, 1.2}},
        {"long, overhead", {-6.0, 0.3, 0.8}, {6.0, 0.3, 0.8}},
        {"across the horizon", {-1.5, -1.0, -0.4}, {-1.0, 1.0, 0.7}},
        {"across the horizon, mostly below", {1.2, -1.0, -1.5}, {0.4, 0.6, 0.2}},
        {"near, nearly through the point", {-0.3, -0.2, 0.02}, {0.4, 0.25, 0.15}},
        {"nearly end-on", {-0.5, 0.0, 0.5}, {-1.5, 0.003, 1.5}},
        {"short and far", {-40.0, 0.0, 30.0}, {-40.0, 0.02, 30.0}},
    };
    bool ok = true;
    int li = 0;
    for (const Lobe &lobe : lobes()) {
        double worst = 0.0;
        for (const LineCase &c : cases) {
            double W = 0.01;
            double want = line_reference(lobe, c.a, c.b, W);
            double got = line_ff(lobe, c.a, c.b, W);
            double rel = want > 0.0 ? std::fabs(got - want) / want : std::fabs(got); // 0 where the lobe sees none
            worst = std::max(worst, rel);
            std::printf("%-16s %-36s quadrature %.6e  ltc_lines %.6e  relative error %.2e\n", lobe.name, c.name, want, got, rel);
        }
        std::printf("%-16s largest relative error %.2e (held at %.1e)\n", lobe.name, worst, bound[li]);
        ok = ok && worst <= bound[li++];
    }
    assert_true(ok);
}

void test_line_below_horizon(void **) {
    for (const Lobe &lobe : lobes()) {
        D3 a = {-1.0, -1.0, -1e-3}, b = {-1.0, 1.0, -1e-4};
        double leak = line_reference(lobe, a, b, 0.01, false);
        float got = line_ff(lobe, a, b, 0.01);
        std::printf("%-16s just below the ground: ltc_lines %.3e (the lobe's own integral there %.3e)\n", lobe.name, got, leak);
        assert_true(got == 0.0f);
        assert_true(lobe.m20 == 0.0 || leak > 1e-4); // the sheared lobes do reach below
    }
}

// The line is the limit of the facing quad as its width W -> 0: a real quad of width W
// differs by O((W / n)^2). Measured (W = 0.1 and 0.01 at n ~ 1.5): Lambert 8.3e-4, 8.3e-6;
// GGX 0.25 1.3e-2, 1.3e-4; GGX 0.5 1.5e-3, 1.5e-5; GGX 0.75 8.1e-4, 8.1e-6; grazing 4.9e-4,
// 4.9e-6: second order (x 100 for W / 10), largest for the sharpest lobe.
void test_line_against_thin_quad(void **) {
    for (const Lobe &lobe : lobes()) {
        D3 a = {-1.0, -0.8, 1.0}, b = {0.5, 0.9, 1.6};
        double err[2];
        for (int k = 0; k < 2; ++k) {
            double W = k ? 0.01 : 0.1;
            double quad = quad_reference(lobe, a, b, W), line = line_reference(lobe, a, b, W);
            float got = line_ff(lobe, a, b, W);
            err[k] = std::fabs(got - quad) / quad;
            std::printf("%-16s W = %.2f quad %.6e  line %.6e (%.2e)  ltc_lines %.6e (%.2e)\n", lobe.name, W, quad, line,
                        std::fabs(line - quad) / quad, got, err[k]);
        }
        assert_true(err[0] < 1.5e-2 && err[1] < 1.5e-4 && err[1] < err[0] / 50.0);
    }
}

struct TubeCase {
    const char *name;
    D3 a, b;
    double r;
    double bound[5]; // the relative error held per lobe (lobes()'s order), measured: see the printout
};

// Measured relative errors (Lambert, GGX 0.25, 0.5, 0.75, 0.5 grazing), held at the bounds:
//   broadside, far        3.8e-5 1.6e-4 5.3e-4 1.5e-4 5.7e-4
//   broadside, near       3.5e-3 2.3e-4 5.2e-3 7.0e-3 4.2e-3
//   oblique               1.1e-3 8.1e-4 3.1e-3 1.9e-3 2.9e-3
//   fat and short         2.3e-3 2.6e-1 5.1e-2 1.1e-2 4.0e-2  (length ~ radius: the spheres are
//                         counted whole, weighted, where only their parts outside the quad
//                         show; a sharp lobe on the inner parts counts them twice)
//   nearly end-on, end-on <= 5.0e-7 (one sphere hides the rest: exact)
//   toward end-on         3.7e-4 3.1e-2 1.6e-3 4.4e-4 3.6e-3  (the far sphere mostly hidden)
//   half end-on           7.6e-5 4.4e-2 2.3e-3 4.7e-4 9.7e-4
//   long, overhead        2.8e-5 3.4e-5 3.6e-5 3.8e-5 1.1e-4
//   close (d = 1.9 r)     9.5e-3 1.1e-4 2.3e-3 7.7e-3 1.5e-3
//   across the horizon    1.4e-3 1.3e-3 1.5e-3 2.8e-4 4.2e-4
// The reference's own error (the rule doubled in each direction): <= 1.7e-6, 3.8e-5 across the
// horizon (D's step there).
const TubeCase kTubes[] = {
    {"broadside, far", {-3.0, -1.0, 3.0}, {-3.0, 1.0, 3.0}, 0.05, {5e-5, 2e-4, 7e-4, 2e-4, 7e-4}},
    {"broadside, near", {-1.0, -1.0, 1.0}, {-1.0, 1.0, 1.0}, 0.2, {4e-3, 3e-4, 6e-3, 8e-3, 5e-3}},
    {"oblique", {-2.0, -0.5, 1.0}, {0.5, 0.8, 2.5}, 0.15, {1.3e-3, 1e-3, 4e-3, 2.5e-3, 4e-3}},
    {"fat and short", {-1.0, 0.0, 1.5}, {-1.3, 0.2, 1.6}, 0.3, {3e-3, 0.3, 6e-2, 1.3e-2, 5e-2}},
    {"nearly end-on", {-1.5, 0.0, 1.5}, {-2.7, 0.12, 2.7}, 0.2, {1e-6, 1e-6, 1e-6, 1e-6, 1e-6}},
    {"end-on", {-1.5, 0.0, 1.5}, {-2.7, 0.0, 2.7}, 0.2, {1e-6, 1e-6, 1e-6, 1e-6, 1e-6}},
    {"toward end-on", {-1.5, 0.0, 1.5}, {-2.7, 0.25, 2.7}, 0.2, {5e-4, 4e-2, 2e-3, 6e-4, 4.5e-3}},
    {"half end-on", {-1.5, 0.0, 1.5}, {-2.7, 0.5, 2.7}, 0.2, {1e-4, 5.5e-2, 3e-3, 6e-4, 1.2e-3}},
    {"long, overhead", {-5.0, 0.3, 0.8}, {5.0, 0.3, 0.8}, 0.1, {4e-5, 5e-5, 5e-5, 5e-5, 1.3e-4}},
    {"close", {-0.3, -1.0, 0.5}, {-0.3, 1.0, 0.5}, 0.3, {1.2e-2, 1.5e-4, 3e-3, 1e-2, 2e-3}},
    {"across the horizon", {-1.5, -1.0, -0.3}, {-1.5, 1.0, 0.6}, 0.1, {2e-3, 1.6e-3, 1.7e-3, 3e-4, 5e-4}},
};

void test_tube_against_quadrature(void **) {
    bool ok = true;
    int li = 0;
    for (const Lobe &lobe : lobes()) {
        for (const TubeCase &c : kTubes) {
            double want = capsule_reference(lobe, c.a, c.b, c.r);
            double got = tube_ff(lobe, c.a, c.b, c.r);
            double rel = std::fabs(got - want) / want;
            bool pass = rel <= c.bound[li];
            std::printf("%-16s %-20s quadrature %.6e  ltc_lines %.6e  relative error %.2e (held at %.1e)%s\n", lobe.name,
                        c.name, want, got, rel, c.bound[li], pass ? "" : "  FAIL");
            ok = ok && pass;
        }
        ++li;
    }
    assert_true(ok);
}

// The limits, for a sphere above the horizon and one across it. Length 0: LTC_EvaluateSphere's
// value, bit for bit; length L: off by at most 0.64 L / r relative (measured 2.6e-4 at
// L = 1e-4, r = 0.25: the caps' weights and the quad move linearly). Radius -> 0: the line of width
// 2 r, off by at most 1.7 r relative (measured 1.7e-5 at r = 1e-5: the caps, O(r^2) against
// the line's O(r)); below RTPBR_LTC_TUBE_THIN the tube takes the line's closed form, which
// keeps that linear convergence (the quad alone, in float, was 1.7e-2 off at r = 1e-5).
// Also: a tube just below the ground gives exactly 0, a point inside the capsule 1.
void test_tube_limits(void **) {
    const D3 centres[] = {{-1.0, 0.2, 1.5}, {-1.0, -0.5, 0.1}}; // above; across the horizon
    const D3 dir = unit({0.3, 1.0, 0.2});
    bool ok = true;
    for (const Lobe &lobe : lobes()) {
        for (D3 c : centres) {
            double r = 0.25;
            float sphere = rtpbr::LTC_EvaluateSphere(kN, kV, kP, f3(c), float(r), lobe.ltc1());
            ok = ok && tube_ff(lobe, c, c, r) == sphere && sphere > 0.0f;
            std::printf("%-16s sphere %.6e; relative difference at length", lobe.name, sphere);
            for (double L : {1e-2, 1e-3, 1e-4}) {
                D3 a = c - dir * (0.5 * L), b = c + dir * (0.5 * L);
                double rel = std::fabs(tube_ff(lobe, a, b, r) - sphere) / sphere;
                std::printf("  %.0e: %.2e", L, rel);
                ok = ok && rel <= 0.8 * L / r;
            }
            D3 a = c - dir * 0.8, b = c + dir * 0.8;
            std::printf("; from the line at radius");
            for (double rr : {1e-2, 1e-3, 1e-4, 1e-5}) {
                double line = line_ff(lobe, a, b, 2.0 * rr);
                double rel = std::fabs(tube_ff(lobe, a, b, rr) - line) / line;
                std::printf("  %.0e: %.2e", rr, rel);
                ok = ok && rel <= 2.0 * rr;
            }
            std::printf("\n");
        }
        // just below the ground: exactly nothing; inside the capsule: everything
        ok = ok && tube_ff(lobe, {-1.0, -1.0, -0.1001}, {-1.0, 1.0, -0.1001}, 0.1) == 0.0f;
        ok = ok && tube_ff(lobe, {-0.5, -1.0, 0.05}, {0.5, 1.0, 0.05}, 0.1) == 1.0f;
    }
    assert_true(ok);
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_line_against_quadrature), cmocka_unit_test(test_line_below_horizon),
                cmocka_unit_test(test_line_against_thin_quad), cmocka_unit_test(test_tube_against_quadrature),
                cmocka_unit_test(test_tube_limits))
