// Textured quad lights (rtpbr_light_desc.emission_texture, issue 30): a quad whose radiance is
// its emission times a texture, shaded with the LTC textured lookup (shaderlib
// ltc_textured.h, each lobe reading a chain prefiltered at load: engine/src/light_texture.c),
// by the Monte Carlo pass at the texture's point, and by the forward pass.
//   constant_texture   a constant texture c is the untextured quad at emission x c, on every
//                      pass and material (every level of the chain is c: exact up to half floats)
//   half_texture       a texture black on one half: against the untextured half quad (LTC's
//                      exact polygon for Lambert; its measured error for GGX); the Monte Carlo
//                      pass's mean within 4 standard errors of it; nothing brighter than the
//                      untextured whole quad anywhere
//   bad_textured       what is refused, with a message and no crash
#include <stdlib.h>

#include "engine_test.h"

enum { W = 96, H = 72, TEX = 64 };

static const rtpbr_camera_desc camera = {.position = {0.2f, -1.6f, 2.4f}, .target = {0.0f, 0.0f, 0.0f}, .yfov = 1.0f,
                                         .znear = 0.1f, .zfar = 100.0f};

// A 1 x 0.6 quad 0.8 above the plane z = 0, facing down: s along v1 - v0 (+Y), t along v3 - v0
// (+X). half: only its s < 1/2 part (the texture's left half), untextured.
static rtpbr_light_desc quad_light(float emission, bool half)
{
    float y1 = half ? 0.0f : 0.3f;
    rtpbr_light_desc l = {.vertex_count = 4,
                          .vertices = {{-0.5f, -0.3f, 0.8f}, {-0.5f, y1, 0.8f}, {0.5f, y1, 0.8f}, {0.5f, -0.3f, 0.8f}},
                          .emission = {emission, emission, emission}};
    return l;
}

// A TEX x TEX linear texture: every texel `value`, or (left_half) `value` where u < 1/2 and 0
// elsewhere.
static uint8_t *make_texture(uint8_t value, bool left_half)
{
    uint8_t *rgba = malloc(TEX * TEX * 4);
    assert_non_null(rgba);
    for (int y = 0; y < TEX; ++y)
        for (int x = 0; x < TEX; ++x)
            for (int c = 0; c < 4; ++c) rgba[4 * (y * TEX + x) + c] = c == 3 ? 255 : (!left_half || x < TEX / 2) ? value : 0;
    return rgba;
}

static const rtpbr_material_desc ggx_material = {.base_color = {0.9f, 0.8f, 0.7f}, .metallic = 1.0f, .roughness = 0.4f};
// a clear coat: the full lighting variant's tiles
static const rtpbr_material_desc coat_material = {.base_color = {0.3f, 0.5f, 0.7f}, .roughness = 0.6f,
                                                  .clearcoat_factor = 1.0f, .clearcoat_roughness_factor = 0.1f};

// The plane under `light` (with `texture`, or none), rendered with desc.
static float *render(rtpbr_context *ctx, const rtpbr_material_desc *material, const rtpbr_light_desc *light,
                     const uint8_t *texture, const rtpbr_render_desc *desc)
{
    float plane[12];
    rtpbr_mesh_desc mesh = test_square_mesh(3.0f, 0.0f, plane);
    rtpbr_texture_desc tex = {.width = TEX, .height = TEX, .rgba = texture};
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){
                                                 .meshes = &mesh, .mesh_count = 1, .materials = material,
                                                 .material_count = 1, .lights = light, .light_count = 1,
                                                 .cameras = &camera, .camera_count = 1, .textures = &tex,
                                                 .texture_count = texture ? 1 : 0});
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    float *px = test_render_radiance(r, scene, desc, W, H);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
    return px;
}

typedef struct pass {
    rtpbr_render_desc desc;
    bool blend; // the plane BLEND (alpha 1): the forward pass
    const char *what;
} pass;
static const pass passes[] = {
    {{0}, false, "LTC pass"},
    {{.mc_samples = 16, .mc_seed = 7}, false, "Monte Carlo pass"},
    {{0}, true, "forward pass"},
};

static void constant_texture(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const uint8_t value = 128;
    const double c = 128.0 / 255.0;
    uint8_t *texture = make_texture(value, false);
    const rtpbr_material_desc *materials[3] = {&test_lambert_material, &ggx_material, &coat_material};
    const char *names[3] = {"Lambert", "GGX", "clear coat"};
    for (int m = 0; m < 3; ++m)
        for (size_t p = 0; p < sizeof passes / sizeof passes[0]; ++p) {
            rtpbr_material_desc material = *materials[m];
            if (passes[p].blend) material.alpha_mode = RTPBR_ALPHA_BLEND, material.alpha = 1.0f;
            rtpbr_light_desc textured = quad_light(2.0f, false);
            textured.emission_texture = 1;
            rtpbr_light_desc plain = quad_light((float)(2.0 * c), false);
            float *got = render(ctx, &material, &textured, texture, &passes[p].desc);
            float *want = render(ctx, &material, &plain, NULL, &passes[p].desc);
            double worst = 0.0, peak = 0.0;
            int lit = 0;
            for (int i = 0; i < W * H; ++i)
                for (int k = 0; k < 3; ++k) {
                    peak = fmax(peak, want[4 * i + k]);
                    worst = fmax(worst, fabs((double)got[4 * i + k] - want[4 * i + k]) / fmax(want[4 * i + k], 1e-3));
                    lit += k == 0 && want[4 * i] > 1e-3f;
                }
            printf("constant texture, %s, %s: largest relative difference %.3g (peak %.3g, %d lit pixels)\n",
                   names[m], passes[p].what, worst, peak, lit);
            assert_true(lit > W * H / 4);
            // half floats (2^-11) and the Monte Carlo pass's bilinear reads: 2e-3; the Monte Carlo
            // pass draws the same samples for both (one light, the same seed)
            assert_true(worst < 2e-3);
            free(got);
            free(want);
        }
    free(texture);
}

static void half_texture(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    uint8_t *texture = make_texture(255, true);
    const rtpbr_material_desc *materials[3] = {&test_lambert_material, &ggx_material, &coat_material};
    const char *names[3] = {"Lambert", "GGX", "clear coat"};
    // of the peak: the largest and mean difference from the half quad (LTC pass; Lambert: the
    // half quad's LTC is exact, so this is the textured lookup's own error). Lambert's is the
    // method's weak case (ltc_textured.h): under a light as large as its height the lobe's
    // footprint is the whole quad, whose one blurred read is the texture's mean (1/2)
    // measured: worst 0.1736, 0.1287, 0.1126; mean 0.0287, 0.0051, 0.0144
    const double bound_worst[3] = {0.21, 0.16, 0.14}, bound_mean[3] = {0.035, 0.0065, 0.018};
    for (int m = 0; m < 3; ++m) {
        rtpbr_light_desc textured = quad_light(2.0f, false);
        textured.emission_texture = 1;
        rtpbr_light_desc halfq = quad_light(2.0f, true), whole = quad_light(2.0f, false);
        float *want = render(ctx, materials[m], &halfq, NULL, &passes[0].desc);
        float *upper = render(ctx, materials[m], &whole, NULL, &passes[0].desc);
        for (size_t p = 0; p < 2; ++p) {
            float *got = render(ctx, materials[m], &textured, texture, &passes[p].desc);
            double worst = 0.0, peak = 0.0, errSum = 0.0, sum = 0.0, sum2 = 0.0, wantSum = 0.0, over = 0.0;
            int n = 0;
            for (int i = 0; i < W * H; ++i) {
                double g = got[4 * i], w = want[4 * i];
                if (!(w > 0.0) && !(g > 0.0)) continue;
                peak = fmax(peak, w);
                worst = fmax(worst, fabs(g - w));
                errSum += fabs(g - w);
                sum += g - w, sum2 += (g - w) * (g - w), wantSum += w;
                over = fmax(over, g - upper[4 * i]);
                ++n;
            }
            if (getenv("RTPBR_TEXTURED_DUMP")) { // debugging: got | want as a PGM
                char name[64];
                snprintf(name, sizeof name, "/tmp/textured_%d_%zu.pgm", m, p);
                FILE *f = fopen(name, "wb");
                fprintf(f, "P5 %d %d 255\n", 2 * W, H);
                for (int y = H - 1; y >= 0; --y)
                    for (int x = 0; x < 2 * W; ++x) {
                        double v = (x < W ? got[4 * (y * W + x)] : want[4 * (y * W + x - W)]) / peak;
                        fputc((int)fmin(255.0, 255.0 * sqrt(fmax(v, 0.0))), f);
                    }
                fclose(f);
            }
            double mean = sum / n, se = sqrt(fmax(sum2 / n - mean * mean, 0.0) / n);
            printf("half texture, %s, %s: largest difference %.4f of the peak %.4g, mean |difference| %.4f of "
                   "it; mean difference %.3g (%.2f standard errors); above the whole quad by %.3g\n",
                   names[m], passes[p].what, worst / peak, peak, errSum / n / peak, mean,
                   se > 0.0 ? fabs(mean) / se : 0.0, over);
            assert_true(n > W * H / 4);
            if (p == 0) {
                assert_true(over <= 1e-3 * peak); // a texture of at most 1 adds no light
                assert_true(worst <= bound_worst[m] * peak);
                assert_true(errSum / n <= bound_mean[m] * peak);
            } else if (m == 0) {
                // the Monte Carlo pass reads the texture where each sample lands: unbiased
                // against the exact half quad (the step is at a texel edge of the chain)
                assert_true(fabs(mean) <= 4.0 * se + 2e-3 * wantSum / n);
            }
            free(got);
        }
        free(want);
        free(upper);
    }
    free(texture);
}

static void bad_textured(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    uint8_t *texture = make_texture(200, false);
    rtpbr_texture_desc tex = {.width = TEX, .height = TEX, .rgba = texture};
    float plane[12];
    rtpbr_mesh_desc mesh = test_square_mesh(3.0f, 0.0f, plane);
    rtpbr_light_desc cases[5];
    cases[0] = quad_light(1.0f, false), cases[0].emission_texture = 2;           // past the scene's textures
    cases[1] = quad_light(1.0f, false), cases[1].emission_texture = 1;           // not a parallelogram
    cases[1].vertices[2][0] = 0.7f;
    cases[2] = quad_light(1.0f, false), cases[2].emission_texture = 1;           // a triangle
    cases[2].vertex_count = 3;
    cases[3] = quad_light(1.0f, false), cases[3].emission_texture = 1;           // NaN coordinates
    cases[3].emission_uv[1][0] = NAN;
    cases[4] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DISK, .position = {0, 0, 1}, .direction = {0, 0, -1},
                                  .radius = 0.3f, .emission = {1, 1, 1}, .emission_texture = 1}; // a disk
    for (int i = 0; i < 5; ++i) {
        rtpbr_gpu_scene *scene = NULL;
        rtpbr_result r = rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                            .lights = &cases[i], .light_count = 1,
                                                                            .textures = &tex, .texture_count = 1},
                                                &scene);
        assert_int_equal(r, RTPBR_ERROR_INVALID_ARGUMENT);
        assert_null(scene);
    }
    // set_lights: the creation's texture and coordinates move with the quad; others are refused
    rtpbr_light_desc good = quad_light(1.0f, false);
    good.emission_texture = 1;
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1, .lights = &good,
                                                                     .light_count = 1, .textures = &tex,
                                                                     .texture_count = 1});
    rtpbr_light_desc moved = good;
    for (int v = 0; v < 4; ++v) moved.vertices[v][2] += 0.2f;
    assert_int_equal(rtpbr_gpu_scene_set_lights(scene, &moved, 1), RTPBR_SUCCESS);
    rtpbr_light_desc other = good;
    other.emission_uv[1][0] = 0.5f; // other coordinates: a chain the scene does not have
    assert_int_equal(rtpbr_gpu_scene_set_lights(scene, &other, 1), RTPBR_ERROR_INVALID_ARGUMENT);
    rtpbr_gpu_scene_destroy(scene);
    // a light set has no textures
    rtpbr_light_set *set = NULL;
    assert_int_equal(rtpbr_light_set_create(ctx, &(rtpbr_light_set_desc){.frames_in_flight = 1}, &set), RTPBR_SUCCESS);
    assert_int_equal(rtpbr_light_set_update(set, 0, &good, 1), RTPBR_ERROR_INVALID_ARGUMENT);
    rtpbr_light_set_destroy(set);
    free(texture);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(constant_texture),
        cmocka_unit_test(half_texture),
        cmocka_unit_test(bad_textured),
    };
    return cmocka_run_group_tests(tests, test_env_setup, test_env_teardown);
}
