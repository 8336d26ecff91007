// Engine: tile classification (cull.comp). Each tile is shaded by the lighting variant of the
// most demanding material in it: the basic variant (metallic-roughness without clear coat,
// sheen or anisotropy) or the full one. A plain plane alone is all basic tiles; a small
// clear-coated quad over it makes the tiles it touches full. The plane's pixels in those full
// tiles must read what the basic variant gave them without the quad (the full variant shades a
// basic material the same), and the quad's own pixels must differ (the coat is shaded).
#include <math.h>
#include <stdlib.h>

#include "engine_test.h"

enum { W = 96, H = 64, TILE = RTPBR_TILE_SIZE_PIXELS };

static rtpbr_camera_desc test_tiles_camera(void)
{
    return (rtpbr_camera_desc){.position = {0.3f, -1.5f, 2.5f}, .target = {0.2f, 0.0f, 0.0f}, .yfov = 1.0f,
                               .znear = 0.1f, .zfar = 100.0f};
}

static float *render(rtpbr_context *ctx, bool with_quad)
{
    float plane[12];
    square_positions(4.0f, 0.0f, plane);
    // The quad, 0.3 x 0.3 at z = 0.01 near the plane's centre (a few tiles of the image).
    float quad[12];
    square_positions(0.15f, 0.01f, quad);
    for (int k = 0; k < 4; ++k) quad[3 * k] += 0.4f;
    rtpbr_material_desc materials[2] = {
        {.base_color = {0.6f, 0.5f, 0.4f}, .roughness = 0.45f},
        {.base_color = {0.2f, 0.3f, 0.8f}, .roughness = 0.6f, .clearcoat_factor = 1.0f, .clearcoat_roughness_factor = 0.1f},
    };
    rtpbr_mesh_desc meshes[2] = {
        {.positions = plane, .indices = square_indices, .vertex_count = 4, .index_count = 6, .material = 0},
        {.positions = quad, .indices = square_indices, .vertex_count = 4, .index_count = 6, .material = 1},
    };
    rtpbr_light_desc light = {.vertices = {{-1.0f, -0.5f, 1.2f}, {-1.0f, 0.7f, 1.5f}, {0.6f, 0.7f, 1.5f}, {0.6f, -0.5f, 1.2f}},
                              .vertex_count = 4, .emission = {3.0f, 2.0f, 1.0f}};
    rtpbr_camera_desc camera = test_tiles_camera();
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = meshes, .mesh_count = with_quad ? 2 : 1,
                                                                     .materials = materials, .material_count = 2,
                                                                     .lights = &light, .light_count = 1,
                                                                     .cameras = &camera, .camera_count = 1});
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){0}), RTPBR_SUCCESS);
    float *px = malloc(W * H * 16);
    assert_non_null(px);
    assert_int_equal(test_read_radiance(r, px, W * H * 16), RTPBR_SUCCESS);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
    return px;
}

static void full_tiles_shade_basic_materials_alike(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float *plain = render(ctx, false), *mixed = render(ctx, true);

    // Where the quad is, from the camera (test_plane_point, independent of the engine): its
    // pixels must show the coat; the plane's pixels in the tiles it touches (the full tiles)
    // must equal the basic variant's. Pixels within 0.03 of the quad's edge are left out
    // (parallax of its 0.01 height, edge pixels).
    rtpbr_camera_desc camera = test_tiles_camera();
    bool full_tile[(H + TILE - 1) / TILE][(W + TILE - 1) / TILE] = {{false}};
    int quad_pixels = 0, compared = 0;
    double worst = 0.0;
    for (int pass = 0; pass < 2; ++pass)
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double p[3];
                if (!test_plane_point(&camera, x, y, W, H, p)) continue;
                double edge = fmax(fabs(p[0] - 0.4), fabs(p[1])) - 0.15; // < 0: inside the quad
                const float *a = plain + 4 * (y * W + x), *b = mixed + 4 * (y * W + x);
                double d = fabs(a[0] - b[0]) + fabs(a[1] - b[1]) + fabs(a[2] - b[2]);
                double rel = d / (a[0] + a[1] + a[2]);
                if (pass == 0 && edge < 0.03) full_tile[y / TILE][x / TILE] = true;
                if (pass == 0 && edge < -0.03) {
                    quad_pixels++;
                    if (rel < 0.01) fail_msg("pixel (%d, %d) on the coated quad reads the plane (%.2e)", x, y, rel);
                }
                if (pass == 1 && edge > 0.03 && full_tile[y / TILE][x / TILE]) {
                    compared++;
                    if (rel > worst) worst = rel;
                }
            }
    printf("tile classes: %d quad pixels; %d plane pixels in full tiles, largest relative difference %.2e\n",
           quad_pixels, compared, worst);
    assert_true(quad_pixels >= 9);
    assert_true(compared >= 100);
    assert_true(worst < 1e-5);
    free(plain);
    free(mixed);
}

// A basic tile where no pixel can give the streak estimate any weight is shaded by the basic
// variant with the estimate compiled out (RTPBR_TILE_CLASS_BASIC_NO_STREAK, cull.comp's
// streak_possible): the same image. A sphere light among a tile's lights puts it in the spheres'
// basic class, which runs the estimate for its polygons wherever it applies. So a glossy metal
// floor under a wide panel low above its far part must read the same to 1e-5 (the classes'
// code compiled apart) with and without a sphere light too dim to add anything (1e-20),
// from views that put the floor's tiles in either class: low views toward the panel (the
// streak: 11 to 103 % of a pixel, test_engine_mc.c's ltc_streak_floor), steep ones (every
// pixel too steep for it), and views between, across the cone test's limit. Measured: 0 in
// every view (the same to the bit). Planted: every basic tile put in the class: up to 8.2;
// the cones' spreads taken as 0 (cull.comp): up to 0.61; every pixel steep from NoV 0.3: up
// to 0.52; the class's tiles left black: 1 in 18 of the 20 views (so the class is used).
static void basic_tiles_without_streak_alike(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    enum { SW = 128, SH = 96 };
    float plane[12];
    square_positions(4.0f, 0.0f, plane);
    rtpbr_light_desc lights[2] = {
        {.vertices = {{-0.8f, 1.5f, 0.12f}, {-0.8f, 1.9f, 0.12f}, {0.8f, 1.9f, 0.12f}, {0.8f, 1.5f, 0.12f}}, .vertex_count = 4,
         .emission = {20.0f, 20.0f, 20.0f}},
        {.type = RTPBR_LIGHT_POINT, .position = {0.0f, 0.0f, 3.0f}, .radius = 0.3f, .emission = {1e-20f, 1e-20f, 1e-20f}},
    };
    const float roughness[2] = {0.45f, 0.2f};
    const float elevation[5] = {0.08f, 0.25f, 0.5f, 0.8f, 1.3f}, azimuth[2] = {0.0f, 0.7f};
    double worst = 0.0;
    int compared = 0;
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = SW, .height = SH});
    for (int m = 0; m < 2; ++m)
        for (int e = 0; e < 5; ++e)
            for (int a = 0; a < 2; ++a) {
                // the camera 2.5 from (0, 0.6, 0), toward the panel's side (+y)
                float ce = cosf(elevation[e]), se = sinf(elevation[e]);
                rtpbr_camera_desc camera = {.position = {2.5f * ce * sinf(azimuth[a]), 0.6f - 2.5f * ce * cosf(azimuth[a]),
                                                         0.02f + 2.5f * se},
                                            .target = {0.0f, 0.6f, 0.0f}, .yfov = 0.8f, .znear = 0.05f, .zfar = 100.0f};
                rtpbr_material_desc copper = {.base_color = {0.95f, 0.64f, 0.54f}, .metallic = 1.0f, .roughness = roughness[m]};
                rtpbr_mesh_desc mesh = {.positions = plane, .indices = square_indices, .vertex_count = 4, .index_count = 6};
                float *px[2];
                for (int sphere = 0; sphere < 2; ++sphere) {
                    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){
                                                                 .meshes = &mesh, .mesh_count = 1, .materials = &copper,
                                                                 .material_count = 1, .lights = lights, .light_count = 1 + sphere,
                                                                 .cameras = &camera, .camera_count = 1});
                    px[sphere] = test_render_radiance(r, scene, &(rtpbr_render_desc){0}, SW, SH);
                    rtpbr_gpu_scene_destroy(scene);
                }
                double frame_worst = 0.0;
                for (int y = 0; y < SH; ++y)
                    for (int x = 0; x < SW; ++x) {
                        double p[3];
                        if (!test_plane_point(&camera, x, y, SW, SH, p) || fmax(fabs(p[0]), fabs(p[1])) > 3.9) continue;
                        const float *o = px[0] + 4 * (y * SW + x), *b = px[1] + 4 * (y * SW + x);
                        double d = fabs(o[0] - b[0]) + fabs(o[1] - b[1]) + fabs(o[2] - b[2]);
                        double rel = d / fmax(b[0] + b[1] + b[2], 1e-12);
                        compared++;
                        if (rel > frame_worst) frame_worst = rel;
                    }
                printf("streak tiles: roughness %.2f, view elevation %.2f azimuth %.1f: without and with the sphere, largest "
                       "relative difference %.2e\n",
                       (double)roughness[m], (double)elevation[e], (double)azimuth[a], frame_worst);
                if (frame_worst > worst) worst = frame_worst;
                free(px[0]);
                free(px[1]);
            }
    rtpbr_renderer_destroy(r);
    assert_true(compared >= 20 * SW * SH / 4);
    assert_true(worst < 1e-5);
}

RTPBR_TEST_MAIN(test_env_case(full_tiles_shade_basic_materials_alike),
                test_env_case(basic_tiles_without_streak_alike))
