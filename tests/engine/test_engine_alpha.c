// glTF alphaMode (issue 28), read back from rendered pixels against closed forms: MASK cuts
// the quad out where baseColorFactor alpha x texture alpha < alphaCutoff (the white furnace
// box shows through), BLEND draws it over what is behind as 0.5 quad + 0.5 background, and a
// MASK occluder with holes lets the shadow rays through the holes. Scenes from
// tests/common/texture_scenes.h (the oracle renders them in tests/oracle/test_alpha.cpp).
#define _DEFAULT_SOURCE // mkstemps
#include "engine_gltf_file.h"

#include "texture_scenes.h"

#include <stdlib.h>

#include <rtpbr/rtpbr_gltf.h>

enum { N = 48 }; // image side

typedef struct rendered {
    float px[N * N * 4];
} rendered;

// Writes a scene to a temporary file, loads it through the glTF loader and renders it.
static void render_file(test_gltf_writer write, const void *user, uint32_t supersample, const rtpbr_render_desc *desc,
                        rendered *out)
{
    test_render_gltf(write, user, &(rtpbr_renderer_desc){.width = N, .height = N, .supersample = supersample}, desc,
                     out->px, sizeof out->px);
}

static int write_texture_scene(const void *user, const char *path)
{
    return texture_scene_write(user, path);
}

// MASK: a 4x4 red texture whose alpha is 255 and 128 in a checkerboard, baseColorFactor alpha
// 0.8, cutoff 0.5: coverage 0.8 (kept: red, the furnace's albedo) or 0.8 x 128/255 = 0.40 (cut:
// the box's emission 1 behind it).
static const uint8_t *mask_texture(void)
{
    static uint8_t t[4 * 4 * 4];
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            uint8_t *p = t + 4 * (4 * y + x);
            p[0] = 255, p[1] = 0, p[2] = 0, p[3] = (x + y) % 2 ? 128 : 255;
        }
    return t;
}

static void test_mask_cutout(void **state)
{
    (void)state;
    texture_scene s = texture_scene_quad(4, 4, mask_texture(), 33071, 9728);
    s.alpha_mode = 1;
    s.base_alpha = 0.8f;
    s.alpha_cutoff = 0.5f;
    rendered *img = malloc(sizeof *img);
    render_file(write_texture_scene, &s, 1, &(rtpbr_render_desc){0}, img);
    int cut = 0, kept = 0;
    for (uint32_t py = 0; py < N; ++py)
        for (uint32_t px = 0; px < N; ++px) {
            double x, y, uv[2], du, dv;
            texture_scene_pixel_point(px, py, N, &x, &y);
            texture_scene_uv(&s, x, y, uv);
            int tx = texture_scene_texel(uv[0], s.wrap_s, 4, &du), ty = texture_scene_texel(uv[1], s.wrap_t, 4, &dv);
            if (du < 0.1 || dv < 0.1) continue;
            bool is_cut = (tx + ty) % 2 != 0;
            const float *p = img->px + 4 * (py * N + px);
            double expected[3] = {1.0, is_cut ? 1.0 : 0.0, is_cut ? 1.0 : 0.0};
            for (int c = 0; c < 3; ++c)
                if (fabs(p[c] - expected[c]) > 0.05)
                    fail_msg("MASK: pixel (%u, %u) (texel %d, %d, %s) is (%g, %g, %g)", px, py, tx, ty,
                             is_cut ? "cut" : "kept", p[0], p[1], p[2]);
            is_cut ? ++cut : ++kept;
        }
    assert_true(cut > N * N / 4 && kept > N * N / 4);
    free(img);
}

// BLEND: the red quad at alpha 0.5 over the box (emission 1): 0.5 (1, 0, 0) + 0.5 (1, 1, 1),
// at 1x and 2x supersampling (the forward pass draws into the shading-size image).
static void test_blend_half(void **state)
{
    (void)state;
    texture_scene s = texture_scene_red_quad();
    s.alpha_mode = 2;
    s.base_alpha = 0.5f;
    rendered *img = malloc(sizeof *img);
    for (uint32_t ss = 1; ss <= 2; ++ss) {
        render_file(write_texture_scene, &s, ss, &(rtpbr_render_desc){0}, img);
        for (uint32_t py = 0; py < N; ++py)
            for (uint32_t px = 0; px < N; ++px) {
                const float *p = img->px + 4 * (py * N + px);
                const double expected[3] = {1.0, 0.5, 0.5};
                for (int c = 0; c < 3; ++c)
                    if (fabs(p[c] - expected[c]) > 0.03)
                        fail_msg("BLEND (supersample %u): pixel (%u, %u) is (%g, %g, %g), expected (1, 0.5, 0.5)", ss,
                                 px, py, p[0], p[1], p[2]);
            }
    }
    free(img);
}

// Shadows: the occluder's texture is cut (alpha 0) in its left column and solid (255) in its
// right one; the floor is lit below the left half and shadowed below the right half. With
// alphaMode OPAQUE instead (the control), both halves are shadowed.
typedef struct shadow_scene {
    int opaque;
} shadow_scene;

static int write_shadow_scene(const void *user, const char *path)
{
    static const uint8_t t[16] = {255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 255};
    return alpha_shadow_scene_write(2, 2, t, ((const shadow_scene *)user)->opaque, path);
}

// The mean red radiance of the floor's pixels with x in [x0, x1] (|y| < 0.8).
static double floor_mean(const rendered *img, double x0, double x1)
{
    double sum = 0.0;
    int n = 0;
    for (uint32_t py = 0; py < N; ++py)
        for (uint32_t px = 0; px < N; ++px) {
            double x, y;
            texture_scene_pixel_point(px, py, N, &x, &y);
            if (x < x0 || x > x1 || fabs(y) > 0.8) continue;
            sum += img->px[4 * (py * N + px)];
            ++n;
        }
    assert_true(n > 0);
    return sum / n;
}

static void test_mask_shadow(void **state)
{
    (void)state;
    rendered *img = malloc(sizeof *img);
    const rtpbr_render_desc shadows = {.shadows = RTPBR_SHADOWS_ON, .shadow_samples = 16};
    render_file(write_shadow_scene, &(shadow_scene){0}, 1, &(rtpbr_render_desc){0}, img);
    double unshadowed = floor_mean(img, -0.9, -0.25);
    assert_true(unshadowed > 0.01);
    render_file(write_shadow_scene, &(shadow_scene){0}, 1, &shadows, img);
    double holes = floor_mean(img, -0.9, -0.25), solid = floor_mean(img, 0.25, 0.9);
    render_file(write_shadow_scene, &(shadow_scene){1}, 1, &shadows, img);
    double opaque = floor_mean(img, -0.9, -0.25);
    fprintf(stderr, "floor: unshadowed %g, below the holes %g, below the solid half %g, below an opaque occluder %g\n",
            unshadowed, holes, solid, opaque);
    assert_true(holes > 0.9 * unshadowed);
    assert_true(solid < 0.05 * unshadowed);
    assert_true(opaque < 0.05 * unshadowed);
    free(img);
}

// The shadow rays test an alpha only where the scene has a MASK or BLEND material (the trace's
// pipeline is chosen per frame, passes/shadow.c) and only on the triangles flagged as such
// (e1.w, kept by rtpbr_gpu_scene_set_material, bvh.c). Editing the OPAQUE occluder to MASK, back
// and to MASK again in one scene must switch both: the holes shadowed, lit, shadowed, lit.
static void test_mask_shadow_edit(void **state)
{
    (void)state;
    char path[] = "/tmp/rtpbr-engine-scene-XXXXXX.gltf";
    test_gltf_file(path, write_shadow_scene, &(shadow_scene){1});
    rtpbr_gltf_scene *loaded = NULL;
    rtpbr_gltf_result loaded_result = rtpbr_gltf_load(path, NULL, &loaded);
    unlink(path);
    assert_int_equal(loaded_result, RTPBR_GLTF_SUCCESS);
    test_log log = {0};
    rtpbr_context *ctx = test_context(&log);
    rtpbr_gpu_scene *scene = NULL;
    assert_int_equal(rtpbr_gpu_scene_from_loaded(ctx, loaded, &scene), RTPBR_SUCCESS);
    rtpbr_material_desc opaque;
    rtpbr_material_desc_from_loaded(loaded, 1, &opaque); // the occluder's
    rtpbr_gltf_destroy(loaded);
    assert_int_equal(opaque.alpha_mode, RTPBR_ALPHA_OPAQUE);
    rtpbr_material_desc mask = opaque;
    mask.alpha_mode = RTPBR_ALPHA_MASK; // alpha_cutoff: glTF's default, 0.5
    rtpbr_renderer *renderer = test_renderer(ctx, &(rtpbr_renderer_desc){.width = N, .height = N});
    const rtpbr_render_desc shadows = {.shadows = RTPBR_SHADOWS_ON, .shadow_samples = 16};
    rendered *img = malloc(sizeof *img);
    double holes[4], solid[4];
    const rtpbr_material_desc *edits[4] = {NULL, &mask, &opaque, &mask};
    for (int i = 0; i < 4; ++i) {
        if (edits[i]) assert_int_equal(rtpbr_gpu_scene_set_material(scene, 1, edits[i]), RTPBR_SUCCESS);
        assert_int_equal(rtpbr_render(renderer, scene, &shadows), RTPBR_SUCCESS);
        assert_int_equal(test_read_radiance(renderer, img->px, sizeof img->px), RTPBR_SUCCESS);
        holes[i] = floor_mean(img, -0.9, -0.25);
        solid[i] = floor_mean(img, 0.25, 0.9);
    }
    fprintf(stderr, "below the holes: OPAQUE %g, edited to MASK %g, to OPAQUE %g, to MASK %g (solid half %g %g %g %g)\n",
            holes[0], holes[1], holes[2], holes[3], solid[0], solid[1], solid[2], solid[3]);
    assert_true(holes[1] > 0.01);
    assert_true(holes[0] < 0.05 * holes[1]);
    assert_true(holes[2] == holes[0]); // the same frames as before the edits
    assert_true(holes[3] == holes[1]);
    for (int i = 0; i < 4; ++i) assert_true(solid[i] < 0.05 * holes[1]);
    free(img);
    rtpbr_renderer_destroy(renderer);
    rtpbr_gpu_scene_destroy(scene);
    test_context_done(ctx, &log);
}

RTPBR_TEST_MAIN_SHARED_ENV(test_env_shared_case(test_mask_cutout),
                test_env_shared_case(test_blend_half),
                test_env_shared_case(test_mask_shadow),
                test_env_shared_case(test_mask_shadow_edit))
