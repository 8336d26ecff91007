// LTC against a converged quadrature on floors lit by lights near their horizon (issue 19):
// the cases of rtpbr-ltc-floor (tools/ltcfit/floor.cpp, which documents the geometry and the
// error measure) and of the test (tests/shaderlib/ltc/test_ltc_mc.cpp, a reduced sweep).
#pragma once

#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "ltc_mc.hpp"

namespace ltcfloor {

using ltcmc::float2;
using ltcmc::float3;
using ltcmc::float4;
using ltcmc::Lobe;

struct Case {
    float roughness, elevDeg, nov, azimDeg;
};

struct CaseResult {
    Case c;
    double sumAbs = 0, sumSigned = 0, sumRef = 0;
    double err = 0;         // sum |ltc - ref| / sum ref
    double signedErr = 0;   // sum (ltc - ref) / sum ref
    double quadDiff = 0;    // max |ref(n) - ref(n/2)| / max ref over the patch
    std::vector<float> map; // (ltc - ref) / ref per point, P x P
};

constexpr float kHalf = 0.15f;  // light half-size
constexpr float kPatch = 0.2f;  // patch half-size

// Gauss-Legendre nodes and weights on [-1, 1], 8 points (Abramowitz & Stegun 25.4.30).
constexpr double kGlX[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr double kGlW[4] = {0.3626837833783620, 0.3137066859002945, 0.2223810344533745, 0.1012285362903763};

// n-point composite Gauss-Legendre rule (panels of 8) on [a, b]: nodes and weights appended.
inline void gauss_legendre(double a, double b, int panels, std::vector<double> &x, std::vector<double> &w) {
    const double h = (b - a) / panels;
    for (int k = 0; k < panels; k++)
        for (int i = 0; i < 8; i++) {
            double t = i < 4 ? -kGlX[3 - i] : kGlX[i - 4], wt = i < 4 ? kGlW[3 - i] : kGlW[i - 4];
            x.push_back(a + h * (k + 0.5 * (t + 1.0)));
            w.push_back(0.5 * h * wt);
        }
}

// Integral over the light (horizontal square at centre.z facing down) of f NoL seen from point
// p. Across the plane of incidence (y) the lobe of a grazing view is very narrow (H turns by
// about dy / (V.z + L.z) for a lateral step dy of L): there y = p.y + w sinh(t) with w = 1e-3
// puts the nodes densest at the plane of incidence (y = p.y) and still covers the whole
// light; `sub` panels of 8 points along x, 2 sub along t.
// `half`: the light's half-size (kHalf unless given; rtpbr-ltc-floor --second-lobe trains on others).
inline double quadrature(const ltcmc::Brdf &brdf, float3 V, float3 p, float3 centre, int sub, double half = kHalf) {
    std::vector<double> xs, wx, ts, wt;
    gauss_legendre(centre.x - half, centre.x + half, sub, xs, wx);
    const double w = 1e-3;
    gauss_legendre(std::asinh((centre.y - half - p.y) / w), std::asinh((centre.y + half - p.y) / w), 2 * sub, ts, wt);
    double sum = 0.0;
    for (size_t i = 0; i < xs.size(); i++)
        for (size_t j = 0; j < ts.size(); j++) {
            double y = p.y + w * std::sinh(ts[j]);
            double jac = w * std::cosh(ts[j]);
            glm::dvec3 d(xs[i] - p.x, y - p.y, double(centre.z) - p.z);
            double d2 = glm::dot(d, d);
            glm::dvec3 L = d / std::sqrt(d2);
            float pdf;
            double f = brdf.value_cos(V, float3(L), pdf); // f NoL
            // dA -> solid angle: cos at the light (its normal is -z) / d^2
            sum += f * L.z / d2 * wx[i] * wt[j] * jac;
        }
    return sum;
}

// Experiments (issue 19, rtpbr-ltc-floor --elevation-correction / --direction-correction;
// not in the engine): the LTC result scaled by a factor that depends on where the lit part of
// the light is, seen from the surface: F = the vector form factor of the horizon-clipped
// polygon in the shading frame (x toward V; what the engine's basic variant computes already
// for Lambert), its elevation sin e = F.z / |F| and (with azimuth bins) its azimuth phi =
// atan2(|F.y|, F.x) from the viewer's side. The factor of a bin is the ratio of the true
// BRDF's integral over the bin's directions (a band of elevations, all azimuths or a range of
// them) to the LTC's, for this (NoV, roughness): where the LTC puts too much light (the mirror
// side at 2 degrees) it is < 1, too little > 1. Elevation bins uniform in sqrt(sin e) (dense
// near the horizon), azimuth bins uniform in phi; bilinear between bin centres as a texture.
struct DirectionCorrection {
    static constexpr int kElev = 32, kMaxAz = 24; // at most
    int elev = 16, az = 1; // elevation bins; azimuth bins (1: elevation only)
    double c[kElev][kMaxAz];   // the ratio (--elevation-correction, --direction-correction)
    double add[kElev][kMaxAz]; // (ref - LTC) / the bin's cosine mass (--residual-correction)
    double hc[kElev][kMaxAz], hadd[kElev][kMaxAz]; // --hybrid-correction (below)
    int elev_bin(double z) const { return std::min(int(std::sqrt(std::max(z, 0.0)) * elev), elev - 1); }
    int az_bin(double x, double y) const {
        return std::min(int(std::atan2(std::fabs(y), x) / 3.14159265358979 * az), az - 1);
    }
    double at(float3 F) const { return lookup(F, c); }
    double residual_at(float3 F) const { return lookup(F, add); }
    double lookup(float3 F, const double (&tab)[kElev][kMaxAz]) const {
        const double len = glm::length(glm::dvec3(F));
        if (!(len > 0.0))
            return 1.0;
        auto coord = [](double v, int n) {
            double x = std::clamp(v * n - 0.5, 0.0, double(n - 1));
            int i = std::min(int(x), std::max(n - 2, 0));
            return std::pair<int, double>(i, n > 1 ? x - i : 0.0);
        };
        auto [i, fi] = coord(std::sqrt(std::clamp(double(F.z) / len, 0.0, 1.0)), elev);
        auto [j, fj] = coord(std::atan2(std::fabs(double(F.y)), double(F.x)) / 3.14159265358979, az);
        const int j1 = std::min(j + 1, az - 1);
        double lo = tab[i][j] + (tab[i][j1] - tab[i][j]) * fj, hi = tab[i + 1][j] + (tab[i + 1][j1] - tab[i + 1][j]) * fj;
        return lo + (hi - lo) * fi;
    }
};

inline DirectionCorrection direction_correction(Lobe lobe, float nov, float r, float4 l1, float4 l2, int elevBins,
                                                int azBins, int side) {
    DirectionCorrection e;
    e.elev = elevBins;
    e.az = azBins;
    const float3 V(std::sqrt(1.0f - nov * nov), 0.0f, nov);
    const ltcmc::Brdf brdf = ltcmc::Brdf::make(lobe, r);
    const glm::dmat3 M = glm::inverse(glm::dmat3(rtpbr::LTC_InverseMatrix(l1)));
    double ref[DirectionCorrection::kElev][DirectionCorrection::kMaxAz] = {};
    double ltc[DirectionCorrection::kElev][DirectionCorrection::kMaxAz] = {};
    double cosMass[DirectionCorrection::kElev][DirectionCorrection::kMaxAz] = {};
    const double n = double(side) * side;
    for (int j = 0; j < side; j++)
        for (int i = 0; i < side; i++) {
            float2 u((i + 0.5f) / side, (j + 0.5f) / side);
            float3 L = brdf.sample(V, u);
            float pdf;
            float f = brdf.value_cos(V, L, pdf);
            if (L.z > 0.0f && pdf > 0.0f && f > 0.0f)
                ref[e.elev_bin(double(L.z))][e.az_bin(double(L.x), double(L.y))] += double(f) / double(pdf) / n;
            const glm::dvec3 cosL(rtpbr::Sample_CosineHemisphere(u));
            cosMass[e.elev_bin(cosL.z)][e.az_bin(cosL.x, cosL.y)] += 1.0 / n;
            glm::dvec3 Lt = glm::normalize(M * cosL);
            if (Lt.z > 0.0)
                ltc[e.elev_bin(Lt.z)][e.az_bin(Lt.x, Lt.y)] += double(l2.x) / n;
        }
    for (int k = 0; k < DirectionCorrection::kElev; k++)
        for (int a = 0; a < DirectionCorrection::kMaxAz; a++) {
            const bool used = a < azBins, lit = ltc[k][a] > 1e-4 * double(l2.x);
            e.c[k][a] = used && lit ? ref[k][a] / ltc[k][a] : 1.0;
            e.add[k][a] = used && cosMass[k][a] > 0.0 ? (ref[k][a] - ltc[k][a]) / cosMass[k][a] : 0.0;
            // hybrid: the ratio where the LTC holds at least 10% of the true light, the
            // residual density where it holds less (its support cuts the bin off)
            const bool ratioHolds = ltc[k][a] >= 0.1 * ref[k][a] && lit;
            e.hc[k][a] = used && ratioHolds ? ref[k][a] / ltc[k][a] : 1.0;
            e.hadd[k][a] = used && !ratioHolds && cosMass[k][a] > 0.0 ? (ref[k][a] - ltc[k][a]) / cosMass[k][a] : 0.0;
        }
    return e;
}

struct Tables {
    Tables(const float *a, const float *b) : t1(a), t2(b) {}
    const float *t1, *t2;
    // If set: the LTC of this case without the table's interpolation (ltc1, ltc2 as fetched);
    // rtpbr-ltc-floor --exact-cells.
    std::function<void(const Case &, float4 &, float4 &)> exact;
    int correctionAzimuths = 0; // 0: none; else DirectionCorrection's azimuth bins (above)
    int correctionElevations = 16, correctionSamples = 512; // its elevation bins, samples per side
    // the corrections of each (roughness, NoV), computed once (shared by the threads)
    std::shared_ptr<std::mutex> cacheMutex = std::make_shared<std::mutex>();
    std::shared_ptr<std::map<std::pair<float, float>, DirectionCorrection>> cache =
        std::make_shared<std::map<std::pair<float, float>, DirectionCorrection>>();
    bool residual = false;      // additive (LTC + residual x F.z) instead of the ratio
    bool hybrid = false;        // ratio where the LTC is lit, residual where it is not
    // 0: the LTC alone (rtpbr-ltc-floor --no-point); 1: with the engine's point correction
    // (ltc_corrections.h, LTC_PointFactor, and the tail estimate unless tail = false; the
    // default); experiments of the fourth round: 2: the raw ratio (no clamp, no fade; --point-raw); 3: no LTC, the true f
    // at the lit part's centroid x its cosine form factor (--point-ff)
    int point = 1;
    // with point = 1: the tail estimate too (ltc_corrections.h, LTC_PointTail; the fifth
    // round's engine and the default); false: the point correction alone (rtpbr-ltc-floor --no-tail)
    bool tail = true;
    // with tail: the streak estimate too (ltc_corrections.h, LTC_StreakEnd; the sixth round's
    // engine and the default); false: the fifth round's engine (rtpbr-ltc-floor --no-streak)
    bool streak = true;
};

inline CaseResult run_case(const Case &c, Lobe lobe, Tables tab, int P, int sub) {
    CaseResult r;
    r.c = c;
    const float deg = 3.14159265f / 180.0f;
    float3 V(std::sqrt(1.0f - c.nov * c.nov), 0.0f, c.nov);
    float e = c.elevDeg * deg, az = c.azimDeg * deg;
    float3 centre(std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e));
    ltcmc::Brdf brdf = ltcmc::Brdf::make(lobe, c.roughness);
    float3 N(0, 0, 1);
    float4 l1 = ltcmc::fetch(tab.t1, rtpbr::LTC_LutCoord(c.nov, c.roughness));
    float4 l2 = ltcmc::fetch(tab.t2, rtpbr::LTC_LutCoord(c.nov, c.roughness));
    if (tab.exact)
        tab.exact(c, l1, l2);
    rtpbr::float3x3 frame = rtpbr::LTC_Frame(N, V);
    DirectionCorrection corr{};
    if (tab.correctionAzimuths > 0) {
        bool have = false;
        {
            std::lock_guard<std::mutex> lock(*tab.cacheMutex);
            auto it = tab.cache->find({c.roughness, c.nov});
            if (it != tab.cache->end()) {
                corr = it->second;
                have = true;
            }
        }
        if (!have) {
            corr = direction_correction(lobe, c.nov, c.roughness, l1, l2, tab.correctionElevations,
                                        tab.correctionAzimuths, tab.correctionSamples);
            std::lock_guard<std::mutex> lock(*tab.cacheMutex);
            (*tab.cache)[{c.roughness, c.nov}] = corr;
        }
    }
    double sumAbs = 0, sumSigned = 0, sumRef = 0, maxRef = 0, maxDiff = 0;
    r.map.resize(size_t(P) * P);
    for (int j = 0; j < P; j++)
        for (int i = 0; i < P; i++) {
            float3 p(kPatch * (2.0f * (i + 0.5f) / P - 1.0f), kPatch * (2.0f * (j + 0.5f) / P - 1.0f), 0.0f);
            // facing down: counter-clockwise seen from below
            float3 q0 = centre + float3(-kHalf, -kHalf, 0), q1 = centre + float3(-kHalf, kHalf, 0),
                   q2 = centre + float3(kHalf, kHalf, 0), q3 = centre + float3(kHalf, -kHalf, 0);
            rtpbr::LtcPolygon poly = rtpbr::LTC_Quad(q0, q1, q2, q3);
            const rtpbr::LtcLocalPolygon local = rtpbr::LTC_PolygonToLocal(frame, p, poly, true);
            double ltc = double(l2.x) * rtpbr::LTC_IntegrateLocal(local, l1);
            if (tab.correctionAzimuths > 0) {
                const float3 F = rtpbr::LTC_FormFactorVector(local, rtpbr::LTC_Identity());
                ltc = tab.hybrid     ? std::max(ltc * corr.lookup(F, corr.hc) + corr.lookup(F, corr.hadd) * double(F.z), 0.0)
                      : tab.residual ? std::max(ltc + corr.residual_at(F) * double(F.z), 0.0)
                                     : ltc * corr.at(F);
            }
            if (tab.point == 1 || tab.point == 2) {
                if (lobe == Lobe::GGX || lobe == Lobe::Beckmann) // as the engine: microfacet lobes only
                    ltc = tab.point == 2 ? ltc * ltcmc::point_ratio(brdf, V, local, l1, l2.x, true)
                                         : ltcmc::point_value(brdf, V, local, l1, l2.x, ltc, tab.tail, nullptr, tab.streak);
            } else if (tab.point == 3) {
                // true f at the lit part's centroid x its cosine form factor
                const glm::dvec3 Fc = ltcmc::clipped_centroid(local, glm::dmat3(1.0));
                const double lf = glm::length(Fc);
                ltc = 0.0;
                if (lf > 0.0) {
                    const glm::dvec3 w = Fc / lf;
                    float pdf;
                    const double f = brdf.value_cos(V, float3(w), pdf);
                    const double ff = rtpbr::LTC_IntegrateLocal(local, rtpbr::LTC_Identity());
                    if (w.z > 0.0)
                        ltc = f / w.z * 3.14159265358979 * ff;
                }
            }
            double ref = quadrature(brdf, V, p, centre, sub);
            double coarse = quadrature(brdf, V, p, centre, sub / 2);
            maxDiff = std::max(maxDiff, std::fabs(ref - coarse));
            maxRef = std::max(maxRef, ref);
            sumAbs += std::fabs(ltc - ref);
            sumSigned += ltc - ref;
            sumRef += ref;
            r.map[size_t(j) * P + i] = ref > 0 ? float((ltc - ref) / ref) : 0.0f;
        }
    r.sumAbs = sumAbs, r.sumSigned = sumSigned, r.sumRef = sumRef;
    r.err = sumRef > 0 ? sumAbs / sumRef : 0.0;
    r.signedErr = sumRef > 0 ? sumSigned / sumRef : 0.0;
    r.quadDiff = maxRef > 0 ? maxDiff / maxRef : 0.0;
    return r;
}

// One floor = the cases of all azimuths of a (roughness, elevation, NoV): azimuths strictly
// between 0 and 180 stand for their mirror images too and count twice.
// Its error: sum |LTC - ref| / sum ref over all its points.
inline double floor_error(const std::vector<CaseResult> &azimuths) {
    double abs = 0.0, ref = 0.0;
    for (const CaseResult &c : azimuths) {
        double w = c.c.azimDeg == 0.0f || c.c.azimDeg == 180.0f ? 1.0 : 2.0;
        abs += w * c.sumAbs;
        ref += w * c.sumRef;
    }
    return ref > 0.0 ? abs / ref : 0.0;
}

} // namespace ltcfloor
