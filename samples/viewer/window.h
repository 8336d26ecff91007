// The viewer's Vulkan host: a GLFW window, an instance/device/swapchain of its own (rtpbr runs
// embedded in it), one frame in flight, and read-back of the presented image for screenshots.
#ifndef RTPBR_VIEWER_WINDOW_H
#define RTPBR_VIEWER_WINDOW_H

#include <stdbool.h>
#include <stdint.h>
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#define VIEWER_MAX_SWAPCHAIN_IMAGES 8

typedef struct viewer_window {
    GLFWwindow *glfw;
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkSurfaceKHR surface;
    VkPhysicalDevice physical_device;
    VkDevice device;
    uint32_t queue_family;
    VkQueue queue;
    VkPhysicalDeviceVulkan13Features features13;
    VkPhysicalDeviceFeatures2 features; // the chain given to vkCreateDevice (rtpbr reads it)

    VkSwapchainKHR swapchain;
    VkFormat format;
    VkExtent2D extent;
    uint32_t image_count;
    VkImage images[VIEWER_MAX_SWAPCHAIN_IMAGES];
    VkImageView views[VIEWER_MAX_SWAPCHAIN_IMAGES];

    VkCommandPool pool;
    VkCommandBuffer cmd;
    VkFence fence;
    VkSemaphore acquired, rendered;

    // Host-visible buffers: the screenshot read-back and the reference image (split view).
    VkBuffer readback, overlay;
    VkDeviceMemory readback_memory, overlay_memory;
    void *readback_mapped, *overlay_mapped;

    // GPU time of the ui() pass of the last frame (two timestamps around it; 0 when none).
    VkQueryPool ui_queries;
    float ns_per_tick;
    double ui_gpu_ms;

    uint32_t validation_messages;
} viewer_window;

// The program name messages start with and the window's first title ("rtpbr-viewer"; the
// sample host's window sets its own).
extern const char *viewer_window_program;

// Creates window, device and swapchain. validation: the Khronos layer with a messenger that
// counts warnings and errors (sync_validation: its synchronization validation too). Returns
// false with a message on stderr.
bool viewer_window_create(viewer_window *w, int width, int height, bool validation, bool sync_validation);
void viewer_window_destroy(viewer_window *w);
// Recreates the swapchain (and the per-size buffers) at the framebuffer's current size.
bool viewer_window_resize(viewer_window *w);

// One frame: acquire, let record() fill the command buffer for the acquired image, optionally
// copy overlay rows into the image from column split_x on (split view; 0: the whole image,
// e.g. the FLIP heat map), let ui() (if not NULL) draw over it, optionally read the image
// back, submit, present, wait. record and ui leave the image in TRANSFER_DST_OPTIMAL.
// Returns false on failure; *out_of_date asks for a resize.
typedef bool (*viewer_record_fn)(VkCommandBuffer cmd, VkImage image, VkImageView view, uint32_t image_index,
                                 void *user);
bool viewer_window_frame(viewer_window *w, viewer_record_fn record, viewer_record_fn ui, void *user, int split_x,
                         bool screenshot, bool *out_of_date);

// The overlay buffer (extent.width * extent.height * 4 bytes, in the swapchain's byte order)
// and whether the swapchain stores B, G, R, A.
uint8_t *viewer_window_overlay(viewer_window *w);
bool viewer_window_bgra(const viewer_window *w);
// Writes the image read back by the last frame with screenshot = true as an RGBA PNG.
bool viewer_window_write_screenshot(const viewer_window *w, const char *path);

#endif
