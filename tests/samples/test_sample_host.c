// Issue 33's sample host (samples/host) against the engine. The sample's own code (its mesh
// parser, device, geometry pass, rtpbr_lighting_record, tone mapping) renders its bundled
// room with validation and synchronization validation on (any message fails); the engine, on
// the same device, renders the same scene with rtpbr_render: the same triangles, materials and
// lights uploaded through rtpbr_gpu_scene_create, the same camera as an rtpbr_camera_desc.
// The two linear radiance images must agree within 1e-5 relative at every pixel. The check can
// fail: references with one light left out, or with the camera moved by 1 cm, are far off.
// The sample's tone mapping is checked against its formula computed here; the mesh parser's
// refusals give the file, the line and the reason.
#include "test_main.h"

#include "host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// Measured on lavapipe (Mesa 22.3.6): the sample's radiance equals rtpbr_render's bit for bit
// (max relative difference 0): same rasterised triangles, same G-buffer through GBuffer_Encode,
// same lighting pipelines. Held at issue 33's 1e-5.
#define MAX_REL 1e-5

typedef struct stats { double max, mean; int surfaces; } stats;

// Per pixel the largest over r, g, b of |a - b| / max(|b|, 1e-3); alpha (surface or
// background) must agree exactly (counted in mismatched_alpha).
static stats compare(const float *a, const float *b, size_t pixels, size_t *mismatched_alpha)
{
    stats s = {0};
    double sum = 0.0;
    *mismatched_alpha = 0;
    for (size_t i = 0; i < pixels; ++i) {
        double r = 0.0;
        for (int c = 0; c < 3; ++c) r = fmax(r, fabs(a[4 * i + c] - b[4 * i + c]) / fmax(fabs(b[4 * i + c]), 1e-3));
        s.max = fmax(s.max, r);
        sum += r;
        s.surfaces += b[4 * i + 3] == 1.0f;
        *mismatched_alpha += a[4 * i + 3] != b[4 * i + 3];
    }
    s.mean = sum / (double)pixels;
    return s;
}

// rtpbr_render of the scene's triangles (one mesh per material), materials and lights
// [0, light_count), seen by camera; its linear radiance.
static float *engine_render(rtpbr_context *ctx, const sh_scene *s, uint32_t light_count, const rtpbr_camera_desc *camera)
{
    rtpbr_mesh_desc meshes[SH_MAX_MATERIALS];
    rtpbr_material_desc materials[SH_MAX_MATERIALS];
    rtpbr_light_desc lights[SH_MAX_LIGHTS];
    float *positions = malloc((size_t)s->vertex_count * 3 * sizeof(float));
    float *normals = malloc((size_t)s->vertex_count * 3 * sizeof(float));
    assert_true(positions && normals);
    for (uint32_t v = 0; v < s->vertex_count; ++v) {
        memcpy(&positions[3 * v], s->vertices[v].position, 3 * sizeof(float));
        memcpy(&normals[3 * v], s->vertices[v].normal, 3 * sizeof(float));
    }
    uint32_t mesh_count = 0;
    for (uint32_t m = 0; m < s->material_count; ++m) {
        materials[m] = sh_material_record(&s->materials[m]);
        const sh_draw *d = &s->draws[m];
        if (d->vertex_count) // vertices three at a time, in the sample's draw order
            meshes[mesh_count++] = (rtpbr_mesh_desc){.positions = &positions[3 * d->first_vertex],
                .normals = &normals[3 * d->first_vertex], .vertex_count = d->vertex_count, .material = m};
    }
    for (uint32_t i = 0; i < light_count; ++i) lights[i] = sh_light_record(&s->lights[i]);
    rtpbr_gpu_scene *scene = NULL;
    assert_int_equal(rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.meshes = meshes, .mesh_count = mesh_count,
        .materials = materials, .material_count = s->material_count, .lights = lights, .light_count = light_count}, &scene),
        RTPBR_SUCCESS);
    rtpbr_renderer *renderer = NULL;
    assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = s->width, .height = s->height}, &renderer),
                     RTPBR_SUCCESS);
    rtpbr_render_desc rd = {.camera = camera};
    memcpy(rd.background, s->background, sizeof rd.background);
    assert_int_equal(rtpbr_render(renderer, scene, &rd), RTPBR_SUCCESS);
    size_t size = (size_t)s->width * s->height * 16;
    float *out = malloc(size);
    assert_non_null(out);
    assert_int_equal(rtpbr_read_radiance(renderer, out, size), RTPBR_SUCCESS);
    rtpbr_renderer_destroy(renderer);
    rtpbr_gpu_scene_destroy(scene);
    free(positions);
    free(normals);
    return out;
}

static double srgb_encode(double c) // IEC 61966-2-1
{
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

static void sample_host_equals_engine(void **state)
{
    (void)state;
    char error[512] = "";
    sh_scene s;
    if (sh_scene_load(RTPBR_SAMPLE_HOST_MESH, &s, error, sizeof error)) fail_msg("%s", error);
    assert_true(s.light_count >= 2);
    sample_device device;
    if (sample_device_create(&device, "test-sample-host", 1, 1, error, sizeof error)) fail_msg("sample_device_create: %s", error);
    rtpbr_context *ctx = NULL;
    assert_int_equal(rtpbr_context_create(&(rtpbr_context_desc){.embedded = device.vk}, &ctx), RTPBR_SUCCESS);

    // The sample's frame, as rtpbr-sample-host renders it (two frames: the second reuses
    // everything made once).
    size_t pixels = (size_t)s.width * s.height;
    float *hdr = malloc(pixels * 16);
    uint8_t *ldr = malloc(pixels * 4);
    assert_true(hdr && ldr);
    sh_renderer r;
    if (sh_renderer_create(&r, &device, ctx, &s, error, sizeof error)) fail_msg("sh_renderer_create: %s", error);
    for (int frame = 0; frame < 2; ++frame)
        if (sh_render_frame(&r, &s, 0.0f, hdr, ldr, error, sizeof error)) fail_msg("sh_render_frame: %s", error);

    // The engine: the same scene and camera.
    rtpbr_camera_desc camera = {.yfov = s.camera.yfov, .znear = SH_ZNEAR, .zfar = SH_ZFAR};
    memcpy(camera.position, s.camera.position, sizeof camera.position);
    memcpy(camera.target, s.camera.target, sizeof camera.target);
    float *engine = engine_render(ctx, &s, s.light_count, &camera);
    size_t bad_alpha;
    stats st = compare(hdr, engine, pixels, &bad_alpha);
    printf("sample host vs rtpbr_render: %d surface pixels of %zu; relative difference max %.3g, mean %.3g; "
           "alpha differs at %zu\n", st.surfaces, pixels, st.max, st.mean, bad_alpha);
    assert_int_equal(bad_alpha, 0);
    assert_true(st.surfaces > (int)pixels * 9 / 10); // the room fills the view
    assert_true(st.max <= MAX_REL);

    // The comparison can fail: a light left out, or the camera moved by 1 cm.
    float *missing = engine_render(ctx, &s, s.light_count - 1, &camera);
    stats sm = compare(hdr, missing, pixels, &bad_alpha);
    rtpbr_camera_desc moved = camera;
    moved.position[0] += 0.01f;
    float *shifted = engine_render(ctx, &s, s.light_count, &moved);
    size_t shifted_alpha;
    stats ss = compare(hdr, shifted, pixels, &shifted_alpha);
    printf("against a reference without the last light: max %.3g, mean %.3g; with the camera moved 1 cm: "
           "max %.3g, mean %.3g\n", sm.max, sm.mean, ss.max, ss.mean);
    assert_true(sm.max > 0.1 && sm.mean > 0.01);
    assert_true(ss.max > 0.1);

    // The sample's tone mapping: Reinhard on luminance, sRGB, 8 bits (its shader's float
    // arithmetic and the UNORM rounding: within one level). The image is not black.
    double luma = 0.0;
    int off = 0;
    for (size_t i = 0; i < pixels; ++i) {
        double c[3], l = 0.0;
        for (int k = 0; k < 3; ++k) c[k] = fmax(hdr[4 * i + k], 0.0);
        l = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        for (int k = 0; k < 3; ++k) {
            double expect = 255.0 * srgb_encode(fmin(c[k] / (1.0 + l), 1.0));
            off += fabs(ldr[4 * i + k] - expect) > 1.0;
        }
        off += ldr[4 * i + 3] != 255;
        luma += (0.2126 * ldr[4 * i] + 0.7152 * ldr[4 * i + 1] + 0.0722 * ldr[4 * i + 2]) / 255.0;
    }
    luma /= (double)pixels;
    printf("tone mapping: %d channels off by more than one level; mean display luma %.3f\n", off, luma);
    assert_int_equal(off, 0);
    assert_true(luma > 0.1);

    free(engine);
    free(missing);
    free(shifted);
    free(hdr);
    free(ldr);
    sh_renderer_destroy(&r);
    rtpbr_context_destroy(ctx);
    sample_device_destroy(&device);
    assert_int_equal(device.validation_messages, 0);
    sh_scene_free(&s);
}

// A mesh file holding text; its path.
static const char *write_mesh(const char *name, const char *text)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/%s", RTPBR_SAMPLE_HOST_TMP, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    return path;
}

#define HEAD "camera 0 1 3  0 1 0  60\nmaterial m 0.5 0.5 0.5 0 0.5\nquad m -1 0 1  1 0 1  1 0 -1  -1 0 -1\n"
#define LIGHT "light 1 1 1  -1 2 -1  1 2 -1  1 2 1  -1 2 1\n"

static void parser_refuses_bad_files(void **state)
{
    (void)state;
    char error[512];
    sh_scene s;
    // A good file first (the smallest one), then the refusals: each its line and reason.
    assert_int_equal(sh_scene_load(write_mesh("good.mesh", HEAD LIGHT), &s, error, sizeof error), 0);
    assert_int_equal(s.vertex_count, 6);
    assert_int_equal(s.light_count, 1);
    sh_scene_free(&s);
    static const struct { const char *text, *expect; } bad[] = {
        {"material m 0.5 0.5 0.5 0 0.5\nquad m -1 0 1  1 0 1  1 0 -1  -1 0 -1\n", ":2: no camera line"},
        {"camera 0 1 3  0 1 0  60\n", "nothing to draw"},
        {HEAD "quad x -1 0 1  1 0 1  1 0 -1  -1 0 -1\n", ":4: unknown material 'x'"},
        {HEAD "quad m -1 0 1  1 0 1  1 0 -1\n", ":4: quad takes"},
        {HEAD "tri m 0 0 0  1 0 0  2 0 0\n", ":4: degenerate face"},
        {HEAD "quad m -1 0 1  1 0 1  1 1 -1  -1 0 -1\n", ":4: quad is not planar"},
        {HEAD "quad m -1 0 1  1 0 -1  1 0 1  -1 0 -1\n", ":4: quad is not convex"},
        {HEAD "material m 1 1 1 0 0.5\n", ":4: material 'm' defined twice"},
        {HEAD "material n 1 1 1 2 0.5\n", ":4: metallic must be in [0, 1]"},
        {HEAD "material n 1 1 1 0 0.5 glitter 3\n", ":4: material: unexpected 'glitter'"},
        {HEAD "material n 1 nan 1 0 0.5\n", ":4: material: 'nan' is not a finite number"},
        {HEAD "light 1 1 1  -1 2 -1  1 2 -1  1 2 1\n", ":4: light takes"},
        {HEAD "light -1 1 1  -1 2 -1  1 2 -1  1 2 1  -1 2 1\n", ":4: light radiance must not be negative"},
        {HEAD "size 0 10\n", ":4: size: '0' is not a whole number"},
        {"camera 0 1 3  0 1 3  60\n", ":1: camera: the target is the position"},
        {"camera 0 1 3  0 5 3  60\n", ":1: camera: looks straight up or down"},
        {HEAD "teapot 1\n", ":4: unknown keyword 'teapot'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        error[0] = 0;
        const char *path = write_mesh("bad.mesh", bad[i].text);
        assert_int_not_equal(sh_scene_load(path, &s, error, sizeof error), 0);
        printf("refused: %s\n", error);
        if (!strstr(error, bad[i].expect)) fail_msg("case %zu: '%s' does not say '%s'", i, error, bad[i].expect);
        assert_null(s.vertices);
    }
    // More lights than the host's light set holds.
    size_t size = strlen(HEAD) + (SH_MAX_LIGHTS + 1) * strlen(LIGHT) + 1;
    char *many = malloc(size);
    assert_non_null(many);
    strcpy(many, HEAD);
    for (uint32_t i = 0; i <= SH_MAX_LIGHTS; ++i) strcat(many, LIGHT);
    assert_int_not_equal(sh_scene_load(write_mesh("many.mesh", many), &s, error, sizeof error), 0);
    free(many);
    printf("refused: %s\n", error);
    assert_non_null(strstr(error, ":68: too many lights (at most 64)"));
    // A file that is not there.
    assert_int_not_equal(sh_scene_load(RTPBR_SAMPLE_HOST_TMP "/none/x.mesh", &s, error, sizeof error), 0);
    assert_non_null(strstr(error, "cannot open"));
}

// The camera handed as the host's own matrices, then with a reversed-Z projection (depth cleared
// to 0, compared GREATER_OR_EQUAL, rtpbr_lighting_record_desc.reversed_z set), on a scene whose
// upper part is background: every pixel's surface-or-background flag (alpha) must be the same
// in the three modes and the background must read the background radiance, and the radiance
// must agree. Not bit for bit: each mode reconstructs positions through another matrix and
// depth encoding, and lifts the shading point by a few of its own depth quanta
// (lighting_common.glsl), so lights seen at grazing angles differ slightly. A lighting pass that
// took reversed-Z depth for the standard one would shade the background (depth 0) as surfaces
// at the near plane: caught by the alpha check (tried: all 8,990 background pixels of 19,200).
static void sample_host_camera_modes(void **state)
{
    (void)state;
    const char *path = write_mesh("modes.mesh",
        "size 160 120\ncamera 0 1.2 3  0 0.6 0  55\nbackground 0.1 0.2 0.4\n"
        "material floor 0.6 0.6 0.6 0 0.5\nmaterial copper 0.955 0.638 0.538 1 0.35\n"
        "quad floor -4 0 4  4 0 4  4 0 -4  -4 0 -4\n"
        "quad copper -0.4 0.8 0.4  0.4 0.8 0.4  0.4 0.8 -0.4  -0.4 0.8 -0.4\n"
        "quad copper -0.4 0 0.4  0.4 0 0.4  0.4 0.8 0.4  -0.4 0.8 0.4\n"
        "quad copper 0.4 0 0.4  0.4 0 -0.4  0.4 0.8 -0.4  0.4 0.8 0.4\n"
        "quad copper -0.4 0 -0.4  -0.4 0 0.4  -0.4 0.8 0.4  -0.4 0.8 -0.4\n"
        "light 6 6 6  -0.5 2 -0.5  0.5 2 -0.5  0.5 2 0.5  -0.5 2 0.5\n"
        "light 3 2 1  1.5 0.2 -1  1.5 1.2 -1  1.5 1.2 0  1.5 0.2 0\n");
    char error[512] = "";
    sh_scene s;
    if (sh_scene_load(path, &s, error, sizeof error)) fail_msg("%s", error);
    sample_device device;
    if (sample_device_create(&device, "test-sample-host", 1, 1, error, sizeof error)) fail_msg("sample_device_create: %s", error);
    rtpbr_context *ctx = NULL;
    assert_int_equal(rtpbr_context_create(&(rtpbr_context_desc){.embedded = device.vk}, &ctx), RTPBR_SUCCESS);
    size_t pixels = (size_t)s.width * s.height;
    float *hdr[3];
    sh_renderer r;
    if (sh_renderer_create(&r, &device, ctx, &s, error, sizeof error)) fail_msg("sh_renderer_create: %s", error);
    const sh_camera_mode modes[3] = {SH_CAMERA_RTPBR, SH_CAMERA_MATRICES, SH_CAMERA_REVERSED_Z};
    for (int m = 0; m < 3; ++m) {
        hdr[m] = malloc(pixels * 16);
        assert_non_null(hdr[m]);
        r.camera_mode = modes[m];
        if (sh_render_frame(&r, &s, 0.0f, hdr[m], NULL, error, sizeof error)) fail_msg("sh_render_frame: %s", error);
    }
    size_t background = 0, wrong_background = 0;
    for (size_t i = 0; i < pixels; ++i) {
        if (hdr[2][4 * i + 3] != 0.0f) continue;
        ++background;
        for (int c = 0; c < 3; ++c) wrong_background += hdr[2][4 * i + c] != s.background[c];
    }
    size_t bad_alpha[2];
    stats matrices = compare(hdr[1], hdr[0], pixels, &bad_alpha[0]);
    stats reversed = compare(hdr[2], hdr[1], pixels, &bad_alpha[1]);
    printf("camera modes: %zu background pixels of %zu (%zu wrong channels); the host's matrices against rtpbr's "
           "camera: max %.3g, mean %.3g, alpha differs at %zu; reversed-Z against them: max %.3g, mean %.3g, alpha "
           "differs at %zu\n", background, pixels, wrong_background, matrices.max, matrices.mean, bad_alpha[0],
           reversed.max, reversed.mean, bad_alpha[1]);
    assert_true(background > pixels / 5 && background < pixels * 4 / 5);
    assert_int_equal(wrong_background, 0);
    assert_int_equal(bad_alpha[0], 0);
    assert_int_equal(bad_alpha[1], 0);
    // Measured on lavapipe: the host's matrices against rtpbr's camera max 0 (this scene; the
    // room differs at a few dark pixels, frame.c); reversed-Z against them max 3.8e-4, mean
    // 2.4e-5. Held at 5x.
    assert_true(matrices.max <= 1e-5);
    assert_true(reversed.max <= 2e-3 && reversed.mean <= 1.2e-4);
    for (int m = 0; m < 3; ++m) free(hdr[m]);
    sh_renderer_destroy(&r);
    rtpbr_context_destroy(ctx);
    sample_device_destroy(&device);
    assert_int_equal(device.validation_messages, 0);
    sh_scene_free(&s);
}

RTPBR_TEST_MAIN(cmocka_unit_test(parser_refuses_bad_files), cmocka_unit_test(sample_host_equals_engine),
                cmocka_unit_test(sample_host_camera_modes))
