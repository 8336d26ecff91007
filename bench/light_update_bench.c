// Light-update benchmark (issue 33): the CPU cost of moving and recolouring every light of a
// frame, through rtpbr_light_set_update (the lighting-only path: records written into the
// set's persistently mapped region of the frame in flight) against
// rtpbr_gpu_scene_set_lights (a scene's lights: the same validation and records, plus a host
// allocation for the derived facts per call). Blocks of both interleaved, so that machine load
// hits both alike; medians over the blocks. Not a test: read the ratio of one run.
//   rtpbr-bench-light-update [--lights N] [--updates N] [--blocks N]
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rtpbr/rtpbr.h"

// Nanoseconds of CLOCK_MONOTONIC.
static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1e9 * (double)t.tv_sec + (double)t.tv_nsec;
}

// The median of v[0 .. n) (sorted in place, by insertion: n is small).
static double median(double *v, uint32_t n)
{
    for (uint32_t i = 1; i < n; ++i)
        for (uint32_t j = i; j > 0 && v[j - 1] > v[j]; --j) {
            double x = v[j];
            v[j] = v[j - 1], v[j - 1] = x;
        }
    return v[n / 2];
}

// Frame `frame`'s lights: quads facing down on a circle that turns, colours that cycle.
static void animate(rtpbr_light_desc *lights, uint32_t count, uint32_t frame)
{
    float t = 0.01f * (float)frame;
    for (uint32_t i = 0; i < count; ++i) {
        float a = t + 6.2831853f * (float)i / (float)count, x = 4.0f * cosf(a), z = 4.0f * sinf(a), s = 0.2f;
        rtpbr_light_desc l = {.vertex_count = 4,
                              .vertices = {{x - s, 3, z - s}, {x + s, 3, z - s}, {x + s, 3, z + s}, {x - s, 3, z + s}},
                              .emission = {1.0f + sinf(a), 1.0f + cosf(a), 1.5f}};
        lights[i] = l;
    }
}

enum { MAX_BLOCKS = 64 };

int main(int argc, char **argv)
{
    uint32_t count = 64, updates = 2000, blocks = 15;
    for (int i = 1; i < argc; ++i) {
        if (i + 1 < argc && strcmp(argv[i], "--lights") == 0) count = (uint32_t)atoi(argv[++i]);
        else if (i + 1 < argc && strcmp(argv[i], "--updates") == 0) updates = (uint32_t)atoi(argv[++i]);
        else if (i + 1 < argc && strcmp(argv[i], "--blocks") == 0) blocks = (uint32_t)atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: rtpbr-bench-light-update [--lights N (1..1024, default 64)] [--updates N "
                            "(per block, default 2000)] [--blocks N (1..64, default 15)]\n");
            return 2;
        }
    }
    if (count < 1 || count > RTPBR_MAX_LIGHTS || updates < 1 || blocks < 1 || blocks > MAX_BLOCKS) {
        fprintf(stderr, "rtpbr-bench-light-update: arguments out of range\n");
        return 2;
    }
    rtpbr_context *ctx = NULL;
    rtpbr_result r = rtpbr_context_create(&(rtpbr_context_desc){0}, &ctx);
    if (r != RTPBR_SUCCESS) {
        fprintf(stderr, "context: %s\n", rtpbr_result_string(r));
        return 1;
    }
    rtpbr_light_desc *lights = calloc(count, sizeof *lights);
    rtpbr_light_set *set = NULL;
    rtpbr_gpu_scene *scene = NULL;
    int status = 1;
    if (!lights) goto done;
    animate(lights, count, 0);
    if (rtpbr_light_set_create(ctx, &(rtpbr_light_set_desc){.capacity = count, .frames_in_flight = 2}, &set) ||
        rtpbr_gpu_scene_create(ctx, &(rtpbr_gpu_scene_desc){.lights = lights, .light_count = count}, &scene))
        goto done;
    double set_ns[MAX_BLOCKS], scene_ns[MAX_BLOCKS], animate_ns[MAX_BLOCKS];
    uint32_t frame = 0;
    for (uint32_t b = 0; b < blocks; ++b) {
        // The animation alone (what both columns include), then each update path.
        double t0 = now_ns();
        for (uint32_t u = 0; u < updates; ++u) animate(lights, count, ++frame);
        double t1 = now_ns();
        for (uint32_t u = 0; u < updates; ++u) {
            animate(lights, count, ++frame);
            if (rtpbr_light_set_update(set, frame % 2, lights, count)) goto done;
        }
        double t2 = now_ns();
        for (uint32_t u = 0; u < updates; ++u) {
            animate(lights, count, ++frame);
            if (rtpbr_gpu_scene_set_lights(scene, lights, count)) goto done;
        }
        double t3 = now_ns();
        animate_ns[b] = (t1 - t0) / updates;
        set_ns[b] = (t2 - t1) / updates - animate_ns[b];
        scene_ns[b] = (t3 - t2) / updates - animate_ns[b];
    }
    double a = median(set_ns, blocks), s = median(scene_ns, blocks);
    printf("%u lights, %u blocks of %u updates (medians; the host's animation, %.0f ns, subtracted)\n", count, blocks,
           updates, median(animate_ns, blocks));
    printf("rtpbr_light_set_update      %9.0f ns per update  %6.1f ns per light\n", a, a / count);
    printf("rtpbr_gpu_scene_set_lights  %9.0f ns per update  %6.1f ns per light\n", s, s / count);
    printf("ratio light_set / scene     %9.2f\n", a / s);
    status = 0;
done:
    if (status) fprintf(stderr, "rtpbr-bench-light-update: a call failed\n");
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_light_set_destroy(set);
    rtpbr_context_destroy(ctx);
    free(lights);
    return status;
}
