// The prefiltered mip chain of a textured quad light (light_texture.h): level 0 by supersampled
// bilinear reads of the source, levels 1.. by a normalised Gaussian blur of level 0 and a block
// mean, applied as one separable pass per axis with the blur and the block mean folded into one
// set of weights per level.
#include "light_texture.h"

#include <math.h>
#include <stdbool.h>

enum {
    LT_S = RTPBR_LIGHT_TEXTURE_SIZE,
    LT_MAX_SAMPLES = 16, // supersamples per axis of a level-0 cell
    // Weights of one level (lt_weights): output o of S >> k reads at most 2^k + 2R level-0 texels,
    // and R = ceil(3.5 sigma) <= 3 * 2^k (3.5 / 1.1774 < 3), so S >> k outputs read at most 7 S.
    LT_WEIGHT_CAPACITY = 7 * LT_S,
};
_Static_assert(RTPBR_LIGHT_TEXTURE_SIZE >> (RTPBR_LIGHT_TEXTURE_LEVELS - 1) == 1, "the last level is 1 x 1");

// A 2D Gaussian holds half of its mass within radius R where 1 - exp(-R^2 / (2 sigma^2)) = 1/2,
// i.e. R = sigma sqrt(2 ln 2) = 1.1774 sigma (ltc_textured.h: "sigma = footprint / 1.1774").
#define LT_HALF_MASS_RADIUS_PER_SIGMA 1.1774100225154747
#define LT_TRUNCATION_SIGMAS 3.5

size_t rtpbr_light_texture_level_offset(uint32_t k)
{
    size_t offset = 0;
    for (uint32_t level = 0; level < k && level < RTPBR_LIGHT_TEXTURE_LEVELS; ++level) {
        size_t side = (size_t)LT_S >> level;
        offset += side * side * 4;
    }
    return offset;
}

size_t rtpbr_light_texture_floats(void)
{
    return rtpbr_light_texture_level_offset(RTPBR_LIGHT_TEXTURE_LEVELS);
}

// IEC 61966-2-1 sRGB EOTF: c / 12.92 up to 0.04045, else ((c + 0.055) / 1.055)^2.4.
static double lt_srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

// One axis of the source: n texels and the wrap mode (repeat has period n, mirrored repeat 2n).
typedef struct lt_axis {
    uint32_t n;
    rtpbr_wrap wrap;
    double period, inv_period;
} lt_axis;

typedef struct lt_source {
    const uint8_t *rgba;
    lt_axis s, t;
    float decode[256]; // linear value of each 8-bit code
} lt_source;

static lt_axis lt_axis_make(uint32_t n, rtpbr_wrap wrap)
{
    double period = wrap == RTPBR_WRAP_MIRRORED_REPEAT ? 2.0 * n : (double)n;
    return (lt_axis){.n = n, .wrap = wrap, .period = period, .inv_period = 1.0 / period};
}

// The two texels a bilinear read blends along an axis, after the wrap, and the weight f of the
// second; x is the texel coordinate less 1/2 (texel i's centre at i: x = u n - 1/2).
static void lt_axis_texels(double x, const lt_axis *axis, uint32_t *i0, uint32_t *i1, float *f)
{
    double lower = floor(x);
    *f = (float)(x - lower);
    if (axis->wrap == RTPBR_WRAP_CLAMP_TO_EDGE) {
        double hi = (double)axis->n - 1.0;
        *i0 = (uint32_t)(lower < 0.0 ? 0.0 : lower > hi ? hi : lower);
        *i1 = (uint32_t)(lower + 1.0 < 0.0 ? 0.0 : lower + 1.0 > hi ? hi : lower + 1.0);
        return;
    }
    // The reduction's rounding is corrected once, and a coordinate too large for a texel index
    // to mean anything reads texel 0 (no out-of-range read).
    double period = axis->period;
    double m = lower - period * floor(lower * axis->inv_period);
    if (m < 0.0) m += period;
    if (m >= period) m -= period;
    if (!(m >= 0.0 && m < period)) m = 0.0;
    uint32_t a = (uint32_t)m, b = a + 1 == (uint32_t)period ? 0 : a + 1, n = axis->n;
    if (axis->wrap == RTPBR_WRAP_MIRRORED_REPEAT) { // texel i of the mirrored copy is texel 2n - 1 - i
        a = a < n ? a : 2 * n - 1 - a;
        b = b < n ? b : 2 * n - 1 - b;
    }
    *i0 = a;
    *i1 = b;
}

typedef struct lt_rgb {
    float r, g, b;
} lt_rgb;

// Bilinear read of the decoded RGB at texel coordinates (x, y) less 1/2.
static lt_rgb lt_read(const lt_source *src, double x, double y)
{
    uint32_t x0, x1, y0, y1;
    float fx, fy;
    lt_axis_texels(x, &src->s, &x0, &x1, &fx);
    lt_axis_texels(y, &src->t, &y0, &y1, &fy);
    size_t row = (size_t)src->s.n * 4;
    const uint8_t *r0 = src->rgba + y0 * row, *r1 = src->rgba + y1 * row;
    const uint8_t *p00 = r0 + (size_t)x0 * 4, *p10 = r0 + (size_t)x1 * 4;
    const uint8_t *p01 = r1 + (size_t)x0 * 4, *p11 = r1 + (size_t)x1 * 4;
    const float *d = src->decode;
    float c[3];
    for (int i = 0; i < 3; ++i) {
        float top = d[p00[i]] + fx * (d[p10[i]] - d[p00[i]]);
        float bottom = d[p01[i]] + fx * (d[p11[i]] - d[p01[i]]);
        c[i] = top + fy * (bottom - top);
    }
    return (lt_rgb){c[0], c[1], c[2]};
}

// Supersamples per axis of a cell whose edge spans `texels` texels: two per texel, 2..16.
static int lt_samples(double texels)
{
    double n = ceil(2.0 * texels);
    return n <= 2.0 ? 2 : n >= LT_MAX_SAMPLES ? LT_MAX_SAMPLES : (int)n;
}

// Sample (i, j) of cell (x, y) is at s = (x ns + i + 1/2) / (ns S), t likewise; in texel
// coordinates less 1/2, (u W, v H) - 1/2 with (u, v) = uv0 + s du + t dv.
static void lt_level0(const lt_source *src, const float uv0[2], const float du[2], const float dv[2], float *out)
{
    double w = src->s.n, h = src->t.n;
    int ns = lt_samples(hypot(du[0] * w, du[1] * h) / LT_S);
    int nt = lt_samples(hypot(dv[0] * w, dv[1] * h) / LT_S);
    double ds = 1.0 / ((double)ns * LT_S), dt = 1.0 / ((double)nt * LT_S);
    double step_x = du[0] * w * ds, step_y = du[1] * h * ds; // per sample along s
    double inv = 1.0 / ((double)ns * nt);
    for (int y = 0; y < LT_S; ++y)
        for (int x = 0; x < LT_S; ++x) {
            double r = 0.0, g = 0.0, b = 0.0; // in registers: no chain through memory
            double s0 = (x * ns + 0.5) * ds;
            for (int j = 0; j < nt; ++j) {
                double t = (y * nt + j + 0.5) * dt;
                double x0 = (uv0[0] + s0 * du[0] + t * dv[0]) * w - 0.5;
                double y0 = (uv0[1] + s0 * du[1] + t * dv[1]) * h - 0.5;
                for (int i = 0; i < ns; ++i) {
                    lt_rgb c = lt_read(src, x0 + i * step_x, y0 + i * step_y);
                    r += c.r, g += c.g, b += c.b;
                }
            }
            float *texel = out + ((size_t)y * LT_S + x) * 4;
            texel[0] = (float)(r * inv), texel[1] = (float)(g * inv), texel[2] = (float)(b * inv);
            texel[3] = 1.0f;
        }
}

// Level k's weights along one axis (the same for both): output o of S >> k is
// sum over j in [first[o], first[o] + count[o]) of w[offset[o] + j - first[o]] * level0[j], the
// block mean over x in [o 2^k, (o + 1) 2^k) of the normalised blur at level-0 texel x.
typedef struct lt_weights {
    uint32_t first[LT_S], count[LT_S], offset[LT_S];
    double w[LT_WEIGHT_CAPACITY];
} lt_weights;

// Standard normal CDF: Phi(z) = erfc(-z / sqrt 2) / 2.
static double lt_phi(double z)
{
    return 0.5 * erfc(-z * 0.70710678118654752440);
}

static void lt_level_weights(uint32_t k, lt_weights *lw)
{
    double sigma = (double)(1u << k) / LT_HALF_MASS_RADIUS_PER_SIGMA;
    int radius = (int)ceil(LT_TRUNCATION_SIGMAS * sigma);
    if (radius > LT_S - 1) radius = LT_S - 1; // level-0 texels are at most S - 1 apart
    // The Gaussian integrated over the level-0 texel d texels away (level 0 is piecewise constant).
    double g[LT_S];
    for (int d = 0; d <= radius; ++d) g[d] = lt_phi((d + 0.5) / sigma) - lt_phi((d - 0.5) / sigma);
    // The blur of the light's indicator at each texel: the normalisation.
    double inv_norm[LT_S];
    for (int x = 0; x < LT_S; ++x) {
        double sum = 0.0;
        for (int j = x - radius; j <= x + radius; ++j)
            if (j >= 0 && j < LT_S) sum += g[j > x ? j - x : x - j];
        inv_norm[x] = 1.0 / sum;
    }
    int block = 1 << k;
    uint32_t offset = 0;
    for (int o = 0; o < LT_S >> k; ++o) {
        int lo = o * block - radius, hi = (o + 1) * block - 1 + radius;
        lo = lo < 0 ? 0 : lo;
        hi = hi > LT_S - 1 ? LT_S - 1 : hi;
        lw->first[o] = (uint32_t)lo;
        lw->count[o] = (uint32_t)(hi - lo + 1);
        lw->offset[o] = offset;
        for (int j = lo; j <= hi; ++j) {
            double sum = 0.0;
            for (int x = o * block; x < (o + 1) * block; ++x) {
                int d = j > x ? j - x : x - j;
                if (d <= radius) sum += g[d] * inv_norm[x];
            }
            lw->w[offset++] = sum / block;
        }
    }
}

// Level k from level 0: per output row, the column pass (all S columns), then the row pass.
static void lt_level(const float *level0, uint32_t k, lt_weights *lw, float *out)
{
    lt_level_weights(k, lw);
    int side = LT_S >> k;
    for (int o = 0; o < side; ++o) {
        double column[LT_S][3] = {{0.0}};
        const double *wo = lw->w + lw->offset[o];
        for (uint32_t i = 0; i < lw->count[o]; ++i) {
            const float *row = level0 + (size_t)(lw->first[o] + i) * LT_S * 4;
            for (int x = 0; x < LT_S; ++x)
                for (int c = 0; c < 3; ++c) column[x][c] += wo[i] * row[x * 4 + c];
        }
        for (int p = 0; p < side; ++p) {
            double acc[3] = {0.0, 0.0, 0.0};
            const double *wp = lw->w + lw->offset[p];
            for (uint32_t i = 0; i < lw->count[p]; ++i)
                for (int c = 0; c < 3; ++c) acc[c] += wp[i] * column[lw->first[p] + i][c];
            float *texel = out + ((size_t)o * side + p) * 4;
            for (int c = 0; c < 3; ++c) texel[c] = (float)acc[c];
            texel[3] = 1.0f;
        }
    }
}

static bool lt_finite2(const float v[2])
{
    return isfinite(v[0]) && isfinite(v[1]);
}

static bool lt_wrap_known(rtpbr_wrap wrap)
{
    return wrap == RTPBR_WRAP_REPEAT || wrap == RTPBR_WRAP_CLAMP_TO_EDGE || wrap == RTPBR_WRAP_MIRRORED_REPEAT;
}

int rtpbr_light_texture_prefilter(const rtpbr_texture_desc *src, const float uv0[2], const float du[2],
                                  const float dv[2], float *out)
{
    if (!src || !src->rgba || !uv0 || !du || !dv || !out) return -1;
    if (src->width == 0 || src->height == 0 || src->width > RTPBR_MAX_RENDER_SIZE ||
        src->height > RTPBR_MAX_RENDER_SIZE)
        return -1;
    if (!lt_wrap_known(src->wrap_s) || !lt_wrap_known(src->wrap_t)) return -1;
    if (!lt_finite2(uv0) || !lt_finite2(du) || !lt_finite2(dv)) return -1;

    lt_source source = {.rgba = src->rgba, .s = lt_axis_make(src->width, src->wrap_s),
                        .t = lt_axis_make(src->height, src->wrap_t)};
    for (int code = 0; code < 256; ++code)
        source.decode[code] = (float)(src->srgb ? lt_srgb_to_linear(code / 255.0) : code / 255.0);
    lt_level0(&source, uv0, du, dv, out);
    lt_weights weights;
    for (uint32_t k = 1; k < RTPBR_LIGHT_TEXTURE_LEVELS; ++k)
        lt_level(out, k, &weights, out + rtpbr_light_texture_level_offset(k));
    return 0;
}
