// FLIP image difference (LDR-FLIP and HDR-FLIP), written from the papers:
//   Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020 (LDR-FLIP)
//   Andersson et al. 2021, "Visualizing Errors in Rendered High Dynamic Range Images",
//   Eurographics 2021 short paper (HDR-FLIP)
//
// Conventions of this library (all functions):
// - Images are interleaved RGB float triplets, row-major, w*h*3 values, *linear* sRGB
//   primaries (D65). Callers holding sRGB-encoded data (8-bit PNG) decode it first
//   (srgb_to_linear, rtpbr_common/srgb.hpp, included here); the CLI does.
// - LDR functions clamp their inputs to [0, 1]; HDR functions clamp negatives to 0.
//   Non-finite inputs (NaN, +-Inf) are rejected with FlipResult::non_finite_input.
// - The error map holds w*h values in [0, 1]; 0 means no perceived difference.
// - Borders are handled by clamp-to-edge, so a uniform image stays uniform under every filter.
// - No global state; nothing throws except std::bad_alloc from std::vector.
#pragma once

#include "rtpbr_common/srgb.hpp" // srgb_to_linear, linear_to_srgb

#include <cstddef>
#include <vector>

namespace rtpbr {

enum class FlipResult {
    ok = 0,
    null_input,        // an image pointer is null
    invalid_size,      // w or h not positive, or w*h*3 overflows
    invalid_ppd,       // ppd not finite or outside (0, kFlipMaxPpd]
    non_finite_input,  // an image holds NaN or Inf
};

const char* flip_result_string(FlipResult result);

// Default viewing condition of the FLIP papers: a 0.7 m wide monitor of 3840 pixels seen from
// 0.7 m, giving 0.7 * (3840 / 0.7) * pi / 180 = 67.02 pixels per degree, rounded to 67.
inline constexpr float kFlipDefaultPpd = 67.0f;
// Filters grow linearly with ppd; beyond this a caller surely passed the wrong unit.
inline constexpr float kFlipMaxPpd = 1000.0f;

// LDR-FLIP error map of two linear RGB images in [0, 1] (clamped), seen at ppd pixels per degree.
FlipResult flip_ldr(const float* ref_rgb, const float* test_rgb, int w, int h, float ppd,
                    std::vector<float>& error_map);

// Exposure compensations (in stops, image scaled by 2^c) HDR-FLIP evaluates: count values
// spread uniformly from start to stop inclusive.
struct FlipExposures {
    float start = 0.0f;
    float stop = 0.0f;
    int count = 0;
};

// HDR-FLIP's exposure range from the reference (HDR-FLIP paper, Sec. 3): c_start brings the
// largest luminance, c_stop the median luminance, to where the tone mapper outputs 0.85;
// count = max(2, ceil(c_stop - c_start)). Luminance is 0.2126 R + 0.7152 G + 0.0722 B.
// Cases the paper leaves undefined: an all-black reference gives start = stop = 0; when half or
// more of the pixels are black (median 0), the median is taken over the non-black pixels.
FlipResult flip_hdr_exposures(const float* ref_rgb, int w, int h, FlipExposures& exposures);

// HDR-FLIP: for each exposure c of flip_hdr_exposures, both images are scaled by 2^c, tone
// mapped (flip_tonemap_aces), clamped to [0, 1] and compared with LDR-FLIP; the error map is
// the per-pixel maximum over exposures. `used` (optional) receives the exposures.
FlipResult flip_hdr(const float* ref_rgb, const float* test_rgb, int w, int h, float ppd,
                    std::vector<float>& error_map, FlipExposures* used = nullptr);

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve", with his 0.6 pre-exposure folded into the
// coefficients as in the HDR-FLIP paper: (k0 x^2 + k1 x) / (k3 x^2 + k4 x + k5), unclamped.
float flip_tonemap_aces(float x);

// The two halves of LDR-FLIP, exposed so tests can check each against hand-derived values.
// flip_ldr(...) == pow(color, 1 - feature) element-wise.
// Colour pipeline: CSF filtering in YyCxCz, Hunt-adjusted L*a*b*, HyAB, ^qc, remapped with cmax.
FlipResult flip_color_difference(const float* ref_rgb, const float* test_rgb, int w, int h,
                                 float ppd, std::vector<float>& color_map);
// Feature pipeline: edge/point detector differences on the relative luminance Y/Yn, ^qf.
FlipResult flip_feature_difference(const float* ref_rgb, const float* test_rgb, int w, int h,
                                   float ppd, std::vector<float>& feature_map);

// Summary of an error map. Percentiles interpolate linearly between order statistics at rank
// q * (n - 1) (numpy's default); the median is the 50th percentile.
struct FlipStats {
    double mean = 0.0;
    double median = 0.0;
    double p95 = 0.0;
    double p99 = 0.0;
    double max = 0.0;
};
FlipStats flip_stats(const std::vector<float>& error_map);

} // namespace rtpbr
