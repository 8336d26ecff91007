// rtpbr-sample-host: a C engine with its own mesh format, device, geometry pass and tone
// mapping, using rtpbr as its lighting pass (rtpbr_lighting_record in its command buffer).
// Headless: renders one frame and writes the display image (PNG) and, optionally, the linear
// radiance (PFM). --window: the same frame in a window with the viewer's mouse and keys
// (windowed.c). See samples/README.md, "rtpbr-sample-host".
#include "host.h"

#include <stb_image_write.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const usage =
    "usage: rtpbr-sample-host [MESH] [-o OUT.png] [--hdr OUT.pfm] [--exposure EV] [--camera MODE]\n"
    "                         [--keys KEYS] [--window [--frames N] [--screenshot OUT.png]] [--validation]\n"
    "A host engine's frame with rtpbr as its lighting pass: reads MESH (the sample's own text mesh\n"
    "format; default: the bundled room.mesh), draws its G-buffer with its own geometry pass, lights\n"
    "it with rtpbr_lighting_record, tone-maps it with its own pass (Reinhard on luminance, sRGB).\n"
    "  -o OUT.png        the display image (default sample-host.png; not with --window)\n"
    "  --hdr OUT.pfm     also the linear radiance, as a PFM (RGB float, bottom row first)\n"
    "  --exposure EV     scale the radiance by 2^EV before tone mapping (default 0)\n"
    "  --camera MODE     how the camera reaches rtpbr: rtpbr (rtpbr_camera_desc, the default),\n"
    "                    matrices (the host's view and projection) or reversed-z (those with a\n"
    "                    reversed-Z projection and depth test, reversed_z set)\n"
    "  --keys KEYS       replay key presses before the first frame, as the window's keys (below):\n"
    "                    upper-case letters, - and = as themselves; l r u d = arrow keys,\n"
    "                    p n = PgUp PgDn, t = Tab, h = Home (headless too)\n"
    "  --window          show the frame in a window (GLFW) instead of writing a file, with the\n"
    "                    viewer's mouse and the keys below; resizing re-creates the renderer\n"
    "  --frames N        with --window: render N frames, then exit (default: until closed)\n"
    "  --screenshot OUT.png  with --window and --frames: the last frame as presented\n"
    "  --validation      VK_LAYER_KHRONOS_validation with synchronization validation; any message\n"
    "                    fails the run\n"
    "  -h, --help        this text\n"
    "Window controls:\n%s"
    "Exit status: 0 written, 1 bad input or failure, 2 bad command line.\n";

// PFM (Portable Float Map): "PF", width height, -1 (little-endian), then RGB float rows from
// the bottom up.
static int write_pfm(const char *path, const float *rgba, uint32_t w, uint32_t h)
{
    FILE *f = fopen(path, "wb");
    if (!f) return 1;
    int ok = fprintf(f, "PF\n%u %u\n-1.0\n", w, h) > 0;
    for (uint32_t y = h; ok && y-- > 0;)
        for (uint32_t x = 0; ok && x < w; ++x) ok = fwrite(&rgba[4 * ((size_t)y * w + x)], sizeof(float), 3, f) == 3;
    return fclose(f) != 0 || !ok;
}

int main(int argc, char **argv)
{
    const char *mesh_path = RTPBR_SAMPLE_HOST_DEFAULT_MESH, *png_path = "sample-host.png", *pfm_path = NULL;
    const char *keys = "", *screenshot = NULL;
    float exposure = 0.0f;
    int validation = 0, have_mesh = 0, window = 0;
    long frames = 0;
    sh_camera_mode camera_mode = SH_CAMERA_RTPBR;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) return printf(usage, sh_controls_help), 0;
        if (!strcmp(a, "--validation")) validation = 1;
        else if (!strcmp(a, "--window")) window = 1;
        else if (!strcmp(a, "--keys") && i + 1 < argc) keys = argv[++i];
        else if (!strcmp(a, "--screenshot") && i + 1 < argc) screenshot = argv[++i];
        else if (!strcmp(a, "--frames") && i + 1 < argc) {
            char *end;
            frames = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || frames < 1 || frames > 1000000) {
                fprintf(stderr, "rtpbr-sample-host: --frames: '%s' is not a whole number in 1..1000000\n", argv[i]);
                return 2;
            }
        }
        else if (!strcmp(a, "--camera") && i + 1 < argc) {
            const char *v = argv[++i];
            if (!strcmp(v, "rtpbr")) camera_mode = SH_CAMERA_RTPBR;
            else if (!strcmp(v, "matrices")) camera_mode = SH_CAMERA_MATRICES;
            else if (!strcmp(v, "reversed-z")) camera_mode = SH_CAMERA_REVERSED_Z;
            else {
                fprintf(stderr, "rtpbr-sample-host: --camera: '%s' is not rtpbr, matrices or reversed-z\n", v);
                return 2;
            }
        }
        else if ((!strcmp(a, "-o") || !strcmp(a, "--hdr") || !strcmp(a, "--exposure")) && i + 1 < argc) {
            const char *v = argv[++i];
            if (a[1] == 'o') png_path = v;
            else if (a[2] == 'h') pfm_path = v;
            else {
                char *end;
                exposure = strtof(v, &end);
                if (end == v || *end || !(exposure >= -30.0f && exposure <= 30.0f)) {
                    fprintf(stderr, "rtpbr-sample-host: --exposure: '%s' is not a number in [-30, 30]\n", v);
                    return 2;
                }
            }
        } else if (a[0] != '-' && !have_mesh) mesh_path = a, have_mesh = 1;
        else {
            fprintf(stderr, "rtpbr-sample-host: unexpected argument '%s'\n", a);
            fprintf(stderr, usage, sh_controls_help);
            return 2;
        }
    }
    if (!window && (frames || screenshot)) {
        fprintf(stderr, "rtpbr-sample-host: --frames and --screenshot are for --window\n");
        return 2;
    }
    if (screenshot && !frames) {
        fprintf(stderr, "rtpbr-sample-host: --screenshot needs --frames\n");
        return 2;
    }

    char error[512] = "";
    sh_scene scene;
    if (sh_scene_load(mesh_path, &scene, error, sizeof error)) {
        fprintf(stderr, "rtpbr-sample-host: %s\n", error);
        return 1;
    }
    // The controls: --keys edit the scene before the first frame, in the window or not.
    sh_controls controls;
    sh_controls_init(&controls, &scene, exposure);
    for (const char *k = keys; *k; ++k)
        if (sh_controls_key(&controls, &scene, *k)) {
            fprintf(stderr, "rtpbr-sample-host: --keys: no key for '%c'\n", *k);
            sh_scene_free(&scene);
            return 2;
        }
    exposure = controls.exposure;
    if (window) {
#ifdef SH_HAVE_WINDOW
        int rc = sh_run_window(&scene, &controls, &(sh_window_options){.frames = (uint32_t)frames,
            .screenshot = screenshot, .validation = validation, .camera_mode = camera_mode});
        sh_scene_free(&scene);
        return rc;
#else
        fprintf(stderr, "rtpbr-sample-host: --window: this build has no window support (GLFW was not found, or "
                        "-Dviewer=disabled)\n");
        sh_scene_free(&scene);
        return 1;
#endif
    }
    sh_controls_frame(&controls, &scene); // 'A': one animation step, as before a window's frame
    sample_device device = {0};
    rtpbr_context *ctx = NULL;
    sh_renderer renderer = {0};
    size_t pixels = (size_t)scene.width * scene.height;
    float *hdr = malloc(pixels * 16);
    uint8_t *ldr = malloc(pixels * 4);
    int status = 1;
    if (!hdr || !ldr) {
        snprintf(error, sizeof error, "out of memory");
        goto done;
    }
    if (sample_device_create(&device, "rtpbr-sample-host", validation, validation, error, sizeof error)) goto done;
    // rtpbr on the host's device and queue (embedded mode): it creates only its own objects.
    rtpbr_result rr = rtpbr_context_create(&(rtpbr_context_desc){.embedded = device.vk}, &ctx);
    if (rr != RTPBR_SUCCESS) {
        snprintf(error, sizeof error, "rtpbr_context_create: %s", rtpbr_result_string(rr));
        goto done;
    }
    if (sh_renderer_create(&renderer, &device, ctx, &scene, error, sizeof error)) goto done;
    renderer.camera_mode = camera_mode;
    if (sh_render_frame(&renderer, &scene, exposure, hdr, ldr, error, sizeof error)) goto done;
    if (!stbi_write_png(png_path, (int)scene.width, (int)scene.height, 4, ldr, (int)scene.width * 4)) {
        snprintf(error, sizeof error, "cannot write %s", png_path);
        goto done;
    }
    if (pfm_path && write_pfm(pfm_path, hdr, scene.width, scene.height)) {
        snprintf(error, sizeof error, "cannot write %s", pfm_path);
        goto done;
    }
    printf("rtpbr-sample-host: %s: %u triangles, %u materials, %u lights; wrote %s%s%s (%ux%u) on %s\n", mesh_path,
           scene.vertex_count / 3, scene.material_count, scene.light_count, png_path, pfm_path ? " and " : "",
           pfm_path ? pfm_path : "", scene.width, scene.height, rtpbr_context_device_name(ctx));
    status = 0;
done:
    if (status && error[0]) fprintf(stderr, "rtpbr-sample-host: %s\n", error);
    sh_renderer_destroy(&renderer);
    rtpbr_context_destroy(ctx);
    if (device.vk.instance) {
        sample_device_destroy(&device);
        if (device.validation_messages) {
            fprintf(stderr, "rtpbr-sample-host: %u validation message(s)\n", device.validation_messages);
            status = 1;
        }
    }
    sh_scene_free(&scene);
    free(hdr);
    free(ldr);
    return status;
}
