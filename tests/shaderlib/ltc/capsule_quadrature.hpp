// A noise-free double-precision rule over a capsule (a tube light: the cylinder of radius r
// around a -> b closed by two hemispheres) seen from the origin, for the tube tests
// (test_ltc_lines.cpp: the LTC distribution; test_area_light.cpp: the true BRDF). A convex body
// is seen exactly through its front-facing points, so the integral of g over the solid angle it
// fills above the horizon (z > 0) is int g(w) max(0, -n.w) / |x|^2 dA over its surface.
#pragma once

#include <cmath>
#include <vector>

#include "quadrature.hpp" // gauss_legendre

namespace capsule_rule {
struct V3 {
    double x, y, z;
};
inline V3 add(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 scale(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 unit(V3 a) { return scale(a, 1.0 / std::sqrt(dot(a, a))); }
} // namespace capsule_rule

// Gauss-Legendre on [a, b] in `panels` panels of `order` nodes.
template <class F> double integrate(double a, double b, int panels, int order, F f) {
    std::vector<double> x, w;
    gauss_legendre(order, x, w);
    double h = (b - a) / panels, sum = 0.0;
    for (int p = 0; p < panels; ++p)
        for (int k = 0; k < order; ++k) sum += h * w[k] * f(a + h * (p + x[k]));
    return sum;
}

// int g(w) dw over the capsule of radius r around a -> b (relative to the point; a == b: a
// sphere) above the horizon, g(wx, wy, wz) at unit directions: 1024 density azimuths, the
// cylinder in 64 density panels of 8 nodes along the axis, each hemisphere in 32 density panels of 8
// in the cosine from its pole (dA = r^2 du dphi).
template <class G> double capsule_integral(const double a[3], const double b[3], double r, G g, int density = 1) {
    using namespace capsule_rule;
    V3 A = {a[0], a[1], a[2]}, B = {b[0], b[1], b[2]};
    V3 ab = {B.x - A.x, B.y - A.y, B.z - A.z};
    double L = std::sqrt(dot(ab, ab));
    V3 T = L > 0.0 ? scale(ab, 1.0 / L) : V3{0.0, 0.0, 1.0};
    V3 t = std::fabs(T.z) < 0.9 ? V3{0, 0, 1} : V3{1, 0, 0};
    V3 e1 = unit(cross(t, T)), e2 = cross(T, e1);
    auto visible = [&](V3 x, V3 normal) { // g(w) max(0, -n.w) / |x|^2, above the horizon
        if (x.z <= 0.0) return 0.0;
        double d = std::sqrt(dot(x, x));
        V3 w = scale(x, 1.0 / d);
        double c = -dot(normal, w);
        return c > 0.0 ? g(w.x, w.y, w.z) * c / (d * d) : 0.0;
    };
    const int nphi = 1024 * density;
    double sum = 0.0;
    for (int j = 0; j < nphi; ++j) {
        double phi = 2.0 * M_PI * (j + 0.5) / nphi, dphi = 2.0 * M_PI / nphi;
        V3 radial = add(scale(e1, std::cos(phi)), scale(e2, std::sin(phi)));
        if (L > 0.0)
            sum += dphi * r * integrate(0.0, L, 64 * density, 8, [&](double l) {
                       return visible(add(add(A, scale(T, l)), scale(radial, r)), radial);
                   });
        // the hemispheres: u = cos of the angle from the outward axis, dA = r^2 du dphi
        for (int end = 0; end < 2; ++end) {
            V3 c = end ? B : A, out = end ? T : scale(T, -1.0);
            sum += dphi * r * r * integrate(0.0, 1.0, 32 * density, 8, [&](double u) {
                       V3 nrm = add(scale(out, u), scale(radial, std::sqrt(1.0 - u * u)));
                       return visible(add(c, scale(nrm, r)), nrm);
                   });
        }
    }
    return sum;
}
