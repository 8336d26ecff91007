// Statistics of a set of relative errors: the fitter's per-cell errors (ltc_fit.hpp) and the
// LTC-against-Monte-Carlo errors (ltc_mc.hpp).
#pragma once

#include <algorithm>
#include <vector>

namespace ltcfit {

// Mean, median, 95th percentile and largest (all 0 for no errors).
struct ErrorStats {
    double mean, median, p95, max;
};

inline ErrorStats error_stats(std::vector<double> e) {
    if (e.empty())
        return {0.0, 0.0, 0.0, 0.0};
    std::sort(e.begin(), e.end());
    double sum = 0;
    for (double x : e)
        sum += x;
    auto q = [&](double f) { return e[std::min(e.size() - 1, size_t(f * double(e.size() - 1) + 0.5))]; };
    return {sum / double(e.size()), q(0.5), q(0.95), e.back()};
}

} // namespace ltcfit
