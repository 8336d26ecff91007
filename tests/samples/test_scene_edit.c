// The viewer's light edits (samples/viewer/scene_edit.c) against closed forms: a regular
// n-gon's area, right-handed rotations, areas under scaling, the tracked transform that moves
// the uploaded polygon in place; the loader-to-viewer mapping of the bundled quad_light and
// showcase scenes (numbers read from scenes.json by hand); and picking by ray.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include "test_main.h"
#include <math.h>

#include "scene_edit.h"

static const double pi = 3.14159265358979323846;

// Area by the shoelace formula on the polygon's projection onto the plane with normal n.
static double polygon_area(const viewer_light *l)
{
    double c[3] = {0, 0, 0};
    for (uint32_t i = 0; i < l->vertex_count; ++i) {
        const float *a = l->vertices[i], *b = l->vertices[(i + 1) % l->vertex_count];
        c[0] += (double)a[1] * b[2] - (double)a[2] * b[1];
        c[1] += (double)a[2] * b[0] - (double)a[0] * b[2];
        c[2] += (double)a[0] * b[1] - (double)a[1] * b[0];
    }
    return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

// A 2 x 2 square at height 3 facing down (counter-clockwise seen from below).
static viewer_light square(void)
{
    viewer_light l = {.vertex_count = 4, .color = {1, 1, 1}, .intensity = 1,
                      .transform = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    const float v[4][3] = {{1, 3, 1}, {-1, 3, 1}, {-1, 3, -1}, {1, 3, -1}};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) l.vertices[i][c] = v[i][c];
    return l;
}

static void test_vertex_count(void **state)
{
    (void)state;
    for (uint32_t n = 3; n <= 8; ++n) {
        viewer_light l = square();
        viewer_light_set_vertex_count(&l, n);
        assert_int_equal(l.vertex_count, n);
        float center[3], normal[3];
        viewer_light_center(&l, center);
        viewer_light_normal(&l, normal);
        assert_float_equal(center[0], 0.0f, 1e-5f);
        assert_float_equal(center[1], 3.0f, 1e-5f);
        assert_float_equal(center[2], 0.0f, 1e-5f);
        assert_float_equal(normal[1], -1.0f, 1e-5f); // still facing down
        // Circumradius sqrt(2) (the square's mean radius): area = n/2 R^2 sin(2 pi / n).
        assert_float_equal(polygon_area(&l), 0.5 * n * 2.0 * sin(2.0 * pi / n), 1e-5);
    }
    viewer_light l = square();
    viewer_light_set_vertex_count(&l, 9); // out of range: unchanged
    viewer_light_set_vertex_count(&l, 2);
    assert_int_equal(l.vertex_count, 4);
}

static void test_rotate_scale_translate(void **state)
{
    (void)state;
    viewer_light l = square();
    viewer_light_rotate(&l, 1, (float)(pi / 2)); // about +Y: (1, 0, 1) -> (1, 0, -1) around the centre
    assert_float_equal(l.vertices[0][0], 1.0f, 1e-5f);
    assert_float_equal(l.vertices[0][2], -1.0f, 1e-5f);
    viewer_light_rotate(&l, 0, (float)(pi / 2)); // about +X: the down normal (0, -1, 0) -> (0, 0, -1)
    float normal[3];
    viewer_light_normal(&l, normal);
    assert_float_equal(normal[2], -1.0f, 1e-5f);
    viewer_light_scale(&l, 2.0f);
    assert_float_equal(polygon_area(&l), 16.0, 1e-4);
    viewer_light_translate(&l, (const float[3]){0.5f, -1.0f, 2.0f});
    float center[3];
    viewer_light_center(&l, center);
    assert_float_equal(center[0], 0.5f, 1e-5f);
    assert_float_equal(center[1], 2.0f, 1e-5f);
    assert_float_equal(center[2], 2.0f, 1e-5f);
}

// The transform the edits compose (the light's emissive mesh is drawn with it instead of being
// re-uploaded) maps the polygon as uploaded onto the edited polygon.
static void test_tracked_transform(void **state)
{
    (void)state;
    viewer_light l = square();
    float uploaded[4][3];
    for (int v = 0; v < 4; ++v)
        for (int c = 0; c < 3; ++c) uploaded[v][c] = l.vertices[v][c];
    viewer_light_rotate(&l, 0, 0.3f);
    viewer_light_translate(&l, (const float[3]){0.25f, -0.5f, 1.0f});
    viewer_light_scale(&l, 1.7f);
    viewer_light_rotate(&l, 2, -1.1f);
    viewer_light_rotate(&l, 1, 2.0f);
    assert_false(l.reshaped);
    for (int v = 0; v < 4; ++v)
        for (int r = 0; r < 3; ++r) {
            float x = l.transform[12 + r]; // column-major: m[col * 4 + row]
            for (int c = 0; c < 3; ++c) x += l.transform[c * 4 + r] * uploaded[v][c];
            assert_float_equal(x, l.vertices[v][r], 1e-5f);
        }
    viewer_light_set_vertex_count(&l, 6); // not affine: needs a new mesh
    assert_true(l.reshaped);
}

static void test_load_quad_light(void **state)
{
    (void)state;
    viewer_scene s;
    assert_true(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/quad_light.gltf"));
    // One light: emissiveFactor (1, 0.95, 0.9) x emissiveStrength 8, a 0.8 x 0.8 quad
    // (corners at +-0.5657 along the diagonals) at y = 1.4, facing down; primitive 1 is it.
    assert_int_equal(s.light_count, 1);
    assert_int_equal(s.material_count, 2);
    assert_float_equal(s.lights[0].intensity, 8.0f, 1e-5f);
    assert_float_equal(s.lights[0].color[1], 0.95f, 1e-5f);
    assert_float_equal(polygon_area(&s.lights[0]), 4.0 * 0.5656854249 * 0.5656854249, 1e-5);
    assert_false(s.lights[0].two_sided);
    assert_false(s.primitive_is_light[0]);
    assert_true(s.primitive_is_light[1]);
    assert_float_equal(s.materials[0].roughness, 0.35f, 1e-6f);
    assert_float_equal(s.materials[0].metallic, 1.0f, 1e-6f);
    viewer_scene_destroy(&s);
    assert_false(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/no_such_scene.gltf"));
}

// showcase (scenes.json): five lights, the KHR extensions mapped as the engine's loader path
// maps them (clearcoat roughness = 1 - the loader's gloss), and rays from the camera picking
// the copper sphere, the white quad light and nothing.
static void test_showcase(void **state)
{
    (void)state;
    viewer_scene s;
    assert_true(viewer_scene_load(&s, RTPBR_SAMPLES_SCENES "/showcase.gltf"));
    assert_int_equal(s.light_count, 5);
    assert_int_equal(s.material_count, 12);
    const rtpbr_material_desc *layered = &s.materials[3], *velvet = &s.materials[5], *steel = &s.materials[6];
    assert_float_equal(layered->clearcoat_factor, 1.0f, 1e-6f);
    assert_float_equal(layered->clearcoat_roughness_factor, 0.05f, 1e-6f);
    assert_float_equal(layered->ior, 1.5f, 1e-6f);
    assert_float_equal(velvet->sheen_color_factor[1], 0.6f, 1e-6f);
    assert_float_equal(velvet->sheen_roughness_factor, 0.35f, 1e-6f);
    assert_float_equal(steel->anisotropy_strength, 0.8f, 1e-6f);
    const float eye[3] = {0.0f, 1.5f, 6.5f};
    const float to_copper[3] = {-1.725f - eye[0], 0.45f - eye[1], 0.0f - eye[2]}; // sphere 1 of 6, spacing 1.15
    int32_t light, material;
    assert_true(viewer_scene_pick(&s, eye, to_copper, &light, &material));
    assert_int_equal(light, -1);
    assert_int_equal(material, 2);
    const float to_quad[3] = {-0.9f - eye[0], 1.8f - eye[1], -2.8f - eye[2]};
    assert_true(viewer_scene_pick(&s, eye, to_quad, &light, &material));
    assert_int_equal(material, -1);
    assert_int_equal(s.lights[light].material, 9); // light_white
    const float up[3] = {0.0f, 1.0f, -0.2f};
    assert_false(viewer_scene_pick(&s, eye, up, &light, &material));
    viewer_scene_destroy(&s);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_vertex_count),
                cmocka_unit_test(test_rotate_scale_translate),
                cmocka_unit_test(test_tracked_transform),
                cmocka_unit_test(test_load_quad_light),
                cmocka_unit_test(test_showcase))
