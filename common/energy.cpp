// The energy bound of a rendered image: rtpbr_common/energy.hpp.
#include "rtpbr_common/energy.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

namespace rtpbr_tools {

EnergyStats energy_stats(const float *pixels, int width, int height, int channels, double brightest_emitter)
{
    EnergyStats s;
    s.brightest_emitter = brightest_emitter;
    if (!pixels || width <= 0 || height <= 0 || channels <= 0)
        return s;
    const size_t n = size_t(width) * size_t(height);
    std::vector<double> energy;
    energy.reserve(n);
    double total = 0.0, largest = -1.0, sum_max = 0.0;
    for (size_t p = 0; p < n; ++p) {
        const float *px = pixels + p * size_t(channels);
        double rgb[3];
        for (int c = 0; c < 3; ++c)
            rgb[c] = px[channels >= 3 ? c : 0];
        if (!std::isfinite(rgb[0]) || !std::isfinite(rgb[1]) || !std::isfinite(rgb[2])) {
            s.non_finite++;
            continue;
        }
        double m = std::max(rgb[0], std::max(rgb[1], rgb[2]));
        sum_max += m;
        if (m > largest) {
            largest = m;
            s.largest = m;
            s.max_x = int(p % size_t(width));
            s.max_y = int(p / size_t(width));
        }
        if (brightest_emitter > 0.0 && m > 1.01 * brightest_emitter)
            s.over++;
        double e = std::max(rgb[0], 0.0) + std::max(rgb[1], 0.0) + std::max(rgb[2], 0.0);
        energy.push_back(e);
        total += e;
    }
    if (brightest_emitter > 0.0 && largest > 0.0)
        s.max_ratio = largest / brightest_emitter;
    if (brightest_emitter > 0.0 && !energy.empty())
        s.mean_ratio = sum_max / double(energy.size()) / brightest_emitter;
    if (!energy.empty() && total > 0.0) {
        size_t k = std::max<size_t>(1, size_t(std::ceil(double(n) * 1e-4)));
        k = std::min(k, energy.size());
        std::nth_element(energy.begin(), energy.begin() + std::ptrdiff_t(k - 1), energy.end(), std::greater<double>());
        double top = 0.0;
        for (size_t i = 0; i < k; ++i)
            top += energy[i];
        s.top_share = top / total;
    }
    return s;
}

EnergyStats energy_stats_unbounded(const float *pixels, int width, int height, int channels)
{
    EnergyStats s = energy_stats(pixels, width, height, channels, 0.0); // 0: no ratios
    s.bounded = false;
    return s;
}

std::string energy_summary(const EnergyStats &s)
{
    char line[400];
    if (!s.bounded) {
        std::snprintf(line, sizeof line,
                      "no energy bound (punctual lights: a delta light's irradiance I / d^2 has no upper limit); "
                      "largest pixel %.6g at (%d, %d); the brightest 0.01 %% of pixels hold %.3g %% of the energy; "
                      "%zu not finite",
                      s.largest, s.max_x, s.max_y, 100.0 * s.top_share, s.non_finite);
        return line;
    }
    std::snprintf(line, sizeof line,
                  "largest pixel / brightest emitter (%.6g) %.4g at (%d, %d); the brightest 0.01 %% of pixels hold "
                  "%.3g %% of the energy; %zu over 1.01, %zu not finite",
                  s.brightest_emitter, s.max_ratio, s.max_x, s.max_y, 100.0 * s.top_share, s.over, s.non_finite);
    return line;
}

std::string energy_json(const EnergyStats &s)
{
    char line[400];
    std::snprintf(line, sizeof line,
                  "{\"bounded\": %s, \"brightest_emitter\": %.9g, \"largest\": %.9g, \"max_ratio\": %.9g, "
                  "\"max_x\": %d, \"max_y\": %d, \"mean_ratio\": %.9g, \"top_share\": %.9g, \"over\": %zu, "
                  "\"non_finite\": %zu}",
                  s.bounded ? "true" : "false", s.brightest_emitter, s.largest, s.max_ratio, s.max_x, s.max_y,
                  s.mean_ratio, s.top_share, s.over, s.non_finite);
    return line;
}

} // namespace rtpbr_tools
