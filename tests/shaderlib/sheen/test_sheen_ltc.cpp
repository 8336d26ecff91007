// The sheen LTC table (shaderlib/luts/rtpbr_ltc_sheen_tables.h) against Monte Carlo
// integration of the true lobe (D_Charlie V_Charlie cos, sheenColor 1) over square lights on
// the reduced grid of tools/ltcfit/ltc_mc.hpp (the full grid: rtpbr-ltc-validate --sheen, in
// shaderlib/luts/sheen.md), and its norm x the LTC's mass above the horizon against the
// directional albedo by an independent quadrature (sheen_reference.hpp).
// Bounds: the measured values on this deterministic grid with ~30% margin (they are what a
// linearly transformed cosine can do for this lobe, see sheen.md; a broken table, layout or
// frame fails them): lights that matter (20): mean < 29% (21.9%), 95th pct < 92% (70%),
// max < 117% (89%); far tail < 5.5% (4.1%) of the albedo; norm x mass within 0.5% (0.36%) of
// the quadrature albedo.
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
extern "C" {
#include "test_main.h"
}

#include "ltc_mc.hpp"
#include "sheen_reference.hpp"

using namespace ltcmc;

static void test_sheen_vs_mc(void **state) {
    (void)state;
    std::vector<Config> g = grid(true, {Lobe::Sheen});
    std::vector<double> rel;
    double worstRef = 0.0, worstTail = 0.0;
    uint64_t seed = 1;
    for (const Config &c : g) {
        Outcome o = run_config(c, FresnelChoice{}, 1e-3, 1l << 21, seed++);
        assert_true(std::isfinite(o.ltc.exact) && std::isfinite(o.ltc.clipless_table));
        if (o.significant) {
            worstRef = std::max(worstRef, o.ref.relStdErr);
            rel.push_back(o.relExact);
            if (o.relExact > 0.3)
                fprintf(stderr, "  r=%.2f view=%g half=%g %s ref=%.5f ltc=%.5f\n", c.roughness, c.viewDeg, c.half,
                        position_name(c.position), o.ref.mean, o.ltc.exact);
        } else {
            worstTail = std::max(worstTail, o.relExact);
        }
    }
    Summary s = summarize(rel);
    fprintf(stderr, "Sheen LTC vs MC (%d lights that matter, reference rel. std. error <= %.2e): mean %.2f%%, 95th pct "
            "%.2f%%, max %.2f%%; far-tail max |LTC - MC| / albedo %.2e\n", s.count, worstRef, 100 * s.mean,
            100 * s.p95, 100 * s.max, worstTail);
    assert_true(s.count >= 15);
    assert_true(s.mean < 0.29);
    assert_true(s.p95 < 0.92);
    assert_true(s.max < 1.17);
    assert_true(worstTail < 0.055);
}

// norm x the LTC's mass above the horizon = the directional albedo (quadrature of the
// independent formulas) on an 8 x 8 subset of texel centres; the Fresnel columns are 0.
static void test_sheen_ltc_albedo(void **state) {
    (void)state;
    const int n = RTPBR_LTC_SIZE;
    double worst = 0.0;
    for (int row = 0; row < n; row++)
        for (int col = 0; col < n; col++) {
            const float *t2 = rtpbr_ltc_sheen_2 + (size_t(row) * n + col) * 4;
            assert_true(t2[1] == 0.0f && t2[2] == 0.0f && std::isfinite(t2[0]) && t2[0] >= 0.0f);
        }
    for (int row = 0; row < n; row += 9)
        for (int col = 0; col < n; col += 9) {
            const float *t2 = rtpbr_ltc_sheen_2 + (size_t(row) * n + col) * 4;
            double x = double(row) / (n - 1);
            double nov = std::max(1.0 - x * x, 1e-3);
            double r = double(col) / (n - 1);
            double ref = sheenref::quadratureAlbedo(0, nov, std::max(r * r, 1e-3), 800, 400);
            double e = std::fabs(double(t2[0]) - ref) / std::max(ref, 0.01);
            worst = std::max(worst, e);
        }
    fprintf(stderr, "Sheen LTC: norm vs quadrature albedo: max relative difference %.3f%%\n", 100 * worst);
    assert_true(worst < 0.005);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_sheen_ltc_albedo),
                cmocka_unit_test(test_sheen_vs_mc))
