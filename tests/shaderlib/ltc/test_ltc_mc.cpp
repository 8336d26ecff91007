// GGX, Beckmann and Disney diffuse LTC (committed tables, bilinear fetch) against Monte Carlo integration of
// the true BRDF x cosine over square lights, on a reduced grid of roughness, view angle, light
// size and position (the full grid is in shaderlib/luts/ltc.md, from rtpbr-ltc-validate).
// The reference's relative standard error is below 0.1% (its error is under 0.2% at 2 sigma).
// Relative errors are over the lights that receive at least 1% of the lobe's energy
// (albedo); lights in the far tail are checked by |LTC - MC| / albedo.
// Bounds: the measured values on this deterministic grid (in parentheses; full-grid tables
// in shaderlib/luts/ltc.md) with ~30% margin, so that a refit may move them a little while a
// broken table, layout or frame convention (errors of 50-100% and more) fails:
//   GGX:      mean < 5.6% (4.32%), 95th pct < 30% (24.1%), max < 42% (32.2%);
//             mirror-direction lights mean < 3% (2.89%), max < 19% (15.0%); tail < 0.2% (0.14%).
//             (Polygon-refined tables; the L3-only tables measured mean 4.6%, 95th 23%,
//             max 39%, mirror mean 2.0%, max 13%, tail 0.34%: the refinement gives some
//             accuracy at the peak for the flanks, see ltc.md. Bounds never loosened.)
//   Beckmann: mean < 8.8% (6.77%), 95th pct < 17.5% (13.4%), max < 81% (62%); mirror mean < 4.6%
//             (3.57%), max < 11.3% (8.7%); tail < 3% (2.27%). A clamped cosine transformed
//             linearly has GGX's heavy (1 + t^2/m^2)^-2 tail; Beckmann's Gaussian tail is
//             far lighter, so lights off the lobe's peak get too much (see ltc.md).
//   With the point correction and the tail estimate (ltc_corrections.h, LTC_PointFactor, LTC_PointTail:
//   what the engine computes; issue 19, fourth and fifth rounds): GGX mean < 2.7% (2.05%;
//   fourth round 2.85%), 95th < 10.3% (7.86%; 12.2%), max < 26% (19.5%; 32.2%); Beckmann
//   mean < 7.1% (5.48%), 95th < 15% (11.5%), max < 77% (59.4%); and its mean must be below
//   the LTC's alone (the full grid in ltc.md: GGX 4.22% -> 2.34%, Beckmann 6.42% -> 4.28%).
//   The aim of a mean under 3% is met for GGX at the mirror direction only: off-peak lights
//   at grazing view angles carry most of the error (ltc.md, breakdown by position).
//   Disney diffuse (Burley, white, subsurface 0): mean < 1.1% (0.81%), 95th pct < 3% (2.25%),
//             max < 6% (4.55%), mirror-position lights likewise (0.87% / 2.25%); tail < 5e-4
//             (2.6e-4). A smooth lobe, near a clamped cosine: the LTC follows it closely;
//             checked to fail with the former identity (Lambert) slot: mean 2.7%, 95th
//             10%, max 13% (and the albedo test by far more).
//             norm x the LTC's mass above the horizon within 0.15% (0.106%, the moment
//             quadrature's error at the most grazing row) of the closed-form albedo
//             Disney_DiffuseAlbedo at every texel.
//   Tables' integrals: norm x the LTC's mass above the horizon within 1% of the directional
//   albedo; the Schlick scale within 1% and the conductor (F82) within 2% of the
//   Fresnel-weighted fraction of the albedo.
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
extern "C" {
#include "test_main.h"
}

#include "ltc_floor.hpp"
#include "ltc_mc.hpp"

// Floor errors of the committed GGX table on test_ggx_floor's sweep, measured: the LTC alone
// mean 22.0%, worst 57.2% (r 0.8, elevation 5, NoV 0.1); with the engine's point correction
// (ltc_corrections.h, LTC_PointFactor) mean 11.5%, worst 28.8% (r 0.5, elevation 5, NoV 0.3); with the
// tail estimate too (LTC_PointTail, the engine since the fifth round) mean 7.8%, worst 23.0%;
// bounds + ~30% (see ltc.md, "Floors lit near their horizon").
static const double FLOOR_MEAN_BOUND = 0.286, FLOOR_WORST_BOUND = 0.74;
static const double FLOOR_POINT_MEAN_BOUND = 0.15, FLOOR_POINT_WORST_BOUND = 0.375;
static const double FLOOR_TAIL_MEAN_BOUND = 0.101, FLOOR_TAIL_WORST_BOUND = 0.30;
// With the streak estimate too (LTC_StreakEnd, the engine since the sixth round): mean 1.32%,
// worst 2.78%; at elevation 2 (the thin slivers; the tail estimate there: mean 31.9%, worst
// 69.9%) mean 1.02%, worst 2.02%; bounds + ~30%.
static const double FLOOR_STREAK_MEAN_BOUND = 0.0172, FLOOR_STREAK_WORST_BOUND = 0.0362;
static const double FLOOR_SLIVER_MEAN_BOUND = 0.0133, FLOOR_SLIVER_WORST_BOUND = 0.0263;

using namespace ltcmc;

static const double kTargetRelErr = 1e-3; // 2 sigma = 0.2%
static const long kMaxPairs = 1l << 21;

struct Bounds {
    double mean, p95, max;             // every light that matters
    double mirrorMean, mirrorMax;      // lights at the mirror direction (the highlight)
    double tailMax;                    // far-tail lights: |LTC - MC| / albedo
    int minMirror = 10;                // the grid must hold this many mirror-direction lights
    double pointMean = 0, pointP95 = 0, pointMax = 0; // with the point correction (the engine's)
};

static void run_lobe(Lobe lobe, Bounds b) {
    std::vector<Config> g = grid(true, {lobe});
    std::vector<double> rel, relClipless, relClipTable, mirror, relPoint;
    double worstRef = 0.0, worstAbsSmall = 0.0;
    uint64_t seed = 1;
    for (const Config &c : g) {
        if (c.lobe != lobe)
            continue;
        Outcome o = run_config(c, FresnelChoice{}, kTargetRelErr, kMaxPairs, seed++);
        assert_true(std::isfinite(o.ltc.exact) && std::isfinite(o.ltc.clipless) && std::isfinite(o.ltc.clipless_table) &&
                    std::isfinite(o.ltc.point));
        // the point correction scales the LTC by a factor in [0, 16] (LTC_PointFactor); the
        // engine's value is the larger of that and the weighted tail estimate (LTC_PointCombine)
        assert_true(o.ltc.pointOnly >= 0.0 && o.ltc.pointOnly <= 16.0 * o.ltc.exact * (1.0 + 1e-6));
        assert_true(o.ltc.tail >= 0.0 && std::isfinite(o.ltc.tail));
        // with the streak estimate (sixth round; GGX) mixed in by its weight in [0, 1]
        assert_true(o.ltc.streakWeight >= 0.0 && o.ltc.streakWeight <= 1.0);
        const double combined = std::max(o.ltc.pointOnly, o.ltc.tail);
        const double expected = o.ltc.streak >= 0.0 ? combined + (o.ltc.streak - combined) * o.ltc.streakWeight : combined;
        assert_true(lobe == Lobe::GGX || o.ltc.streakWeight == 0.0);
        assert_true(std::fabs(o.ltc.point - expected) <= 1e-5 * o.ltc.point + 1e-12);
        if (o.significant) {
            worstRef = std::max(worstRef, o.ref.relStdErr);
            assert_true(o.ref.relStdErr <= kTargetRelErr * 1.01);
            if (c.position == 0)
                mirror.push_back(o.relExact);
            rel.push_back(o.relExact);
            relClipless.push_back(o.relClipless);
            relClipTable.push_back(o.relClipTable);
            relPoint.push_back(o.relPoint);
            if (o.relExact > b.max)
                fprintf(stderr, "  worst: r=%.2f view=%g half=%g %s ref=%.5f ltc=%.5f\n", c.roughness, c.viewDeg,
                        c.half, position_name(c.position), o.ref.mean, o.ltc.exact);
        } else {
            worstAbsSmall = std::max(worstAbsSmall, o.relExact);
        }
    }
    Summary s = summarize(rel), sc = summarize(relClipless), st = summarize(relClipTable), sm = summarize(mirror),
            sp = summarize(relPoint);
    fprintf(stderr, "%s LTC vs MC (%d configurations, reference rel. std. error <= %.2e):\n", lobe_name(lobe), s.count,
            worstRef);
    fprintf(stderr, "| method | mean | 95th pct | max |\n|---|---|---|---|\n");
    fprintf(stderr, "| exact clipping | %.2f%% | %.2f%% | %.2f%% |\n", 100 * s.mean, 100 * s.p95, 100 * s.max);
    fprintf(stderr, "| clipless (analytic sphere) | %.2f%% | %.2f%% | %.2f%% |\n", 100 * sc.mean, 100 * sc.p95, 100 * sc.max);
    fprintf(stderr, "| clipless (sphere table) | %.2f%% | %.2f%% | %.2f%% |\n", 100 * st.mean, 100 * st.p95, 100 * st.max);
    fprintf(stderr, "| exact clipping, mirror-direction lights | %.2f%% | %.2f%% | %.2f%% |\n", 100 * sm.mean, 100 * sm.p95,
            100 * sm.max);
    fprintf(stderr, "| exact clipping + point correction (the engine) | %.2f%% | %.2f%% | %.2f%% |\n", 100 * sp.mean,
            100 * sp.p95, 100 * sp.max);
    fprintf(stderr, "far-tail lights: max |LTC - MC| / albedo = %.2e\n", worstAbsSmall);
    assert_true(s.count >= 30 && sm.count >= b.minMirror);
    assert_true(s.mean < b.mean);
    assert_true(s.p95 < b.p95);
    assert_true(s.max < b.max);
    assert_true(sm.mean < b.mirrorMean);
    assert_true(sm.max < b.mirrorMax);
    assert_true(worstAbsSmall < b.tailMax);
    if (b.pointMean > 0.0) {
        assert_true(sp.mean < b.pointMean);
        assert_true(sp.p95 < b.pointP95);
        assert_true(sp.max < b.pointMax);
        assert_true(sp.mean < s.mean); // the correction must pay for itself on this grid
    }
}

static void test_ggx_vs_mc(void **state) {
    (void)state;
    run_lobe(Lobe::GGX, Bounds{0.056, 0.30, 0.42, 0.03, 0.19, 0.002, 10, 0.027, 0.103, 0.26});
}

static void test_beckmann_vs_mc(void **state) {
    (void)state;
    run_lobe(Lobe::Beckmann, Bounds{0.088, 0.175, 0.81, 0.046, 0.113, 0.03, 10, 0.071, 0.15, 0.77});
}

// Fresnel over the whole lobe: the tables' norm, fresnel and f82 terms combined by
// LTC_FresnelScale (Schlick, exact for its integrals) and LTC_FresnelScaleConductor (gold
// through the F82 model) against a stratified visible-normal estimate of the integral of
// f F cos over the hemisphere with Schlick's and the exact conductor's F (F_Conductor).
static void test_fresnel_scales(void **state) {
    (void)state;
    double worst[3] = {0, 0, 0};
    for (int kind = 1; kind <= 2; kind++)
        for (float r : {0.2f, 0.5f, 0.8f})
            for (float view : {0.0f, 40.0f, 70.0f, 85.0f}) {
                float th = view * 3.14159265f / 180.0f;
                float3 V(std::sin(th), 0.0f, std::cos(th));
                Brdf brdf{Lobe::GGX, rtpbr::Alpha_FromPerceptual(r)};
                FresnelChoice fr{kind};
                const int side = 256;
                double ref = 0.0, albedo = 0.0;
                for (int i = 0; i < side * side; i++) {
                    float3 L = brdf.sample(V, float2((float(i % side) + 0.5f) / side, (float(i / side) + 0.5f) / side));
                    float pb;
                    float f = brdf.value_cos(V, L, pb);
                    if (f > 0.0f && pb > 0.0f) {
                        ref += double(f) / double(pb) * fr.weight(glm::dot(V, glm::normalize(V + L)));
                        albedo += double(f) / double(pb);
                    }
                }
                // Compared as the Fresnel-weighted fraction of the albedo: the tables' integrals
                // share one normalisation (see ltc.md), the Fresnel combination must not care.
                ref /= albedo;
                float4 t2 = fetch(rtpbr_ltc_ggx_2, rtpbr::LTC_LutCoord(V.z, r));
                // norm = the directional albedo itself
                worst[0] = std::max(worst[0], std::fabs(t2.x * side * side / albedo - 1.0));
                double ltc = kind == 1 ? rtpbr::LTC_FresnelScale(t2, float3(0.04f), 1.0f).y
                                       : rtpbr::LTC_FresnelScaleConductor(t2, float3(0.143f, 0.374f, 1.442f),
                                                                          float3(3.983f, 2.385f, 1.603f)).y;
                ltc /= t2.x;
                double e = std::fabs(ltc - ref) / ref;
                worst[kind] = std::max(worst[kind], e);
            }
    fprintf(stderr, "norm vs albedo: max %.2f%%; Fresnel-weighted fraction of the albedo: Schlick max %.2f%%, "
            "gold conductor (F82) max %.2f%%\n", 100 * worst[0], 100 * worst[1], 100 * worst[2]);
    assert_true(worst[0] < 0.01);
    assert_true(worst[1] < 0.01);
    assert_true(worst[2] < 0.02);
}

// The tables' last row (NoV = 1e-3, where LTC_LutCoord's lookups end at grazing views) holds
// regular lobes: each keeps at least 0.05 of itself above the horizon (the fitter's
// kMinVisibleMass where the lobe reaches the horizon). The GGX table's columns 0-7 once had
// 1e-15 (M^-1's third row 0: LTC_HorizonFraction divided rounding by rounding; ltc.md, "Known
// limitations").
static void test_last_row_regular(void **state) {
    (void)state;
    struct Table { const char *name; const float *t1; } tables[] = {
        {"ggx", rtpbr_ltc_ggx_1}, {"beckmann", rtpbr_ltc_beckmann_1},
        {"disney_diffuse", rtpbr_ltc_disney_diffuse_1}, {"sheen", rtpbr_ltc_sheen_1}};
    for (const Table &tab : tables) {
        float least = 1.0f;
        int leastCol = 0;
        for (int col = 0; col < RTPBR_LTC_SIZE; col++) {
            const float *t = tab.t1 + size_t((RTPBR_LTC_SIZE - 1) * RTPBR_LTC_SIZE + col) * 4;
            const float mass = rtpbr::LTC_HorizonMass(rtpbr::LTC_InverseMatrix(float4(t[0], t[1], t[2], t[3])));
            if (mass < least)
                least = mass, leastCol = col;
        }
        fprintf(stderr, "%s: last row's least horizon mass %.3g (column %d)\n", tab.name, double(least), leastCol);
        assert_true(least >= 0.05f);
    }
}

static void test_disney_diffuse_vs_mc(void **state) {
    (void)state;
    // The mirror direction means nothing to a diffuse lobe: those lights get the overall bounds.
    run_lobe(Lobe::DisneyDiffuse, Bounds{0.011, 0.03, 0.06, 0.011, 0.03, 5e-4, 0});
}

// The diffuse table's norm, times the LTC's mass above the horizon (ltc.md's convention),
// against the closed-form albedo Disney_DiffuseAlbedo at every texel centre; its Fresnel
// columns are 0 (documented: no Schlick split for the diffuse lobe).
static void test_disney_diffuse_albedo(void **state) {
    (void)state;
    assert_int_equal(RTPBR_LTC_DISNEY_DIFFUSE_FITTED, 1);
    const int n = RTPBR_LTC_SIZE;
    double worst = 0.0;
    int worstRow = 0, worstCol = 0;
    for (int row = 0; row < n; row++)
        for (int col = 0; col < n; col++) {
            const float *t2 = rtpbr_ltc_disney_diffuse_2 + (size_t(row) * n + col) * 4;
            double x = double(row) / (n - 1);
            float nov = float(std::max(1.0 - x * x, 1e-3));
            float r = float(col) / float(n - 1);
            double e = std::fabs(double(t2[0]) / double(rtpbr::Disney_DiffuseAlbedo(nov, r)) - 1.0);
            assert_true(std::isfinite(e));
            assert_true(t2[1] == 0.0f && t2[2] == 0.0f);
            if (e > worst) {
                worst = e;
                worstRow = row;
                worstCol = col;
            }
        }
    fprintf(stderr, "Disney diffuse: norm vs Disney_DiffuseAlbedo: max relative difference %.3f%% (row %d, "
            "column %d)\n", 100 * worst, worstRow, worstCol);
    assert_true(worst < 0.0015);
}

// Anisotropic GGX through LTC_AnisotropicInverseMatrix: the isotropic GGX LTC at
// alpha = sqrt(at ab), stretched about the mirror direction along the anisotropy direction,
// against Monte Carlo of the anisotropic BRDF (BRDF_SpecularLocal, F = 1, height-correlated
// Smith) times the cosine over square lights near the highlight, the anisotropy direction at
// several azimuths. The reference samples the square's area (256 x 256 stratified points).
// Measured on this grid (108 lights): mean relative error 10.7% stretched vs 108% for the
// isotropic LTC at sqrt(at ab) alone (the engine's former approximation); bounds: stretched
// < 12% (measured + ~30%) and below 0.3 of the isotropic error.
static void test_anisotropic_stretch_vs_mc(void **state) {
    (void)state;
    double sumStretch = 0.0, sumIso = 0.0;
    int count = 0;
    rtpbr::FresnelParams one = rtpbr::Fresnel_FromF0(float3(1.0f));
    for (float roughness : {0.3f, 0.5f})
        for (float strength : {0.5f, 0.9f})
            for (float viewDeg : {0.0f, 30.0f, 55.0f})
                for (float azimuthDeg : {0.0f, 50.0f, 90.0f})
                    for (int where = 0; where < 3; where++) {
                        float alpha = roughness * roughness;
                        float at = std::min(alpha + (1.0f - alpha) * strength * strength, 1.0f), ab = alpha;
                        float vr = glm::radians(viewDeg), az = glm::radians(azimuthDeg);
                        float3 V(std::sin(vr), 0.0f, std::cos(vr));
                        float3 T(std::cos(az), std::sin(az), 0.0f), B(-std::sin(az), std::cos(az), 0.0f);
                        // Lights at the mirror direction, and tilted along and across the direction.
                        float3 mirror(-V.x, -V.y, V.z);
                        float3 dir = where == 0 ? mirror : where == 1 ? glm::normalize(mirror + 0.35f * T)
                                                                      : glm::normalize(mirror + 0.35f * B);
                        if (!(dir.z > 0.2f))
                            continue;
                        Square sq = make_square(dir, 0.15f);
                        // Reference: area sampling of the square (distance 1, facing the origin).
                        const int n = 256;
                        double ref = 0.0;
                        for (int i = 0; i < n; i++)
                            for (int j = 0; j < n; j++) {
                                float a = -1.0f + 2.0f * (i + 0.5f) / n, b = -1.0f + 2.0f * (j + 0.5f) / n;
                                float3 p = sq.c + sq.half * (a * sq.e1 + b * sq.e2);
                                float d2 = glm::dot(p, p);
                                float3 L = p / std::sqrt(d2);
                                float3 wo(glm::dot(V, T), glm::dot(V, B), V.z), wi(glm::dot(L, T), glm::dot(L, B), L.z);
                                float f = rtpbr::BRDF_SpecularLocal(wo, wi, at, ab, one).x * wi.z;
                                ref += double(f) * std::fabs(glm::dot(sq.d, L)) / d2;
                            }
                        ref *= (2.0 * sq.half) * (2.0 * sq.half) / (double(n) * n);
                        if (!(ref > 1e-3))
                            continue;
                        // LTC at the isotropic alpha, with and without the stretch.
                        float r = std::sqrt(std::sqrt(at * ab));
                        float4 l1 = fetch(rtpbr_ltc_ggx_1, rtpbr::LTC_LutCoord(V.z, r));
                        float norm = fetch(rtpbr_ltc_ggx_2, rtpbr::LTC_LutCoord(V.z, r)).x;
                        rtpbr::float3x3 frame = rtpbr::LTC_Frame(float3(0, 0, 1), V);
                        rtpbr::LtcLocalPolygon local = rtpbr::LTC_PolygonToLocal(frame, float3(0), sq.poly(), false);
                        float3 m = rtpbr::rtpbr_mul(frame, mirror), t = rtpbr::rtpbr_mul(frame, T);
                        float3 e1 = glm::normalize(t - m * glm::dot(t, m));
                        double iso = norm * rtpbr::LTC_IntegrateLocal(local, l1);
                        rtpbr::float3x3 stretch = rtpbr::LTC_AnisotropicInverseMatrix(l1, m, e1, std::sqrt(at / ab));
                        double stretched = norm * rtpbr::LTC_AnisotropicAlbedoScale(l1, stretch) *
                                           rtpbr::LTC_IntegrateLocalMatrix(local, stretch);
                        sumStretch += std::fabs(stretched - ref) / ref;
                        sumIso += std::fabs(iso - ref) / ref;
                        count++;
                    }
    double meanStretch = sumStretch / count, meanIso = sumIso / count;
    fprintf(stderr, "anisotropic GGX over %d lights: mean relative error %.2f%% stretched, %.2f%% isotropic\n", count,
            100 * meanStretch, 100 * meanIso);
    assert_true(count > 60);
    assert_true(meanStretch < 0.12);
    assert_true(meanStretch < 0.3 * meanIso);
}

// Floors lit near their horizon and seen at low angles (issue 19; the full sweep:
// rtpbr-ltc-floor, shaderlib/luts/ltc.md): a reduced sweep of the same cases, GGX against the
// Gauss-Legendre quadrature of the true BRDF (its convergence checked: the rule with half the
// points per axis agrees within 1e-4 of the patch's largest value). Bounds: the measured floor
// errors of the committed tables with ~30% margin (FLOOR_MEAN_BOUND above).
static void test_ggx_floor(void **state) {
    (void)state;
    // 0: the LTC alone; 1: with the point correction (the fourth round's engine); 2: with the
    // point correction and the tail estimate (the fifth round's); 3: with the streak estimate
    // too (the engine since the sixth round). Elevation 2 (the thin sliver of the sixth round)
    // counts apart: sliver[] (modes 2 and 3).
    double worst[4] = {0.0, 0.0, 0.0, 0.0}, sum[4] = {0.0, 0.0, 0.0, 0.0}, quad = 0.0;
    double sliverSum[4] = {0.0, 0.0, 0.0, 0.0}, sliverWorst[4] = {0.0, 0.0, 0.0, 0.0};
    int nSliver = 0;
    static const char *label[4] = {"", ", point correction", ", point correction + tail", ", + streak"};
    int n = 0;
    for (float r : {0.3f, 0.5f, 0.8f})
        for (float e : {2.0f, 5.0f, 10.0f, 20.0f})
            for (float v : {0.1f, 0.3f}) {
                for (int mode = e == 2.0f ? 2 : 0; mode < 4; mode++) {
                    ltcfloor::Tables tab{rtpbr_ltc_ggx_1, rtpbr_ltc_ggx_2};
                    tab.point = mode > 0 ? 1 : 0;
                    tab.tail = mode >= 2;
                    tab.streak = mode == 3;
                    std::vector<ltcfloor::CaseResult> az;
                    for (float a : {0.0f, 30.0f, 60.0f, 90.0f, 120.0f, 150.0f, 180.0f}) {
                        az.push_back(ltcfloor::run_case({r, e, v, a}, Lobe::GGX, tab, 4, 4));
                        assert_true(std::isfinite(az.back().sumAbs) && std::isfinite(az.back().sumRef));
                        quad = std::max(quad, az.back().quadDiff);
                    }
                    double f = ltcfloor::floor_error(az);
                    fprintf(stderr, "  floor r=%.1f elevation=%g NoV=%.1f%s: %.2f%%\n", double(r), double(e), double(v),
                            label[mode], 100 * f);
                    double *w = e == 2.0f ? sliverWorst : worst, *su = e == 2.0f ? sliverSum : sum;
                    w[mode] = std::max(w[mode], f);
                    su[mode] += f;
                }
                (e == 2.0f ? nSliver : n)++;
            }
    fprintf(stderr, "GGX floors: LTC alone mean %.2f%%, worst %.2f%%; with the point correction mean %.2f%%, worst %.2f%%; "
                    "with the tail estimate too mean %.2f%%, worst %.2f%%; with the streak estimate too mean %.2f%%, "
                    "worst %.2f%%; at elevation 2, tail mean %.2f%%, worst %.2f%%, streak mean %.2f%%, worst %.2f%%; "
                    "quadrature agreement %.1e\n",
            100 * sum[0] / n, 100 * worst[0], 100 * sum[1] / n, 100 * worst[1], 100 * sum[2] / n, 100 * worst[2],
            100 * sum[3] / n, 100 * worst[3], 100 * sliverSum[2] / nSliver, 100 * sliverWorst[2],
            100 * sliverSum[3] / nSliver, 100 * sliverWorst[3], quad);
    assert_true(quad < 1e-4);
    assert_true(sum[0] / n < FLOOR_MEAN_BOUND);
    assert_true(worst[0] < FLOOR_WORST_BOUND);
    assert_true(sum[1] / n < FLOOR_POINT_MEAN_BOUND);
    assert_true(worst[1] < FLOOR_POINT_WORST_BOUND);
    assert_true(sum[2] / n < FLOOR_TAIL_MEAN_BOUND);
    assert_true(worst[2] < FLOOR_TAIL_WORST_BOUND);
    assert_true(sum[3] / n < FLOOR_STREAK_MEAN_BOUND);
    assert_true(worst[3] < FLOOR_STREAK_WORST_BOUND);
    assert_true(sum[1] < sum[0]);
    assert_true(sum[2] < sum[1]);
    assert_true(sum[3] < sum[2]);
    assert_true(sliverSum[3] / nSliver < FLOOR_SLIVER_MEAN_BOUND);
    assert_true(sliverWorst[3] < FLOOR_SLIVER_WORST_BOUND);
    assert_true(sliverSum[3] < sliverSum[2]);
}

// The point correction's pieces (ltc.h's LTC_LobeEndVector, ltc_corrections.h's LTC_LobePoint, LTC_PointFactor)
// against an independent double-precision computation: the lobe's view of random quads (the
// horizon-clipped local polygon mapped by M^-1, clipped to z >= 0 by Sutherland-Hodgman, its
// vector form factor from exact atan2 edge angles: clipped_centroid in ltc_mc.hpp), its
// centre w = M F / |M F| and the LTC density there from the definition D(w) = D_o(M^-1 w /
// |M^-1 w|) |det M^-1| / |M^-1 w|^3 (Heitz et al. 2016, eq. 1); then the factor's closed form.
static void test_point_correction(void **state) {
    (void)state;
    Rng rng(19);
    auto u01 = [&]() { return rng.uniform(); };
    double worstDir = 0.0, worstDensity = 0.0;
    int seen = 0;
    for (int k = 0; k < 4000; k++) {
        const float r = 0.1f + 0.9f * u01(), nov = 0.05f + 0.95f * u01();
        const float4 l1 = fetch(rtpbr_ltc_ggx_1, rtpbr::LTC_LutCoord(nov, r));
        const float3 V(std::sqrt(1.0f - nov * nov), 0.0f, nov);
        // a square of random size, direction and turn facing the shading point
        float3 d(2.0f * u01() - 1.0f, 2.0f * u01() - 1.0f, 1.2f * u01() - 0.2f);
        if (glm::length(d) < 0.1f)
            continue;
        Square sq = make_square(glm::normalize(d), 0.05f + 0.6f * u01());
        const rtpbr::LtcLocalPolygon local =
            rtpbr::LTC_PolygonToLocal(rtpbr::LTC_Frame(float3(0, 0, 1), V), float3(0), sq.poly(), false);
        if (local.count < 3)
            continue;
        const glm::dmat3 minv(rtpbr::LTC_InverseMatrix(l1)), M = glm::inverse(minv);
        const glm::dvec3 Fd = clipped_centroid(local, minv);
        const rtpbr::LtcPoint pt = rtpbr::LTC_LobePoint(rtpbr::LTC_IntegrateLocalVector(local, l1), l1);
        assert_true(std::isfinite(pt.density) && pt.density >= 0.0f);
        // where the lobe sees almost nothing (a sliver at its support's edge, ill-conditioned in
        // float) the factor scales a result below 1e-4 of the lobe: not measured
        if (rtpbr::LTC_IntegrateLocal(local, l1) < 1e-4f || glm::length(Fd) < 1e-6)
            continue;
        const glm::dvec3 w = glm::normalize(M * Fd);
        const glm::dvec3 m = minv * w;
        const double lm = glm::length(m);
        // per unit of the LTC's mass above the horizon: (1 + cos of the angle between M^T z and
        // z) / 2 (the sky view factor of the transformed horizon; ltc.h takes it from M^-1's columns)
        const glm::dvec3 mz(M[0][2], M[1][2], M[2][2]);
        const double mass = 0.5 * (1.0 + mz.z / glm::length(mz));
        const double density =
            std::max(m.z / lm, 0.0) / 3.14159265358979 * std::fabs(glm::determinant(minv)) / (lm * lm * lm) / mass;
        worstDir = std::max(worstDir, glm::length(w - glm::dvec3(pt.dir)));
        worstDensity = std::max(worstDensity, std::fabs(double(pt.density) - density) / density);
        seen++;
    }
    fprintf(stderr, "point correction: %d quads; centre within %.2e (unit vectors), density within %.2e relative\n", seen,
            worstDir, worstDensity);
    assert_true(seen > 1500);
    assert_true(worstDir < 2e-3);     // (1.2e-3) float edge integrals (fitted theta / sin theta) vs exact atan2
    assert_true(worstDensity < 5e-3); // (2.9e-3) the density goes with the cube of |M^-1 w|
    // LTC_PointFactor's closed form: k = fCos / ltcValue, taken as it is below 1; above 1 (at
    // most 16) scaled by smoothstep(1, 1.5, width ratio): none at <= 1, all at >= 1.5, half at
    // 1.25; no fade at ff = 0, none left at ff = 1, k t + 1 - t between (t = (1 - ff)^16); 1 for
    // NaN or zero values.
    auto near = [](double a, double b) { return std::fabs(a - b) < 1e-6; };
    assert_true(near(rtpbr::LTC_PointFactor(0.25f, 1.0f, 0.0f, 0.0f), 0.25));
    assert_true(near(rtpbr::LTC_PointFactor(0.25f, 1.0f, 1.0f, 0.0f), 1.0));
    const double t = std::pow(0.9, 16.0);
    assert_true(near(rtpbr::LTC_PointFactor(0.25f, 1.0f, 0.1f, 5.0f), 0.25 * t + 1.0 - t));
    assert_true(near(rtpbr::LTC_PointFactor(2.0f, 1.0f, 0.0f, 1.0f), 1.0));
    assert_true(near(rtpbr::LTC_PointFactor(2.0f, 1.0f, 0.0f, 1.25f), 1.5));
    assert_true(near(rtpbr::LTC_PointFactor(2.0f, 1.0f, 0.0f, 1.5f), 2.0));
    assert_true(near(rtpbr::LTC_PointFactor(100.0f, 1.0f, 0.0f, 9.0f), 16.0));
    assert_true(near(rtpbr::LTC_PointFactor(2.0f, 1.0f, 0.1f, 3.0f), 2.0 * t + 1.0 - t));
    assert_true(near(rtpbr::LTC_PointFactor(std::nanf(""), 1.0f, 0.1f, 3.0f), 1.0));
    assert_true(near(rtpbr::LTC_PointFactor(0.5f, 0.0f, 0.1f, 3.0f), 1.0));
    assert_true(near(rtpbr::LTC_PointFactor(2.0f, 1.0f, 0.0f, std::nanf("")), 1.0));
    assert_true(rtpbr::LTC_PointFactor(0.0f, 1.0f, 0.0f, 3.0f) == 0.0f);
    // the width ratio: alpha |V + w| / sqrt(|F|), raised to at least 1.5 (x - 0.6) / 0.4 for
    // |V + w| = x from 0.6 to 1 (no streak there: fifth round)
    assert_true(near(rtpbr::LTC_PointWidthRatio(0.25f, 0.5f, 0.01f), 1.25));
    assert_true(near(rtpbr::LTC_PointWidthRatio(0.01f, 0.5f, 0.01f), 0.05));
    assert_true(near(rtpbr::LTC_PointWidthRatio(0.01f, 0.8f, 0.01f), 0.75));
    assert_true(near(rtpbr::LTC_PointWidthRatio(0.01f, 1.2f, 0.01f), 1.5));
    assert_true(near(rtpbr::LTC_PointWidthRatio(0.5f, 1.2f, 0.01f), 6.0));
    assert_true(near(rtpbr::LTC_PointWidthRatio(0.01f, std::nanf(""), 0.01f), 0.0) ||
                std::isnan(rtpbr::LTC_PointWidthRatio(0.01f, std::nanf(""), 0.01f)));
    // The tail estimate (fifth round): f pi formFactor / norm; its weight from the lobe vector's
    // cosine c = z / |F|: 1 up to 0.2 (and for a zero vector), 0 from 0.4, 0.5 at 0.3; the larger
    // of the corrected LTC and the weighted tail; 0 / the other for NaN, negative or infinite.
    const double pi = 3.14159265358979;
    assert_true(near(rtpbr::LTC_PointTail(0.5f, 0.2f, 0.8f), 0.5 * pi * 0.2 / 0.8));
    assert_true(rtpbr::LTC_PointTail(std::nanf(""), 0.2f, 0.8f) == 0.0f && rtpbr::LTC_PointTail(0.5f, -0.2f, 0.8f) == 0.0f &&
                rtpbr::LTC_PointTail(0.5f, 0.2f, 0.0f) == 0.0f && rtpbr::LTC_PointTail(INFINITY, 0.2f, 0.8f) == 0.0f);
    // ... and times 1 - smoothstep(0.5, 2, ltcFF / formFactor)
    auto dirAt = [](double c) { return float3(float(std::sqrt(1.0 - c * c)), 0.0f, float(c)) * 3.0f; };
    auto tw = [](float3 d, float ratio) { return rtpbr::LTC_PointTailWeight(d, 0.1f * ratio, 0.1f); };
    assert_true(tw(dirAt(0.1), 0.0f) == 1.0f && tw(float3(0.0f), 0.5f) == 1.0f);
    assert_true(tw(dirAt(0.2), 0.3f) == 1.0f && tw(dirAt(0.45), 0.0f) == 0.0f);
    assert_true(std::fabs(tw(dirAt(0.3), 0.0f) - 0.5) < 1e-5);
    assert_true(std::fabs(tw(dirAt(0.1), 1.25f) - 0.5) < 1e-5 && tw(dirAt(0.1), 2.0f) == 0.0f);
    assert_true(std::fabs(tw(dirAt(0.3), 1.25f) - 0.25) < 1e-5);
    assert_true(rtpbr::LTC_PointTailWeight(float3(0.0f, 0.0f, std::nanf("")), 0.0f, 0.1f) == 1.0f);
    assert_true(rtpbr::LTC_PointTailWeight(dirAt(0.1), std::nanf(""), 0.1f) == 1.0f &&
                rtpbr::LTC_PointTailWeight(dirAt(0.1), 0.05f, std::nanf("")) == 1.0f);
    assert_true(rtpbr::LTC_PointCombine(0.3f, 0.5f, 0.5f) == 0.3f && rtpbr::LTC_PointCombine(0.2f, 0.5f, 0.5f) == 0.25f);
    assert_true(rtpbr::LTC_PointCombine(std::nanf(""), 0.5f, 1.0f) == 0.5f &&
                rtpbr::LTC_PointCombine(0.3f, std::nanf(""), 1.0f) == 0.3f && rtpbr::LTC_PointCombine(-1.0f, 0.0f, 1.0f) == 0.0f);

    // The streak estimate (sixth round). Its atan against the C library's: within 3e-7
    // relative (fitted to 1.5e-8; float rounding), NaN -> 0, +-Inf -> +-pi / 2.
    double worstAtan = 0.0;
    for (int i = -200000; i <= 200000; i++) {
        const float x = float(i) * 1e-4f * (i % 3 == 0 ? 100.0f : 1.0f);
        const double ref = std::atan(double(x));
        if (ref != 0.0)
            worstAtan = std::max(worstAtan, std::fabs(double(rtpbr::LTC_Atan(x)) - ref) / std::fabs(ref));
    }
    fprintf(stderr, "LTC_Atan: largest relative error %.2g\n", worstAtan);
    assert_true(worstAtan < 3e-7); // measured 1.7e-7 (~3 ulps)
    assert_true(rtpbr::LTC_Atan(std::nanf("")) == 0.0f && rtpbr::LTC_Atan(INFINITY) == float(pi / 2) &&
                rtpbr::LTC_Atan(-INFINITY) == -float(pi / 2) && rtpbr::LTC_Atan(0.0f) == 0.0f);
    // Its lateral closed form against a composite midpoint
    // sum of (c + s^2)^2 / (a^2 + s^2)^2 (c - a^2 = m), over limits on both sides and one side.
    for (double a2 : {1e-4, 0.01, 0.3})
        for (double m : {0.99, 0.5})
            for (auto lim : {std::pair<double, double>{-2.0, 1.5}, {0.05, 0.4}, {-0.3, -0.01}}) {
                const int N = 400000;
                const double h = (lim.second - lim.first) / N;
                double num = 0.0;
                for (int i = 0; i < N; i++) {
                    const double x = lim.first + (i + 0.5) * h, c = a2 + m;
                    num += (c + x * x) * (c + x * x) / ((a2 + x * x) * (a2 + x * x)) * h;
                }
                const double cf = rtpbr::LTC_StreakLateral(float(lim.first), float(lim.second), float(a2), float(m));
                assert_true(std::fabs(cf - num) <= 2e-4 * std::fabs(num) + 1e-6);
            }
    // its weight: 1 - smoothstep(0.35, 0.75, |V + c|), 0 for a zero or NaN F
    const float3 vg(std::sqrt(1.0f - 0.01f), 0.0f, 0.1f);
    auto sw = [&](float3 F) { return rtpbr::LTC_StreakWeight(vg, F); };
    assert_true(sw(float3(-vg.x, 0.0f, vg.z * 0.2f)) == 1.0f); // mirror side near the horizon: |V + c| ~ 0.12
    assert_true(sw(float3(vg.x, 0.0f, vg.z)) == 0.0f);          // the viewer's side: |V + c| = 2
    assert_true(sw(float3(0.0f, 1.0f, 0.0f)) == 0.0f);          // beside: |V + c| = sqrt 2
    assert_true(sw(float3(0.0f)) == 0.0f && sw(float3(std::nanf(""), 0.0f, 0.1f)) == 0.0f);
    {
        // |V + c| = 0.55 exactly: c = V reflected and turned (weight 0.5)
        const float3 c = glm::normalize(float3(-vg.x, 0.0f, vg.z)) ;
        const float3 u = glm::normalize(float3(0.0f, 1.0f, 0.0f));
        // rotate c toward y until |V + c| = 0.55: |V + c|^2 = 2 + 2 V.c
        const double target = (0.55 * 0.55 - 2.0) / 2.0, base = glm::dot(vg, c);
        double lo = 0.0, hi = 1.5;
        for (int i = 0; i < 60; i++) {
            const double t = 0.5 * (lo + hi);
            const float3 d = c * float(std::cos(t)) + u * float(std::sin(t));
            (glm::dot(vg, d) < target ? lo : hi) = t;
        }
        (void)base;
        const double t = 0.5 * (lo + hi);
        assert_true(std::fabs(sw(c * float(std::cos(t)) + u * float(std::sin(t))) - 0.5) < 1e-3);
    }
    // a degenerate polygon: (-1, 0); NaN vertices: finite, weight 0 or no estimate
    rtpbr::LtcLocalPolygon tri{};
    tri.count = 3;
    tri.v[0] = float3(-1.0f, -0.1f, 0.05f), tri.v[1] = float3(-1.0f, 0.1f, 0.05f), tri.v[2] = float3(-0.8f, 0.0f, 0.05f);
    const float3 Ft = rtpbr::LTC_FormFactorVector(tri, rtpbr::LTC_Identity());
    const float2 ok = rtpbr::LTC_StreakLocal(tri, Ft, vg, 0.1f);
    assert_true(ok.x > 0.0f && std::isfinite(ok.x) && ok.y >= 0.0f && ok.y <= 1.0f);
    // either orientation of F (this triangle's is z < 0): the same
    const float2 flipped = rtpbr::LTC_StreakLocal(tri, -Ft, vg, 0.1f);
    assert_true(flipped.x == ok.x && flipped.y == ok.y && sw(Ft) == sw(-Ft));
    rtpbr::LtcLocalPolygon bad = tri;
    bad.v[1] = float3(std::nanf(""), 0.1f, 0.05f);
    const float2 nb = rtpbr::LTC_StreakLocal(bad, Ft, vg, 0.1f);
    assert_true(nb.x == -1.0f || (std::isfinite(nb.x) && nb.x >= 0.0f && std::isfinite(nb.y)));
    // the candidate test: the light's angular diameter 2 r / sqrt(d^2 - r^2) against alpha NoV
    // (W0 = 1); inside the sphere or NaN: a candidate (the trust decides)
    assert_true(rtpbr::LTC_StreakCandidate(0.1f, 1.0f, 0.2f, 0.5f));   // 0.201 >= 0.1
    assert_true(!rtpbr::LTC_StreakCandidate(0.1f, 1.0f, 0.5f, 0.5f));  // 0.201 < 0.25
    assert_true(rtpbr::LTC_StreakCandidate(0.1f, 1.0f, 0.402f, 0.5f) && !rtpbr::LTC_StreakCandidate(0.1f, 1.0f, 0.403f, 0.5f));
    assert_true(rtpbr::LTC_StreakCandidate(1.0f, 0.5f, 0.5f, 0.5f) && rtpbr::LTC_StreakCandidate(0.1f, std::nanf(""), 0.5f, 0.5f));
    // V.h at the middle of the range: a light straddling the mirror direction gives h = the
    // normal, V.h = NoV
    {
        rtpbr::LtcLocalPolygon mir{};
        mir.count = 4;
        const float3 m(-vg.x, 0.0f, vg.z);
        const float3 t1(0.0f, 0.1f, 0.0f), t2 = glm::normalize(glm::cross(m, t1)) * 0.1f;
        mir.v[0] = m - t1 - t2, mir.v[1] = m + t1 - t2, mir.v[2] = m + t1 + t2, mir.v[3] = m - t1 + t2;
        rtpbr::LtcStreak st = rtpbr::LTC_StreakBegin();
        for (int i = 0; i < 4; i++)
            rtpbr::LTC_StreakEdge(st, mir.v[i], mir.v[(i + 1) % 4]);
        rtpbr::LTC_StreakNodes(st, rtpbr::LTC_FormFactorVector(mir, rtpbr::LTC_Identity()));
        assert_true(std::fabs(rtpbr::LTC_StreakVoH(st, vg) - vg.z) < 2e-3);
    }
    rtpbr::LtcLocalPolygon two = tri;
    two.count = 2;
    assert_true(rtpbr::LTC_StreakLocal(two, Ft, vg, 0.1f).x == -1.0f);
}

// Every lobe is a distribution: the six faces of a cube around the shading point partition the
// sphere, so their fractions of the lobe (each clipped to the horizon) sum to 1, for every
// table at the lookups LTC_LutCoord makes, down to NoV = 0 (a normal-mapped normal turned away
// from the viewer). Before the refit of its last row (test_last_row_regular), the GGX table's
// singular cells there put the sum 4 away from 1 (ClearCoatTest's coat: 4.9 x the brightest
// emitter) while the Beckmann, Disney and sheen tables summed to 1.
static void test_grazing_partition(void **state) {
    (void)state;
    struct Table { const char *name; const float *t1; } tables[] = {
        {"ggx", rtpbr_ltc_ggx_1}, {"beckmann", rtpbr_ltc_beckmann_1},
        {"disney_diffuse", rtpbr_ltc_disney_diffuse_1}, {"sheen", rtpbr_ltc_sheen_1}};
    const float3 N(0.0f, 0.0f, 1.0f);
    int cases = 0;
    for (const Table &tab : tables) {
        double worst = 0.0;
        float worstR = 0, worstNoV = 0;
        for (float r : {0.0f, 0.02f, 0.045f, 0.08f, 0.11f, 0.125f, 0.135f, 0.15f, 0.2f, 0.5f, 1.0f})
            for (float nov : {0.0f, 1e-6f, 1e-4f, 1e-3f, 0.01f, 0.02f, 0.03f, 0.05f, 0.2f})
                for (int turn = 0; turn < 3; turn++) {
                    float3 V(std::sqrt(1.0f - nov * nov), 0.0f, nov);
                    float4 ltc1 = fetch(tab.t1, rtpbr::LTC_LutCoord(nov, r));
                    // the cube turned about two axes, so that no edge lies on the horizon
                    float a = 0.37f + 0.9f * float(turn), b = 0.21f + 0.5f * float(turn);
                    auto place = [&](float3 p) {
                        float3 q(p.x * std::cos(a) - p.y * std::sin(a), p.x * std::sin(a) + p.y * std::cos(a), p.z);
                        return float3(q.x, q.y * std::cos(b) - q.z * std::sin(b), q.y * std::sin(b) + q.z * std::cos(b));
                    };
                    double sum = 0.0;
                    for (int axis = 0; axis < 3; axis++)
                        for (float side : {-1.0f, 1.0f}) {
                            float3 c[4];
                            for (int k = 0; k < 4; k++) {
                                float u = (k == 1 || k == 2) ? 1.0f : -1.0f, w = k >= 2 ? 1.0f : -1.0f;
                                float3 p;
                                p[axis] = side;
                                p[(axis + 1) % 3] = u;
                                p[(axis + 2) % 3] = w;
                                c[k] = place(p);
                            }
                            float f = rtpbr::LTC_EvaluatePolygon(N, V, float3(0.0f), rtpbr::LTC_Quad(c[0], c[1], c[2], c[3]),
                                                                 ltc1, true);
                            assert_true(f >= 0.0f && f <= 1.0f);
                            sum += f;
                        }
                    cases++;
                    if (std::fabs(sum - 1.0) > worst) worst = std::fabs(sum - 1.0), worstR = r, worstNoV = nov;
                }
        fprintf(stderr, "%s: the six faces of a cube sum to 1 within %.2g (worst at roughness %g, NoV %g)\n", tab.name,
                worst, double(worstR), double(worstNoV));
        assert_true(worst < 1e-3);
    }
    assert_true(cases == 4 * 11 * 9 * 3);
}

// The streak estimate's culling tests (ltc_corrections.h, LTC_StreakSteep, LTC_StreakOutside):
// where either says so, LTC_StreakWeight must be 0 for every view and light direction it covers
// (sampled: each cone's boundary and inside, the view's worst light at the horizon), and
// neither may be vacuous: just past its limit a pair with weight > 0 exists. Planted: the
// limit of |V + c| taken at RTPBR_LTC_STREAK_V0 instead of V1, or the spreads subtracted,
// fails the first part.
static void test_streak_culling(void **state) {
    (void)state;
    // the weight of view V and light direction c (world; unit): in a frame whose normal has
    // both above the horizon (between them), V in its xz-plane, as LTC_StreakWeight takes them
    auto weight = [](float3 V, float3 c) {
        float3 n = V + c;
        n = glm::dot(n, n) > 1e-12f ? glm::normalize(n) : glm::normalize(glm::cross(V, float3(0.3f, 0.5f, 0.8f)));
        float3 x = V - n * glm::dot(V, n);
        x = glm::dot(x, x) > 1e-14f ? glm::normalize(x) : glm::normalize(glm::cross(n, float3(0.3f, 0.5f, 0.8f)));
        const float3 y = glm::cross(n, x);
        return rtpbr::LTC_StreakWeight(float3(glm::dot(V, x), 0.0f, glm::dot(V, n)),
                                       float3(glm::dot(c, x), glm::dot(c, y), glm::dot(c, n)));
    };
    // LTC_StreakSteep: at NoV on a grid, the light at the horizon opposite the view (the
    // smallest |V + c|) and random lights above the horizon
    Rng rng(41);
    auto u01 = [&]() { return float(rng.uniform()); };
    int steep = 0;
    for (int k = 0; k <= 1000; k++) {
        const float nov = float(k) / 1000.0f;
        const float3 V(std::sqrt(std::max(1.0f - nov * nov, 0.0f)), 0.0f, nov);
        if (!rtpbr::LTC_StreakSteep(nov)) continue;
        steep++;
        assert_true(rtpbr::LTC_StreakWeight(V, float3(-1.0f, 0.0f, 1e-7f)) == 0.0f);
        for (int j = 0; j < 64; j++) {
            const float z = u01(), phi = 6.2831853f * u01(), rxy = std::sqrt(std::max(1.0f - z * z, 0.0f));
            assert_true(rtpbr::LTC_StreakWeight(V, float3(rxy * std::cos(phi), rxy * std::sin(phi), z)) == 0.0f);
        }
    }
    // the limit sqrt(1 - 0.71875^2) = 0.6953 plus the margin 0.01
    assert_true(steep > 280 && steep < 300);
    assert_true(!rtpbr::LTC_StreakSteep(0.69f) && rtpbr::LTC_StreakSteep(0.71f) && !rtpbr::LTC_StreakSteep(std::nanf("")));
    assert_true(rtpbr::LTC_StreakWeight(float3(std::sqrt(1.0f - 0.69f * 0.69f), 0.0f, 0.69f), float3(-1.0f, 0.0f, 1e-7f)) > 0.0f);
    // LTC_StreakOutside: random cones; a direction within spread s of axis a, at angle t <= s
    // from it toward the azimuth phi
    auto unit = [&]() {
        const float z = 2.0f * u01() - 1.0f, phi = 6.2831853f * u01(), r = std::sqrt(std::max(1.0f - z * z, 0.0f));
        return float3(r * std::cos(phi), r * std::sin(phi), z);
    };
    auto within = [](float3 a, float t, float phi) {
        const float3 e1 = glm::normalize(glm::cross(a, std::fabs(a.x) < 0.9f ? float3(1.0f, 0.0f, 0.0f) : float3(0.0f, 1.0f, 0.0f)));
        const float3 e2 = glm::cross(a, e1);
        return glm::normalize(a * std::cos(t) + (e1 * std::cos(phi) + e2 * std::sin(phi)) * std::sin(t));
    };
    const double limit = std::acos(0.5 * 0.75 * 0.75 - 1.0); // RTPBR_LTC_STREAK_V1 0.75: 136 degrees
    int outside = 0, tight = 0;
    for (int k = 0; k < 4000; k++) {
        const float3 a = unit(), b = unit();
        const float sa = 0.6f * u01() * u01(), sb = 0.6f * u01() * u01();
        const double axes = std::acos(std::min(std::max(double(glm::dot(a, b)), -1.0), 1.0));
        // the axes given unnormalised (any length)
        const bool out = rtpbr::LTC_StreakOutside(a * (0.5f + 3.0f * u01()), sa, b * (0.5f + 3.0f * u01()), sb);
        if (out) {
            outside++;
            assert_true(axes + sa + sb < limit);
            for (int j = 0; j < 200; j++) {
                const float ta = j < 100 ? sa : sa * u01(), tb = j < 100 ? sb : sb * u01();
                assert_true(weight(within(a, ta, 6.2831853f * u01()), within(b, tb, 6.2831853f * u01())) == 0.0f);
            }
            // the farthest pair: each axis turned away from the other by its spread
            const float3 away = glm::cross(a, b);
            if (glm::dot(away, away) > 1e-6f) {
                const float3 n = glm::normalize(away);
                const float3 fa = glm::normalize(a * std::cos(sa) + glm::cross(a, n) * std::sin(sa));
                const float3 fb = glm::normalize(b * std::cos(sb) - glm::cross(b, n) * std::sin(sb));
                assert_true(weight(fa, fb) == 0.0f);
            }
        } else if (axes + sa + sb > limit + 0.02 && axes + sa + sb < 3.1) {
            // not vacuous: the farthest pair has a weight
            const float3 away = glm::cross(a, b);
            if (glm::dot(away, away) > 1e-6f) {
                const float3 n = glm::normalize(away);
                const float3 fa = glm::normalize(a * std::cos(sa) + glm::cross(a, n) * std::sin(sa));
                const float3 fb = glm::normalize(b * std::cos(sb) - glm::cross(b, n) * std::sin(sb));
                assert_true(weight(fa, fb) > 0.0f);
                tight++;
            }
        }
    }
    fprintf(stderr, "streak culling: %d steep NoV of 1001, %d of 4000 cone pairs outside, %d past the limit with a weight\n",
            steep, outside, tight);
    assert_true(outside > 1000 && tight > 200);
    assert_true(!rtpbr::LTC_StreakOutside(float3(1.0f, 0.0f, 0.0f), std::nanf(""), float3(0.0f, 1.0f, 0.0f), 0.1f));
    assert_true(rtpbr::LTC_StreakOutside(float3(1.0f, 0.0f, 0.0f), 0.1f, float3(0.0f, 1.0f, 0.0f), 0.1f));
    // a light cone wider than a hemisphere is not convex: never outside (two directions 91
    // degrees off its axis on either side average to the opposite of the axis)
    assert_true(!rtpbr::LTC_StreakOutside(float3(1.0f, 0.0f, 0.0f), 0.0f, float3(1.0f, 0.0f, 0.0f), 1.6f));
    assert_true(rtpbr::LTC_StreakOutside(float3(1.0f, 0.0f, 0.0f), 0.0f, float3(1.0f, 0.0f, 0.0f), 1.5f));
}

// LTC_StreakSpan, LTC_StreakSpanTrusted: AreaLight_StreakEstimate skips the chords pass and
// LTC_StreakEnd where the span says untrusted, so that must be only where LTC_StreakEnd's trust
// is 0. Random rectangles of every aspect (tall lights across the plane of incidence included)
// over views down to grazing and GGX alphas from 0.01: wherever the end trusts the estimate at
// all, the span must say trusted; and the skip is not vacuous (many skipped) nor loose (cases
// with the span between Q0 and Q1 keep a trust: a test at Q0 would fail).
static void test_streak_span(void **state) {
    (void)state;
    Rng rng(77);
    auto u01 = [&]() { return float(rng.uniform()); };
    int skipped = 0, trusted = 0, between = 0, seen = 0;
    for (int k = 0; k < 20000; k++) {
        const float nov = 0.02f + 0.98f * u01() * u01();
        const float3 vLocal(std::sqrt(1.0f - nov * nov), 0.0f, nov);
        const float alpha = 0.01f + 0.5f * u01() * u01();
        // the light's centre: above the horizon, on the mirror side more often than not
        const float el = 1.5f * u01() * u01(), az = (u01() < 0.7f ? 3.14159265f : 0.0f) + 1.2f * (u01() - 0.5f);
        const float3 c = (0.5f + 3.0f * u01()) * float3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el) + 0.02f);
        float3 e1 = glm::normalize(glm::cross(c, float3(u01() - 0.5f, u01() - 0.5f, u01() - 0.5f)));
        float3 e2 = glm::normalize(glm::cross(c, e1));
        e1 *= 0.05f + 1.5f * u01() * u01();
        e2 *= 0.05f + 1.5f * u01() * u01();
        rtpbr::LtcPolygon poly{};
        poly.count = 4;
        poly.v[0] = c - e1 - e2, poly.v[1] = c + e1 - e2, poly.v[2] = c + e1 + e2, poly.v[3] = c - e1 + e2;
        const rtpbr::LtcLocalPolygon local =
            rtpbr::LTC_PolygonToLocal(rtpbr::LTC_Frame(float3(0.0f, 0.0f, 1.0f), vLocal), float3(0.0f), poly, true);
        if (local.count < 3)
            continue;
        const float3 F = rtpbr::LTC_FormFactorVector(local, rtpbr::LTC_Identity());
        // AreaLight_StreakEstimate's steps over a stored polygon (LTC_StreakLocal's)
        rtpbr::LtcStreak st = rtpbr::LTC_StreakBegin();
        for (int i = 0; i < local.count; i++)
            rtpbr::LTC_StreakEdge(st, local.v[i], local.v[(i + 1) % local.count]);
        rtpbr::LTC_StreakNodes(st, F);
        const float q = rtpbr::LTC_StreakSpan(st, vLocal, alpha);
        // q by its definition, in double: the half vector's slopes h.x / h.z toward the range's
        // two ends (x, z), their difference over the lobe's width sqrt(alpha^2 + s^2) at the
        // slope nearer 0 (alpha alone where the range crosses the normal's slope 0)
        const double s0 = (double(vLocal.x) + st.ends.x) / (double(vLocal.z) + st.ends.y),
                     s1 = (double(vLocal.x) + st.ends.z) / (double(vLocal.z) + st.ends.w);
        const double nearest = s0 * s1 <= 0.0 ? 0.0 : std::min(std::fabs(s0), std::fabs(s1));
        const double qRef = std::fabs(s1 - s0) / std::sqrt(double(alpha) * alpha + nearest * nearest);
        if (st.ends.y + vLocal.z > 1e-3f && st.ends.w + vLocal.z > 1e-3f)
            assert_true(std::fabs(q - qRef) <= 1e-4 * std::max(qRef, 1.0));
        for (int i = 0; i < local.count; i++)
            rtpbr::LTC_StreakChordEdge(st, local.v[i], local.v[(i + 1) % local.count]);
        const float2 e = rtpbr::LTC_StreakEnd(st, vLocal, alpha);
        const float2 whole = rtpbr::LTC_StreakLocal(local, F, vLocal, alpha);
        assert_true(whole.x == e.x && whole.y == e.y); // the steps above are LTC_StreakLocal's
        if (e.x < 0.0f)
            continue;
        seen++;
        if (!rtpbr::LTC_StreakSpanTrusted(q)) {
            skipped++;
            assert_true(e.y == 0.0f);
        } else if (e.y > 0.0f) {
            trusted++;
            if (q > RTPBR_LTC_STREAK_Q0)
                between++;
        }
    }
    fprintf(stderr, "streak span: %d estimates, %d skipped by the span, %d trusted (%d with the span between Q0 and Q1)\n",
            seen, skipped, trusted, between);
    assert_true(seen > 10000 && skipped > 1000 && trusted > 100 && between > 20);
    assert_true(!rtpbr::LTC_StreakSpanTrusted(std::nanf("")) && !rtpbr::LTC_StreakSpanTrusted(RTPBR_LTC_STREAK_Q1) &&
                rtpbr::LTC_StreakSpanTrusted(0.99f * RTPBR_LTC_STREAK_Q1));
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_ggx_vs_mc),
                cmocka_unit_test(test_beckmann_vs_mc),
                cmocka_unit_test(test_fresnel_scales),
                cmocka_unit_test(test_last_row_regular),
                cmocka_unit_test(test_disney_diffuse_albedo),
                cmocka_unit_test(test_disney_diffuse_vs_mc),
                cmocka_unit_test(test_anisotropic_stretch_vs_mc),
                cmocka_unit_test(test_ggx_floor),
                cmocka_unit_test(test_point_correction),
                cmocka_unit_test(test_grazing_partition),
                cmocka_unit_test(test_streak_culling),
                cmocka_unit_test(test_streak_span))
