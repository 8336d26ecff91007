// rtpbr-sample-host in a window (host.h, sh_run_window): the same frame as the headless run
// (sh_record_frame: the host's geometry pass, rtpbr_lighting_record, the host's tone mapping),
// recorded into the window's command buffer, then the display image copied into the acquired
// swapchain image. The window, its device and swapchain are the viewer's (samples/viewer/
// window.c): rtpbr runs embedded in that device, as in any host engine with a window.
#include "host.h"
#include "window.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct win_app {
    viewer_window win;
    sample_device device; // the window's device as the renderer takes it (not created here)
    rtpbr_context *ctx;
    sh_renderer renderer;
    sh_scene *scene;
    sh_controls *controls;
    sh_camera_mode camera_mode;
    int drag; // 0 none, 1 orbit, 2 pan
    double mouse_x, mouse_y;
    uint32_t screenshots; // written by P so far
    int pending_shot;     // P: read the next frame back
    int failed;
} win_app;

// The host's renderer at the swapchain's size (again after a resize).
static int renderer_fit(win_app *a)
{
    if (a->renderer.device && a->renderer.width == a->win.extent.width && a->renderer.height == a->win.extent.height)
        return 0;
    sh_renderer_destroy(&a->renderer); // the window waited for the device (viewer_window_resize)
    a->scene->width = a->win.extent.width, a->scene->height = a->win.extent.height;
    char error[512];
    if (sh_renderer_create(&a->renderer, &a->device, a->ctx, a->scene, error, sizeof error)) {
        fprintf(stderr, "rtpbr-sample-host: %s\n", error);
        return 1;
    }
    a->renderer.camera_mode = a->camera_mode;
    return 0;
}

static void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                          VkAccessFlags dst_access)
{
    VkImageMemoryBarrier b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, .dstAccessMask = dst_access,
        .oldLayout = from, .newLayout = to, .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image,
        .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, NULL, 0, NULL, 1, &b);
}

// viewer_window_frame's record(): the host's frame, then its display image into the swapchain
// image (a copy of bytes: the tone mapping wrote sRGB-encoded values in the swapchain's channel
// order, and an _SRGB or _UNORM swapchain format shows those bytes as they are). Leaves the
// image in TRANSFER_DST_OPTIMAL, as window.h asks.
static bool record(VkCommandBuffer cmd, VkImage image, VkImageView view, uint32_t index, void *user)
{
    (void)view, (void)index;
    win_app *a = user;
    char error[512];
    if (sh_record_frame(&a->renderer, cmd, a->scene, a->controls->exposure, viewer_window_bgra(&a->win), error,
                        sizeof error)) {
        fprintf(stderr, "rtpbr-sample-host: %s\n", error);
        a->failed = 1;
        return false;
    }
    // The acquire semaphore's wait (all commands) orders this after the presentation engine.
    image_barrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkImageCopy copy = {.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .extent = {a->renderer.width, a->renderer.height, 1}};
    vkCmdCopyImage(cmd, a->renderer.ldr.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    return true;
}

static void print_help(void)
{
    printf("rtpbr-sample-host controls\n%s", sh_controls_help);
}

// A key in the window: the window's own (Esc, H, P), or sh_controls' (spelled as --keys spells
// them, host.h).
static void handle_key(win_app *a, int key)
{
    char c = 0;
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(a->win.glfw, GLFW_TRUE); return;
    case GLFW_KEY_H: print_help(); return;
    case GLFW_KEY_P: a->pending_shot = 1; return; // the next frame is read back and written
    case GLFW_KEY_TAB: c = 't'; break;
    case GLFW_KEY_HOME: c = 'h'; break;
    case GLFW_KEY_LEFT: c = 'l'; break;
    case GLFW_KEY_RIGHT: c = 'r'; break;
    case GLFW_KEY_UP: c = 'u'; break;
    case GLFW_KEY_DOWN: c = 'd'; break;
    case GLFW_KEY_PAGE_UP: c = 'p'; break;
    case GLFW_KEY_PAGE_DOWN: c = 'n'; break;
    case GLFW_KEY_MINUS: c = '-'; break;
    case GLFW_KEY_EQUAL: c = '='; break;
    case GLFW_KEY_C: c = 'C'; break;
    case GLFW_KEY_A: c = 'A'; break;
    case GLFW_KEY_E: c = 'E'; break;
    case GLFW_KEY_D: c = 'D'; break;
    default: return;
    }
    sh_controls_key(a->controls, a->scene, c);
}

static void on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    (void)scancode, (void)mods;
    if (action == GLFW_PRESS || action == GLFW_REPEAT) handle_key(glfwGetWindowUserPointer(window), key);
}

static void on_button(GLFWwindow *window, int button, int action, int mods)
{
    (void)mods;
    win_app *a = glfwGetWindowUserPointer(window);
    glfwGetCursorPos(window, &a->mouse_x, &a->mouse_y);
    a->drag = action != GLFW_PRESS ? 0 : button == GLFW_MOUSE_BUTTON_LEFT ? 1 : button == GLFW_MOUSE_BUTTON_RIGHT ? 2 : 0;
}

static void on_cursor(GLFWwindow *window, double x, double y)
{
    win_app *a = glfwGetWindowUserPointer(window);
    float dx = (float)(x - a->mouse_x), dy = (float)(y - a->mouse_y);
    a->mouse_x = x, a->mouse_y = y;
    if (a->drag == 1) sh_camera_orbit(&a->scene->camera, -0.01f * dx, 0.01f * dy);
    else if (a->drag == 2) sh_camera_pan(&a->scene->camera, -0.002f * dx, 0.002f * dy);
}

static void on_scroll(GLFWwindow *window, double dx, double dy)
{
    (void)dx;
    win_app *a = glfwGetWindowUserPointer(window);
    sh_camera_zoom(&a->scene->camera, powf(0.9f, (float)dy));
}

static void set_title(win_app *a, double ms)
{
    char title[256];
    snprintf(title, sizeof title, "rtpbr-sample-host  %ux%u  %.1f ms (%.1f fps)  light %u/%u  exposure %+.1f%s  (H: help)",
             a->renderer.width, a->renderer.height, ms, ms > 0.0 ? 1000.0 / ms : 0.0,
             a->scene->light_count ? a->controls->light % a->scene->light_count + 1 : 0, a->scene->light_count,
             a->controls->exposure, a->controls->animate ? "  animated" : "");
    glfwSetWindowTitle(a->win.glfw, title);
}

int sh_run_window(sh_scene *scene, sh_controls *controls, const sh_window_options *o)
{
    win_app *a = calloc(1, sizeof *a);
    if (!a) return fprintf(stderr, "rtpbr-sample-host: out of memory\n"), 1;
    a->scene = scene, a->controls = controls, a->camera_mode = o->camera_mode;
    viewer_window_program = "rtpbr-sample-host";
    int status = 1;
    if (!viewer_window_create(&a->win, (int)scene->width, (int)scene->height, o->validation, o->validation)) goto done;
    a->device.vk = (rtpbr_vulkan_device){.instance = a->win.instance, .physical_device = a->win.physical_device,
        .device = a->win.device, .queue = a->win.queue, .queue_family_index = a->win.queue_family,
        .enabled_features = &a->win.features};
    rtpbr_result rr = rtpbr_context_create(&(rtpbr_context_desc){.embedded = a->device.vk}, &a->ctx);
    if (rr != RTPBR_SUCCESS) {
        fprintf(stderr, "rtpbr-sample-host: rtpbr_context_create: %s\n", rtpbr_result_string(rr));
        goto done;
    }
    glfwSetWindowUserPointer(a->win.glfw, a);
    glfwSetKeyCallback(a->win.glfw, on_key);
    glfwSetMouseButtonCallback(a->win.glfw, on_button);
    glfwSetCursorPosCallback(a->win.glfw, on_cursor);
    glfwSetScrollCallback(a->win.glfw, on_scroll);
    if (!o->frames) print_help();

    double last_title = 0.0, frame_ms = 0.0;
    for (uint32_t frame = 0; !glfwWindowShouldClose(a->win.glfw) && (!o->frames || frame < o->frames); ++frame) {
        glfwPollEvents();
        if (!a->win.swapchain || a->win.extent.width == 0 || a->win.extent.height == 0) { // minimised
            glfwWaitEvents();
            if (!viewer_window_resize(&a->win)) goto done;
            --frame;
            continue;
        }
        if (renderer_fit(a)) goto done;
        sh_controls_frame(controls, scene);
        bool last = o->frames && frame + 1 == o->frames;
        bool shot = (last && o->screenshot) || a->pending_shot;
        double t0 = glfwGetTime();
        bool out_of_date = false;
        if (!viewer_window_frame(&a->win, record, NULL, a, -1, shot, &out_of_date)) goto done;
        frame_ms = 1000.0 * (glfwGetTime() - t0);
        if (shot) {
            char path[64];
            const char *file = last && o->screenshot ? o->screenshot : path;
            if (file == path) snprintf(path, sizeof path, "rtpbr-sample-host-%03u.png", a->screenshots++);
            a->pending_shot = 0;
            if (!viewer_window_write_screenshot(&a->win, file)) goto done;
            printf("rtpbr-sample-host: wrote %s\n", file);
        }
        if (out_of_date && !viewer_window_resize(&a->win)) goto done;
        if (glfwGetTime() - last_title > 0.5) set_title(a, frame_ms), last_title = glfwGetTime();
    }
    printf("rtpbr-sample-host: %u lights, %ux%u in a window on %s; last frame %.1f ms\n", scene->light_count,
           a->renderer.width, a->renderer.height, rtpbr_context_device_name(a->ctx), frame_ms);
    status = 0;
done:
    if (a->failed) status = 1;
    if (a->win.device) vkDeviceWaitIdle(a->win.device); // the host's device: its own wait, at exit
    sh_renderer_destroy(&a->renderer);
    rtpbr_context_destroy(a->ctx);
    viewer_window_destroy(&a->win);
    if (a->win.validation_messages) {
        fprintf(stderr, "rtpbr-sample-host: %u validation message(s)\n", a->win.validation_messages);
        status = 1;
    }
    free(a);
    return status;
}
