// Light-update benchmark (issue 33): the CPU cost of moving and recolouring every light of a
// frame, through rtpbr_light_set_update (the lighting-only path: records written into the
// set's persistently mapped region of the frame in flight) against
// rtpbr_gpu_scene_set_lights (a scene's lights: the same validation and records, plus a host
// allocation for the derived facts per call). Blocks of both interleaved, so that machine load
// hits both alike; medians over the blocks. Then the CPU cost of rtpbr_lighting_record itself
// (into a command buffer begun, ended and reset each time, never submitted; targets on images
// made with tests/common/vk_draw), less that of an empty begin/end/reset. Not a test: read the
// ratio of one run.
//   rtpbr-bench-light-update [--lights N] [--updates N] [--blocks N]
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rtpbr/rtpbr.h"
#include "vk_draw.h"

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

// The CPU time of rtpbr_lighting_record at 1280 x 720 (median over blocks), printed; non-zero
// when a call failed.
static int record_cost(rtpbr_context *ctx, rtpbr_light_set *set, uint32_t updates, uint32_t blocks)
{
    rtpbr_vulkan_device d = rtpbr_context_vulkan_device(ctx);
    vk_host h = {.instance = d.instance, .physical_device = d.physical_device, .device = d.device,
                 .queue_family = d.queue_family_index, .queue = d.queue};
    enum { W = 1280, H = 720 };
    static const VkFormat formats[4] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT,
                                        VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT};
    vk_draw_image images[6] = {{0}};
    rtpbr_lighting_targets_desc td = {.width = W, .height = H, .frames_in_flight = 2};
    VkResult r = VK_SUCCESS;
    for (int i = 0; i < 4 && !r; ++i) {
        r = vk_draw_image_create(&h, formats[i], W, H, 1, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                 &images[i]);
        td.gbuffer[i] = (rtpbr_host_image){images[i].image, images[i].view, formats[i]};
    }
    if (!r) r = vk_draw_image_create(&h, VK_FORMAT_D32_SFLOAT, W, H, 1, VK_IMAGE_USAGE_SAMPLED_BIT |
                                     VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, &images[4]);
    if (!r) r = vk_draw_image_create(&h, VK_FORMAT_R32G32B32A32_SFLOAT, W, H, 1, VK_IMAGE_USAGE_STORAGE_BIT, &images[5]);
    td.depth = (rtpbr_host_image){images[4].image, images[4].view, VK_FORMAT_D32_SFLOAT};
    td.output = (rtpbr_host_image){images[5].image, images[5].view, VK_FORMAT_R32G32B32A32_SFLOAT};
    rtpbr_lighting_targets *targets = NULL;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    int failed = 1;
    VkCommandPoolCreateInfo pool_info = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                         .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                         .queueFamilyIndex = d.queue_family_index};
    if (r || rtpbr_lighting_targets_create(ctx, &td, &targets) || vkCreateCommandPool(d.device, &pool_info, NULL, &pool))
        goto done;
    VkCommandBufferAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                         .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    if (vkAllocateCommandBuffers(d.device, &alloc, &cmd)) goto done;
    const rtpbr_camera_desc camera = {.position = {0, 2, 6}};
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    double record_ns[MAX_BLOCKS], empty_ns[MAX_BLOCKS];
    for (uint32_t b = 0; b <= blocks; ++b) { // block 0: warm-up (the first record)
        double t0 = now_ns();
        for (uint32_t u = 0; u < updates; ++u) {
            vkBeginCommandBuffer(cmd, &begin);
            vkEndCommandBuffer(cmd);
            vkResetCommandBuffer(cmd, 0);
        }
        double t1 = now_ns();
        for (uint32_t u = 0; u < updates; ++u) {
            vkBeginCommandBuffer(cmd, &begin);
            if (rtpbr_lighting_record(targets, &(rtpbr_lighting_record_desc){
                    .command_buffer = cmd, .frame = u % 2, .lights = set, .camera = &camera}))
                goto done;
            vkEndCommandBuffer(cmd);
            vkResetCommandBuffer(cmd, 0);
        }
        double t2 = now_ns();
        if (b > 0) {
            empty_ns[b - 1] = (t1 - t0) / updates;
            record_ns[b - 1] = (t2 - t1) / updates - empty_ns[b - 1];
        }
    }
    printf("rtpbr_lighting_record       %9.0f ns per frame (%ux%u; an empty begin/end/reset, %.0f ns, subtracted)\n",
           median(record_ns, blocks), W, H, median(empty_ns, blocks));
    failed = 0;
done:
    if (pool) vkDestroyCommandPool(d.device, pool, NULL);
    rtpbr_lighting_targets_destroy(targets);
    for (int i = 0; i < 6; ++i) vk_draw_image_destroy(&h, &images[i]);
    return failed;
}

int main(int argc, char **argv)
{
    static const char *const usage =
        "usage: rtpbr-bench-light-update [--lights N] [--updates N] [--blocks N]\n"
        "CPU cost of moving and recolouring every light of a frame: rtpbr_light_set_update against\n"
        "rtpbr_gpu_scene_set_lights (interleaved blocks, medians), then of rtpbr_lighting_record.\n"
        "  --lights N   lights per frame (1..1024; default 64)\n"
        "  --updates N  updates per block (default 2000)\n"
        "  --blocks N   blocks (1..64; default 15)\n"
        "  -h, --help   this text\n";
    uint32_t count = 64, updates = 2000, blocks = 15;
    for (int i = 1; i < argc; ++i) {
        if (i + 1 < argc && strcmp(argv[i], "--lights") == 0) count = (uint32_t)atoi(argv[++i]);
        else if (i + 1 < argc && strcmp(argv[i], "--updates") == 0) updates = (uint32_t)atoi(argv[++i]);
        else if (i + 1 < argc && strcmp(argv[i], "--blocks") == 0) blocks = (uint32_t)atoi(argv[++i]);
        else if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) return fputs(usage, stdout), 0;
        else return fputs(usage, stderr), 2;
    }
    if (count < 1 || count > RTPBR_MAX_LIGHTS || updates < 1 || blocks < 1 || blocks > MAX_BLOCKS)
        return fputs(usage, stderr), 2;
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
    if (record_cost(ctx, set, updates, blocks)) goto done;
    status = 0;
done:
    if (status) fprintf(stderr, "rtpbr-bench-light-update: a call failed\n");
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_light_set_destroy(set);
    rtpbr_context_destroy(ctx);
    free(lights);
    return status;
}
