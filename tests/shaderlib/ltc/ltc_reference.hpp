// Independent double-precision references for the LTC tests: polygon clipping and Lambert's
// closed-form polygon irradiance, written separately from shaderlib/rtpbr/ltc.h.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "rtpbr_common/rng.h"

namespace ltcref {

struct d3 {
    double x, y, z;
};
inline d3 operator+(d3 a, d3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline d3 operator-(d3 a, d3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline d3 operator*(d3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(d3 a, d3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline d3 cross(d3 a, d3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double len(d3 a) { return std::sqrt(dot(a, a)); }
inline d3 unit(d3 a) { return a * (1.0 / len(a)); }

// Deterministic generator (SplitMix64, common/), uniform doubles in [0, 1).
struct Rng : rtpbr_tools::SplitMix64 {
    using SplitMix64::SplitMix64;
    double uniform() { return uniform_double(); }
    double range(double a, double b) { return a + (b - a) * uniform(); }
    d3 direction() { // uniform on the sphere
        double z = range(-1.0, 1.0), phi = range(0.0, 2.0 * M_PI), r = std::sqrt(1.0 - z * z);
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
};

// Keeps the part of a convex polygon where dot(p, n) >= 0.
inline std::vector<d3> clip(const std::vector<d3> &poly, d3 n) {
    std::vector<d3> out;
    for (size_t i = 0; i < poly.size(); i++) {
        d3 a = poly[i], b = poly[(i + 1) % poly.size()];
        double da = dot(a, n), db = dot(b, n);
        if (da >= 0.0)
            out.push_back(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0))
            out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

// Lambert's formula (Lambert 1760; Arvo 1995): the form factor (projected solid angle / pi)
// of a polygon, given relative to the shading point, for the surface normal n; the polygon is
// clipped to the hemisphere of n first. One-sided lights (front = counter-clockwise seen from
// the viewer) give 0 from behind.
inline double lambert_form_factor(std::vector<d3> poly, d3 n, bool twoSided) {
    d3 pn = cross(poly[1] - poly[0], poly[2] - poly[0]);
    if (!twoSided && dot(pn, poly[0]) >= 0.0) // the normal points away from the viewer
        return 0.0;
    poly = clip(poly, n);
    if (poly.size() < 3)
        return 0.0;
    double sum = 0.0;
    for (size_t i = 0; i < poly.size(); i++) {
        d3 a = unit(poly[i]), b = unit(poly[(i + 1) % poly.size()]);
        d3 c = cross(a, b);
        double lc = len(c);
        if (lc == 0.0)
            continue;
        double theta = std::acos(std::fmax(-1.0, std::fmin(1.0, dot(a, b))));
        sum += theta * dot(c, n) / lc;
    }
    return std::fabs(sum) / (2.0 * M_PI);
}

// A random convex polygon of k vertices on an ellipse (semi-axes r1, r2) centred at c in the
// plane with normal pn; vertex order counter-clockwise around pn.
inline std::vector<d3> random_polygon(Rng &rng, int k, d3 c, d3 pn, double r1, double r2) {
    d3 t = std::fabs(pn.z) < 0.9 ? unit(cross(d3{0, 0, 1}, pn)) : unit(cross(d3{1, 0, 0}, pn));
    d3 b = cross(pn, t);
    std::vector<double> ang(k);
    // k sorted angles with gaps of at least 0.2 rad so that no three vertices are collinear
    double base = rng.range(0.0, 2.0 * M_PI);
    double slack = 2.0 * M_PI - 0.2 * k;
    std::vector<double> cuts(k);
    double total = 0.0;
    for (int i = 0; i < k; i++) {
        cuts[i] = rng.range(0.05, 1.0);
        total += cuts[i];
    }
    double a = base;
    for (int i = 0; i < k; i++) {
        ang[i] = a;
        a += 0.2 + slack * cuts[i] / total;
    }
    std::vector<d3> poly;
    for (int i = 0; i < k; i++)
        poly.push_back(c + t * (r1 * std::cos(ang[i])) + b * (r2 * std::sin(ang[i])));
    return poly;
}

} // namespace ltcref
