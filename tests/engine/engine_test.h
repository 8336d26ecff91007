// Shared helpers of the engine tests: a logger that counts validation messages (any one
// fails a test) and small scene builders.
#ifndef RTPBR_ENGINE_TEST_H
#define RTPBR_ENGINE_TEST_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_main.h"

#include "rtpbr/rtpbr.h"

#ifdef RTPBR_TEST_MEMCHECK
#include <valgrind/memcheck.h>
#endif

// Pixels read back from the device. Under valgrind's memcheck (meson test --setup valgrind)
// they are marked defined: lavapipe's JIT code computes them on SIMD lanes that start from an
// uninitialised stack variable of lavapipe's (third-party, see valgrind.supp), and memcheck
// cannot tell that the values the tests compare do not depend on those lanes. The values
// themselves are checked against independent references by the tests. No-op otherwise.
static inline void test_device_output(const void *data, size_t size)
{
#ifdef RTPBR_TEST_MEMCHECK
    VALGRIND_MAKE_MEM_DEFINED(data, size);
#else
    (void)data;
    (void)size;
#endif
}

// rtpbr_read_radiance / rtpbr_read_display, then test_device_output on what they wrote.
static inline rtpbr_result test_read_radiance(rtpbr_renderer *r, float *out, size_t size)
{
    rtpbr_result result = rtpbr_read_radiance(r, out, size);
    test_device_output(out, size);
    return result;
}
static inline rtpbr_result test_read_display(rtpbr_renderer *r, uint8_t *out, size_t size)
{
    rtpbr_result result = rtpbr_read_display(r, out, size);
    test_device_output(out, size);
    return result;
}

// Ends `cmd` with a barrier that makes its transfer writes visible to the host, submits it to
// `queue` and waits for `fence` (the tests that record into a host's own command buffer).
static inline void test_submit_for_host(VkDevice device, VkQueue queue, VkCommandBuffer cmd, VkFence fence)
{
    VkMemoryBarrier to_host = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                               .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, NULL, 0, NULL);
    assert_int_equal(vkEndCommandBuffer(cmd), VK_SUCCESS);
    VkSubmitInfo submit = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
    assert_int_equal(vkQueueSubmit(queue, 1, &submit, fence), VK_SUCCESS);
    assert_int_equal(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
}

typedef struct test_log {
    int validation;   // messages from the validation layer
    int errors;       // error-level messages of the library
    char last_error[1024];
} test_log;

static void test_log_func(rtpbr_log_level level, const char *message, void *user_data)
{
    test_log *log = user_data;
    if (strncmp(message, "validation: ", 12) == 0) {
        log->validation++;
        fprintf(stderr, "VALIDATION MESSAGE: %s\n", message);
    }
    if (level == RTPBR_LOG_ERROR) {
        log->errors++;
        snprintf(log->last_error, sizeof log->last_error, "%s", message);
    }
}

// A standalone context with validation (and synchronization validation) on. With
// RTPBR_TEST_SHADOW_RAY_QUERY=on in the environment (the engine-ray-query suite, on a driver
// that has VK_KHR_ray_query: tests/engine/meson.build) its shadow rays are ray queries, and
// the context must say so.
static inline rtpbr_context *test_context(test_log *log)
{
    const char *ray_query = getenv("RTPBR_TEST_SHADOW_RAY_QUERY");
    bool on = ray_query && strcmp(ray_query, "on") == 0;
    rtpbr_context_desc desc = {
        .logger = {test_log_func, log},
        .validation = 1,
        .shadow_ray_query = on ? RTPBR_SHADOW_RAY_QUERY_ON : RTPBR_SHADOW_RAY_QUERY_AUTO,
    };
    rtpbr_context *ctx = NULL;
    rtpbr_result r = rtpbr_context_create(&desc, &ctx);
    if (r != RTPBR_SUCCESS) fprintf(stderr, "context: %s: %s\n", rtpbr_result_string(r), log->last_error);
    assert_int_equal(r, RTPBR_SUCCESS);
    assert_non_null(ctx);
    if (on) assert_true(rtpbr_context_shadow_ray_query(ctx));
    return ctx;
}

// Teardown of a test's context: destroyed, and not one validation message in its life.
static inline void test_context_done(rtpbr_context *ctx, const test_log *log)
{
    rtpbr_context_destroy(ctx);
    assert_int_equal(log->validation, 0);
}

// The fixture of most engine tests (cmocka setup and teardown; test_env_case(name) in the
// runner's list): a context of the test's own, made by test_context before it and destroyed by
// test_context_done after it (not one validation message in its life). The test reads it from
// *state; one that sets no_errors must also see no error-level message of the library.
typedef struct test_env {
    test_log log;
    rtpbr_context *ctx;
    bool no_errors;
} test_env;

static inline int test_env_setup(void **state)
{
    test_env *env = calloc(1, sizeof *env);
    assert_non_null(env);
    env->ctx = test_context(&env->log);
    *state = env;
    return 0;
}
static inline int test_env_teardown(void **state)
{
    test_env *env = *state;
    test_context_done(env->ctx, &env->log);
    if (env->no_errors) assert_int_equal(env->log.errors, 0);
    free(env);
    return 0;
}
// The context of the test's fixture (a test that needs no more of it: reads only this).
static inline rtpbr_context *test_env_context(void **state)
{
    return ((test_env *)*state)->ctx;
}
#define test_env_case(test) cmocka_unit_test_setup_teardown(test, test_env_setup, test_env_teardown)

// The same fixture with one context for the whole group: test_env_group(tests) runs the list of
// test_env_shared_case(name) entries with a context made before the first and destroyed after
// the last (test_context_done: not one validation message in its life). Each test still starts
// with its log's counts at zero and ends with the checks of test_env_teardown (no validation
// message in the test; none at error level where it sets no_errors), so a message is still
// charged to the test that caused it. For the accuracy tests that render through many pipeline
// variants: lavapipe compiles each pipeline again on every new device (its VkPipelineCache is a
// stub in Mesa 22.3; the disk cache keeps only LLVM's code, not the NIR passes before it), which
// was about 3/4 of engine-tube's and engine-punctual's time with a context per test.
static test_env *test_env_shared;
static inline int test_env_group_setup(void **state)
{
    (void)state;
    test_env_shared = calloc(1, sizeof *test_env_shared);
    assert_non_null(test_env_shared);
    test_env_shared->ctx = test_context(&test_env_shared->log);
    return 0;
}
static inline int test_env_group_teardown(void **state)
{
    (void)state;
    test_context_done(test_env_shared->ctx, &test_env_shared->log);
    free(test_env_shared);
    test_env_shared = NULL;
    return 0;
}
static inline int test_env_shared_setup(void **state)
{
    assert_non_null(test_env_shared);
    test_env_shared->log = (test_log){0};
    test_env_shared->no_errors = false;
    *state = test_env_shared;
    return 0;
}
static inline int test_env_shared_teardown(void **state)
{
    test_env *env = *state;
    assert_int_equal(env->log.validation, 0); // (the context's own end: test_env_group_teardown)
    if (env->no_errors) assert_int_equal(env->log.errors, 0);
    return 0;
}
#define test_env_shared_case(test) cmocka_unit_test_setup_teardown(test, test_env_shared_setup, test_env_shared_teardown)
#define test_env_group(tests) cmocka_run_group_tests(tests, test_env_group_setup, test_env_group_teardown)
// RTPBR_TEST_MAIN (test_main.h) with the group's context: main(void) running the listed tests.
#define RTPBR_TEST_MAIN_SHARED_ENV(...)                                                            \
    int main(void)                                                                                 \
    {                                                                                              \
        RTPBR_RUN_TESTS(test_env_group_setup, test_env_group_teardown, __VA_ARGS__);               \
    }

// rtpbr_gpu_scene_create and rtpbr_renderer_create, which must succeed.
static inline rtpbr_gpu_scene *test_scene(rtpbr_context *ctx, const rtpbr_gpu_scene_desc *desc)
{
    rtpbr_gpu_scene *scene = NULL;
    assert_int_equal(rtpbr_gpu_scene_create(ctx, desc, &scene), RTPBR_SUCCESS);
    return scene;
}
static inline rtpbr_renderer *test_renderer(rtpbr_context *ctx, const rtpbr_renderer_desc *desc)
{
    rtpbr_renderer *r = NULL;
    assert_int_equal(rtpbr_renderer_create(ctx, desc, &r), RTPBR_SUCCESS);
    return r;
}

// rtpbr_render, which must succeed, and its radiance read back into a new w x h RGBA buffer
// (the caller frees it).
static inline float *test_render_radiance(rtpbr_renderer *r, const rtpbr_gpu_scene *scene,
                                          const rtpbr_render_desc *desc, int w, int h)
{
    assert_int_equal(rtpbr_render(r, scene, desc), RTPBR_SUCCESS);
    float *px = malloc((size_t)w * h * 16);
    assert_non_null(px);
    assert_int_equal(test_read_radiance(r, px, (size_t)w * h * 16), RTPBR_SUCCESS);
    return px;
}

// The square [-h, h]^2 in the plane z = z0, facing +Z (counter-clockwise seen from +Z).
static inline void square_positions(float h, float z0, float out[12])
{
    const float p[12] = {-h, -h, z0, h, -h, z0, h, h, z0, -h, h, z0};
    memcpy(out, p, sizeof p);
}
static const uint32_t square_indices[6] = {0, 1, 2, 0, 2, 3};
// That square as a mesh (two triangles, material 0); its positions are written to `positions`.
static inline rtpbr_mesh_desc test_square_mesh(float h, float z0, float positions[12])
{
    square_positions(h, z0, positions);
    return (rtpbr_mesh_desc){.positions = positions, .indices = square_indices, .vertex_count = 4, .index_count = 6};
}

// A Lambertian material of albedo 0.8 (exact in 8 bits: 204 / 255) and no specular lobe.
static const rtpbr_material_desc test_lambert_material = {.base_color = {0.8f, 0.8f, 0.8f}, .roughness = 1.0f,
                                                          .flags = RTPBR_MATERIAL_NO_SPECULAR};

// A scene of one mesh, one material, `light_count` lights and one camera.
static inline rtpbr_gpu_scene *test_mesh_scene(rtpbr_context *ctx, const rtpbr_mesh_desc *mesh,
                                               const rtpbr_material_desc *material, const rtpbr_light_desc *lights,
                                               uint32_t light_count, const rtpbr_camera_desc *camera)
{
    return test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = mesh, .mesh_count = 1,
                                                   .materials = material, .material_count = 1,
                                                   .lights = lights, .light_count = light_count,
                                                   .cameras = camera, .camera_count = 1});
}

// Narkowicz 2015 ACES fit, and the sRGB encoding, written here independently of the shader.
static inline double test_aces(double x)
{
    double y = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    return y < 0.0 ? 0.0 : y > 1.0 ? 1.0 : y;
}
static inline int test_srgb8(double c)
{
    double e = c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
    return (int)lround(e * 255.0);
}


// Lambert's formula: the form factor (1/pi) int cos dw of a polygon seen from x with normal n,
// FF = (1 / 2pi) |sum_i theta_i (n . g_i)|, theta_i the angle subtended by edge i, g_i the
// unit normal of the plane through x and that edge (Lambert 1760; Arvo 1995). Computed here
// in double precision, independently of the shader library. Valid for a polygon above x's
// horizon.
static inline double test_form_factor(const double x[3], const double n[3], const float (*v)[3], uint32_t count)
{
    double sum = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        const float *p = v[i], *q = v[(i + 1) % count];
        double a[3] = {p[0] - x[0], p[1] - x[1], p[2] - x[2]}, b[3] = {q[0] - x[0], q[1] - x[1], q[2] - x[2]};
        double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        double cl = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double theta = atan2(cl, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
        if (cl > 0.0) sum += theta * (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / cl;
    }
    return fabs(sum) / (2.0 * 3.14159265358979323846);
}

// The point of the plane z = 0 seen through the centre of pixel (x, y) of a w x h image by a
// look-at pinhole camera (the documented convention: +Y up); false if the ray misses the plane.
static inline bool test_plane_point(const rtpbr_camera_desc *camera, int x, int y, int w, int h, double p[3])
{
    double f[3] = {camera->target[0] - camera->position[0], camera->target[1] - camera->position[1],
                   camera->target[2] - camera->position[2]};
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int k = 0; k < 3; ++k) f[k] /= fl;
    double s[3] = {-f[2], 0.0, f[0]}; // f x (0, 1, 0)
    double sl = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int k = 0; k < 3; ++k) s[k] /= sl;
    double u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
    double t = tan(0.5 * camera->yfov), aspect = (double)w / h;
    double nx = ((x + 0.5) / w * 2.0 - 1.0) * t * aspect, ny = -((y + 0.5) / h * 2.0 - 1.0) * t;
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = f[k] + nx * s[k] + ny * u[k];
    double hit = -camera->position[2] / d[2];
    p[0] = camera->position[0] + hit * d[0];
    p[1] = camera->position[1] + hit * d[1];
    p[2] = 0.0;
    return hit > 0.0;
}

// The scene of lambertian_plane (test_engine_lambert.c) and mc_lambertian_plane
// (test_engine_mc.c): the plane z = 0, [-4, 4]^2, of test_lambert_material, under a tilted quad
// facing down, a two-sided triangle showing its back to the plane, and a one-sided hexagon
// facing away from the plane (it must add nothing), seen from above at an angle.
typedef struct test_lambert_scene {
    float plane[12];
    rtpbr_mesh_desc mesh;
    rtpbr_light_desc lights[3];
    rtpbr_camera_desc camera;
} test_lambert_scene;

static inline rtpbr_gpu_scene *test_lambert_scene_create(rtpbr_context *ctx, test_lambert_scene *s)
{
    s->mesh = test_square_mesh(4.0f, 0.0f, s->plane);
    const rtpbr_light_desc lights[3] = {
        {.vertices = {{-1.0f, -0.5f, 1.2f}, {-1.0f, 0.7f, 1.5f}, {0.6f, 0.7f, 1.5f}, {0.6f, -0.5f, 1.2f}},
         .vertex_count = 4, .emission = {3.0f, 2.0f, 1.0f}},
        {.vertices = {{1.0f, -1.0f, 0.8f}, {2.0f, -0.5f, 0.9f}, {1.2f, 0.2f, 1.0f}}, .vertex_count = 3,
         .emission = {0.5f, 1.0f, 4.0f}, .two_sided = 1},
        {.vertex_count = 6, .emission = {100.0f, 100.0f, 100.0f}},
    };
    memcpy(s->lights, lights, sizeof lights);
    for (int k = 0; k < 6; ++k) { // counter-clockwise seen from +Z: faces up, away from the plane
        s->lights[2].vertices[k][0] = -1.5f + 0.6f * (float)cos(k * 3.14159265358979323846 / 3.0);
        s->lights[2].vertices[k][1] = 1.5f + 0.6f * (float)sin(k * 3.14159265358979323846 / 3.0);
        s->lights[2].vertices[k][2] = 1.0f;
    }
    // Orientation of the triangle as given: (v1 - v0) x (v2 - v0) has z > 0, so it faces up.
    s->camera = (rtpbr_camera_desc){.position = {0.3f, -0.2f, 3.0f}, .target = {0.2f, 0.0f, 0.0f}, .yfov = 1.2f,
                                    .znear = 0.1f, .zfar = 100.0f};
    return test_mesh_scene(ctx, &s->mesh, &test_lambert_material, s->lights, 3, &s->camera);
}

// The radiance of that scene's plane at its point p, by Lambert's formula: 0.8 times the
// irradiance of the quad and of the triangle (the hexagon faces away).
static inline void test_lambert_scene_radiance(const test_lambert_scene *s, const double p[3], double out[3])
{
    const double n[3] = {0.0, 0.0, 1.0};
    double ff0 = test_form_factor(p, n, s->lights[0].vertices, 4);
    double ff1 = test_form_factor(p, n, s->lights[1].vertices, 3);
    for (int c = 0; c < 3; ++c) out[c] = 0.8 * (s->lights[0].emission[c] * ff0 + s->lights[1].emission[c] * ff1);
}

#endif
