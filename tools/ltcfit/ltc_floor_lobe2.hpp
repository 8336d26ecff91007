// Experiment of issue 19's third round (rtpbr-ltc-floor --second-lobe; not in the engine, no
// table): how far a second LTC lobe, added to the table's LTC, could bring the grazing floors.
// Per (roughness, NoV) cell one more lobe a x LTC_IntegrateLocal(polygon, m) (m = the four
// entries of M^-1 the table stores, a a signed amplitude: the second lobe may also take light
// away, where the first is too bright) is fitted by Nelder-Mead to the residual ref - LTC_1 on
// a training set of floors that is not the sweep's: lights of half-size 0.1 and 0.25 (the
// sweep's: 0.15) at elevations 3.5, 7.5, 12, 16, 25 and 35 degrees (the sweep's: 2, 5, 10, 20,
// 40), azimuths 0, 15, 45, ..., 165, 180 (the sweep's: 0, 30, ..., 180), 4 x 4 points per patch;
// the objective is the mean of those floors' relative L1 errors (each floor: all azimuths of
// one elevation and size). The sweep's floors of the cell are then measured with and without
// the lobe. A bound for a table of such lobes (no interpolation between cells), what a third
// and fourth texture per light would buy.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "ltc_floor.hpp"

namespace ltcfloor {

struct Lobe2Point {
    rtpbr::LtcLocalPolygon local;
    double ref, ltc1, w;
    int floor;
};

struct Lobe2Result {
    float roughness, nov;
    std::array<double, 5> m{};          // m00, m02, m20, m22, a
    std::array<double, 5> m1{};         // --second-lobe-joint: the refitted first lobe, its norm last
    double trainBefore = 0, trainAfter = 0;
    std::vector<float> elevs;           // the sweep's elevations
    std::vector<double> before, after;  // the sweep's floor errors per elevation
};

// Floor points of one (r, NoV): lights at elevations x half-sizes (one floor each) x azimuths.
inline std::vector<Lobe2Point> lobe2_points(const ltcmc::Brdf &brdf, float nov, float4 l1, float4 l2,
                                            const std::vector<float> &elevs, const std::vector<float> &halves,
                                            const std::vector<float> &azims, int P, int sub) {
    const float deg = 3.14159265f / 180.0f;
    float3 V(std::sqrt(1.0f - nov * nov), 0.0f, nov), N(0, 0, 1);
    rtpbr::float3x3 frame = rtpbr::LTC_Frame(N, V);
    std::vector<Lobe2Point> pts;
    int floor = 0;
    for (float e : elevs)
        for (float h : halves) {
            for (float az : azims) {
                float3 centre(std::cos(e * deg) * std::cos(az * deg), std::cos(e * deg) * std::sin(az * deg),
                              std::sin(e * deg));
                double w = az == 0.0f || az == 180.0f ? 1.0 : 2.0;
                for (int j = 0; j < P; j++)
                    for (int i = 0; i < P; i++) {
                        float3 p(kPatch * (2.0f * (i + 0.5f) / P - 1.0f), kPatch * (2.0f * (j + 0.5f) / P - 1.0f), 0.0f);
                        float3 q0 = centre + float3(-h, -h, 0), q1 = centre + float3(-h, h, 0),
                               q2 = centre + float3(h, h, 0), q3 = centre + float3(h, -h, 0);
                        Lobe2Point pt;
                        pt.local = rtpbr::LTC_PolygonToLocal(frame, p, rtpbr::LTC_Quad(q0, q1, q2, q3), true);
                        pt.ltc1 = double(l2.x) * rtpbr::LTC_IntegrateLocal(pt.local, l1);
                        pt.ref = quadrature(brdf, V, p, centre, sub, double(h));
                        pt.w = w;
                        pt.floor = floor;
                        pts.push_back(pt);
                    }
            }
            floor++;
        }
    return pts;
}

// Per floor: sum w |LTC_1 + a LTC_2 - ref| / sum w ref (m == nullptr: LTC_1 alone; m1: LTC_1
// replaced by m1[4] x the LTC of m1[0..3]).
inline std::vector<double> lobe2_floor_errors(const std::vector<Lobe2Point> &pts, int floors, const double *m,
                                              const double *m1 = nullptr) {
    std::vector<double> abs(size_t(floors), 0.0), ref(size_t(floors), 0.0);
    float4 l(0.0f), k(0.0f);
    if (m)
        l = float4(float(m[0]), float(m[1]), float(m[2]), float(m[3]));
    if (m1)
        k = float4(float(m1[0]), float(m1[1]), float(m1[2]), float(m1[3]));
    for (const Lobe2Point &p : pts) {
        double v = m1 ? m1[4] * double(rtpbr::LTC_IntegrateLocal(p.local, k)) : p.ltc1;
        if (m)
            v += m[4] * double(rtpbr::LTC_IntegrateLocal(p.local, l));
        abs[size_t(p.floor)] += p.w * std::fabs(v - p.ref);
        ref[size_t(p.floor)] += p.w * p.ref;
    }
    for (int f = 0; f < floors; f++)
        abs[size_t(f)] = ref[size_t(f)] > 0 ? abs[size_t(f)] / ref[size_t(f)] : 0.0;
    return abs;
}

// Nelder & Mead 1965 (standard coefficients 1, 2, 0.5, 0.5), dimension n.
template <size_t N, class F>
std::array<double, N> lobe2_nelder_mead(F &&f, std::array<double, N> x0, std::array<double, N> step, int iterations) {
    constexpr int n = int(N);
    std::array<std::array<double, n>, n + 1> s;
    std::array<double, n + 1> fv;
    for (int i = 0; i <= n; i++) {
        s[size_t(i)] = x0;
        if (i > 0)
            s[size_t(i)][size_t(i - 1)] += step[size_t(i - 1)];
        fv[size_t(i)] = f(s[size_t(i)]);
    }
    for (int it = 0; it < iterations; it++) {
        std::array<int, n + 1> o;
        for (int i = 0; i <= n; i++)
            o[size_t(i)] = i;
        std::sort(o.begin(), o.end(), [&](int a, int b) { return fv[size_t(a)] < fv[size_t(b)]; });
        const int best = o[0], worst = o[n], second = o[n - 1];
        std::array<double, n> c{};
        for (int i = 0; i <= n; i++)
            if (i != worst)
                for (int k = 0; k < n; k++)
                    c[size_t(k)] += s[size_t(i)][size_t(k)] / n;
        auto along = [&](double t) {
            std::array<double, n> x;
            for (int k = 0; k < n; k++)
                x[size_t(k)] = c[size_t(k)] + t * (s[size_t(worst)][size_t(k)] - c[size_t(k)]);
            return x;
        };
        std::array<double, n> xr = along(-1.0);
        double fr = f(xr);
        if (fr < fv[size_t(best)]) {
            std::array<double, n> xe = along(-2.0);
            double fe = f(xe);
            if (fe < fr)
                s[size_t(worst)] = xe, fv[size_t(worst)] = fe;
            else
                s[size_t(worst)] = xr, fv[size_t(worst)] = fr;
        } else if (fr < fv[size_t(second)]) {
            s[size_t(worst)] = xr, fv[size_t(worst)] = fr;
        } else {
            std::array<double, n> xc = fr < fv[size_t(worst)] ? along(-0.5) : along(0.5);
            double fc = f(xc);
            if (fc < std::min(fr, fv[size_t(worst)])) {
                s[size_t(worst)] = xc, fv[size_t(worst)] = fc;
            } else {
                for (int i = 0; i <= n; i++)
                    if (i != best) {
                        for (int k = 0; k < n; k++)
                            s[size_t(i)][size_t(k)] = 0.5 * (s[size_t(i)][size_t(k)] + s[size_t(best)][size_t(k)]);
                        fv[size_t(i)] = f(s[size_t(i)]);
                    }
            }
        }
    }
    int b = 0;
    for (int i = 1; i <= n; i++)
        if (fv[size_t(i)] < fv[size_t(b)])
            b = i;
    return s[size_t(b)];
}

inline Lobe2Result lobe2_cell(Lobe lobe, float r, float nov, float4 l1, float4 l2, int iterations, bool joint) {
    Lobe2Result res;
    res.roughness = r, res.nov = nov;
    ltcmc::Brdf brdf = ltcmc::Brdf::make(lobe, r);
    const std::vector<float> trainElevs{3.5f, 7.5f, 12.0f, 16.0f, 25.0f, 35.0f}, trainHalves{0.1f, 0.25f};
    const std::vector<float> trainAzims{0.0f, 15.0f, 45.0f, 75.0f, 105.0f, 135.0f, 165.0f, 180.0f};
    std::vector<Lobe2Point> train = lobe2_points(brdf, nov, l1, l2, trainElevs, trainHalves, trainAzims, 4, 8);
    const int trainFloors = int(trainElevs.size() * trainHalves.size());
    auto mean = [](const std::vector<double> &v) {
        double s = 0;
        for (double x : v)
            s += x;
        return v.empty() ? 0.0 : s / double(v.size());
    };
    auto cost = [&](const std::array<double, 5> &x) {
        double det = x[0] * x[3] - x[1] * x[2];
        if (!(std::fabs(det) > 1e-4))
            return 1e9;
        double c = mean(lobe2_floor_errors(train, trainFloors, x.data()));
        return std::isfinite(c) ? c : 1e9;
    };
    res.trainBefore = mean(lobe2_floor_errors(train, trainFloors, nullptr));
    // Starts: the first lobe's own shape, leaning toward the horizon either way, and a
    // cosine; amplitudes of either sign.
    const double a1 = l1.x, b1 = l1.y, c1 = l1.z, d1 = l1.w;
    std::vector<std::array<double, 5>> starts{{a1, b1, c1, d1, 0.1}, {a1, b1, c1, d1, -0.1},
                                              {a1, b1 + 0.5, c1, d1, 0.1}, {a1, b1 - 0.5, c1, d1, 0.1},
                                              {1.0, 0.0, 0.0, 1.0, 0.05}, {2.0 * a1, b1, c1, d1, 0.1}};
    double bestCost = res.trainBefore;
    res.m = {a1, b1, c1, d1, 0.0};
    for (const auto &s0 : starts) {
        std::array<double, 5> x = s0;
        for (int pass = 0; pass < 3; pass++) // restarts: the simplex collapses
            x = lobe2_nelder_mead<5>(cost, x, {0.2 * std::max(std::fabs(x[0]), 0.1), 0.2, 0.2, 0.2 * std::max(std::fabs(x[3]), 0.1), 0.05},
                                  iterations);
        double cx = cost(x);
        if (cx < bestCost)
            bestCost = cx, res.m = x;
    }
    res.trainAfter = bestCost;
    res.m1 = {a1, b1, c1, d1, double(l2.x)};
    if (joint) { // both lobes refitted together, from the table's lobe and the best second lobe
        auto cost2 = [&](const std::array<double, 10> &x) {
            double det1 = x[0] * x[3] - x[1] * x[2], det2 = x[5] * x[8] - x[6] * x[7];
            if (!(std::fabs(det1) > 1e-4) || !(std::fabs(det2) > 1e-4))
                return 1e9;
            double c = mean(lobe2_floor_errors(train, trainFloors, x.data() + 5, x.data()));
            return std::isfinite(c) ? c : 1e9;
        };
        std::array<double, 10> x{a1, b1, c1, d1, double(l2.x), res.m[0], res.m[1], res.m[2], res.m[3], res.m[4]};
        for (int pass = 0; pass < 3; pass++)
            x = lobe2_nelder_mead<10>(cost2, x,
                                      {0.2 * std::max(std::fabs(x[0]), 0.1), 0.2, 0.2, 0.2 * std::max(std::fabs(x[3]), 0.1),
                                       0.05 * x[4], 0.2 * std::max(std::fabs(x[5]), 0.1), 0.2, 0.2,
                                       0.2 * std::max(std::fabs(x[8]), 0.1), 0.05},
                                      2 * iterations);
        double cx = cost2(x);
        if (cx < bestCost) {
            bestCost = cx;
            res.m1 = {x[0], x[1], x[2], x[3], x[4]};
            res.m = {x[5], x[6], x[7], x[8], x[9]};
        }
        res.trainAfter = bestCost;
    }
    // The sweep's floors of this cell (as in run_case: half-size kHalf, 8 x 8 points).
    res.elevs = {2.0f, 5.0f, 10.0f, 20.0f, 40.0f};
    const std::vector<float> azims{0.0f, 30.0f, 60.0f, 90.0f, 120.0f, 150.0f, 180.0f};
    std::vector<Lobe2Point> sweep = lobe2_points(brdf, nov, l1, l2, res.elevs, {kHalf}, azims, 8, 8);
    res.before = lobe2_floor_errors(sweep, int(res.elevs.size()), nullptr);
    res.after = lobe2_floor_errors(sweep, int(res.elevs.size()), res.m.data(), joint ? res.m1.data() : nullptr);
    return res;
}

} // namespace ltcfloor
