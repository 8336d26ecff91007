// Textures as glTF means them (issue 28), read back from rendered pixels: sampler wrap modes
// (repeat, clamp, mirror, per axis), KHR_texture_transform with a texCoord override, back faces
// of single-sided materials, mipmaps against aliasing, and the KHR clearcoat, sheen and
// specular textures. Scenes from
// tests/common/texture_scenes.h (also rendered by the oracle in tests/oracle); expectations in
// closed form. A textured Lambertian quad in a white furnace: radiance = base colour.
#define _DEFAULT_SOURCE // mkstemps
#include "engine_gltf_file.h"

#include "texture_scenes.h"

#include <stdlib.h>

enum { N = 48 }; // image side

// Four distinct colours (sRGB texels; linear values: 1 or 0 in each channel).
static const uint8_t palette_2x2[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 0, 255};

typedef struct rendered {
    float px[N * N * 4];
} rendered;

static int write_texture_scene(const void *user, const char *path)
{
    return texture_scene_write(user, path);
}

// Writes the scene to a temporary file, loads it through the glTF loader and renders it with
// the desc.
static void render_scene_with(const texture_scene *s, const rtpbr_render_desc *desc, rendered *out)
{
    test_render_gltf(write_texture_scene, s, &(rtpbr_renderer_desc){.width = N, .height = N}, desc, out->px,
                     sizeof out->px);
}

static void render_scene(const texture_scene *s, rendered *out)
{
    render_scene_with(s, &(rtpbr_render_desc){0}, out);
}

// The pixel's colour must be texel (tx, ty) of a 2x2 palette texture (linear 0/1 channels).
static void expect_texel(const rendered *img, uint32_t px, uint32_t py, const uint8_t *texels, uint32_t w, int tx,
                         int ty, const char *what)
{
    const float *p = img->px + 4 * (py * N + px);
    const uint8_t *t = texels + 4 * ((size_t)ty * w + (size_t)tx);
    for (int c = 0; c < 3; ++c) {
        double expected = texture_scene_srgb_to_linear(t[c]);
        if (fabs(p[c] - expected) > 0.05) {
            fail_msg("%s: pixel (%u, %u) is (%g, %g, %g), expected texel (%d, %d) = (%g, %g, %g)", what, px, py, p[0],
                     p[1], p[2], tx, ty, texture_scene_srgb_to_linear(t[0]), texture_scene_srgb_to_linear(t[1]),
                     texture_scene_srgb_to_linear(t[2]));
        }
    }
}

// Every pixel away from texel edges shows the texel the wrap modes select, nearest filtering.
static void check_wrap(int wrap_s, int wrap_t, const char *what)
{
    texture_scene s = {
        .texture_width = 2, .texture_height = 2, .rgba = palette_2x2, .wrap_s = wrap_s, .wrap_t = wrap_t,
        .mag_filter = 9728, .min_filter = 9728, .uv_min = {-1.0f, -1.0f}, .uv_max = {2.0f, 2.0f}, .texcoord = -1,
    };
    rendered *img = malloc(sizeof *img);
    render_scene(&s, img);
    int checked = 0;
    for (uint32_t py = 0; py < N; ++py)
        for (uint32_t px = 0; px < N; ++px) {
            double x, y, uv[2], du, dv;
            texture_scene_pixel_point(px, py, N, &x, &y);
            texture_scene_uv(&s, x, y, uv);
            int tx = texture_scene_texel(uv[0], wrap_s, 2, &du), ty = texture_scene_texel(uv[1], wrap_t, 2, &dv);
            if (du < 0.15 || dv < 0.15) continue; // a pixel (1/8 texel) away from edges
            expect_texel(img, px, py, palette_2x2, 2, tx, ty, what);
            ++checked;
        }
    assert_true(checked > N * N / 2);
    free(img);
}

static void test_wrap_repeat(void **state)
{
    (void)state;
    check_wrap(10497, 10497, "repeat");
}

static void test_wrap_clamp(void **state)
{
    (void)state;
    check_wrap(33071, 33071, "clamp");
}

static void test_wrap_mirror(void **state)
{
    (void)state;
    check_wrap(33648, 33648, "mirror");
}

static void test_wrap_per_axis(void **state)
{
    (void)state;
    check_wrap(33071, 33648, "clamp S, mirror T");
    check_wrap(33648, 10497, "mirror S, repeat T");
}

// KHR_texture_transform with offset, rotation and scale, read through TEXCOORD_1 (the
// transform's texCoord override; TEXCOORD_0 is all zero). Expected texel from the closed form
// of texture_scenes.h.
static void test_texture_transform(void **state)
{
    (void)state;
    uint8_t texels[64]; // 16 distinct colours
    texture_scene_distinct_texels(texels);
    texture_scene s = texture_scene_transformed_quad(texels);
    rendered *img = malloc(sizeof *img);
    render_scene(&s, img);
    int checked = 0;
    for (uint32_t py = 0; py < N; ++py)
        for (uint32_t px = 0; px < N; ++px) {
            double x, y, uv[2], t[2], du, dv;
            texture_scene_pixel_point(px, py, N, &x, &y);
            texture_scene_uv(&s, x, y, uv);
            texture_scene_transform(&s, uv, t);
            int tx = texture_scene_texel(t[0], 10497, 4, &du), ty = texture_scene_texel(t[1], 10497, 4, &dv);
            if (du < 0.2 || dv < 0.2) continue;
            expect_texel(img, px, py, texels, 4, tx, ty, "texture transform");
            ++checked;
        }
    assert_true(checked > N * N / 4);
    free(img);
}

// doubleSided false: a quad seen from behind is not drawn (the white box behind it shows);
// double-sided, the same quad is drawn.
static void test_single_sided_back_face(void **state)
{
    (void)state;
    texture_scene s = texture_scene_red_quad();
    s.facing_away = 1;
    rendered *img = malloc(sizeof *img);
    render_scene(&s, img);
    // The emissive box (radiance 1, plus what its black dielectric faces reflect of each other).
    for (uint32_t i = 0; i < N * N; ++i)
        for (int c = 0; c < 3; ++c) assert_float_equal(img->px[4 * i + c], 1.0f, 0.05f);
    s.double_sided = 1;
    render_scene(&s, img);
    const float *centre = img->px + 4 * (N / 2 * N + N / 2);
    assert_true(centre[0] > 0.9f && centre[1] < 0.05f && centre[2] < 0.05f);
    free(img);
}

// Mipmaps: a 1-texel checkerboard minified about 21x (16 repeats over 48 pixels) averages to
// its mean, 0.5, with the default (trilinear) filter; without mipmaps (minFilter LINEAR) the
// pixels alias (the control that shows the test can fail).
static void checkerboard_stats(int min_filter, double *mean, double *max_deviation)
{
    enum { T = 64 };
    uint8_t *texels = malloc(4 * T * T);
    for (int y = 0; y < T; ++y)
        for (int x = 0; x < T; ++x) {
            uint8_t v = (x + y) & 1 ? 255 : 0;
            uint8_t *t = texels + 4 * (y * T + x);
            t[0] = t[1] = t[2] = v, t[3] = 255;
        }
    texture_scene s = {
        .texture_width = T, .texture_height = T, .rgba = texels, .wrap_s = 10497, .wrap_t = 10497,
        .min_filter = min_filter, .uv_min = {0.0f, 0.0f}, .uv_max = {16.0f, 16.0f}, .texcoord = -1,
    };
    rendered *img = malloc(sizeof *img);
    render_scene(&s, img);
    double sum = 0.0, dev = 0.0;
    for (uint32_t i = 0; i < N * N; ++i) sum += img->px[4 * i];
    *mean = sum / (N * N);
    for (uint32_t i = 0; i < N * N; ++i) dev = fmax(dev, fabs(img->px[4 * i] - 0.5));
    *max_deviation = dev;
    free(img);
    free(texels);
}

static void test_mipmaps_average(void **state)
{
    (void)state;
    double mean, dev;
    checkerboard_stats(0, &mean, &dev); // no minFilter: trilinear (anisotropic where available)
    fprintf(stderr, "trilinear: mean %.4f, largest deviation from 0.5 %.4f\n", mean, dev);
    assert_true(fabs(mean - 0.5) < 0.02);
    assert_true(dev < 0.05);
    checkerboard_stats(9729, &mean, &dev); // LINEAR, level 0 only
    fprintf(stderr, "no mipmaps: mean %.4f, largest deviation from 0.5 %.4f\n", mean, dev);
    assert_true(dev > 0.2);
}

// ---- Extension textures (issue 28) ----------------------------------------------------------
// A 2x1 texture (nearest, clamped) over the quad: its left half reads texel 0, its right half
// texel 1. The texture multiplies one factor of a KHR extension on a black base in the white
// furnace; each half must render as the same scene without the texture and with the factor
// set to factor x that half's texel (the factor path, which the validation scenes hold to the
// oracle), in the LTC pass and in the Monte Carlo pass (same seed); and the two halves must
// differ, or the texture was not read.
typedef struct extension_case {
    const char *name;
    const char *extension;  // KHR_materials_*
    const char *textured;   // the extension's object, with the texture as {"index":0}
    const char *factor;     // the same without the texture, %1$g the factor (printf)
    uint8_t texels[8];      // RGBA of texel 0 (left half), texel 1 (right half)
    float values[2];        // the factor each half amounts to
} extension_case;

static const extension_case extension_cases[] = {
    {"clearcoat", "KHR_materials_clearcoat",
     "{\"clearcoatFactor\":0.8,\"clearcoatRoughnessFactor\":0.3,\"clearcoatTexture\":{\"index\":0}}",
     "{\"clearcoatFactor\":%1$g,\"clearcoatRoughnessFactor\":0.3}", {0, 0, 0, 255, 255, 0, 0, 255}, {0.0f, 0.8f}},
    {"clearcoat roughness", "KHR_materials_clearcoat",
     "{\"clearcoatFactor\":1,\"clearcoatRoughnessFactor\":1,\"clearcoatRoughnessTexture\":{\"index\":0}}",
     "{\"clearcoatFactor\":1,\"clearcoatRoughnessFactor\":%1$g}", {0, 51, 0, 255, 0, 255, 0, 255}, {0.2f, 1.0f}},
    {"sheen colour", "KHR_materials_sheen",
     "{\"sheenColorFactor\":[1,1,1],\"sheenRoughnessFactor\":0.5,\"sheenColorTexture\":{\"index\":0}}",
     "{\"sheenColorFactor\":[%1$g,%1$g,%1$g],\"sheenRoughnessFactor\":0.5}", {0, 0, 0, 255, 255, 255, 255, 255},
     {0.0f, 1.0f}},
    {"sheen roughness", "KHR_materials_sheen",
     "{\"sheenColorFactor\":[1,1,1],\"sheenRoughnessFactor\":1,\"sheenRoughnessTexture\":{\"index\":0}}",
     "{\"sheenColorFactor\":[1,1,1],\"sheenRoughnessFactor\":%1$g}", {255, 255, 255, 51, 255, 255, 255, 255},
     {0.2f, 1.0f}},
    {"specular", "KHR_materials_specular", "{\"specularFactor\":1,\"specularTexture\":{\"index\":0}}",
     "{\"specularFactor\":%1$g}", {255, 255, 255, 0, 255, 255, 255, 255}, {0.0f, 1.0f}},
    // (texel 0 sRGB 128 = linear 0.2158605; a black colour factor would remove the lobe in the
    // loader's mapping, where a black texel keeps F90)
    {"specular colour", "KHR_materials_specular",
     "{\"specularColorFactor\":[1,1,1],\"specularColorTexture\":{\"index\":0}}",
     "{\"specularColorFactor\":[%1$g,%1$g,%1$g]}", {128, 128, 128, 255, 255, 255, 255, 255},
     {0.2158605f, 1.0f}},
};

static void check_extension_case(const extension_case *c, const rtpbr_render_desc *desc, const char *pass)
{
    char textured[512], factor[2][512], used[64];
    snprintf(used, sizeof used, "\"%s\"", c->extension);
    snprintf(textured, sizeof textured, "\"%s\":%s", c->extension, c->textured);
    texture_scene s = {
        .texture_width = 2, .texture_height = 1, .rgba = c->texels, .wrap_s = 33071, .wrap_t = 33071,
        .mag_filter = 9728, .min_filter = 9728, .uv_min = {0.0f, 0.0f}, .uv_max = {1.0f, 1.0f}, .texcoord = -1,
        .material_extensions = textured, .extensions_used = used,
    };
    rendered *img = malloc(sizeof *img), *ref[2] = {malloc(sizeof *img), malloc(sizeof *img)};
    render_scene_with(&s, desc, img);
    for (int h = 0; h < 2; ++h) {
        char object[384];
        snprintf(object, sizeof object, c->factor, c->values[h]);
        snprintf(factor[h], sizeof factor[h], "\"%s\":%s", c->extension, object);
        s.material_extensions = factor[h];
        render_scene_with(&s, desc, ref[h]);
    }
    double worst = 0.0, contrast = 0.0;
    int contrast_count = 0;
    for (uint32_t py = 0; py < N; ++py)
        for (uint32_t px = 0; px < N; ++px) {
            if (px + 2 > N / 2 && px < N / 2 + 2) continue; // the texel edge
            int h = px >= N / 2;
            const float *p = img->px + 4 * (py * N + px), *q = ref[h]->px + 4 * (py * N + px);
            for (int k = 0; k < 3; ++k) {
                double d = fabs(p[k] - q[k]);
                if (d > worst) worst = d;
            }
            if (!h) {
                contrast += fabs(ref[1]->px[4 * (py * N + px)] - q[0]);
                ++contrast_count;
            }
        }
    contrast /= contrast_count;
    fprintf(stderr, "%s (%s): largest difference from the factor renders %.5f; the halves differ by %.4f\n", c->name,
            pass, worst, contrast);
    if (worst > 0.004)
        fail_msg("%s (%s): a half differs from its factor render by %g (%s / %s)", c->name, pass, worst, factor[0],
                 factor[1]);
    if (contrast < 2 * 0.004) // (twice the tolerance above: a half cannot be within it of both)
        fail_msg("%s (%s): the two references differ by only %g: the case cannot fail", c->name, pass, contrast);
    free(img), free(ref[0]), free(ref[1]);
}

static void test_extension_textures(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof extension_cases / sizeof extension_cases[0]; ++i)
        check_extension_case(&extension_cases[i], &(rtpbr_render_desc){0}, "LTC");
}

static void test_extension_textures_mc(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof extension_cases / sizeof extension_cases[0]; ++i)
        check_extension_case(&extension_cases[i], &(rtpbr_render_desc){.mc_samples = 16, .mc_seed = 7}, "Monte Carlo");
}

RTPBR_TEST_MAIN_SHARED_ENV(test_env_shared_case(test_wrap_repeat),
                test_env_shared_case(test_wrap_clamp),
                test_env_shared_case(test_wrap_mirror),
                test_env_shared_case(test_wrap_per_axis),
                test_env_shared_case(test_texture_transform),
                test_env_shared_case(test_single_sided_back_face),
                test_env_shared_case(test_mipmaps_average),
                test_env_shared_case(test_extension_textures),
                test_env_shared_case(test_extension_textures_mc))
