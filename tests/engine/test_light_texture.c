// The prefiltered mip chain of a textured quad light (engine/src/light_texture.c, issue 30),
// on the host, against references computed here independently of the module:
//   - a constant texture stays that constant at every texel of every level (sRGB and linear);
//   - sRGB decode by the IEC 61966-2-1 EOTF (128 -> 0.2158605), linear data as v / 255;
//   - a step: level 0 against the cell means of the bilinear reconstruction, level k against the
//     closed form of the Gaussian-blurred step normalised over the light,
//     (Phi((S - p) / sigma) - Phi((a - p) / sigma)) / (Phi((S - p) / sigma) - Phi(-p / sigma));
//   - the uv mapping: a quadrant, repeat / clamp / mirror, a flipped dv;
//   - a 1024 x 1024 checkerboard of 1-texel squares averages to 1/2 (no aliasing);
//   - bad input returns -1.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_main.h"

#include "light_texture.h"

enum { S = RTPBR_LIGHT_TEXTURE_SIZE, LEVELS = RTPBR_LIGHT_TEXTURE_LEVELS };

static float *new_chain(void)
{
    float *chain = malloc(rtpbr_light_texture_floats() * sizeof *chain);
    assert_non_null(chain);
    return chain;
}

static const float *texel(const float *chain, uint32_t k, int x, int y)
{
    return chain + rtpbr_light_texture_level_offset(k) + ((size_t)y * (S >> k) + x) * 4;
}

static uint8_t *new_texture(uint32_t w, uint32_t h)
{
    uint8_t *rgba = calloc((size_t)w * h * 4, 1);
    assert_non_null(rgba);
    return rgba;
}

static void set_texel(uint8_t *rgba, uint32_t w, uint32_t x, uint32_t y, uint8_t r, uint8_t g, uint8_t b)
{
    uint8_t *p = rgba + ((size_t)y * w + x) * 4;
    p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
}

static void prefilter(const rtpbr_texture_desc *desc, float u0, float v0, float dux, float duy, float dvx, float dvy,
                      float *chain)
{
    const float uv0[2] = {u0, v0}, du[2] = {dux, duy}, dv[2] = {dvx, dvy};
    assert_int_equal(rtpbr_light_texture_prefilter(desc, uv0, du, dv, chain), 0);
}

// sRGB EOTF (IEC 61966-2-1), in double.
static double srgb_eotf(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static void layout(void **state)
{
    (void)state;
    size_t expected = 0;
    for (uint32_t k = 0; k < LEVELS; ++k) {
        assert_int_equal(rtpbr_light_texture_level_offset(k), expected);
        expected += (size_t)(S >> k) * (S >> k) * 4;
    }
    assert_int_equal(rtpbr_light_texture_floats(), expected);
    assert_int_equal(expected, 4 * (128 * 128 + 64 * 64 + 32 * 32 + 16 * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1));
    assert_int_equal(S >> (LEVELS - 1), 1);
}

// An odd-sized constant texture under a sheared, partly negative mapping with each wrap mode:
// every texel of every level is the decoded constant within 1e-6, alpha 1.
static void constant(void **state)
{
    (void)state;
    const uint8_t code[3] = {128, 37, 200};
    const uint32_t w = 37, h = 23;
    uint8_t *rgba = new_texture(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) set_texel(rgba, w, x, y, code[0], code[1], code[2]);
    float *chain = new_chain();
    for (int srgb = 0; srgb <= 1; ++srgb)
        for (int wrap = RTPBR_WRAP_REPEAT; wrap <= RTPBR_WRAP_MIRRORED_REPEAT; ++wrap) {
            rtpbr_texture_desc desc = {.width = w, .height = h, .rgba = rgba, .srgb = srgb,
                                       .wrap_s = (rtpbr_wrap)wrap, .wrap_t = (rtpbr_wrap)wrap};
            prefilter(&desc, 0.3f, -0.7f, 1.7f, 0.4f, -0.2f, 1.1f, chain);
            double worst = 0.0;
            for (uint32_t k = 0; k < LEVELS; ++k)
                for (int y = 0; y < S >> k; ++y)
                    for (int x = 0; x < S >> k; ++x) {
                        const float *t = texel(chain, k, x, y);
                        for (int c = 0; c < 3; ++c) {
                            double expected = srgb ? srgb_eotf(code[c] / 255.0) : code[c] / 255.0;
                            worst = fmax(worst, fabs(t[c] - expected));
                        }
                        assert_true(t[3] == 1.0f);
                    }
            print_message("constant, srgb %d, wrap %d: max |error| %.2e\n", srgb, wrap, worst);
            assert_true(worst <= 1e-6);
        }
    free(chain);
    free(rgba);
}

// A 1 x 1 texture: the decoded code itself. sRGB 128 -> 0.2158605 (the EOTF's value), 10 on its
// linear segment -> 10 / 255 / 12.92, the ends 0 and 1; linear codes v -> v / 255.
static void decode(void **state)
{
    (void)state;
    float *chain = new_chain();
    const struct { uint8_t code; int srgb; double expected; } cases[] = {
        {128, 1, 0.2158605}, {10, 1, 10.0 / 255.0 / 12.92}, {0, 1, 0.0}, {255, 1, 1.0},
        {128, 0, 128.0 / 255.0}, {1, 0, 1.0 / 255.0}, {0, 0, 0.0}, {255, 0, 1.0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; ++i) {
        uint8_t rgba[4] = {cases[i].code, cases[i].code, cases[i].code, 255};
        rtpbr_texture_desc desc = {.width = 1, .height = 1, .rgba = rgba, .srgb = cases[i].srgb};
        prefilter(&desc, 0, 0, 1, 0, 0, 1, chain);
        for (int c = 0; c < 3; ++c) assert_true(fabs(texel(chain, 0, 77, 5)[c] - cases[i].expected) <= 1e-6);
    }
    free(chain);
}

// Standard normal CDF.
static double phi(double z)
{
    return 0.5 * (1.0 + erf(z / sqrt(2.0)));
}

// The unit step at a (level-0 texel units, the light is [0, S]) blurred by the full Gaussian of
// sigma and normalised over the light, at p.
static double blurred_step(double a, double p, double sigma)
{
    double in_light = phi((S - p) / sigma) - phi(-p / sigma);
    return (phi((S - p) / sigma) - phi((a - p) / sigma)) / in_light;
}

// A step texture, 1024 x 4, left half 0, right half 1 (linear, clamp to edge), over the whole
// light. Level 0: bilinear reads ramp across one texel around u = 1/2, whose cell means are
// S / (8 W) and 1 - S / (8 W) in the two cells beside the boundary (half a texel of mean 1/4 in a
// cell of W / S texels); 0 and 1 elsewhere. Level k: level 0 is then a sum of three steps, at
// S/2 - 1 (height c = S / (8 W)), S/2 (1 - 2c) and S/2 + 1 (c), so its normalised blur is that sum
// of blurred_step; texel o of level k is its mean at the level-0 texel centres of its block.
// Also measured against the ideal step at S/2 (the continuous block mean), which the level-0
// discretisation (the ramp, and sampling at texel centres) separates from the chain.
static void step(void **state)
{
    (void)state;
    const uint32_t w = 1024, h = 4;
    uint8_t *rgba = new_texture(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) set_texel(rgba, w, x, y, x < w / 2 ? 0 : 255, 0, 0);
    rtpbr_texture_desc desc = {.width = w, .height = h, .rgba = rgba, .wrap_s = RTPBR_WRAP_CLAMP_TO_EDGE,
                               .wrap_t = RTPBR_WRAP_CLAMP_TO_EDGE};
    float *chain = new_chain();
    prefilter(&desc, 0, 0, 1, 0, 0, 1, chain);
    const double c = (double)S / (8.0 * w);
    for (int y = 0; y < S; ++y)
        for (int x = 0; x < S; ++x) {
            double expected = x < S / 2 - 1 ? 0.0 : x == S / 2 - 1 ? c : x == S / 2 ? 1.0 - c : 1.0;
            assert_true(fabs(texel(chain, 0, x, y)[0] - expected) <= 1e-6);
        }
    // The chain truncates its Gaussian at 3.5 sigma, dropping 1 - Phi(3.5) = 2.3e-4 of it on each
    // side: measured at most 2.1e-4 (level 5), 0 at levels 6 and 7 (their kernels cover the
    // light). Against the ideal step: at most 1.7e-3 (level 1, beside the step), 2.3e-4 from level 3 on.
    const double tolerance = 3e-4, ideal_tolerance = 3e-3;
    for (uint32_t k = 1; k < LEVELS; ++k) {
        int side = S >> k, block = 1 << k;
        double sigma = block / sqrt(2.0 * log(2.0));
        double worst = 0.0, worst_ideal = 0.0;
        for (int o = 0; o < side; ++o) {
            double expected = 0.0;
            for (int i = 0; i < block; ++i) {
                double p = o * block + i + 0.5;
                expected += (c * blurred_step(S / 2 - 1, p, sigma) + (1.0 - 2.0 * c) * blurred_step(S / 2, p, sigma) +
                             c * blurred_step(S / 2 + 1, p, sigma)) / block;
            }
            double ideal = 0.0; // midpoint rule, 64 points per level-0 texel
            for (int i = 0; i < block * 64; ++i) ideal += blurred_step(S / 2, o * block + (i + 0.5) / 64.0, sigma);
            ideal /= block * 64;
            double got = texel(chain, k, o, side / 2)[0];
            worst = fmax(worst, fabs(got - expected));
            worst_ideal = fmax(worst_ideal, fabs(got - ideal));
        }
        print_message("step, level %u (sigma %.2f): max |error| %.2e, against the ideal step %.2e\n", k, sigma, worst,
                      worst_ideal);
        assert_true(worst <= tolerance);
        assert_true(worst_ideal <= ideal_tolerance);
    }
    // The normalisation matters there: at level 6 the right texel is 0.65, the unnormalised
    // blur's (mean of Phi((S - p) / sigma) - Phi((S/2 - p) / sigma) over p in [S/2, S]) 0.42.
    double sigma6 = 64.0 / sqrt(2.0 * log(2.0)), unnormalised = 0.0;
    for (int i = 0; i < 64 * 64; ++i) {
        double p = S / 2 + (i + 0.5) / 64.0;
        unnormalised += (phi((S - p) / sigma6) - phi((S / 2 - p) / sigma6)) / (64 * 64);
    }
    print_message("step, level 6: right texel %.4f, unnormalised blur %.4f\n", texel(chain, 6, 1, 0)[0], unnormalised);
    assert_true(texel(chain, 6, 1, 0)[0] - unnormalised > 0.1);
    free(chain);
    free(rgba);
}

// The quadrant texture: 1024 x 1024, the top-right quadrant (u >= 1/2, v < 1/2) red, the rest blue.
static int quadrant_red(double u, double v)
{
    return u >= 0.5 && v < 0.5;
}

// The ideal wrap of a texture coordinate (not of texel indices): repeat has period 1, mirrored
// repeat period 2 reflected at 1, clamp to edge stays in [0, 1].
static double wrap_coordinate(double u, rtpbr_wrap wrap)
{
    if (wrap == RTPBR_WRAP_REPEAT) return u - floor(u);
    if (wrap == RTPBR_WRAP_MIRRORED_REPEAT) {
        double m = u - 2.0 * floor(u / 2.0);
        return m > 1.0 ? 2.0 - m : m;
    }
    return u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
}

// Level 0 under one axis-aligned mapping against the ideal quadrant: every cell whose uv
// rectangle, widened by one texel (the bilinear reads), lies on one side of the quadrant's
// edges (checked on a 9 x 9 grid) is exactly red (1, 0, 0) or blue (0, 0, 1); at least
// 90 % of the cells are such, and the red ones are red_fraction of all cells (give or take the
// boundary cells, up to 6 S).
static void check_mapping(const float *chain, float u0, float v0, float du, float dv, rtpbr_wrap wrap,
                          double red_fraction, const char *what)
{
    const double margin = 1.0 / 1024.0;
    int pure = 0, red = 0;
    for (int y = 0; y < S; ++y)
        for (int x = 0; x < S; ++x) {
            double ua = u0 + du * x / S, ub = u0 + du * (x + 1) / S;
            double va = v0 + dv * y / S, vb = v0 + dv * (y + 1) / S;
            double ulo = fmin(ua, ub) - margin, uhi = fmax(ua, ub) + margin;
            double vlo = fmin(va, vb) - margin, vhi = fmax(va, vb) + margin;
            int first = -1, same = 1;
            for (int j = 0; j <= 8 && same; ++j)
                for (int i = 0; i <= 8 && same; ++i) {
                    int r = quadrant_red(wrap_coordinate(ulo + (uhi - ulo) * i / 8, wrap),
                                         wrap_coordinate(vlo + (vhi - vlo) * j / 8, wrap));
                    if (first < 0) first = r;
                    same = r == first;
                }
            if (!same) continue;
            ++pure;
            red += first;
            const float *t = texel(chain, 0, x, y);
            if (fabs(t[0] - first) > 1e-6 || fabs(t[1]) > 1e-6 || fabs(t[2] - (1 - first)) > 1e-6)
                fail_msg("%s: cell (%d, %d) is (%g, %g, %g), expected %s", what, x, y, t[0], t[1], t[2],
                         first ? "red" : "blue");
        }
    print_message("%s: %d pure cells, %d red\n", what, pure, red);
    assert_true(pure >= S * S * 9 / 10);
    assert_true(fabs(red - red_fraction * S * S) <= 6 * S);
}

static void mapping(void **state)
{
    (void)state;
    const uint32_t n = 1024;
    uint8_t *rgba = new_texture(n, n);
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x)
            set_texel(rgba, n, x, y, quadrant_red((x + 0.5) / n, (y + 0.5) / n) ? 255 : 0, 0,
                      quadrant_red((x + 0.5) / n, (y + 0.5) / n) ? 0 : 255);
    float *chain = new_chain();
    rtpbr_texture_desc desc = {.width = n, .height = n, .rgba = rgba};

    // The red quadrant alone (clamp: its outer edges read themselves). Its inner edges blend
    // in the first column and the last row: bilinear reads ramp across one texel there, half a
    // texel of mean 3/4 in a cell of 4 texels: red 31/32, and (31/32)^2 at their corner.
    desc.wrap_s = desc.wrap_t = RTPBR_WRAP_CLAMP_TO_EDGE;
    prefilter(&desc, 0.5f, 0, 0.5f, 0, 0, 0.5f, chain);
    for (int y = 0; y < S; ++y)
        for (int x = 0; x < S; ++x) {
            double expected = (x == 0 ? 31.0 / 32.0 : 1.0) * (y == S - 1 ? 31.0 / 32.0 : 1.0);
            const float *t = texel(chain, 0, x, y);
            assert_true(fabs(t[0] - expected) <= 1e-6 && fabs(t[2] - (1.0 - expected)) <= 1e-6 && t[1] == 0.0f);
        }
    check_mapping(chain, 0.5f, 0, 0.5f, 0.5f, RTPBR_WRAP_CLAMP_TO_EDGE, 1.0, "the quadrant");

    // u over [0, 2]: repeat shows the quadrant twice (s in [1/4, 1/2] and [3/4, 1]), clamp
    // extends its right edge (s in [1/4, 1]), mirror reflects the second copy (s in [1/4, 3/4]).
    desc.wrap_s = desc.wrap_t = RTPBR_WRAP_REPEAT;
    prefilter(&desc, 0, 0, 2, 0, 0, 1, chain);
    check_mapping(chain, 0, 0, 2, 1, RTPBR_WRAP_REPEAT, 0.25, "du = (2, 0), repeat");
    assert_true(texel(chain, 0, 80, 10)[0] < 1e-6f && texel(chain, 0, 112, 10)[0] > 1.0f - 1e-6f);
    desc.wrap_s = desc.wrap_t = RTPBR_WRAP_CLAMP_TO_EDGE;
    prefilter(&desc, 0, 0, 2, 0, 0, 1, chain);
    check_mapping(chain, 0, 0, 2, 1, RTPBR_WRAP_CLAMP_TO_EDGE, 0.375, "du = (2, 0), clamp");
    assert_true(texel(chain, 0, 80, 10)[0] > 1.0f - 1e-6f && texel(chain, 0, 112, 10)[0] > 1.0f - 1e-6f);
    desc.wrap_s = desc.wrap_t = RTPBR_WRAP_MIRRORED_REPEAT;
    prefilter(&desc, 0, 0, 2, 0, 0, 1, chain);
    check_mapping(chain, 0, 0, 2, 1, RTPBR_WRAP_MIRRORED_REPEAT, 0.25, "du = (2, 0), mirror");
    assert_true(texel(chain, 0, 80, 10)[0] > 1.0f - 1e-6f && texel(chain, 0, 112, 10)[0] < 1e-6f);

    // dv negative: v = 1 - t, the image upside down, at every level.
    desc.wrap_s = desc.wrap_t = RTPBR_WRAP_REPEAT;
    float *plain = new_chain();
    prefilter(&desc, 0, 0, 1, 0, 0, 1, plain);
    prefilter(&desc, 0, 1, 1, 0, 0, -1, chain);
    check_mapping(chain, 0, 1, 1, -1, RTPBR_WRAP_REPEAT, 0.25, "dv = (0, -1)");
    double worst = 0.0;
    for (uint32_t k = 0; k < LEVELS; ++k)
        for (int y = 0; y < S >> k; ++y)
            for (int x = 0; x < S >> k; ++x)
                for (int c = 0; c < 4; ++c)
                    worst = fmax(worst, fabs(texel(chain, k, x, y)[c] - texel(plain, k, x, (S >> k) - 1 - y)[c]));
    print_message("dv = (0, -1) against the plain chain's rows reversed: max |difference| %.2e\n", worst);
    assert_true(worst <= 1e-6);
    assert_true(texel(chain, 0, 100, 100)[0] > 1.0f - 1e-6f && texel(plain, 0, 100, 100)[0] < 1e-6f);
    free(plain);
    free(chain);
    free(rgba);
}

// A 1024 x 1024 checkerboard of 1-texel squares (0 / 1, linear) over the light: 8 texels a
// cell, so 16 x 16 reads a cell; level 0 is 1/2 within 0.02 everywhere, also shifted by a
// fraction of a texel (reads at texel edges see 1/2 whatever their number) and rotated by
// 36.87 degrees (du = (0.8, 0.6), dv = (-0.6, 0.8)).
static void checkerboard(void **state)
{
    (void)state;
    const uint32_t n = 1024;
    uint8_t *rgba = new_texture(n, n);
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) set_texel(rgba, n, x, y, (x + y) % 2 ? 255 : 0, (x + y) % 2 ? 255 : 0, 0);
    rtpbr_texture_desc desc = {.width = n, .height = n, .rgba = rgba};
    float *chain = new_chain();
    const float maps[3][6] = {{0, 0, 1, 0, 0, 1}, {0.3f / n, 0.1f / n, 1, 0, 0, 1}, {0, 0, 0.8f, 0.6f, -0.6f, 0.8f}};
    for (int m = 0; m < 3; ++m) {
        prefilter(&desc, maps[m][0], maps[m][1], maps[m][2], maps[m][3], maps[m][4], maps[m][5], chain);
        double worst = 0.0;
        for (int y = 0; y < S; ++y)
            for (int x = 0; x < S; ++x) {
                const float *t = texel(chain, 0, x, y);
                worst = fmax(worst, fmax(fabs(t[0] - 0.5), fabs(t[1] - 0.5)));
                assert_true(t[2] == 0.0f);
            }
        print_message("checkerboard, map %d: max |level 0 - 1/2| %.2e\n", m, worst);
        assert_true(worst <= 0.02);
    }
    free(chain);
    free(rgba);
}

static void bad_input(void **state)
{
    (void)state;
    uint8_t rgba[4 * 4] = {0};
    float *chain = new_chain();
    const float uv0[2] = {0, 0}, du[2] = {1, 0}, dv[2] = {0, 1};
    const float nan_uv[2] = {NAN, 0}, inf_uv[2] = {0, INFINITY};
    rtpbr_texture_desc good = {.width = 2, .height = 2, .rgba = rgba};
    assert_int_equal(rtpbr_light_texture_prefilter(&good, uv0, du, dv, chain), 0);
    assert_int_equal(rtpbr_light_texture_prefilter(NULL, uv0, du, dv, chain), -1);
    assert_int_equal(rtpbr_light_texture_prefilter(&good, uv0, du, dv, NULL), -1);
    assert_int_equal(rtpbr_light_texture_prefilter(&good, NULL, du, dv, chain), -1);
    assert_int_equal(rtpbr_light_texture_prefilter(&good, uv0, NULL, dv, chain), -1);
    assert_int_equal(rtpbr_light_texture_prefilter(&good, uv0, du, NULL, chain), -1);
    assert_int_equal(rtpbr_light_texture_prefilter(&good, nan_uv, du, dv, chain), -1);
    assert_int_equal(rtpbr_light_texture_prefilter(&good, uv0, nan_uv, dv, chain), -1);
    assert_int_equal(rtpbr_light_texture_prefilter(&good, uv0, du, inf_uv, chain), -1);
    rtpbr_texture_desc bad = good;
    bad.rgba = NULL;
    assert_int_equal(rtpbr_light_texture_prefilter(&bad, uv0, du, dv, chain), -1);
    bad = good, bad.width = 0;
    assert_int_equal(rtpbr_light_texture_prefilter(&bad, uv0, du, dv, chain), -1);
    bad = good, bad.height = 0;
    assert_int_equal(rtpbr_light_texture_prefilter(&bad, uv0, du, dv, chain), -1);
    bad = good, bad.width = RTPBR_MAX_RENDER_SIZE + 1;
    assert_int_equal(rtpbr_light_texture_prefilter(&bad, uv0, du, dv, chain), -1);
    bad = good, bad.wrap_t = (rtpbr_wrap)7;
    assert_int_equal(rtpbr_light_texture_prefilter(&bad, uv0, du, dv, chain), -1);
    // Huge but finite coordinates are not bad input: every read stays inside the texture.
    const float huge[2] = {3e38f, -3e38f};
    for (int wrap = RTPBR_WRAP_REPEAT; wrap <= RTPBR_WRAP_MIRRORED_REPEAT; ++wrap) {
        rtpbr_texture_desc far = good;
        far.wrap_s = far.wrap_t = (rtpbr_wrap)wrap;
        assert_int_equal(rtpbr_light_texture_prefilter(&far, huge, huge, huge, chain), 0);
        assert_true(texel(chain, 0, 0, 0)[0] == 0.0f);
    }
    free(chain);
}

RTPBR_TEST_MAIN(cmocka_unit_test(layout), cmocka_unit_test(constant), cmocka_unit_test(decode),
                cmocka_unit_test(step), cmocka_unit_test(mapping), cmocka_unit_test(checkerboard),
                cmocka_unit_test(bad_input))
