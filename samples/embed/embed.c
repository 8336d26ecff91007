// rtpbr embedded in a host's Vulkan device: the smallest complete program. The "host" creates
// its own instance and device (as a game engine already has; sample_device_create in
// samples/common/sample_vk.c: the first Vulkan 1.3 device with a graphics + compute queue,
// dynamicRendering enabled), hands them to rtpbr, loads a glTF scene, renders one frame and
// writes it to a PNG.
//   usage: rtpbr-embed [SCENE.gltf [OUT.png [--validation]]]
// --validation: the host enables VK_LAYER_KHRONOS_validation; any message fails the run.
#include "sample_vk.h" // the host's instance and device (samples/common/sample_vk.c)

#include <rtpbr/rtpbr.h>
#include <stb_image_write.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { WIDTH = 640, HEIGHT = 480 };

static const char *const usage =
    "usage: rtpbr-embed [SCENE.gltf [OUT.png [--validation]]]\n"
    "rtpbr embedded in a host's own Vulkan instance and device: loads SCENE.gltf (default: the\n"
    "bundled quad_light scene), renders one 640 x 480 frame and writes it to OUT.png (default\n"
    "embed.png).\n"
    "  --validation  the host enables VK_LAYER_KHRONOS_validation; any message fails the run\n"
    "  -h, --help    this text\n";

int main(int argc, char **argv)
{
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) return fputs(usage, stdout), 0;
        if (i == 3 ? strcmp(argv[i], "--validation") != 0 : i > 3 || argv[i][0] == '-')
            return fputs(usage, stderr), 2;
    }
    const char *scene_path = argc > 1 ? argv[1] : RTPBR_EMBED_DEFAULT_SCENE;
    const char *out_path = argc > 2 ? argv[2] : "embed.png";
    int validation = argc > 3 && strcmp(argv[3], "--validation") == 0;
    sample_device h = {0};
    char error[256] = "";
    rtpbr_context *ctx = NULL;
    rtpbr_gpu_scene *scene = NULL;
    rtpbr_renderer *renderer = NULL;
    uint8_t *pixels = NULL;
    int status = 1;
    rtpbr_result r = RTPBR_SUCCESS;
    if (sample_device_create(&h, "rtpbr-embed", validation, 0, error, sizeof error)) {
        fprintf(stderr, "rtpbr-embed: %s\n", error);
        goto done;
    }

    // Embedded mode: rtpbr uses the host's device and queue, creates only its own objects.
    // h.vk: instance, physical device, device, queue, queue family and the VkPhysicalDeviceFeatures2
    // chain the host gave vkCreateDevice (rtpbr checks what is enabled).
    rtpbr_context_desc desc = {.embedded = h.vk};
    if ((r = rtpbr_context_create(&desc, &ctx)) != RTPBR_SUCCESS) goto done;
    if ((r = rtpbr_gpu_scene_load_gltf(ctx, scene_path, &scene)) != RTPBR_SUCCESS) goto done;
    if ((r = rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = WIDTH, .height = HEIGHT},
                                   &renderer)) != RTPBR_SUCCESS) goto done;
    if ((r = rtpbr_render(renderer, scene, &(rtpbr_render_desc){0})) != RTPBR_SUCCESS) goto done;
    pixels = malloc((size_t)WIDTH * HEIGHT * 4);
    if (!pixels) goto done;
    if ((r = rtpbr_read_display(renderer, pixels, (size_t)WIDTH * HEIGHT * 4)) != RTPBR_SUCCESS) goto done;
    if (!stbi_write_png(out_path, WIDTH, HEIGHT, 4, pixels, WIDTH * 4)) {
        fprintf(stderr, "rtpbr-embed: cannot write %s\n", out_path);
        goto done;
    }
    printf("rtpbr-embed: wrote %s (%dx%d) on %s\n", out_path, WIDTH, HEIGHT, rtpbr_context_device_name(ctx));
    status = 0;
done:
    if (r != RTPBR_SUCCESS) fprintf(stderr, "rtpbr-embed: %s\n", rtpbr_result_string(r));
    free(pixels);
    rtpbr_renderer_destroy(renderer);
    rtpbr_gpu_scene_destroy(scene);
    rtpbr_context_destroy(ctx);
    sample_device_destroy(&h);
    if (h.validation_messages) {
        fprintf(stderr, "rtpbr-embed: %u validation message(s)\n", h.validation_messages);
        status = 1;
    }
    return status;
}
