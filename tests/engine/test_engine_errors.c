// Engine: bad input gets a result code and a logged message, never a crash.
#define _DEFAULT_SOURCE // mkstemps
#include <stdlib.h>

#include "engine_test.h"

static int setup(void **state)
{
    test_log *log = calloc(1, sizeof *log);
    rtpbr_context *ctx = test_context(log);
    void **pair = calloc(2, sizeof *pair);
    pair[0] = ctx;
    pair[1] = log;
    *state = pair;
    return 0;
}

static int teardown(void **state)
{
    void **pair = *state;
    test_log *log = pair[1];
    rtpbr_context_destroy(pair[0]);
    int validation = log->validation;
    free(log);
    free(pair);
    return validation == 0 ? 0 : -1; // a validation message fails the group
}

#define CTX ((rtpbr_context *)((void **)*state)[0])
#define LOG ((test_log *)((void **)*state)[1])

static const rtpbr_light_desc good_light = {
    .vertices = {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}},
    .vertex_count = 4,
    .emission = {1, 1, 1},
};

// Creates a scene with the given lights and returns the result (destroys it on success).
static rtpbr_result try_lights(rtpbr_context *ctx, const rtpbr_light_desc *lights, uint32_t count)
{
    rtpbr_gpu_scene *scene = (rtpbr_gpu_scene *)(uintptr_t)1; // must be reset to NULL on failure
    rtpbr_result r = rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.lights = lights, .light_count = count}, &scene);
    if (r == RTPBR_SUCCESS) rtpbr_gpu_scene_destroy(scene);
    else assert_null(scene);
    return r;
}

static void result_strings(void **state)
{
    (void)state;
    for (int i = RTPBR_SUCCESS; i <= RTPBR_ERROR_VULKAN; ++i) {
        const char *s = rtpbr_result_string((rtpbr_result)i);
        assert_non_null(s);
        assert_true(strlen(s) > 3);
        for (int j = RTPBR_SUCCESS; j < i; ++j) assert_string_not_equal(s, rtpbr_result_string((rtpbr_result)j));
    }
    assert_non_null(rtpbr_result_string((rtpbr_result)12345));
}

static void free_only(void *ptr, void *user_data)
{
    (void)user_data;
    free(ptr);
}

static void null_arguments(void **state)
{
    rtpbr_context *ctx = CTX;
    rtpbr_context *c = NULL;
    assert_int_equal(rtpbr_context_create(NULL, &c), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_context_create(&(rtpbr_context_desc){.logger = {test_log_func, LOG}}, NULL),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    rtpbr_allocator half = {.alloc = NULL, .free = free_only};
    assert_int_equal(rtpbr_context_create(&(rtpbr_context_desc){.allocator = half, .logger = {test_log_func, LOG}}, &c),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    assert_null(c);

    rtpbr_gpu_scene *scene = NULL;
    assert_int_equal(rtpbr_gpu_scene_create(NULL, &(rtpbr_gpu_scene_desc){0}, &scene), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_gpu_scene_create(ctx, NULL, &scene), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){0}, NULL), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.mesh_count = 2}, &scene),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_gpu_scene_load_gltf(ctx, NULL, &scene), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_gpu_scene_from_loaded(ctx, NULL, &scene), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_gpu_scene_set_lights(NULL, &good_light, 1), RTPBR_ERROR_INVALID_ARGUMENT);

    rtpbr_renderer *r = NULL;
    assert_int_equal(rtpbr_renderer_create(NULL, &(rtpbr_renderer_desc){.width = 4, .height = 4}, &r),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_renderer_create(ctx, NULL, &r), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 4, .height = 4}, NULL),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_render(NULL, NULL, NULL), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_read_radiance(NULL, NULL, 0), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_read_display(NULL, NULL, 0), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_record(NULL, NULL, NULL, NULL), RTPBR_ERROR_INVALID_ARGUMENT);

    // destroy(NULL) is a no-op; queries on NULL are harmless.
    rtpbr_context_destroy(NULL);
    rtpbr_gpu_scene_destroy(NULL);
    rtpbr_renderer_destroy(NULL);
    assert_int_equal(rtpbr_context_validation_message_count(NULL), 0);
    assert_int_equal(rtpbr_gpu_scene_light_count(NULL), 0);
    assert_string_equal(rtpbr_context_device_name(NULL), "");
    assert_true(strlen(rtpbr_context_device_name(ctx)) > 0);
}

static void zero_sizes(void **state)
{
    rtpbr_context *ctx = CTX;
    rtpbr_renderer *r = NULL;
    LOG->errors = 0;
    assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 0, .height = 4}, &r),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 4, .height = 0}, &r),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = RTPBR_MAX_RENDER_SIZE + 1, .height = 4}, &r),
                     RTPBR_ERROR_LIMIT_EXCEEDED);
    assert_null(r);
    assert_true(LOG->errors >= 3); // each failure explained in the log

    // Readback buffers that are too small.
    assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 4, .height = 4}, &r), RTPBR_SUCCESS);
    float px[4 * 4 * 4];
    uint8_t bytes[4 * 4 * 4];
    assert_int_equal(rtpbr_read_radiance(r, px, sizeof px - 1), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_read_radiance(r, NULL, sizeof px), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_read_display(r, bytes, sizeof bytes), RTPBR_ERROR_INVALID_ARGUMENT); // nothing rendered
    rtpbr_renderer_destroy(r);

    // Meshes: no vertices, indices not a multiple of 3, index past the vertices.
    float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t bad_index[3] = {0, 1, 3}, two[2] = {0, 1};
    rtpbr_mesh_desc meshes[] = {
        {.positions = p, .vertex_count = 0},
        {.positions = NULL, .vertex_count = 3},
        {.positions = p, .vertex_count = 3, .indices = two, .index_count = 2},
        {.positions = p, .vertex_count = 3, .indices = bad_index, .index_count = 3},
        {.positions = p, .vertex_count = 3, .material = 1},
    };
    for (size_t i = 0; i < sizeof meshes / sizeof meshes[0]; ++i) {
        rtpbr_gpu_scene *scene = NULL;
        assert_int_equal(rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.meshes = &meshes[i], .mesh_count = 1}, &scene),
                         RTPBR_ERROR_INVALID_ARGUMENT);
        assert_null(scene);
    }
}

// Finite coordinates near FLT_MAX: the shadow BVH's centroids and extents overflow to infinity
// and its bin positions to NaN, which the builder converted to int (undefined; found by
// fuzz_scene_api). The scene is made, or refused with a message. (GCC's -fsanitize=undefined
// has no float-cast-overflow check, so the sanitizer build does not see the conversion itself:
// the fuzz build's replay of fuzz/regressions/scene_api/bvh-nan-bin, in .ci/run, holds it.)
static void huge_coordinates(void **state)
{
    rtpbr_context *ctx = CTX;
    // unit triangles scaled by 3e38 into world space: sums of two coordinates overflow
    float p[] = {1, 1, 1, 1, 1, -1, -1, 1, 1, -1, -1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 1, 0, 0, 0, 1, 0,
                 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
    const float h = 3.0e38f;
    rtpbr_mesh_desc mesh = {.positions = p, .vertex_count = sizeof p / sizeof p[0] / 3,
                            .transform = {h, 0, 0, 0, 0, h, 0, 0, 0, 0, h, 0, 0, 0, 0, 1}};
    rtpbr_gpu_scene *scene = NULL;
    LOG->errors = 0;
    rtpbr_result r = rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1}, &scene);
    print_message("huge coordinates: %s\n", rtpbr_result_string(r));
    assert_true(r == RTPBR_SUCCESS || (scene == NULL && LOG->errors >= 1));
    rtpbr_gpu_scene_destroy(scene);
}

// Materials: NaN or infinite parameters (also in the extension and Disney fields) and an
// unknown model are refused with INVALID_ARGUMENT; out-of-range values are clamped (accepted).
static void bad_materials(void **state)
{
    rtpbr_context *ctx = CTX;
    float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    rtpbr_mesh_desc mesh = {.positions = p, .vertex_count = 3};
    rtpbr_material_desc good = {.base_color = {0.5f, 0.5f, 0.5f}, .roughness = 0.5f, .clearcoat_factor = 2.0f,
                                .sheen_color_factor = {1.5f, 0.0f, 0.0f}, .anisotropy_strength = -1.0f};
    rtpbr_material_desc bad[6];
    for (int i = 0; i < 6; ++i) bad[i] = good;
    bad[0].clearcoat_roughness_factor = NAN;
    bad[1].anisotropy_rotation = INFINITY;
    bad[2].sheen_color_factor[2] = NAN;
    bad[3].model = (rtpbr_material_model)7;
    bad[4].model = RTPBR_MATERIAL_DISNEY;
    bad[4].disney.sheen_tint = NAN;
    bad[5].sheen_roughness_factor = -INFINITY;
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                     .materials = &good, .material_count = 1});
    rtpbr_gpu_scene_destroy(scene);
    for (int i = 0; i < 6; ++i) {
        scene = NULL;
        int errors = LOG->errors;
        assert_int_equal(rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                              .materials = &bad[i], .material_count = 1},
                                                &scene),
                         RTPBR_ERROR_INVALID_ARGUMENT);
        assert_null(scene);
        assert_true(LOG->errors > errors); // explained in the log
    }
}

static void bad_lights(void **state)
{
    rtpbr_context *ctx = CTX;
    assert_int_equal(try_lights(ctx, &good_light, 1), RTPBR_SUCCESS);

    rtpbr_light_desc l = good_light;
    l.vertices[2][1] = NAN;
    assert_int_equal(try_lights(ctx, &l, 1), RTPBR_ERROR_INVALID_ARGUMENT);
    l = good_light;
    l.vertices[0][0] = INFINITY;
    assert_int_equal(try_lights(ctx, &l, 1), RTPBR_ERROR_INVALID_ARGUMENT);
    l = good_light;
    l.emission[1] = NAN;
    assert_int_equal(try_lights(ctx, &l, 1), RTPBR_ERROR_INVALID_ARGUMENT);
    l = good_light;
    l.emission[0] = -1.0f;
    assert_int_equal(try_lights(ctx, &l, 1), RTPBR_ERROR_INVALID_ARGUMENT);
    l = good_light;
    l.vertex_count = 2;
    assert_int_equal(try_lights(ctx, &l, 1), RTPBR_ERROR_INVALID_ARGUMENT);
    l = good_light;
    l.vertex_count = RTPBR_MAX_POLYGON_VERTICES + 1;
    assert_int_equal(try_lights(ctx, &l, 1), RTPBR_ERROR_LIMIT_EXCEEDED);
    l = good_light;
    l.vertices[2][1] = 2.5f; // not planar
    assert_int_equal(try_lights(ctx, &l, 1), RTPBR_ERROR_INVALID_ARGUMENT);
    l = good_light;
    memcpy(l.vertices[1], l.vertices[0], sizeof l.vertices[0]);
    memcpy(l.vertices[2], l.vertices[0], sizeof l.vertices[0]);
    memcpy(l.vertices[3], l.vertices[0], sizeof l.vertices[0]); // zero area
    assert_int_equal(try_lights(ctx, &l, 1), RTPBR_ERROR_INVALID_ARGUMENT);

    // The documented light limit, exactly and one past it.
    rtpbr_light_desc *many = malloc((RTPBR_MAX_LIGHTS + 1) * sizeof *many);
    for (uint32_t i = 0; i <= RTPBR_MAX_LIGHTS; ++i) many[i] = good_light;
    assert_int_equal(try_lights(ctx, many, RTPBR_MAX_LIGHTS), RTPBR_SUCCESS);
    assert_int_equal(try_lights(ctx, many, RTPBR_MAX_LIGHTS + 1), RTPBR_ERROR_LIMIT_EXCEEDED);
    assert_int_equal(try_lights(ctx, NULL, 3), RTPBR_ERROR_INVALID_ARGUMENT);

    // set_lights validates the same way and leaves the scene unchanged on failure.
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.lights = many, .light_count = 2});
    assert_int_equal(rtpbr_gpu_scene_light_count(scene), 2);
    assert_int_equal(rtpbr_gpu_scene_set_lights(scene, many, RTPBR_MAX_LIGHTS + 1), RTPBR_ERROR_LIMIT_EXCEEDED);
    l = good_light;
    l.vertices[1][2] = NAN;
    assert_int_equal(rtpbr_gpu_scene_set_lights(scene, &l, 1), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_gpu_scene_light_count(scene), 2);
    assert_int_equal(rtpbr_gpu_scene_set_lights(scene, many, 7), RTPBR_SUCCESS);
    assert_int_equal(rtpbr_gpu_scene_light_count(scene), 7);
    rtpbr_gpu_scene_destroy(scene);
    free(many);
}

static void bad_render_arguments(void **state)
{
    rtpbr_context *ctx = CTX;
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){0});
    assert_int_equal(rtpbr_gpu_scene_camera_count(scene), 1); // the default camera
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = 8, .height = 8});
    assert_int_equal(rtpbr_render(r, NULL, &(rtpbr_render_desc){0}), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_render(r, scene, NULL), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.camera_index = 1}), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.exposure = NAN}), RTPBR_ERROR_INVALID_ARGUMENT);
    rtpbr_camera_desc cam = {.position = {0, 0, NAN}};
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.camera = &cam}), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.tonemap = (rtpbr_tonemap)99}),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(rtpbr_record(r, scene, &(rtpbr_render_desc){0}, &(rtpbr_record_desc){0}),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    // Still usable after all that.
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.background = {1, 2, 3}}), RTPBR_SUCCESS);
    float px[8 * 8 * 4];
    assert_int_equal(test_read_radiance(r, px, sizeof px), RTPBR_SUCCESS);
    assert_float_equal(px[4 * 27 + 2], 3.0f, 0.0f);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// rtpbr_context_desc.shadow_ray_query: a value that is not a mode, and ON on a device without
// VK_KHR_ray_query (this suite's lavapipe, Mesa 22.3), fail with a message; no context is made.
static void bad_ray_query_modes(void **state)
{
    (void)state;
    const struct {
        int mode;
        rtpbr_result expected;
        const char *says;
    } cases[] = {{7, RTPBR_ERROR_INVALID_ARGUMENT, "shadow_ray_query 7"},
                 {-1, RTPBR_ERROR_INVALID_ARGUMENT, "shadow_ray_query -1"},
                 {RTPBR_SHADOW_RAY_QUERY_ON, RTPBR_ERROR_MISSING_FEATURE, "VK_KHR_ray_query"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        test_log log = {0};
        rtpbr_context *ctx = (rtpbr_context *)(uintptr_t)1; // must be reset to NULL
        rtpbr_context_desc desc = {.logger = {test_log_func, &log}, .validation = 1, .shadow_ray_query = cases[i].mode};
        assert_int_equal(rtpbr_context_create(&desc, &ctx), cases[i].expected);
        assert_null(ctx);
        fprintf(stderr, "shadow_ray_query %d: %s\n", cases[i].mode, log.last_error);
        assert_non_null(strstr(log.last_error, cases[i].says));
        assert_int_equal(log.validation, 0);
    }
    // OFF and AUTO make a context that walks the BVH here.
    for (int mode = RTPBR_SHADOW_RAY_QUERY_AUTO; mode <= RTPBR_SHADOW_RAY_QUERY_OFF; ++mode) {
        test_log log = {0};
        rtpbr_context *ctx = NULL;
        rtpbr_context_desc desc = {.logger = {test_log_func, &log}, .validation = 1, .shadow_ray_query = mode};
        assert_int_equal(rtpbr_context_create(&desc, &ctx), RTPBR_SUCCESS);
        assert_false(rtpbr_context_shadow_ray_query(ctx));
        test_context_done(ctx, &log);
    }
}

static void missing_and_malformed_gltf(void **state)
{
    rtpbr_context *ctx = CTX;
    rtpbr_gpu_scene *scene = NULL;
    rtpbr_result r = rtpbr_gpu_scene_load_gltf(ctx, "/nonexistent/rtpbr/scene.gltf", &scene);
    assert_true(r == RTPBR_ERROR_SCENE_LOAD || r == RTPBR_ERROR_IO);
    assert_null(scene);
    assert_true(strlen(LOG->last_error) > 0);

    char path[] = "/tmp/rtpbr-engine-malformed-XXXXXX.gltf";
    int fd = mkstemps(path, 5);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs("{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [ {\"primitives\": [ {\"attributes\": {\"POSITION\": 7", f);
    fclose(f);
    r = rtpbr_gpu_scene_load_gltf(ctx, path, &scene);
    remove(path);
    assert_int_equal(r, RTPBR_ERROR_SCENE_LOAD);
    assert_null(scene);
}

int main(void)
{
    RTPBR_RUN_TESTS(setup, teardown,
                    cmocka_unit_test(result_strings),
                    cmocka_unit_test(null_arguments),
                    cmocka_unit_test(zero_sizes),
                    cmocka_unit_test(huge_coordinates),
                    cmocka_unit_test(bad_lights),
                    cmocka_unit_test(bad_materials),
                    cmocka_unit_test(bad_render_arguments),
                    cmocka_unit_test(missing_and_malformed_gltf),
                    cmocka_unit_test(bad_ray_query_modes));
}
