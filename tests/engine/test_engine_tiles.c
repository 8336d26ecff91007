// Engine: tile classification (cull.comp). Each tile is shaded by the lighting variant of the
// most demanding material in it: the basic variant (metallic-roughness without clear coat,
// sheen or anisotropy) or the full one. A plain plane alone is all basic tiles; a small
// clear-coated quad over it makes the tiles it touches full. The plane's pixels in those full
// tiles must read what the basic variant gave them without the quad (the full variant shades a
// basic material the same), and the quad's own pixels must differ (the coat is shaded).
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

RTPBR_TEST_MAIN(test_env_case(full_tiles_shade_basic_materials_alike))
