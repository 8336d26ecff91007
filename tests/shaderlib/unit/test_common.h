/* Shared helpers of the shaderlib unit tests: a deterministic RNG, quadrature over the
 * hemisphere of normals, and the chi-square machinery. Everything here is independent of
 * the code under test (double precision, textbook formulas). */
#ifndef RTPBR_TEST_COMMON_H
#define RTPBR_TEST_COMMON_H

#include <math.h>
#include <stdint.h>
#include <stddef.h>
#include "rtpbr_shim.h"
#include "rtpbr_common/rng.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* PCG32 (common/), seeded as pcg-random.org's minimal example seeds stream `seed`. */
typedef rtpbr_tools_pcg32 test_rng;
static inline test_rng test_rng_make(uint64_t seed) { return rtpbr_tools_pcg32_make(0x853c49e6748fea9bULL + seed, seed); }
/* uniform in [0, 1) with 24 random bits, exactly representable as float */
static inline float test_rng_float(test_rng *r) { return rtpbr_tools_pcg32_float(r); }

static inline rtpbr_v3 v3(float x, float y, float z) { rtpbr_v3 v = {x, y, z}; return v; }
static inline rtpbr_v3 v3_spherical(double theta, double phi) {
    return v3((float)(sin(theta) * cos(phi)), (float)(sin(theta) * sin(phi)), (float)cos(theta));
}

/* 5-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun, table 25.4). */
static const double kGL5x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
static const double kGL5w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891};

/* Integrates f(theta, phi) sin(theta) dtheta dphi over the upper hemisphere.
 * theta is warped as theta = atan(scale tan(pi v / 2)), v in [0, 1], which puts the
 * quadrature points where a lobe of width ~scale around the normal lives; composite
 * Gauss-Legendre in v (panels_v panels) and the periodic trapezoid rule in phi. */
typedef double (*hemi_fn)(double theta, double phi, void *user);
static inline double test_integrate_hemisphere(hemi_fn f, void *user, double scale, int panels_v, int n_phi) {
    double sum = 0.0;
    double dv = 1.0 / panels_v;
    for (int p = 0; p < panels_v; p++) {
        for (int g = 0; g < 5; g++) {
            double v = (p + 0.5 + 0.5 * kGL5x[g]) * dv;
            double x = 0.5 * M_PI * v;
            double t = tan(x);
            double theta = atan(scale * t);
            /* dtheta/dv = scale (pi/2) sec^2(x) / (1 + scale^2 tan^2 x) */
            double c = cos(x);
            double dtheta = scale * 0.5 * M_PI / (c * c + scale * scale * sin(x) * sin(x));
            double w = 0.5 * kGL5w[g] * dv * dtheta * sin(theta);
            double inner = 0.0;
            for (int k = 0; k < n_phi; k++) {
                double phi = (k + 0.5) * (2.0 * M_PI / n_phi);
                inner += f(theta, phi, user);
            }
            sum += w * inner * (2.0 * M_PI / n_phi);
        }
    }
    return sum;
}

/* Regularised upper incomplete gamma Q(a, x) (series for x < a + 1, Lentz continued fraction
 * otherwise; Press et al., Numerical Recipes, sec. 6.2 formulas). */
static inline double test_gamma_q(double a, double x) {
    if (x <= 0.0) return 1.0;
    double gln = lgamma(a);
    if (x < a + 1.0) {
        double ap = a, sum = 1.0 / a, del = sum;
        for (int n = 0; n < 10000; n++) {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if (fabs(del) < fabs(sum) * 1e-15) break;
        }
        return 1.0 - sum * exp(-x + a * log(x) - gln);
    }
    double b = x + 1.0 - a, c = 1.0 / 1e-300, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; i++) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (fabs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (fabs(c) < 1e-300) c = 1e-300;
        d = 1.0 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1.0) < 1e-15) break;
    }
    return exp(-x + a * log(x) - gln) * h;
}

/* Pearson's chi-square test of observed counts against expected counts: cells with an
 * expected count below 5 are pooled (pbrt-v4 / Mitsuba 3 practice). Returns the p-value;
 * *dof receives the degrees of freedom. */
static inline double test_chi2_pvalue(const double *obs, const double *expct, int n, int *dof_out) {
    double chsq = 0.0, pool_o = 0.0, pool_e = 0.0;
    int dof = 0;
    for (int i = 0; i < n; i++) {
        if (expct[i] < 5.0) {
            pool_o += obs[i];
            pool_e += expct[i];
        } else {
            chsq += (obs[i] - expct[i]) * (obs[i] - expct[i]) / expct[i];
            dof++;
        }
    }
    if (pool_e > 0.0 || pool_o > 0.0) {
        if (pool_e < 5.0 && pool_o > 10.0) return 0.0; /* mass where the pdf says there is none */
        if (pool_e > 0.0) {
            chsq += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
            dof++;
        }
    }
    dof -= 1;
    if (dof_out) *dof_out = dof;
    if (dof < 1) return 1.0;
    return test_gamma_q(0.5 * dof, 0.5 * chsq);
}

#endif
