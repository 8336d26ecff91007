// Independent double-precision model of the KHR_materials_sheen lobe for the tests: the
// formulas re-typed from Estevez & Kulla 2017 (not the shaderlib code) and a deterministic
// quadrature of the directional albedo.
#pragma once

#include <algorithm>
#include <cmath>

namespace sheenref {

constexpr double kPi = 3.14159265358979323846;

// Estevez & Kulla 2017, table 1: (a, b, c, d, e) at r = 0 and r = 1; interpolation weight
// (1 - r)^2 towards the r = 0 row (KHR_materials_sheen, r = alpha).
inline double refL(double x, double alpha) {
    const double p0[5] = {25.3245, 3.32435, 0.16801, -1.27393, -4.85967};
    const double p1[5] = {21.5473, 3.82987, 0.19823, -1.97760, -4.32054};
    double w = (1.0 - alpha) * (1.0 - alpha), p[5];
    for (int i = 0; i < 5; i++)
        p[i] = w * p0[i] + (1.0 - w) * p1[i];
    return p[0] / (1.0 + p[1] * std::pow(x, p[2])) + p[3] * x + p[4];
}
inline double refLambda(double c, double alpha) {
    return c < 0.5 ? std::exp(refL(c, alpha)) : std::exp(2.0 * refL(0.5, alpha) - refL(1.0 - c, alpha));
}
inline double refD(double NoH, double alpha) {
    double s2 = std::max(0.0, 1.0 - NoH * NoH);
    return (2.0 + 1.0 / alpha) * std::pow(s2, 0.5 / alpha) / (2.0 * kPi);
}
inline double refV(int variant, double NoV, double NoL, double alpha) {
    if (variant == 0)
        return 1.0 / ((1.0 + refLambda(NoV, alpha) + refLambda(NoL, alpha)) * 4.0 * NoV * NoL);
    return 1.0 / (4.0 * (NoL + NoV - NoL * NoV));
}

// E(mu) = int D V cos dw_i by the midpoint rule on cos(theta_i) = u^2 (nodes dense at the
// horizon, where the sharp lobes live) and phi in [0, pi] (the lobe is symmetric), doubled.
inline double quadratureAlbedo(int variant, double mu, double alpha, int nU, int nPhi) {
    const double vx = std::sqrt(std::max(0.0, 1.0 - mu * mu)), vz = mu;
    double sum = 0.0;
    for (int i = 0; i < nU; i++) {
        double u = (i + 0.5) / nU, cl = u * u, dcl = 2.0 * u / nU;
        double sl = std::sqrt(std::max(0.0, 1.0 - cl * cl));
        double vis = refV(variant, mu, cl, alpha);
        double row = 0.0;
        for (int j = 0; j < nPhi; j++) {
            double ph = (j + 0.5) / nPhi * kPi;
            double hx = sl * std::cos(ph) + vx, hy = sl * std::sin(ph), hz = cl + vz;
            double nh = hz / std::sqrt(hx * hx + hy * hy + hz * hz);
            row += refD(nh, alpha);
        }
        sum += row * (kPi / nPhi) * vis * cl * dcl;
    }
    return 2.0 * sum;
}

} // namespace sheenref
