// LTC polygon integration (shaderlib/rtpbr/ltc.h) against independent references:
//   - M = identity equals Lambert's closed-form polygon irradiance, clipped to the hemisphere
//     by the test's own double-precision code, within 1e-4, for random polygons (3 to 8
//     vertices, one- and two-sided, many crossing the horizon);
//   - the closed-form form factor of a rectangle parallel to the surface (Howell's catalogue);
//   - no light from below the surface's horizon, even where an LTC lobe extends below it;
//   - degenerate input stays finite, and is 0 where the light is invisible;
//   - the edge integral keeps its precision at tiny and near-pi angles.
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
extern "C" {
#include "test_main.h"
}

#include <cmath>
#include <cstdio>
#include <limits>

#include "rtpbr/ltc.h"
#include "rtpbr/ltc_clipless.h"
#include "ltc_reference.hpp"

using namespace ltcref;
using rtpbr::float3;
using rtpbr::float4;

static float3 f3(d3 a) { return float3(float(a.x), float(a.y), float(a.z)); }

static rtpbr::LtcPolygon make_poly(const std::vector<d3> &v, d3 offset) {
    rtpbr::LtcPolygon p = rtpbr::LTC_Triangle(f3(v[0] + offset), f3(v[1] + offset), f3(v[2] + offset));
    for (size_t i = 3; i < v.size(); i++)
        p.v[i] = f3(v[i] + offset);
    p.count = int(v.size());
    return p;
}

static void test_identity_matches_lambert(void **state) {
    (void)state;
    Rng rng(0x17c0ffee);
    const int cases = 4000;
    double maxErr = 0.0;
    int crossing = 0, visible = 0;
    for (int c = 0; c < cases; c++) {
        d3 N = rng.direction();
        d3 V = rng.direction();
        if (dot(V, N) < 0.0)
            V = V * -1.0;
        d3 P = {rng.range(-10, 10), rng.range(-10, 10), rng.range(-10, 10)};
        int k = 3 + int(rng.uniform() * 6.0);
        d3 centre = rng.direction() * rng.range(0.3, 4.0);
        double r1 = rng.range(0.05, 3.0), r2 = rng.range(0.05, 3.0);
        std::vector<d3> rel = random_polygon(rng, k, centre, rng.direction(), r1, r2);
        bool twoSided = (c & 1) != 0;
        double ref = lambert_form_factor(rel, N, twoSided);
        bool above = false, below = false;
        for (d3 p : rel) {
            above |= dot(p, N) > 0.0;
            below |= dot(p, N) < 0.0;
        }
        crossing += above && below;
        visible += ref > 0.0;
        float got = rtpbr::LTC_EvaluatePolygon(f3(N), f3(V), f3(P), make_poly(rel, P),
                                               rtpbr::LTC_Identity(), twoSided);
        double err = std::fabs(got - ref);
        if (err > maxErr)
            maxErr = err;
        if (err > 1e-4)
            fprintf(stderr, "case %d: k=%d ref=%.7f ltc=%.7f\n", c, k, ref, double(got));
        assert_true(err <= 1e-4);
    }
    fprintf(stderr, "identity vs Lambert: %d polygons (%d crossing the horizon, %d visible), max |error| %.2e\n",
            cases, crossing, visible, maxErr);
    assert_true(crossing > cases / 4);
    assert_true(visible > cases / 3);
}

// Howell, "A Catalog of Radiation Heat Transfer Configuration Factors" (differential
// area to a parallel rectangle with a corner above it): with X = a/c, Y = b/c,
// F = (1 / 2pi) (X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2))).
static void test_rectangle_closed_form(void **state) {
    (void)state;
    const double dims[][3] = {{1, 1, 1}, {0.1, 2, 0.5}, {5, 3, 0.2}, {0.01, 0.01, 1}, {100, 100, 1}};
    for (const auto &d : dims) {
        double a = d[0], b = d[1], c = d[2];
        double X = a / c, Y = b / c;
        double ref = (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
                      Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) / (2.0 * M_PI);
        // counter-clockwise seen from below (from the shading point at the origin)
        rtpbr::LtcPolygon q = rtpbr::LTC_Quad(float3(0, 0, c), float3(0, b, c), float3(a, b, c), float3(a, 0, c));
        float got = rtpbr::LTC_EvaluatePolygon(float3(0, 0, 1), float3(0.6f, 0, 0.8f), float3(0),
                                               q, rtpbr::LTC_Identity(), false);
        fprintf(stderr, "rectangle %gx%g at %g: closed form %.7f ltc %.7f\n", a, b, c, ref, double(got));
        assert_true(std::fabs(got - ref) <= 1e-5);
    }
}

// A lobe whose support extends below the horizon: (M^-1 w).z = 0.8 w.x + w.z > 0 also for
// w.z < 0 when w.x > 0. A light entirely below the surface must give 0.
static void test_no_light_from_below(void **state) {
    (void)state;
    const float4 ltc1(1.0f, 0.0f, 0.8f, 1.0f);
    rtpbr::LtcPolygon below = rtpbr::LTC_Quad(float3(2, -1, -0.1f), float3(2, 1, -0.1f),
                                              float3(2, 1, -0.6f), float3(2, -1, -0.6f));
    float3 N(0, 0, 1), V(0.2f, 0, 0.98f);
    float got = rtpbr::LTC_EvaluatePolygon(N, V, float3(0), below, ltc1, true);
    assert_true(got == 0.0f);
    // The same polygon without the surface-horizon clip (only the LTC's own clip, which is
    // what clipping after the transform does) receives light: the test can fail.
    rtpbr::LtcLocalPolygon unclipped = rtpbr::LTC_PolygonToLocalUnclipped(rtpbr::LTC_Frame(N, V), float3(0), below, true);
    float leak = rtpbr::LTC_IntegrateLocal(unclipped, ltc1);
    fprintf(stderr, "below-horizon light: clipped %.3g, clipped in LTC space only %.3g\n", double(got), double(leak));
    assert_true(leak > 1e-3f);
    // Half above, half below: only the upper half counts.
    rtpbr::LtcPolygon half = rtpbr::LTC_Quad(float3(2, -1, 0.5f), float3(2, 1, 0.5f),
                                             float3(2, 1, -0.5f), float3(2, -1, -0.5f));
    rtpbr::LtcPolygon upper = rtpbr::LTC_Quad(float3(2, -1, 0.5f), float3(2, 1, 0.5f),
                                              float3(2, 1, 0.0f), float3(2, -1, 0.0f));
    float h = rtpbr::LTC_EvaluatePolygon(N, V, float3(0), half, ltc1, true);
    float u = rtpbr::LTC_EvaluatePolygon(N, V, float3(0), upper, ltc1, true);
    assert_true(std::fabs(h - u) <= 1e-6f && u > 0.0f);
}

static bool finite(float x) { return std::isfinite(x); }

static void test_degenerate_cases(void **state) {
    (void)state;
    const float4 lobes[] = {float4(1, 0, 0, 1), float4(8.0f, -3.0f, 0.4f, 0.9f), float4(300.0f, -200.0f, 0.1f, 0.5f)};
    const float3 N(0, 0, 1), V(0.7f, 0, 0.714f), P(0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const float4 &l : lobes) {
        for (int sided = 0; sided < 2; sided++) {
            bool two = sided != 0;
            auto eval = [&](rtpbr::LtcPolygon p) {
                float a = rtpbr::LTC_EvaluatePolygon(N, V, P, p, l, two);
                rtpbr::LtcLocalPolygon loc = rtpbr::LTC_PolygonToLocalUnclipped(rtpbr::LTC_Frame(N, V), P, p, two);
                float3 F = rtpbr::LTC_FormFactorVector(loc, l);
                float b = rtpbr::LTC_SphereFormFactorApprox(F);
                float c = rtpbr::LTC_SphereFormFactor(F, 0.7f);
                assert_true(finite(a) && finite(b) && finite(c) && finite(F.x) && finite(F.y) && finite(F.z));
                assert_true(a >= 0.0f && a <= 1.0f && b >= 0.0f && b <= 1.0f);
                return a;
            };
            float3 q(0.3f, 0.2f, 1.0f);
            // zero area: coincident vertices, collinear vertices
            assert_true(eval(rtpbr::LTC_Quad(q, q, q, q)) == 0.0f);
            assert_true(eval(rtpbr::LTC_Triangle(q, q * 2.0f, q * 3.0f)) == 0.0f);
            assert_true(eval(rtpbr::LTC_Quad(float3(-1, 0.5f, 1), float3(0, 0.5f, 1), float3(1, 0.5f, 1), float3(2, 0.5f, 1))) == 0.0f);
            // entirely below the horizon
            assert_true(eval(rtpbr::LTC_Quad(float3(-1, -1, -1), float3(-1, 1, -1), float3(1, 1, -1), float3(1, -1, -1))) == 0.0f);
            // a vertex touching the shading point; P inside the polygon; edge-on
            assert_true(eval(rtpbr::LTC_Triangle(P, float3(1, 0, 1), float3(0, 1, 1))) == 0.0f);
            assert_true(eval(rtpbr::LTC_Quad(float3(-1, -1, 0.5f), float3(1, -1, -0.5f), float3(1, 1, -0.5f), float3(-1, 1, 0.5f)) ) >= 0.0f);
            assert_true(eval(rtpbr::LTC_Quad(float3(-1, -1, 1), float3(-1, 1, 1), float3(-1, 1, 2), float3(-1, -1, 2))) >= 0.0f);
            assert_true(eval(rtpbr::LTC_Quad(float3(1, -1, 0), float3(1, 1, 0), float3(1, 1, 1e-30f), float3(1, -1, 1e-30f))) == 0.0f);
            // P exactly on the light's plane, inside it
            assert_true(eval(rtpbr::LTC_Quad(float3(-1, -1, 1), float3(1, -1, -1), float3(1, 1, -1), float3(-1, 1, 1))) == 0.0f);
            // an edge on the horizon; a light lying on the surface plane
            assert_true(eval(rtpbr::LTC_Quad(float3(1, -1, 0), float3(1, 1, 0), float3(1, 1, 1), float3(1, -1, 1))) >= 0.0f);
            // nearly opposite vertices: a huge light overhead (the whole hemisphere)
            float big = 1e6f;
            float h = eval(rtpbr::LTC_Quad(float3(-big, -big, 1), float3(-big, big, 1), float3(big, big, 1), float3(big, -big, 1)));
            if (l.x == 1.0f && l.y == 0.0f)
                assert_true(std::fabs(h - 1.0f) < 1e-4f); // the whole hemisphere
            // a huge triangle whose horizon crossings are nearly opposite
            eval(rtpbr::LTC_Triangle(float3(-big, 0.1f, -1), float3(big, 0.1f, -1), float3(0, 0.1f, big)));
            // bad vertex counts and NaN
            rtpbr::LtcPolygon bad = rtpbr::LTC_Quad(float3(-1, -1, 1), float3(-1, 1, 1), float3(1, 1, 1), float3(1, -1, 1));
            bad.count = 2;
            assert_true(eval(bad) == 0.0f);
            bad.count = 9;
            assert_true(eval(bad) == 0.0f);
            bad.count = -1;
            assert_true(eval(bad) == 0.0f);
            bad.count = 4;
            bad.v[2] = float3(nan, 0, 1);
            assert_true(eval(bad) == 0.0f);
        }
    }
    // A NaN normal or view does not crash and returns a finite value.
    float r = rtpbr::LTC_EvaluatePolygon(float3(nan), float3(0, 0, 1), float3(0),
                                         rtpbr::LTC_Quad(float3(-1, -1, 1), float3(-1, 1, 1), float3(1, 1, 1), float3(1, -1, 1)),
                                         rtpbr::LTC_Identity(), true);
    assert_true(finite(r));
}

static void test_one_sided(void **state) {
    (void)state;
    // Counter-clockwise seen from the origin below: front-facing.
    rtpbr::LtcPolygon front = rtpbr::LTC_Quad(float3(-1, -1, 1), float3(-1, 1, 1), float3(1, 1, 1), float3(1, -1, 1));
    rtpbr::LtcPolygon back = rtpbr::LTC_Quad(float3(-1, -1, 1), float3(1, -1, 1), float3(1, 1, 1), float3(-1, 1, 1));
    float3 N(0, 0, 1), V(0, 0, 1);
    float f = rtpbr::LTC_EvaluatePolygon(N, V, float3(0), front, rtpbr::LTC_Identity(), false);
    float b = rtpbr::LTC_EvaluatePolygon(N, V, float3(0), back, rtpbr::LTC_Identity(), false);
    float b2 = rtpbr::LTC_EvaluatePolygon(N, V, float3(0), back, rtpbr::LTC_Identity(), true);
    assert_true(f > 0.1f && b == 0.0f && std::fabs(b2 - f) < 1e-6f);
}

// The edge integral (the fitted theta / sin theta of LTC_EdgeFactor): 2 pi LTC_EdgeIntegral(a, b)
// = theta * normalize(a x b) for angles from 1e-6 to pi - 1e-4, against double; the fit's own
// error over its whole domain, against the exact theta / sin theta in double.
static void test_edge_precision(void **state) {
    (void)state;
    double worst = 0.0;
    for (int e = 0; e <= 60; e++) {
        double theta = e < 30 ? std::pow(10.0, -6.0 + 0.2 * e) : M_PI - std::pow(10.0, -4.0 + 0.1 * (e - 30)) ;
        d3 a = unit(d3{1, 0.3, 0.2});
        d3 t = unit(cross(a, d3{0, 0, 1}));
        d3 b = a * std::cos(theta) + t * std::sin(theta);
        float3 v = rtpbr::LTC_EdgeIntegral(f3(a), f3(unit(b))) * float(2.0 * M_PI);
        d3 expect = unit(cross(a, b)) * theta;
        double err = len(d3{v.x - expect.x, v.y - expect.y, v.z - expect.z});
        double rel = err / theta;
        if (theta < 3.1 && rel > worst)
            worst = rel;
        assert_true(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
        // Float input directions carry ~6e-8 rounding: the angle is good to that, relative
        // for small angles; near pi the direction of a x b itself is ill-conditioned.
        if (theta < 3.1)
            assert_true(rel < 2e-6 || err < 2e-7);
    }
    fprintf(stderr, "edge integral: worst relative error %.2e (angles 1e-6 .. 3.1)\n", worst);
    double fitWorst = 0.0;
    for (int i = 0; i <= 200000; i++) {
        double x = -0.99999 + 1.99999 * i / 200000.0;
        double theta = std::acos(x), sinT = std::sqrt(1.0 - x * x);
        double exact = (sinT > 0.0 ? theta / sinT : 1.0) / (2.0 * M_PI);
        double fit = rtpbr::LTC_EdgeFactor(float(x), float(sinT));
        fitWorst = std::max(fitWorst, std::fabs(fit - exact) / exact);
    }
    fprintf(stderr, "fitted theta / sin theta: worst relative error %.2e on [-0.99999, 1]\n", fitWorst);
    assert_true(fitWorst < 1e-5);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_identity_matches_lambert),
                cmocka_unit_test(test_rectangle_closed_form),
                cmocka_unit_test(test_no_light_from_below),
                cmocka_unit_test(test_degenerate_cases),
                cmocka_unit_test(test_one_sided),
                cmocka_unit_test(test_edge_precision))
