// Engine: the C API keeps the promises rtpbr.h makes about misuse (issue 18, class 5):
// - rtpbr_gpu_scene_from_loaded refuses a non-zero count with a NULL array;
// - rtpbr_context_destroy destroys the scenes and renderers the host left alive (with a
//   warning), so nothing leaks and no Vulkan object outlives its device (the validation
//   layer's object tracker would report it, and any validation message fails the test);
// - every allocation failure through the host allocator returns OUT_OF_HOST_MEMORY with an
//   error message in the log (failure injected at each allocation index in turn);
// - rtpbr_read_radiance before any render refuses, like rtpbr_read_display;
// - the reads give the last frame's images in any order and number of reads.
#define _DEFAULT_SOURCE // mkstemps
#include <stdio.h>
#include <stdlib.h>

#include <rtpbr/rtpbr_gltf.h>

#include "engine_gltf_file.h"

static const rtpbr_light_desc kLight = {
    .vertices = {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}},
    .vertex_count = 4,
    .emission = {1, 1, 1},
};

static void from_loaded_null_arrays(void **state)
{
    test_env *env = *state;
    rtpbr_context *ctx = env->ctx;
    rtpbr_gltf_material material = {.base_color = {1, 1, 1, 1}, .roughness = 0.5f};
    // Each count non-zero with its array NULL, the other arrays valid or empty.
    for (int which = 0; which < 5; ++which) {
        rtpbr_gltf_scene loaded = {0};
        loaded.material_count = 1;
        loaded.materials = &material;
        switch (which) {
        case 0: loaded.primitive_count = 3; break;
        case 1: loaded.materials = NULL; break;
        case 2: loaded.texture_count = 2; break;
        case 3: loaded.light_count = 1; break;
        case 4: loaded.camera_count = 1; break;
        }
        rtpbr_gpu_scene *scene = (rtpbr_gpu_scene *)(uintptr_t)1;
        int errors = env->log.errors;
        assert_int_equal(rtpbr_gpu_scene_from_loaded(ctx, &loaded, &scene), RTPBR_ERROR_INVALID_ARGUMENT);
        assert_null(scene);
        assert_true(env->log.errors > errors);
        assert_non_null(strstr(env->log.last_error, "is NULL"));
    }
}

// rtpbr_material_desc_from_loaded: the loader's values copied as they are; its zeros that are
// not the desc's defaults (KHR ior 0, specularFactor 0 or a black specularColorFactor,
// alphaCutoff 0, Burley's specular 0) become flags, never negative values (issue 29).
static void material_desc_from_loaded_flags(void **state)
{
    (void)state;
    rtpbr_gltf_material m[3] = {
        {.roughness = 0.5f, .alpha_cutoff = 0.5f, .ior = {1.5f}, .specular = {.specular_factor = 1.0f,
         .specular_color_factor = {1, 1, 1}}, .base_color_texture = -1, .metallic_roughness_texture = -1,
         .normal_texture = -1, .emission_texture = -1},
        {.roughness = 0.5f, .alpha_cutoff = 0.0f, .ior = {0.0f}, .specular = {.specular_factor = 0.0f,
         .specular_color_factor = {1, 1, 1}}, .has_disney = true, .disney = {.specular = 0.0f},
         .base_color_texture = -1, .metallic_roughness_texture = -1, .normal_texture = -1, .emission_texture = -1},
        {.roughness = 0.5f, .alpha_cutoff = 0.5f, .ior = {1.5f}, .specular = {.specular_factor = 1.0f},
         .base_color_texture = -1, .metallic_roughness_texture = -1, .normal_texture = -1, .emission_texture = -1},
    };
    rtpbr_gltf_scene loaded = {.materials = m, .material_count = 3};
    rtpbr_material_desc d[3];
    for (uint32_t i = 0; i < 3; ++i) rtpbr_material_desc_from_loaded(&loaded, i, &d[i]);
    assert_int_equal(d[0].flags, 0);
    assert_true(d[0].ior == 1.5f && d[0].specular_factor == 1.0f && d[0].alpha_cutoff == 0.5f);
    assert_int_equal(d[1].flags, RTPBR_MATERIAL_FRESNEL_ONE | RTPBR_MATERIAL_NO_SPECULAR |
                                     RTPBR_MATERIAL_NO_ALPHA_CUTOFF | RTPBR_MATERIAL_DISNEY_NO_SPECULAR);
    assert_int_equal(d[1].model, RTPBR_MATERIAL_DISNEY);
    assert_int_equal(d[2].flags, RTPBR_MATERIAL_NO_SPECULAR); // black specular colour: no lobe
    for (uint32_t i = 0; i < 3; ++i)
        assert_true(d[i].ior >= 0.0f && d[i].specular_factor >= 0.0f && d[i].alpha_cutoff >= 0.0f && d[i].disney.specular >= 0.0f);
}

typedef struct warn_log {
    test_log base;
    int warnings;
    char last_warning[1024];
} warn_log;

static void warn_log_func(rtpbr_log_level level, const char *message, void *user_data)
{
    warn_log *log = user_data;
    test_log_func(level, message, &log->base);
    if (level == RTPBR_LOG_WARNING && strncmp(message, "validation: ", 12) != 0) {
        log->warnings++;
        snprintf(log->last_warning, sizeof log->last_warning, "%s", message);
    }
}

// Host blocks allocated through rtpbr_allocator and not yet freed.
static void *counting_alloc(size_t size, void *user_data)
{
    void *p = malloc(size);
    if (p) ++*(long *)user_data;
    return p;
}

static void counting_free(void *ptr, void *user_data)
{
    if (ptr) --*(long *)user_data;
    free(ptr);
}

// Live children at rtpbr_context_destroy: destroyed with the context. The host allocator sees
// every block of the library come back (leak checkers, ASan in CI, see the rest); the
// validation layer sees any Vulkan object left (a message fails the test).
static void context_destroys_children(void **state)
{
    (void)state;
    warn_log log = {0};
    long live_blocks = 0;
    rtpbr_context *ctx = NULL;
    rtpbr_context_desc desc = {
        .allocator = {counting_alloc, counting_free, &live_blocks},
        .logger = {warn_log_func, &log},
        .validation = 1,
    };
    assert_int_equal(rtpbr_context_create(&desc, &ctx), RTPBR_SUCCESS);
    rtpbr_gpu_scene *scenes[2] = {NULL, NULL};
    rtpbr_renderer *renderers[3] = {NULL, NULL, NULL};
    for (int i = 0; i < 2; ++i)
        assert_int_equal(rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.lights = &kLight, .light_count = 1},
                                                &scenes[i]),
                         RTPBR_SUCCESS);
    for (int i = 0; i < 3; ++i)
        assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 8, .height = 8}, &renderers[i]),
                         RTPBR_SUCCESS);
    // Destroying some children in an order other than creation keeps the list consistent.
    rtpbr_renderer_destroy(renderers[1]);
    rtpbr_gpu_scene_destroy(scenes[0]);
    assert_int_equal(rtpbr_render(renderers[2], scenes[1], &(rtpbr_render_desc){0}), RTPBR_SUCCESS);
    long live_with_children = live_blocks;
    rtpbr_context_destroy(ctx);
    assert_true(live_with_children > 0);
    assert_int_equal(live_blocks, 0);
    assert_int_equal(log.base.validation, 0);
    assert_int_equal(log.warnings, 1);
    assert_non_null(strstr(log.last_warning, "1 scene(s) and 2 renderer(s)"));
}

static void read_radiance_before_render(void **state)
{
    test_env *env = *state;
    rtpbr_context *ctx = env->ctx;
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = 4, .height = 4});
    float radiance[4 * 4 * 4];
    uint8_t display[4 * 4 * 4];
    int errors = env->log.errors;
    assert_int_equal(rtpbr_read_radiance(r, radiance, sizeof radiance), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(env->log.errors, errors + 1);
    assert_int_equal(rtpbr_read_display(r, display, sizeof display), RTPBR_ERROR_INVALID_ARGUMENT);
    assert_int_equal(env->log.errors, errors + 2);
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){0});
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.background = {1, 2, 3}}), RTPBR_SUCCESS);
    assert_int_equal(test_read_radiance(r, radiance, sizeof radiance), RTPBR_SUCCESS);
    assert_float_equal(radiance[2], 3.0f, 0.0f);
    assert_int_equal(test_read_display(r, display, sizeof display), RTPBR_SUCCESS);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// rtpbr_read_* copy the image on the first read of a frame (renderer.c, copy_back): each read
// gives the last frame, whichever was read first and however often, never an earlier one.
static void reads_follow_the_last_frame(void **state)
{
    test_env *env = *state;
    rtpbr_context *ctx = env->ctx;
    enum { N = 4 * 4 };
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = 4, .height = 4});
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){0});
    const float backgrounds[4][3] = {{1, 2, 3}, {0.25f, 0.5f, 0.125f}, {0.25f, 0.5f, 0.125f}, {4, 0, 0.5f}};
    uint8_t display[4][4 * N];
    for (int f = 0; f < 4; ++f) {
        const float *bg = backgrounds[f];
        assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.background = {bg[0], bg[1], bg[2]}}),
                         RTPBR_SUCCESS);
        float radiance[4 * N];
        uint8_t again[4 * N];
        // Frames 0 and 2 read the radiance first, 1 and 3 the display; each reads both twice.
        for (int k = 0; k < 4; ++k) {
            if ((k + f) % 2 == 0) {
                memset(radiance, 0, sizeof radiance);
                assert_int_equal(test_read_radiance(r, radiance, sizeof radiance), RTPBR_SUCCESS);
                for (int i = 0; i < N; ++i)
                    for (int c = 0; c < 3; ++c) assert_float_equal(radiance[4 * i + c], bg[c], 0.0f);
            } else {
                uint8_t *dst = k < 2 ? display[f] : again;
                memset(dst, 0, 4 * N);
                assert_int_equal(test_read_display(r, dst, 4 * N), RTPBR_SUCCESS);
                if (k >= 2) assert_memory_equal(again, display[f], sizeof again);
            }
        }
    }
    // Every pixel the same in a frame; frames 1 and 2 the same background, the others not
    // (a stale read of the previous frame's display fails here).
    for (int f = 0; f < 4; ++f)
        for (int i = 1; i < N; ++i) assert_memory_equal(display[f] + 4 * i, display[f], 4);
    assert_memory_equal(display[1], display[2], 4 * N);
    assert_memory_not_equal(display[0], display[1], 4);
    assert_memory_not_equal(display[2], display[3], 4);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// A node scaled by 0 and a visible instance of the same triangle.
static const char kHiddenNodeGltf[] =
    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],"
    "\"nodes\":[{\"mesh\":0,\"scale\":[0,0,0]},{\"mesh\":0,\"translation\":[0,-1,0]}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
    "\"min\":[-1,0,-1],\"max\":[1,0,1]}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
    "\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,"
    "AACAvwAAAAAAAIC/AACAPwAAAAAAAIC/AACAPwAAAAAAAIA/\"}]}";

// Issue 18, class 4: a node scaled by 0 (the usual way to hide an object) leaves a primitive
// without triangles; it is skipped with a warning, and the rest of the scene loads (the
// engine refused the whole scene: "the index count is not a positive multiple of 3").
static void hidden_node_does_not_hide_the_scene(void **state)
{
    (void)state;
    char path[] = "/tmp/rtpbr-engine-hidden-XXXXXX.gltf";
    test_gltf_file(path, test_gltf_text, kHiddenNodeGltf);
    warn_log log = {0};
    rtpbr_context *ctx = NULL;
    assert_int_equal(rtpbr_context_create(&(rtpbr_context_desc){.logger = {warn_log_func, &log}, .validation = 1}, &ctx),
                     RTPBR_SUCCESS);
    rtpbr_gpu_scene *scene = NULL;
    rtpbr_result r = rtpbr_gpu_scene_load_gltf(ctx, path, &scene);
    remove(path);
    if (r != RTPBR_SUCCESS) fail_msg("hidden node: %s: %s", rtpbr_result_string(r), log.base.last_error);
    assert_true(log.warnings >= 1);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_context_destroy(ctx);
    assert_int_equal(log.base.validation, 0);
}

// ---- allocation-failure injection --------------------------------------------------------

typedef struct failing_allocator {
    long calls;     // allocations requested so far
    long fail_at;   // the index of the one allocation that fails (-1: none)
    long live;      // blocks not yet freed
} failing_allocator;

static void *failing_alloc(size_t size, void *user_data)
{
    failing_allocator *a = user_data;
    if (a->calls++ == a->fail_at) return NULL;
    void *p = malloc(size);
    if (p) a->live++;
    return p;
}

static void failing_free(void *ptr, void *user_data)
{
    failing_allocator *a = user_data;
    if (ptr) a->live--;
    free(ptr);
}

static const char *g_gltf_path; // written by allocation_failures_are_logged

// A whole session: context, a scene with a light, a renderer, one render, a light update,
// a glTF scene loaded.
// Returns the first failing result (everything created is destroyed either way).
static rtpbr_result session(failing_allocator *a, test_log *log)
{
    rtpbr_context_desc desc = {
        .allocator = {failing_alloc, failing_free, a},
        .logger = {test_log_func, log},
        .validation = 1,
    };
    rtpbr_context *ctx = NULL;
    rtpbr_result r = rtpbr_context_create(&desc, &ctx);
    if (r != RTPBR_SUCCESS) return r;
    static const float positions[] = {-1, 0, -1, 1, 0, -1, 1, 0, 1};
    static const uint32_t indices[] = {0, 2, 1};
    static const uint8_t texel[4] = {255, 128, 0, 255};
    rtpbr_mesh_desc mesh = {.positions = positions, .indices = indices, .vertex_count = 3, .index_count = 3};
    rtpbr_material_desc material = {.base_color = {1, 1, 1}, .roughness = 0.5f, .base_color_texture = 1};
    rtpbr_texture_desc texture = {.width = 1, .height = 1, .rgba = texel};
    rtpbr_gpu_scene_desc scene_desc = {
        .meshes = &mesh, .mesh_count = 1, .materials = &material, .material_count = 1,
        .lights = &kLight, .light_count = 1, .textures = &texture, .texture_count = 1,
    };
    rtpbr_gpu_scene *scene = NULL;
    rtpbr_renderer *renderer = NULL;
    r = rtpbr_gpu_scene_create(ctx, &scene_desc, &scene);
    if (r == RTPBR_SUCCESS) r = rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 4, .height = 4}, &renderer);
    if (r == RTPBR_SUCCESS) r = rtpbr_render(renderer, scene, &(rtpbr_render_desc){0});
    if (r == RTPBR_SUCCESS) r = rtpbr_gpu_scene_set_lights(scene, &kLight, 1);
    // The glTF path: the loader allocates what it returns through the same host allocator.
    rtpbr_gpu_scene *loaded = NULL;
    if (r == RTPBR_SUCCESS) r = rtpbr_gpu_scene_load_gltf(ctx, g_gltf_path, &loaded);
    rtpbr_gpu_scene_destroy(loaded);
    rtpbr_renderer_destroy(renderer);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_context_destroy(ctx);
    return r;
}

static void allocation_failures_are_logged(void **state)
{
    (void)state;
    char path[] = "/tmp/rtpbr-engine-alloc-XXXXXX.gltf";
    test_gltf_file(path, test_gltf_text, kHiddenNodeGltf);
    g_gltf_path = path;
    failing_allocator a = {.fail_at = -1};
    test_log log = {0};
    assert_int_equal(session(&a, &log), RTPBR_SUCCESS);
    assert_int_equal(a.live, 0);
    assert_int_equal(log.validation, 0);
    const long total = a.calls;
    assert_true(total > 0);
    print_message("a session makes %ld host allocations; failing each in turn\n", total);
    for (long i = 0; i < total; ++i) {
        failing_allocator f = {.fail_at = i};
        test_log flog = {0};
        rtpbr_result r = session(&f, &flog);
        if (r != RTPBR_ERROR_OUT_OF_HOST_MEMORY || flog.errors == 0)
            fail_msg("allocation %ld of %ld failed: result %s, %d error message(s), last '%s'", i, total,
                     rtpbr_result_string(r), flog.errors, flog.last_error);
        assert_int_equal(f.live, 0);
        assert_int_equal(flog.validation, 0);
    }
    remove(path);
}

RTPBR_TEST_MAIN(test_env_case(from_loaded_null_arrays),
                cmocka_unit_test(material_desc_from_loaded_flags),
                cmocka_unit_test(context_destroys_children),
                test_env_case(read_radiance_before_render),
                test_env_case(reads_follow_the_last_frame),
                cmocka_unit_test(hidden_node_does_not_hide_the_scene),
                cmocka_unit_test(allocation_failures_are_logged))
