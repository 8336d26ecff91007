// rtpbr-viewer: an interactive area-light viewer. A GLFW window whose Vulkan device the viewer
// creates itself (rtpbr runs embedded in it and records into the swapchain images), an orbit
// camera, editable polygonal lights and materials, the engine's model toggles, a split view
// against an oracle reference image, screenshots. Status and frame time are in the title bar.
//   usage: rtpbr-viewer [SCENE.gltf] [--reference REF.exr] [--width W] [--height H]
//                       [--frames N --screenshot OUT.png] [--keys KEYS] [--validation]
// --keys replays key presses before the first frame (scripted screenshots): upper-case
// letters, digits, [ ] - = as themselves; l r u d = arrow keys, p n = PgUp PgDn, t = Tab,
// h = Home.
#include "reference.h"
#include "scene_edit.h"
#include "window.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const help_text =
    "rtpbr-viewer controls\n"
    "  mouse: left drag orbit, right drag pan, wheel zoom; Home: back to the scene's camera\n"
    "  Tab: select the next light; 1 / 2 / 3: arrows and PgUp/PgDn move / rotate / scale it\n"
    "  [ ]: light vertex count 3..8; C: light colour; - =: intensity; T: one-/two-sided\n"
    "  M: select the next material; 7 8: roughness -/+; 9 0: metallic -/+\n"
    "  K: Kulla-Conty on/off; N: NDF GGX/Beckmann; L: LTC exact clipping vs sphere proxy\n"
    "  E / D: exposure +/-; S: split view against --reference; P: screenshot; H: this help; Esc: quit\n";

typedef struct app {
    viewer_window win;
    rtpbr_context *ctx;
    viewer_scene scene;
    rtpbr_gpu_scene *gpu;
    rtpbr_renderer *renderer;
    uint32_t renderer_w, renderer_h;
    bool scene_dirty;
    // Orbit camera: position = target + distance (cos p sin y, sin p, cos p cos y).
    float target[3], yaw, pitch, distance, yfov;
    float home_target[3], home_yaw, home_pitch, home_distance;
    int drag; // 0 none, 1 orbit, 2 pan
    double mouse_x, mouse_y;
    // Settings.
    rtpbr_ndf ndf;
    bool multiscatter_off;
    float exposure;
    int mode; // 0 move, 1 rotate, 2 scale
    uint32_t light, material, colour_index;
    // Split view.
    float *reference;
    int reference_w, reference_h;
    bool split, overlay_dirty;
    // Status.
    double frame_ms, last_title;
    double steady_ms_sum; // frames after the first (which builds pipelines), for the summary
    long steady_frames;
    bool screenshot_request;
    unsigned screenshot_counter;
    uint32_t engine_errors;
    const char *notice;
} app;

static void on_log(rtpbr_log_level level, const char *message, void *user)
{
    if (level <= RTPBR_LOG_WARNING) {
        fprintf(stderr, "rtpbr: %s\n", message);
        if (level == RTPBR_LOG_ERROR) ((app *)user)->engine_errors++;
    }
}

static void camera_position(const app *a, float out[3])
{
    out[0] = a->target[0] + a->distance * cosf(a->pitch) * sinf(a->yaw);
    out[1] = a->target[1] + a->distance * sinf(a->pitch);
    out[2] = a->target[2] + a->distance * cosf(a->pitch) * cosf(a->yaw);
}

// The scene's first camera if it has one (looking at the point nearest the scene's centre
// along its view ray), else a view of the whole bounding box.
static void camera_home(app *a)
{
    const rtpbr_scene *s = a->scene.loaded;
    float center[3], extent = 0.0f;
    for (int c = 0; c < 3; ++c) {
        center[c] = 0.5f * (s->bounds_min[c] + s->bounds_max[c]);
        extent = fmaxf(extent, s->bounds_max[c] - s->bounds_min[c]);
    }
    a->yfov = 0.7853982f;
    if (s->camera_count > 0) {
        const rtpbr_scene_camera *cam = &s->cameras[0];
        float to_center[3] = {center[0] - cam->position[0], center[1] - cam->position[1], center[2] - cam->position[2]};
        float d = to_center[0] * cam->forward[0] + to_center[1] * cam->forward[1] + to_center[2] * cam->forward[2];
        a->distance = d > 0.1f ? d : fmaxf(extent, 1.0f);
        for (int c = 0; c < 3; ++c) a->target[c] = cam->position[c] + a->distance * cam->forward[c];
        a->pitch = asinf(fmaxf(-1.0f, fminf(1.0f, -cam->forward[1])));
        a->yaw = atan2f(-cam->forward[0], -cam->forward[2]);
        if (cam->yfov > 0.0f) a->yfov = cam->yfov;
    } else {
        memcpy(a->target, center, sizeof center);
        a->distance = fmaxf(extent, 1e-3f) / tanf(0.5f * a->yfov);
        a->yaw = 0.0f;
        a->pitch = 0.3f;
    }
    memcpy(a->home_target, a->target, sizeof a->target);
    a->home_yaw = a->yaw, a->home_pitch = a->pitch, a->home_distance = a->distance;
}

static float aces(float x) // Narkowicz 2015, the engine's default tone curve (rtpbr.h)
{
    float y = x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f);
    return y < 0.0f ? 0.0f : (y > 1.0f ? 1.0f : y);
}

static uint8_t srgb_encode(float x) // IEC 61966-2-1
{
    float y = x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
    return (uint8_t)(y * 255.0f + 0.5f);
}

// The reference, scaled to the window (nearest texel) and tone-mapped like the engine's
// default, into the overlay buffer; a white line marks the split.
static void fill_overlay(app *a)
{
    uint8_t *dst = viewer_window_overlay(&a->win);
    uint32_t w = a->win.extent.width, h = a->win.extent.height;
    bool bgra = viewer_window_bgra(&a->win);
    float scale = powf(2.0f, a->exposure);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            size_t sx = (size_t)x * a->reference_w / w, sy = (size_t)y * a->reference_h / h;
            const float *p = a->reference + 4 * (sy * a->reference_w + sx);
            uint8_t *o = dst + 4 * ((size_t)y * w + x);
            uint8_t r = srgb_encode(aces(p[0] * scale)), g = srgb_encode(aces(p[1] * scale)),
                    b = srgb_encode(aces(p[2] * scale));
            if (x == w / 2) r = g = b = 255;
            o[0] = bgra ? b : r, o[1] = g, o[2] = bgra ? r : b, o[3] = 255;
        }
    a->overlay_dirty = false;
}

static void update_title(app *a)
{
    char title[512];
    int n = snprintf(title, sizeof title, "rtpbr viewer | %.1f ms | %s, Kulla-Conty %s, LTC exact clipping | EV %+.1f",
                     a->frame_ms, a->ndf == RTPBR_NDF_BECKMANN_MODEL ? "Beckmann" : "GGX",
                     a->multiscatter_off ? "off" : "on", a->exposure);
    if (a->scene.light_count > 0 && n > 0 && (size_t)n < sizeof title) {
        const viewer_light *l = &a->scene.lights[a->light];
        static const char *const modes[] = {"move", "rotate", "scale"};
        n += snprintf(title + n, sizeof title - n, " | light %u/%u [%s] %u-gon I=%.2f %s", a->light + 1,
                      a->scene.light_count, modes[a->mode], l->vertex_count, l->intensity,
                      l->two_sided ? "two-sided" : "one-sided");
    }
    if (a->scene.material_count > 0 && n > 0 && (size_t)n < sizeof title) {
        const rtpbr_material_desc *m = &a->scene.materials[a->material];
        n += snprintf(title + n, sizeof title - n, " | material %u/%u r=%.2f m=%.2f", a->material + 1,
                      a->scene.material_count, m->roughness, m->metallic);
    }
    if (a->split && n > 0 && (size_t)n < sizeof title) n += snprintf(title + n, sizeof title - n, " | right: reference");
    if (a->notice && n > 0 && (size_t)n < sizeof title) snprintf(title + n, sizeof title - n, " | %s", a->notice);
    glfwSetWindowTitle(a->win.glfw, title);
}

static void edit_light(app *a, int key)
{
    if (a->scene.light_count == 0) return;
    viewer_light *l = &a->scene.lights[a->light];
    // Arrows: X and Z; PgUp/PgDn: Y (world axes).
    int axis = key == GLFW_KEY_LEFT || key == GLFW_KEY_RIGHT ? 0 : (key == GLFW_KEY_UP || key == GLFW_KEY_DOWN ? 2 : 1);
    float sign = key == GLFW_KEY_RIGHT || key == GLFW_KEY_DOWN || key == GLFW_KEY_PAGE_UP ? 1.0f : -1.0f;
    if (a->mode == 0) {
        float d[3] = {0.0f, 0.0f, 0.0f};
        d[axis] = 0.1f * sign;
        viewer_light_translate(l, d);
    } else if (a->mode == 1) {
        viewer_light_rotate(l, axis, sign * 0.0872665f); // 5 degrees
    } else {
        viewer_light_scale(l, sign > 0.0f ? 1.1f : 1.0f / 1.1f);
    }
    a->scene_dirty = true;
}

static void on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    (void)scancode, (void)mods;
    app *a = glfwGetWindowUserPointer(window);
    if (action == GLFW_RELEASE) return;
    viewer_light *l = a->scene.light_count ? &a->scene.lights[a->light] : NULL;
    rtpbr_material_desc *m = a->scene.material_count ? &a->scene.materials[a->material] : NULL;
    static const float colours[][3] = {{1, 1, 1}, {1, 0.85f, 0.7f}, {0.7f, 0.85f, 1}, {1, 0.2f, 0.1f},
                                       {0.2f, 1, 0.3f}, {0.2f, 0.4f, 1}};
    a->notice = NULL;
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
    case GLFW_KEY_H: fputs(help_text, stdout); break;
    case GLFW_KEY_HOME:
        memcpy(a->target, a->home_target, sizeof a->target);
        a->yaw = a->home_yaw, a->pitch = a->home_pitch, a->distance = a->home_distance;
        break;
    case GLFW_KEY_TAB: if (a->scene.light_count) a->light = (a->light + 1) % a->scene.light_count; break;
    case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3: a->mode = key - GLFW_KEY_1; break;
    case GLFW_KEY_LEFT: case GLFW_KEY_RIGHT: case GLFW_KEY_UP: case GLFW_KEY_DOWN:
    case GLFW_KEY_PAGE_UP: case GLFW_KEY_PAGE_DOWN: edit_light(a, key); break;
    case GLFW_KEY_LEFT_BRACKET: case GLFW_KEY_RIGHT_BRACKET:
        if (l) viewer_light_set_vertex_count(l, l->vertex_count + (key == GLFW_KEY_RIGHT_BRACKET ? 1 : -1));
        a->scene_dirty = true;
        break;
    case GLFW_KEY_C:
        if (l) a->colour_index = (a->colour_index + 1) % 6, memcpy(l->color, colours[a->colour_index], sizeof l->color);
        a->scene_dirty = true;
        break;
    case GLFW_KEY_EQUAL: case GLFW_KEY_MINUS:
        if (l) l->intensity *= key == GLFW_KEY_EQUAL ? 1.25f : 0.8f;
        a->scene_dirty = true;
        break;
    case GLFW_KEY_T: if (l) l->two_sided = !l->two_sided; a->scene_dirty = true; break;
    case GLFW_KEY_M: if (a->scene.material_count) a->material = (a->material + 1) % a->scene.material_count; break;
    case GLFW_KEY_7: case GLFW_KEY_8:
        if (m) m->roughness = fminf(1.0f, fmaxf(0.0f, m->roughness + (key == GLFW_KEY_8 ? 0.05f : -0.05f)));
        a->scene_dirty = true;
        break;
    case GLFW_KEY_9: case GLFW_KEY_0:
        if (m) m->metallic = fminf(1.0f, fmaxf(0.0f, m->metallic + (key == GLFW_KEY_0 ? 0.1f : -0.1f)));
        a->scene_dirty = true;
        break;
    case GLFW_KEY_K: a->multiscatter_off = !a->multiscatter_off; break;
    case GLFW_KEY_N: a->ndf = a->ndf == RTPBR_NDF_BECKMANN_MODEL ? RTPBR_NDF_GGX_MODEL : RTPBR_NDF_BECKMANN_MODEL; break;
    case GLFW_KEY_L: a->notice = "the engine API has no run-time LTC sphere-proxy variant"; break;
    case GLFW_KEY_E: case GLFW_KEY_D:
        a->exposure += key == GLFW_KEY_E ? 0.5f : -0.5f;
        a->overlay_dirty = true;
        break;
    case GLFW_KEY_S:
        if (a->reference) a->split = !a->split;
        else a->notice = "no --reference image";
        break;
    case GLFW_KEY_P: a->screenshot_request = true; break;
    default: break;
    }
    a->last_title = 0.0; // refresh now
}

// Replays --keys (see the top of this file); false for a character with no key.
static bool replay_keys(app *a, const char *keys)
{
    for (const char *c = keys; *c; ++c) {
        int key = 0;
        if ((*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '[' || *c == ']' || *c == '-' || *c == '=')
            key = *c; // GLFW key codes of these are their ASCII codes
        else if (*c == 'l') key = GLFW_KEY_LEFT;
        else if (*c == 'r') key = GLFW_KEY_RIGHT;
        else if (*c == 'u') key = GLFW_KEY_UP;
        else if (*c == 'd') key = GLFW_KEY_DOWN;
        else if (*c == 'p') key = GLFW_KEY_PAGE_UP;
        else if (*c == 'n') key = GLFW_KEY_PAGE_DOWN;
        else if (*c == 't') key = GLFW_KEY_TAB;
        else if (*c == 'h') key = GLFW_KEY_HOME;
        if (!key) {
            fprintf(stderr, "rtpbr-viewer: --keys: no key for '%c'\n", *c);
            return false;
        }
        on_key(a->win.glfw, key, 0, GLFW_PRESS, 0);
    }
    return true;
}

static void on_button(GLFWwindow *window, int button, int action, int mods)
{
    (void)mods;
    app *a = glfwGetWindowUserPointer(window);
    if (action == GLFW_PRESS) {
        a->drag = button == GLFW_MOUSE_BUTTON_LEFT ? 1 : (button == GLFW_MOUSE_BUTTON_RIGHT ? 2 : 0);
        glfwGetCursorPos(window, &a->mouse_x, &a->mouse_y);
    } else {
        a->drag = 0;
    }
}

static void on_cursor(GLFWwindow *window, double x, double y)
{
    app *a = glfwGetWindowUserPointer(window);
    float dx = (float)(x - a->mouse_x), dy = (float)(y - a->mouse_y);
    a->mouse_x = x, a->mouse_y = y;
    if (a->drag == 1) {
        a->yaw -= 0.01f * dx;
        a->pitch = fminf(1.55f, fmaxf(-1.55f, a->pitch + 0.01f * dy));
    } else if (a->drag == 2) {
        // Pan in the camera's plane: right = (cos y, 0, -sin y), up ~ world Y.
        float k = 0.002f * a->distance;
        a->target[0] -= k * dx * cosf(a->yaw);
        a->target[2] += k * dx * sinf(a->yaw);
        a->target[1] += k * dy;
    }
}

static void on_scroll(GLFWwindow *window, double dx, double dy)
{
    (void)dx;
    app *a = glfwGetWindowUserPointer(window);
    a->distance = fmaxf(0.05f, a->distance * powf(0.9f, (float)dy));
}

static bool record_frame(VkCommandBuffer cmd, VkImage image, VkImageView view, void *user)
{
    app *a = user;
    rtpbr_camera_desc camera = {.yfov = a->yfov, .up = {0.0f, 1.0f, 0.0f}};
    camera_position(a, camera.position);
    memcpy(camera.target, a->target, sizeof camera.target);
    rtpbr_render_desc desc = {.camera = &camera, .exposure = a->exposure, .ndf = a->ndf,
        .multiscatter = a->multiscatter_off ? RTPBR_MULTISCATTER_OFF : RTPBR_MULTISCATTER_ON};
    rtpbr_record_desc target = {.command_buffer = cmd, .image = image, .view = view, .format = a->win.format,
        .old_layout = VK_IMAGE_LAYOUT_UNDEFINED, .new_layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
    rtpbr_result r = rtpbr_record(a->renderer, a->gpu, &desc, &target);
    if (r != RTPBR_SUCCESS) fprintf(stderr, "rtpbr-viewer: rtpbr_record: %s\n", rtpbr_result_string(r));
    return r == RTPBR_SUCCESS;
}

// Keeps the engine scene and renderer in step with edits and the window size.
static bool sync_engine(app *a)
{
    rtpbr_result r = RTPBR_SUCCESS;
    if (a->scene_dirty || !a->gpu) {
        rtpbr_gpu_scene_destroy(a->gpu); // the last frame has completed (one frame in flight)
        a->gpu = NULL;
        if ((r = viewer_scene_upload(&a->scene, a->ctx, &a->gpu)) != RTPBR_SUCCESS) {
            fprintf(stderr, "rtpbr-viewer: scene upload: %s\n", rtpbr_result_string(r));
            return false;
        }
        a->scene_dirty = false;
    }
    if (!a->renderer || a->renderer_w != a->win.extent.width || a->renderer_h != a->win.extent.height) {
        rtpbr_renderer_destroy(a->renderer);
        a->renderer = NULL;
        rtpbr_renderer_desc desc = {.width = a->win.extent.width, .height = a->win.extent.height};
        if ((r = rtpbr_renderer_create(a->ctx, &desc, &a->renderer)) != RTPBR_SUCCESS) {
            fprintf(stderr, "rtpbr-viewer: renderer: %s\n", rtpbr_result_string(r));
            return false;
        }
        a->renderer_w = desc.width, a->renderer_h = desc.height;
        a->overlay_dirty = true;
    }
    if (a->reference && a->overlay_dirty) fill_overlay(a);
    return true;
}

int main(int argc, char **argv)
{
    const char *scene_path = RTPBR_VIEWER_DEFAULT_SCENE, *reference_path = NULL, *screenshot_path = NULL;
    const char *keys = "";
    long frames = 0, width = 960, height = 720;
    bool validation = false;
    for (int i = 1; i < argc; ++i) {
        bool has_value = i + 1 < argc;
        if (!strcmp(argv[i], "--reference") && has_value) reference_path = argv[++i];
        else if (!strcmp(argv[i], "--screenshot") && has_value) screenshot_path = argv[++i];
        else if (!strcmp(argv[i], "--frames") && has_value) frames = strtol(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--width") && has_value) width = strtol(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--height") && has_value) height = strtol(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--keys") && has_value) keys = argv[++i];
        else if (!strcmp(argv[i], "--validation")) validation = true;
        else if (argv[i][0] != '-') scene_path = argv[i];
        else {
            fprintf(stderr, "usage: rtpbr-viewer [SCENE.gltf] [--reference REF.exr] [--width W] [--height H]\n"
                            "                    [--frames N --screenshot OUT.png] [--keys KEYS] [--validation]\n");
            return 2;
        }
    }
    if (frames < 0 || width < 1 || height < 1 || width > 16384 || height > 16384 || (screenshot_path && frames < 1)) {
        fprintf(stderr, "rtpbr-viewer: --frames must be >= 1 with --screenshot; sizes 1..16384\n");
        return 2;
    }
    app *a = calloc(1, sizeof *a);
    if (!a) return 1;
    int status = 1;
    if (reference_path && !(a->reference = viewer_reference_load(reference_path, &a->reference_w, &a->reference_h)))
        goto done;
    a->split = a->reference != NULL;
    if (!viewer_scene_load(&a->scene, scene_path)) goto done;
    if (!viewer_window_create(&a->win, (int)width, (int)height, validation)) goto done;
    glfwSetWindowUserPointer(a->win.glfw, a);
    glfwSetKeyCallback(a->win.glfw, on_key);
    glfwSetMouseButtonCallback(a->win.glfw, on_button);
    glfwSetCursorPosCallback(a->win.glfw, on_cursor);
    glfwSetScrollCallback(a->win.glfw, on_scroll);
    rtpbr_context_desc desc = {.logger = {.func = on_log, .user_data = a},
        .embedded = {.instance = a->win.instance, .physical_device = a->win.physical_device,
                     .device = a->win.device, .queue = a->win.queue, .queue_family_index = a->win.queue_family,
                     .enabled_features = &a->win.features}};
    rtpbr_result r = rtpbr_context_create(&desc, &a->ctx);
    if (r != RTPBR_SUCCESS) {
        fprintf(stderr, "rtpbr-viewer: rtpbr_context_create: %s\n", rtpbr_result_string(r));
        goto done;
    }
    camera_home(a);
    if (!replay_keys(a, keys)) goto done;
    if (!frames) fputs(help_text, stdout);
    bool screenshot_written = false;
    for (long frame = 0; !glfwWindowShouldClose(a->win.glfw) && (!frames || frame < frames);) {
        glfwPollEvents();
        if (a->win.extent.width == 0 || a->win.extent.height == 0) {
            glfwWaitEvents();
            if (!viewer_window_resize(&a->win)) goto done;
            continue;
        }
        if (!sync_engine(a)) goto done;
        bool shot = a->screenshot_request || (screenshot_path && frame == frames - 1);
        double start = glfwGetTime();
        bool out_of_date = false;
        int split_x = a->split ? (int)(a->win.extent.width / 2) : -1;
        if (!viewer_window_frame(&a->win, record_frame, a, split_x, shot, &out_of_date)) goto done;
        if (out_of_date) { // the image may not have been shown: resize and draw the frame again
            if (!viewer_window_resize(&a->win)) goto done;
            continue;
        }
        double now = glfwGetTime();
        a->frame_ms = a->frame_ms > 0.0 ? 0.9 * a->frame_ms + 100.0 * (now - start) : 1000.0 * (now - start);
        if (frame > 0) a->steady_ms_sum += 1000.0 * (now - start), a->steady_frames++;
        if (shot) {
            char name[64];
            const char *path = screenshot_path && frame == frames - 1 ? screenshot_path : name;
            snprintf(name, sizeof name, "rtpbr-viewer-%03u.png", a->screenshot_counter++);
            if (!viewer_window_write_screenshot(&a->win, path)) goto done;
            printf("rtpbr-viewer: wrote %s (%ux%u)\n", path, a->win.extent.width, a->win.extent.height);
            screenshot_written |= path == screenshot_path;
            a->screenshot_request = false;
        }
        if (now - a->last_title > 0.25) update_title(a), a->last_title = now;
        ++frame;
    }
    if (a->steady_frames > 0)
        printf("rtpbr-viewer: %.1f ms per frame (mean of %ld frames after the first) at %ux%u on %s\n",
               a->steady_ms_sum / (double)a->steady_frames, a->steady_frames, a->win.extent.width,
               a->win.extent.height, rtpbr_context_device_name(a->ctx));
    status = (screenshot_path && !screenshot_written) || a->engine_errors ? 1 : 0;
done:
    rtpbr_renderer_destroy(a->renderer);
    rtpbr_gpu_scene_destroy(a->gpu);
    if (a->win.device) vkDeviceWaitIdle(a->win.device);
    rtpbr_context_destroy(a->ctx);
    viewer_window_destroy(&a->win);
    viewer_scene_destroy(&a->scene);
    free(a->reference);
    if (a->win.validation_messages) {
        fprintf(stderr, "rtpbr-viewer: %u validation message(s)\n", a->win.validation_messages);
        status = 1;
    }
    free(a);
    return status;
}
