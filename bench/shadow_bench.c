// Shadow benchmark (issue 17): the frame time of a glTF scene with area-light shadows on
// (at several samples per pixel and light) against the same frame without, renders
// interleaved so that machine load hits both alike. Not a test: compare the ratios of one run.
//   rtpbr-bench-shadows SCENE.gltf [--width W] [--height H] [--repeat N] [--samples 1,4,16]
//                       [--cull-ab] [--ray-query auto|on|off]
#define _POSIX_C_SOURCE 200809L
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_time.h"
#include "rtpbr/rtpbr.h"


enum { MAX_CONFIGS = 8, MAX_REPEAT = 64 };

static const char *const usage =
    "usage: rtpbr-bench-shadows SCENE.gltf [--width W] [--height H] [--repeat N] [--samples 1,4,16] [--cull-ab]\n"
    "                           [--ray-query auto|on|off]\n"
    "Frame time of SCENE with area-light shadows at several samples per pixel and light against\n"
    "the same frame without, interleaved; compare the ratios of one run.\n"
    "  --width W       image width (default 960)\n"
    "  --height H      image height (default 720)\n"
    "  --repeat N      rounds (1..64; default 5)\n"
    "  --samples LIST  shadow samples per pixel and light (default 4)\n"
    "  --cull-ab       each shadowed configuration also with shadow-ray culling off\n"
    "  --ray-query M   shadow rays by VK_KHR_ray_query (on), the compute BVH walk (off), or as the\n"
    "                  library chooses (auto, the default: rtpbr_context_desc.shadow_ray_query)\n"
    "  -h, --help      this text\n";

int main(int argc, char **argv)
{
    const char *path = NULL;
    uint32_t width = 960, height = 720;
    int repeat = 5;
    int samples[MAX_CONFIGS] = {0, 4}, configs = 2; // 0: shadows off
    bool no_cull[MAX_CONFIGS] = {false}, cull_ab = false;
    int ray_query = RTPBR_SHADOW_RAY_QUERY_AUTO;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--width") && i + 1 < argc) width = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--height") && i + 1 < argc) height = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--repeat") && i + 1 < argc) repeat = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--samples") && i + 1 < argc) {
            configs = 1;
            char *copy = strdup(argv[++i]), *save = NULL;
            for (char *t = strtok_r(copy, ",", &save); t && configs < MAX_CONFIGS; t = strtok_r(NULL, ",", &save))
                samples[configs++] = atoi(t);
            free(copy);
        } else if (!strcmp(argv[i], "--cull-ab")) cull_ab = true;
        else if (!strcmp(argv[i], "--ray-query") && i + 1 < argc) {
            const char *m = argv[++i];
            if (!strcmp(m, "auto")) ray_query = RTPBR_SHADOW_RAY_QUERY_AUTO;
            else if (!strcmp(m, "on")) ray_query = RTPBR_SHADOW_RAY_QUERY_ON;
            else if (!strcmp(m, "off")) ray_query = RTPBR_SHADOW_RAY_QUERY_OFF;
            else return fputs(usage, stderr), 2;
        }
        else if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) return fputs(usage, stdout), 0;
        else if (argv[i][0] != '-' && !path) path = argv[i];
        else return fputs(usage, stderr), 2;
    }
    if (!path || repeat < 1 || repeat > MAX_REPEAT) return fputs(usage, stderr), 2;
    for (int c = 1, n = configs; cull_ab && c < n && configs < MAX_CONFIGS; ++c) {
        samples[configs] = samples[c];
        no_cull[configs++] = true;
    }
    rtpbr_context *ctx = NULL;
    rtpbr_gpu_scene *scene = NULL;
    rtpbr_renderer *r = NULL;
    int status = 1;
    if (rtpbr_context_create(&(rtpbr_context_desc){.shadow_ray_query = ray_query}, &ctx) != RTPBR_SUCCESS ||
        rtpbr_gpu_scene_load_gltf(ctx, path, &scene) != RTPBR_SUCCESS ||
        rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = width, .height = height}, &r) != RTPBR_SUCCESS) {
        fprintf(stderr, "shadow bench: setup failed\n");
        goto done;
    }
    double wall[MAX_CONFIGS][MAX_REPEAT], cpu[MAX_CONFIGS][MAX_REPEAT];
    for (int rep = -1; rep < repeat; ++rep) // rep -1: warm-up (pipelines compiled on first use)
        for (int c = 0; c < configs; ++c) {
            rtpbr_render_desc desc = {.shadows = samples[c] ? RTPBR_SHADOWS_ON : RTPBR_SHADOWS_OFF,
                                      .shadow_samples = (uint32_t)samples[c],
                                      .shadow_cull = no_cull[c] ? RTPBR_SHADOW_CULL_OFF : RTPBR_SHADOW_CULL_ON};
            double w0 = bench_seconds(CLOCK_MONOTONIC), c0 = bench_seconds(CLOCK_PROCESS_CPUTIME_ID);
            if (rtpbr_render(r, scene, &desc) != RTPBR_SUCCESS) {
                fprintf(stderr, "shadow bench: render failed\n");
                goto done;
            }
            if (rep >= 0) {
                wall[c][rep] = bench_seconds(CLOCK_MONOTONIC) - w0;
                cpu[c][rep] = bench_seconds(CLOCK_PROCESS_CPUTIME_ID) - c0;
            }
        }
    printf("%s, %ux%u, %u lights, shadow rays by %s, median of %d frames\n\n", path, width, height,
           rtpbr_gpu_scene_light_count(scene), rtpbr_context_shadow_ray_query(ctx) ? "ray queries" : "the BVH walk",
           repeat);
    printf("| shadows | wall ms | CPU ms | wall / unshadowed | CPU / unshadowed |\n|---|---|---|---|---|\n");
    double base_wall = 0.0, base_cpu = 0.0;
    for (int c = 0; c < configs; ++c) {
        qsort(wall[c], (size_t)repeat, sizeof(double), bench_compare_double);
        qsort(cpu[c], (size_t)repeat, sizeof(double), bench_compare_double);
        double mw = wall[c][repeat / 2], mc = cpu[c][repeat / 2];
        if (c == 0) base_wall = mw, base_cpu = mc;
        char label[48];
        if (samples[c])
            snprintf(label, sizeof label, "on, %d samples%s", samples[c], no_cull[c] ? ", no culling" : "");
        else snprintf(label, sizeof label, "off");
        printf("| %s | %.1f | %.1f | %.2f | %.2f |\n", label, 1e3 * mw, 1e3 * mc, mw / base_wall, mc / base_cpu);
    }
    status = 0;
done:
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_context_destroy(ctx);
    return status;
}
