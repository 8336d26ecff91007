// rtpbr tools: the energy bound of a rendered image (issue 28). A surface that does not emit
// reflects at most the brightest radiance that reaches it (albedo <= 1), so no pixel of a
// render may exceed the brightest emitter's radiance (lights, emissive surfaces, the
// background); a pixel that shows an emitter holds that emitter's radiance, which is no more.
// A mean image error cannot see a few pixels at 1e8 (they were 99.99 % of one image's energy):
// these figures can.
// A scene with punctual lights (KHR_lights_punctual) has no such bound: a delta light has no
// radiance, and the irradiance I / d^2 it gives grows without limit near it, so a surface may
// reflect any radiance. Its images get energy_stats_unbounded: the same figures without a bound
// (bounded false), never a bound taken from the other emitters alone.
#ifndef RTPBR_TOOLS_ENERGY_HPP
#define RTPBR_TOOLS_ENERGY_HPP

#include <cstddef>
#include <string>

namespace rtpbr_tools {

struct EnergyStats {
    bool bounded = true;            // false: no bound exists (punctual lights); the ratios are 0
    double brightest_emitter = 0.0; // the bound L_max the ratios are taken against
    double largest = 0.0;           // the largest channel value of any finite pixel
    double max_ratio = 0.0;         // the largest channel value of any pixel / L_max
    int max_x = -1, max_y = -1;     // where (column, row from the top); -1: empty image
    double mean_ratio = 0.0;        // the mean over the finite pixels of their largest channel /
                                    // L_max: a Monte Carlo image's bound in expectation
    double top_share = 0.0;         // share of the image's energy (sum of RGB) held by its
                                    // brightest 0.01 % of pixels (at least one pixel)
    size_t over = 0;                // pixels whose ratio exceeds 1.01
    size_t non_finite = 0;          // pixels with a NaN or infinite channel (never in a ratio)
};

// rgb: width x height pixels of `channels` floats (the first three are R, G, B; a grey image
// is read as R = G = B), rows top to bottom; brightest_emitter > 0 (else every ratio is 0).
EnergyStats energy_stats(const float *pixels, int width, int height, int channels, double brightest_emitter);

// The figures of an image whose scene has no energy bound (punctual lights): the largest pixel,
// the share of the brightest 0.01 %, non-finite pixels; bounded false, no ratios.
EnergyStats energy_stats_unbounded(const float *pixels, int width, int height, int channels);

// One line for people: "largest pixel / brightest emitter 0.93 at (12, 40); the brightest
// 0.01 % of pixels hold 0.4 % of the energy; 0 over 1.01, 0 not finite", or for an unbounded
// image "no energy bound (punctual lights: ...); largest pixel 12.5 at (12, 40); ...".
std::string energy_summary(const EnergyStats &s);

// The same as a JSON object (no trailing newline): "bounded", "brightest_emitter", "largest",
// "max_ratio", "max_x", "max_y", "mean_ratio", "top_share", "over", "non_finite".
std::string energy_json(const EnergyStats &s);

} // namespace rtpbr_tools

#endif
