#define _DEFAULT_SOURCE // M_PI
// Engine: a Lambertian plane under polygonal lights against the closed-form irradiance of a
// polygon (Lambert 1760; see Arvo 1995, "Applications of Irradiance Tensors"), computed here
// in double precision, independently of the shader library. Every pixel within 1%.
#include <stdlib.h>

#include "engine_test.h"

static void lambertian_plane(void **state)
{
    rtpbr_context *ctx = test_env_context(state);

    // The plane z = 0, [-4, 4]^2, albedo 0.8, no specular lobe, under a tilted quad facing down,
    // a two-sided triangle showing its back to the plane, and a one-sided hexagon facing away
    // from the plane (it must add nothing).
    test_lambert_scene ls;
    rtpbr_gpu_scene *scene = test_lambert_scene_create(ctx, &ls);
    enum { W = 120, H = 90 };
    // Supersampled, a pixel is the mean of 2 x 2 shading points around its centre: on this
    // smooth irradiance the same as its centre's within the 1% bound.
    for (uint32_t ss = 1; ss <= 2; ++ss)
    for (int ms = RTPBR_MULTISCATTER_ON; ms <= RTPBR_MULTISCATTER_OFF; ++ms) {
        rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H, .supersample = ss});
        float *px = test_render_radiance(r, scene, &(rtpbr_render_desc){.multiscatter = (rtpbr_multiscatter)ms}, W, H);
        int checked = 0;
        double worst = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double p[3]; // the pixel's point of the plane (the documented pinhole camera)
                if (!test_plane_point(&ls.camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
                double lambert[3];
                test_lambert_scene_radiance(&ls, p, lambert);
                const float *got = px + 4 * (y * W + x);
                for (int c = 0; c < 3; ++c) {
                    double expect = lambert[c];
                    double rel = fabs(got[c] - expect) / expect;
                    if (rel > worst) worst = rel;
                    if (rel > 0.01)
                        fail_msg("pixel (%d, %d) channel %d: %.6f, Lambert's formula %.6f (%.3f%%)", x, y, c, got[c],
                                 expect, 100.0 * rel);
                }
                ++checked;
            }
        printf("lambertian plane (multiscatter %s, supersample %u): %d pixels, largest relative error %.4f%%\n",
               ms == RTPBR_MULTISCATTER_ON ? "on" : "off", ss, checked, 100.0 * worst);
        assert_true(checked > W * H / 2);
        free(px);
        rtpbr_renderer_destroy(r);
    }
    rtpbr_gpu_scene_destroy(scene);
}

// A constant normal texture tilts the shading normal: the plane then matches Lambert's formula
// for the tilted normal, decoded here from the same 8-bit texel (n = 2 texel / 255 - 1, in the
// tangent frame T = +X, B = N x T = +Y, N = +Z), wherever the light is above the tilted horizon.
static void normal_mapped_plane(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float plane[12];
    square_positions(4.0f, 0.0f, plane);
    const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    const float tangents[16] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
    const uint8_t texel[4] = {204, 128, 230, 255}; // about (0.6, 0, 0.8): tilted toward +X
    rtpbr_texture_desc texture = {.width = 1, .height = 1, .rgba = texel};
    rtpbr_material_desc material = {.base_color = {0.8f, 0.8f, 0.8f}, .roughness = 1.0f, .flags = RTPBR_MATERIAL_NO_SPECULAR,
                                    .normal_texture = 1};
    rtpbr_mesh_desc mesh = {.positions = plane, .texcoords = uv, .tangents = tangents, .indices = square_indices,
                            .vertex_count = 4, .index_count = 6};
    rtpbr_light_desc light = {.vertices = {{-1.0f, -0.5f, 1.2f}, {-1.0f, 0.7f, 1.5f}, {0.6f, 0.7f, 1.5f}, {0.6f, -0.5f, 1.2f}},
                              .vertex_count = 4, .emission = {3.0f, 2.0f, 1.0f}};
    rtpbr_camera_desc camera = {.position = {0.0f, 0.0f, 3.0f}, .target = {0.0f, 0.0f, 0.0f}, .yfov = 1.2f,
                                .znear = 0.1f, .zfar = 100.0f};
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                     .materials = &material, .material_count = 1,
                                                                     .lights = &light, .light_count = 1,
                                                                     .cameras = &camera, .camera_count = 1,
                                                                     .textures = &texture, .texture_count = 1});
    enum { W = 80, H = 60 };
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){0}), RTPBR_SUCCESS);
    float *px = malloc(W * H * 16);
    assert_int_equal(test_read_radiance(r, px, W * H * 16), RTPBR_SUCCESS);
    double n[3] = {2.0 * texel[0] / 255.0 - 1.0, 2.0 * texel[1] / 255.0 - 1.0, 2.0 * texel[2] / 255.0 - 1.0};
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) n[k] /= nl;
    // Camera straight down the -Z axis, +Y up: pixel (x, y) sees the plane at
    // (ndc_x t aspect 3, -ndc_y t 3).
    double t = tan(0.5 * camera.yfov), aspect = (double)W / H;
    int checked = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double p[3] = {((x + 0.5) / W * 2.0 - 1.0) * t * aspect * 3.0, -((y + 0.5) / H * 2.0 - 1.0) * t * 3.0, 0.0};
            bool above = true;
            for (int v = 0; v < 4; ++v) {
                double d = 0.0;
                for (int k = 0; k < 3; ++k) d += n[k] * (light.vertices[v][k] - p[k]);
                above = above && d > 0.0;
            }
            if (!above || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
            double ff = test_form_factor(p, n, light.vertices, 4);
            const float *got = px + 4 * (y * W + x);
            for (int c = 0; c < 3; ++c) {
                double expect = 0.8 * light.emission[c] * ff;
                if (fabs(got[c] - expect) > 0.01 * expect)
                    fail_msg("pixel (%d, %d) channel %d: %.6f, Lambert with the mapped normal %.6f", x, y, c, got[c], expect);
            }
            ++checked;
        }
    printf("normal-mapped plane: %d pixels within 1%%\n", checked);
    assert_true(checked > W * H / 3);
    free(px);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// The G-buffer pass compiles each set of texture slots its materials use into a pipeline of its
// own (RTPBR_SPEC_GBUFFER_TEXTURES) and binds it per draw: a draw whose material has a texture
// must read it, one without must read as the white stand-in, in the same frame, and a material
// edited to gain or lose a texture (rtpbr_gpu_scene_set_material) must follow. A plane in two
// halves, each a mesh of its own material (Lambertian, no specular lobe), under a quad light:
// radiance is linear in the albedo, so the half whose material gains a base-colour texture
// (linear, one texel of 255, 0, 255: values every device reads exactly, 1 and 0; lavapipe reads
// 128 as 0.5, not 128 / 255) must read the untextured render times (1, 0, 1), and the other
// half and a material edited back must read the untextured render to the bit.
static void texture_slots_per_material(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    const float halves[2][12] = {{-4, -4, 0, 0, -4, 0, 0, 4, 0, -4, 4, 0}, {0, -4, 0, 4, -4, 0, 4, 4, 0, 0, 4, 0}};
    const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    rtpbr_mesh_desc meshes[2];
    for (uint32_t i = 0; i < 2; ++i)
        meshes[i] = (rtpbr_mesh_desc){.positions = halves[i], .texcoords = uv, .indices = square_indices,
                                      .vertex_count = 4, .index_count = 6, .material = i};
    const uint8_t texel[4] = {255, 0, 255, 255};
    rtpbr_texture_desc texture = {.width = 1, .height = 1, .rgba = texel};
    const rtpbr_material_desc plain = {.base_color = {0.8f, 0.8f, 0.8f}, .roughness = 1.0f,
                                       .flags = RTPBR_MATERIAL_NO_SPECULAR};
    rtpbr_material_desc textured = plain;
    textured.base_color_texture = 1;
    rtpbr_material_desc materials[2] = {plain, plain};
    rtpbr_light_desc light = {.vertices = {{-1.0f, -0.5f, 1.2f}, {-1.0f, 0.7f, 1.5f}, {0.6f, 0.7f, 1.5f}, {0.6f, -0.5f, 1.2f}},
                              .vertex_count = 4, .emission = {3.0f, 2.0f, 1.0f}};
    rtpbr_camera_desc camera = {.position = {0.0f, 0.0f, 3.0f}, .target = {0.0f, 0.0f, 0.0f}, .yfov = 1.2f,
                                .znear = 0.1f, .zfar = 100.0f};
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = meshes, .mesh_count = 2,
                                                                     .materials = materials, .material_count = 2,
                                                                     .lights = &light, .light_count = 1,
                                                                     .cameras = &camera, .camera_count = 1,
                                                                     .textures = &texture, .texture_count = 1});
    enum { W = 80, H = 60 };
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    float *base = test_render_radiance(r, scene, &(rtpbr_render_desc){0}, W, H);
    // (which half a pixel shows: the camera looks down -Z with +X to the right)
    // textured: bit 0 for material 0 (left half), bit 1 for material 1 (right half)
    const unsigned steps[] = {2u, 3u, 1u, 0u};
    for (size_t k = 0; k < sizeof steps / sizeof steps[0]; ++k) {
        for (uint32_t m = 0; m < 2; ++m)
            assert_int_equal(rtpbr_gpu_scene_set_material(scene, m, (steps[k] >> m) & 1u ? &textured : &plain),
                             RTPBR_SUCCESS);
        float *px = test_render_radiance(r, scene, &(rtpbr_render_desc){0}, W, H);
        int lit[2] = {0, 0};
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                if (x == W / 2 - 1 || x == W / 2) continue; // (the seam)
                uint32_t m = x < W / 2 ? 0u : 1u;
                bool on = (steps[k] >> m) & 1u;
                const float *got = px + 4 * (y * W + x), *ref = base + 4 * (y * W + x);
                for (int c = 0; c < 3; ++c) {
                    if (!on) {
                        if (got[c] != ref[c])
                            fail_msg("step %zu: untextured pixel (%d, %d) channel %d: %.9g, %.9g before", k, x, y, c,
                                     got[c], ref[c]);
                        continue;
                    }
                    double expect = ref[c] * (texel[c] / 255.0);
                    if (fabs(got[c] - expect) > 1e-5 * ref[c])
                        fail_msg("step %zu: textured pixel (%d, %d) channel %d: %.9g, the untextured %.9g x %d / 255 = %.9g",
                                 k, x, y, c, got[c], ref[c], texel[c], expect);
                }
                if (ref[0] > 0.01f) ++lit[m];
            }
        assert_true(lit[0] > W * H / 8 && lit[1] > W * H / 8); // both halves lit: the checks see light
        free(px);
    }
    printf("texture slots per material: 4 edits, every pixel of both halves as expected\n");
    free(base);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// Per-tile culling keeps its documented bound: on a Lambertian plane (albedo 0.8) the image
// with culling differs from the image without by at most 0.8 * cull_form_factor * the sum of
// the emissions of all lights (each culled light's form factor is below the threshold). It
// also prints the error relative to each pixel's unculled radiance (bench/README.md, "Many
// lights", compares culling bounds with it).
static void culling_bound(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float plane[12];
    rtpbr_material_desc material = test_lambert_material;
    rtpbr_mesh_desc mesh = test_square_mesh(30.0f, 0.0f, plane);
    enum { N = 256 };
    rtpbr_light_desc *lights = calloc(N, sizeof *lights);
    double emission_sum = 0.0;
    uint32_t seed = 12345u;
    for (int i = 0; i < N; ++i) { // small squares facing down (or, one in four, up), 0.5 to 3 m high
        seed = seed * 1664525u + 1013904223u;
        float x = -28.0f + 56.0f * (float)(seed >> 8) / 16777216.0f;
        seed = seed * 1664525u + 1013904223u;
        float y = -28.0f + 56.0f * (float)(seed >> 8) / 16777216.0f;
        float z = 0.5f + 2.5f * (float)(i % 7) / 6.0f, h = 0.1f + 0.05f * (float)(i % 5);
        bool up = i % 4 == 3;
        float v[4][3] = {{x - h, y - h, z}, {x - h, y + h, z}, {x + h, y + h, z}, {x + h, y - h, z}};
        for (int k = 0; k < 4; ++k) memcpy(lights[i].vertices[up ? 3 - k : k], v[k], sizeof v[k]);
        lights[i].vertex_count = 4;
        lights[i].emission[0] = lights[i].emission[1] = lights[i].emission[2] = 5.0f + (float)(i % 3);
        emission_sum += lights[i].emission[0];
    }
    rtpbr_camera_desc camera = {.position = {0.0f, -12.0f, 14.0f}, .yfov = 1.0f, .znear = 0.1f, .zfar = 200.0f};
    rtpbr_gpu_scene *scene = test_mesh_scene(ctx, &mesh, &material, lights, N, &camera);
    enum { W = 96, H = 64 };
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    float *culled = malloc(W * H * 16), *full = malloc(W * H * 16);
    const float threshold = 1e-3f;
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.light_cull_form_factor = threshold}), RTPBR_SUCCESS);
    assert_int_equal(test_read_radiance(r, culled, W * H * 16), RTPBR_SUCCESS);
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.light_cull_form_factor = -1.0f}), RTPBR_SUCCESS);
    assert_int_equal(test_read_radiance(r, full, W * H * 16), RTPBR_SUCCESS);
    // Per pixel, a light can be culled only if the documented test holds for the tile, and the
    // tile's box contains the pixel's point p, so only if A < cull_form_factor pi d^2 with d the
    // distance from p to any sphere around the light, which is at most the distance from p to
    // the light itself. The difference is therefore at most the sum, over the downward lights
    // with A < threshold pi dist(p, light)^2, of their Lambertian contribution 0.8 L FF(p)
    // (Lambert's formula, which the engine matches within 1%: lambertian_plane).
    const double n[3] = {0.0, 0.0, 1.0};
    double loose = 0.8 * threshold * emission_sum, worst = 0.0, worst_ratio = 0.0, mean_full = 0.0, worst_rel = 0.0,
           mean_rel = 0.0;
    int checked = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            int i = y * W + x;
            double d = fabs((double)full[4 * i] - culled[4 * i]);
            if (d > worst) worst = d;
            mean_full += full[4 * i] / (W * H);
            assert_true(culled[4 * i] <= full[4 * i] + 1e-5f * full[4 * i]); // culling only removes light
            double p[3];
            if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 29.5 || fabs(p[1]) > 29.5) continue;
            double bound = 0.0;
            for (int l = 0; l < N; ++l) {
                if (l % 4 == 3) continue; // faces up: lights nothing below it, culled or not
                const float *lo = lights[l].vertices[0], *hi = lights[l].vertices[2];
                double dx = fmax(fmax(lo[0] - p[0], p[0] - hi[0]), 0.0);
                double dy = fmax(fmax(lo[1] - p[1], p[1] - hi[1]), 0.0);
                double dist2 = dx * dx + dy * dy + (double)lo[2] * lo[2];
                double area = (double)(hi[0] - lo[0]) * (hi[1] - lo[1]);
                if (area < threshold * M_PI * dist2)
                    bound += 0.8 * lights[l].emission[0] * test_form_factor(p, n, lights[l].vertices, 4);
            }
            if (d > 1.01 * bound + 1e-6)
                fail_msg("pixel (%d, %d): culling removed %.4g, more than the cullable lights give (%.4g)", x, y, d,
                         bound);
            if (bound > 0.0 && d / bound > worst_ratio) worst_ratio = d / bound;
            if (full[4 * i] > 0.0f) worst_rel = fmax(worst_rel, d / full[4 * i]), mean_rel += d / full[4 * i];
            ++checked;
        }
    printf("culling (form factor < %g): largest difference %.3g (bound over all lights %.3g), largest fraction of "
           "the per-pixel bound %.3f, mean radiance %.3g, %d pixels; relative to the pixel: largest %.3g, mean %.3g\n",
           threshold, worst, loose, worst_ratio, mean_full, checked, worst_rel, mean_rel / checked);
    assert_true(checked > W * H / 2);
    assert_true(worst <= loose);
    assert_true(worst > 0.0); // something was culled: the test exercises the distance bound
    free(culled);
    free(full);
    free(lights);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// The tile masks' summary words (RTPBR_TILE_MASK_SUMMARY): with 1,024 lights of which only
// lights 33, 700 and 1023 can light the plane (the others face up, away from it: culled
// exactly), the lighting pass must find those three in mask words 1, 21 and 31 and nothing in
// the others. The culled image matches Lambert's formula for the three (within 1%, as
// lambertian_plane), and the frame with only those three lights to 1e-5.
static void culled_sparse_words(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float plane[12];
    rtpbr_material_desc material = test_lambert_material;
    rtpbr_mesh_desc mesh = test_square_mesh(4.0f, 0.0f, plane);
    enum { N = 1024 };
    static const int lit[3] = {33, 700, 1023};
    rtpbr_light_desc *lights = calloc(N, sizeof *lights), three[3];
    for (int i = 0; i < N; ++i) {
        bool down = i == lit[0] || i == lit[1] || i == lit[2];
        float x = -3.5f + 7.0f * (float)(i % 32) / 31.0f, y = -3.5f + 7.0f * (float)(i / 32) / 31.0f;
        float h = down ? 0.4f : 0.05f, z = down ? 1.0f + 0.25f * (float)(i % 3) : 2.0f;
        float v[4][3] = {{x - h, y - h, z}, {x - h, y + h, z}, {x + h, y + h, z}, {x + h, y - h, z}};
        for (int k = 0; k < 4; ++k) memcpy(lights[i].vertices[down ? k : 3 - k], v[k], sizeof v[k]);
        lights[i].vertex_count = 4;
        lights[i].emission[0] = lights[i].emission[1] = lights[i].emission[2] = down ? 4.0f : 50.0f;
    }
    for (int k = 0; k < 3; ++k) three[k] = lights[lit[k]];
    rtpbr_camera_desc camera = {.position = {0.0f, -5.0f, 6.0f}, .target = {0.0f, 0.0f, 0.0f}, .yfov = 1.0f,
                                .znear = 0.1f, .zfar = 100.0f};
    rtpbr_gpu_scene *scene = test_mesh_scene(ctx, &mesh, &material, lights, N, &camera);
    rtpbr_gpu_scene *only = test_mesh_scene(ctx, &mesh, &material, three, 3, &camera);
    enum { W = 96, H = 64 };
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    float *all = test_render_radiance(r, scene, &(rtpbr_render_desc){0}, W, H);
    float *alone = test_render_radiance(r, only, &(rtpbr_render_desc){0}, W, H);
    const double n[3] = {0.0, 0.0, 1.0};
    int checked = 0;
    double worst = 0.0, worst_alone = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            int i = y * W + x;
            double p[3];
            if (!test_plane_point(&camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
            double expect = 0.0;
            for (int k = 0; k < 3; ++k) expect += 0.8 * three[k].emission[0] * test_form_factor(p, n, three[k].vertices, 4);
            double rel = fabs(all[4 * i] - expect) / expect;
            worst = fmax(worst, rel);
            if (rel > 0.01)
                fail_msg("pixel (%d, %d): %.6f, Lambert's formula for lights 33, 700, 1023 %.6f", x, y, all[4 * i], expect);
            worst_alone = fmax(worst_alone, fabs((double)all[4 * i] - alone[4 * i]) / fmax(alone[4 * i], 1e-6));
            ++checked;
        }
    printf("1,024 lights, 3 lighting the plane (mask words 1, 21, 31): %d pixels, largest error against Lambert "
           "%.4f%%, against the 3-light frame %.3g\n", checked, 100.0 * worst, worst_alone);
    assert_true(checked > W * H / 2);
    assert_true(worst_alone <= 1e-5);
    free(all);
    free(alone);
    free(lights);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_gpu_scene_destroy(only);
}

// A regular n-gon of radius r at height z around (x, y), facing down (clockwise seen from above).
static rtpbr_light_desc down_polygon(uint32_t n, float x, float y, float z, float r, float emission)
{
    rtpbr_light_desc l = {.vertex_count = n, .emission = {emission, emission, emission}};
    for (uint32_t k = 0; k < n; ++k) {
        double a = -2.0 * M_PI * k / n + 0.3;
        l.vertices[k][0] = x + r * (float)cos(a);
        l.vertices[k][1] = y + r * (float)sin(a);
        l.vertices[k][2] = z;
    }
    return l;
}

// Every pixel of px (W x H, RGBA) that sees the 4 m square at z = 0 away from its edges against
// Lambert's formula for albedo 0.8 under lights (polygons: albedo Le F, F their form factor;
// point lights: albedo / pi x I cos / d^2), within 1 %.
static void check_lambert(const char *name, const rtpbr_camera_desc *camera, const float *px, int W, int H,
                          const rtpbr_light_desc *lights, uint32_t count)
{
    const double n[3] = {0.0, 0.0, 1.0};
    int checked = 0;
    double worst = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double p[3];
            if (!test_plane_point(camera, x, y, W, H, p) || fabs(p[0]) > 3.9 || fabs(p[1]) > 3.9) continue;
            double expect = 0.0;
            for (uint32_t l = 0; l < count; ++l) {
                if (lights[l].type == RTPBR_LIGHT_POINT) {
                    double d[3] = {lights[l].position[0] - p[0], lights[l].position[1] - p[1], lights[l].position[2] - p[2]};
                    double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                    expect += 0.8 / M_PI * lights[l].emission[0] * (d[2] / sqrt(d2)) / d2;
                } else {
                    expect += 0.8 * lights[l].emission[0] * test_form_factor(p, n, lights[l].vertices, lights[l].vertex_count);
                }
            }
            double rel = fabs(px[4 * (y * W + x)] - expect) / expect;
            worst = fmax(worst, rel);
            if (rel > 0.01)
                fail_msg("%s: pixel (%d, %d): %.6f, Lambert's formula %.6f", name, x, y, px[4 * (y * W + x)], expect);
            ++checked;
        }
    printf("%s: %d pixels, largest error against Lambert %.4f%%\n", name, checked, 100.0 * worst);
    assert_true(checked > W * H / 2);
}

// A frame's lights choose how its LTC pipelines are specialized (rtpbr_lights_needs: polygons
// of at most 3, 4 or 8 vertices; punctual lights or none; shade_lights.glsl): frames of
// triangles only, of a triangle and a quad, of those and a pentagon and an octagon, and of the
// triangle, the quad and a point light, rendered one after the other by one renderer, each
// against Lambert's formula (the point light's: albedo / pi x I cos / d^2) within 1% at every
// pixel. A frame shaded by a pipeline too specialized for it loses a polygon's last edges (a
// quad shaded as a triangle) or its point light.
static void polygon_sizes(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float plane[12];
    rtpbr_mesh_desc mesh = test_square_mesh(4.0f, 0.0f, plane);
    const rtpbr_light_desc all[6] = {
        down_polygon(3, -1.5f, -1.0f, 1.2f, 0.6f, 3.0f), down_polygon(4, 1.5f, -1.0f, 1.0f, 0.5f, 2.0f),
        down_polygon(5, -1.5f, 1.5f, 1.4f, 0.6f, 2.5f),  down_polygon(8, 1.5f, 1.5f, 1.1f, 0.5f, 2.0f),
        down_polygon(3, 0.0f, 0.5f, 1.6f, 0.4f, 4.0f),
        {.type = RTPBR_LIGHT_POINT, .position = {0.3f, -0.2f, 1.3f}, .emission = {2.0f, 2.0f, 2.0f}},
    };
    static const struct {
        const char *name;
        uint32_t lights[5], count;
    } frames[] = {
        {"triangles", {0, 4}, 2},
        {"a triangle and a quad", {0, 1}, 2},
        {"up to an octagon", {0, 1, 2, 3, 4}, 5},
        {"triangles again", {4, 0}, 2},
        {"a quad and a point light", {0, 1, 5}, 3},
    };
    rtpbr_camera_desc camera = {.position = {0.0f, -5.0f, 6.0f}, .target = {0.0f, 0.0f, 0.0f}, .yfov = 1.0f,
                                .znear = 0.1f, .zfar = 100.0f};
    enum { W = 96, H = 64 };
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    for (size_t f = 0; f < sizeof frames / sizeof frames[0]; ++f) {
        rtpbr_light_desc lights[5];
        for (uint32_t l = 0; l < frames[f].count; ++l) lights[l] = all[frames[f].lights[l]];
        rtpbr_gpu_scene *scene = test_mesh_scene(ctx, &mesh, &test_lambert_material, lights, frames[f].count, &camera);
        float *px = test_render_radiance(r, scene, &(rtpbr_render_desc){0}, W, H);
        check_lambert(frames[f].name, &camera, px, W, H, lights, frames[f].count);
        free(px);
        rtpbr_gpu_scene_destroy(scene);
    }
    rtpbr_renderer_destroy(r);
}

// On a CPU device (lavapipe) the lighting pass reads a frame's lights from a uniform buffer where
// they fit, RTPBR_UNIFORM_LIGHTS_MAX (315) records, and from the storage buffer beyond
// (RTPBR_SPEC_LIGHTING_UNIFORM_LIGHTS, passes/lighting.c). Frames of the six lights of
// polygon_sizes alone, after 309 others (the last records of the uniform range: 315 lights),
// after 310 (316: the storage buffer) and after 600, one after the other in one renderer, each
// against Lambert's formula within 1 % at every pixel. The others are 1 cm squares 40 m up (each
// adds about 1e-8 of the light's radiance, summed in the reference too). A frame read from
// the uniform buffer past its range would lose its six lights (out-of-range reads are zero),
// and one whose records were read at the wrong stride or offset would light the floor wrong.
static void uniform_lights_limit(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float plane[12];
    rtpbr_mesh_desc mesh = test_square_mesh(4.0f, 0.0f, plane);
    enum { SIX = 6, MOST = 606 };
    rtpbr_light_desc *lights = calloc(MOST, sizeof *lights);
    assert_non_null(lights);
    const rtpbr_light_desc six[SIX] = {
        down_polygon(3, -1.5f, -1.0f, 1.2f, 0.6f, 3.0f), down_polygon(4, 1.5f, -1.0f, 1.0f, 0.5f, 2.0f),
        down_polygon(5, -1.5f, 1.5f, 1.4f, 0.6f, 2.5f),  down_polygon(8, 1.5f, 1.5f, 1.1f, 0.5f, 2.0f),
        down_polygon(3, 0.0f, 0.5f, 1.6f, 0.4f, 4.0f),
        {.type = RTPBR_LIGHT_POINT, .position = {0.3f, -0.2f, 1.3f}, .emission = {2.0f, 2.0f, 2.0f}},
    };
    static const uint32_t others[] = {0, 309, 310, 600};
    rtpbr_camera_desc camera = {.position = {0.0f, -5.0f, 6.0f}, .target = {0.0f, 0.0f, 0.0f}, .yfov = 1.0f,
                                .znear = 0.1f, .zfar = 100.0f};
    enum { W = 96, H = 64 };
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    for (size_t f = 0; f < sizeof others / sizeof others[0]; ++f) {
        uint32_t n = others[f];
        for (uint32_t l = 0; l < n; ++l)
            lights[l] = down_polygon(4, -3.0f + 0.01f * (float)l, 0.0f, 40.0f, 0.007f, 1.0f);
        for (uint32_t l = 0; l < SIX; ++l) lights[n + l] = six[l];
        rtpbr_gpu_scene *scene = test_mesh_scene(ctx, &mesh, &test_lambert_material, lights, n + SIX, &camera);
        float *px = test_render_radiance(r, scene, &(rtpbr_render_desc){0}, W, H);
        char name[64];
        snprintf(name, sizeof name, "six lights after %u others (%u lights)", n, n + SIX);
        check_lambert(name, &camera, px, W, H, lights, n + SIX);
        free(px);
        rtpbr_gpu_scene_destroy(scene);
    }
    rtpbr_renderer_destroy(r);
    free(lights);
}

// Supersampling resolves coverage: a square seen straight on, its edges off the pixel grid.
// Without supersampling every pixel is in or out (alpha 0 or 1); with s = 2 the edge pixels
// get the covered fraction of their 2 x 2 samples (alpha in quarters), and the alpha sum over
// the image, the square's area in pixels, stays within one pixel per edge pixel of the
// geometric area. Past the documented limits the renderer is refused.
static void supersampled_coverage(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float square[12];
    rtpbr_material_desc material = {.base_color = {0.5f, 0.5f, 0.5f}, .roughness = 1.0f, .flags = RTPBR_MATERIAL_NO_SPECULAR};
    rtpbr_mesh_desc mesh = test_square_mesh(0.37f, 0.0f, square);
    // An orthographic-like view: far away with a narrow field, the square 0.74 m wide.
    rtpbr_camera_desc camera = {.position = {0.013f, 0.021f, 100.0f}, .target = {0.013f, 0.021f, 0.0f},
                                .yfov = 0.01f, .znear = 50.0f, .zfar = 200.0f};
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                     .materials = &material, .material_count = 1,
                                                                     .cameras = &camera, .camera_count = 1});
    enum { W = 64, H = 64 };
    double pixel = 2.0 * 100.0 * tan(0.005) / H; // metres per pixel
    double area_px = (0.74 / pixel) * (0.74 / pixel);
    for (uint32_t ss = 1; ss <= 2; ++ss) {
        rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H, .supersample = ss});
        assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){0}), RTPBR_SUCCESS);
        float *px = malloc(W * H * 16);
        assert_int_equal(test_read_radiance(r, px, W * H * 16), RTPBR_SUCCESS);
        double coverage = 0.0;
        int partial = 0, off_grid = 0;
        for (int i = 0; i < W * H; ++i) {
            float a = px[4 * i + 3];
            coverage += a;
            if (a > 0.0f && a < 1.0f) ++partial;
            float q = a * (float)(ss * ss);
            if (fabsf(q - roundf(q)) > 1e-5f) ++off_grid; // not a whole number of samples
        }
        printf("supersample %u: coverage %.2f px (square %.2f px), %d partial pixels\n", ss, coverage, area_px, partial);
        assert_int_equal(off_grid, 0);
        if (ss == 1) assert_int_equal(partial, 0);
        // An edge pixel is partial when the edge passes between its sample rows (offsets 1/4
        // and 3/4): about half of the 4 x 47 edge pixels for edges at arbitrary offsets.
        else assert_true(partial > 0.74 / pixel);
        assert_true(fabs(coverage - area_px) < 4.0 * 0.74 / pixel);
        free(px);
        rtpbr_renderer_destroy(r);
    }
    rtpbr_renderer *bad = NULL;
    assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 8, .height = 8, .supersample = 5}, &bad),
                     RTPBR_ERROR_LIMIT_EXCEEDED);
    assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 8192, .height = 8, .supersample = 3}, &bad),
                     RTPBR_ERROR_LIMIT_EXCEEDED);
    assert_null(bad);
    rtpbr_gpu_scene_destroy(scene);
}

RTPBR_TEST_MAIN_SHARED_ENV(test_env_shared_case(supersampled_coverage),
                test_env_shared_case(lambertian_plane),
                test_env_shared_case(polygon_sizes),
                test_env_shared_case(uniform_lights_limit),
                test_env_shared_case(normal_mapped_plane),
                test_env_shared_case(texture_slots_per_material),
                test_env_shared_case(culling_bound),
                test_env_shared_case(culled_sparse_words))
