// Unit tests of the FLIP library (common/rtpbr_common/flip.hpp), with cmocka.
// References are computed here independently: colours through the IEC 61966-2-1 matrix rounded to
// 4 digits, CIELAB, the Hunt adjustment, HyAB and the remap written out again from the paper;
// feature detector responses derived by hand for a step edge and an impulse; the tone mapper's
// inverse found by bisection rather than the quadratic formula.
#include "rtpbr_common/flip.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

// cmocka needs these before its header.
#include <csetjmp>
#include <cstdarg>
#include <cstddef>
extern "C" {
#include "test_main.h"
}

using namespace rtpbr;

namespace {

#define EXPECT_NEAR(actual, expected, tol)                                                           \
    do {                                                                                             \
        const double a_ = (actual), e_ = (expected), t_ = (tol);                                     \
        if (!(std::fabs(a_ - e_) <= t_)) {                                                           \
            print_error("%s = %.9g, expected %.9g (tolerance %.3g)\n", #actual, a_, e_, t_);         \
            fail();                                                                                  \
        }                                                                                            \
    } while (0)

struct Rgb {
    float r, g, b;
};

std::vector<float> uniform(int w, int h, Rgb c) {
    std::vector<float> img(static_cast<std::size_t>(w) * h * 3);
    for (std::size_t i = 0; i < img.size(); i += 3) {
        img[i] = c.r;
        img[i + 1] = c.g;
        img[i + 2] = c.b;
    }
    return img;
}

void set_pixel(std::vector<float>& img, int w, int x, int y, Rgb c) {
    float* p = &img[(static_cast<std::size_t>(y) * w + x) * 3];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
}

double mean_of(const std::vector<float>& v) {
    double s = 0.0;
    for (float x : v) s += x;
    return s / static_cast<double>(v.size());
}

double max_of(const std::vector<float>& v) {
    double m = -1.0;
    for (float x : v) m = std::max(m, static_cast<double>(x));
    return m;
}

// Deterministic noise in [-1, 1] (64-bit LCG, Knuth's MMIX constants).
std::vector<float> noise_pattern(std::size_t n, std::uint64_t seed) {
    std::vector<float> v(n);
    for (auto& x : v) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        x = static_cast<float>(static_cast<double>(seed >> 11) / 9007199254740992.0 * 2.0 - 1.0);
    }
    return v;
}

// ---- Independent colour reference: Hunt-adjusted CIELAB, HyAB, qc, remap (LDR-FLIP Sec. 4.1) --

struct Lab {
    double L, a, b;
};

Lab hunt_lab(Rgb c) {
    // IEC 61966-2-1 matrix (4 digits), white = its row sums.
    const double m[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
    const double rgb[3] = {c.r, c.g, c.b};
    double f[3];
    for (int i = 0; i < 3; ++i) {
        const double xyz = m[i][0] * rgb[0] + m[i][1] * rgb[1] + m[i][2] * rgb[2];
        const double t = xyz / (m[i][0] + m[i][1] + m[i][2]);
        f[i] = t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0;
    }
    const double L = 116.0 * f[1] - 16.0;
    return {L, L / 100.0 * 500.0 * (f[0] - f[1]), L / 100.0 * 200.0 * (f[1] - f[2])};
}

double hyab(Lab p, Lab q) { return std::fabs(p.L - q.L) + std::hypot(p.a - q.a, p.b - q.b); }

double hand_color_error(Rgb ref, Rgb test) {
    const double cmax = std::pow(hyab(hunt_lab({0, 1, 0}), hunt_lab({0, 0, 1})), 0.7);
    const double d = std::pow(hyab(hunt_lab(ref), hunt_lab(test)), 0.7);
    const double pc = 0.4, pt = 0.95;
    return d < pc * cmax ? pt / (pc * cmax) * d : pt + (d - pc * cmax) / (cmax - pc * cmax) * (1.0 - pt);
}

// ---- Tests -------------------------------------------------------------------------------------

void test_identical_is_zero(void**) {
    const int w = 40, h = 30;
    const std::vector<float> n = noise_pattern(static_cast<std::size_t>(w) * h * 3, 7);
    std::vector<float> img(n.size()), hdr(n.size());
    for (std::size_t i = 0; i < n.size(); ++i) {
        img[i] = 0.5f + 0.5f * n[i];
        hdr[i] = std::exp2(6.0f * n[i]);  // 1/64 .. 64
    }
    std::vector<float> map;
    assert_int_equal(flip_ldr(img.data(), img.data(), w, h, kFlipDefaultPpd, map), FlipResult::ok);
    assert_int_equal(map.size(), static_cast<std::size_t>(w * h));
    assert_true(mean_of(map) == 0.0);
    assert_true(max_of(map) == 0.0);
    FlipExposures ex;
    assert_int_equal(flip_hdr(hdr.data(), hdr.data(), w, h, kFlipDefaultPpd, map, &ex), FlipResult::ok);
    assert_true(ex.count >= 2);
    assert_true(mean_of(map) == 0.0);
    assert_true(max_of(map) == 0.0);
}

// Uniform images: every spatial filter is the identity (normalised kernels, clamp-to-edge), and
// no feature responds, so FLIP is the remapped HyAB distance of the Hunt-adjusted colours.
void test_uniform_colour_pipeline_by_hand(void**) {
    const struct {
        Rgb ref, test;
    } cases[] = {
        {{0, 0, 0}, {1, 1, 1}},            // black/white
        {{0, 1, 0}, {0, 0, 1}},            // green/blue: cmax itself, FLIP = 1 by definition
        {{0.2f, 0.2f, 0.2f}, {0.25f, 0.25f, 0.25f}},
        {{0.5f, 0.5f, 0.5f}, {0.5f, 0.45f, 0.55f}},
        {{1, 0, 0}, {0, 1, 0}},
        {{0.01f, 0.01f, 0.01f}, {0.02f, 0.02f, 0.02f}},  // below the knee pc * cmax
        {{0.8f, 0.3f, 0.1f}, {0.7f, 0.35f, 0.1f}},
    };
    const int w = 24, h = 20;
    for (const auto& c : cases) {
        const std::vector<float> ref = uniform(w, h, c.ref), test = uniform(w, h, c.test);
        std::vector<float> flip, feature;
        assert_int_equal(flip_ldr(ref.data(), test.data(), w, h, kFlipDefaultPpd, flip), FlipResult::ok);
        assert_int_equal(flip_feature_difference(ref.data(), test.data(), w, h, kFlipDefaultPpd, feature),
                         FlipResult::ok);
        const double expected = hand_color_error(c.ref, c.test);
        EXPECT_NEAR(mean_of(flip), expected, 2e-3);
        EXPECT_NEAR(max_of(flip), expected, 2e-3);
        EXPECT_NEAR(max_of(feature), 0.0, 1e-3);
    }
    // The two anchors of the normalisation, checked explicitly.
    EXPECT_NEAR(hand_color_error({0, 1, 0}, {0, 0, 1}), 1.0, 1e-12);
    EXPECT_NEAR(hand_color_error({0, 0, 0}, {1, 1, 1}), 0.9674, 1e-3);
}

// 1D Gaussian and second-derivative weights at the centre, normalised as in LDR-FLIP Sec. 4.2
// (Gaussian sums to 1; second derivative's negative lobe sums to -1).
void hand_feature_centre(double ppd, double& g0, double& dd0) {
    const double sigma = 0.5 * 0.082 * ppd;
    const int r = static_cast<int>(std::ceil(3.0 * sigma));
    double gsum = 0.0, neg = 0.0;
    for (int k = -r; k <= r; ++k) {
        const double gk = std::exp(-k * k / (2.0 * sigma * sigma));
        gsum += gk;
        if (k * k < sigma * sigma) neg += (1.0 - k * k / (sigma * sigma)) * gk;  // |raw weight| on the negative lobe
    }
    g0 = 1.0 / gsum;
    dd0 = -1.0 / neg;  // raw centre weight is -1 * exp(0)
}

// A vertical black/white step against black. Next to the step the edge detector sees one whole
// lobe of the first-derivative kernel (sum 1), the point detector |dd(0)|/2 < 1, so
// feature = (max(1, |dd0|/2) / sqrt(2))^0.5 = 2^(-1/4), whatever the ppd.
void test_feature_step_edge_by_hand(void**) {
    const int w = 64, h = 12, x0 = 32;
    std::vector<float> ref = uniform(w, h, {0, 0, 0});
    const std::vector<float> black = uniform(w, h, {0, 0, 0});
    for (int y = 0; y < h; ++y)
        for (int x = x0; x < w; ++x) set_pixel(ref, w, x, y, {1, 1, 1});
    for (float ppd : {20.0f, 67.0f, 120.0f}) {
        std::vector<float> feature;
        assert_int_equal(flip_feature_difference(ref.data(), black.data(), w, h, ppd, feature), FlipResult::ok);
        const int r = static_cast<int>(std::ceil(3.0 * 0.5 * 0.082 * ppd));
        for (int y = 0; y < h; ++y) {
            EXPECT_NEAR(feature[static_cast<std::size_t>(y) * w + x0], std::pow(2.0, -0.25), 1e-5);
            EXPECT_NEAR(feature[static_cast<std::size_t>(y) * w + x0 - 1], std::pow(2.0, -0.25), 1e-5);
            EXPECT_NEAR(feature[static_cast<std::size_t>(y) * w + x0 - r - 1], 0.0, 1e-6);  // out of reach
        }
    }
}

// A single white pixel against black. At its centre the edge response is 0 (odd kernel) and the
// point response is (dd0 g0, dd0 g0), so feature = (sqrt(2) |dd0| g0 / sqrt(2))^0.5.
void test_feature_point_by_hand(void**) {
    const int w = 41, h = 41, c = 20;
    std::vector<float> ref = uniform(w, h, {0, 0, 0});
    const std::vector<float> black = uniform(w, h, {0, 0, 0});
    set_pixel(ref, w, c, c, {1, 1, 1});
    for (float ppd : {30.0f, 67.0f}) {
        double g0, dd0;
        hand_feature_centre(ppd, g0, dd0);
        std::vector<float> feature;
        assert_int_equal(flip_feature_difference(ref.data(), black.data(), w, h, ppd, feature), FlipResult::ok);
        EXPECT_NEAR(feature[static_cast<std::size_t>(c) * w + c], std::sqrt(std::fabs(dd0) * g0), 1e-5);
        // Swapping the images changes nothing: the detector compares magnitudes.
        std::vector<float> swapped;
        assert_int_equal(flip_feature_difference(black.data(), ref.data(), w, h, ppd, swapped), FlipResult::ok);
        EXPECT_NEAR(swapped[static_cast<std::size_t>(c) * w + c], feature[static_cast<std::size_t>(c) * w + c], 0.0);
    }
}

// LDR-FLIP Sec. 4.3: final error = colour^(1 - feature), with the edge making it larger than the
// colour error alone.
void test_features_amplify_colour_error(void**) {
    const int w = 48, h = 16;
    std::vector<float> ref = uniform(w, h, {0.1f, 0.1f, 0.1f});
    const std::vector<float> test = uniform(w, h, {0.1f, 0.1f, 0.1f});
    for (int y = 0; y < h; ++y)
        for (int x = 24; x < w; ++x) set_pixel(ref, w, x, y, {0.6f, 0.6f, 0.6f});
    std::vector<float> flip, colour, feature;
    assert_int_equal(flip_ldr(ref.data(), test.data(), w, h, 67.0f, flip), FlipResult::ok);
    assert_int_equal(flip_color_difference(ref.data(), test.data(), w, h, 67.0f, colour), FlipResult::ok);
    assert_int_equal(flip_feature_difference(ref.data(), test.data(), w, h, 67.0f, feature), FlipResult::ok);
    for (std::size_t i = 0; i < flip.size(); ++i) {
        EXPECT_NEAR(flip[i], std::pow(colour[i], 1.0 - feature[i]), 1e-6);
        assert_true(flip[i] >= colour[i] - 1e-7f);
    }
    assert_true(flip[8 * w + 24] > colour[8 * w + 24] + 0.05f);
}

void test_monotonic_in_offset(void**) {
    const int w = 32, h = 32;
    const std::vector<float> ref = uniform(w, h, {0.2f, 0.2f, 0.2f});
    double previous = 0.0;
    for (float offset : {0.005f, 0.01f, 0.02f, 0.05f, 0.1f, 0.2f, 0.4f, 0.8f}) {
        const std::vector<float> test = uniform(w, h, {0.2f + offset, 0.2f + offset, 0.2f + offset});
        std::vector<float> map;
        assert_int_equal(flip_ldr(ref.data(), test.data(), w, h, kFlipDefaultPpd, map), FlipResult::ok);
        const double m = mean_of(map);
        assert_true(m > previous);
        previous = m;
    }
}

void test_monotonic_in_noise_amplitude(void**) {
    const int w = 48, h = 48;
    const std::vector<float> n = noise_pattern(static_cast<std::size_t>(w) * h * 3, 42);
    const std::vector<float> ref = uniform(w, h, {0.4f, 0.4f, 0.4f});
    double previous_ldr = 0.0, previous_hdr = 0.0;
    for (float amplitude : {0.01f, 0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
        std::vector<float> test(ref.size());
        for (std::size_t i = 0; i < test.size(); ++i) test[i] = std::max(0.0f, ref[i] + amplitude * n[i]);
        std::vector<float> map;
        assert_int_equal(flip_ldr(ref.data(), test.data(), w, h, kFlipDefaultPpd, map), FlipResult::ok);
        const double m = mean_of(map);
        assert_true(m > previous_ldr);
        previous_ldr = m;
        assert_int_equal(flip_hdr(ref.data(), test.data(), w, h, kFlipDefaultPpd, map), FlipResult::ok);
        const double mh = mean_of(map);
        assert_true(mh > previous_hdr);
        previous_hdr = mh;
    }
}

// A uniform difference is the same everywhere, so the mean cannot depend on the image size.
void test_uniform_difference_size_independent(void**) {
    double means[2];
    int i = 0;
    for (int size : {32, 128}) {
        const std::vector<float> ref = uniform(size, size, {0.3f, 0.4f, 0.2f});
        const std::vector<float> test = uniform(size, size, {0.35f, 0.38f, 0.25f});
        std::vector<float> map;
        assert_int_equal(flip_ldr(ref.data(), test.data(), size, size, kFlipDefaultPpd, map), FlipResult::ok);
        means[i++] = mean_of(map);
    }
    EXPECT_NEAR(means[1], means[0], 1e-6);
}

std::vector<float> disc_image(int size, double radius, Rgb inside, Rgb outside) {
    std::vector<float> img = uniform(size, size, outside);
    const double c = 0.5 * size;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            if (std::hypot(x + 0.5 - c, y + 0.5 - c) < radius) set_pixel(img, size, x, y, inside);
    return img;
}

// A centred feature: (a) padding the image with identical background adds only zero error, so
// the summed error is unchanged; (b) doubling image, feature and ppd together keeps the angular
// sizes, so the mean error stays the same up to discretisation (the paper's model is angular).
void test_centred_feature_scaling(void**) {
    const Rgb bg = {0.2f, 0.2f, 0.2f}, fg = {0.6f, 0.3f, 0.3f}, fg_test = {0.45f, 0.35f, 0.3f};
    double sums[2];
    int i = 0;
    for (int size : {64, 128}) {
        const std::vector<float> ref = disc_image(size, 8.0, fg, bg), test = disc_image(size, 8.0, fg_test, bg);
        std::vector<float> map;
        assert_int_equal(flip_ldr(ref.data(), test.data(), size, size, kFlipDefaultPpd, map), FlipResult::ok);
        sums[i++] = mean_of(map) * size * size;
    }
    EXPECT_NEAR(sums[1] / sums[0], 1.0, 1e-4);

    double means[2];
    i = 0;
    for (int scale : {1, 2}) {
        const int size = 48 * scale;
        const std::vector<float> ref = disc_image(size, 8.0 * scale, fg, bg);
        const std::vector<float> test = disc_image(size, 8.0 * scale, fg_test, bg);
        std::vector<float> map;
        assert_int_equal(flip_ldr(ref.data(), test.data(), size, size, 30.0f * scale, map), FlipResult::ok);
        means[i++] = mean_of(map);
    }
    print_message("scaled disc: mean %.6f at 48px/30ppd, %.6f at 96px/60ppd\n", means[0], means[1]);
    EXPECT_NEAR(means[1] / means[0], 1.0, 0.05);
}

// ACES inverse by bisection (the library solves the quadratic).
double aces_inverse_bisection(double target) {
    double lo = 0.0, hi = 1e6;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (flip_tonemap_aces(static_cast<float>(mid)) < target ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

void test_hdr_exposures(void**) {
    // Narkowicz's curve with the 0.6 pre-exposure: 0.6x(2.51*0.6x + 0.03) / (0.6x(2.43*0.6x + 0.59) + 0.14).
    for (double x : {0.1, 1.0, 4.0}) {
        const double y = 0.6 * x;
        EXPECT_NEAR(flip_tonemap_aces(static_cast<float>(x)), y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14), 1e-6);
    }
    const double x85 = aces_inverse_bisection(0.85);
    const int w = 16, h = 8;
    // Uniform grey of luminance 2: start = stop = log2(x85 / 2), two exposures.
    std::vector<float> img = uniform(w, h, {2, 2, 2});
    FlipExposures ex;
    assert_int_equal(flip_hdr_exposures(img.data(), w, h, ex), FlipResult::ok);
    EXPECT_NEAR(ex.start, std::log2(x85 / 2.0), 1e-4);
    EXPECT_NEAR(ex.stop, std::log2(x85 / 2.0), 1e-4);
    assert_int_equal(ex.count, 2);
    // Max luminance 50 (one pixel), median 1: stop - start = log2(50) = 5.64 stops, 6 exposures.
    img = uniform(w, h, {1, 1, 1});
    set_pixel(img, w, 3, 3, {50, 50, 50});
    assert_int_equal(flip_hdr_exposures(img.data(), w, h, ex), FlipResult::ok);
    EXPECT_NEAR(ex.start, std::log2(x85 / 50.0), 1e-4);
    EXPECT_NEAR(ex.stop, std::log2(x85), 1e-4);
    assert_int_equal(ex.count, 6);
    // Mostly black: the median is taken over the lit pixels (here all 4).
    img = uniform(w, h, {0, 0, 0});
    for (int x = 0; x < 4; ++x) set_pixel(img, w, x, 0, {4, 4, 4});
    assert_int_equal(flip_hdr_exposures(img.data(), w, h, ex), FlipResult::ok);
    EXPECT_NEAR(ex.stop, std::log2(x85 / 4.0), 1e-4);
    // All black: defined, finite.
    img = uniform(w, h, {0, 0, 0});
    assert_int_equal(flip_hdr_exposures(img.data(), w, h, ex), FlipResult::ok);
    assert_int_equal(ex.count, 2);
    std::vector<float> map;
    const std::vector<float> grey = uniform(w, h, {0.5f, 0.5f, 0.5f});
    assert_int_equal(flip_hdr(img.data(), grey.data(), w, h, kFlipDefaultPpd, map), FlipResult::ok);
    assert_true(std::isfinite(mean_of(map)) && mean_of(map) > 0.0);
}

// HDR-FLIP of uniform images: every exposure compares two uniform tone-mapped colours, so the
// result is the hand colour error of the tone-mapped pair at the (single) exposure.
void test_hdr_uniform_by_hand(void**) {
    const int w = 16, h = 16;
    const std::vector<float> ref = uniform(w, h, {3, 3, 3}), test = uniform(w, h, {4, 3.5f, 3});
    std::vector<float> map;
    FlipExposures ex;
    assert_int_equal(flip_hdr(ref.data(), test.data(), w, h, kFlipDefaultPpd, map, &ex), FlipResult::ok);
    const double lum = 3.0;
    const double scale = aces_inverse_bisection(0.85) / lum;  // 2^c_start = 2^c_stop
    auto tm = [&](float v) { return std::min(1.0f, flip_tonemap_aces(static_cast<float>(scale * v))); };
    const double expected = hand_color_error({tm(3), tm(3), tm(3)}, {tm(4), tm(3.5f), tm(3)});
    EXPECT_NEAR(mean_of(map), expected, 2e-3);
}

// HDR-FLIP (Sec. 3 of the HDR paper) as a composition: the per-pixel max over count exposures
// spaced uniformly from start to stop (inclusive) of LDR-FLIP on the ACES-tone-mapped, clamped
// images. The tone mapping is written out again here from Narkowicz's formula.
void test_hdr_is_max_over_exposures(void**) {
    const int w = 24, h = 20;
    const std::vector<float> n = noise_pattern(static_cast<std::size_t>(w) * h * 3, 99);
    std::vector<float> ref(n.size()), test(n.size());
    for (std::size_t i = 0; i < n.size(); ++i) {
        ref[i] = std::exp2(4.0f * n[i]);                  // 1/16 .. 16
        test[i] = ref[i] * (1.0f + 0.1f * n[(i * 7) % n.size()]);
    }
    FlipExposures ex;
    std::vector<float> hdr;
    assert_int_equal(flip_hdr(ref.data(), test.data(), w, h, kFlipDefaultPpd, hdr, &ex), FlipResult::ok);
    assert_true(ex.count >= 3);
    auto aces = [](double x) {
        const double y = 0.6 * x;
        return std::min(1.0, y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14));
    };
    std::vector<float> expected(hdr.size(), 0.0f), map, r(n.size()), t(n.size());
    for (int e = 0; e < ex.count; ++e) {
        const double scale = std::exp2(ex.start + (ex.stop - ex.start) * e / (ex.count - 1.0));
        for (std::size_t i = 0; i < n.size(); ++i) {
            r[i] = static_cast<float>(aces(scale * ref[i]));
            t[i] = static_cast<float>(aces(scale * test[i]));
        }
        assert_int_equal(flip_ldr(r.data(), t.data(), w, h, kFlipDefaultPpd, map), FlipResult::ok);
        for (std::size_t i = 0; i < map.size(); ++i) expected[i] = std::max(expected[i], map[i]);
    }
    for (std::size_t i = 0; i < hdr.size(); ++i) EXPECT_NEAR(hdr[i], expected[i], 1e-4);
}

// Mean errors of NVIDIA's published implementation (PyPI flip-evaluator 1.7, linear inputs,
// float64 mean of its error map), computed once for the deterministic images below; an independent
// check of the readings flip.hpp documents. Its HDR median convention differs slightly from ours,
// hence the wider tolerance on the stop exposure.
std::vector<float> gradient_scene(int w, int h, float gain, bool modulate) {
    std::vector<float> img(static_cast<std::size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool square = x >= 40 && x < 90 && y >= 30 && y < 70;
            Rgb c = square ? Rgb{0.9f, 0.8f, 0.2f} : Rgb{0.2f + 0.6f * x / w, 0.3f + 0.4f * y / h, 0.5f};
            const float m = gain * (modulate ? std::exp2(4.0f * std::sin(x / 7.0f) * std::cos(y / 5.0f)) : 1.0f);
            set_pixel(img, w, x, y, {c.r * m, c.g * m, c.b * m});
        }
    return img;
}

void test_matches_published_implementation(void**) {
    const int w = 128, h = 96;
    std::vector<float> step = uniform(w, h, {0, 0, 0});
    for (int y = 0; y < h; ++y)
        for (int x = 64; x < w; ++x) set_pixel(step, w, x, y, {1, 1, 1});
    const std::vector<float> grey = uniform(w, h, {0.5f, 0.5f, 0.5f});
    const std::vector<float> scene = gradient_scene(w, h, 1.0f, false);
    std::vector<float> shifted(scene.size()), scaled(scene.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const std::size_t i = (static_cast<std::size_t>(y) * w + x) * 3 + c;
                shifted[i] = scene[(static_cast<std::size_t>(y) * w + (x + w - 1) % w) * 3 + c];
                scaled[i] = std::min(1.0f, scene[i] * (c == 0 ? 1.1f : c == 1 ? 0.9f : 1.0f));
            }
    const struct {
        const std::vector<float>* ref;
        const std::vector<float>* test;
        float ppd;
        double expected;
    } cases[] = {
        {&step, &grey, 67.0f, 0.7581453649}, {&scene, &shifted, 67.0f, 0.0509257275},
        {&scene, &scaled, 67.0f, 0.2555267348}, {&step, &grey, 30.0f, 0.7515062117},
        {&scene, &shifted, 30.0f, 0.0434673458}, {&scene, &scaled, 30.0f, 0.2508349261},
    };
    std::vector<float> map;
    for (const auto& c : cases) {
        assert_int_equal(flip_ldr(c.ref->data(), c.test->data(), w, h, c.ppd, map), FlipResult::ok);
        EXPECT_NEAR(mean_of(map), c.expected, 5e-5);
    }
    const std::vector<float> hdr_ref = gradient_scene(w, h, 16.0f, true);
    std::vector<float> hdr_test(hdr_ref);
    for (float& v : hdr_test) v *= 1.2f;
    FlipExposures ex;
    assert_int_equal(flip_hdr(hdr_ref.data(), hdr_test.data(), w, h, 67.0f, map, &ex), FlipResult::ok);
    EXPECT_NEAR(ex.start, -6.553166389, 1e-4);
    EXPECT_NEAR(ex.stop, -1.989931226, 1e-3);
    assert_int_equal(ex.count, 5);
    EXPECT_NEAR(mean_of(map), 0.2385057445, 2e-4);
}

void test_bad_input(void**) {
    const int w = 8, h = 8;
    std::vector<float> a = uniform(w, h, {0.5f, 0.5f, 0.5f}), b = a, map;
    assert_int_equal(flip_ldr(nullptr, b.data(), w, h, 67.0f, map), FlipResult::null_input);
    assert_int_equal(flip_ldr(a.data(), nullptr, w, h, 67.0f, map), FlipResult::null_input);
    assert_int_equal(flip_ldr(a.data(), b.data(), 0, h, 67.0f, map), FlipResult::invalid_size);
    assert_int_equal(flip_ldr(a.data(), b.data(), w, -1, 67.0f, map), FlipResult::invalid_size);
    assert_int_equal(flip_ldr(a.data(), b.data(), w, h, 0.0f, map), FlipResult::invalid_ppd);
    assert_int_equal(flip_ldr(a.data(), b.data(), w, h, NAN, map), FlipResult::invalid_ppd);
    assert_int_equal(flip_ldr(a.data(), b.data(), w, h, 5000.0f, map), FlipResult::invalid_ppd);
    b[5] = NAN;
    assert_int_equal(flip_ldr(a.data(), b.data(), w, h, 67.0f, map), FlipResult::non_finite_input);
    b[5] = INFINITY;
    assert_int_equal(flip_hdr(a.data(), b.data(), w, h, 67.0f, map), FlipResult::non_finite_input);
    FlipExposures ex;
    assert_int_equal(flip_hdr_exposures(b.data(), w, h, ex), FlipResult::non_finite_input);
    // Tiny ppd: kernels degenerate to identity, still a valid map.
    b = a;
    b[0] = 0.9f;
    assert_int_equal(flip_ldr(a.data(), b.data(), w, h, 0.01f, map), FlipResult::ok);
    assert_true(std::isfinite(max_of(map)) && max_of(map) > 0.0 && max_of(map) <= 1.0);
    // Huge HDR values do not overflow into NaN.
    b = a;
    b[0] = 3e38f;
    assert_int_equal(flip_hdr(a.data(), b.data(), w, h, 67.0f, map), FlipResult::ok);
    assert_true(std::isfinite(max_of(map)) && max_of(map) <= 1.0);
    assert_string_equal(flip_result_string(FlipResult::invalid_ppd), "pixels per degree must be finite and in (0, 1000]");
}

void test_stats(void**) {
    std::vector<float> v;
    for (int i = 10; i >= 0; --i) v.push_back(static_cast<float>(i));  // 0..10, unsorted
    const FlipStats s = flip_stats(v);
    EXPECT_NEAR(s.mean, 5.0, 1e-12);
    EXPECT_NEAR(s.median, 5.0, 1e-12);
    EXPECT_NEAR(s.p95, 9.5, 1e-9);  // rank 0.95 * 10
    EXPECT_NEAR(s.p99, 9.9, 1e-6);
    EXPECT_NEAR(s.max, 10.0, 0.0);
    const FlipStats empty = flip_stats({});
    EXPECT_NEAR(empty.mean, 0.0, 0.0);
}

void test_srgb_transfer(void**) {
    EXPECT_NEAR(srgb_to_linear(0.5f), 0.2140411, 1e-6);  // ((0.5 + 0.055) / 1.055)^2.4
    EXPECT_NEAR(srgb_to_linear(0.04f), 0.04 / 12.92, 1e-9);
    EXPECT_NEAR(linear_to_srgb(srgb_to_linear(0.73f)), 0.73, 1e-6);
}

} // namespace

RTPBR_TEST_MAIN(cmocka_unit_test(test_identical_is_zero),
                cmocka_unit_test(test_uniform_colour_pipeline_by_hand),
                cmocka_unit_test(test_feature_step_edge_by_hand),
                cmocka_unit_test(test_feature_point_by_hand),
                cmocka_unit_test(test_features_amplify_colour_error),
                cmocka_unit_test(test_monotonic_in_offset),
                cmocka_unit_test(test_monotonic_in_noise_amplitude),
                cmocka_unit_test(test_uniform_difference_size_independent),
                cmocka_unit_test(test_centred_feature_scaling),
                cmocka_unit_test(test_hdr_exposures),
                cmocka_unit_test(test_hdr_uniform_by_hand),
                cmocka_unit_test(test_hdr_is_max_over_exposures),
                cmocka_unit_test(test_matches_published_implementation),
                cmocka_unit_test(test_bad_input),
                cmocka_unit_test(test_stats),
                cmocka_unit_test(test_srgb_transfer))
