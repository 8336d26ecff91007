// Small statistics helpers shared by the oracle tests.
#ifndef RTPBR_TESTS_ORACLE_TEST_COMMON_H
#define RTPBR_TESTS_ORACLE_TEST_COMMON_H

// C++ headers first: cmocka defines a fail() macro that clashes with std::basic_ios::fail.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
extern "C" {
#include "test_main.h"
}

#include <cmath>
#include <cstdio>

// Running mean and standard error of the mean.
struct MeanEstimator {
    double n = 0.0, sum = 0.0, sumSq = 0.0;
    void add(double x) {
        n += 1.0;
        sum += x;
        sumSq += x * x;
    }
    double mean() const { return n > 0.0 ? sum / n : 0.0; }
    double variance() const { return n > 1.0 ? std::fmax(0.0, (sumSq - sum * sum / n) / (n - 1.0)) : 0.0; }
    double stderror() const { return n > 0.0 ? std::sqrt(variance() / n) : 0.0; }
};

// |a - b| <= k standard errors (combined) + an absolute floor.
#define EXPECT_AGREE(a, sa, b, sb, k, floor_)                                                              \
    do {                                                                                                   \
        double _d = std::fabs(double(a) - double(b));                                                      \
        double _s = std::sqrt(double(sa) * double(sa) + double(sb) * double(sb));                          \
        if (!(_d <= double(k) * _s + double(floor_))) {                                                    \
            fail_msg("%s = %.6g (se %.3g) vs %s = %.6g (se %.3g): difference %.3g > %g se + %g", #a,       \
                     double(a), double(sa), #b, double(b), double(sb), _d, double(k), double(floor_));     \
        }                                                                                                  \
    } while (0)

#endif
