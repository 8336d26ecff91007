// Engine benchmark: frame time of rtpbr_render on the current device against the number of
// polygonal lights and the resolution, with per-tile culling at its default threshold and
// without distance culling. Not a test: numbers depend on the machine; compare the ratios
// printed in one run.
//   rtpbr-bench-engine [--repeat N] [--sizes 1280x720,512] [--lights 0,16,64] [--cpu] [--cull X]
// Per size it prints the median frame time for each light count (with tile culling at its
// default threshold, and with every light shaded that faces the tile), then the fixed cost per
// pixel (the frame with no lights) and the cost per pixel-light, (t(L) - t(0)) / (pixels L),
// when 0 is in the light list; otherwise t(L) / (pixels L).
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_time.h"
#include "rtpbr/rtpbr.h"

// The culling threshold of the culled frames (--cull; rtpbr_render_desc.light_cull_form_factor,
// 0: the engine's default).
static float cull_form_factor = 0.0f;
// --passes: each culled row also gives the GPU time of each pass (rtpbr_renderer_timings,
// medians over the frames) and what the frame's time has beyond them (submit, wait).
static int show_passes = 0;
// --readback: after each culled frame, rtpbr_read_radiance and rtpbr_read_display, timed apart
// from the frame (the copies a frame that is read back costs besides rtpbr_render: they are
// made by the first read of a frame).
static int show_readback = 0;

// Wall-clock time, or with --cpu the CPU time of the whole process (lavapipe's worker threads
// included): steadier than wall time on a shared machine, and what a software device spends.
static clockid_t bench_clock = CLOCK_MONOTONIC;

static double now(void)
{
    return bench_seconds(bench_clock);
}

static int parse_list(const char *text, int *out, int max)
{
    int n = 0;
    char *copy = strdup(text), *save = NULL;
    for (char *tok = strtok_r(copy, ",", &save); tok && n < max; tok = strtok_r(NULL, ",", &save)) out[n++] = atoi(tok);
    free(copy);
    return n;
}

// "W" or "WxH" items.
static int parse_sizes(const char *text, int (*out)[2], int max)
{
    int n = 0;
    char *copy = strdup(text), *save = NULL;
    for (char *tok = strtok_r(copy, ",", &save); tok && n < max; tok = strtok_r(NULL, ",", &save)) {
        char *x = strchr(tok, 'x');
        out[n][0] = atoi(tok);
        out[n][1] = x ? atoi(x + 1) : out[n][0];
        if (out[n][0] > 0 && out[n][1] > 0) n++;
    }
    free(copy);
    return n;
}

// The scenes (--scene), each a 60 m floor under n small square lights:
//   benchmark  a rough dielectric floor seen from 12 m back and 14 m up, lights at 0.5 to 3 m
//              scattered by a fixed linear congruential sequence, one in four facing up;
//   floor      a rough metal floor seen at 45 degrees from above, the lights in a grid over
//              the view, 2 to 3 m up, all facing down: every pixel sees every light and
//              culling keeps them all (issue 32's "scene unlike the benchmark's");
//   full       the benchmark's layout with a material that needs the full lighting variant
//              (clear coat, sheen and anisotropy on metallic-roughness);
//   points     the benchmark's layout with point lights (KHR_lights_punctual's) at the
//              squares' centres, of the squares' intensity seen head-on (radiance x area):
//              the cost of a punctual light (issue 30);
//   spheres    the same with a radius: spheres of the squares' area (pi r^2 = the square's)
//              and intensity (the spheres' lighting variants: issue 30);
//   disks      the benchmark's squares as disks of their area, radiance and facing (the
//              spheres' lighting variants, AreaLight_AddDisk: issue 30);
//   textured   the benchmark's squares with an emission texture (a 64 x 64 checker of 8 x 8
//              squares, one for all: AreaLight_AddTexturedQuad in the spheres' variants);
//   tubes      the benchmark's squares as tubes (capsules) along x, as long as the square's
//              side, of a quarter of its half-side in radius, of its radiance (the tubes'
//              lighting variants, AreaLight_AddTube: issue 30);
//   many       the benchmark's layout with its lights' total area held at 16 lights': n > 16
//              lights have sqrt(16 / n) of the side, so 1,024 lights are 64 times as many, an
//              eighth of the side, the same power in all (issue 32's "1,024 small lights",
//              read as a lighting budget spread over more, smaller lights; the benchmark
//              scene is the other reading, lights of the same size at 64x the density).
typedef enum bench_scene { SCENE_BENCHMARK, SCENE_FLOOR, SCENE_FULL, SCENE_POINTS, SCENE_SPHERES, SCENE_DISKS,
                           SCENE_TEXTURED, SCENE_TUBES, SCENE_MANY, SCENE_COUNT } bench_scene;
static const char *const scene_names[SCENE_COUNT] = {"benchmark", "floor", "full", "points", "spheres", "disks",
                                                     "textured", "tubes", "many"};

static void square_light(rtpbr_light_desc *light, float x, float y, float z, float s, int up)
{
    float v[4][3] = {{x - s, y - s, z}, {x - s, y + s, z}, {x + s, y + s, z}, {x + s, y - s, z}};
    for (int k = 0; k < 4; ++k) memcpy(light->vertices[up ? 3 - k : k], v[k], sizeof v[k]);
    light->vertex_count = 4;
    light->emission[0] = light->emission[1] = light->emission[2] = 20.0f;
}

static rtpbr_result make_scene(rtpbr_context *ctx, bench_scene kind, int n, rtpbr_gpu_scene **out)
{
    static const float h = 30.0f;
    float plane[12] = {-h, -h, 0, h, -h, 0, h, h, 0, -h, h, 0};
    static const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    rtpbr_material_desc material = {.base_color = {0.7f, 0.7f, 0.7f}, .roughness = 0.4f};
    rtpbr_camera_desc camera = {.position = {0.0f, -12.0f, 14.0f}, .yfov = 1.0f, .znear = 0.1f, .zfar = 200.0f};
    if (kind == SCENE_FLOOR) {
        material = (rtpbr_material_desc){.base_color = {0.95f, 0.64f, 0.54f}, .metallic = 1.0f, .roughness = 0.5f};
        camera = (rtpbr_camera_desc){.position = {0.0f, -6.0f, 6.0f}, .target = {0.0f, 0.0f, 0.0f}, .yfov = 1.0f,
                                     .znear = 0.1f, .zfar = 200.0f};
    } else if (kind == SCENE_FULL) {
        material.clearcoat_factor = 1.0f;
        material.clearcoat_roughness_factor = 0.1f;
        material.sheen_color_factor[0] = material.sheen_color_factor[1] = material.sheen_color_factor[2] = 0.5f;
        material.sheen_roughness_factor = 0.5f;
        material.anisotropy_strength = 0.6f;
    }
    rtpbr_mesh_desc mesh = {.positions = plane, .indices = indices, .vertex_count = 4, .index_count = 6};
    rtpbr_light_desc *lights = calloc((size_t)(n > 0 ? n : 1), sizeof *lights);
    if (!lights) return RTPBR_ERROR_OUT_OF_HOST_MEMORY;
    uint32_t seed = 12345u;
    int side = 1;
    while (side * side < n) ++side;
    for (int i = 0; i < n; ++i) {
        if (kind == SCENE_FLOOR) { // a side x side grid over the 8 m x 8 m around the view's centre
            float x = -4.0f + 8.0f * ((float)(i % side) + 0.5f) / (float)side;
            float y = -4.0f + 8.0f * ((float)(i / side) + 0.5f) / (float)side;
            square_light(&lights[i], x, y, 2.0f + (float)(i % 3) * 0.5f, 0.1f, 0);
            continue;
        }
        seed = seed * 1664525u + 1013904223u;
        float x = -28.0f + 56.0f * (float)(seed >> 8) / 16777216.0f;
        seed = seed * 1664525u + 1013904223u;
        float y = -28.0f + 56.0f * (float)(seed >> 8) / 16777216.0f;
        float z = 0.5f + 2.5f * (float)(i % 7) / 6.0f, half = 0.1f + 0.05f * (float)(i % 5);
        if (kind == SCENE_MANY && n > 16) half *= sqrtf(16.0f / (float)n);
        if (kind == SCENE_POINTS || kind == SCENE_SPHERES)
            lights[i] = (rtpbr_light_desc){.type = RTPBR_LIGHT_POINT, .position = {x, y, z},
                                           .emission = {20.0f * 4.0f * half * half, 20.0f * 4.0f * half * half,
                                                        20.0f * 4.0f * half * half},
                                           .radius = kind == SCENE_SPHERES ? 2.0f * half / 1.7724539f : 0.0f};
        else if (kind == SCENE_DISKS)
            lights[i] = (rtpbr_light_desc){.type = RTPBR_LIGHT_DISK, .position = {x, y, z},
                                           .direction = {0.0f, 0.0f, i % 4 == 3 ? 1.0f : -1.0f},
                                           .radius = 2.0f * half / 1.7724539f, .emission = {20.0f, 20.0f, 20.0f}};
        else if (kind == SCENE_TUBES)
            lights[i] = (rtpbr_light_desc){.type = RTPBR_LIGHT_TUBE, .position = {x, y, z}, .direction = {1.0f, 0.0f, 0.0f},
                                           .length = 2.0f * half, .radius = 0.25f * half, .emission = {20.0f, 20.0f, 20.0f}};
        else
            square_light(&lights[i], x, y, z, half, i % 4 == 3);
        if (kind == SCENE_TEXTURED) lights[i].emission_texture = 1;
    }
    static uint8_t checker[64 * 64 * 4];
    for (int t = 0; t < 64 * 64; ++t)
        for (int c = 0; c < 4; ++c) checker[4 * t + c] = c == 3 || ((t % 64) / 8 + (t / 64) / 8) % 2 ? 255 : 40;
    rtpbr_texture_desc texture = {.width = 64, .height = 64, .rgba = checker};
    rtpbr_gpu_scene_desc desc = {.meshes = &mesh, .mesh_count = 1, .materials = &material, .material_count = 1,
                                 .lights = lights, .light_count = (uint32_t)n, .cameras = &camera, .camera_count = 1,
                                 .textures = &texture, .texture_count = kind == SCENE_TEXTURED ? 1 : 0};
    rtpbr_result r = rtpbr_gpu_scene_create(ctx, &desc, out);
    free(lights);
    return r;
}

// One scene's table: for each size and light count, the median frame time with culling and with
// every light, and the costs per pixel and per pixel-light. t: scratch for `repeat` times.
static rtpbr_result run_scene(rtpbr_context *ctx, bench_scene scene_kind, const int (*sizes)[2], int size_count,
                              const int *lights, int light_count, int repeat, double *t)
{
    rtpbr_result r = RTPBR_SUCCESS;
    printf("# scene: %s\n", scene_names[scene_kind]);
    for (int si = 0; si < size_count && r == RTPBR_SUCCESS; ++si) {
        rtpbr_renderer *renderer = NULL;
        int w = sizes[si][0], h = sizes[si][1];
        double base[2] = {0.0, 0.0}; // the frame with no lights, when measured
        char label[32];
        snprintf(label, sizeof label, "%dx%d", w, h);
        r = rtpbr_renderer_create(
            ctx, &(rtpbr_renderer_desc){.width = (uint32_t)w, .height = (uint32_t)h, .timings = show_passes}, &renderer);
        for (int li = 0; li < light_count && r == RTPBR_SUCCESS; ++li) {
            rtpbr_gpu_scene *scene = NULL;
            r = make_scene(ctx, scene_kind, lights[li], &scene);
            double ms[2] = {0.0, 0.0}, pass[3][1000], pass_ms[3] = {0.0, 0.0, 0.0}, read[1000], read_ms = 0.0;
            float *radiance = show_readback ? malloc((size_t)w * h * 16) : NULL;
            uint8_t *display = show_readback ? malloc((size_t)w * h * 4) : NULL;
            if (show_readback && (!radiance || !display)) r = RTPBR_ERROR_OUT_OF_HOST_MEMORY;
            for (int mode = 0; mode < 2 && r == RTPBR_SUCCESS; ++mode) {
                rtpbr_render_desc rd = {.light_cull_form_factor = mode == 0 ? cull_form_factor : -1.0f};
                r = rtpbr_render(renderer, scene, &rd); // warm-up
                for (int k = 0; k < repeat && r == RTPBR_SUCCESS; ++k) {
                    double t0 = now();
                    r = rtpbr_render(renderer, scene, &rd);
                    t[k] = now() - t0;
                    rtpbr_timings tm = {0};
                    if (r == RTPBR_SUCCESS && show_passes && mode == 0) r = rtpbr_renderer_timings(renderer, &tm);
                    pass[0][k] = tm.gbuffer_ms, pass[1][k] = tm.lighting_ms, pass[2][k] = tm.tonemap_ms;
                    if (r == RTPBR_SUCCESS && show_readback && mode == 0) {
                        double t1 = now();
                        r = rtpbr_read_radiance(renderer, radiance, (size_t)w * h * 16);
                        if (r == RTPBR_SUCCESS) r = rtpbr_read_display(renderer, display, (size_t)w * h * 4);
                        read[k] = now() - t1;
                    }
                }
                if (show_readback && mode == 0 && r == RTPBR_SUCCESS) {
                    qsort(read, (size_t)repeat, sizeof read[0], bench_compare_double);
                    read_ms = 1e3 * read[repeat / 2];
                }
                for (int q = 0; q < 3 && show_passes && mode == 0; ++q) {
                    qsort(pass[q], (size_t)repeat, sizeof pass[q][0], bench_compare_double);
                    pass_ms[q] = pass[q][repeat / 2];
                }
                qsort(t, (size_t)repeat, sizeof *t, bench_compare_double);
                ms[mode] = 1e3 * t[repeat / 2];
            }
            double px = (double)w * h;
            if (r == RTPBR_SUCCESS && lights[li] == 0) {
                base[0] = ms[0];
                base[1] = ms[1];
                printf("%10s %6d %12.2f %12.2f %16s %16s   fixed: %.1f ns/px\n", label, 0, ms[0], ms[1], "-", "-",
                       1e6 * ms[0] / px);
            } else if (r == RTPBR_SUCCESS) {
                double pl = px * lights[li];
                printf("%10s %6d %12.2f %12.2f %16.2f %16.2f\n", label, lights[li], ms[0], ms[1],
                       1e6 * (ms[0] - base[0]) / pl, 1e6 * (ms[1] - base[1]) / pl);
            }
            if (r == RTPBR_SUCCESS && show_passes)
                printf("%10s %6d   culled, GPU ms: G-buffer %.2f, lighting %.2f, tone mapping %.2f; the rest of the "
                       "frame %.2f\n", label, lights[li], pass_ms[0], pass_ms[1], pass_ms[2],
                       ms[0] - pass_ms[0] - pass_ms[1] - pass_ms[2]);
            if (r == RTPBR_SUCCESS && show_readback)
                printf("%10s %6d   read back after the culled frame (rtpbr_read_radiance and rtpbr_read_display): "
                       "%.2f ms, %.1f ns/px\n", label, lights[li], read_ms, 1e6 * read_ms / ((double)w * h));
            free(radiance);
            free(display);
            fflush(stdout);
            rtpbr_gpu_scene_destroy(scene);
        }
        rtpbr_renderer_destroy(renderer);
    }
    return r;
}

static const char *const usage =
    "usage: rtpbr-bench-engine [--repeat N] [--sizes 1280x720,512] [--lights 0,16,64] [--cpu] [--cull X]\n"
    "                          [--passes] [--readback]\n"
    "                          [--scene benchmark|floor|full|points|spheres|disks|textured|tubes|many|all]\n"
    "Median frame time of rtpbr_render against light count and resolution; compare the ratios\n"
    "printed in one run.\n"
    "  --repeat N     frames per configuration (1..1000; default 5)\n"
    "  --sizes LIST   resolutions, WxH or N for N x N (default 128,256,512)\n"
    "  --lights LIST  light counts (default 0,1,4,16,64,256)\n"
    "  --cpu          the process CPU time (lavapipe's threads included) instead of wall time\n"
    "  --passes       also the culled frames' GPU time per pass (G-buffer, lighting, tone mapping)\n"
    "                 and the rest of the frame (submit, wait)\n"
    "  --readback     also the time of rtpbr_read_radiance and rtpbr_read_display after each culled\n"
    "                 frame (their copies, made by a frame's first read; not in the frame time)\n"
    "  --cull X       the culled frames' light_cull_form_factor (default 0: the engine's default,\n"
    "                 RTPBR_DEFAULT_CULL_FORM_FACTOR)\n"
    "  --scene NAME   benchmark, floor (metal floor at 45 degrees, every light seen by\n"
    "                 every pixel), full (materials of the full lighting variant), points\n"
    "                 (the benchmark's layout with point lights), spheres (with radii), disks, textured, tubes,\n"
    "                 many (the benchmark's layout, n > 16 lights of 16 lights' total area), all\n"
    "                 (default)\n"
    "  -h, --help     this text\n";

int main(int argc, char **argv)
{
    int repeat = 5, sizes[8][2] = {{128, 128}, {256, 256}, {512, 512}}, lights[16] = {0, 1, 4, 16, 64, 256};
    int size_count = 3, light_count = 6, scene_first = 0, scene_last = SCENE_COUNT - 1;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--repeat") && i + 1 < argc) repeat = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--sizes") && i + 1 < argc) size_count = parse_sizes(argv[++i], sizes, 8);
        else if (!strcmp(argv[i], "--lights") && i + 1 < argc) light_count = parse_list(argv[++i], lights, 16);
        else if (!strcmp(argv[i], "--cpu")) bench_clock = CLOCK_PROCESS_CPUTIME_ID;
        else if (!strcmp(argv[i], "--passes")) show_passes = 1;
        else if (!strcmp(argv[i], "--readback")) show_readback = 1;
        else if (!strcmp(argv[i], "--cull") && i + 1 < argc) cull_form_factor = strtof(argv[++i], NULL);
        else if (!strcmp(argv[i], "--scene") && i + 1 < argc) {
            const char *name = argv[++i];
            scene_first = strcmp(name, "all") == 0 ? 0 : -1;
            scene_last = scene_first == 0 ? SCENE_COUNT - 1 : -1;
            for (int k = 0; k < SCENE_COUNT && scene_first < 0; ++k)
                if (!strcmp(name, scene_names[k])) scene_first = scene_last = k;
            if (scene_first < 0) return fprintf(stderr, "rtpbr-bench-engine: unknown scene '%s'\n%s", name, usage), 2;
        }
        else if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) return fputs(usage, stdout), 0;
        else return fputs(usage, stderr), 2;
    }
    if (repeat < 1 || repeat > 1000) repeat = 5;
    rtpbr_context *ctx = NULL;
    rtpbr_result r = rtpbr_context_create(&(rtpbr_context_desc){0}, &ctx);
    if (r != RTPBR_SUCCESS) {
        fprintf(stderr, "rtpbr-bench-engine: %s\n", rtpbr_result_string(r));
        return 1;
    }
    printf("# device: %s; median of %d frames (%s time); ns per pixel-light = (frame time - the 0-light frame's) / "
           "(pixels x lights)\n",
           rtpbr_context_device_name(ctx), repeat, bench_clock == CLOCK_MONOTONIC ? "wall" : "process CPU");
    printf("%10s %6s %12s %12s %16s %16s\n", "size", "lights", "culled_ms", "all_ms", "culled_ns/px/l",
           "all_ns/px/l");
    double *t = calloc((size_t)repeat, sizeof *t);
    for (int k = scene_first; k <= scene_last && r == RTPBR_SUCCESS && t; ++k)
        r = run_scene(ctx, (bench_scene)k, (const int (*)[2])sizes, size_count, lights, light_count, repeat, t);
    free(t);
    if (r != RTPBR_SUCCESS) fprintf(stderr, "rtpbr-bench-engine: %s\n", rtpbr_result_string(r));
    rtpbr_context_destroy(ctx);
    return r == RTPBR_SUCCESS ? 0 : 1;
}
