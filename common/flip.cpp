// LDR-FLIP and HDR-FLIP, implemented from the papers (see rtpbr_common/flip.hpp for the citations).
// Section numbers below refer to the LDR-FLIP paper (HPG 2020) unless they say HDR-FLIP.
#include "rtpbr_common/flip.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtpbr {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Lindbloom, "RGB/XYZ Matrices": linear sRGB (D65) to CIE XYZ and back.
constexpr float kRgbToXyz[3][3] = {
    {0.4124564f, 0.3575761f, 0.1804375f},
    {0.2126729f, 0.7151522f, 0.0721750f},
    {0.0193339f, 0.1191920f, 0.9503041f},
};
constexpr float kXyzToRgb[3][3] = {
    {3.2404542f, -1.5371385f, -0.4985314f},
    {-0.9692660f, 1.8760108f, 0.0415560f},
    {0.0556434f, -0.2040259f, 1.0572252f},
};
// Reference white: XYZ of linear RGB (1, 1, 1), so white maps to L* = 100, a* = b* = 0.
constexpr float kWhite[3] = {
    kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2],
    kRgbToXyz[1][0] + kRgbToXyz[1][1] + kRgbToXyz[1][2],
    kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2],
};

// Sec. 4.1, Table 1: spatial contrast sensitivity as sums of Gaussians per opponent channel,
// S(x) = a1 sqrt(pi/b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi/b2) exp(-pi^2 x^2 / b2), x in degrees.
struct CsfTerm {
    double a;
    double b;
};
struct Csf {
    CsfTerm terms[2];
};
constexpr Csf kCsfAchromatic = {{{1.0, 0.0047}, {0.0, 1e-5}}};
constexpr Csf kCsfRedGreen = {{{1.0, 0.0053}, {0.0, 1e-5}}};
constexpr Csf kCsfBlueYellow = {{{34.1, 0.04}, {13.5, 0.025}}};
constexpr double kCsfWidestB = 0.04;  // sets the common filter radius, 3 sigma of the widest term

// Sec. 4.1 and 4.3: colour error exponent and remapping knees.
constexpr float kQc = 0.7f;
constexpr float kPc = 0.4f;
constexpr float kPt = 0.95f;
// Sec. 4.2: feature detectors' width (degrees) and feature error exponent.
constexpr double kFeatureWidthDeg = 0.082;
constexpr float kQf = 0.5f;

// ACES fit of Narkowicz 2015 with the 0.6 pre-exposure folded in (HDR-FLIP, Sec. 3).
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
// HDR-FLIP, Sec. 3: tone-mapped value the extreme exposures aim the max/median luminance at.
constexpr double kExposureTarget = 0.85;

using Kernel = std::vector<float>;  // odd length 2r + 1, centre at index r

FlipResult check_image(const float* rgb, int w, int h) {
    if (!rgb) return FlipResult::null_input;
    if (w <= 0 || h <= 0) return FlipResult::invalid_size;
    if (static_cast<std::size_t>(w) > std::numeric_limits<std::size_t>::max() / 3 / static_cast<std::size_t>(h))
        return FlipResult::invalid_size;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3;
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(rgb[i])) return FlipResult::non_finite_input;
    return FlipResult::ok;
}

FlipResult check_pair(const float* ref, const float* test, int w, int h, float ppd) {
    if (!std::isfinite(ppd) || ppd <= 0.0f || ppd > kFlipMaxPpd) return FlipResult::invalid_ppd;
    FlipResult r = check_image(ref, w, h);
    if (r != FlipResult::ok) return r;
    return check_image(test, w, h);
}

std::size_t pixel_count(int w, int h) { return static_cast<std::size_t>(w) * static_cast<std::size_t>(h); }

float clamp01(float x) { return std::min(1.0f, std::max(0.0f, x)); }

void mul3(const float m[3][3], const float in[3], float out[3]) {
    for (int i = 0; i < 3; ++i) out[i] = m[i][0] * in[0] + m[i][1] * in[1] + m[i][2] * in[2];
}

// CIELAB of a linear RGB colour (CIE 15:2004), reference white kWhite.
void rgb_to_lab(const float rgb[3], float lab[3]) {
    float xyz[3];
    mul3(kRgbToXyz, rgb, xyz);
    constexpr float delta = 6.0f / 29.0f;
    float f[3];
    for (int i = 0; i < 3; ++i) {
        const float t = xyz[i] / kWhite[i];
        f[i] = t > delta * delta * delta ? std::cbrt(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
    }
    lab[0] = 116.0f * f[1] - 16.0f;
    lab[1] = 500.0f * (f[0] - f[1]);
    lab[2] = 200.0f * (f[1] - f[2]);
}

// Sec. 4.1: the Hunt effect (chroma appears weaker in the dark), a* and b* scaled by L*/100.
void hunt_adjust(float lab[3]) {
    lab[1] *= 0.01f * lab[0];
    lab[2] *= 0.01f * lab[0];
}

// Sec. 4.1: HyAB distance (Abasi et al. 2020): city-block in L*, Euclidean in a*b*.
float hyab(const float p[3], const float q[3]) {
    const float da = p[1] - q[1];
    const float db = p[2] - q[2];
    return std::fabs(p[0] - q[0]) + std::sqrt(da * da + db * db);
}

// Linear RGB <-> YyCxCz (Johnson & Fairchild's opponent space, linear version of L*a*b*).
void rgb_to_ycxcz(const float rgb[3], float out[3]) {
    float xyz[3];
    mul3(kRgbToXyz, rgb, xyz);
    const float x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
    out[0] = 116.0f * y - 16.0f;
    out[1] = 500.0f * (x - y);
    out[2] = 200.0f * (y - z);
}

void ycxcz_to_rgb(const float in[3], float rgb[3]) {
    const float y = (in[0] + 16.0f) / 116.0f;
    const float xyz[3] = {(in[1] / 500.0f + y) * kWhite[0], y * kWhite[1], (y - in[2] / 200.0f) * kWhite[2]};
    mul3(kXyzToRgb, xyz, rgb);
}

// Correlates each row with kernel k, clamp-to-edge.
void filter_rows(const std::vector<float>& in, std::vector<float>& out, int w, int h, const Kernel& k) {
    const int r = static_cast<int>(k.size() / 2);
    std::vector<float> padded(static_cast<std::size_t>(w + 2 * r));
    out.resize(in.size());
    for (int y = 0; y < h; ++y) {
        const float* row = in.data() + static_cast<std::size_t>(y) * w;
        for (int i = 0; i < w + 2 * r; ++i) padded[i] = row[std::min(w - 1, std::max(0, i - r))];
        float* dst = out.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            float s = 0.0f;
            for (int j = 0; j <= 2 * r; ++j) s += k[j] * padded[x + j];
            dst[x] = s;
        }
    }
}

// Correlates each column with kernel k, clamp-to-edge.
void filter_cols(const std::vector<float>& in, std::vector<float>& out, int w, int h, const Kernel& k) {
    const int r = static_cast<int>(k.size() / 2);
    out.assign(in.size(), 0.0f);
    for (int y = 0; y < h; ++y) {
        float* dst = out.data() + static_cast<std::size_t>(y) * w;
        for (int j = -r; j <= r; ++j) {
            const int sy = std::min(h - 1, std::max(0, y + j));
            const float* src = in.data() + static_cast<std::size_t>(sy) * w;
            const float kj = k[j + r];
            for (int x = 0; x < w; ++x) dst[x] += kj * src[x];
        }
    }
}

// Sec. 4.1: one opponent channel filtered by its CSF. Each Gaussian term is separable, so the
// 2D kernel is a weighted sum of separable Gaussians, normalised to unit sum as a whole.
void csf_filter(const std::vector<float>& in, std::vector<float>& out, int w, int h, const Csf& csf,
                double ppd) {
    const int r = std::max(1, static_cast<int>(std::ceil(3.0 * std::sqrt(kCsfWidestB / (2.0 * kPi * kPi)) * ppd)));
    Kernel kernels[2];
    double weights[2] = {0.0, 0.0};
    double total = 0.0;
    for (int t = 0; t < 2; ++t) {
        const CsfTerm& term = csf.terms[t];
        if (term.a == 0.0) continue;
        kernels[t].resize(static_cast<std::size_t>(2 * r + 1));
        double sum = 0.0;
        for (int i = -r; i <= r; ++i) {
            const double xdeg = i / ppd;
            const double e = std::exp(-kPi * kPi * xdeg * xdeg / term.b);
            kernels[t][i + r] = static_cast<float>(e);
            sum += e;
        }
        weights[t] = term.a * std::sqrt(kPi / term.b);
        total += weights[t] * sum * sum;  // 2D sum of this term = weight * (1D sum)^2
    }
    out.assign(in.size(), 0.0f);
    std::vector<float> tmp, filtered;
    for (int t = 0; t < 2; ++t) {
        if (kernels[t].empty()) continue;
        filter_rows(in, tmp, w, h, kernels[t]);
        filter_cols(tmp, filtered, w, h, kernels[t]);
        const float s = static_cast<float>(weights[t] / total);
        for (std::size_t i = 0; i < out.size(); ++i) out[i] += s * filtered[i];
    }
}

// Scales the positive weights to sum 1 and the negative ones to sum -1 (Sec. 4.2). A side
// with no weight (very small sigma) stays zero.
void normalize_signed(std::vector<double>& k) {
    double pos = 0.0, neg = 0.0;
    for (double v : k) (v > 0.0 ? pos : neg) += v;
    for (double& v : k) {
        if (v > 0.0 && pos > 0.0) v /= pos;
        if (v < 0.0 && neg < 0.0) v /= -neg;
    }
}

struct FeatureKernels {
    Kernel gauss;   // sums to 1
    Kernel first;   // d/dx of the Gaussian, positives sum to 1, negatives to -1
    Kernel second;  // d2/dx2 of the Gaussian, same normalisation
};

// Sec. 4.2: Gaussian derivative detectors with sigma = 0.5 * 0.082 degrees, radius 3 sigma.
FeatureKernels feature_kernels(double ppd) {
    const double sigma = 0.5 * kFeatureWidthDeg * ppd;
    const int r = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
    std::vector<double> g(2 * r + 1), d1(2 * r + 1), d2(2 * r + 1);
    double gsum = 0.0;
    for (int i = -r; i <= r; ++i) {
        const double gi = std::exp(-(i * i) / (2.0 * sigma * sigma));
        g[i + r] = gi;
        d1[i + r] = -i * gi;
        d2[i + r] = (i * i / (sigma * sigma) - 1.0) * gi;
        gsum += gi;
    }
    for (double& v : g) v /= gsum;
    normalize_signed(d1);
    normalize_signed(d2);
    FeatureKernels k;
    k.gauss.assign(g.begin(), g.end());
    k.first.assign(d1.begin(), d1.end());
    k.second.assign(d2.begin(), d2.end());
    return k;
}

// Magnitudes of the edge (gradient) and point (second derivatives along x and y) responses.
void feature_responses(const std::vector<float>& lum, int w, int h, const FeatureKernels& k,
                       std::vector<float>& edge, std::vector<float>& point) {
    std::vector<float> hg, hd, hdd, a, b;
    filter_rows(lum, hg, w, h, k.gauss);
    filter_rows(lum, hd, w, h, k.first);
    filter_rows(lum, hdd, w, h, k.second);
    filter_cols(hd, a, w, h, k.gauss);   // d/dx
    filter_cols(hg, b, w, h, k.first);   // d/dy
    edge.resize(lum.size());
    for (std::size_t i = 0; i < lum.size(); ++i) edge[i] = std::sqrt(a[i] * a[i] + b[i] * b[i]);
    filter_cols(hdd, a, w, h, k.gauss);  // d2/dx2
    filter_cols(hg, b, w, h, k.second);  // d2/dy2
    point.resize(lum.size());
    for (std::size_t i = 0; i < lum.size(); ++i) point[i] = std::sqrt(a[i] * a[i] + b[i] * b[i]);
}

void relative_luminance(const float* rgb, std::size_t n, std::vector<float>& lum) {
    lum.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float c[3] = {clamp01(rgb[3 * i]), clamp01(rgb[3 * i + 1]), clamp01(rgb[3 * i + 2])};
        lum[i] = (kRgbToXyz[1][0] * c[0] + kRgbToXyz[1][1] * c[1] + kRgbToXyz[1][2] * c[2]) / kWhite[1];
    }
}

// Sec. 4.1: CSF-filtered, re-clamped, Hunt-adjusted L*a*b* of one image (3 floats a pixel).
void perceived_lab(const float* rgb, int w, int h, double ppd, std::vector<float>& lab) {
    const std::size_t n = pixel_count(w, h);
    std::vector<float> chan[3];
    for (auto& c : chan) c.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float c[3] = {clamp01(rgb[3 * i]), clamp01(rgb[3 * i + 1]), clamp01(rgb[3 * i + 2])};
        float o[3];
        rgb_to_ycxcz(c, o);
        chan[0][i] = o[0];
        chan[1][i] = o[1];
        chan[2][i] = o[2];
    }
    const Csf* csf[3] = {&kCsfAchromatic, &kCsfRedGreen, &kCsfBlueYellow};
    std::vector<float> filtered[3];
    for (int c = 0; c < 3; ++c) csf_filter(chan[c], filtered[c], w, h, *csf[c], ppd);
    lab.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const float o[3] = {filtered[0][i], filtered[1][i], filtered[2][i]};
        float c[3];
        ycxcz_to_rgb(o, c);
        for (float& v : c) v = clamp01(v);
        rgb_to_lab(c, &lab[3 * i]);
        hunt_adjust(&lab[3 * i]);
    }
}

// Sec. 4.1: the largest colour difference, between pure green and pure blue.
float cmax() {
    const float green[3] = {0.0f, 1.0f, 0.0f}, blue[3] = {0.0f, 0.0f, 1.0f};
    float g[3], b[3];
    rgb_to_lab(green, g);
    rgb_to_lab(blue, b);
    hunt_adjust(g);
    hunt_adjust(b);
    return std::pow(hyab(g, b), kQc);
}

// Sec. 4.1: compresses large colour differences into [pt, 1], stretches small ones to [0, pt).
float remap_color(float d, float c_max) {
    const float knee = kPc * c_max;
    const float e = d < knee ? d * (kPt / knee) : kPt + (d - knee) / (c_max - knee) * (1.0f - kPt);
    return std::min(1.0f, e);
}

double percentile_sorted(const std::vector<float>& s, double q) {
    const double rank = q * static_cast<double>(s.size() - 1);
    const std::size_t lo = static_cast<std::size_t>(std::floor(rank));
    const std::size_t hi = std::min(s.size() - 1, lo + 1);
    const double t = rank - static_cast<double>(lo);
    return static_cast<double>(s[lo]) * (1.0 - t) + static_cast<double>(s[hi]) * t;
}

// Positive root of y(x) = t for a tone mapper (k0 x^2 + k1 x + k2) / (k3 x^2 + k4 x + k5):
// (t k3 - k0) x^2 + (t k4 - k1) x + (t k5 - k2) = 0 (HDR-FLIP, Sec. 3).
double tonemap_inverse(double t) {
    const double a = t * kAces[3] - kAces[0];
    const double b = t * kAces[4] - kAces[1];
    const double c = t * kAces[5] - kAces[2];
    if (a == 0.0) return -c / b;
    const double disc = std::sqrt(b * b - 4.0 * a * c);
    return std::max((-b + disc) / (2.0 * a), (-b - disc) / (2.0 * a));
}

double tonemap(double v) {
    if (v > 1e100) return kAces[0] / kAces[3];  // the limit, before v * v overflows
    return (kAces[0] * v * v + kAces[1] * v + kAces[2]) / (kAces[3] * v * v + kAces[4] * v + kAces[5]);
}

float luminance(const float* rgb) {
    return 0.2126f * std::max(0.0f, rgb[0]) + 0.7152f * std::max(0.0f, rgb[1]) + 0.0722f * std::max(0.0f, rgb[2]);
}

float median_of(std::vector<float>& v) {
    const std::size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
    const float upper = v[mid];
    if (v.size() % 2 == 1) return upper;
    const float lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid));
    return 0.5f * (lower + upper);
}

} // namespace

const char* flip_result_string(FlipResult result) {
    switch (result) {
    case FlipResult::ok: return "ok";
    case FlipResult::null_input: return "image pointer is null";
    case FlipResult::invalid_size: return "image size must be positive (and w*h*3 must fit in memory)";
    case FlipResult::invalid_ppd: return "pixels per degree must be finite and in (0, 1000]";
    case FlipResult::non_finite_input: return "image holds NaN or infinite values";
    }
    return "unknown FLIP result";
}

float flip_tonemap_aces(float x) { return static_cast<float>(tonemap(x)); }

FlipResult flip_color_difference(const float* ref_rgb, const float* test_rgb, int w, int h, float ppd,
                                 std::vector<float>& color_map) {
    const FlipResult r = check_pair(ref_rgb, test_rgb, w, h, ppd);
    if (r != FlipResult::ok) return r;
    const std::size_t n = pixel_count(w, h);
    std::vector<float> lab_ref, lab_test;
    perceived_lab(ref_rgb, w, h, ppd, lab_ref);
    perceived_lab(test_rgb, w, h, ppd, lab_test);
    const float c_max = cmax();
    color_map.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        color_map[i] = remap_color(std::pow(hyab(&lab_ref[3 * i], &lab_test[3 * i]), kQc), c_max);
    return FlipResult::ok;
}

FlipResult flip_feature_difference(const float* ref_rgb, const float* test_rgb, int w, int h, float ppd,
                                   std::vector<float>& feature_map) {
    const FlipResult r = check_pair(ref_rgb, test_rgb, w, h, ppd);
    if (r != FlipResult::ok) return r;
    const std::size_t n = pixel_count(w, h);
    const FeatureKernels k = feature_kernels(ppd);
    std::vector<float> lum, edge_ref, point_ref, edge_test, point_test;
    relative_luminance(ref_rgb, n, lum);
    feature_responses(lum, w, h, k, edge_ref, point_ref);
    relative_luminance(test_rgb, n, lum);
    feature_responses(lum, w, h, k, edge_test, point_test);
    feature_map.resize(n);
    const float inv_sqrt2 = static_cast<float>(1.0 / std::sqrt(2.0));
    for (std::size_t i = 0; i < n; ++i) {
        const float d = std::max(std::fabs(edge_ref[i] - edge_test[i]), std::fabs(point_ref[i] - point_test[i]));
        feature_map[i] = std::pow(std::min(1.0f, inv_sqrt2 * d), kQf);
    }
    return FlipResult::ok;
}

FlipResult flip_ldr(const float* ref_rgb, const float* test_rgb, int w, int h, float ppd,
                    std::vector<float>& error_map) {
    std::vector<float> feature;
    FlipResult r = flip_color_difference(ref_rgb, test_rgb, w, h, ppd, error_map);
    if (r != FlipResult::ok) return r;
    r = flip_feature_difference(ref_rgb, test_rgb, w, h, ppd, feature);
    if (r != FlipResult::ok) return r;
    // Sec. 4.3: feature differences amplify the colour error.
    for (std::size_t i = 0; i < error_map.size(); ++i) error_map[i] = std::pow(error_map[i], 1.0f - feature[i]);
    return FlipResult::ok;
}

FlipResult flip_hdr_exposures(const float* ref_rgb, int w, int h, FlipExposures& exposures) {
    const FlipResult r = check_image(ref_rgb, w, h);
    if (r != FlipResult::ok) return r;
    const std::size_t n = pixel_count(w, h);
    std::vector<float> lum(n);
    for (std::size_t i = 0; i < n; ++i) lum[i] = luminance(&ref_rgb[3 * i]);
    const float y_max = *std::max_element(lum.begin(), lum.end());
    if (!(y_max > 0.0f)) {
        exposures = {0.0f, 0.0f, 2};
        return FlipResult::ok;
    }
    float y_median = median_of(lum);
    if (!(y_median > 0.0f)) {
        lum.erase(std::remove_if(lum.begin(), lum.end(), [](float v) { return !(v > 0.0f); }), lum.end());
        y_median = median_of(lum);
    }
    const double x_target = tonemap_inverse(kExposureTarget);
    exposures.start = static_cast<float>(std::log2(x_target / y_max));
    exposures.stop = static_cast<float>(std::log2(x_target / y_median));
    exposures.count = std::max(2, static_cast<int>(std::ceil(exposures.stop - exposures.start)));
    return FlipResult::ok;
}

FlipResult flip_hdr(const float* ref_rgb, const float* test_rgb, int w, int h, float ppd,
                    std::vector<float>& error_map, FlipExposures* used) {
    FlipResult r = check_pair(ref_rgb, test_rgb, w, h, ppd);
    if (r != FlipResult::ok) return r;
    FlipExposures ex;
    r = flip_hdr_exposures(ref_rgb, w, h, ex);
    if (r != FlipResult::ok) return r;
    const std::size_t n3 = pixel_count(w, h) * 3;
    std::vector<float> ref_ldr(n3), test_ldr(n3), map;
    error_map.assign(pixel_count(w, h), 0.0f);
    for (int e = 0; e < ex.count; ++e) {
        const double c = ex.start + (ex.stop - ex.start) * e / (ex.count - 1);
        const double scale = std::exp2(c);
        for (std::size_t i = 0; i < n3; ++i) {
            ref_ldr[i] = clamp01(static_cast<float>(tonemap(scale * std::max(0.0f, ref_rgb[i]))));
            test_ldr[i] = clamp01(static_cast<float>(tonemap(scale * std::max(0.0f, test_rgb[i]))));
        }
        r = flip_ldr(ref_ldr.data(), test_ldr.data(), w, h, ppd, map);
        if (r != FlipResult::ok) return r;
        for (std::size_t i = 0; i < map.size(); ++i) error_map[i] = std::max(error_map[i], map[i]);
    }
    if (used) *used = ex;
    return FlipResult::ok;
}

FlipStats flip_stats(const std::vector<float>& error_map) {
    FlipStats s;
    if (error_map.empty()) return s;
    std::vector<float> sorted(error_map);
    std::sort(sorted.begin(), sorted.end());
    double sum = 0.0;
    for (float v : sorted) sum += v;
    s.mean = sum / static_cast<double>(sorted.size());
    s.median = percentile_sorted(sorted, 0.50);
    s.p95 = percentile_sorted(sorted, 0.95);
    s.p99 = percentile_sorted(sorted, 0.99);
    s.max = sorted.back();
    return s;
}

} // namespace rtpbr
