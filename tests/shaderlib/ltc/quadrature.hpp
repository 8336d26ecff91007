// Gauss-Legendre quadrature for the LTC shape tests (test_ltc_shapes.cpp, test_area_light.cpp)
// and the oracle's disk lights (tests/oracle/test_disk_light.cpp): their noise-free references
// over disks, caps and ellipses.
#pragma once

#include <cmath>
#include <vector>

// Gauss-Legendre nodes and weights on [0, 1] (Newton on the Legendre polynomial).
inline void gauss_legendre(int n, std::vector<double> &x, std::vector<double> &w) {
    x.resize(n);
    w.resize(n);
    for (int i = 0; i < n; ++i) {
        double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = z;
            for (int k = 2; k <= n; ++k) {
                double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            double dz = p1 / dp;
            z -= dz;
            if (std::fabs(dz) < 1e-15) break;
        }
        x[i] = 0.5 * (1.0 - z);
        w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
    }
}
